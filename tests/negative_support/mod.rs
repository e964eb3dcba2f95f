//! Shared support for the negative-fixture tests: each fixture starts with a comment line
//! `% expect: CODE LINE:COL` naming a diagnostic it must produce and where.

#![allow(dead_code)]

use goal::diag::Diagnostic;
use std::path::Path;

/// `(relative path, code, line, column)` of every fixture with extension `ext` in `dir`
/// (relative to the crate root), sorted by file name.
pub fn negative_fixtures(dir: &str, ext: &str) -> Vec<(String, String, usize, usize)> {
    let abs = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let mut names: Vec<String> = std::fs::read_dir(&abs)
        .expect("fixture directory readable")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(&format!(".{ext}")))
        .collect();
    names.sort();
    assert!(!names.is_empty(), "no fixtures in {dir}");
    names
        .into_iter()
        .map(|n| {
            let rel = format!("{dir}/{n}");
            let text = std::fs::read_to_string(abs.join(&n)).expect("fixture readable");
            let header = text.lines().next().unwrap_or("");
            let spec = header
                .strip_prefix("% expect: ")
                .unwrap_or_else(|| panic!("{rel}: first line must be `% expect: CODE LINE:COL`"));
            let (code, at) = spec.trim().split_once(' ').expect("`CODE LINE:COL`");
            let (l, c) = at.split_once(':').expect("`LINE:COL`");
            assert!(
                n.starts_with(code),
                "{rel}: file name must start with its code {code}"
            );
            (
                rel,
                code.to_string(),
                l.parse().expect("line"),
                c.parse().expect("column"),
            )
        })
        .collect()
}

/// Asserts that `diags` has a diagnostic `code` at `line:col`, and that all spans are valid.
pub fn assert_reported(
    rel: &str,
    source: &str,
    diags: &[Diagnostic],
    code: &str,
    line: usize,
    col: usize,
) {
    for d in diags {
        assert!(
            d.span.start <= d.span.end && d.span.end <= source.len(),
            "{rel}: bad span {d:?}"
        );
    }
    let found: Vec<(String, (usize, usize))> = diags
        .iter()
        .map(|d| (d.code.clone(), d.line_col(source)))
        .collect();
    assert!(
        found.iter().any(|(c, at)| c == code && *at == (line, col)),
        "{rel}: expected {code} at {line}:{col}, found {found:?}\n{}",
        render_all(source, diags)
    );
}

/// All diagnostics rendered rustc-style, one after the other.
pub fn render_all(source: &str, diags: &[Diagnostic]) -> String {
    diags
        .iter()
        .map(|d| d.render(source))
        .collect::<Vec<_>>()
        .join("")
}

/// A random mutant of `src`: 1-4 rounds of deleting, inserting (a fragment of `tokens`),
/// duplicating, swapping or overwriting byte ranges. Invalid UTF-8 is replaced lossily.
pub fn mutate(rng: &mut rand_chacha::ChaCha8Rng, src: &[u8], tokens: &[&str]) -> String {
    use rand::Rng;
    let mut v = src.to_vec();
    for _ in 0..rng.gen_range(1..=4) {
        let len = v.len();
        let a = rng.gen_range(0..=len);
        let b = (a + rng.gen_range(0..=40)).min(len);
        match rng.gen_range(0..5) {
            0 => {
                v.drain(a..b);
            }
            1 => {
                let t = tokens[rng.gen_range(0..tokens.len())];
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
            _ => {
                if a < len {
                    v[a] = rng.gen_range(0x20..0x7f);
                }
            }
        }
    }
    String::from_utf8_lossy(&v).into_owned()
}

/// Asserts that every diagnostic lies within `src` and belongs to `file` or names another file.
pub fn assert_spans_inside(file: &str, src: &str, diags: &[Diagnostic]) {
    for d in diags {
        if d.file != file {
            continue; // diagnostics about other files (e.g. a MAS file named by a test)
        }
        assert!(
            d.span.start <= d.span.end && d.span.end <= src.len(),
            "span {:?} outside the file ({} bytes): {d:?}\n--- input ---\n{src}",
            d.span,
            src.len()
        );
        assert!(!d.message.is_empty());
    }
}
