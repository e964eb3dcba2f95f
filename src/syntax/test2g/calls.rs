//! Actions, module calls and macros used in a test must exist in the programs of the tested
//! agents (found through the MAS file's launch rules).

use super::ast::{MasTest, TemporalCondition, TestCondition, TestSection};
use crate::diag::Diagnostic;
use crate::syntax::ast::{Action, ActionKind, Ident, Literal, LiteralKind, ModuleKind};
use crate::syntax::mas2g::MasFile;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

type Key = (String, usize);

/// What one agent program offers to a test: actions and modules, and macros.
#[derive(Default)]
struct Offers {
    callable: BTreeSet<Key>,
    macros: BTreeSet<Key>,
}

fn offers(path: &Path) -> Option<Offers> {
    let text = crate::syntax::check::read_source(path).ok()?;
    let (program, _) = crate::syntax::goal::parse_goal(&path.display().to_string(), &text);
    // Modules of imported `.mod2g` files are the program's too.
    let dir = path.parent().unwrap_or(Path::new("."));
    let imports = crate::syntax::goal::imports::read_imports(&program, dir);
    let mut o = Offers::default();
    let imported = imports.modules.iter().map(|m| &m.module);
    for m in program.modules.iter().chain(imported) {
        if let ModuleKind::User { name, params } = &m.kind {
            o.callable
                .insert((name.name.name().to_string(), params.len()));
        }
        for s in &m.action_specs {
            o.callable
                .insert((s.name.name.name().to_string(), s.params.len()));
        }
        if let Some(p) = &m.program {
            o.macros.extend(
                p.macros
                    .iter()
                    .map(|x| (x.name.name.name().to_string(), x.params.len())),
            );
        }
    }
    Some(o)
}

/// The calls (name, arity, name span) and macro uses of a test block.
#[derive(Default)]
struct Used<'a> {
    calls: Vec<(&'a Ident, usize)>,
    macros: Vec<(&'a Ident, usize)>,
}

impl<'a> Used<'a> {
    fn action(&mut self, a: &'a Action) {
        if let ActionKind::Call { name, args } = &a.kind {
            self.calls.push((name, args.len()));
        }
    }
    fn literals(&mut self, ls: &'a [Literal]) {
        for l in ls {
            if let LiteralKind::MacroUse { name, args } = &l.kind {
                self.macros.push((name, args.len()));
            }
        }
    }
    fn condition(&mut self, c: &'a TestCondition) {
        self.literals(&c.literals);
        if let Some(d) = &c.done {
            self.action(&d.action);
        }
    }
}

/// Variables in the actions that a test runs (`do ...` and `in do ...`) can never be bound.
pub fn check_ground(test: &MasTest) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    let combos = test
        .agents
        .iter()
        .flat_map(|a| &a.tests)
        .flat_map(|t| &t.sections)
        .map(|s| match s {
            TestSection::Do { combo, .. } | TestSection::Evaluate { combo, .. } => combo.as_slice(),
            TestSection::Assert { .. } => &[],
        });
    for a in combos.flatten() {
        let terms: Vec<&crate::syntax::prolog::Located> = match &a.kind {
            ActionKind::Adopt { content, .. }
            | ActionKind::Drop { content, .. }
            | ActionKind::Insert { content, .. }
            | ActionKind::Delete { content, .. } => vec![content],
            ActionKind::Send { mood, content, .. } | ActionKind::SendOnce { mood, content, .. } => {
                if *mood == crate::syntax::ast::Mood::Interrogative {
                    vec![]
                } else {
                    vec![content]
                }
            }
            ActionKind::Print(t) | ActionKind::Log(t) => vec![t],
            ActionKind::Call { args, .. } | ActionKind::Timing { args, .. } => {
                args.iter().collect()
            }
            ActionKind::ExitModule | ActionKind::BuiltinModule(_) => vec![],
        };
        let found = terms.into_iter().find_map(|t| {
            crate::syntax::validate::terms::var_occurrences(t)
                .into_iter()
                .next()
        });
        if let Some((v, span)) = found {
            diags.push(
                Diagnostic::error(
                    "E0311",
                    format!(
                        "variable `{}` in a test action can never be bound",
                        crate::syntax::validate::terms::var_name(v)
                    ),
                    test.file.clone(),
                    span,
                )
                .with_hint("actions that a test runs must be ground: write the value"),
            );
        }
    }
    diags
}

/// Checks the calls and macro uses of `test` against the programs of the tested agents.
pub fn check_calls(test: &MasTest, mas: &MasFile, mas_dir: &Path) -> Vec<Diagnostic> {
    let mut diags = Vec::new();
    let mut cache: BTreeMap<PathBuf, Option<Offers>> = BTreeMap::new();
    for block in &test.agents {
        let mut files: Vec<PathBuf> = Vec::new();
        for name in &block.agents {
            for f in mas.agent_files_for(name.name.name()) {
                let p = mas_dir.join(&f.path.value);
                if !files.contains(&p) {
                    files.push(p);
                }
            }
        }
        let mut known = Offers::default();
        let mut any = false;
        for f in files {
            let o = cache.entry(f.clone()).or_insert_with(|| offers(&f));
            if let Some(o) = o {
                any = true;
                known.callable.extend(o.callable.iter().cloned());
                known.macros.extend(o.macros.iter().cloned());
            }
        }
        if !any {
            continue; // reported elsewhere (agent not launched, or its file is missing)
        }
        let mut used = Used::default();
        for t in &block.tests {
            for s in &t.sections {
                match s {
                    TestSection::Do { combo, .. } => combo.iter().for_each(|a| used.action(a)),
                    TestSection::Assert { condition, .. } => used.literals(condition),
                    TestSection::Evaluate {
                        conditions,
                        combo,
                        boundary,
                        ..
                    } => {
                        combo.iter().for_each(|a| used.action(a));
                        if let Some(b) = boundary {
                            used.condition(&b.condition);
                        }
                        for c in conditions {
                            match c {
                                TemporalCondition::Chain { parts, .. } => {
                                    parts.iter().for_each(|p| used.condition(&p.condition))
                                }
                                TemporalCondition::ReactTo {
                                    trigger, reaction, ..
                                } => {
                                    used.condition(trigger);
                                    used.condition(reaction);
                                }
                            }
                        }
                    }
                }
            }
        }
        let agents: Vec<&str> = block.agents.iter().map(|i| i.name.name()).collect();
        for (name, arity) in used.calls {
            if !known
                .callable
                .contains(&(name.name.name().to_string(), arity))
            {
                diags.push(
                    Diagnostic::error(
                        "E0309",
                        format!(
                            "the program of `{}` has no action or module `{}/{arity}`",
                            agents.join("`, `"),
                            name.name.name()
                        ),
                        test.file.clone(),
                        name.span.clone(),
                    )
                    .with_hint(
                        "tests can call the agent's action specs and modules, and init/main/event",
                    ),
                );
            }
        }
        for (name, arity) in used.macros {
            if !known
                .macros
                .contains(&(name.name.name().to_string(), arity))
            {
                diags.push(
                    Diagnostic::error(
                        "E0310",
                        format!("the program of `{}` has no macro `{}/{arity}`", agents.join("`, `"), name.name.name()),
                        test.file.clone(),
                        name.span.clone(),
                    )
                    .with_hint("use `bel(...)`/`goal(...)` literals, or a macro defined with `#define` in the agent"),
                );
            }
        }
    }
    diags
}
