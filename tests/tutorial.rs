//! Every command of `docs/tutorial.md` runs, in order, in a fresh directory: the ```sh blocks
//! are run line by line (`cd` changes the directory of the following lines; a comment saying
//! `exit code N` expects N, every other line 0), blocks with `file=PATH` in their info string
//! are written where the reader is told to write them, and every line of a ```text block right
//! after a ```sh block must appear in that block's output. So the tutorial cannot silently rot.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One fenced block: its info string and its lines.
struct Block {
    info: String,
    lines: Vec<String>,
    /// The line of the opening fence in the page (1-based), for messages.
    at: usize,
}

fn blocks(page: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut lines = page.lines().enumerate();
    while let Some((i, line)) = lines.next() {
        let Some(info) = line.strip_prefix("```") else {
            continue;
        };
        let body = lines
            .by_ref()
            .map(|(_, l)| l)
            .take_while(|l| *l != "```")
            .map(str::to_string)
            .collect();
        out.push(Block {
            info: info.trim().to_string(),
            lines: body,
            at: i + 1,
        });
    }
    out
}

/// The exit code a command line expects: `# ... exit code N ...`, or 0.
fn expected_exit(comment: &str) -> i32 {
    comment
        .split("exit code ")
        .nth(1)
        .and_then(|rest| rest.split(|c: char| !c.is_ascii_digit()).next())
        .and_then(|n| n.parse().ok())
        .unwrap_or(0)
}

/// Runs the lines of one ```sh block; returns everything they printed.
fn run_block(block: &Block, cwd: &mut PathBuf, path_var: &str) -> String {
    let mut printed = String::new();
    for line in &block.lines {
        let (command, comment) = match line.find(" #") {
            Some(i) => (line[..i].trim(), &line[i..]),
            None => (line.trim(), ""),
        };
        if command.is_empty() || command.starts_with('#') {
            continue;
        }
        if let Some(dir) = command.strip_prefix("cd ") {
            *cwd = cwd.join(dir.trim());
            assert!(
                cwd.is_dir(),
                "line {}: no directory {}",
                block.at,
                cwd.display()
            );
            continue;
        }
        let out = Command::new("sh")
            .arg("-c")
            .arg(command)
            .current_dir(&*cwd)
            .env("PATH", path_var)
            .output()
            .expect("sh runs");
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(
            out.status.code(),
            Some(expected_exit(comment)),
            "tutorial block at line {}: `{command}` in {}:\n{text}",
            block.at,
            cwd.display()
        );
        printed.push_str(&text);
    }
    printed
}

#[test]
fn every_command_of_the_tutorial_runs_as_the_tutorial_says() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = std::fs::read_to_string(root.join("docs/tutorial.md")).expect("docs/tutorial.md");
    let home = std::env::temp_dir().join(format!("goal-tutorial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&home);
    std::fs::create_dir_all(&home).expect("temp dir");
    let bin = Path::new(env!("CARGO_BIN_EXE_goal"))
        .parent()
        .expect("bin dir");
    let path_var = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut cwd = home.clone();
    let mut last_output: Option<String> = None;
    let (mut commands, mut checked_lines, mut files) = (0, 0, 0);
    for block in blocks(&page) {
        let mut words = block.info.split_whitespace();
        let lang = words.next().unwrap_or("");
        let file = words.find_map(|w| w.strip_prefix("file="));
        if let Some(file) = file {
            std::fs::write(cwd.join(file), block.lines.join("\n") + "\n").expect("write");
            files += 1;
            last_output = None;
        } else if lang == "sh" {
            commands += block.lines.iter().filter(|l| !l.trim().is_empty()).count();
            last_output = Some(run_block(&block, &mut cwd, &path_var));
        } else if lang == "text" {
            if let Some(printed) = last_output.take() {
                for want in block.lines.iter().filter(|l| !l.trim().is_empty()) {
                    assert!(
                        printed.contains(want.as_str()),
                        "tutorial block at line {}: `{want}` not in the output:\n{printed}",
                        block.at
                    );
                    checked_lines += 1;
                }
            }
        } else {
            last_output = None;
        }
    }
    println!("{commands} commands, {files} files, {checked_lines} output lines checked");
    assert!(commands >= 20 && files >= 3 && checked_lines >= 10);
    let _ = std::fs::remove_dir_all(&home);
}
