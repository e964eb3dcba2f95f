//! `docs/builtins.md` lists exactly the predicates the engine defines: every `name/arity` in its
//! "Every built-in" section is defined by the engine, every predicate of the engine is listed
//! there (or, for protected names, in the "Protected names" section), and every protected name
//! listed is protected.

use goal::kr::knowledge::is_protected;
use goal::kr::native::library::known_predicates;
use std::collections::BTreeSet;

fn page() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/builtins.md");
    std::fs::read_to_string(path).expect("docs/builtins.md")
}

/// The text of `## {title}` up to the next `## ` heading.
fn section<'a>(page: &'a str, title: &str) -> &'a str {
    let start = page
        .find(&format!("\n## {title}\n"))
        .unwrap_or_else(|| panic!("no section {title}"));
    let rest = &page[start + 1..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |i| i + 3);
    &rest[..end]
}

/// Everything written in backticks in a text (`\|` in tables is `|`).
fn quoted(text: &str) -> Vec<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(|s| s.replace("\\|", "|"))
        .collect()
}

/// The `name/arity` items of the listing section.
fn listed(page: &str) -> BTreeSet<(String, usize)> {
    quoted(section(page, "Every built-in"))
        .into_iter()
        .filter_map(|q| {
            let (name, arity) = q.rsplit_once('/')?;
            let arity = arity.parse().ok()?;
            (!name.is_empty() && !name.contains(' ')).then(|| (name.to_string(), arity))
        })
        .collect()
}

#[test]
fn every_listed_built_in_is_defined_by_the_engine() {
    let known: BTreeSet<(String, usize)> = known_predicates()
        .into_iter()
        .map(|(n, a)| (n.to_string(), a))
        .collect();
    let page = page();
    let listed = listed(&page);
    assert!(listed.len() > 150, "{}", listed.len());
    let unknown: Vec<_> = listed.difference(&known).collect();
    assert!(unknown.is_empty(), "listed but not defined: {unknown:?}");
}

#[test]
fn every_predicate_the_engine_defines_is_listed() {
    let page = page();
    let listed = listed(&page);
    // The list of names: the lines of the section that start with a name in backticks.
    let names: String = section(&page, "Protected names")
        .lines()
        .filter(|l| l.starts_with('`'))
        .collect::<Vec<_>>()
        .join("\n");
    let protected: BTreeSet<String> = quoted(&names)
        .into_iter()
        .filter(|q| !q.contains('/'))
        .collect();
    for name in &protected {
        assert!(
            is_protected(name),
            "`{name}` is listed as protected but is not"
        );
    }
    let mut missing = Vec::new();
    for (name, arity) in known_predicates() {
        let key = (name.to_string(), arity);
        if !listed.contains(&key) && !(is_protected(name) && protected.contains(name)) {
            missing.push(format!("{name}/{arity}"));
        }
    }
    assert!(
        missing.is_empty(),
        "defined but not in docs/builtins.md: {missing:?}"
    );
}
