//! The example corpus parses without errors; the printed AST of each program is snapshotted.

use goal::syntax::ast::dump;
use goal::syntax::goal::{parse_goal, parse_mod2g};
use std::path::Path;

fn read(rel: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(rel);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Parses a corpus program, asserts that it has no errors, and returns its dump.
fn dump_program(rel: &str) -> String {
    let src = read(rel);
    let (program, diags) = parse_goal(rel, &src);
    let errors: Vec<String> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.render(&src))
        .collect();
    assert!(errors.is_empty(), "{rel}:\n{}", errors.join("\n"));
    let mut out = dump::agent_program(&program, &src);
    for d in diags {
        out.push_str(&format!(
            "{:?} {} {}: {}\n",
            d.severity,
            d.code,
            d.line_col(&src).0,
            d.message
        ));
    }
    out
}

#[test]
fn blocksworld_stacker() {
    insta::assert_snapshot!(dump_program("agents/blocksworld/stacker.goal"));
}

#[test]
fn bw4t_robot() {
    insta::assert_snapshot!(dump_program("agents/bw4t/robot.goal"));
}

#[test]
fn counter() {
    insta::assert_snapshot!(dump_program("agents/counter/counter.goal"));
}

#[test]
fn pingpong_ping() {
    insta::assert_snapshot!(dump_program("agents/pingpong/ping.goal"));
}

#[test]
fn pingpong_pong() {
    insta::assert_snapshot!(dump_program("agents/pingpong/pong.goal"));
}

#[test]
fn every_construct() {
    insta::assert_snapshot!(dump_program("tests/fixtures/goal/every_construct.goal"));
}

#[test]
fn module_file() {
    let rel = "tests/fixtures/goal/helpers.mod2g";
    let src = read(rel);
    let (module, diags) = parse_mod2g(rel, &src);
    assert!(diags.is_empty(), "{diags:?}");
    let module = module.expect("one module");
    insta::assert_snapshot!(dump::module(&module, &src));
}
