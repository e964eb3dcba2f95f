//! Which names a compiled program mentions: an agent skips bookkeeping that nothing in its
//! program can observe (its own conversation book and the `session/4` facts it keeps).

use super::program::{Act, Block, Body, Lit, ModuleDef, Receivers, SpecDef};
use crate::term::{Sym, Term};

/// The parts of a compiled program whose terms can reach a query or a goal.
pub struct Parts<'p> {
    pub modules: &'p [ModuleDef],
    pub blocks: &'p [Block],
    pub specs: &'p [SpecDef],
    /// The knowledge clauses as written.
    pub knowledge: &'p [Term],
    /// Conditions compiled apart from the blocks (a test's).
    pub conditions: &'p [Vec<Lit>],
}

/// True when the program can see the `session/4` facts of its own conversations: some term
/// names `session` (a query, a goal, a rule of the knowledge, an action's content), or some
/// action logs a base (`log(mb)` writes every mail fact).
pub fn uses_sessions(p: &Parts<'_>) -> bool {
    let name = Sym::intern(crate::clamr::session::FACT);
    let mut work: Vec<&Term> = p.knowledge.iter().collect();
    for m in p.modules {
        work.extend(m.params.iter().chain(&m.beliefs).chain(&m.goals));
    }
    for s in p.specs {
        work.extend(s.params.iter().chain([&s.pre, &s.post]));
    }
    for c in p.conditions {
        condition_terms(c, &mut work);
    }
    for r in p.blocks.iter().flat_map(|b| &b.rules) {
        condition_terms(&r.cond, &mut work);
        let Body::Combo(actions) = &r.body else {
            continue;
        };
        for a in actions {
            match &a.kind {
                Act::Log(_) => return true,
                Act::Adopt { content, .. } => work.push(content),
                Act::Drop(t) | Act::Insert(t) | Act::Print(t) => work.push(t),
                Act::Delete(d) => work.push(&d.fact),
                Act::Send { to, content, .. } => {
                    work.push(content);
                    if let Receivers::Agents(ts) = to {
                        work.extend(ts);
                    }
                }
                Act::Module { args, .. } | Act::Spec { args, .. } | Act::Timing { args, .. } => {
                    work.extend(args)
                }
                Act::ExitModule => {}
            }
        }
    }
    any_mentions(work, name)
}

fn condition_terms<'p>(cond: &'p [Lit], work: &mut Vec<&'p Term>) {
    for l in cond {
        if let Lit::Mental { query, .. } = l {
            work.push(query);
        }
    }
}

/// True when one of `work` has `name` as an atom or functor anywhere (an explicit stack: terms
/// may nest deeply).
fn any_mentions(mut work: Vec<&Term>, name: Sym) -> bool {
    while let Some(t) = work.pop() {
        match t {
            Term::Atom(a) if *a == name => return true,
            Term::Compound(c) => {
                if c.name == name {
                    return true;
                }
                work.extend(c.args.iter());
            }
            _ => {}
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_name_deep_inside_terms() {
        let deep = (0..10_000).fold(Term::atom("session"), |t, _| {
            Term::compound("f", vec![Term::Int(1), t])
        });
        assert!(any_mentions(vec![&deep], Sym::intern("session")));
        assert!(!any_mentions(vec![&deep], Sym::intern("sessions")));
        let functor = Term::compound("session", vec![Term::var("A")]);
        assert!(any_mentions(vec![&functor], Sym::intern("session")));
    }
}
