//! Percept load (after Jason's bufeval): a synthetic environment with one entity whose percepts,
//! 5,000 `lit(I, V)` literals with random values, are all replaced after every action. The
//! agent (`agents/bench/percepts.goal`) answers each batch with `next(V)`, V the value of
//! `lit(0, V)`, which the environment checks.

use super::reason::agent;
use super::{file, rss, Params, Report};
use crate::agent::{PerceptType as AgentPerceptType, PerceptTypes};
use crate::env::{ActionResult, EntityInfo, Environment, PerceptDecl, PerceptType};
use crate::term::Term;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;
use std::time::Instant;

/// The percept-load environment.
pub struct BufEnv {
    rng: ChaCha8Rng,
    size: usize,
    ticks: u64,
    cycles: u64,
    current: Vec<Term>,
    /// Value of `lit(0, _)` in the batch last handed out.
    shown: Option<i64>,
    /// Actions that named the value of the batch last handed out.
    pub matched: u64,
    /// Actions that did not.
    pub mismatched: u64,
}

/// The single entity's name.
pub const ENTITY: &str = "agent";

impl BufEnv {
    /// An environment of `size` percepts that finishes after `cycles` actions.
    pub fn new(seed: u64, size: usize, cycles: u64) -> BufEnv {
        let mut e = BufEnv {
            rng: ChaCha8Rng::seed_from_u64(seed),
            size,
            ticks: 0,
            cycles,
            current: Vec::new(),
            shown: None,
            matched: 0,
            mismatched: 0,
        };
        e.refill();
        e
    }

    fn refill(&mut self) {
        let lit = crate::term::Sym::intern("lit");
        let rng = &mut self.rng;
        self.current = (0..self.size)
            .map(|i| {
                let v: i64 = rng.gen_range(0..1_000_000_000);
                Term::compound(lit, vec![Term::Int(i as i64), Term::Int(v)])
            })
            .collect();
    }
}

impl Environment for BufEnv {
    fn entities(&self) -> Vec<EntityInfo> {
        vec![EntityInfo {
            name: ENTITY.into(),
            kind: "agent".into(),
        }]
    }
    fn declarations(&self) -> Vec<PerceptDecl> {
        vec![PerceptDecl::new("lit", 2, PerceptType::Always)]
    }
    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult {
        if entity != ENTITY {
            return ActionResult::fail(format!("no entity {entity}"));
        }
        match (action.functor(), action.args()) {
            (Some((f, 1)), [Term::Int(v)]) if f.name() == "next" => {
                if Some(*v) == self.shown {
                    self.matched += 1;
                } else {
                    self.mismatched += 1;
                }
                self.refill();
                ActionResult::Ok
            }
            _ => ActionResult::fail(format!("unknown action {action}")),
        }
    }
    fn tick(&mut self) {
        self.ticks += 1;
    }
    fn ticks(&self) -> u64 {
        self.ticks
    }
    fn percepts(&mut self, entity: &str) -> Vec<Term> {
        if entity != ENTITY {
            return Vec::new();
        }
        self.shown = match self.current.first().map(Term::args) {
            Some([_, Term::Int(v)]) => Some(*v),
            _ => None,
        };
        self.current.clone()
    }
    fn is_finished(&self) -> bool {
        self.matched + self.mismatched >= self.cycles
    }
    fn stats(&self) -> serde_json::Value {
        serde_json::json!({ "matched": self.matched, "mismatched": self.mismatched })
    }
}

/// `percepts`: `size` (default 5,000) percepts replaced for `cycles` (default 50) cycles.
pub fn run(params: &Params) -> Result<Report, String> {
    let size = params.get("size", 5000)?;
    let cycles = params.get("cycles", 50)?;
    let t0 = Instant::now();
    let mut env = BufEnv::new(7, size as usize, cycles);
    let types = Arc::new(PerceptTypes::new(env.declarations().into_iter().map(|d| {
        let k = match d.kind {
            PerceptType::Once => AgentPerceptType::Once,
            PerceptType::OnChange => AgentPerceptType::OnChange,
            PerceptType::OnChangeWithNegation => AgentPerceptType::OnChangeNeg,
            PerceptType::Always => AgentPerceptType::Always,
        };
        ((d.name, d.arity), k)
    })));
    let mut a = agent(
        "agents/bench/percepts.goal",
        file("percepts.goal")?,
        "agent",
        types,
    )?;
    let create = t0.elapsed();
    let t1 = Instant::now();
    let mut steps = 0u64;
    let mut failure = None;
    while !env.is_finished() {
        if steps >= cycles * 2 + 10 {
            failure = Some(format!(
                "the agent acted {} times in {steps} cycles",
                env.matched
            ));
            break;
        }
        let batch = env.percepts(ENTITY);
        let out = a.step(&batch, &[]);
        steps += 1;
        if let Some(r) = out.stopped {
            failure = Some(format!("agent stopped: {r:?}"));
            break;
        }
        for act in &out.env_actions {
            if let ActionResult::Failed(m) = env.perform(ENTITY, act) {
                failure = Some(format!("action {act} failed: {m}"));
            }
        }
        env.tick();
    }
    let run = t1.elapsed();
    if failure.is_none() && (env.matched != cycles || env.mismatched != 0) {
        failure = Some(format!(
            "{} actions saw their batch, {} did not (expected {cycles})",
            env.matched, env.mismatched
        ));
    }
    let percepts = steps * size;
    Ok(Report {
        name: "percepts".into(),
        config: format!("size={size} cycles={cycles}"),
        failure,
        agents: 1,
        workers: 1,
        create,
        run,
        count: percepts,
        unit: "percepts",
        cycles: steps,
        cpu: None,
        peak_rss_kib: rss::peak_kib(),
        extra: vec![(
            "per cycle".into(),
            format!("{:.3} ms", run.as_secs_f64() * 1e3 / steps.max(1) as f64),
        )],
        targets: Vec::new(),
    })
}
