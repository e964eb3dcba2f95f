//! A class: one directory per submission under the class directory, each with the `.mas2g`
//! file to run and its `.test2g` files.

use std::path::{Path, PathBuf};

/// How deep below a submission's directory files are looked for.
const MAX_DEPTH: usize = 6;

/// One student's (or team's) submission.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Submission {
    /// The directory's name (the submission's name in every table).
    pub name: String,
    pub dir: PathBuf,
    /// The `.mas2g` file to run, or why there is none to run.
    pub mas: Result<PathBuf, String>,
    /// Its `.test2g` files, sorted.
    pub tests: Vec<PathBuf>,
}

/// The submissions of `class_dir`, in name order, with absolute paths (each runs in its own
/// directory); hidden directories are left out.
pub fn discover(class_dir: &Path) -> Result<Vec<Submission>, String> {
    let class_dir = std::fs::canonicalize(class_dir).map_err(|e| {
        format!(
            "cannot read the class directory {}: {e}",
            class_dir.display()
        )
    })?;
    let entries = std::fs::read_dir(&class_dir).map_err(|e| {
        format!(
            "cannot read the class directory {}: {e}",
            class_dir.display()
        )
    })?;
    let mut dirs: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_dir() && !is_hidden(p))
        .collect();
    dirs.sort();
    Ok(dirs.into_iter().map(|d| submission(&d)).collect())
}

fn is_hidden(p: &Path) -> bool {
    p.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.starts_with('.'))
}

/// The submission in `dir`.
pub fn submission(dir: &Path) -> Submission {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| dir.display().to_string());
    let files = files_under(dir);
    let with = |ext: &str| -> Vec<PathBuf> {
        files
            .iter()
            .filter(|p| p.extension().and_then(|x| x.to_str()) == Some(ext))
            .cloned()
            .collect()
    };
    Submission {
        name,
        dir: dir.to_path_buf(),
        mas: choose_mas(dir, &with("mas2g")),
        tests: with("test2g"),
    }
}

/// The one `.mas2g` to run: the only one directly in `dir`, else the only one below it.
fn choose_mas(dir: &Path, found: &[PathBuf]) -> Result<PathBuf, String> {
    let top: Vec<&PathBuf> = found.iter().filter(|p| p.parent() == Some(dir)).collect();
    let candidates: Vec<&PathBuf> = if top.is_empty() {
        found.iter().collect()
    } else {
        top
    };
    match candidates.as_slice() {
        [one] => Ok((*one).clone()),
        [] => Err("no .mas2g file found".into()),
        many => {
            let names: Vec<String> = many
                .iter()
                .map(|p| p.strip_prefix(dir).unwrap_or(p).display().to_string())
                .collect();
            Err(format!(
                "{} .mas2g files, cannot tell which to run: {} (keep one at the top of the \
                 submission)",
                names.len(),
                names.join(", ")
            ))
        }
    }
}

/// Every file below `dir` (at most [`MAX_DEPTH`] levels, hidden entries and symbolic links
/// left out), sorted.
fn files_under(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![(dir.to_path_buf(), 0usize)];
    while let Some((d, depth)) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            let Ok(kind) = e.file_type() else { continue };
            if is_hidden(&p) || kind.is_symlink() {
                continue;
            }
            if kind.is_dir() && depth < MAX_DEPTH {
                stack.push((p, depth + 1));
            } else if kind.is_file() {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touch(p: &Path) {
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, "").unwrap();
    }

    #[test]
    fn one_mas_per_submission_or_a_reason() {
        let root = std::env::temp_dir().join(format!("goal-class-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        std::fs::create_dir_all(&root).unwrap();
        let root = std::fs::canonicalize(&root).unwrap();
        touch(&root.join("alice/team.mas2g"));
        touch(&root.join("alice/tests/team.test2g"));
        touch(&root.join("bob/src/deep/team.mas2g"));
        touch(&root.join("carol/a.mas2g"));
        touch(&root.join("carol/b.mas2g"));
        touch(&root.join("dave/readme.txt"));
        touch(&root.join("erin/main.mas2g"));
        touch(&root.join("erin/old/main.mas2g"));
        touch(&root.join(".git/x.mas2g"));
        let subs = discover(&root).unwrap();
        let names: Vec<&str> = subs.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["alice", "bob", "carol", "dave", "erin"]);
        assert_eq!(subs[0].mas, Ok(root.join("alice/team.mas2g")));
        assert_eq!(subs[0].tests, [root.join("alice/tests/team.test2g")]);
        assert_eq!(subs[1].mas, Ok(root.join("bob/src/deep/team.mas2g")));
        let carol = subs[2].mas.clone().unwrap_err();
        assert!(carol.contains("a.mas2g, b.mas2g"), "{carol}");
        assert_eq!(subs[3].mas, Err("no .mas2g file found".into()));
        // A file at the top wins over older copies below it.
        assert_eq!(subs[4].mas, Ok(root.join("erin/main.mas2g")));
        let _ = std::fs::remove_dir_all(&root);
    }
}
