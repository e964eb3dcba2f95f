//! Assembling one agent of a modular `.mas2g` into a 2014 [`AgentProgram`]: resolve the use
//! clauses (docs/modular-goal.md), parse every file once into one [`SourceSet`], give
//! the role modules their 2014 kinds, pool knowledge, beliefs, goals and action specs, and lower
//! what has no 2014 form into ordinary rules and specs:
//! * (B) percept declarations `add`/`update`/`replace p/n` become `forall` rules at the start of
//!   the updates (event) module;
//! * (B) actions that are neither modules nor specified become environment actions with a
//!   `true` pre- and postcondition;
//! * messages are visible for one cycle: the event module ends by deleting `received/2` and
//!   `sent/2` facts.

use super::ast::{ActFile, Generation, ModFile, UseCase, UseClause};
use super::build::located;
use super::lower::{
    clear_messages, environment_actions, local_macros, mentions, percept_declaration, query,
};
use super::mas::{AgentDef, AgentItem, Role};
use super::pl::{blank_dynamic, declared, kr_clauses};
use super::sources::SourceSet;
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::*;
use crate::syntax::prolog::Reader;
use crate::term::Term;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The assembled program of one agent definition, with every file it reads.
pub struct AgentBuild {
    pub program: AgentProgram,
    pub sources: SourceSet,
    /// Problems found (spans in the shared text; see [`SourceSet::localize`]).
    pub diagnostics: Vec<Diagnostic>,
    /// Predicates the `.pl` files declare `dynamic` (querying them is never an error).
    pub declared: BTreeSet<(String, usize)>,
}

struct Loaded {
    role: Option<Role>,
    file: ModFile,
}

struct Assembler<'a> {
    gen: Generation,
    sources: SourceSet,
    diags: Vec<Diagnostic>,
    /// Module files by canonical path.
    modules: BTreeMap<PathBuf, usize>,
    loaded: Vec<Loaded>,
    act_files: BTreeSet<PathBuf>,
    kr_files: BTreeSet<(PathBuf, &'static str)>,
    specs: Vec<ActionSpec>,
    knowledge: Vec<Located>,
    beliefs: Vec<Located>,
    goals: Vec<Located>,
    declared: BTreeSet<(String, usize)>,
    agent: &'a AgentDef,
}

/// Assembles agent definition `agent` of the `.mas2g` file `mas_name` (text `mas_text`, in
/// directory `base`).
pub fn assemble(
    mas_name: &str,
    mas_text: &str,
    base: &Path,
    agent: &AgentDef,
    gen: Generation,
) -> AgentBuild {
    let mut a = Assembler {
        gen,
        sources: SourceSet::default(),
        diags: Vec::new(),
        modules: BTreeMap::new(),
        loaded: Vec::new(),
        act_files: BTreeSet::new(),
        kr_files: BTreeSet::new(),
        specs: Vec::new(),
        knowledge: Vec::new(),
        beliefs: Vec::new(),
        goals: Vec::new(),
        declared: BTreeSet::new(),
        agent,
    };
    // The MAS text comes first: spans of what the lowering adds point at the agent definition.
    a.sources.add(mas_name, mas_text);
    let mut roles: BTreeMap<&'static str, Span> = BTreeMap::new();
    for item in &agent.items {
        if let AgentItem::Use {
            reference, role, ..
        } = item
        {
            if roles
                .insert(role.value.keyword(), role.span.clone())
                .is_some()
            {
                a.error(
                    "E0606",
                    format!("the {} module is given twice", role.value.keyword()),
                    role.span.clone(),
                    "an agent has at most one module per role",
                );
                continue;
            }
            match resolve(base, &reference.value, &["mod2g"]) {
                Some(p) => a.load_module(&p, Some(role.value), reference.span.clone()),
                None => a.not_found(base, &reference.value, "mod2g", reference.span.clone()),
            }
        }
    }
    if !roles.contains_key("main") && !roles.contains_key("event") {
        let what = if gen == Generation::Marbel {
            "`use m for decisions.`"
        } else {
            "`use m as main module.`"
        };
        a.error(
            "E0606",
            format!(
                "agent `{}` has no main (decisions) and no event (updates) module",
                agent.name.value
            ),
            agent.name.span.clone(),
            &format!("add {what}"),
        );
    }
    a.finish()
}

/// The files a bare `use X.` may name, in the order tried: a module, an action-spec file, in
/// MARBEL a `.pl` knowledge file, and last a `.mas2g` (which test files name; a module ignores
/// it). A MARBEL project often has `X.mas2g` beside `X.pl`: the knowledge must win.
pub fn bare_use_extensions(gen: Generation) -> &'static [&'static str] {
    match gen {
        Generation::Marbel => &["mod2g", "act2g", "pl", "mas2g"],
        _ => &["mod2g", "act2g", "mas2g"],
    }
}

/// The file `r` relative to `dir`, trying the extensions in order when it has none of them.
pub fn resolve(dir: &Path, r: &str, exts: &[&str]) -> Option<PathBuf> {
    let p = dir.join(r);
    let has_ext = p
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| exts.contains(&e));
    if has_ext && p.is_file() {
        return Some(p);
    }
    exts.iter()
        .map(|e| dir.join(format!("{r}.{e}")))
        .find(|q| q.is_file())
}

/// The file of `dir` with extension `ext` whose name (without the extension) is closest to
/// the reference `r`.
pub fn near_file(dir: &Path, r: &str, ext: &str) -> Option<String> {
    let (sub, name) = match r.rsplit_once('/') {
        Some((d, n)) => (dir.join(d), n),
        None => (dir.to_path_buf(), r),
    };
    let mut stems: Vec<String> = std::fs::read_dir(&sub)
        .ok()?
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().and_then(|e| e.to_str()) == Some(ext))
        .filter_map(|p| p.file_stem().and_then(|s| s.to_str()).map(str::to_string))
        .take(10_000)
        .collect();
    // Directory order depends on the file system: compare in name order.
    stems.sort();
    let near = crate::suggest::closest(name, stems.iter().map(String::as_str))?;
    let prefix = r
        .rsplit_once('/')
        .map_or(String::new(), |(d, _)| format!("{d}/"));
    Some(format!("{prefix}{near}"))
}

fn canonical(p: &Path) -> PathBuf {
    p.canonicalize().unwrap_or_else(|_| p.to_path_buf())
}

impl Assembler<'_> {
    fn error(&mut self, code: &str, msg: impl Into<String>, span: Span, hint: &str) {
        let file = self.sources.segments[0].name.clone();
        self.diags
            .push(Diagnostic::error(code, msg, file, span).with_hint(hint));
    }

    fn not_found(&mut self, dir: &Path, r: &str, ext: &str, span: Span) {
        let hint = match near_file(dir, r, ext) {
            Some(f) => format!("did you mean `{f}`?"),
            None => "references are relative to the file that contains the use clause".into(),
        };
        self.error(
            "E0607",
            format!("`{r}` not found (looked for `{r}` and `{r}.{ext}`)"),
            span,
            &hint,
        );
    }

    /// Reads a file into the shared text; returns its segment range.
    fn read(&mut self, path: &Path, span: &Span) -> Option<(String, usize, usize)> {
        match crate::syntax::check::read_source(path) {
            Ok(text) => {
                let name = path.display().to_string();
                let i = self.sources.add(&name, &text);
                let s = &self.sources.segments[i];
                Some((name, s.start, s.end))
            }
            Err(mut d) => {
                d.span = span.clone();
                d.file = self.sources.segments[0].name.clone();
                self.diags.push(d);
                None
            }
        }
    }

    fn load_module(&mut self, path: &Path, role: Option<Role>, span: Span) {
        let key = canonical(path);
        if let Some(&i) = self.modules.get(&key) {
            if role.is_some() && self.loaded[i].role.is_some() {
                self.error(
                    "E0606",
                    format!("`{}` is used for two roles", path.display()),
                    span,
                    "give each role its own module file",
                );
            } else if role.is_some() {
                self.loaded[i].role = role;
            }
            return;
        }
        let Some((name, start, end)) = self.read(path, &span) else {
            return;
        };
        let marbel = self.gen == Generation::Marbel;
        let dir = path.parent().unwrap_or(Path::new("."));
        let written = super::detect::module_generation(&self.sources.text[start..end], dir);
        let mismatch = written == Generation::Classic
            || (written == Generation::Marbel && self.gen == Generation::Modular);
        if mismatch {
            let d = Diagnostic::error(
                "E0611",
                format!(
                    "`{name}` is a {} module, but the MAS file is {}",
                    written.label(),
                    self.gen.label()
                ),
                self.sources.segments[0].name.clone(),
                span,
            )
            .with_hint(match written {
                Generation::Classic => "a 2014 module (with `program { }` sections) is imported by a `.goal` file with `#import`",
                _ => "write the conditions with mental operators (`bel(..)`, `percept(..)`), or use a MARBEL MAS file (`define a { use m for decisions. }`)",
            });
            self.diags.push(d);
            return;
        }
        let (file, diags) = super::parse_mod2g(&name, &self.sources.text, start, end, marbel);
        self.diags.extend(diags);
        let Some(file) = file else { return };
        self.modules.insert(key, self.loaded.len());
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        let uses = file.uses.clone();
        self.loaded.push(Loaded { role, file });
        self.duplicate_uses(&dir, &uses);
        for u in &uses {
            self.use_clause(&dir, u, true);
        }
    }

    /// Follows the use clauses of a module (`in_module`) or action-spec file.
    fn use_clause(&mut self, dir: &Path, u: &UseClause, in_module: bool) {
        let case = u.case.as_ref().map(|c| c.value);
        for r in &u.refs {
            let span = r.span.clone();
            match case {
                Some(UseCase::Knowledge | UseCase::Beliefs | UseCase::Goals) => {
                    let c = case.unwrap_or(UseCase::Knowledge);
                    match resolve(dir, &r.value, &["pl"]) {
                        Some(p) => self.load_kr(&p, c, span),
                        None => self.not_found(dir, &r.value, "pl", span),
                    }
                }
                _ if !in_module => self.error(
                    "E0608",
                    "an action specification file can only use knowledge files",
                    u.span.clone(),
                    "write `use file as knowledge.`",
                ),
                Some(UseCase::Module) => match resolve(dir, &r.value, &["mod2g"]) {
                    Some(p) => self.load_module(&p, None, span),
                    None => self.not_found(dir, &r.value, "mod2g", span),
                },
                Some(UseCase::ActionSpec) => match resolve(dir, &r.value, &["act2g"]) {
                    Some(p) => self.load_act(&p, span),
                    None => self.not_found(dir, &r.value, "act2g", span),
                },
                Some(UseCase::Mas | UseCase::Planner) => {}
                None => match resolve(dir, &r.value, bare_use_extensions(self.gen)) {
                    Some(p) => match p.extension().and_then(|e| e.to_str()) {
                        Some("mod2g") => self.load_module(&p, None, span),
                        Some("act2g") => self.load_act(&p, span),
                        Some("pl") => self.load_kr(&p, UseCase::Knowledge, span),
                        _ => {}
                    },
                    None => {
                        let hint = if self.gen == Generation::Marbel {
                            "a bare `use` names a .mod2g, .act2g or .pl file"
                        } else {
                            "a bare `use` names a .mod2g or .act2g file; write `use f as knowledge.` for a .pl file"
                        };
                        self.error("E0607", format!("`{}` not found", r.value), span, hint)
                    }
                },
            }
        }
    }

    /// E0612: one file named twice by the use clauses of one file.
    fn duplicate_uses(&mut self, dir: &Path, uses: &[UseClause]) {
        let mut seen: BTreeSet<PathBuf> = BTreeSet::new();
        for u in uses {
            let exts: &[&str] = match u.case.as_ref().map(|c| c.value) {
                Some(UseCase::Knowledge | UseCase::Beliefs | UseCase::Goals) => &["pl"],
                Some(UseCase::Module) => &["mod2g"],
                Some(UseCase::ActionSpec) => &["act2g"],
                Some(UseCase::Mas | UseCase::Planner) => continue,
                None => bare_use_extensions(self.gen),
            };
            for r in &u.refs {
                let Some(p) = resolve(dir, &r.value, exts) else {
                    continue;
                };
                if !seen.insert(canonical(&p)) {
                    let file = self
                        .sources
                        .segment_of(r.span.start)
                        .map_or(String::new(), |s| s.name.clone());
                    self.diags.push(
                        Diagnostic::error(
                            "E0612",
                            format!("`{}` is used twice in this file", r.value),
                            file,
                            r.span.clone(),
                        )
                        .with_hint("remove one of the use clauses"),
                    );
                }
            }
        }
    }

    fn load_act(&mut self, path: &Path, span: Span) {
        if !self.act_files.insert(canonical(path)) {
            return;
        }
        let Some((name, start, end)) = self.read(path, &span) else {
            return;
        };
        let (file, diags) = super::parse_act2g(&name, &self.sources.text, start, end);
        self.diags.extend(diags);
        let Some(ActFile { uses, specs, .. }) = file else {
            return;
        };
        self.specs.extend(specs);
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        for u in &uses {
            self.use_clause(&dir, u, false);
        }
    }

    fn load_kr(&mut self, path: &Path, case: UseCase, span: Span) {
        if !self.kr_files.insert((canonical(path), case.keyword())) {
            return;
        }
        let Some((name, start, end)) = self.read(path, &span) else {
            return;
        };
        let text = blank_dynamic(&self.sources.text[start..end]);
        let (clauses, diags) = Reader::new(name.as_str()).clauses(&text, start);
        self.diags.extend(diags);
        let raw = &self.sources.text[start..end];
        self.declared.extend(declared(raw, &clauses));
        for c in kr_clauses(clauses, &name, &mut self.diags) {
            let rule = matches!(c.term.functor(), Some((f, 2)) if f.name() == ":-");
            match case {
                // (B): the .pl file is the initial database: ground facts are beliefs (the
                // program may delete them), rules and facts with variables are knowledge.
                UseCase::Knowledge
                    if self.gen == Generation::Marbel && !rule && c.term.vars().is_empty() =>
                {
                    self.beliefs.push(c)
                }
                UseCase::Knowledge => self.knowledge.push(c),
                UseCase::Beliefs | UseCase::Goals if rule => {
                    let what = case.keyword();
                    self.diags.push(
                        Diagnostic::error(
                            "E0609",
                            format!("a rule in a file used as {what}"),
                            name.clone(),
                            c.spans.span.clone(),
                        )
                        .with_hint("rules belong in a file used as knowledge"),
                    );
                }
                UseCase::Beliefs => self.beliefs.push(c),
                _ => self.goals.push(c),
            }
        }
    }

    fn finish(mut self) -> AgentBuild {
        let agent_span = self.agent.span.clone();
        let mut modules: Vec<Module> = Vec::new();
        let mut has = BTreeSet::new();
        for l in std::mem::take(&mut self.loaded) {
            let mut m = l.file.module;
            match l.role {
                Some(Role::Init) => m.kind = ModuleKind::Init,
                Some(Role::Main) => m.kind = ModuleKind::Main,
                Some(Role::Event) => m.kind = ModuleKind::Event,
                Some(Role::Shutdown) => m.kind = ModuleKind::Shutdown,
                None => self.name_check(&m, &l.file.file),
            }
            has.insert(m.name().to_string());
            modules.push(m);
        }
        let by_kind = |k: &str, ms: &mut Vec<Module>, span: &Span| -> usize {
            if let Some(i) = ms
                .iter()
                .position(|m| m.name() == k && !matches!(m.kind, ModuleKind::User { .. }))
            {
                return i;
            }
            ms.push(Module {
                kind: match k {
                    "init" => ModuleKind::Init,
                    _ => ModuleKind::Event,
                },
                options: ModuleOptions::default(),
                knowledge: Vec::new(),
                beliefs: Vec::new(),
                goals: Vec::new(),
                program: Some(ProgramSection {
                    order: None,
                    nested_order: None,
                    macros: Vec::new(),
                    rules: Vec::new(),
                    span: span.clone(),
                }),
                action_specs: Vec::new(),
                imports: Vec::new(),
                sections: Vec::new(),
                head_span: span.clone(),
                span: span.clone(),
            });
            ms.len() - 1
        };
        local_macros(&mut modules);
        if self.gen == Generation::Marbel {
            self.goal_predicate(&mut modules);
        }
        self.unused_declarations(&modules);
        let percepts = self.percept_rules();
        // (B) percepts are stored before the init module runs, in the first cycle, too.
        if !self.beliefs.is_empty() || !self.goals.is_empty() || !percepts.is_empty() {
            let i = by_kind("init", &mut modules, &agent_span);
            modules[i].beliefs.append(&mut self.beliefs);
            modules[i].goals.append(&mut self.goals);
            if let Some(p) = modules[i].program.as_mut() {
                p.rules.splice(0..0, percepts.iter().cloned());
            }
        }
        let ev = by_kind("event", &mut modules, &agent_span);
        let mut first = percepts;
        if let Some(p) = modules[ev].program.as_mut() {
            first.append(&mut p.rules);
            first.extend(clear_messages(&agent_span));
            p.rules = first;
        }
        if self.gen == Generation::Marbel {
            let env = environment_actions(&modules, &self.specs, &agent_span);
            self.specs.extend(env);
        }
        if let Some(m) = modules.first_mut() {
            m.knowledge.append(&mut self.knowledge);
            m.action_specs.append(&mut self.specs);
        }
        let program = AgentProgram {
            file: self.sources.segments[0].name.clone(),
            modules,
            imports: Vec::new(),
            span: agent_span,
        };
        AgentBuild {
            program,
            sources: self.sources,
            diagnostics: self.diags,
            declared: self.declared,
        }
    }

    /// (B) when the database defines `goal/1`, a `goal(..)` literal queries that predicate
    /// (MARBEL has no goals of its own in the course programs); a warning says so once.
    fn goal_predicate(&mut self, modules: &mut [Module]) {
        let defines = self.knowledge.iter().chain(self.beliefs.iter()).any(|c| {
            let head = match c.term.functor() {
                Some((f, 2)) if f.name() == ":-" => &c.term.args()[0],
                _ => &c.term,
            };
            matches!(head.functor(), Some((f, 1)) if f.name() == "goal")
        });
        if !defines {
            return;
        }
        let mut first: Option<Span> = None;
        for m in modules.iter_mut() {
            let Some(p) = m.program.as_mut() else {
                continue;
            };
            let mut stack: Vec<&mut Rule> = p.rules.iter_mut().collect();
            while let Some(r) = stack.pop() {
                for l in r.condition.iter_mut() {
                    if let LiteralKind::Mental { op, query, .. } = &mut l.kind {
                        if *op == MentalOp::Goal {
                            *op = MentalOp::Bel;
                            let t = Term::compound("goal", vec![query.term.clone()]);
                            *query = located(t, query.spans.span.clone());
                            first.get_or_insert(l.span.clone());
                        }
                    }
                }
                if let RuleBody::Block(rs) = &mut r.body {
                    stack.extend(rs.iter_mut());
                }
            }
        }
        if let Some(span) = first {
            let file = self
                .sources
                .segment_of(span.start)
                .map_or(String::new(), |s| s.name.clone());
            self.diags.push(
                Diagnostic::warning(
                    "W0610",
                    "`goal(..)` queries the predicate goal/1 of the database",
                    file,
                    span,
                )
                .with_hint("the .pl files define goal/1; rename it to use the goal operator"),
            );
        }
    }

    /// W0611: a (B) percept declaration whose predicate no condition or knowledge rule reads.
    fn unused_declarations(&mut self, modules: &[Module]) {
        let mut read: Vec<&Term> = self.knowledge.iter().map(|c| &c.term).collect();
        for m in modules {
            let Some(p) = &m.program else { continue };
            read.extend(
                p.macros
                    .iter()
                    .flat_map(|d| d.body.iter())
                    .filter_map(query),
            );
            let mut stack: Vec<&Rule> = p.rules.iter().collect();
            while let Some(r) = stack.pop() {
                read.extend(r.condition.iter().filter_map(query));
                if let RuleBody::Block(rs) = &r.body {
                    stack.extend(rs.iter());
                }
            }
        }
        for item in &self.agent.items {
            let AgentItem::Percept {
                name, arity, span, ..
            } = item
            else {
                continue;
            };
            if !read.iter().any(|t| mentions(t, &name.value, *arity)) {
                let d = Diagnostic::warning(
                    "W0611",
                    format!("percept {}/{arity} is stored but never read", name.value),
                    self.sources.segments[0].name.clone(),
                    span.clone(),
                )
                .with_hint("remove the declaration, or use the predicate in a condition");
                self.diags.push(d);
            }
        }
    }

    /// W0603: a called module whose declared name is not its file's name.
    fn name_check(&mut self, m: &Module, file: &str) {
        let base = Path::new(file)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("");
        if m.name() != base {
            let d = Diagnostic::warning(
                "W0603",
                format!("module `{}` is declared in `{file}`", m.name()),
                file,
                m.head_span.clone(),
            )
            .with_hint(format!("calls use the declared name `{}`", m.name()));
            self.diags.push(d);
        }
    }

    /// (B) percept declarations as rules of the updates module (in declaration order).
    fn percept_rules(&mut self) -> Vec<Rule> {
        let mut out = Vec::new();
        let mut seen: BTreeMap<(String, usize), Span> = BTreeMap::new();
        for item in &self.agent.items {
            let AgentItem::Percept {
                mode,
                name,
                arity,
                span,
            } = item
            else {
                continue;
            };
            if seen
                .insert((name.value.clone(), *arity), span.clone())
                .is_some()
            {
                let d = Diagnostic::error(
                    "E0610",
                    format!("percept {}/{arity} is declared twice", name.value),
                    self.sources.segments[0].name.clone(),
                    span.clone(),
                )
                .with_hint("declare each percept once, with one of add, update, replace");
                self.diags.push(d);
                continue;
            }
            out.extend(percept_declaration(*mode, &name.value, *arity, span));
        }
        out
    }
}
