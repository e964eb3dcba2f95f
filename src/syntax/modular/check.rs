//! `goal check` for modular files: a modular `.mas2g` with every agent it defines (each agent
//! assembled and validated as one program, diagnostics mapped back to their files), and
//! `.mod2g`/`.act2g`/`.pl` files on their own.

use super::assemble::{assemble, AgentBuild};
use super::ast::Generation;
use super::mas::ModMas;
use super::pl::kr_clauses;
use crate::diag::{Diagnostic, Severity};
use crate::syntax::ast::{Module, ModuleKind, ModuleOptions};
use crate::syntax::check::FileReport;
use crate::syntax::mas2g::ast::EntitySpec;
use crate::syntax::prolog::Reader;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

/// Assembles and validates one agent definition; diagnostics are in the shared text of the
/// returned build.
pub fn check_agent(
    mas: &ModMas,
    mas_text: &str,
    base: &Path,
    agent: &super::mas::AgentDef,
) -> (AgentBuild, Vec<Diagnostic>) {
    let build = assemble(&mas.file, mas_text, base, agent, mas.generation);
    let mut diags = build.diagnostics.clone();
    if !diags.iter().any(Diagnostic::is_error) {
        let mas_end = build.sources.segments[0].end;
        for d in crate::syntax::validate::validate(&build.program, None) {
            // What the lowering added points into the MAS file: its warnings are not the user's.
            // `newpercept/1` (this cycle's raw percepts) is provided by the runtime.
            let runtime = d.code == "E0121" && d.message.starts_with("`newpercept/1`");
            // A predicate declared `:- dynamic` is a belief that may not exist yet (GOAL too).
            let dynamic = d.code == "E0121"
                && build
                    .declared
                    .iter()
                    .any(|(n, a)| d.message.starts_with(&format!("`{n}/{a}`")));
            if dynamic {
                continue;
            }
            if runtime || (d.span.start <= mas_end && !d.is_error()) {
                continue;
            }
            // (B) a .pl file holds facts and rules of one predicate (database and knowledge).
            if mas.generation == Generation::Marbel && d.code == "E0122" {
                continue;
            }
            // `p/1.` lines after `:- dynamic` are facts of '/'/2, already warned about (W0609).
            if d.code == "W0110" && d.message.starts_with("`//2`") {
                continue;
            }
            diags.push(d);
        }
    }
    (build, diags)
}

/// Checks a modular `.mas2g` file and every file its agents use; one report per file.
pub fn check_mas(path: &Path, text: &str) -> Vec<FileReport> {
    let file = path.display().to_string();
    let base = path.parent().unwrap_or(Path::new("."));
    let (mas, mut mas_diags) = super::mas::parse(text, &file);
    mas_diags.extend(mas_checks(&mas));
    let mut by_file: BTreeMap<String, (Arc<str>, Vec<Diagnostic>)> = BTreeMap::new();
    for agent in &mas.agents {
        let (build, diags) = check_agent(&mas, text, base, agent);
        for s in &build.sources.segments[1..] {
            by_file
                .entry(s.name.clone())
                .or_insert_with(|| (s.text.clone(), Vec::new()));
        }
        for d in diags {
            let (d, _) = build.sources.localize(d);
            if d.file == file {
                mas_diags.push(d);
            } else if let Some(e) = by_file.get_mut(&d.file) {
                e.1.push(d);
            }
        }
    }
    let mut out = vec![report(file, Arc::from(text), mas_diags)];
    out.extend(
        by_file
            .into_iter()
            .map(|(f, (src, diags))| report(f, src, diags)),
    );
    out
}

fn report(file: String, source: Arc<str>, mut diagnostics: Vec<Diagnostic>) -> FileReport {
    diagnostics.sort_by(|a, b| {
        (a.span.start, a.span.end, &a.code, &a.message).cmp(&(
            b.span.start,
            b.span.end,
            &b.code,
            &b.message,
        ))
    });
    diagnostics.dedup();
    FileReport {
        file,
        source: source.to_string(),
        diagnostics,
    }
}

/// Checks of the MAS file itself: the environment, launch rules naming definitions, and
/// definitions never launched.
fn mas_checks(mas: &ModMas) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let f = mas.file.clone();
    // The environment itself is checked by `mas::envcheck`, as for every generation.
    let defined: Vec<&str> = mas.agents.iter().map(|a| a.name.value.as_str()).collect();
    let mut launched = Vec::new();
    for r in &mas.launch {
        for i in &r.instructions {
            launched.push(i.reference.value.clone());
            if !defined.contains(&i.reference.value.as_str()) {
                out.push(
                    Diagnostic::error(
                        "E0206",
                        format!("no agent definition `{}`", i.reference.value),
                        f.clone(),
                        i.reference.span.clone(),
                    )
                    .with_hint(
                        match crate::suggest::closest(&i.reference.value, defined.clone()) {
                            Some(d) => format!("did you mean `{d}`?"),
                            None => format!("defined: {}", defined.join(", ")),
                        },
                    ),
                );
            }
        }
        if let Some(EntitySpec::Constraints {
            entity_type: Some(t),
            ..
        }) = &r.condition
        {
            let bw4t = mas
                .env
                .as_ref()
                .is_some_and(|e| is_builtin_env(&e.reference.value));
            if bw4t && t.value != "bot" && t.value != "human" {
                out.push(
                    Diagnostic::warning(
                        "W0607",
                        format!("BW4T has no entities of type `{}`", t.value),
                        f.clone(),
                        t.span.clone(),
                    )
                    .with_hint("BW4T entity types are `bot` and `human`"),
                );
            }
        }
    }
    for a in &mas.agents {
        if !launched.contains(&a.name.value) {
            out.push(
                Diagnostic::warning(
                    "W0208",
                    format!("agent `{}` is never launched", a.name.value),
                    f.clone(),
                    a.name.span.clone(),
                )
                .with_hint(format!(
                    "add `when * launch {}.` to the launch policy",
                    a.name.value
                )),
            );
        }
    }
    out
}

/// True for environment references run by the built-in BW4T (`bw4t-client-3.8.5.jar`, ...).
pub fn is_builtin_env(reference: &str) -> bool {
    let name = reference.rsplit(['/', '\\']).next().unwrap_or(reference);
    name.to_ascii_lowercase().contains("bw4t")
}

/// Checks a `.mod2g` file of generation (A) or (B) on its own.
pub fn check_module_file(path: &Path, text: &str, gen: Generation) -> Vec<Diagnostic> {
    let file = path.display().to_string();
    let dir = path.parent().unwrap_or(Path::new("."));
    let (parsed, mut diags) =
        super::parse_mod2g(&file, text, 0, text.len(), gen == Generation::Marbel);
    let Some(m) = parsed else { return diags };
    for u in &m.uses {
        for r in &u.refs {
            let exts: &[&str] = match u.case.as_ref().map(|c| c.value) {
                Some(super::ast::UseCase::Module) => &["mod2g"],
                Some(super::ast::UseCase::ActionSpec) => &["act2g"],
                Some(super::ast::UseCase::Mas | super::ast::UseCase::Planner) => continue,
                Some(_) => &["pl"],
                None => super::assemble::bare_use_extensions(gen),
            };
            if super::assemble::resolve(dir, &r.value, exts).is_none() {
                diags.push(
                    Diagnostic::error(
                        "E0607",
                        format!("`{}` not found", r.value),
                        file.clone(),
                        r.span.clone(),
                    )
                    .with_hint(
                        match super::assemble::near_file(dir, &r.value, exts[0]) {
                            Some(f) => format!("did you mean `{f}`?"),
                            None => "references are relative to this file's directory".into(),
                        },
                    ),
                );
            }
        }
    }
    if gen == Generation::Modular {
        diags.extend(undefined_macros(&m.module, &file));
    }
    diags.extend(crate::syntax::validate::validate_module_file(
        &m.module, &file, None,
    ));
    diags
}

/// E0118 for macro uses with no definition in the file: macros are local to their file in
/// modular GOAL, so this needs no other file; a plain Prolog literal lands here.
fn undefined_macros(m: &Module, file: &str) -> Vec<Diagnostic> {
    use crate::syntax::ast::{LiteralKind, RuleBody};
    let Some(p) = &m.program else {
        return Vec::new();
    };
    let defined: Vec<(String, usize)> = p
        .macros
        .iter()
        .map(|d| (d.name.name.name().to_string(), d.params.len()))
        .collect();
    let mut out = Vec::new();
    let mut stack: Vec<&crate::syntax::ast::Rule> = p.rules.iter().collect();
    while let Some(r) = stack.pop() {
        if let RuleBody::Block(rs) = &r.body {
            stack.extend(rs.iter());
        }
        for l in &r.condition {
            if let LiteralKind::MacroUse { name, args } = &l.kind {
                let key = (name.name.name().to_string(), args.len());
                if !defined.contains(&key) {
                    out.push(
                        Diagnostic::error(
                            "E0118",
                            format!("macro `{}/{}` is not defined in this file", key.0, key.1),
                            file,
                            l.span.clone(),
                        )
                        .with_hint(format!(
                            "conditions use mental operators (`bel({0}(...))`, `percept({0}(...))`); plain Prolog literals are MARBEL",
                            key.0
                        )),
                    );
                }
            }
        }
    }
    out.sort_by_key(|d| d.span.start);
    out
}

/// Checks an `.act2g` file on its own.
pub fn check_act_file(path: &Path, text: &str) -> Vec<Diagnostic> {
    let file = path.display().to_string();
    let (parsed, mut diags) = super::parse_act2g(&file, text, 0, text.len());
    let Some(a) = parsed else { return diags };
    let span = 0..text.len();
    // An init module may have no rules: the specs are checked on their own.
    let module = Module {
        kind: ModuleKind::Init,
        options: ModuleOptions::default(),
        knowledge: Vec::new(),
        beliefs: Vec::new(),
        goals: Vec::new(),
        program: None,
        action_specs: a.specs,
        imports: Vec::new(),
        sections: Vec::new(),
        head_span: 0..0,
        span,
    };
    diags.extend(
        crate::syntax::validate::validate_module_file(&module, &file, None)
            .into_iter()
            .filter(|d| d.severity == Severity::Error || d.code != "W0101"),
    );
    diags
}

/// Checks a `.pl` file: `:- dynamic` directives are allowed (modular GOAL and MARBEL).
pub fn check_pl_file(path: &Path, text: &str) -> Vec<Diagnostic> {
    let file = path.display().to_string();
    let text = super::pl::blank_dynamic(text);
    // Read as GOAL reads Prolog files (its leniencies, with warnings).
    let mut reader = Reader::goal(file.as_str());
    let (clauses, mut diags) = reader.clauses(&text, 0);
    diags.append(&mut reader.warnings);
    let clauses = kr_clauses(clauses, &file, &mut diags);
    diags.extend(crate::syntax::validate::validate_prolog(&clauses, &file));
    diags
}
