//! The `.goal` lexer: `logos` recognises GOAL-level tokens; this wrapper cuts KR (Prolog) content
//! out as single tokens, skips comments, and turns bad input into diagnostics. It yields
//! `(start, Tok, end)` triples for lalrpop's external-lexer mode.

pub mod kr;
mod token;

pub use token::Tok;

use crate::diag::Diagnostic;
use kr::ScanError;
use logos::Logos;
use std::cell::Cell;
use std::rc::Rc;

/// Deepest `{ }` nesting of GOAL-level blocks accepted (modules, programs, nested rule blocks).
pub const MAX_BLOCK_DEPTH: usize = 100;

/// After this many unexpected characters the rest of the file is skipped.
pub const MAX_LEX_ERRORS: usize = 50;

/// The lexer error type seen by the parser; the lexer reports problems as diagnostics instead
/// and never yields it.
pub type LexError = Diagnostic;

/// What the previous token lets the next `(` / `{` / word be.
#[derive(Clone, Copy, PartialEq, Eq)]
enum After {
    Plain,
    /// A mental operator, built-in action or name: `(` starts KR arguments.
    KrParens,
    /// `knowledge`, `beliefs`, `goals`, `pre`, `post`: `{` starts a KR block.
    KrBraces,
    /// `not`: the next `(` is an ordinary bracket.
    Not,
    /// `listall`: a variable followed by `<-` may come.
    Listall,
}

/// The `.goal` token stream of one file.
pub struct Lexer<'s> {
    src: &'s str,
    file: String,
    /// Byte position where the next token is searched.
    pos: usize,
    after: After,
    depth: usize,
    /// Problems found so far (unexpected characters, unterminated quotes, ...).
    pub diagnostics: Vec<Diagnostic>,
    /// True once input had to be abandoned (the parser's end-of-file error is then noise).
    pub stopped_early: bool,
    /// Set by the parser's builder when it has seen too many errors: the lexer then ends the
    /// token stream so that a hopeless file costs no more time.
    pub give_up: Rc<Cell<bool>>,
}

impl<'s> Lexer<'s> {
    /// A lexer over the whole text of `file`.
    pub fn new(src: &'s str, file: &str) -> Lexer<'s> {
        Lexer {
            src,
            file: file.to_string(),
            pos: 0,
            after: After::Plain,
            depth: 0,
            diagnostics: Vec::new(),
            stopped_early: false,
            give_up: Rc::new(Cell::new(false)),
        }
    }

    fn stop(&mut self, d: Diagnostic) -> Option<(usize, Tok, usize)> {
        self.diagnostics.push(d);
        self.stopped_early = true;
        self.pos = self.src.len();
        None
    }

    fn scan_error(&mut self, e: ScanError) -> Option<(usize, Tok, usize)> {
        let d = e.diagnostic(self.src, &self.file);
        self.stop(d)
    }

    /// Skips whitespace and comments from `self.pos`.
    fn skip_trivia(&mut self) -> Result<(), ScanError> {
        self.pos = kr::skip_trivia(self.src, self.pos, self.src.len())?;
        Ok(())
    }

    /// KR content in brackets starting at `self.pos`: the whole bracketed span.
    fn kr_span(&mut self, open: u8, close: u8, tok: Tok) -> Option<(usize, Tok, usize)> {
        let start = self.pos;
        match kr::matching_close(self.src, start, open, close) {
            Ok(end) => {
                self.pos = end + 1;
                Some((start, tok, end + 1))
            }
            Err(e) => self.scan_error(e),
        }
    }

    /// After `listall`: `Var <-` gives a ListallVar token.
    fn listall_var(&mut self) -> Option<(usize, Tok, usize)> {
        let b = self.src.as_bytes();
        let start = self.pos;
        let mut i = start;
        while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_' || b[i] == b'?') {
            i += 1;
        }
        if i == start {
            return None;
        }
        let mut j = i;
        while j < b.len() && b[j].is_ascii_whitespace() {
            j += 1;
        }
        if self.src[j..].starts_with("<-") {
            self.pos = i;
            Some((start, Tok::ListallVar, i))
        } else {
            None
        }
    }

    fn next_token(&mut self) -> Option<(usize, Tok, usize)> {
        loop {
            if let Err(e) = self.skip_trivia() {
                return self.scan_error(e);
            }
            let b = self.src.as_bytes();
            let c = *b.get(self.pos)?;
            let after = std::mem::replace(&mut self.after, After::Plain);
            match (c, after) {
                (b'{', After::KrBraces) => return self.kr_span(b'{', b'}', Tok::KrBraces),
                (b'(', After::KrParens) => return self.kr_span(b'(', b')', Tok::KrParens),
                (b'(', After::Not) => {}
                (b'(', _) => return self.kr_span(b'(', b')', Tok::SelParens),
                (_, After::Listall) => {
                    if let Some(t) = self.listall_var() {
                        return Some(t);
                    }
                }
                _ => {}
            }
            // A logos token starting at self.pos.
            let rest = &self.src[self.pos..];
            // A fresh logos lexer on the rest: KR spans and comments are skipped by hand above.
            let mut inner = Tok::lexer(rest);
            let start = self.pos;
            let tok = inner.next()?;
            let span = inner.span();
            let end = start + span.end;
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

    fn classify(&mut self, start: usize, t: Tok, end: usize) -> Option<(usize, Tok, usize)> {
        let b = self.src.as_bytes();
        if t == Tok::Ident
            && b.get(end) == Some(&b'.')
            && b.get(end + 1).is_some_and(|c| c.is_ascii_alphabetic())
        {
            return Some((start, Tok::SelName, end));
        }
        self.after = if t.takes_kr_parens() {
            After::KrParens
        } else if t.takes_kr_braces() {
            After::KrBraces
        } else if t == Tok::Not {
            After::Not
        } else if t == Tok::Listall {
            After::Listall
        } else {
            After::Plain
        };
        match t {
            Tok::LBrace => {
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
            Tok::RBrace => self.depth = self.depth.saturating_sub(1),
            _ => {}
        }
        Some((start, t, end))
    }
}

impl Iterator for Lexer<'_> {
    type Item = Result<(usize, Tok, usize), LexError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.give_up.get() {
            self.stopped_early = true;
            return None;
        }
        self.next_token().map(Ok)
    }
}

/// All tokens of `src` with the lexer's diagnostics (for tests and tools).
pub fn tokens(src: &str, file: &str) -> (Vec<(usize, Tok, usize)>, Vec<Diagnostic>) {
    let mut lx = Lexer::new(src, file);
    let toks: Vec<_> = lx.by_ref().filter_map(Result::ok).collect();
    (toks, lx.diagnostics)
}
