//! Checks of a parsed `.test2g` file: its MAS file exists and parses, the tested agents are
//! launched by it, names are not repeated, and every agent has the same number of named tests.

use super::ast::MasTest;
use crate::diag::Diagnostic;
use crate::syntax::mas2g;
use crate::syntax::mas2g::ast::AgentName;
use std::collections::BTreeSet;
use std::path::Path;

/// Checks `test`, whose MAS path is relative to `base_dir` (the test file's directory).
pub fn check_files(test: &MasTest, base_dir: &Path) -> Vec<Diagnostic> {
    let file = test.file.as_str();
    let mut diags = super::calls::check_ground(test);
    let mut seen_agents: BTreeSet<&str> = BTreeSet::new();
    for a in &test.agents {
        for name in &a.agents {
            let n = name.name.name();
            if !seen_agents.insert(n) {
                diags.push(
                    Diagnostic::warning(
                        "W0302",
                        format!("agent `{n}` is tested in more than one block"),
                        file,
                        name.span.clone(),
                    )
                    .with_hint("put all tests of an agent in one block"),
                );
            }
        }
        let mut seen_tests: BTreeSet<&str> = BTreeSet::new();
        for t in &a.tests {
            let n = t.name.name.name();
            if !seen_tests.insert(n) {
                diags.push(
                    Diagnostic::warning(
                        "W0301",
                        format!("duplicate test name `{n}`"),
                        file,
                        t.name.span.clone(),
                    )
                    .with_hint("give every test of an agent a different name"),
                );
            }
        }
    }
    if let Some(first) = test.agents.first() {
        for a in &test.agents[1..] {
            if a.tests.len() != first.tests.len() {
                let span = a.agents.first().map_or(a.span.clone(), |i| i.span.clone());
                diags.push(
                    Diagnostic::error(
                        "E0307",
                        format!(
                            "all agents must have the same number of named tests: this block has {}, the first has {}",
                            a.tests.len(),
                            first.tests.len()
                        ),
                        file,
                        span,
                    )
                    .with_hint("add or remove named tests so every agent block has as many"),
                );
            }
        }
    }
    let path = &test.mas.value;
    let full = base_dir.join(path);
    if !path.ends_with(".mas2g") {
        diags.push(
            Diagnostic::error(
                "E0305",
                format!("`{path}` is not a `.mas2g` file"),
                file,
                test.mas.span.clone(),
            )
            .with_hint("`mas = \"...\"` names the MAS file that the test launches"),
        );
        return diags;
    }
    let source = match std::fs::read(&full) {
        Ok(bytes) if full.is_file() => String::from_utf8_lossy(&bytes).into_owned(),
        _ => {
            diags.push(
                Diagnostic::error(
                    "E0305",
                    format!("MAS file `{path}` not found"),
                    file,
                    test.mas.span.clone(),
                )
                .with_hint("the path is relative to the directory of the test file"),
            );
            return diags;
        }
    };
    // A modular GOAL or MARBEL MAS: its launch rules in the 2014 form (calls are checked
    // when the test compiles against the assembled program).
    let modular = crate::syntax::modular::mas::classic_launch(&source, &full.to_string_lossy());
    let is_modular = modular.is_some();
    let (mas, mas_diags) =
        modular.unwrap_or_else(|| mas2g::parse(&source, &full.to_string_lossy()));
    if mas_diags.iter().any(Diagnostic::is_error) {
        diags.push(
            Diagnostic::error(
                "E0308",
                format!("MAS file `{path}` has errors"),
                file,
                test.mas.span.clone(),
            )
            .with_hint("run `goal check` on the MAS file to see them"),
        );
        return diags;
    }
    for a in &test.agents {
        for name in &a.agents {
            // (A) test files may name an agent definition: every agent launched from it.
            let definition = is_modular
                && mas
                    .launch_rules
                    .iter()
                    .flat_map(|r| &r.instructions)
                    .any(|i| i.reference.value == name.name.name());
            if !definition && !mas.may_launch(name.name.name()) {
                let launched = launched_names(&mas);
                let launched = launched.iter().map(String::as_str);
                let hint = match crate::suggest::closest(name.name.name(), launched) {
                    Some(n) => format!("did you mean `{n}`?"),
                    None => "test blocks are named after the agents that the MAS file launches"
                        .to_string(),
                };
                diags.push(
                    Diagnostic::error(
                        "E0306",
                        format!("agent `{}` is not launched by `{path}`", name.name.name()),
                        file,
                        name.span.clone(),
                    )
                    .with_hint(hint),
                );
            }
        }
    }
    if is_modular {
        return diags;
    }
    let mas_dir = full.parent().unwrap_or(base_dir);
    diags.extend(super::calls::check_calls(test, &mas, mas_dir));
    diags
}

/// The names the launch rules of `mas` give (up to 100 of each numbered series).
fn launched_names(mas: &mas2g::ast::MasFile) -> Vec<String> {
    let mut out = Vec::new();
    for i in mas.launch_rules.iter().flat_map(|r| &r.instructions) {
        let base = match &i.name {
            Some(AgentName::Given(g)) => g.value.as_str(),
            _ => i.reference.value.as_str(),
        };
        match i.count() {
            0 | 1 => out.push(base.to_string()),
            n => out.extend((1..=n.min(100)).map(|k| format!("{base}{k}"))),
        }
    }
    out
}
