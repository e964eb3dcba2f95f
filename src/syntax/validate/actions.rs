//! Action specs and actions: duplicate and unused specs, spec parameters, `post` variables,
//! calls of undefined actions or modules and arity mismatches, `_` arguments, update contents,
//! send receivers, and actions after `exit-module`.

use super::terms::{conjuncts, is_anonymous, var_name, var_occurrences, var_set, Sub, VarSet};
use super::{call_key, Ctx, Key};
use crate::syntax::ast::{ActionKind, RuleBody, SelectorKind};
use crate::syntax::prolog::Located;
use std::collections::BTreeSet;

/// Runs the action checks.
pub fn check(ctx: &mut Ctx<'_>) {
    specs(ctx);
    calls(ctx);
    contents(ctx);
    after_exit(ctx);
}

/// Reports parameters that occur twice (`what` is "action" or "module"): an error in an action
/// spec, a warning in a module head.
pub fn duplicate_params(ctx: &mut Ctx<'_>, params: &[Located], what: &str) {
    let mut seen = VarSet::new();
    for p in params {
        if let crate::term::Term::Var(v) = &p.term {
            if seen.insert(*v) || is_anonymous(*v) {
                continue;
            }
            let msg = format!("parameter `{}` occurs twice in the {what} head", v.name());
            let span = p.spans.span.clone();
            if what == "module" {
                // GOAL accepted this: a call then needs equal arguments for the two places.
                ctx.warning(
                    "W0113",
                    msg,
                    span,
                    "a call must pass equal arguments here, or it stops the agent; use distinct variables",
                );
            } else {
                ctx.error("E0106", msg, span, "parameters must be distinct variables");
            }
        }
    }
}

fn specs(ctx: &mut Ctx<'_>) {
    let index: Vec<(Key, Vec<_>)> = ctx
        .spec_index
        .iter()
        .map(|(k, v)| (k.clone(), v.clone()))
        .collect();
    let used: BTreeSet<Key> = ctx
        .actions()
        .into_iter()
        .filter_map(|(_, a)| call_key(a).map(|(k, _)| k))
        .collect();
    for ((name, arity), specs) in index {
        for s in &specs[1..] {
            ctx.error(
                "E0103",
                format!("action `{name}/{arity}` is specified more than once"),
                s.name.span.clone(),
                "keep one spec per name and arity (the first one is used)",
            );
        }
        if ctx.module_index.contains_key(&(name.clone(), arity)) {
            ctx.error(
                "E0103",
                format!("`{name}/{arity}` is both an action and a module"),
                specs[0].name.span.clone(),
                "actions and modules share one namespace; rename one of them",
            );
        }
        if !ctx.module_file && !used.contains(&(name.clone(), arity)) {
            ctx.warning(
                "W0101",
                format!("action `{name}/{arity}` is never used"),
                specs[0].name.span.clone(),
                "use it in a rule, or remove its spec",
            );
        }
        for s in &specs {
            spec(ctx, s);
        }
    }
}

fn spec(ctx: &mut Ctx<'_>, s: &crate::syntax::ast::ActionSpec) {
    let name = s.name.name.name();
    let mut params = VarSet::new();
    for p in &s.params {
        match &p.term {
            crate::term::Term::Var(v) => {
                params.insert(*v);
            }
            other => ctx.error(
                "E0108",
                format!("parameter `{other}` of action `{name}` is not a variable"),
                p.spans.span.clone(),
                "action parameters are variables; test values in the precondition instead",
            ),
        }
    }
    duplicate_params(ctx, &s.params, "action");
    for (cond, which) in [(&s.pre, "pre"), (&s.post, "post")] {
        if cond.empty {
            ctx.warning(
                "W0105",
                format!("empty `{which}` of action `{name}`"),
                cond.span.clone(),
                format!("write `{which} {{ true }}` if that is what you mean"),
            );
        }
    }
    let pre_vars = var_set(&s.pre.term.term);
    for (v, span) in var_occurrences(&s.post.term) {
        if !params.contains(&v) && !pre_vars.contains(&v) {
            ctx.error(
                "E0107",
                format!("variable `{}` in the postcondition of `{name}` is not bound by its parameters or precondition", var_name(v)),
                span,
                "bind it in the precondition or make it a parameter",
            );
            break;
        }
    }
    let post_vars = var_set(&s.post.term.term);
    // The parameters of an environment action are used: they go to the environment.
    let internal = matches!(s.kind, crate::syntax::ast::ActionSpecKind::Int);
    for p in s.params.iter().filter(|_| internal) {
        if let crate::term::Term::Var(v) = &p.term {
            if !is_anonymous(*v) && !pre_vars.contains(v) && !post_vars.contains(v) {
                ctx.warning(
                    "W0106",
                    format!(
                        "parameter `{}` of action `{name}` is used in neither pre nor post",
                        v.name()
                    ),
                    p.spans.span.clone(),
                    "an internal action only changes beliefs: use the parameter in pre or post, or drop it",
                );
            }
        }
    }
    update_literals(ctx, &s.post.term, "the postcondition", false);
}

fn calls(ctx: &mut Ctx<'_>) {
    for (_, a) in ctx.actions() {
        let (Some((key, span)), ActionKind::Call { args, .. }) = (call_key(a), &a.kind) else {
            continue;
        };
        let known = ctx.spec_index.contains_key(&key)
            || ctx.module_index.contains_key(&key)
            || ctx.imported.specs.contains(&key)
            || ctx.imported.modules.contains(&key);
        if !known && !ctx.module_file {
            let mut arities: Vec<usize> = ctx
                .spec_index
                .keys()
                .chain(ctx.module_index.keys())
                .chain(ctx.imported.specs.iter())
                .chain(ctx.imported.modules.iter())
                .filter(|(n, _)| *n == key.0)
                .map(|(_, a)| *a)
                .collect();
            arities.sort();
            arities.dedup();
            if arities.is_empty() {
                let known = ctx
                    .spec_index
                    .keys()
                    .chain(ctx.module_index.keys())
                    .chain(ctx.imported.specs.iter())
                    .chain(ctx.imported.modules.iter())
                    .map(|(n, a)| (n.as_str(), *a));
                let hint = match crate::suggest::closest_arity(&key.0, key.1, known) {
                    Some((n, a)) => format!("did you mean `{n}/{a}`?"),
                    None => format!(
                        "add an action spec `{}` in an `actionspec` section, or a module of that name",
                        head(&key)
                    ),
                };
                ctx.error(
                    "E0104",
                    format!(
                        "action or module `{}/{}` is used but never specified",
                        key.0, key.1
                    ),
                    span,
                    hint,
                );
            } else {
                let list: Vec<String> = arities.iter().map(|n| format!("{}/{n}", key.0)).collect();
                ctx.error(
                    "E0105",
                    format!(
                        "`{}` is called with {} argument{}, but only {} {}",
                        key.0,
                        key.1,
                        if key.1 == 1 { "" } else { "s" },
                        list.join(", "),
                        if list.len() == 1 { "exists" } else { "exist" }
                    ),
                    a.span.clone(),
                    "pass as many arguments as the action spec or module has parameters",
                );
            }
        }
        for arg in args {
            if let Some((_, s)) = var_occurrences(arg)
                .into_iter()
                .find(|(v, _)| is_anonymous(*v))
            {
                ctx.error(
                    "E0115",
                    format!("`_` as an argument of `{}`", key.0),
                    s,
                    "actions and module calls need values: bind a named variable in the rule condition",
                );
            }
        }
    }
}

fn head(key: &Key) -> String {
    if key.1 == 0 {
        return key.0.clone();
    }
    let params: Vec<String> = (1..=key.1).map(|i| format!("P{i}")).collect();
    format!("{}({})", key.0, params.join(", "))
}

fn contents(ctx: &mut Ctx<'_>) {
    for (_, a) in ctx.actions() {
        match &a.kind {
            ActionKind::Adopt { content, .. } => update_literals(ctx, content, "`adopt`", true),
            ActionKind::Drop { content, .. } => update_literals(ctx, content, "`drop`", true),
            ActionKind::Delete { content, .. } => update_literals(ctx, content, "`delete`", true),
            ActionKind::Insert { content, .. } => update_literals(ctx, content, "`insert`", false),
            ActionKind::Send { selector, .. } | ActionKind::SendOnce { selector, .. } => {
                let word = match selector.kind {
                    SelectorKind::This => "this",
                    SelectorKind::Some => "some",
                    SelectorKind::SomeOther => "someother",
                    _ => continue,
                };
                if let Some(span) = &selector.span {
                    ctx.error(
                        "E0116",
                        format!("a message cannot be sent to `{word}`"),
                        span.clone(),
                        "send to `all`, `allother`, `self` or a list of agents such as `(bob, carol)`",
                    );
                }
            }
            _ => {}
        }
    }
}

/// Checks that `content` is a conjunction of literals; `positive_only` for adopt/drop/delete.
fn update_literals(ctx: &mut Ctx<'_>, content: &Located, what: &str, positive_only: bool) {
    let parts = conjuncts(Sub::of(content));
    let trivial = parts.iter().all(|p| {
        p.term
            .functor()
            .is_some_and(|(n, a)| n.name() == "true" && a == 0)
    });
    if trivial && what != "the postcondition" {
        ctx.error(
            "E0111",
            format!("empty update in {what}"),
            content.spans.span.clone(),
            "write the facts to change; `true` changes nothing",
        );
        return;
    }
    for p in parts {
        let Some((name, arity)) = p.term.functor() else {
            ctx.error(
                "E0124",
                format!("`{}` in {what} is not a fact", p.term),
                p.span.clone(),
                "an update is a conjunction of facts `p(...)` and negated facts `not(p(...))`",
            );
            continue;
        };
        let n = name.name();
        if n == "not" && arity == 1 {
            if positive_only {
                ctx.error(
                    "E0112",
                    format!("`not(...)` inside {what}"),
                    p.span.clone(),
                    "adopt, drop and delete take positive facts only; use `insert(not(...))` to remove a belief",
                );
            }
            continue;
        }
        let bad = match (n, arity) {
            (";", 2) | ("->", 2) | ("*->", 2) | ("|", 2) => Some("a disjunction or if-then-else"),
            (":-", 2) | (":-", 1) | ("-->", 2) => Some("a rule"),
            ("\\+", 1) => Some("`\\+` (write `not(...)` for a negative literal)"),
            _ if super::builtins::is_builtin(n, arity) && n != "true" => {
                Some("a built-in predicate")
            }
            _ => None,
        };
        if let Some(why) = bad {
            ctx.error(
                "E0124",
                format!("{what} contains {why}: `{}`", p.term),
                p.span.clone(),
                "an update is a conjunction of facts `p(...)` and negated facts `not(p(...))`",
            );
        }
    }
}

fn after_exit(ctx: &mut Ctx<'_>) {
    for (_, r) in ctx.rules() {
        if let RuleBody::Combo(actions) = &r.body {
            if let Some(i) = actions
                .iter()
                .position(|a| matches!(a.kind, ActionKind::ExitModule))
            {
                if let Some(next) = actions.get(i + 1) {
                    ctx.warning(
                        "W0107",
                        "action after `exit-module` is never executed",
                        next.span.clone(),
                        "move `exit-module` to the end of the combo",
                    );
                }
            }
        }
    }
}
