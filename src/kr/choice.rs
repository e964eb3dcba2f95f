//! Which engine answers an agent's queries: the native engine (the default) or scryer
//! (`--kr scryer`, `language = scryer`), behind one type the agent holds.

use super::error::{KrResult, Limits};
use super::{Engine, Knowledge, NativeEngine, View};
use crate::term::{Subst, Term};
use std::time::Instant;

/// The KR engines a run can choose from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum KrKind {
    /// The engine written for GOAL (fast, bounded memory).
    #[default]
    Native,
    /// scryer-prolog 0.10 (full ISO Prolog: `catch/3`, DCGs, ...).
    Scryer,
}

impl KrKind {
    /// Reads an engine name (`native`, `scryer`); `swiprolog` means the run's engine (`None`).
    pub fn parse(name: &str) -> Result<Option<KrKind>, String> {
        match name.to_ascii_lowercase().as_str() {
            "native" => Ok(Some(KrKind::Native)),
            "scryer" | "scryer-prolog" | "scryer_prolog" => Ok(Some(KrKind::Scryer)),
            "swiprolog" | "swi-prolog" | "swi_prolog" | "prolog" => Ok(None),
            other => Err(format!(
                "unknown KR engine `{other}` (choose native or scryer; swiprolog means the run's engine)"
            )),
        }
    }

    /// The engine's name as users write it.
    pub fn name(self) -> &'static str {
        match self {
            KrKind::Native => "native",
            KrKind::Scryer => "scryer",
        }
    }

    /// True when this build includes the engine.
    pub fn available(self) -> bool {
        match self {
            KrKind::Native => true,
            KrKind::Scryer => cfg!(feature = "scryer"),
        }
    }
}

/// An agent's engine.
#[derive(Clone, Debug)]
pub enum AgentEngine {
    /// The native engine.
    Native(NativeEngine),
    /// The scryer engine.
    #[cfg(feature = "scryer")]
    Scryer(Box<super::scryer::ScryerEngine>),
}

impl AgentEngine {
    /// The engine of `kind` for `knowledge`; refused (with the reason) when the build lacks
    /// the engine, the knowledge needs scryer but `kind` is native, or scryer refuses it.
    pub fn new(
        kind: KrKind,
        knowledge: &Knowledge,
        seed: u64,
        limits: Limits,
    ) -> Result<AgentEngine, String> {
        if !kind.available() {
            return Err(format!(
                "this goal was built without the {} engine (cargo feature `{}`)",
                kind.name(),
                kind.name()
            ));
        }
        match kind {
            KrKind::Native => {
                if let Some((i, what)) = needs_scryer(knowledge.source()) {
                    return Err(format!(
                        "knowledge clause {} uses {what}, which only the scryer engine runs: add `language = scryer` to the agent's entry in the .mas2g, or run with `--kr scryer`",
                        i + 1
                    ));
                }
                Ok(AgentEngine::Native(
                    NativeEngine::new(seed).with_limits(limits),
                ))
            }
            #[cfg(feature = "scryer")]
            KrKind::Scryer => super::scryer::ScryerEngine::new(knowledge.source())
                .map(|e| AgentEngine::Scryer(Box::new(e.with_limits(limits))))
                .map_err(|e| format!("the scryer engine refuses the knowledge: {e}")),
            #[cfg(not(feature = "scryer"))]
            KrKind::Scryer => Err("this goal was built without the scryer engine".into()),
        }
    }

    /// The first `cap` answers, and whether the search stopped at `cap`.
    pub fn query_upto(
        &mut self,
        view: &View,
        query: &Term,
        cap: usize,
    ) -> KrResult<(Vec<Subst>, bool)> {
        match self {
            AgentEngine::Native(e) => e.query_upto(view, query, cap),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => e.query_upto(view, query, cap),
        }
    }

    /// The limits applied to every query.
    pub fn limits_mut(&mut self) -> &mut Limits {
        match self {
            AgentEngine::Native(e) => &mut e.limits,
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => &mut e.limits,
        }
    }

    /// Sets the deadline of the next queries.
    pub fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.limits_mut().deadline = deadline;
    }

    /// Sets the simulated time `get_time/1` answers (native engine; scryer reads the wall clock).
    pub fn set_clock(&mut self, now: Option<f64>) {
        // Irrefutable when the scryer engine is not compiled in.
        #[allow(irrefutable_let_patterns)]
        if let AgentEngine::Native(e) = self {
            e.clock.now = now;
        }
    }

    /// False only when nothing printed since the last `take_output` (a scryer engine always
    /// answers true: its output is simply taken).
    pub fn has_output(&self) -> bool {
        match self {
            AgentEngine::Native(e) => e.has_output(),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(_) => true,
        }
    }

    /// Changes whenever a query drew a random number or read the clock (native engine; a
    /// scryer agent is never considered waiting on chance: 0 always).
    pub fn chance(&self) -> u128 {
        match self {
            AgentEngine::Native(e) => e.chance(),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(_) => 0,
        }
    }

    /// Which engine this is.
    pub fn kind(&self) -> KrKind {
        match self {
            AgentEngine::Native(_) => KrKind::Native,
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(_) => KrKind::Scryer,
        }
    }
}

impl Engine for AgentEngine {
    fn query(&mut self, view: &View, query: &Term) -> KrResult<Vec<Subst>> {
        match self {
            AgentEngine::Native(e) => e.query(view, query),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => e.query(view, query),
        }
    }

    fn query_first(&mut self, view: &View, query: &Term) -> KrResult<Option<Subst>> {
        match self {
            AgentEngine::Native(e) => e.query_first(view, query),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => e.query_first(view, query),
        }
    }

    fn holds(&mut self, view: &View, query: &Term) -> KrResult<bool> {
        match self {
            AgentEngine::Native(e) => e.holds(view, query),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => e.holds(view, query),
        }
    }

    fn take_output(&mut self) -> String {
        match self {
            AgentEngine::Native(e) => e.take_output(),
            #[cfg(feature = "scryer")]
            AgentEngine::Scryer(e) => e.take_output(),
        }
    }
}

/// The first knowledge clause that only the scryer engine runs (a DCG rule, `catch/3` or
/// `throw/1` in a body), with what it uses: (clause index, `name/arity`).
pub fn needs_scryer(clauses: &[Term]) -> Option<(usize, String)> {
    clauses
        .iter()
        .enumerate()
        .find_map(|(i, c)| scryer_feature(c).map(|f| (i, f)))
}

fn scryer_feature(c: &Term) -> Option<String> {
    if c.is_functor(crate::term::Sym::intern("-->"), 2) {
        return Some("-->/2 (a DCG rule)".into());
    }
    if !c.is_functor(crate::term::well_known::NECK, 2) {
        return None;
    }
    // An explicit stack: bodies can be long conjunctions.
    let mut stack = vec![&c.args()[1]];
    while let Some(t) = stack.pop() {
        if let Some((n, a)) = t.functor() {
            if matches!((n.name(), a), ("catch", 3) | ("throw", 1)) {
                return Some(format!("{}/{a}", n.name()));
            }
            stack.extend(t.args().iter());
        }
    }
    None
}

/// Clauses the native engine can compile that define the same predicates as `clauses`: a
/// clause only scryer runs becomes `Head :- fail` (a DCG rule's head gets its two list
/// arguments). Agents whose knowledge needs scryer keep these for the checks made outside
/// the engine (which predicates knowledge defines), while scryer loads the clauses as written.
pub fn native_stand_ins(clauses: &[Term]) -> Vec<Term> {
    clauses
        .iter()
        .map(|c| {
            if scryer_feature(c).is_none() {
                return c.clone();
            }
            let head = if c.is_functor(crate::term::Sym::intern("-->"), 2) {
                let h = &c.args()[0];
                let mut args = h.args().to_vec();
                args.push(Term::var("S0"));
                args.push(Term::var("S"));
                match h.functor() {
                    Some((n, _)) => Term::compound(n, args),
                    None => h.clone(),
                }
            } else {
                c.args()[0].clone()
            };
            Term::compound(
                crate::term::well_known::NECK,
                vec![head, Term::atom("fail")],
            )
        })
        .collect()
}
