//! Control constructs (`,` `;` `->` `*->` `\+` `call/N` `findall/3,4`), the nondeterministic
//! built-ins kept in the solver (`between/3`, `member/2`, `repeat/0`) and the dispatch to the
//! deterministic built-ins.

use super::builtins::{self, B};
use super::machine::{Alt, Bag, Goal, Solver, NONE};
use super::store::Cell;
use crate::kr::error::{KrError, KrResult};
use crate::term::{well_known as wk, Sym, Term};

impl Solver<'_, '_> {
    // ---- control constructs and built-ins ----

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn builtin(
        &mut self,
        b: B,
        g: Cell,
        p: u32,
        next: u32,
        cut: u32,
        depth: u32,
    ) -> KrResult<bool> {
        let cps = self.m.cps.len() as u32;
        match b {
            B::True => {
                self.cont = next;
                Ok(true)
            }
            B::Fail => Ok(false),
            B::Cut => {
                self.m.cps.truncate(cut as usize);
                self.cont = next;
                Ok(true)
            }
            B::Comma => {
                let f2 = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), f2, cut, depth);
                Ok(true)
            }
            B::Or => {
                let lhs = self.ad(p, 0);
                let else_ = self.a(p, 1);
                match self.m.st.functor(lhs) {
                    Some((s, 2)) if s == wk::ARROW || s == wk::SOFT_ARROW => {
                        let Cell::Ptr(q) = lhs else { return Ok(false) };
                        self.push_choice(Alt::Goal(else_), next, cut, depth);
                        let then = self.push_frame(Goal::Call(self.a(q, 1)), next, cut, depth);
                        let gate = if s == wk::ARROW {
                            Goal::CutTo(cps)
                        } else {
                            Goal::SoftCut(cps)
                        };
                        let gate = self.push_frame(gate, then, cut, depth);
                        self.cont = self.push_frame(Goal::Call(self.a(q, 0)), gate, cps + 1, depth);
                    }
                    _ => {
                        self.push_choice(Alt::Goal(else_), next, cut, depth);
                        self.cont = self.push_frame(Goal::Call(lhs), next, cut, depth);
                    }
                }
                Ok(true)
            }
            B::IfThen => {
                let then = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                let gate = self.push_frame(Goal::CutTo(cps), then, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), gate, cps, depth);
                Ok(true)
            }
            B::SoftIfThen => {
                let then = self.push_frame(Goal::Call(self.a(p, 1)), next, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), then, cps, depth);
                Ok(true)
            }
            B::Not => {
                self.push_choice(Alt::NafSucceed, next, cut, depth);
                let f = self.push_frame(Goal::NafFail(cps), NONE, cut, depth);
                self.cont = self.push_frame(Goal::Call(self.a(p, 0)), f, cps + 1, depth);
                Ok(true)
            }
            B::Call => {
                let arity = self.m.st.heap[p as usize].fun().map_or(1, |f| f.1);
                let goal = self.a(p, 0);
                let goal = if arity > 1 {
                    let extra: Vec<Cell> = (1..arity).map(|i| self.a(p, i)).collect();
                    self.add_args(goal, &extra)?
                } else {
                    goal
                };
                self.cont = self.push_frame(Goal::Call(goal), next, cps, depth);
                Ok(true)
            }
            B::Findall | B::Findall4 => {
                let (_, end) = self.m.st.list_items(self.a(p, 2));
                if !matches!(end, Cell::Ref(_) | Cell::Atom(wk::NIL)) {
                    let r = self.a(p, 2);
                    let arity = if b == B::Findall4 { 4 } else { 3 };
                    return Err(builtins::type_error(self, "list", r, "findall", arity));
                }
                let bag = self.m.bags.len() as u32;
                self.m.bags.push(Bag::default());
                let tail = if b == B::Findall4 {
                    self.a(p, 3)
                } else {
                    Cell::Atom(wk::NIL)
                };
                self.push_choice(
                    Alt::FindallEnd {
                        bag,
                        result: self.a(p, 2),
                        tail,
                    },
                    next,
                    cut,
                    depth,
                );
                let f = self.push_frame(
                    Goal::Collect {
                        bag,
                        tmpl: self.a(p, 0),
                    },
                    NONE,
                    cut,
                    depth,
                );
                self.cont = self.push_frame(Goal::Call(self.a(p, 1)), f, cps + 1, depth);
                Ok(true)
            }
            B::Between => {
                let lo = builtins::int_arg(self, p, 0, "between", 3)?;
                let hi = match self.ad(p, 1) {
                    Cell::Atom(s) if matches!(s.name(), "inf" | "infinite") => i64::MAX,
                    _ => builtins::int_arg(self, p, 1, "between", 3)?,
                };
                match self.ad(p, 2) {
                    Cell::Int(x) => {
                        if lo <= x && x <= hi {
                            self.cont = next;
                            return Ok(true);
                        }
                        Ok(false)
                    }
                    x @ Cell::Ref(_) => {
                        if lo > hi {
                            return Ok(false);
                        }
                        if lo < hi {
                            self.push_choice(Alt::Between { x, cur: lo + 1, hi }, next, cut, depth);
                        }
                        let ok = self.unify(x, Cell::Int(lo));
                        self.cont = next;
                        Ok(ok)
                    }
                    other => Err(builtins::type_error(self, "integer", other, "between", 3)),
                }
            }
            B::Member => {
                let x = self.a(p, 0);
                let list = self.a(p, 1);
                self.push_choice(Alt::Member { x, list }, next, cut, depth);
                if self.member_step(x, list) {
                    self.cont = next;
                    Ok(true)
                } else {
                    Ok(false)
                }
            }
            B::Catch => {
                self.catch(p, next, cut, depth);
                Ok(true)
            }
            B::Throw => Err(self.throw(p)),
            B::Protected => Err(protected(self.m.st.functor(g))),
            B::Repeat => {
                self.push_choice(Alt::Repeat, next, cut, depth);
                self.cont = next;
                Ok(true)
            }
            _ => match self.det_checked(b, g, p)? {
                builtins::Flow::Fail => Ok(false),
                builtins::Flow::True => {
                    self.cont = next;
                    Ok(true)
                }
                builtins::Flow::Call(goal) => {
                    self.cont = self.push_frame(Goal::Call(goal), next, cps, depth);
                    Ok(true)
                }
            },
        }
    }

    /// A deterministic built-in, then the memory and output budgets (a built-in may build a
    /// large term or write much text in one step).
    fn det_checked(&mut self, b: B, g: Cell, p: u32) -> KrResult<builtins::Flow> {
        let flow = builtins::det(self, b, g, p)?;
        let l = self.cx.limits;
        if self.m.st.heap.len() as u64 > l.max_heap_cells || self.cx.out.len() as u64 > l.max_output
        {
            let name = self.m.st.functor(g).map_or((wk::NIL, 0), |f| f);
            self.check_memory(&|| format!("{}/{}", Term::Atom(name.0), name.1))?;
        }
        Ok(flow)
    }

    /// `goal` with `extra` arguments appended (for `call/N`, `maplist`, ...).
    pub fn add_args(&mut self, goal: Cell, extra: &[Cell]) -> KrResult<Cell> {
        let goal = self.m.st.deref(goal);
        let (name, args): (Sym, Vec<Cell>) = match goal {
            Cell::Atom(s) => (s, Vec::new()),
            Cell::Ptr(q) => match self.m.st.heap[q as usize] {
                Cell::Fun(s, n) => (s, (0..n).map(|i| self.a(q, i)).collect()),
                _ => return Ok(goal),
            },
            Cell::Ref(_) => return Err(KrError::iso(Term::atom("instantiation_error"), None)),
            other => {
                return Err(builtins::type_error(
                    self,
                    "callable",
                    other,
                    "call",
                    1 + extra.len(),
                ))
            }
        };
        let mut all = args;
        all.extend_from_slice(extra);
        Ok(self.m.st.new_struct(name, &all))
    }
}

/// `error(permission_error(access, private_procedure, Name/Arity), Hint)` for a protected
/// predicate called at run time, with a hint saying how agents change their beliefs.
fn protected(f: Option<(Sym, u32)>) -> KrError {
    let (name, arity) = f.unwrap_or((wk::NIL, 0));
    let pi = Term::compound("/", vec![Term::Atom(name), Term::Int(arity as i64)]);
    let hint = if name.name().starts_with("assert") || name.name().starts_with("retract") {
        "protected in GOAL: agents change beliefs with insert/1 and delete/1 actions"
    } else {
        "protected in GOAL: this predicate cannot be called from agent knowledge or queries"
    };
    KrError::Iso(Term::compound(
        "error",
        vec![
            Term::compound(
                "permission_error",
                vec![Term::atom("access"), Term::atom("private_procedure"), pi],
            ),
            Term::compound("context", vec![Term::var("_"), Term::atom(hint)]),
        ],
    ))
}
