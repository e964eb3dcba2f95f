//! No input makes the modular parsers panic or hang: mutated fixtures and random text through
//! the `.mod2g` (both generations), `.act2g` and modular `.mas2g` parsers, with a fixed seed.

use goal::syntax::modular::{mas, parse_act2g, parse_mod2g};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;

fn fixtures() -> Vec<String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/modular");
    let mut out = Vec::new();
    for sub in ["a", "b"] {
        let mut files: Vec<_> = std::fs::read_dir(root.join(sub))
            .expect("fixtures")
            .flatten()
            .map(|e| e.path())
            .collect();
        files.sort();
        out.extend(
            files
                .iter()
                .map(|f| std::fs::read_to_string(f).expect("read")),
        );
    }
    out
}

const PIECES: &[&str] = &[
    "(", ")", "{", "}", "[", "]", ".", ",", "'", "\"", "%", "/*", "*/", "if", "then", "do",
    "forall", "listall", "<-", "not(", "send!(", "sent?(", "post-", "post+", "define", "use", "as",
    "module", "with", "pre", "é", "\\", "0'", "=", "+", "\n",
];

fn mutate(rng: &mut ChaCha8Rng, text: &str) -> String {
    let mut s: Vec<char> = text.chars().collect();
    for _ in 0..rng.gen_range(1..6) {
        let at = if s.is_empty() {
            0
        } else {
            rng.gen_range(0..s.len())
        };
        match rng.gen_range(0..3) {
            0 if !s.is_empty() => {
                let end = (at + rng.gen_range(1..8)).min(s.len());
                s.drain(at..end);
            }
            1 => {
                let p = PIECES[rng.gen_range(0..PIECES.len())];
                for (i, c) in p.chars().enumerate() {
                    s.insert(at + i, c);
                }
            }
            _ => {
                let c = char::from_u32(rng.gen_range(32..0x250)).unwrap_or('x');
                s.insert(at, c);
            }
        }
    }
    s.into_iter().collect()
}

fn parse_all(text: &str) {
    let n = text.len();
    let _ = parse_mod2g("f.mod2g", text, 0, n, false);
    let _ = parse_mod2g("f.mod2g", text, 0, n, true);
    let _ = parse_act2g("f.act2g", text, 0, n);
    let _ = mas::parse(text, "f.mas2g");
}

#[test]
fn mutated_fixtures_never_panic() {
    let mut rng = ChaCha8Rng::seed_from_u64(13);
    let base = fixtures();
    for i in 0..1500 {
        let text = mutate(&mut rng, &base[i % base.len()]);
        parse_all(&text);
    }
}

#[test]
fn deep_nesting_and_long_input_are_errors_not_crashes() {
    let deep = format!("module m {{ {} }}", "if true then {".repeat(5000));
    let (_, d) = parse_mod2g("d.mod2g", &deep, 0, deep.len(), false);
    assert!(d.iter().any(|x| x.code == "E0016"));
    let cond = |n: usize| format!("module m {{ if {} then print(a). }}", "a, ".repeat(n) + "b");
    let ok = cond(500);
    let (m, d) = parse_mod2g("c.mod2g", &ok, 0, ok.len(), true);
    assert!(d.is_empty(), "{:?}", d.first());
    let rules = &m.expect("parsed").module.program.expect("rules").rules;
    assert_eq!(rules[0].condition.len(), 501);
    // The Prolog reader's bound on operator chains makes a huge condition an error.
    let huge = cond(20000);
    let (_, d) = parse_mod2g("c.mod2g", &huge, 0, huge.len(), true);
    assert!(d.iter().any(|x| x.code == "E0010"));
    let vals = format!(
        "use \"bw4t\" as environment with x = {}1{}.",
        "[".repeat(100),
        "]".repeat(100)
    );
    let (_, d) = mas::parse(&vals, "v.mas2g");
    assert!(d.iter().any(|x| x.code == "E0201"));
}
