//! Property test: random token sequences and mutants of the corpus (deleted, inserted, duplicated and swapped byte ranges and
//! tokens; seeded ChaCha) never panic, and every diagnostic has a span inside the file.

use goal::syntax::goal::{parse_goal, parse_mod2g};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::path::Path;

const CORPUS: &[&str] = &[
    "agents/blocksworld/stacker.goal",
    "agents/bw4t/robot.goal",
    "agents/counter/counter.goal",
    "agents/pingpong/ping.goal",
    "agents/pingpong/pong.goal",
    "tests/fixtures/goal/every_construct.goal",
    "tests/fixtures/goal/helpers.mod2g",
];

/// Fragments that stress the lexer and the grammar when inserted at random places.
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
    "not(",
    "bel(",
    "a-goal(",
    "goal-a",
    "exit-module",
    "if ",
    " then ",
    "forall ",
    " do ",
    "listall ",
    " <- ",
    " -> ",
    "#import ",
    "#define ",
    "@int",
    "@env",
    "module ",
    "main module ",
    "program ",
    "knowledge ",
    "beliefs {",
    "pre {",
    "post {",
    "actionspec {",
    "(bob).",
    "all.",
    "send(",
    "?",
    "!",
    ":",
    "X",
    "_",
    "é",
    "=..",
    "3.14",
    "[exit=",
    "order=",
    "\\",
    "\0",
];

fn mutate(rng: &mut ChaCha8Rng, src: &[u8]) -> Vec<u8> {
    let mut v = src.to_vec();
    let rounds = rng.gen_range(1..=4);
    for _ in 0..rounds {
        let len = v.len();
        let a = rng.gen_range(0..=len);
        let b = (a + rng.gen_range(0..=40)).min(len);
        match rng.gen_range(0..6) {
            0 => {
                v.drain(a..b);
            }
            1 => {
                let t = TOKENS[rng.gen_range(0..TOKENS.len())];
                v.splice(a..a, t.bytes());
            }
            2 => {
                let piece = v[a..b].to_vec();
                v.splice(b..b, piece);
            }
            3 => {
                let c = rng.gen_range(0..=len);
                let d = (c + rng.gen_range(0..=40)).min(len);
                if b <= c {
                    let (x, y) = (v[a..b].to_vec(), v[c..d].to_vec());
                    v.splice(c..d, x);
                    v.splice(a..b, y);
                }
            }
            4 => {
                if a < len {
                    v[a] = rng.gen_range(0x20..0x7f);
                }
            }
            _ => {
                let n = rng.gen_range(1..=30);
                let t = TOKENS[rng.gen_range(0..TOKENS.len())];
                let rep = t.repeat(n);
                v.splice(a..a, rep.bytes());
            }
        }
    }
    v
}

fn check(file: &str, src: &str) {
    let diags = if file.ends_with(".mod2g") {
        parse_mod2g(file, src).1
    } else {
        parse_goal(file, src).1
    };
    for d in &diags {
        assert!(
            d.span.start <= d.span.end && d.span.end <= src.len(),
            "span {:?} outside the file ({} bytes): {d:?}\n--- input ---\n{src}",
            d.span,
            src.len()
        );
        assert_eq!(d.file, file);
        assert!(!d.message.is_empty());
    }
}

#[test]
fn mutated_corpus_never_panics_and_spans_stay_in_the_file() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let corpus: Vec<(String, Vec<u8>)> = CORPUS
        .iter()
        .map(|f| {
            let text = std::fs::read(root.join(f)).expect("corpus file");
            (f.to_string(), text)
        })
        .collect();
    let mut rng = ChaCha8Rng::seed_from_u64(0x60a1);
    let mut count = 0usize;
    while count < 100_000 {
        let (file, text) = &corpus[rng.gen_range(0..corpus.len())];
        // Mostly windows of a program (fast), sometimes the whole file.
        let piece: &[u8] = if rng.gen_ratio(1, 50) {
            text
        } else {
            let start = rng.gen_range(0..text.len());
            let end = (start + rng.gen_range(1..400)).min(text.len());
            &text[start..end]
        };
        // One input in ten is a random sequence of tokens instead of a mutant.
        let mutant = if rng.gen_ratio(1, 10) {
            let n = rng.gen_range(1..80);
            let mut v = Vec::new();
            for _ in 0..n {
                v.extend_from_slice(TOKENS[rng.gen_range(0..TOKENS.len())].as_bytes());
                if rng.gen_bool(0.5) {
                    v.push(b' ');
                }
            }
            v
        } else {
            mutate(&mut rng, piece)
        };
        let src = String::from_utf8_lossy(&mutant);
        let result = std::panic::catch_unwind(|| check(file, &src));
        if result.is_err() {
            panic!("input #{count} from {file} panicked:\n{src}");
        }
        count += 1;
    }
    assert_eq!(count, 100_000);
}
