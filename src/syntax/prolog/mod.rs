//! The Prolog reader: Prolog text (KR content of `.goal` files, `.pl` files, queries) to terms
//! with byte spans, using GOAL's fixed operator table.

use crate::diag::{Diagnostic, Span};
use crate::term::Term;

/// Byte spans of a term and, for compound terms, of each argument (list cells: head and tail).
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct TermSpans {
    pub span: Span,
    pub args: Vec<TermSpans>,
}

/// A term read from source text, with its spans.
#[derive(Clone, Debug, PartialEq)]
pub struct Located {
    pub term: Term,
    pub spans: TermSpans,
}

/// Reads Prolog text from one file; numbers anonymous variables `_` apart across all calls
/// (`_G1`, `_G2`, ...), so that terms read from one file never share an anonymous variable.
pub struct Reader {
    file: String,
    next_anonymous: u32,
}

impl Reader {
    /// A reader for text that comes from `file` (used in diagnostics).
    pub fn new(file: impl Into<String>) -> Reader {
        Reader { file: file.into(), next_anonymous: 0 }
    }

    /// Reads one term (priority up to 1200, no final `.`) from `text`, which starts at byte
    /// `offset` of the file: the content of `pre{}`, `bel(...)`, a query, ...
    pub fn term(&mut self, text: &str, offset: usize) -> Result<Located, Diagnostic> {
        let _ = (text, &mut self.next_anonymous);
        Err(Diagnostic::error("E0001", "the Prolog reader is not built yet", self.file.clone(), offset..offset))
    }

    /// Reads a comma-separated list of terms (priority 999 each): action and module arguments.
    pub fn term_list(&mut self, text: &str, offset: usize) -> Result<Vec<Located>, Diagnostic> {
        self.term(text, offset).map(|t| vec![t])
    }

    /// Reads `.`-terminated clauses: `knowledge`, `beliefs`, `goals` blocks and `.pl` files.
    /// Recovers after a syntax error at the next end token, so every error is reported.
    pub fn clauses(&mut self, text: &str, offset: usize) -> (Vec<Located>, Vec<Diagnostic>) {
        match self.term(text, offset) {
            Ok(t) => (vec![t], vec![]),
            Err(d) => (vec![], vec![d]),
        }
    }
}
