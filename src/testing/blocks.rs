//! A small blocks world for testing agents that need one (the blocks-world stacker): blocks on
//! a table, one entity `arm` (type `arm`) that moves a clear block onto the table or onto
//! another clear block. Percepts: `on(X, Y)` for every block, in every batch. `goal test` uses
//! it when a MAS file says `env = "blocksworld"` with `init = [blocks = [on(a, b), ...]]`.

use crate::env::{ActionResult, EntityInfo, Environment, PerceptDecl, PerceptType};
use crate::syntax::mas2g::ast::{InitValue, MasFile};
use crate::term::Term;
use std::collections::BTreeMap;

/// The environment name in a `.mas2g` file.
pub const NAME: &str = "blocksworld";

/// Blocks and what each one is on.
pub struct BlocksWorld {
    on: BTreeMap<String, String>,
    ticks: u64,
    moves: u64,
}

fn name(v: &InitValue) -> Option<String> {
    match v {
        InitValue::Ident(s) | InitValue::Str(s) => Some(s.value.clone()),
        _ => None,
    }
}

impl BlocksWorld {
    /// The world described by `mas`'s environment section, if it names this environment.
    pub fn from_mas(mas: &MasFile) -> Option<Result<BlocksWorld, String>> {
        let env = mas.environment.as_ref()?;
        if !env.env.as_ref()?.value.eq_ignore_ascii_case(NAME) {
            return None;
        }
        let mut on = BTreeMap::new();
        for p in env.init.iter().filter(|p| p.key.value == "blocks") {
            let InitValue::List { items, .. } = &p.value else {
                return Some(Err("`blocks` must be a list of on(X, Y)".into()));
            };
            for it in items {
                match it {
                    InitValue::Function { name: f, args, .. }
                        if f.value == "on" && args.len() == 2 =>
                    {
                        match (name(&args[0]), name(&args[1])) {
                            (Some(x), Some(y)) => {
                                on.insert(x, y);
                            }
                            _ => return Some(Err("on(X, Y) needs two block names".into())),
                        }
                    }
                    _ => return Some(Err("`blocks` must be a list of on(X, Y)".into())),
                }
            }
        }
        Some(Ok(BlocksWorld {
            on,
            ticks: 0,
            moves: 0,
        }))
    }

    fn clear(&self, b: &str) -> bool {
        b == "table" || (self.on.contains_key(b) && !self.on.values().any(|y| y == b))
    }
}

impl Environment for BlocksWorld {
    fn entities(&self) -> Vec<EntityInfo> {
        vec![EntityInfo {
            name: "arm".into(),
            kind: "arm".into(),
        }]
    }
    fn declarations(&self) -> Vec<PerceptDecl> {
        vec![PerceptDecl::new("on", 2, PerceptType::Always)]
    }
    fn perform(&mut self, _entity: &str, action: &Term) -> ActionResult {
        let args: Vec<String> = action.args().iter().map(|a| a.to_string()).collect();
        if !action.is_functor(crate::term::Sym::intern("move"), 2) {
            return ActionResult::Failed(format!("unknown action {action}"));
        }
        let (x, y) = (&args[0], &args[1]);
        if x == y || x == "table" || !self.clear(x) || !self.clear(y) {
            return ActionResult::Failed(format!("{action} is not possible"));
        }
        self.on.insert(x.clone(), y.clone());
        self.moves += 1;
        ActionResult::Ok
    }
    fn tick(&mut self) {
        self.ticks += 1;
    }
    fn ticks(&self) -> u64 {
        self.ticks
    }
    fn percepts(&mut self, _entity: &str) -> Vec<Term> {
        self.on
            .iter()
            .map(|(x, y)| Term::compound("on", vec![Term::atom(x), Term::atom(y)]))
            .collect()
    }
    fn is_finished(&self) -> bool {
        false
    }
    fn stats(&self) -> serde_json::Value {
        serde_json::json!({ "moves": self.moves })
    }
}
