//! Every relative link in `README.md` and `docs/**/*.md` points at a file of the repository, so
//! pages cannot silently lose their targets when files move; the `.goal` examples of the language
//! reference check clean.

use std::path::{Path, PathBuf};

/// Pages written on other branches at the same time (the browser view and `goal why`); links to
/// them are reported, not failed, while they are absent.
const WRITTEN_ELSEWHERE: &[&str] = &["docs/view.md", "docs/why.md"];

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("docs").flatten() {
        let p = e.path();
        if p.is_dir() {
            markdown_files(&p, out);
        } else if p.extension().and_then(|e| e.to_str()) == Some("md") {
            out.push(p);
        }
    }
}

/// The targets of `[text](target)` links in a page.
fn links(text: &str) -> Vec<String> {
    text.match_indices("](")
        .filter_map(|(i, _)| {
            let rest = &text[i + 2..];
            rest.find(')').map(|end| rest[..end].to_string())
        })
        .collect()
}

#[test]
fn relative_links_in_the_docs_resolve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages = vec![root.join("README.md")];
    markdown_files(&root.join("docs"), &mut pages);
    let mut broken = Vec::new();
    for page in &pages {
        let text = std::fs::read_to_string(page).expect("page");
        for target in links(&text) {
            if target.contains("://") || target.starts_with('#') || target.starts_with("mailto:") {
                continue;
            }
            let file = target.split('#').next().unwrap_or("");
            let path = page.parent().expect("dir").join(file);
            let elsewhere = WRITTEN_ELSEWHERE.iter().any(|w| path.ends_with(w));
            if !path.exists() && elsewhere {
                println!("{}: {target} is not here yet", page.display());
            } else if !path.exists() {
                broken.push(format!("{}: {target}", page.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

/// The fenced blocks of a page whose info string starts with `lang`.
fn blocks<'a>(text: &'a str, lang: &str) -> Vec<&'a str> {
    let open = format!("```{lang}\n");
    text.match_indices(&open)
        .filter_map(|(i, _)| {
            let body = &text[i + open.len()..];
            body.find("```").map(|end| &body[..end])
        })
        .collect()
}

#[test]
fn the_goal_examples_of_the_language_reference_check_without_errors() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("docs/language.md")).expect("language.md");
    let examples = blocks(&text, "goal");
    assert!(!examples.is_empty());
    let dir = std::env::temp_dir().join(format!("goal-docs-examples-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    for (i, example) in examples.iter().enumerate() {
        let file = dir.join(format!("example{i}.goal"));
        std::fs::write(&file, example).expect("write");
        let reports = goal::mas::envcheck::check_path(&file);
        let problems: Vec<String> = reports
            .iter()
            .flat_map(|r| r.diagnostics.iter().map(|d| d.render(&r.source)))
            .collect();
        assert!(problems.is_empty(), "example {i}:\n{}", problems.join(""));
    }
    let _ = std::fs::remove_dir_all(&dir);
}
