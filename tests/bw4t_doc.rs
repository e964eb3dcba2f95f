//! `docs/bw4t.md` lists exactly the actions BW4T robots understand and exactly the percepts they
//! get, each percept with the sending type the environment declares (and so for the requests of
//! human-controlled robots and the percepts of e-partners), so the reference cannot drift from
//! the environment.

use goal::bw4t::actions::ACTIONS;
use goal::bw4t::percepts::declarations;
use goal::env::{PerceptDecl, PerceptType};
use std::collections::BTreeSet;

fn page() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/docs/bw4t.md");
    std::fs::read_to_string(path).expect("docs/bw4t.md")
}

/// The rows of the first table after `## {title}` whose first cell is `` `name(...)` ``:
/// `(name/arity, the rest of the row)`.
fn rows(page: &str, title: &str, header: &str) -> Vec<(String, String)> {
    let start = page
        .find(&format!("\n## {title}\n"))
        .unwrap_or_else(|| panic!("no section {title}"));
    let section = &page[start..];
    let table = &section[section.find(header).expect("table header")..];
    table
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .filter_map(|row| {
            let cells: Vec<&str> = row.split(" | ").collect();
            let first = cells[0].trim_start_matches("| ").trim();
            let term = first.strip_prefix('`')?.strip_suffix('`')?;
            let (name, arity) = match term.split_once('(') {
                Some((name, args)) => (name, args.split(',').count()),
                None => (term, 0),
            };
            Some((format!("{name}/{arity}"), cells[1..].join(" | ")))
        })
        .collect()
}

#[test]
fn every_action_is_documented_and_every_documented_action_exists() {
    let page = page();
    let documented: BTreeSet<String> = rows(&page, "Actions", "| action |")
        .into_iter()
        .map(|(a, _)| a)
        .collect();
    let actual: BTreeSet<String> = ACTIONS.iter().map(|a| a.to_string()).collect();
    assert_eq!(documented, actual);
}

#[test]
fn every_percept_is_documented_with_its_sending_type() {
    let page = page();
    let documented: BTreeSet<(String, String)> = rows(&page, "Percepts", "| percept |")
        .into_iter()
        .map(|(p, rest)| (p, rest.split(" | ").next().unwrap_or("").to_string()))
        .collect();
    assert_eq!(documented, typed(declarations()));
}

/// `(name/arity, sending type as the page writes it)` of each declaration.
fn typed(decls: Vec<PerceptDecl>) -> BTreeSet<(String, String)> {
    decls
        .into_iter()
        .map(|d| {
            let kind = match d.kind {
                PerceptType::Once => "once",
                PerceptType::OnChange => "on change",
                PerceptType::OnChangeWithNegation => "on change with negation",
                PerceptType::Always => "always",
            };
            (format!("{}/{}", d.name, d.arity), kind.to_string())
        })
        .collect()
}

#[test]
fn every_request_and_every_epartner_percept_is_documented() {
    let page = page();
    let requests: BTreeSet<String> = rows(&page, "Humans and e-partners", "| request |")
        .into_iter()
        .map(|(r, _)| r)
        .collect();
    let actual: BTreeSet<String> = goal::bw4t::human::REQUESTS
        .iter()
        .map(|r| r.to_string())
        .collect();
    assert_eq!(requests, actual);
    let documented: BTreeSet<(String, String)> =
        rows(&page, "Humans and e-partners", "| e-partner percept |")
            .into_iter()
            .map(|(p, rest)| (p, rest.split(" | ").next().unwrap_or("").to_string()))
            .collect();
    assert_eq!(documented, typed(goal::bw4t::epartner::declarations()));
}
