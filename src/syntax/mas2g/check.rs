//! Checks of a parsed `.mas2g` file against the file system and itself: agent files exist,
//! launch rules reference known agent files, `*` only in conditional rules, duplicate names.

use super::ast::{AgentName, MasFile};
use crate::diag::Diagnostic;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Checks `mas`, whose agent file paths are relative to `base_dir` (the `.mas2g` file's directory).
/// The environment is checked by `mas::envcheck`, which knows the built-in environments.
pub fn check_files(mas: &MasFile, base_dir: &Path) -> Vec<Diagnostic> {
    let file = mas.file.as_str();
    let mut diags = Vec::new();
    let mut refs: BTreeMap<String, usize> = BTreeMap::new();
    for (i, f) in mas.agent_files.iter().enumerate() {
        let path = &f.path.value;
        if !path.ends_with(".goal") {
            diags.push(
                Diagnostic::error(
                    "E0205",
                    format!("agent file `{path}` is not a `.goal` file"),
                    file,
                    f.path.span.clone(),
                )
                .with_hint("agent files are single-file GOAL programs ending in `.goal`"),
            );
        } else if !base_dir.join(path).is_file() {
            diags.push(
                Diagnostic::error(
                    "E0205",
                    format!("agent file `{path}` not found"),
                    file,
                    f.path.span.clone(),
                )
                .with_hint("agent file paths are relative to the directory of the .mas2g file"),
            );
        }
        let name = f.reference_name();
        if let std::collections::btree_map::Entry::Vacant(e) = refs.entry(name.clone()) {
            e.insert(i);
        } else {
            let span = f
                .name
                .as_ref()
                .map_or(f.path.span.clone(), |n| n.span.clone());
            diags.push(
                Diagnostic::warning(
                    "W0206",
                    format!("duplicate agent file reference name `{name}`; the first file is used"),
                    file,
                    span,
                )
                .with_hint("give one of the files a different `[name = ...]`"),
            );
        }
    }
    // `name` (one agent) and `name[N]` (name1..nameN) do not clash with each other.
    let mut given: BTreeMap<(String, bool), ()> = BTreeMap::new();
    for inst in mas.launch_rules.iter().flat_map(|r| &r.instructions) {
        let (name, span) = match &inst.name {
            Some(AgentName::Entity(_)) => continue,
            Some(AgentName::Given(g)) => (g.value.clone(), g.span.clone()),
            None => (inst.reference.value.clone(), inst.reference.span.clone()),
        };
        if given.insert((name.clone(), inst.count() > 1), ()).is_some() {
            diags.push(
                Diagnostic::warning(
                    "W0209",
                    format!("agent name `{name}` is launched by more than one instruction"),
                    file,
                    span,
                )
                .with_hint("agent names must be unique; the runtime renames the later agents"),
            );
        }
    }
    let mut launched = vec![false; mas.agent_files.len()];
    for rule in &mas.launch_rules {
        for inst in &rule.instructions {
            match refs.get(&inst.reference.value) {
                Some(&i) => launched[i] = true,
                None => {
                    let known: Vec<&str> = refs.keys().map(String::as_str).collect();
                    let near = crate::suggest::closest(&inst.reference.value, known.clone());
                    let hint = if let Some(k) = near {
                        format!("did you mean `{k}`?")
                    } else if known.is_empty() {
                        "declare the agent file in the `agentfiles` section".to_string()
                    } else {
                        format!("known agent files: {}", known.join(", "))
                    };
                    diags.push(
                        Diagnostic::error(
                            "E0206",
                            format!(
                                "launch rule refers to unknown agent file `{}`",
                                inst.reference.value
                            ),
                            file,
                            inst.reference.span.clone(),
                        )
                        .with_hint(hint),
                    );
                }
            }
            if let (None, Some(AgentName::Entity(span))) = (&rule.condition, &inst.name) {
                diags.push(
                    Diagnostic::error(
                        "E0207",
                        "`*` (the entity's name) is allowed only in conditional launch rules",
                        file,
                        span.clone(),
                    )
                    .with_hint("write `when entity@env do launch *:ref.` or give the agent a name"),
                );
            }
        }
    }
    for (i, (f, used)) in mas.agent_files.iter().zip(&launched).enumerate() {
        if !used && refs.get(&f.reference_name()) == Some(&i) {
            diags.push(Diagnostic::warning(
                "W0208",
                format!("agent file `{}` is never launched", f.path.value),
                file,
                f.path.span.clone(),
            ));
        }
    }
    diags
}

/// The paths of the agent files named in `mas`, resolved against `base_dir` (the first entry of
/// each reference name only).
pub fn agent_file_paths(mas: &MasFile, base_dir: &Path) -> Vec<PathBuf> {
    let mut seen = std::collections::BTreeSet::new();
    let mut out = Vec::new();
    for f in &mas.agent_files {
        if seen.insert(f.reference_name()) {
            out.push(base_dir.join(&f.path.value));
        }
    }
    out
}

impl MasFile {
    /// True if an agent called `name` can be launched by this file: a given name (with a number
    /// suffix `1..N` for `[N]` with N > 1), or any name when some rule names agents after entities.
    pub fn may_launch(&self, name: &str) -> bool {
        self.launch_rules
            .iter()
            .flat_map(|r| &r.instructions)
            .any(|inst| {
                let base = match &inst.name {
                    Some(AgentName::Entity(_)) => return true,
                    Some(AgentName::Given(g)) => g.value.as_str(),
                    None => inst.reference.value.as_str(),
                };
                if inst.count() <= 1 {
                    return name == base;
                }
                name.strip_prefix(base)
                    .and_then(|n| n.parse::<u64>().ok())
                    .is_some_and(|k| k >= 1 && k <= inst.count())
            })
    }
}

impl MasFile {
    /// The agent files that an agent called `name` may run (by the launch instructions that can
    /// create that name; several when entity-named rules are involved).
    pub fn agent_files_for(&self, name: &str) -> Vec<&super::ast::AgentFile> {
        let mut refs: Vec<&str> = Vec::new();
        for inst in self.launch_rules.iter().flat_map(|r| &r.instructions) {
            let base = match &inst.name {
                Some(AgentName::Entity(_)) => None,
                Some(AgentName::Given(g)) => Some(g.value.as_str()),
                None => Some(inst.reference.value.as_str()),
            };
            let matches = match base {
                None => true,
                Some(b) if inst.count() <= 1 => name == b,
                Some(b) => name
                    .strip_prefix(b)
                    .and_then(|n| n.parse::<u64>().ok())
                    .is_some_and(|k| k >= 1 && k <= inst.count()),
            };
            if matches && !refs.contains(&inst.reference.value.as_str()) {
                refs.push(inst.reference.value.as_str());
            }
        }
        let mut out: Vec<&super::ast::AgentFile> = Vec::new();
        for r in refs {
            if let Some(f) = self.agent_files.iter().find(|f| f.reference_name() == r) {
                out.push(f);
            }
        }
        out
    }
}
