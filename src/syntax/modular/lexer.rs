//! The lexer of modular `.mod2g`/`.act2g` files: `logos` recognises the tokens of [`MTok`]; this
//! wrapper skips comments, cuts KR content out as single tokens (argument lists, `pre{}`/`post{}`
//! blocks and, for MARBEL (B), whole conditions), and turns bad input into diagnostics.
//!
//! The lexer reads `src[start..end]` of a larger text, so that the files of one agent can share
//! one text and every span stays unique (see `sources.rs`).

use super::token::MTok;
use crate::diag::Diagnostic;
use crate::syntax::lexer::kr::{self, ScanError, Significant};
use logos::Logos;

/// Deepest `{ }` nesting of rule blocks accepted.
pub const MAX_BLOCK_DEPTH: usize = 100;
/// After this many unexpected characters the rest of the file is skipped.
const MAX_LEX_ERRORS: usize = 50;

#[derive(Clone, Copy, PartialEq, Eq)]
enum After {
    Plain,
    KrParens,
    KrBraces,
    Not,
    Listall,
    Condition,
}

/// True for a byte of a name: ASCII letters, digits, `_`, and bytes of non-ASCII characters.
fn is_name_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_' || c >= 0x80
}

/// The token stream of one modular file.
pub struct ModLexer<'s> {
    src: &'s str,
    file: String,
    pos: usize,
    end: usize,
    after: After,
    depth: usize,
    /// (B) MARBEL: conditions are raw Prolog text up to `then`/`do`.
    raw_conditions: bool,
    /// Problems found (unexpected characters, unterminated quotes, ...).
    pub diagnostics: Vec<Diagnostic>,
    /// True once input had to be abandoned (the parser's end-of-file error is then noise).
    pub stopped_early: bool,
    /// An (A) test file: the test keywords are recognised.
    pub test_file: bool,
}

impl<'s> ModLexer<'s> {
    /// A lexer over `src[start..end]`, diagnostics naming `file`.
    pub fn new(src: &'s str, start: usize, end: usize, file: &str, raw_conditions: bool) -> Self {
        ModLexer {
            src,
            file: file.to_string(),
            pos: start,
            end: end.min(src.len()),
            after: After::Plain,
            depth: 0,
            raw_conditions,
            diagnostics: Vec::new(),
            stopped_early: false,
            test_file: false,
        }
    }

    fn stop(&mut self, d: Diagnostic) -> Option<(usize, MTok, usize)> {
        self.diagnostics.push(d);
        self.pos = self.end;
        self.stopped_early = true;
        None
    }

    fn scan_error(&mut self, e: ScanError) -> Option<(usize, MTok, usize)> {
        let d = e.diagnostic(self.src, &self.file);
        self.stop(d)
    }

    fn skip_trivia(&mut self) -> Result<(), ScanError> {
        self.pos = kr::skip_trivia(self.src, self.pos, self.end)?;
        Ok(())
    }

    fn kr_span(&mut self, open: u8, close: u8, tok: MTok) -> Option<(usize, MTok, usize)> {
        let start = self.pos;
        match kr::matching_close(&self.src[..self.end], start, open, close) {
            Ok(end) => {
                self.pos = end + 1;
                Some((start, tok, end + 1))
            }
            Err(e) => self.scan_error(e),
        }
    }

    /// After `listall`: `Var <-` gives a ListallVar token.
    fn listall_var(&mut self) -> Option<(usize, MTok, usize)> {
        let b = self.src.as_bytes();
        let start = self.pos;
        let mut i = start;
        while i < self.end && is_name_byte(b[i]) {
            i += 1;
        }
        let rest = self.src[i..self.end].trim_start();
        if i > start && rest.starts_with("<-") {
            self.pos = i;
            return Some((start, MTok::ListallVar, i));
        }
        None
    }

    /// (B) A raw condition from `self.pos` up to the word `then` or `do` at bracket depth 0.
    fn raw_condition(&mut self) -> Option<(usize, MTok, usize)> {
        let b = self.src.as_bytes();
        let start = self.pos;
        let mut walk = Significant::new(self.src, start, self.end);
        let mut depth = 0i64;
        while let Some(item) = walk.next_byte() {
            let (p, c) = match item {
                Ok(x) => x,
                Err(e) => return self.scan_error(e),
            };
            match c {
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => depth -= 1,
                _ => {}
            }
            let word_start = p == 0 || !is_name_byte(b[p - 1]);
            if depth == 0 && word_start && c.is_ascii_alphabetic() {
                let mut q = p;
                while q < self.end && is_name_byte(b[q]) {
                    q += 1;
                }
                if matches!(&self.src[p..q], "then" | "do") {
                    self.pos = p;
                    let end = start + self.src[start..p].trim_end().len();
                    return Some((start, MTok::KrCond, end));
                }
            }
        }
        self.stop(
            Diagnostic::error(
                "E0015",
                "condition without `then` or `do`",
                self.file.clone(),
                start..start,
            )
            .with_hint(
                "a condition is followed by `then` (for `if`) or `do` (for `forall`/`listall`)",
            ),
        )
    }

    fn next_token(&mut self) -> Option<(usize, MTok, usize)> {
        loop {
            if let Err(e) = self.skip_trivia() {
                return self.scan_error(e);
            }
            if self.pos >= self.end {
                return None;
            }
            let c = self.src.as_bytes()[self.pos];
            let after = std::mem::replace(&mut self.after, After::Plain);
            match (c, after) {
                (b'{', After::KrBraces) => return self.kr_span(b'{', b'}', MTok::KrBraces),
                (b'(', After::KrParens) => return self.kr_span(b'(', b')', MTok::KrParens),
                (_, After::Condition) => return self.raw_condition(),
                (b'(', After::Not) => {}
                (b'(', _) => return self.kr_span(b'(', b')', MTok::SelParens),
                (_, After::Listall) => {
                    if let Some(t) = self.listall_var() {
                        self.after = After::Plain;
                        return Some(t);
                    }
                }
                _ => {}
            }
            let rest = &self.src[self.pos..self.end];
            let mut inner = MTok::lexer(rest);
            let start = self.pos;
            let tok = inner.next()?;
            let end = start + inner.span().end;
            self.pos = end;
            match tok {
                Ok(t) => return self.classify(start, t, end),
                Err(()) => {
                    let ch = rest.chars().next().unwrap_or(' ');
                    let end = start + ch.len_utf8();
                    self.pos = end;
                    if ch == '"' || ch == '\'' {
                        return self.scan_error(ScanError::UnterminatedQuote { start, quote: ch });
                    }
                    let d = Diagnostic::error(
                        "E0009",
                        format!("unexpected character `{}`", ch.escape_debug()),
                        self.file.clone(),
                        start..end,
                    );
                    if self.diagnostics.len() >= MAX_LEX_ERRORS {
                        return self.stop(d.with_hint("too many unexpected characters: giving up"));
                    }
                    self.diagnostics.push(d);
                }
            }
        }
    }

    fn classify(&mut self, start: usize, t: MTok, end: usize) -> Option<(usize, MTok, usize)> {
        let b = self.src.as_bytes();
        let t = match MTok::test_keyword(&self.src[start..end]) {
            Some(k) if self.test_file && t == MTok::Ident => k,
            _ => t,
        };
        if t == MTok::Ident
            && b.get(end) == Some(&b'.')
            && end + 1 < self.end
            && super::mas::starts_name(b[end + 1])
        {
            return Some((start, MTok::PathName, end));
        }
        self.after = if self.raw_conditions && t.starts_condition() {
            After::Condition
        } else if t.takes_kr_parens() {
            After::KrParens
        } else if t.takes_kr_braces() {
            After::KrBraces
        } else if t == MTok::Not || t == MTok::Done {
            After::Not
        } else if t == MTok::Listall {
            After::Listall
        } else {
            After::Plain
        };
        match t {
            MTok::LBrace => {
                self.depth += 1;
                if self.depth > MAX_BLOCK_DEPTH {
                    return self.stop(Diagnostic::error(
                        "E0016",
                        format!("blocks nested more than {MAX_BLOCK_DEPTH} deep"),
                        self.file.clone(),
                        start..end,
                    ));
                }
            }
            MTok::RBrace => self.depth = self.depth.saturating_sub(1),
            _ => {}
        }
        Some((start, t, end))
    }
}

impl Iterator for ModLexer<'_> {
    type Item = Result<(usize, MTok, usize), Diagnostic>;

    fn next(&mut self) -> Option<Self::Item> {
        self.next_token().map(Ok)
    }
}
