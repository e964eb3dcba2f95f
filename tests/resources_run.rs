//! `goal run` and `goal prolog` with runaway agents and queries (issue 11): the agent or query
//! stops with a located error, the rest of the run goes on, and peak memory stays bounded.
//! Agents run through the real scheduler on worker threads.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/resources")
        .join(name)
}

/// Output of a finished `goal` run and the child's peak resident memory (KiB, from the
/// rusage of the reaped child: the same figure as VmHWM).
struct Finished {
    stdout: String,
    stderr: String,
    success: bool,
    peak_kib: u64,
}

fn goal(args: &[&str]) -> Finished {
    let mut child = Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("goal runs");
    let pid = child.id();
    // Drain the pipes on threads so the child never blocks on a full pipe.
    let mut out = child.stdout.take().unwrap();
    let mut err = child.stderr.take().unwrap();
    let out = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut out, &mut s).unwrap();
        s
    });
    let err = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut err, &mut s).unwrap();
        s
    });
    // Reap the child with wait4: its rusage holds the peak resident set (ru_maxrss, KiB).
    let mut status: libc::c_int = 0;
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::wait4(pid as libc::pid_t, &mut status, 0, &mut usage) };
    assert_eq!(rc, pid as libc::pid_t, "wait4");
    let peak_kib = usage.ru_maxrss as u64;
    let success = libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0;
    drop(child);
    Finished {
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
        success,
        peak_kib,
    }
}

const MAX_PEAK_KIB: u64 = 500 * 1024;

#[test]
fn a_runaway_agent_stops_with_a_located_error_and_the_others_finish() {
    let mas = fixture("runaway.mas2g");
    // Building the deep term takes seconds in a debug build: a generous cycle quota keeps a
    // loaded machine from cutting it.
    let r = goal(&[
        "run",
        "--workers",
        "2",
        "--cycle-time",
        "120",
        mas.to_str().unwrap(),
    ]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert_eq!(r.stdout.matches("counted to 30").count(), 2, "{all}");
    assert!(
        r.stderr
            .contains("runaway.goal:10: query grow([]): memory (heap cells) budget"),
        "{all}"
    );
    assert!(r.stderr.contains("(while calling grow/1)"), "{all}");
    assert!(r.peak_kib < MAX_PEAK_KIB, "peak RSS {} KiB", r.peak_kib);
}

#[test]
fn an_agent_making_new_atoms_every_cycle_meets_its_atom_budget_and_the_others_finish() {
    let mas = fixture("atoms.mas2g");
    // Building the deep term takes seconds in a debug build: a generous cycle quota keeps a
    // loaded machine from cutting it.
    let r = goal(&[
        "run",
        "--workers",
        "2",
        "--cycle-time",
        "120",
        mas.to_str().unwrap(),
    ]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert!(r.stdout.contains("counted to 30"), "{all}");
    // Seven cycles remaking the same 200000 atoms: 1400000 atoms made, 200000 of them new.
    assert!(r.stdout.contains("reused 7 times"), "{all}");
    assert!(!r.stdout.contains("never here"), "{all}");
    assert!(
        r.stderr.contains(
            "atoms.goal:17: query round(N),fresh(N),M is N+1: new atoms (never freed) budget of 1000000 exceeded (while calling atom_concat/3)"
        ),
        "{all}"
    );
    assert!(!r.stderr.contains("agent reuse stopped"), "{all}");
    assert!(r.peak_kib < MAX_PEAK_KIB, "peak RSS {} KiB", r.peak_kib);
}

#[test]
fn an_agent_with_a_million_deep_term_works_beside_the_others() {
    let mas = fixture("deep.mas2g");
    // Building the deep term takes seconds in a debug build: a generous cycle quota keeps a
    // loaded machine from cutting it.
    let r = goal(&[
        "run",
        "--workers",
        "2",
        "--cycle-time",
        "120",
        mas.to_str().unwrap(),
    ]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert!(r.success, "{all}");
    assert!(
        r.stdout.contains("built") && r.stdout.contains("queried"),
        "{all}"
    );
    assert_eq!(r.stdout.matches("counted to 30").count(), 2, "{all}");
    assert!(r.peak_kib < MAX_PEAK_KIB, "peak RSS {} KiB", r.peak_kib);
}

/// The warning `goal run` prints when an `if` rule's condition was cut at 1,000 answers.
const CUT_WARNING: &str = "has 1000 answers or more; only the first 1000 were considered";

#[test]
fn an_infinite_generator_in_an_if_rule_picks_one_of_its_first_answers_and_runs_on() {
    let r = goal(&[
        "run",
        "--max-cycles",
        "3",
        fixture("generator.goal").to_str().unwrap(),
    ]);
    let all = format!("{}{}", r.stdout, r.stderr);
    // The agent acts in each of the 3 cycles and is still running at the cycle limit.
    let printed: Vec<u64> = r
        .stdout
        .lines()
        .filter_map(|l| l.trim().parse().ok())
        .collect();
    assert_eq!(printed.len(), 3, "{all}");
    assert!(printed.iter().all(|x| (6..=1000).contains(x)), "{all}");
    assert!(all.contains("cycle limit reached"), "{all}");
    assert!(!r.stderr.contains("budget"), "{all}");
    // Warned once for the rule, although it was evaluated in every cycle.
    assert_eq!(r.stderr.matches(CUT_WARNING).count(), 1, "{all}");
    assert!(
        r.stderr
            .contains("generator.goal:4: the condition of rule main:4"),
        "{all}"
    );
    assert!(r.peak_kib < MAX_PEAK_KIB, "peak RSS {} KiB", r.peak_kib);
}

#[test]
fn a_length_enumeration_in_an_if_rule_binds_a_length() {
    let r = goal(&["run", fixture("lengths.goal").to_str().unwrap()]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert!(r.success, "{all}");
    let n: u64 = r
        .stdout
        .lines()
        .find_map(|l| l.trim().parse().ok())
        .unwrap_or_else(|| panic!("no length printed: {all}"));
    assert!((2..1002).contains(&n), "{all}");
    assert!(
        r.stderr.contains("lengths.goal:4:") && r.stderr.contains(CUT_WARNING),
        "{all}"
    );
}

#[test]
fn error_texts_with_huge_culprits_are_bounded() {
    let r = goal(&["run", fixture("culprit.goal").to_str().unwrap()]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert!(r.stderr.contains("culprit.goal:10: query"), "{all}");
    assert!(r.stderr.contains("type_error(atomic,f(f(f("), "{all}");
    // The culprit is nested 100,000 deep; the message shows its start only.
    assert!(
        r.stderr.len() < 20_000,
        "{} bytes of stderr",
        r.stderr.len()
    );
}

#[test]
fn runaway_prolog_queries_end_with_resource_errors() {
    for (query, want) in [
        ("between(1, inf, X)", "error(resource_error(answers)"),
        (
            "numlist(1, 100000000, L)",
            "error(resource_error(memory),'numlist/3')",
        ),
        (
            "length(L, 100000000)",
            "error(resource_error(memory),'length/2')",
        ),
        (
            "X = [a|X], member(b, X)",
            "error(resource_error(inferences(10000000))",
        ),
        (
            "X = [a|X], length(X, N)",
            "representation_error(cyclic_term)",
        ),
        (
            "repeat, write(x), fail",
            "error(resource_error(output),'write/1')",
        ),
        (
            "catch(X is foo + 1, error(E, _), true)",
            "E = type_error(evaluable,foo/0)",
        ),
        (
            "assert(foo)",
            "permission_error(access,private_procedure,assert/1)",
        ),
    ] {
        let r = goal(&["prolog", "-q", query]);
        let last = r.stdout.lines().last().unwrap_or_default().to_string();
        assert!(last.contains(want), "{query}: {last} / {}", r.stderr);
        assert!(
            r.peak_kib < MAX_PEAK_KIB,
            "{query}: peak RSS {} KiB",
            r.peak_kib
        );
    }
}

#[test]
fn agents_with_long_lists_deep_terms_and_long_operator_chains_run_on_worker_threads() {
    let dir = std::env::temp_dir().join(format!("goal-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A belief with 100,000 operators (left-nested), a 30,000-element list from a query,
    // and a term nested 8,000 deep built by the agent: inserted, queried, printed.
    let chain = vec!["a"; 100_001].join("+");
    let agent = format!(
        "init module {{\n\tknowledge {{\n\t\tdeep(0, z) :- !.\n\t\t\
         deep(N, f(T)) :- N1 is N - 1, deep(N1, T).\n\t}}\n\tbeliefs {{\n\t\tp({chain}).\n\t}}\n\
         \tgoals {{\n\t\tdone.\n\t}}\n}}\n\
         main module [exit=nogoals] {{\n\tprogram {{\n\
         \t\tif a-goal(done), bel(got(L), deep8(T), p(X), X = _ + a) then print(all) + insert(done).\n\
         \t\tif a-goal(done), not(bel(deep8(_))), bel(deep(8000, T)) then insert(deep8(T)).\n\
         \t\tif a-goal(done), not(bel(got(_))), bel(numlist(1, 30000, L)) then insert(got(L)).\n\
         \t}}\n}}\n"
    );
    std::fs::write(dir.join("big.goal"), agent).unwrap();
    std::fs::write(
        dir.join("big.mas2g"),
        "agentfiles {\n\t\"big.goal\".\n}\nlaunchpolicy {\n\tlaunch a : big.\n\tlaunch b : big.\n}\n",
    )
    .unwrap();
    let mas = dir.join("big.mas2g");
    // Building the deep term takes seconds in a debug build: a generous cycle quota keeps a
    // loaded machine from cutting it.
    let r = goal(&[
        "run",
        "--workers",
        "2",
        "--cycle-time",
        "120",
        mas.to_str().unwrap(),
    ]);
    let all = format!("{}{}", r.stdout, r.stderr);
    assert!(r.success, "{all}");
    assert_eq!(r.stdout.matches("all").count(), 2, "{all}");
    let check = goal(&["check", dir.join("big.goal").to_str().unwrap()]);
    assert!(check.success, "{}{}", check.stdout, check.stderr);
    let _ = std::fs::remove_dir_all(&dir);
}
