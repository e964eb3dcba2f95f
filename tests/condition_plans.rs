//! Belief conditions answered without the engine (`goal::agent::conjunction`) give exactly the
//! engine's answers: many generated conjunctions of fact patterns, negations, arithmetic (with
//! unbound operands, overflow, zero divisors and floats), `=` and `\=`, over a small fact base
//! of integers and atoms in two bases, are answered by a plan and by the native engine. Where
//! the plan answers, the answers, their order and the cut flag are the engine's; where the
//! engine raises an error, the plan answers nothing (so the engine runs and raises it).

use goal::agent::conjunction::Plan;
use goal::kr::{FactBase, Knowledge, NativeEngine, View};
use goal::term::{Subst, Sym, Term};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const VARS: [&str; 5] = ["X", "Y", "Z", "W", "V"];

fn int(i: i64) -> Term {
    Term::Int(i)
}

fn c(name: &str, args: Vec<Term>) -> Term {
    Term::compound(Sym::intern(name), args)
}

/// Two fact bases: the beliefs and a second one (as percepts or mail are), sharing a fact.
fn bases() -> (FactBase, FactBase) {
    let mut beliefs = FactBase::new();
    let mut other = FactBase::new();
    for i in 0..5i64 {
        for a in ["a", "b"] {
            if (i + a.len() as i64) % 3 != 0 {
                beliefs.insert(c("p", vec![int(i), Term::atom(a)]));
            }
        }
        beliefs.insert(c("q", vec![int(i * 2 % 5)]));
        beliefs.insert(c("r", vec![int(i), c("f", vec![int(4 - i)])]));
    }
    beliefs.insert(c("s", vec![int(i64::MAX - 1)]));
    beliefs.insert(c("s", vec![int(3)]));
    beliefs.insert(c("t", vec![Term::from(1.5)]));
    beliefs.insert(c("t", vec![Term::atom("a")]));
    beliefs.insert(Term::atom("flag"));
    other.insert(c("p", vec![int(1), Term::atom("a")]));
    other.insert(c("p", vec![int(7), Term::atom("c")]));
    other.insert(c("q", vec![int(3)]));
    (beliefs, other)
}

struct Gen(ChaCha8Rng);

impl Gen {
    fn pick<T: Clone>(&mut self, xs: &[T]) -> T {
        xs[self.0.gen_range(0..xs.len())].clone()
    }

    fn var(&mut self) -> Term {
        Term::var(self.pick(&VARS))
    }

    /// A pattern argument: a variable, `_`, a small integer or an atom.
    fn arg(&mut self) -> Term {
        match self.0.gen_range(0..10) {
            0..=4 => self.var(),
            5 => Term::var("_"),
            6..=7 => int(self.0.gen_range(0..5)),
            _ => Term::atom(self.pick(&["a", "b", "c"])),
        }
    }

    fn pattern(&mut self) -> Term {
        match self.0.gen_range(0..9) {
            0..=2 => c("p", vec![self.arg(), self.arg()]),
            3 => c("q", vec![self.arg()]),
            4 => c("r", vec![self.arg(), c("f", vec![self.arg()])]),
            5 => c("r", vec![self.arg(), self.arg()]),
            6 => c("s", vec![self.arg()]),
            7 => c("t", vec![self.arg()]),
            _ => Term::atom(self.pick(&["flag", "none"])),
        }
    }

    fn expr(&mut self, depth: u32) -> Term {
        if depth == 0 || self.0.gen_bool(0.4) {
            return match self.0.gen_range(0..10) {
                0..=5 => self.var(),
                6..=7 => int(self.0.gen_range(-2..6)),
                8 => int(i64::MAX),
                _ => self.pick(&[Term::from(0.5), Term::atom("a")]),
            };
        }
        let op = self.pick(&["+", "-", "*", "//", "mod", "neg", "max"]);
        match op {
            "neg" => c("-", vec![self.expr(depth - 1)]),
            op => c(op, vec![self.expr(depth - 1), self.expr(depth - 1)]),
        }
    }

    fn conjunct(&mut self) -> Term {
        match self.0.gen_range(0..20) {
            0..=6 => self.pattern(),
            7..=8 => c("not", vec![self.pattern()]),
            9 => c("\\+", vec![self.pattern()]),
            10..=11 => c("is", vec![self.var(), self.expr(2)]),
            12 => c("is", vec![int(self.0.gen_range(0..4)), self.expr(1)]),
            13..=14 => {
                let op = self.pick(&["<", ">", "=<", ">=", "=:=", "=\\="]);
                c(op, vec![self.expr(1), self.expr(1)])
            }
            15 => c("=", vec![self.arg(), self.arg()]),
            16 => c("\\=", vec![self.arg(), self.arg()]),
            17 => Term::atom("true"),
            18 => c("known", vec![self.var()]),
            _ => c("=", vec![self.var(), c("f", vec![self.var()])]),
        }
    }

    fn query(&mut self) -> Term {
        let n = self.0.gen_range(1..=4);
        Term::conjunction((0..n).map(|_| self.conjunct()).collect())
    }

    fn theta(&mut self) -> Subst {
        let mut s = Subst::new();
        for v in VARS {
            match self.0.gen_range(0..8) {
                0 => s.bind(Sym::intern(v), int(self.0.gen_range(0..5))),
                1 => s.bind(Sym::intern(v), Term::atom(self.pick(&["a", "b"]))),
                _ => {}
            }
        }
        s
    }
}

/// Knowledge with one rule, `known(K) :- q(K)`: conditions on `known/1` are the engine's.
fn knowledge() -> std::sync::Arc<Knowledge> {
    Knowledge::load(&[c(
        ":-",
        vec![
            c("known", vec![Term::var("K")]),
            c("q", vec![Term::var("K")]),
        ],
    )])
    .expect("knowledge")
}

#[test]
fn planned_conditions_answer_as_the_engine_does() {
    let (beliefs, other) = bases();
    let bases = [&beliefs, &other];
    let kn = knowledge();
    let view = View::beliefs(&kn, &bases);
    let mut engine = NativeEngine::new(7);
    let mut g = Gen(ChaCha8Rng::seed_from_u64(16));
    let (mut planned, mut answered, mut bailed, mut errors, mut answers) = (0, 0, 0, 0, 0);
    for case in 0..6000 {
        let q = g.query();
        let theta = g.theta();
        let cap = g.pick(&[0, 1, 2, 3, usize::MAX]);
        let expected = engine
            .query_upto_in(&view, &q, &theta, cap)
            .expect("theta is ground");
        let Some(plan) = Plan::prepare(&q, &kn) else {
            continue;
        };
        planned += 1;
        let got = plan.answers_in(&bases, &theta, cap);
        match (&expected, got) {
            (Ok(e), Some(g)) => {
                answered += 1;
                answers += g.0.len();
                assert_eq!(
                    (&e.0, e.1),
                    (&g.0, g.1),
                    "case {case}: {q} under {theta:?}, cap {cap}"
                );
            }
            (Err(err), Some(g)) => {
                panic!("case {case}: {q} under {theta:?}: the engine raises {err}, the plan answers {g:?}")
            }
            (Err(_), None) => errors += 1,
            (Ok(_), None) => bailed += 1,
        }
    }
    // The generator reaches every outcome, most conditions are planned and answered.
    assert!(planned > 3000, "{planned} planned");
    assert!(answered > 2000, "{answered} answered");
    assert!(answers > 1000, "{answers} answers");
    assert!(errors > 100, "{errors} engine errors");
    assert!(bailed > 50, "{bailed} left to the engine");
}

#[test]
fn what_a_plan_cannot_decide_is_not_planned() {
    let kn = knowledge();
    let not_planned = [
        c("known", vec![Term::var("X")]),
        c(";", vec![c("q", vec![Term::var("X")]), Term::atom("true")]),
        c("q", vec![Term::from(1.0)]),
        c(
            "is",
            vec![Term::var("X"), c("+", vec![Term::from(1.0), int(1)])],
        ),
        c("is", vec![Term::var("X"), c("max", vec![int(1), int(2)])]),
        c("=", vec![Term::var("X"), c("f", vec![Term::var("Y")])]),
        c("member", vec![Term::var("X"), Term::atom("[]")]),
        Term::atom("!"),
    ];
    for q in not_planned {
        assert!(Plan::prepare(&q, &kn).is_none(), "{q}");
    }
    let q = Term::conjunction(vec![
        c("p", vec![Term::var("X"), Term::var("_")]),
        c("not", vec![c("q", vec![Term::var("X")])]),
        c(
            "is",
            vec![Term::var("Y"), c("mod", vec![Term::var("X"), int(3)])],
        ),
        c("=<", vec![Term::var("Y"), int(2)]),
        c("\\=", vec![Term::var("X"), Term::atom("a")]),
    ]);
    assert!(Plan::prepare(&q, &kn).is_some());
    // A plan keeps at most 16 variables (in a fixed array): more are the engine's.
    let pairs = |n: usize| {
        Term::conjunction(
            (0..n)
                .map(|i| {
                    c(
                        "p",
                        vec![Term::var(&format!("A{i}")), Term::var(&format!("B{i}"))],
                    )
                })
                .collect(),
        )
    };
    assert!(Plan::prepare(&pairs(8), &kn).is_some());
    assert!(Plan::prepare(&pairs(9), &kn).is_none());
}
