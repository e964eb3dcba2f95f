//! Lowering what modular GOAL and MARBEL have and 2014 programs have not into ordinary 2014
//! rules and action specs: MARBEL percept declarations, environment actions nobody specified,
//! messages that live one cycle, and macros local to their file.

use super::build::located;
use super::mas::PerceptMode;
use crate::diag::Span;
use crate::syntax::ast::*;
use crate::term::{Sym, Term};
use std::collections::{BTreeMap, BTreeSet};

fn vars(prefix: &str, n: usize) -> Vec<Term> {
    (1..=n)
        .map(|i| Term::var(&format!("{prefix}{i}")))
        .collect()
}

fn lit(t: Term, span: &Span) -> Literal {
    Literal {
        kind: LiteralKind::Mental {
            negated: false,
            selector: Selector::default_this(),
            op: MentalOp::Bel,
            query: located(t, span.clone()),
        },
        span: span.clone(),
    }
}

fn forall(cond: Term, action: ActionKind, span: &Span) -> Rule {
    Rule {
        kind: RuleKind::Forall,
        condition: vec![lit(cond, span)],
        body: RuleBody::Combo(vec![Action {
            kind: action,
            span: span.clone(),
        }]),
        span: span.clone(),
    }
}

fn insert(t: Term, span: &Span) -> ActionKind {
    ActionKind::Insert {
        selector: Selector::default_this(),
        content: located(t, span.clone()),
    }
}

fn delete(t: Term, span: &Span) -> ActionKind {
    ActionKind::Delete {
        selector: Selector::default_this(),
        content: located(t, span.clone()),
    }
}

fn and(items: Vec<Term>) -> Term {
    super::build::conjunction(items)
}

fn naf(t: Term) -> Term {
    Term::compound("\\+", vec![t])
}

fn wrap(name: &str, t: Term) -> Term {
    Term::compound(name, vec![t])
}

/// The rules of one percept declaration (docs/modular-goal.md):
/// * `add p/n`: insert each `p` of this cycle's batch;
/// * `update p/n`: when the batch has `p` facts, they replace the old ones; a `not(p)` in the
///   batch deletes `p`;
/// * `replace p/n`: the `p` facts mirror the percepts that hold now.
pub fn percept_declaration(mode: PerceptMode, name: &str, arity: usize, span: &Span) -> Vec<Rule> {
    let p = Term::compound(name, vars("V", arity));
    let new = |t: Term| wrap("newpercept", t);
    let perceived = |t: Term| wrap("percept", t);
    let add_new = forall(
        and(vec![new(p.clone()), naf(p.clone())]),
        insert(p.clone(), span),
        span,
    );
    match mode {
        PerceptMode::Add => vec![add_new],
        PerceptMode::Update => {
            let any = Term::compound(name, vars("_W", arity));
            vec![
                forall(
                    and(vec![naf(naf(new(any))), p.clone(), naf(new(p.clone()))]),
                    delete(p.clone(), span),
                    span,
                ),
                add_new,
                forall(
                    and(vec![new(wrap("not", p.clone())), p.clone()]),
                    delete(p.clone(), span),
                    span,
                ),
            ]
        }
        PerceptMode::Replace => vec![
            forall(
                and(vec![p.clone(), naf(perceived(p.clone()))]),
                delete(p.clone(), span),
                span,
            ),
            forall(
                and(vec![perceived(p.clone()), naf(p.clone())]),
                insert(p, span),
                span,
            ),
        ],
    }
}

/// Messages live for one cycle: the event module ends by forgetting them.
pub(super) fn clear_messages(span: &Span) -> Vec<Rule> {
    ["received", "sent"]
        .iter()
        .map(|f| {
            let t = Term::compound(*f, vec![Term::var("S"), Term::var("M")]);
            forall(t.clone(), delete(t, span), span)
        })
        .collect()
}

/// (B) every called name that is neither a module nor a specified action: an environment
/// action, always enabled, without effects on the database.
pub(super) fn environment_actions(
    modules: &[Module],
    specs: &[ActionSpec],
    span: &Span,
) -> Vec<ActionSpec> {
    let mut known: BTreeSet<(String, usize)> = specs
        .iter()
        .map(|s| (s.name.name.name().to_string(), s.params.len()))
        .collect();
    for m in modules {
        if let ModuleKind::User { name, params } = &m.kind {
            known.insert((name.name.name().to_string(), params.len()));
        }
    }
    let mut out = Vec::new();
    for m in modules {
        let mut stack: Vec<&Rule> = m.program.iter().flat_map(|p| p.rules.iter()).collect();
        while let Some(r) = stack.pop() {
            match &r.body {
                RuleBody::Block(rs) => stack.extend(rs.iter()),
                RuleBody::Combo(actions) => {
                    for a in actions {
                        let ActionKind::Call { name, args } = &a.kind else {
                            continue;
                        };
                        let key = (name.name.name().to_string(), args.len());
                        if !known.insert(key) {
                            continue;
                        }
                        let truth = SpecCondition {
                            term: located(Term::atom("true"), span.clone()),
                            empty: false,
                            span: span.clone(),
                        };
                        out.push(ActionSpec {
                            name: Ident {
                                name: Sym::intern(name.name.name()),
                                span: span.clone(),
                            },
                            params: vars("X", args.len())
                                .into_iter()
                                .map(|v| located(v, span.clone()))
                                .collect(),
                            kind: ActionSpecKind::Env,
                            kind_span: None,
                            pre: truth.clone(),
                            post: truth,
                            span: span.clone(),
                        });
                    }
                }
            }
        }
    }
    out
}

/// Macros are local to their file, but the 2014 compiler keeps one macro per name/arity: a
/// macro whose name/arity an earlier file defines too is renamed `name'module` in its file
/// (definition and uses), so each file keeps its own.
pub(super) fn local_macros(modules: &mut [Module]) {
    let mut seen: BTreeSet<(String, usize)> = BTreeSet::new();
    for m in modules.iter_mut() {
        let module = m.name().to_string();
        let Some(p) = m.program.as_mut() else {
            continue;
        };
        let mut clash: BTreeMap<(String, usize), Sym> = BTreeMap::new();
        for d in &p.macros {
            let key = (d.name.name.name().to_string(), d.params.len());
            if seen.contains(&key) {
                clash.insert(key.clone(), Sym::intern(&format!("{}'{module}", key.0)));
            }
        }
        seen.extend(
            p.macros
                .iter()
                .map(|d| (d.name.name.name().to_string(), d.params.len())),
        );
        if clash.is_empty() {
            continue;
        }
        let rename = |l: &mut Literal| {
            if let LiteralKind::MacroUse { name, args } = &mut l.kind {
                if let Some(n) = clash.get(&(name.name.name().to_string(), args.len())) {
                    name.name = *n;
                }
            }
        };
        for d in p.macros.iter_mut() {
            if let Some(n) = clash.get(&(d.name.name.name().to_string(), d.params.len())) {
                d.name.name = *n;
            }
            d.body.iter_mut().for_each(rename);
        }
        let mut stack: Vec<&mut Rule> = p.rules.iter_mut().collect();
        while let Some(r) = stack.pop() {
            r.condition.iter_mut().for_each(rename);
            if let RuleBody::Block(rs) = &mut r.body {
                stack.extend(rs.iter_mut());
            }
        }
    }
}

pub(super) fn query(l: &Literal) -> Option<&Term> {
    match &l.kind {
        LiteralKind::Mental { query, .. } => Some(&query.term),
        _ => None,
    }
}

/// True when `t` has a subterm `name/arity` (iterative walk).
pub(super) fn mentions(t: &Term, name: &str, arity: usize) -> bool {
    let mut stack = vec![t];
    while let Some(t) = stack.pop() {
        if matches!(t.functor(), Some((f, n)) if n == arity && f.name() == name) {
            return true;
        }
        stack.extend(t.args().iter());
    }
    false
}
