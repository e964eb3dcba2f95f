//! Module structure: main/event present, program sections, duplicate and unused modules,
//! module parameters, and the `exit`/`focus` options of built-in modules.

use super::{call_key, module_key, Ctx};
use crate::syntax::ast::ModuleKind;

/// Runs the module checks.
pub fn check(ctx: &mut Ctx<'_>) {
    let modules = ctx.modules.clone();
    let has_main_or_event = modules
        .iter()
        .any(|m| matches!(m.kind, ModuleKind::Main | ModuleKind::Event));
    if ctx.module_file {
        // A module file is imported into a program that has the main/event modules.
    } else if !has_main_or_event && !modules.is_empty() {
        let span = modules[0].head_span.clone();
        ctx.error(
            "E0101",
            "the program has neither a `main` nor an `event` module",
            span,
            "add `main module { program { ... } }` (the agent's decisions) or an `event` module",
        );
    } else if modules.is_empty() && ctx.program.imports.is_empty() {
        ctx.error(
            "E0101",
            "the program has no modules",
            0..0,
            "add `main module { program { ... } }`",
        );
    }
    for m in &modules {
        let what = describe(m);
        match &m.program {
            None if !matches!(m.kind, ModuleKind::Init) => ctx.error(
                "E0102",
                format!("{what} has no `program` section"),
                m.head_span.clone(),
                "add `program { ... }` with the module's rules (only `init` may leave it out)",
            ),
            Some(p) if p.rules.is_empty() => ctx.warning(
                "W0104",
                format!("the program of {what} has no rules"),
                p.span.clone(),
                "add rules, or remove the empty `program` section",
            ),
            _ => {}
        }
        if let ModuleKind::User { params, .. } = &m.kind {
            for p in params {
                if !p.term.is_var() {
                    ctx.error(
                        "E0108",
                        format!("module parameter `{}` is not a variable", p.term),
                        p.spans.span.clone(),
                        "module parameters are variables, e.g. `module go(Room)`",
                    );
                }
            }
            super::actions::duplicate_params(ctx, params, "module");
        }
        let builtin = matches!(
            m.kind,
            ModuleKind::Init | ModuleKind::Main | ModuleKind::Event | ModuleKind::Shutdown
        );
        if let Some(exit) = &m.options.exit {
            if matches!(
                m.kind,
                ModuleKind::Init | ModuleKind::Event | ModuleKind::Shutdown
            ) {
                ctx.warning(
                    "W0108",
                    format!("the `exit` option of {what} is ignored"),
                    option_span(m, "exit").unwrap_or(exit.span.clone()),
                    "init and event modules always run one pass; remove the option",
                );
            }
        }
        if let Some(focus) = &m.options.focus {
            if builtin {
                ctx.warning(
                    "W0109",
                    format!("the `focus` option is not allowed on {what}; it is ignored"),
                    option_span(m, "focus").unwrap_or(focus.span.clone()),
                    "focus applies to user modules that are called from rules; remove the option",
                );
            }
        }
    }
    // Duplicate modules.
    let dups: Vec<_> = ctx
        .module_index
        .iter()
        .filter(|(_, ms)| ms.len() > 1)
        .map(|(k, ms)| {
            (
                k.clone(),
                ms[1..]
                    .iter()
                    .map(|m| m.head_span.clone())
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    for ((name, arity), spans) in dups {
        for span in spans {
            ctx.error(
                "E0103",
                format!("module `{name}/{arity}` is defined more than once"),
                span,
                "rename one of the modules; modules are identified by name and arity",
            );
        }
    }
    let builtin_kinds = |k: &ModuleKind| match k {
        ModuleKind::Init => Some("init"),
        ModuleKind::Main => Some("main"),
        ModuleKind::Event => Some("event"),
        ModuleKind::Shutdown => Some("shutdown"),
        ModuleKind::User { .. } => None,
    };
    let mut seen = Vec::new();
    for m in &modules {
        if let Some(n) = builtin_kinds(&m.kind) {
            if seen.contains(&n) {
                ctx.error(
                    "E0103",
                    format!("there is more than one `{n}` module"),
                    m.head_span.clone(),
                    format!("merge the two `{n}` modules into one"),
                );
            }
            seen.push(n);
        }
    }
    // Unused user modules (never called by a rule).
    if ctx.module_file {
        return;
    }
    let called: std::collections::BTreeSet<_> = ctx
        .actions()
        .into_iter()
        .filter_map(|(_, a)| call_key(a).map(|(k, _)| k))
        .collect();
    for m in &modules {
        if let (Some(k), ModuleKind::User { name, .. }) = (module_key(m), &m.kind) {
            if !called.contains(&k) {
                ctx.warning(
                    "W0102",
                    format!("module `{}/{}` is never called", k.0, k.1),
                    name.span.clone(),
                    "call it from a rule, or remove it",
                );
            }
        }
    }
}

/// `init module`, `module foo/2`, ... for messages.
pub fn describe(m: &crate::syntax::ast::Module) -> String {
    match &m.kind {
        ModuleKind::Init => "the init module".into(),
        ModuleKind::Main => "the main module".into(),
        ModuleKind::Event => "the event module".into(),
        ModuleKind::Shutdown => "the shutdown module".into(),
        ModuleKind::User { name, params } => {
            format!("module `{}/{}`", name.name.name(), params.len())
        }
    }
}

/// The span of the written option `key=...` of `m`.
fn option_span(m: &crate::syntax::ast::Module, key: &str) -> Option<crate::diag::Span> {
    m.options
        .written
        .iter()
        .find(|o| o.key.name.name() == key)
        .map(|o| o.span.clone())
}
