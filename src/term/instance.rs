//! The instance of a pattern under variable values, hashed and compared exactly as the instance
//! term would be, without building it: a ground fact is looked up in a fact base
//! ([`crate::kr::factbase::FactBase::contains_instance`]) with no allocation.

use super::{Sym, Term};
use hashbrown::Equivalent;
use smallvec::{smallvec, SmallVec};
use std::hash::{Hash, Hasher};

/// The value a variable of a pattern stands for: a ground term, or an integer computed on the
/// way (an `is/2` result) that stands for `Term::Int`.
#[derive(Clone, Copy, Debug)]
pub enum Value<'a> {
    /// A ground term.
    Term(&'a Term),
    /// An integer.
    Int(i64),
}

/// A pattern whose variables `value` gives (each must be bound to a ground value: check with
/// the caller's own rules first), hashed and compared as the term it stands for.
pub struct Instance<'a, F> {
    pattern: &'a Term,
    value: F,
}

impl<'a, F: Fn(Sym) -> Option<Value<'a>>> Instance<'a, F> {
    /// The instance of `pattern` under `value`.
    pub fn new(pattern: &'a Term, value: F) -> Self {
        Instance { pattern, value }
    }
}

impl<'a, F: Fn(Sym) -> Option<Value<'a>>> Hash for Instance<'a, F> {
    /// Writes what hashing the instance term writes (depth first, left to right: the same
    /// sequence whatever the nesting), so that it finds the stored fact.
    fn hash<H: Hasher>(&self, state: &mut H) {
        let mut stack: SmallVec<[&Term; 16]> = smallvec![self.pattern];
        while let Some(t) = stack.pop() {
            match t {
                Term::Var(v) => match (self.value)(*v) {
                    Some(Value::Term(x)) => x.hash(state),
                    Some(Value::Int(i)) => Term::Int(i).hash(state),
                    // Not an instance of a ground term: hashes as nothing, equals no fact.
                    None => {}
                },
                Term::Compound(c) => {
                    std::mem::discriminant(t).hash(state);
                    c.name.hash(state);
                    c.args.len().hash(state);
                    stack.extend(c.args.iter().rev());
                }
                t => t.hash(state),
            }
        }
    }
}

impl<'a, F: Fn(Sym) -> Option<Value<'a>>> Equivalent<Term> for Instance<'a, F> {
    /// True when `fact` is the instance term.
    fn equivalent(&self, fact: &Term) -> bool {
        let mut stack: SmallVec<[(&Term, &Term); 16]> = smallvec![(self.pattern, fact)];
        while let Some((p, f)) = stack.pop() {
            let same = match p {
                Term::Var(v) => match (self.value)(*v) {
                    Some(Value::Term(x)) => x == f,
                    Some(Value::Int(i)) => matches!(f, Term::Int(j) if *j == i),
                    None => false,
                },
                Term::Compound(pc) => match f {
                    Term::Compound(fc) if pc.name == fc.name && pc.args.len() == fc.args.len() => {
                        stack.extend(pc.args.iter().zip(fc.args.iter()));
                        true
                    }
                    _ => false,
                },
                p => p == f,
            };
            if !same {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kr::fxhash::FxHasher;

    fn hash_of(t: &impl Hash) -> u64 {
        let mut h = FxHasher::default();
        t.hash(&mut h);
        h.finish()
    }

    #[test]
    fn an_instance_hashes_and_compares_as_the_term_it_stands_for() {
        let (x, y) = (Sym::intern("X"), Sym::intern("Y"));
        let pattern = Term::compound(
            "percept",
            vec![Term::compound(
                "seen",
                vec![Term::Var(x), Term::Var(y), Term::atom("a")],
            )],
        );
        let bound = Term::compound("f", vec![Term::atom("b"), Term::Int(3)]);
        let value = |v: Sym| {
            if v == x {
                Some(Value::Int(7))
            } else if v == y {
                Some(Value::Term(&bound))
            } else {
                None
            }
        };
        let inst = Instance::new(&pattern, value);
        let built = Term::compound(
            "percept",
            vec![Term::compound(
                "seen",
                vec![Term::Int(7), bound.clone(), Term::atom("a")],
            )],
        );
        assert_eq!(hash_of(&inst), hash_of(&built));
        assert!(inst.equivalent(&built));
        let other = Term::compound(
            "percept",
            vec![Term::compound(
                "seen",
                vec![Term::Int(8), bound.clone(), Term::atom("a")],
            )],
        );
        assert!(!inst.equivalent(&other));
        let unbound = Instance::new(&pattern, |_| None);
        assert!(
            !unbound.equivalent(&built),
            "an unbound variable equals nothing"
        );
    }

    #[test]
    fn a_fact_base_finds_and_removes_the_fact_an_instance_stands_for() {
        use crate::kr::factbase::FactBase;
        let x = Sym::intern("X");
        let fact = |i: i64| Term::compound("seen", vec![Term::Int(i), Term::atom("b")]);
        let mut base = FactBase::new();
        for i in 0..3 {
            base.insert(fact(i));
        }
        let pattern = Term::compound("seen", vec![Term::Var(x), Term::atom("b")]);
        let one = Instance::new(&pattern, |_| Some(Value::Int(1)));
        let nine = Instance::new(&pattern, |_| Some(Value::Int(9)));
        assert!(base.contains_instance(&one));
        assert!(!base.contains_instance(&nine));
        assert_eq!(base.take_instance(&nine), None);
        let edits = base.edits();
        assert_eq!(base.take_instance(&one), Some(fact(1)));
        assert_eq!(base.edits(), edits + 1, "one edit, as a delete");
        assert!(!base.contains(&fact(1)));
        let rest: Vec<String> = base.iter().map(|f| f.to_string()).collect();
        assert_eq!(rest, ["seen(0,b)", "seen(2,b)"]);
        let seen = Sym::intern("seen");
        assert_eq!(base.facts_of(seen, 2).count(), 2, "gone from the index too");
    }
}
