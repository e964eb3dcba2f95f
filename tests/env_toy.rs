//! The environment interface is not BW4T-specific: a toy environment (a counter per entity)
//! runs behind an environment handle in lock-step mode with typed percepts.

use goal::env::thread::{EnvError, EnvHandle, Mode};
use goal::env::{ActionResult, EntityInfo, Environment, PerceptDecl, PerceptFilter, PerceptType};
use goal::term::Term;

struct Counters {
    values: Vec<i64>,
    filters: Vec<PerceptFilter>,
    ticks: u64,
}

impl Counters {
    fn new(n: usize) -> Counters {
        let decls = Counters::decls();
        Counters {
            values: vec![0; n],
            filters: (0..n).map(|_| PerceptFilter::new(&decls)).collect(),
            ticks: 0,
        }
    }

    fn decls() -> Vec<PerceptDecl> {
        vec![
            PerceptDecl::new("name", 1, PerceptType::Once),
            PerceptDecl::new("value", 1, PerceptType::OnChange),
            PerceptDecl::new("big", 0, PerceptType::OnChangeWithNegation),
            PerceptDecl::new("tick", 1, PerceptType::Always),
        ]
    }

    fn index(&self, name: &str) -> Option<usize> {
        name.strip_prefix('c')?
            .parse()
            .ok()
            .filter(|i| *i < self.values.len())
    }
}

impl Environment for Counters {
    fn entities(&self) -> Vec<EntityInfo> {
        (0..self.values.len())
            .map(|i| EntityInfo {
                name: format!("c{i}"),
                kind: "counter".into(),
            })
            .collect()
    }
    fn declarations(&self) -> Vec<PerceptDecl> {
        Counters::decls()
    }
    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult {
        let Some(i) = self.index(entity) else {
            return ActionResult::fail("no such counter");
        };
        match action {
            Term::Atom(s) if s.name() == "inc" => {
                self.values[i] += 1;
                ActionResult::Ok
            }
            Term::Atom(s) if s.name() == "reset" => {
                self.values[i] = 0;
                ActionResult::Ok
            }
            _ => ActionResult::fail(format!("cannot {action}")),
        }
    }
    fn tick(&mut self) {
        self.ticks += 1;
    }
    fn ticks(&self) -> u64 {
        self.ticks
    }
    fn percepts(&mut self, entity: &str) -> Vec<Term> {
        let Some(i) = self.index(entity) else {
            return Vec::new();
        };
        let mut now = vec![
            Term::compound("name", vec![Term::atom(entity)]),
            Term::compound("value", vec![Term::Int(self.values[i])]),
            Term::compound("tick", vec![Term::Int(self.ticks as i64)]),
        ];
        if self.values[i] >= 2 {
            now.push(Term::atom("big"));
        }
        self.filters[i].batch(now)
    }
    fn is_finished(&self) -> bool {
        self.values.iter().all(|v| *v >= 3)
    }
    fn stats(&self) -> serde_json::Value {
        serde_json::json!({ "values": self.values })
    }
}

fn show(b: &[Term]) -> String {
    b.iter()
        .map(|t| t.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn a_toy_environment_runs_in_lock_step_with_typed_percepts() {
    let h = EnvHandle::spawn(Box::new(Counters::new(2)), Mode::LockStep);
    let info = h.info().unwrap();
    assert_eq!(info.entities[1].name, "c1");
    let first = h.perceive(&[]).unwrap();
    assert_eq!(show(&first[0].1), "name(c0) value(0) tick(0)");
    let mut log = Vec::new();
    for round in 0..4 {
        let mut actions = vec![("c0".to_string(), Term::atom("inc"))];
        if round == 2 {
            actions.push(("c0".to_string(), Term::atom("reset")));
        }
        actions.push(("c1".to_string(), Term::atom("inc")));
        let r = h.round(actions).unwrap();
        log.push(format!("{} {}", r.tick, show(&r.percepts[0].1)));
        assert!(r.results.iter().all(|(_, res)| res.is_ok()));
        assert!(!r.finished);
    }
    // Actions apply in the given order (inc then reset), one tick per round; on-change
    // percepts only when changed; `not(big)` when big stops holding.
    assert_eq!(
        log,
        [
            "1 value(1) tick(1)",
            "2 value(2) big tick(2)",
            "3 value(0) not(big) tick(3)",
            "4 value(1) tick(4)",
        ]
    );
    let r = h.round(vec![("c9".into(), Term::atom("inc"))]).unwrap();
    assert_eq!(r.results[0].1, ActionResult::fail("no such counter"));
    let s = h.status().unwrap();
    assert_eq!(s.stats["values"], serde_json::json!([1, 4]));
    h.round(vec![("c0".into(), Term::atom("inc"))]).unwrap();
    let r = h.round(vec![("c0".into(), Term::atom("inc"))]).unwrap();
    assert!(r.finished);
    drop(h);
}

/// A counter world whose `explode` action panics (a bug in an environment).
struct Fragile(Counters);

impl Environment for Fragile {
    fn entities(&self) -> Vec<EntityInfo> {
        self.0.entities()
    }
    fn declarations(&self) -> Vec<PerceptDecl> {
        self.0.declarations()
    }
    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult {
        if *action == Term::atom("explode") {
            panic!("the toy environment broke");
        }
        self.0.perform(entity, action)
    }
    fn tick(&mut self) {
        self.0.tick()
    }
    fn ticks(&self) -> u64 {
        self.0.ticks()
    }
    fn percepts(&mut self, entity: &str) -> Vec<Term> {
        self.0.percepts(entity)
    }
    fn is_finished(&self) -> bool {
        self.0.is_finished()
    }
    fn stats(&self) -> serde_json::Value {
        self.0.stats()
    }
}

#[test]
fn a_lock_step_environment_that_panics_stops_with_an_error_value() {
    let h = EnvHandle::spawn(Box::new(Fragile(Counters::new(1))), Mode::LockStep);
    let r = h.round(vec![("c0".into(), Term::atom("inc"))]).unwrap();
    assert_eq!(r.tick, 1);
    // The panic does not reach the caller: the environment is stopped from then on.
    let boom = h.round(vec![("c0".into(), Term::atom("explode"))]);
    assert_eq!(boom.err(), Some(EnvError::Stopped));
    assert_eq!(h.status().err(), Some(EnvError::Stopped));
    assert_eq!(h.round(vec![]).err(), Some(EnvError::Stopped));
    assert_eq!(h.perceive(&[]).err(), Some(EnvError::Stopped));
    h.stop();
}
