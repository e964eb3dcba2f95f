//! Variable binding: variables in actions and selectors must be bound by the rule condition,
//! the listall variable, module parameters or enclosing rules; variables in `beliefs`/`goals`
//! only by module parameters; `goals` entries are positive conjunctions.

use super::terms::{
    binding_vars, conjuncts, is_anonymous, var_name, var_occurrences, var_set, Sub, VarSet,
};
use super::Ctx;
use crate::syntax::ast::{
    Action, ActionKind, Literal, LiteralKind, Module, ModuleKind, Mood, Rule, RuleBody, RuleKind,
    Selector, SelectorKind,
};
use crate::syntax::prolog::Located;
use crate::term::Sym;

/// Runs the variable checks.
pub fn check(ctx: &mut Ctx<'_>) {
    for m in ctx.modules.clone() {
        let params: VarSet = match &m.kind {
            ModuleKind::User { params, .. } => {
                params.iter().flat_map(|p| var_set(&p.term)).collect()
            }
            _ => VarSet::new(),
        };
        sections(ctx, m, &params);
        if let Some(p) = &m.program {
            for r in &p.rules {
                rule(ctx, r, &params);
            }
        }
    }
}

fn sections(ctx: &mut Ctx<'_>, m: &Module, params: &VarSet) {
    let unbound_hint = if matches!(m.kind, ModuleKind::User { .. }) {
        "only module parameters may occur as variables here; use a ground term"
    } else {
        "beliefs and goals are ground facts; replace the variable by a value"
    };
    for b in &m.beliefs {
        if b.term.is_functor(Sym::intern(":-"), 2) {
            continue; // a rule among the beliefs: its variables are local to it
        }
        if let Some((v, span)) = var_occurrences(b)
            .into_iter()
            .find(|(v, _)| !params.contains(v))
        {
            ctx.error(
                "E0109",
                format!(
                    "variable `{}` in a belief is not bound by a module parameter",
                    var_name(v)
                ),
                span,
                unbound_hint,
            );
        }
    }
    for g in &m.goals {
        if let Some((v, span)) = var_occurrences(g)
            .into_iter()
            .find(|(v, _)| !params.contains(v))
        {
            ctx.error(
                "E0109",
                format!(
                    "variable `{}` in a goal is not bound by a module parameter",
                    var_name(v)
                ),
                span,
                unbound_hint,
            );
        }
        for c in conjuncts(Sub::of(g)) {
            let why = match c.term.functor() {
                None => Some("it is not a fact"),
                Some((n, a)) => match (n.name(), a) {
                    ("not", 1) | ("\\+", 1) => Some("it is negated"),
                    (";", 2) | ("->", 2) | ("*->", 2) | ("|", 2) => Some("it is a disjunction"),
                    (":-", _) => Some("it is a rule"),
                    (n, a) if super::builtins::is_builtin(n, a) => {
                        Some("it is a built-in predicate")
                    }
                    _ => None,
                },
            };
            if let Some(why) = why {
                ctx.error(
                    "E0110",
                    format!("goal `{}` is not a positive conjunction: {why}", g.term),
                    c.span.clone(),
                    "a goal is a conjunction of facts such as `on(a, b), on(b, table)`",
                );
            }
        }
    }
}

/// Variables of a selector that are not yet bound (reported as E0114).
fn selector(ctx: &mut Ctx<'_>, s: &Selector, bound: &VarSet) {
    if let SelectorKind::Agents(ts) = &s.kind {
        for t in ts {
            if let Some((v, span)) = var_occurrences(t)
                .into_iter()
                .find(|(v, _)| !bound.contains(v))
            {
                ctx.error(
                    "E0114",
                    format!("variable `{}` in a selector is not bound", var_name(v)),
                    span,
                    "bind the variable in an earlier literal of the condition, e.g. `bel(agent(A))`",
                );
            }
        }
    }
}

/// Binds the variables of the condition literals in order; returns the bound set after them.
fn condition(ctx: &mut Ctx<'_>, lits: &[Literal], bound: &VarSet) -> VarSet {
    let mut bound = bound.clone();
    for l in lits {
        match &l.kind {
            LiteralKind::Mental {
                negated,
                selector: s,
                query,
                ..
            } => {
                selector(ctx, s, &bound);
                if !negated {
                    bound.extend(binding_vars(query));
                }
            }
            LiteralKind::MacroUse { name, args } => {
                let key = (name.name.name().to_string(), args.len());
                // A macro binds the arguments whose parameters its body binds (macros are
                // scoped per module: any definition of the name counts); an unknown macro
                // (imported, or reported as undefined) is assumed to bind them all.
                let binds = ctx.macro_index.get(&key).map(|defs| {
                    (0..args.len())
                        .map(|i| {
                            defs.iter().any(|m| {
                                let body = positive_bindings(&m.body);
                                m.params.get(i).is_some_and(|p| {
                                    var_set(&p.term).iter().all(|v| body.contains(v))
                                })
                            })
                        })
                        .collect::<Vec<bool>>()
                });
                for (i, a) in args.iter().enumerate() {
                    if binds
                        .as_ref()
                        .is_none_or(|b| b.get(i).copied().unwrap_or(true))
                    {
                        bound.extend(var_set(&a.term));
                    }
                }
            }
            LiteralKind::True => {}
        }
    }
    bound
}

/// The variables that the positive literals of a macro body bind (nested macros bind their
/// arguments).
fn positive_bindings(lits: &[Literal]) -> VarSet {
    let mut out = VarSet::new();
    for l in lits {
        match &l.kind {
            LiteralKind::Mental {
                negated: false,
                query,
                ..
            } => out.extend(binding_vars(query)),
            LiteralKind::MacroUse { args, .. } => {
                args.iter().for_each(|a| out.extend(var_set(&a.term)))
            }
            _ => {}
        }
    }
    out
}

fn rule(ctx: &mut Ctx<'_>, r: &Rule, outer: &VarSet) {
    let after = condition(ctx, &r.condition, outer);
    let body_bound: VarSet = match &r.kind {
        RuleKind::Listall { var } => {
            let mut b = outer.clone();
            b.extend(var_set(&var.term));
            b
        }
        _ => after,
    };
    match &r.body {
        RuleBody::Combo(actions) => {
            for a in actions {
                action(ctx, a, &body_bound, &r.kind);
            }
        }
        RuleBody::Block(rules) => {
            for inner in rules {
                rule(ctx, inner, &body_bound);
            }
        }
    }
}

fn unbound(ctx: &mut Ctx<'_>, t: &Located, bound: &VarSet, kind: &RuleKind, skip_anonymous: bool) {
    let found = var_occurrences(t)
        .into_iter()
        .find(|(v, _)| !(bound.contains(v) || skip_anonymous && is_anonymous(*v)));
    if let Some((v, span)) = found {
        let hint = match kind {
            RuleKind::Listall { .. } => {
                "in a listall rule only the list variable (and module parameters) are bound in the body"
            }
            _ => "bind it in the rule condition (or make it a module parameter)",
        };
        ctx.error(
            "E0113",
            format!(
                "variable `{}` is not bound by the rule condition",
                var_name(v)
            ),
            span,
            hint,
        );
    }
}

fn action(ctx: &mut Ctx<'_>, a: &Action, bound: &VarSet, kind: &RuleKind) {
    match &a.kind {
        ActionKind::Adopt {
            selector: s,
            content,
        }
        | ActionKind::Drop {
            selector: s,
            content,
        }
        | ActionKind::Insert {
            selector: s,
            content,
        }
        | ActionKind::Delete {
            selector: s,
            content,
        } => {
            selector(ctx, s, bound);
            unbound(ctx, content, bound, kind, false);
        }
        ActionKind::Send {
            selector: s,
            mood,
            content,
        }
        | ActionKind::SendOnce {
            selector: s,
            mood,
            content,
        } => {
            selector(ctx, s, bound);
            if *mood != Mood::Interrogative {
                unbound(ctx, content, bound, kind, false);
            }
        }
        ActionKind::Print(t) | ActionKind::Log(t) => unbound(ctx, t, bound, kind, false),
        // `_` arguments are reported as E0115 by the action checks.
        ActionKind::Call { args, .. } | ActionKind::Timing { args, .. } => {
            for arg in args {
                unbound(ctx, arg, bound, kind, true);
            }
        }
        ActionKind::ExitModule | ActionKind::BuiltinModule(_) => {}
    }
}
