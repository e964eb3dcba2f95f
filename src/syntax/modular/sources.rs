//! The files of one modular agent in one text. Each file is appended to a shared text, so that
//! every span of the assembled program is unique and the 2014 compiler (which reads one source)
//! can be used unchanged; diagnostics and line numbers are mapped back to their own file.

use crate::diag::{line_col, Diagnostic};
use std::sync::Arc;

/// One file inside a [`SourceSet`].
#[derive(Clone, Debug)]
pub struct Segment {
    /// The file name as shown to users.
    pub name: String,
    /// The file's own text.
    pub text: Arc<str>,
    /// Byte range in the shared text.
    pub start: usize,
    pub end: usize,
    /// 1-based line of `start` in the shared text.
    first_line: usize,
}

/// The shared text of an agent's files.
#[derive(Clone, Debug, Default)]
pub struct SourceSet {
    pub text: String,
    pub segments: Vec<Segment>,
}

impl SourceSet {
    /// Appends a file; returns its segment index.
    pub fn add(&mut self, name: &str, text: &str) -> usize {
        let start = self.text.len();
        let first_line = line_col(&self.text, start).0;
        self.text.push_str(text);
        let end = self.text.len();
        // A line break keeps every file starting on a line of its own.
        self.text.push('\n');
        self.segments.push(Segment {
            name: name.to_string(),
            text: Arc::from(text),
            start,
            end,
            first_line,
        });
        self.segments.len() - 1
    }

    /// The segment containing byte `offset` of the shared text.
    pub fn segment_of(&self, offset: usize) -> Option<&Segment> {
        let i = self.segments.partition_point(|s| s.start <= offset);
        self.segments.get(i.checked_sub(1)?)
    }

    /// A diagnostic whose span is in the shared text, moved to its own file; with that file's
    /// text for rendering.
    pub fn localize(&self, mut d: Diagnostic) -> (Diagnostic, Arc<str>) {
        match self.segment_of(d.span.start) {
            Some(s) if d.span.start <= s.end + 1 => {
                let end = d.span.end.min(s.end);
                d.span = d.span.start - s.start..end.max(d.span.start) - s.start;
                d.file = s.name.clone();
                (d, s.text.clone())
            }
            _ => (d, Arc::from("")),
        }
    }

    /// A line of the shared text as (file, line in that file).
    pub fn local_line(&self, line: usize) -> (&str, usize) {
        let i = self.segments.partition_point(|s| s.first_line <= line);
        match i.checked_sub(1).and_then(|i| self.segments.get(i)) {
            Some(s) => (&s.name, line - s.first_line + 1),
            None => ("", line),
        }
    }
}
