//! Diagnostics: errors and warnings with a file, a byte span, a code, a message and a hint,
//! rendered like rustc's (`error[E0009]: ...` with the source line and a caret, ending with where
//! to read more: `goal explain E0009`) or as JSON lines.

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label, Severity as CsSeverity};
use codespan_reporting::files::SimpleFiles;
use codespan_reporting::term::{self, termcolor::NoColor};
use serde::Serialize;
use std::ops::Range;

/// Files larger than this are shown with a window of the offending line only.
const LARGE_FILE: usize = 1_000_000;
/// Lines longer than this are shown as a window around the span.
const LONG_LINE: usize = 1_000;
/// Characters of context shown on each side of the span in a window.
const WINDOW: usize = 60;

/// A byte range in a source file.
pub type Span = Range<usize>;

/// How bad a diagnostic is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    Warning,
    Error,
}

/// One problem found in one file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnostic {
    pub severity: Severity,
    /// A stable code such as `E0009` (errors) or `W0001` (warnings).
    pub code: String,
    pub message: String,
    /// The file the span refers to (as given by the user).
    pub file: String,
    /// Byte range of the offending text; empty ranges point between characters.
    pub span: Span,
    /// What to do about it, if there is something useful to say.
    pub hint: Option<String>,
}

impl Diagnostic {
    /// An error at `span` of `file`.
    pub fn error(
        code: &str,
        message: impl Into<String>,
        file: impl Into<String>,
        span: Span,
    ) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code: code.into(),
            message: message.into(),
            file: file.into(),
            span,
            hint: None,
        }
    }

    /// A warning at `span` of `file`.
    pub fn warning(
        code: &str,
        message: impl Into<String>,
        file: impl Into<String>,
        span: Span,
    ) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            code: code.into(),
            message: message.into(),
            file: file.into(),
            span,
            hint: None,
        }
    }

    /// Adds a hint saying what to do.
    pub fn with_hint(mut self, hint: impl Into<String>) -> Diagnostic {
        self.hint = Some(hint.into());
        self
    }

    /// True for errors (as opposed to warnings).
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }

    /// 1-based line and column (in characters) of the span start within `source`.
    pub fn line_col(&self, source: &str) -> (usize, usize) {
        line_col(source, self.span.start)
    }

    /// Renders the diagnostic like rustc, with the source line and a caret under the span.
    pub fn render(&self, source: &str) -> String {
        let start = clamp_to_char_boundary(source, self.span.start.min(source.len()));
        let end = clamp_to_char_boundary(source, self.span.end.clamp(start, source.len()));
        let line_start = source[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = source[start..]
            .find('\n')
            .map_or(source.len(), |i| start + i);
        // Very long lines and huge files would flood the terminal and cost time per diagnostic:
        // show a window of the line instead.
        if source.len() > LARGE_FILE || line_end - line_start > LONG_LINE {
            return self.render_window(source, start, end, line_start, line_end);
        }
        let mut files = SimpleFiles::new();
        let id = files.add(self.file.as_str(), source);
        let severity = match self.severity {
            Severity::Error => CsSeverity::Error,
            Severity::Warning => CsSeverity::Warning,
        };
        let mut d = CsDiagnostic::new(severity)
            .with_code(self.code.clone())
            .with_message(self.message.clone())
            .with_labels(source_label(id, source, start..end));
        let notes: Vec<String> = self
            .hint
            .iter()
            .map(|h| format!("help: {h}"))
            .chain(self.footer())
            .collect();
        d = d.with_notes(notes);
        let mut out = NoColor::new(Vec::new());
        let config = term::Config::default();
        if term::emit(&mut out, &config, &files, &d).is_err() {
            return self.render_window(source, start, end, line_start, line_end);
        }
        String::from_utf8_lossy(&out.into_inner()).into_owned()
    }

    /// The rustc layout with at most [`WINDOW`] characters of the source line on each side of
    /// the span start.
    fn render_window(
        &self,
        source: &str,
        start: usize,
        end: usize,
        line_start: usize,
        line_end: usize,
    ) -> String {
        let (line, col) = self.line_col(source);
        let before: Vec<char> = source[line_start..start].chars().collect();
        let skip = before.len().saturating_sub(WINDOW);
        let shown_before: String = before[skip..].iter().collect();
        let after: String = source[start..line_end].chars().take(WINDOW).collect();
        let caret_len = source[start..end.min(line_end).max(start)]
            .chars()
            .count()
            .clamp(1, WINDOW);
        let prefix = if skip > 0 { "..." } else { "" };
        let lineno = line.to_string();
        let pad = " ".repeat(lineno.len());
        let mut out = format!(
            "{}[{}]: {}\n{pad}--> {}:{line}:{col}\n{pad} |\n{lineno} | {prefix}{shown_before}{after}\n{pad} | {}{}\n",
            self.severity_word(),
            self.code,
            self.message,
            self.file,
            " ".repeat(prefix.len() + shown_before.chars().count()),
            "^".repeat(caret_len),
        );
        if let Some(h) = &self.hint {
            out.push_str(&format!("{pad} = help: {h}\n"));
        }
        if let Some(f) = self.footer() {
            out.push_str(&format!("{pad} = {f}\n"));
        }
        out.push('\n');
        out
    }

    /// The last line of a rendered diagnostic: where its code is explained. Every `E`, `W` and
    /// `M` code has a page (the table in `syntax::codes`; a test keeps every code the source
    /// emits there).
    fn footer(&self) -> Option<String> {
        matches!(self.code.chars().next(), Some('E' | 'W' | 'M'))
            .then(|| format!("for more, run goal explain {}", self.code))
    }

    /// One JSON object (no trailing newline) for editors and graders.
    pub fn to_json(&self, source: &str) -> String {
        let (line, column) = self.line_col(source);
        serde_json::json!({
            "severity": self.severity,
            "code": self.code,
            "message": self.message,
            "file": self.file,
            "line": line,
            "column": column,
            "start": self.span.start,
            "end": self.span.end,
            "hint": self.hint,
        })
        .to_string()
    }

    fn severity_word(&self) -> &'static str {
        match self.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        }
    }
}

fn clamp_to_char_boundary(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// 1-based line and column (in characters) of byte `offset` in `source`.
pub fn line_col(source: &str, offset: usize) -> (usize, usize) {
    let offset = clamp_to_char_boundary(source, offset.min(source.len()));
    let before = &source[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, source[line_start..offset].chars().count() + 1)
}

/// The label under the source line; none when there is no source (a file that could not be
/// read, the start of a run), because an empty line with a caret says nothing.
fn source_label(id: usize, source: &str, span: Range<usize>) -> Vec<Label<usize>> {
    if source.is_empty() {
        Vec::new()
    } else {
        vec![Label::primary(id, span)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_with_file_line_column_and_caret() {
        let src = "main module {\n  program { if bel(p) then foo. }\n}\n";
        let d = Diagnostic::error(
            "E0104",
            "action `foo/0` is used but never specified",
            "a.goal",
            39..42,
        )
        .with_hint("add an action spec for foo/0");
        let text = d.render(src);
        assert!(
            text.contains("error[E0104]: action `foo/0` is used but never specified"),
            "{text}"
        );
        assert!(
            text.trim_end()
                .ends_with("= for more, run goal explain E0104"),
            "{text}"
        );
        assert!(!d.to_json(src).contains("goal explain"));
        assert!(text.contains("a.goal:2:26"), "{text}");
        assert!(text.contains("^^^"), "{text}");
        assert!(text.contains("help: add an action spec"), "{text}");
        assert_eq!(d.line_col(src), (2, 26));
    }

    #[test]
    fn long_lines_show_a_window_with_a_caret() {
        let src = format!("{}bad{}", "x ".repeat(5_000), " y".repeat(5_000));
        let d = Diagnostic::error("E0009", "bad token", "big.goal", 10_000..10_003);
        let text = d.render(&src);
        assert!(
            text.contains("= for more, run goal explain E0009"),
            "{text}"
        );
        assert!(text.contains("big.goal:1:10001"), "{text}");
        assert!(text.contains("...") && text.contains("^^^"), "{text}");
        assert!(text.len() < 1_000, "{}", text.len());
    }

    #[test]
    fn map_codes_end_with_goal_explain() {
        let d = Diagnostic::error("M0013", "rooms overlap", "m.toml", 0..1);
        let text = d.render("x = 1\n");
        assert!(text.contains("error[M0013]"), "{text}");
        assert!(
            text.trim_end()
                .ends_with("= for more, run goal explain M0013"),
            "{text}"
        );
    }

    #[test]
    fn without_source_there_is_no_empty_snippet() {
        let d = Diagnostic::error("M0031", "the run cannot start", "run", 0..0);
        let text = d.render("");
        assert!(
            text.contains("error[M0031]: the run cannot start"),
            "{text}"
        );
        assert!(!text.contains("run:1:1") && !text.contains('^'), "{text}");
        assert!(
            text.contains("= for more, run goal explain M0031"),
            "{text}"
        );
    }

    #[test]
    fn out_of_range_spans_do_not_panic() {
        let d = Diagnostic::warning("W0001", "x", "f", 100..200);
        let _ = d.render("short");
        let _ = d.render("");
        let _ = d.to_json("é");
    }
}
