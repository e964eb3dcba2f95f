//! Differential tests: the native KR engine must give the same answers as scryer-prolog 0.10 on
//! generated fact sets, fixed knowledge programs (family tree, blocks world, path finding) and
//! generated list/arithmetic queries.
//!
//! Run with `cargo test --test kr_diff`; add `-- --nocapture` for per-program timings, and set
//! `KR_DIFF_STATS=1` (`=all` for every answer) to print what scryer answers for each program.
//!
//! Both sides are compared in a canonical printed form (`scryer::Outcome`): the answers of a query
//! are the instances of the template `ans(V1..Vn)` of its named variables, in order, with variables
//! renamed by first appearance; an error is compared on the formal part of `error(Formal, _)`
//! (the context term is implementation-specific).
//!
//! Where GOAL semantics differ from ISO Prolog (and scryer) on purpose, the difference is mapped
//! or avoided, and said here:
//! - undefined predicates fail in GOAL: scryer runs with the `unknown` flag `fail` instead of
//!   raising `existence_error` (`scryer::PRELUDE`);
//! - `not/1` exists (defined as `\+` in the prelude); SWI-only list predicates scryer lacks
//!   (`msort/2`, `sort/4`, `aggregate_all/3`, `last/2`, `delete/3`, `subtract/3`, ...) are given
//!   their SWI meaning in the prelude;
//! - arithmetic is SWI's: `/` of integers is an integer when exact and `**` of integers is an
//!   integer; scryer's `is/2` and comparisons are routed through a prelude evaluator that does
//!   the same (`scryer::to_scryer`);
//! - `*->` (soft cut) is not an operator in scryer 0.10: rewritten to an equivalent prelude call;
//!   `ignore/1` is missing in scryer 0.10: defined in the prelude;
//! - scryer 0.10 bugs worked around: a cut in an if-then-else condition cuts the else branch too
//!   (conditions are sent under `call/1`); a discontiguous predicate keeps only its last group of
//!   clauses (clauses are grouped by predicate before loading); an error escaping a query comes
//!   back as the answer of later queries (every query runs under `catch/3`);
//! - avoided rather than mapped: strings (`"..."` are strings in GOAL/SWI, char lists in
//!   scryer), the standard order of mixed integers and floats (SWI compares by value, scryer
//!   puts every float first as ISO says), and one-character atoms as list elements (scryer 0.10
//!   takes `[d,2]` for a partial string and rejects it as a list), the standard order of two
//!   distinct unbound variables (implementation-defined), and the error cases listed with
//!   `gen::error_queries` where SWI itself departs from ISO.

#[path = "kr_diff/build.rs"]
mod build;
#[path = "kr_diff/gen.rs"]
mod gen;
#[path = "kr_diff/gen_text.rs"]
mod gen_text;
#[path = "kr_diff/native.rs"]
mod native;
#[path = "kr_diff/programs.rs"]
mod programs;
#[path = "kr_diff/scryer.rs"]
mod scryer;

use goal::term::{Sym, Term};
use programs::Program;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use scryer::{template, Outcome, Scryer};

/// Keeps only the formal part of `error(Formal, Context)` so contexts may differ.
fn normalise(o: Outcome) -> Outcome {
    match o {
        Outcome::Error(e) => Outcome::Error(formal_part(&e)),
        other => other,
    }
}

fn formal_part(printed: &str) -> String {
    // Printed form `error(Formal,Context)`: cut at the top-level comma.
    let Some(body) = printed
        .strip_prefix("error(")
        .and_then(|s| s.strip_suffix(')'))
    else {
        return printed.to_string();
    };
    let mut depth = 0i32;
    let mut quoted = false;
    let mut prev = ' ';
    for (k, ch) in body.char_indices() {
        match ch {
            '\'' if prev != '\\' => quoted = !quoted,
            '(' | '[' | '{' if !quoted => depth += 1,
            ')' | ']' | '}' if !quoted => depth -= 1,
            ',' if !quoted && depth == 0 => return body[..k].to_string(),
            _ => {}
        }
        prev = ch;
    }
    body.to_string()
}

/// Disagreements found by this suite and not fixed in the native engine yet: (query as printed,
/// what ISO/SWI say). They do not fail the suite (they are listed in its output) so the rest of
/// the suite keeps guarding; the output says when an entry agrees again and can be removed.
/// Fixed so far by kr-core: `atom_chars(X,[ab])` (type_error(character,ab)), `findall/3` and
/// `aggregate_all(bag(..))` with a non-list result (type_error(list,9)).
const KNOWN_DISAGREEMENTS: &[(&str, &str)] = &[];

/// Runs every query of `program` on both engines; returns the disagreements as messages.
/// Unless `facts` is `Knowledge`, the program's ground facts go into a belief base or a goal (a
/// set: duplicates are dropped on both sides) and only the rules into knowledge.
fn compare(
    program: &Program,
    scryer: &mut Scryer,
    native: &mut native::Native,
    at: native::Facts,
) -> Vec<String> {
    let loaded = if at != native::Facts::Knowledge {
        let (facts, rules): (Vec<Term>, Vec<Term>) = program
            .clauses
            .iter()
            .cloned()
            .partition(|c| c.is_ground() && !c.is_functor(Sym::intern(":-"), 2));
        let mut unique: Vec<Term> = Vec::new();
        for f in facts {
            if !unique.contains(&f) {
                unique.push(f);
            }
        }
        scryer.load(&[rules.clone(), unique.clone()].concat());
        native.load_split(&rules, &unique, at)
    } else {
        scryer.load(&program.clauses);
        native.load(&program.clauses)
    };
    if std::env::var("KR_DIFF_STATS").is_ok() {
        let (mut err, mut none, mut some, mut answers) = (0, 0, 0, 0);
        for q in &program.queries {
            eprintln!("  query: {q}");
            match scryer.query(&template(q), q) {
                Outcome::Error(e) => {
                    err += 1;
                    println!("  error: ?- {q}. -> {e}");
                }
                Outcome::Answers(a) if a.is_empty() => none += 1,
                Outcome::Answers(a) if std::env::var("KR_DIFF_STATS").as_deref() == Ok("all") => {
                    some += 1;
                    answers += a.len();
                    println!("  {q}  =>  {}", a.join(" ; "));
                }
                Outcome::Answers(a) => {
                    some += 1;
                    answers += a.len();
                }
            }
        }
        println!(
            "{}: {} queries: {err} errors, {none} without answers, {some} with {answers} answers",
            program.name,
            program.queries.len()
        );
    }
    if let Err(e) = loaded {
        return vec![format!(
            "{}: native engine refused the program: {e}",
            program.name
        )];
    }
    let mut failures = Vec::new();
    let mut times = (std::time::Duration::ZERO, std::time::Duration::ZERO);
    for q in &program.queries {
        let printed = q.to_string();
        let known = KNOWN_DISAGREEMENTS.iter().find(|(k, _)| *k == printed);
        let t = template(q);
        let start = std::time::Instant::now();
        let want = normalise(scryer.query(&t, q));
        let mid = std::time::Instant::now();
        let got = normalise(native.query(&t, q));
        times.0 += mid - start;
        times.1 += mid.elapsed();
        match known {
            Some((_, why)) if want != got => {
                println!(
                    "{}: known disagreement: ?- {printed}. ({why})",
                    program.name
                )
            }
            Some(_) => println!(
                "{}: ?- {printed}. now agrees: remove it from KNOWN_DISAGREEMENTS",
                program.name
            ),
            None if want != got => failures.push(format!(
                "{}: ?- {q}.\n  scryer: {want:?}\n  native: {got:?}",
                program.name
            )),
            None => {}
        }
    }
    println!(
        "{}: {} queries, scryer {:?}, native {:?}",
        program.name,
        program.queries.len(),
        times.0,
        times.1
    );
    failures
}

fn report(failures: &[String], total: usize) {
    if !failures.is_empty() {
        let shown: Vec<&String> = failures.iter().take(15).collect();
        panic!(
            "{} of {total} queries disagree with scryer, first ones:\n{}",
            failures.len(),
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}

fn run_programs(programs: Vec<Program>) {
    run_programs_with(programs, native::Facts::Knowledge)
}

fn run_programs_with(programs: Vec<Program>, facts: native::Facts) {
    let total = programs.iter().map(|p| p.queries.len()).sum();
    let mut failures = Vec::new();
    for p in &programs {
        // A fresh scryer machine per program: modules loaded into one machine are not kept apart.
        let mut scryer = Scryer::new();
        let mut native = native::Native::new();
        failures.extend(compare(p, &mut scryer, &mut native, facts));
    }
    println!("{total} queries over {} programs compared", programs.len());
    report(&failures, total);
}

#[test]
fn generated_fact_sets_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let programs = (0..10).map(|_| gen::fact_set(&mut rng, 150)).collect();
    run_programs(programs);
}

#[test]
fn generated_fact_sets_in_a_belief_base_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let programs = (0..4).map(|_| gen::fact_set(&mut rng, 150)).collect();
    run_programs_with(programs, native::Facts::Beliefs);
}

#[test]
fn generated_fact_sets_as_goal_facts_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let programs = (0..2).map(|_| gen::fact_set(&mut rng, 150)).collect();
    run_programs_with(programs, native::Facts::Goal);
}

#[test]
fn family_trees_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    run_programs(vec![
        programs::family(&mut rng, 8),
        programs::family(&mut rng, 15),
        programs::family(&mut rng, 25),
    ]);
}

#[test]
fn blocks_worlds_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    run_programs(vec![
        programs::blocks(&mut rng, 5),
        programs::blocks(&mut rng, 9),
        programs::blocks(&mut rng, 14),
    ]);
}

#[test]
fn path_finding_agrees() {
    let mut rng = ChaCha8Rng::seed_from_u64(33);
    run_programs(vec![
        programs::paths(&mut rng, 5),
        programs::paths(&mut rng, 6),
        programs::paths(&mut rng, 7),
    ]);
}

#[test]
fn list_and_arithmetic_queries_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(34);
    let queries: Vec<Term> = (0..1500).map(|_| gen::list_query(&mut rng)).collect();
    run_programs(vec![Program {
        name: "lists".into(),
        clauses: vec![],
        queries,
    }]);
}

#[test]
fn atom_set_and_pair_queries_agree() {
    let mut rng = ChaCha8Rng::seed_from_u64(35);
    let queries: Vec<Term> = (0..600).map(|_| gen_text::text_query(&mut rng)).collect();
    run_programs(vec![Program {
        name: "atoms".into(),
        clauses: vec![],
        queries,
    }]);
}

#[test]
fn error_terms_agree() {
    run_programs(vec![Program {
        name: "errors".into(),
        clauses: vec![],
        queries: gen::error_queries(),
    }]);
}

/// Reads `tests/kr_programs/NAME.pl` and one query per line of `NAME.queries` with the crate's
/// Prolog reader.
fn text_program(name: &str) -> Program {
    use goal::syntax::prolog::Reader;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/kr_programs");
    let read = |ext: &str| {
        let path = dir.join(format!("{name}.{ext}"));
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    };
    let text = read("pl");
    let (clauses, diags) = Reader::new(format!("{name}.pl")).clauses(&text, 0);
    let errors: Vec<String> = diags.iter().map(|d| d.render(&text)).collect();
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    let mut queries = Vec::new();
    for line in read("queries").lines().filter(|l| !l.trim().is_empty()) {
        match Reader::new(format!("{name}.queries")).term(line, 0) {
            Ok(q) => queries.push(q.term),
            Err(d) => panic!("{}", d.render(line)),
        }
    }
    Program {
        name: name.into(),
        clauses: clauses.into_iter().map(|c| c.term).collect(),
        queries,
    }
}

#[test]
fn text_programs_agree() {
    run_programs(vec![text_program("lists"), text_program("bw4t_route")]);
}

/// The harness itself: scryer's answers come back in the canonical form the comparison relies on.
#[test]
fn scryer_harness_reads_answers_back() {
    use crate::build::*;
    let mut s = Scryer::new();
    let q = c("append", vec![v("X"), v("Y"), list(vec![a("ab"), i(1)])]);
    assert_eq!(
        s.query(&template(&q), &q),
        Outcome::Answers(vec![
            "ans([],[ab,1])".into(),
            "ans([ab],[1])".into(),
            "ans([ab,1],[])".into()
        ])
    );
    // Shared and unbound variables survive, renamed canonically.
    let q = op("=", v("X"), c("f", vec![v("Y"), v("Z"), v("Y")]));
    assert_eq!(
        s.query(&template(&q), &q),
        Outcome::Answers(vec!["ans(f(_A,_B,_A),_A,_B)".into()])
    );
    // GOAL semantics: an undefined predicate fails.
    let q = c("undefined_here", vec![v("X")]);
    assert_eq!(s.query(&template(&q), &q), Outcome::Answers(vec![]));
    let q = c("not", vec![c("undefined_here", vec![a("x")])]);
    assert_eq!(
        s.query(&template(&q), &q),
        Outcome::Answers(vec!["ans".into()])
    );
    // Errors come back as error terms.
    let q = op("is", v("X"), op("+", v("Y"), i(1)));
    assert_eq!(
        normalise(s.query(&template(&q), &q)),
        Outcome::Error("instantiation_error".into())
    );
    // Prelude predicates in SWI's meaning.
    let q = c(
        "sort",
        vec![
            i(2),
            a("@>="),
            list(vec![
                c("f", vec![a("a"), i(1)]),
                c("f", vec![a("b"), i(2)]),
                c("f", vec![a("c"), i(1)]),
            ]),
            v("L"),
        ],
    );
    assert_eq!(
        s.query(&template(&q), &q),
        Outcome::Answers(vec!["ans([f(b,2),f(a,1),f(c,1)])".into()])
    );
    let q = c(
        "aggregate_all",
        vec![
            c("max", vec![v("X")]),
            c("member", vec![v("X"), list(vec![i(3), i(7), i(2)])]),
            v("M"),
        ],
    );
    assert_eq!(
        s.query(&template(&q), &q),
        Outcome::Answers(vec!["ans(_A,7)".into()])
    );
}

#[test]
fn formal_part_cuts_the_context() {
    assert_eq!(
        formal_part("error(type_error(evaluable,foo/0),context(is/2,_))"),
        "type_error(evaluable,foo/0)"
    );
    assert_eq!(
        formal_part("error(instantiation_error,_A)"),
        "instantiation_error"
    );
    assert_eq!(formal_part("foo"), "foo");
}
