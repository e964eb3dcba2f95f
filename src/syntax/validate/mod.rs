//! The validator of `.goal` programs: every error and warning the 2014
//! validator gave, over the AST, each pointing at the exact span with a hint.
//!
//! Entry point: [`validate`]. Concerns are split by file: module structure (`modules`), action
//! specs and calls (`actions`), variable binding (`variables`), macros (`macros`) and KR
//! predicates (`predicates`). The built-in predicate names live in `builtins`.

mod actions;
pub mod builtins;
mod macros;
mod modules;
mod predicates;
pub mod terms;
mod variables;

use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::{
    Action, ActionKind, ActionSpec, AgentProgram, Literal, LiteralKind, Macro, Module, ModuleKind,
    Rule, RuleBody,
};
use crate::syntax::goal::imports::Imports;
use crate::syntax::prolog::Located;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Name/arity keys defined by imported `.mod2g` files.
#[derive(Default)]
pub struct Imported {
    pub modules: BTreeSet<Key>,
    pub specs: BTreeSet<Key>,
    pub macros: BTreeSet<Key>,
}

/// A name/arity key (by name, so maps iterate in a deterministic, readable order).
pub type Key = (String, usize);

/// Everything the checks share: the program, the file name, name/arity indexes, and the
/// diagnostics found so far.
pub struct Ctx<'a> {
    pub program: &'a AgentProgram,
    pub file: &'a str,
    /// The modules of the program (those of imported `.mod2g` files are only indexed).
    pub modules: Vec<&'a Module>,
    /// Names of modules, action specs and macros of imported `.mod2g` files (for resolution).
    pub imported: Imported,
    /// User modules by name/arity (several entries: duplicates).
    pub module_index: BTreeMap<Key, Vec<&'a Module>>,
    /// Action specs of all modules by name/arity.
    pub spec_index: BTreeMap<Key, Vec<&'a ActionSpec>>,
    /// Macros of all modules by name/arity.
    pub macro_index: BTreeMap<Key, Vec<&'a Macro>>,
    /// Clauses of imported `.pl` files (knowledge).
    pub imported_knowledge: Vec<Located>,
    pub diags: Vec<Diagnostic>,
    /// True when checking a `.mod2g` file on its own: checks that need the whole program
    /// (undefined names, unused definitions, a main module) are skipped.
    pub module_file: bool,
}

impl<'a> Ctx<'a> {
    /// Adds an error.
    pub fn error(
        &mut self,
        code: &str,
        msg: impl Into<String>,
        span: Span,
        hint: impl Into<String>,
    ) {
        self.diags
            .push(Diagnostic::error(code, msg, self.file, span).with_hint(hint));
    }

    /// Adds a warning.
    pub fn warning(
        &mut self,
        code: &str,
        msg: impl Into<String>,
        span: Span,
        hint: impl Into<String>,
    ) {
        self.diags
            .push(Diagnostic::warning(code, msg, self.file, span).with_hint(hint));
    }

    /// Every rule of every module (nested rules included) with its module, in source order.
    pub fn rules(&self) -> Vec<(&'a Module, &'a Rule)> {
        let mut out = Vec::new();
        for m in &self.modules {
            if let Some(p) = &m.program {
                let mut stack: Vec<&'a Rule> = p.rules.iter().rev().collect();
                while let Some(r) = stack.pop() {
                    out.push((*m, r));
                    if let RuleBody::Block(rs) = &r.body {
                        stack.extend(rs.iter().rev());
                    }
                }
            }
        }
        out
    }

    /// Every action in rule bodies, with its module.
    pub fn actions(&self) -> Vec<(&'a Module, &'a Action)> {
        let mut out = Vec::new();
        for (m, r) in self.rules() {
            if let RuleBody::Combo(actions) = &r.body {
                out.extend(actions.iter().map(|a| (m, a)));
            }
        }
        out
    }

    /// Every literal of rule conditions and macro bodies.
    pub fn literals(&self) -> Vec<&'a Literal> {
        let mut out: Vec<&'a Literal> = Vec::new();
        for (_, r) in self.rules() {
            out.extend(r.condition.iter());
        }
        for ms in self.macro_index.values() {
            for m in ms {
                out.extend(m.body.iter());
            }
        }
        out
    }
}

/// The name/arity key of a user module, if `m` is one.
pub fn module_key(m: &Module) -> Option<Key> {
    match &m.kind {
        ModuleKind::User { name, params } => Some((name.name.name().to_string(), params.len())),
        _ => None,
    }
}

/// The name/arity a call action refers to.
pub fn call_key(a: &Action) -> Option<(Key, Span)> {
    match &a.kind {
        ActionKind::Call { name, args } => Some((
            (name.name.name().to_string(), args.len()),
            name.span.clone(),
        )),
        _ => None,
    }
}

/// The name/arity a macro use refers to.
pub fn macro_use_key(l: &Literal) -> Option<Key> {
    match &l.kind {
        LiteralKind::MacroUse { name, args } => Some((name.name.name().to_string(), args.len())),
        _ => None,
    }
}

/// Checks the clauses of a standalone `.pl` file: protected predicates and directives.
pub fn validate_prolog(clauses: &[Located], file: &str) -> Vec<Diagnostic> {
    predicates::check_prolog_clauses(clauses, file)
}

/// Validates `program`; `base_dir` is the directory that `#import` paths are relative to (no
/// file checks when `None`). Returns every error and warning, sorted by position.
pub fn validate(program: &AgentProgram, base_dir: Option<&Path>) -> Vec<Diagnostic> {
    run(program, &read(program, base_dir), false)
}

/// Validates `program` with its imports already read (see `syntax::goal::imports`).
pub fn validate_with(program: &AgentProgram, imports: &Imports) -> Vec<Diagnostic> {
    run(program, imports, false)
}

fn read(program: &AgentProgram, base_dir: Option<&Path>) -> Imports {
    match base_dir {
        Some(dir) => crate::syntax::goal::imports::read_imports(program, dir),
        None => Imports::default(),
    }
}

/// Validates a `.mod2g` module file on its own: the checks that do not need the program that
/// imports it.
pub fn validate_module_file(
    module: &Module,
    file: &str,
    base_dir: Option<&Path>,
) -> Vec<Diagnostic> {
    let program = AgentProgram {
        file: file.to_string(),
        modules: vec![module.clone()],
        imports: Vec::new(),
        span: module.span.clone(),
    };
    run(&program, &read(&program, base_dir), true)
}

fn run(program: &AgentProgram, imports: &Imports, module_file: bool) -> Vec<Diagnostic> {
    // Problems inside imported files are reported when those files are checked themselves.
    let diags = imports.missing.clone();
    let imported_modules: Vec<&Module> = imports.modules.iter().map(|m| &m.module).collect();
    let imported_knowledge = imports.knowledge.clone();
    let file = program.file.as_str();
    let mut ctx = Ctx {
        program,
        file,
        modules: program.modules.iter().collect(),
        module_index: BTreeMap::new(),
        spec_index: BTreeMap::new(),
        macro_index: BTreeMap::new(),
        imported_knowledge,
        imported: Imported::default(),
        diags,
        module_file,
    };
    for m in &imported_modules {
        ctx.imported.modules.extend(module_key(m));
        ctx.imported.specs.extend(
            m.action_specs
                .iter()
                .map(|s| (s.name.name.name().to_string(), s.params.len())),
        );
        if let Some(p) = &m.program {
            ctx.imported.macros.extend(
                p.macros
                    .iter()
                    .map(|x| (x.name.name.name().to_string(), x.params.len())),
            );
        }
    }
    for m in &program.modules {
        if let Some(k) = module_key(m) {
            ctx.module_index.entry(k).or_default().push(m);
        }
        for s in &m.action_specs {
            ctx.spec_index
                .entry((s.name.name.name().to_string(), s.params.len()))
                .or_default()
                .push(s);
        }
        if let Some(p) = &m.program {
            for mac in &p.macros {
                ctx.macro_index
                    .entry((mac.name.name.name().to_string(), mac.params.len()))
                    .or_default()
                    .push(mac);
            }
        }
    }
    modules::check(&mut ctx);
    actions::check(&mut ctx);
    macros::check(&mut ctx);
    variables::check(&mut ctx);
    predicates::check(&mut ctx);
    let mut diags = ctx.diags;
    diags.sort_by(|a, b| {
        (a.span.start, a.span.end, &a.code).cmp(&(b.span.start, b.span.end, &b.code))
    });
    diags.dedup();
    diags
}
