//! Attack test (issue 11): malformed files of every kind (.goal, .mas2g, .test2g, .pl, maps in
//! TOML and XML), deep and long terms, runaway queries and bad maps. Nothing may panic or
//! abort; every problem is a diagnostic located in its file (or a KR error value).
//! Mutations come from a seeded ChaCha generator, so a failure reproduces.

use goal::bw4t::{map, xml};
use goal::diag::Diagnostic;
use goal::kr::{Engine, Knowledge, Limits, NativeEngine, View};
use goal::syntax::check::check_path;
use goal::syntax::prolog::Reader;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Fragments inserted at random places: brackets, quotes, keywords, operators, bad bytes.
const TOKENS: &[&str] = &[
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    "'",
    "\"",
    "`",
    ".",
    ",",
    "+",
    "%",
    "/*",
    "*/",
    "0'",
    "\n",
    "bel(",
    "not(",
    "if ",
    " then ",
    "forall ",
    " do ",
    "module ",
    "=",
    "<",
    ">",
    "</",
    "/>",
    "\u{0}",
    "\u{feff}",
    "é",
    "launch ",
    "agentfiles ",
    "[[",
    "]]",
    "= \"",
    "x = 1e999",
];

/// Deep and long inputs: nesting and chains far beyond anything a person writes.
fn bombs() -> Vec<String> {
    vec![
        "f(".repeat(20_000),
        "[".repeat(20_000),
        "{".repeat(20_000),
        "(".repeat(20_000),
        vec!["a"; 50_000].join("+"),
        vec!["- "; 20_000].concat(),
        "a".repeat(1 << 20),
        format!("[{}]", vec!["1"; 100_000].join(",")),
        "<a>".repeat(20_000),
    ]
}

fn mutate(rng: &mut ChaCha8Rng, src: &[u8], bombs: &[String]) -> Vec<u8> {
    let mut out = src.to_vec();
    for _ in 0..rng.gen_range(1..4) {
        let len = out.len().max(1);
        let at = rng.gen_range(0..len).min(out.len());
        match rng.gen_range(0..6) {
            0 => {
                let end = (at + rng.gen_range(1..40)).min(out.len());
                out.drain(at..end);
            }
            1 | 2 => {
                let t = TOKENS[rng.gen_range(0..TOKENS.len())];
                out.splice(at..at, t.bytes());
            }
            3 => {
                let end = (at + rng.gen_range(1..200)).min(out.len());
                let copy = out[at..end].to_vec();
                out.splice(at..at, copy);
            }
            4 => {
                // Invalid UTF-8.
                out.insert(at, 0xff);
            }
            _ => {
                let b = &bombs[rng.gen_range(0..bombs.len())];
                out.splice(at..at, b.bytes());
            }
        }
    }
    out
}

/// Every diagnostic names `file` and points inside the source.
fn located(diags: &[Diagnostic], file: &str, source_len: usize, what: &str) {
    for d in diags {
        assert_eq!(d.file, file, "{what}: {}", d.message);
        assert!(!d.message.is_empty(), "{what}");
        assert!(
            d.span.start <= d.span.end && d.span.end <= source_len,
            "{what}: span {:?} outside {} bytes: {}",
            d.span,
            source_len,
            d.message
        );
    }
}

/// A scratch directory for this test run, with the agent files the MAS files name.
fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-attack-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in ["counter.goal", "runaway.goal", "deep.goal"] {
        let from = Path::new(ROOT).join("tests/fixtures/resources").join(f);
        std::fs::copy(from, dir.join(f)).unwrap();
    }
    dir
}

const PROLOG: &str = "app([], L, L).\napp([H|T], L, [H|R]) :- app(T, L, R).\n\
    len([], 0).\nlen([_|T], N) :- len(T, M), N is M + 1.\n";

#[test]
fn malformed_files_of_every_kind_give_located_diagnostics() {
    // Unoptimized builds of the logos lexers use a stack frame per character of a long token
    // (optimized builds loop); a big stack keeps the debug test about our code, not that.
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(check_mutants)
        .unwrap()
        .join()
        .unwrap();
}

fn check_mutants() {
    let dir = scratch();
    let bombs = bombs();
    let seeds: Vec<(&str, String)> = vec![
        ("goal", read("agents/counter/counter.goal")),
        ("goal", read("tests/fixtures/resources/deep.goal")),
        ("mas2g", read("tests/fixtures/resources/runaway.mas2g")),
        ("test2g", read("agents/counter/counter.test2g")),
        ("pl", PROLOG.to_string()),
    ];
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (i, (ext, src)) in seeds.iter().enumerate() {
        for k in 0..30 {
            let bytes = mutate(&mut rng, src.as_bytes(), &bombs);
            let path = dir.join(format!("m{i}_{k}.{ext}"));
            std::fs::write(&path, &bytes).unwrap();
            let report = check_path(&path);
            let what = format!("mutant {k} of seed {i} ({ext})");
            // An unreadable file (invalid UTF-8) has no source text: spans are into its bytes.
            let len = report.source.len().max(bytes.len());
            located(&report.diagnostics, &report.file, len, &what);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(Path::new(ROOT).join(rel)).unwrap()
}

#[test]
fn malformed_maps_in_toml_and_xml_give_located_diagnostics() {
    let bombs = bombs();
    let toml = read("maps/banana.toml");
    let xml_dir = Path::new(ROOT).join("../shared/bw4t-maps");
    let xml = match std::fs::read_to_string(xml_dir.join("banana.xml")) {
        Ok(x) => x,
        Err(_) => {
            println!("no BW4T XML maps beside the worktree: XML mutants use a small map");
            "<newMap><area><x>50.0</x><y>80.0</y></area></newMap>".to_string()
        }
    };
    let mut rng = ChaCha8Rng::seed_from_u64(12);
    for k in 0..40 {
        let m = String::from_utf8_lossy(&mutate(&mut rng, toml.as_bytes(), &bombs)).into_owned();
        if let Err(d) = map::from_toml(&m, "bad.toml") {
            located(&d, "bad.toml", m.len(), &format!("toml mutant {k}"));
        }
        let m = String::from_utf8_lossy(&mutate(&mut rng, xml.as_bytes(), &bombs)).into_owned();
        if let Err(d) = xml::import(&m, "bad.xml") {
            located(&d, "bad.xml", m.len(), &format!("xml mutant {k}"));
        }
    }
}

#[test]
fn deep_and_long_prolog_text_is_read_or_rejected_without_crashing() {
    for b in bombs() {
        let text = format!("p({b}).\n");
        let (_, diags) = Reader::new("bomb.pl").clauses(&text, 0);
        located(&diags, "bomb.pl", text.len(), "bomb");
    }
}

#[test]
fn runaway_and_hostile_queries_end_as_values() {
    let (clauses, _) = Reader::new("k.pl").clauses(
        "grow(L) :- grow([a|L]).\nloop :- loop.\nleft :- left, x.\n\
         dbl(A, B) :- atom_concat(A, A, C), dbl(C, B).\n",
        0,
    );
    let kn = Knowledge::load(&clauses.into_iter().map(|c| c.term).collect::<Vec<_>>()).unwrap();
    let limits = Limits {
        max_inferences: 300_000,
        max_heap_cells: 1 << 20,
        ..Limits::default()
    };
    let mut e = NativeEngine::new(3).with_limits(limits);
    let view = View::beliefs(&kn, &[]);
    for q in [
        "grow([])",
        "loop",
        "left",
        "dbl(ab, B)",
        "between(1, inf, X)",
        "length(L, N)",
        "repeat, fail",
        "X = [a|X], member(b, X)",
        "X = f(X), Y = f(Y), X == Y, fail",
        "X = f(X), copy_term(X, Y)",
        "findall(X, between(1, inf, X), L)",
        "numlist(1, 50000000, L)",
        "atom_codes(A, L)",
        "catch(loop, _, true)",
        "throw(f(_))",
        "assert(x)",
        "X is 2 ** 100000",
        "atom_length(A, N)",
        "sub_atom(abc, B, L, A, S), fail",
        "format(\"~*c\", [100000000, 0'x])",
        "tab(100000000)",
        "atom_to_term('foo(', T, B)",
        "term_to_atom(T, 'f(((((')",
    ] {
        let t = Reader::new("q").term(q, 0).unwrap().term;
        // Either answers or an error value: never a panic, never a hang.
        if let Err(err) = e.query(&view, &t) {
            assert!(!err.to_string().is_empty(), "{q}");
            assert!(
                err.to_string().len() < 3_000,
                "{q}: {} bytes",
                err.to_string().len()
            );
        }
        let _ = e.take_output();
    }
}
