//! GOAL updates: a conjunction of literals where `not(L)` deletes `L` and every other literal
//! adds itself; applied to a fact base as "delete first, then add".

use super::error::{KrError, KrResult};
use super::factbase::FactBase;
use super::knowledge::is_protected;
use crate::term::{well_known as wk, Term};

/// The delete and add lists of an update.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Update {
    /// Atoms under `not/1`, in order.
    pub delete: Vec<Term>,
    /// Positive literals, in order.
    pub add: Vec<Term>,
}

/// `error(type_error(update_literal, Culprit), _)`.
fn bad(t: &Term) -> KrError {
    KrError::iso(
        Term::compound("type_error", vec![Term::atom("update_literal"), t.clone()]),
        None,
    )
}

impl Update {
    /// Splits a conjunction of literals (`true` conjuncts are ignored). Rejects variables,
    /// numbers, control constructs (`;`, `->`, `\+`) and protected predicates as literals.
    pub fn parse(update: &Term) -> KrResult<Update> {
        let mut u = Update::default();
        for lit in update.conjuncts() {
            if lit.is_functor(wk::TRUE, 0) {
                continue;
            }
            let (target, positive) = if lit.is_functor(wk::NOT, 1) {
                (&lit.args()[0], false)
            } else {
                (lit, true)
            };
            let Some((name, arity)) = target.functor() else {
                return Err(bad(lit));
            };
            let n = name.name();
            let control = matches!(
                (n, arity),
                (",", 2) | (";", 2) | ("->", 2) | ("\\+", 1) | (":-", 2) | ("not", 1)
            );
            if control || is_protected(n) {
                return Err(bad(lit));
            }
            if positive {
                u.add.push(target.clone());
            } else {
                u.delete.push(target.clone());
            }
        }
        Ok(u)
    }

    /// Applies the update (delete list first, then add list); true when the base changed.
    pub fn apply(&self, base: &mut FactBase) -> bool {
        let mut changed = false;
        for d in &self.delete {
            changed |= base.delete(d);
        }
        for a in &self.add {
            changed |= base.insert(a.clone());
        }
        changed
    }
}
