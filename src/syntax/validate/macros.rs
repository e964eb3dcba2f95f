//! `#define` macros: duplicates, ill-formed definitions (a parameter that is not a variable or
//! does not occur in the body), uses of undefined macros, and unused macros.

use super::terms::{is_anonymous, var_set, VarSet};
use super::{macro_use_key, Ctx, Key};
use crate::syntax::ast::{LiteralKind, Macro};
use crate::term::Term;
use std::collections::BTreeSet;

/// A macro defined twice in one module. Macros are scoped per module (a use finds its own
/// module's macro first), so one name in two modules is allowed, as in GOAL.
fn duplicates(ctx: &mut Ctx<'_>) {
    let mut twice = Vec::new();
    for m in &ctx.modules {
        let mut seen = BTreeSet::new();
        for d in m.program.iter().flat_map(|p| p.macros.iter()) {
            let key = (d.name.name.name().to_string(), d.params.len());
            if !seen.insert(key.clone()) {
                twice.push((key, d.name.span.clone()));
            }
        }
    }
    for ((name, arity), span) in twice {
        ctx.error(
            "E0117",
            format!("macro `{name}/{arity}` is defined more than once in this module"),
            span,
            "rename or remove one definition",
        );
    }
}

/// Runs the macro checks.
pub fn check(ctx: &mut Ctx<'_>) {
    let index: Vec<(Key, Vec<&Macro>)> = ctx
        .macro_index
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    let uses: BTreeSet<Key> = ctx
        .literals()
        .into_iter()
        .filter_map(macro_use_key)
        .collect();
    duplicates(ctx);
    for ((name, arity), defs) in &index {
        for d in defs {
            well_formed(ctx, d);
        }
        if !ctx.module_file && !uses.contains(&(name.clone(), *arity)) {
            ctx.warning(
                "W0103",
                format!("macro `{name}/{arity}` is never used"),
                defs[0].name.span.clone(),
                "use it in a rule condition, or remove it",
            );
        }
    }
    for l in ctx.literals() {
        let LiteralKind::MacroUse { name, .. } = &l.kind else {
            continue;
        };
        let Some(key) = macro_use_key(l) else {
            continue;
        };
        if ctx.module_file
            || ctx.macro_index.contains_key(&key)
            || ctx.imported.macros.contains(&key)
        {
            continue;
        }
        let others: Vec<String> = ctx
            .macro_index
            .keys()
            .filter(|(n, _)| *n == key.0)
            .map(|(n, a)| format!("{n}/{a}"))
            .collect();
        let known = ctx
            .macro_index
            .keys()
            .chain(ctx.imported.macros.iter())
            .map(|(n, a)| (n.as_str(), *a));
        let near = crate::suggest::closest_arity(&key.0, key.1, known);
        let hint = if let Some((n, a)) = near.filter(|_| others.is_empty()) {
            format!("did you mean the macro `{n}/{a}`?")
        } else if others.is_empty() {
            format!(
                "define it with `#define {}(...) condition.` at the top of a program section",
                key.0
            )
        } else {
            format!(
                "the macro is defined as {}; pass as many arguments",
                others.join(", ")
            )
        };
        ctx.error(
            "E0118",
            format!("undefined macro `{}/{}`", key.0, key.1),
            name.span.clone(),
            hint,
        );
    }
}

fn well_formed(ctx: &mut Ctx<'_>, d: &Macro) {
    let mut body_vars = VarSet::new();
    for l in &d.body {
        match &l.kind {
            LiteralKind::Mental {
                query, selector, ..
            } => {
                body_vars.extend(var_set(&query.term));
                if let crate::syntax::ast::SelectorKind::Agents(ts) = &selector.kind {
                    for t in ts {
                        body_vars.extend(var_set(&t.term));
                    }
                }
            }
            LiteralKind::MacroUse { args, .. } => {
                for a in args {
                    body_vars.extend(var_set(&a.term));
                }
            }
            LiteralKind::True => {}
        }
    }
    let name = d.name.name.name();
    for p in &d.params {
        match &p.term {
            Term::Var(v) if is_anonymous(*v) || !body_vars.contains(v) => ctx.error(
                "E0119",
                format!(
                    "parameter `{}` of macro `{name}` does not occur in its body",
                    super::terms::var_name(*v)
                ),
                p.spans.span.clone(),
                "use the parameter in the macro's condition, or remove it",
            ),
            Term::Var(_) => {}
            other => ctx.error(
                "E0119",
                format!("parameter `{other}` of macro `{name}` is not a variable"),
                p.spans.span.clone(),
                "macro parameters are variables",
            ),
        }
    }
}
