//! The blocks world of GOAL's examples: blocks stacked on a table and one gripper (entity
//! `gripper`, type `gripper`) that moves a clear block onto the table or onto another clear
//! block in one step. Percepts, every batch: `block(X)` for every block and `on(X, Y)` for what
//! it stands on (`table` for the table). The one action is `move(X, Y)`.
//!
//! A `.mas2g` file selects it with any jar whose name contains `blocksworld` (see
//! `mas::environment`); the initial towers come from the init parameters ([`init`]).

pub mod init;

use crate::diag::Diagnostic;
use crate::env::{ActionResult, EntityInfo, Environment, InitParams, PerceptDecl, PerceptType};
use crate::term::{Sym, Term};

/// The name of the built-in environment (`env = "blocksworld"`).
pub const NAME: &str = "blocksworld";

/// The name (and type) of the one entity.
pub const ENTITY: &str = "gripper";

/// The actions the gripper understands, as `name/arity`.
pub const ACTIONS: &[&str] = &["move/2"];

/// The percepts the gripper receives, as `name/arity`.
pub const PERCEPTS: &[&str] = &["block/1", "on/2"];

/// Blocks (in the order they were given) and what each one stands on.
pub struct BlocksWorld {
    blocks: Vec<Term>,
    on: Vec<Term>,
    ticks: u64,
    moves: u64,
}

impl BlocksWorld {
    /// A world from `(block, support)` pairs, already checked by [`init`].
    pub fn new(towers: Vec<(Term, Term)>) -> BlocksWorld {
        let (blocks, on) = towers.into_iter().unzip();
        BlocksWorld {
            blocks,
            on,
            ticks: 0,
            moves: 0,
        }
    }

    /// A world set up from init parameters (`start = [...]` or `blocks = [on(X, Y), ...]`).
    pub fn from_params(params: &InitParams) -> Result<BlocksWorld, Vec<Diagnostic>> {
        init::towers(params).map(BlocksWorld::new)
    }

    fn index(&self, b: &Term) -> Option<usize> {
        self.blocks.iter().position(|x| x == b)
    }

    fn is_table(t: &Term) -> bool {
        matches!(t, Term::Atom(s) if s.name() == "table")
    }

    /// Why `X` cannot be moved onto `Y`, if it cannot.
    fn refusal(&self, x: &Term, y: &Term) -> Option<String> {
        let Some(i) = self.index(x) else {
            return Some(format!("`{x}` is not a block"));
        };
        if !Self::is_table(y) && self.index(y).is_none() {
            return Some(format!("`{y}` is neither a block nor `table`"));
        }
        if x == y {
            return Some(format!("block {x} cannot be put on itself"));
        }
        if let Some(top) = self.blocks.iter().zip(&self.on).find(|(_, s)| *s == x) {
            return Some(format!("block {x} is not clear: {} is on it", top.0));
        }
        if !Self::is_table(y) {
            if let Some(top) = self.blocks.iter().zip(&self.on).find(|(_, s)| *s == y) {
                return Some(format!("block {y} is not clear: {} is on it", top.0));
            }
        }
        if &self.on[i] == y {
            return Some(format!("block {x} is already on {y}"));
        }
        None
    }
}

impl Environment for BlocksWorld {
    fn entities(&self) -> Vec<EntityInfo> {
        vec![EntityInfo {
            name: ENTITY.into(),
            kind: ENTITY.into(),
        }]
    }

    fn declarations(&self) -> Vec<PerceptDecl> {
        vec![
            PerceptDecl::new("block", 1, PerceptType::Always),
            PerceptDecl::new("on", 2, PerceptType::Always),
        ]
    }

    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult {
        if entity != ENTITY {
            return ActionResult::fail(format!("unknown entity `{entity}`"));
        }
        if !action.is_functor(Sym::intern("move"), 2) {
            return ActionResult::fail(crate::env::unknown_action(action, ACTIONS));
        }
        let (x, y) = (&action.args()[0], &action.args()[1]);
        if let Some(why) = self.refusal(x, y) {
            return ActionResult::fail(format!("move({x}, {y}) is not possible: {why}"));
        }
        if let Some(i) = self.index(x) {
            self.on[i] = y.clone();
        }
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
        let blocks = self
            .blocks
            .iter()
            .map(|b| Term::compound("block", vec![b.clone()]));
        let on = self
            .blocks
            .iter()
            .zip(&self.on)
            .map(|(x, y)| Term::compound("on", vec![x.clone(), y.clone()]));
        blocks.chain(on).collect()
    }

    /// The blocks world has no goal of its own: the agents decide when they are done.
    fn is_finished(&self) -> bool {
        false
    }

    fn stats(&self) -> serde_json::Value {
        serde_json::json!({ "moves": self.moves, "blocks": self.blocks.len() })
    }
}
