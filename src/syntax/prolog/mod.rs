//! The Prolog reader: Prolog text (KR content of `.goal` files, `.pl` files, queries) to terms
//! with byte spans, using GOAL's fixed operator table.
//!
//! Reading happens in three steps: `lexer` (logos) makes tokens, the lalrpop grammar
//! `grammar/prolog.lalrpop` finds the structure (arguments, lists, brackets), and `resolve`
//! applies operator priorities to each flat operator sequence.

mod item;
pub mod lexer;
mod resolve;

use crate::diag::{Diagnostic, Span};
use crate::term::Term;
use lalrpop_util::{lalrpop_mod, ParseError};
use lexer::{LexError, Tok};

lalrpop_mod!(
    #[allow(clippy::all, unused_parens, dead_code)]
    grammar,
    "/prolog.rs"
);

/// Diagnostic code of Prolog syntax errors.
pub const SYNTAX_ERROR: &str = "E0010";

/// A clause list stops being read after this many syntax errors: past that point the text is
/// almost certainly not Prolog, and reporting more only costs time.
pub const MAX_CLAUSE_ERRORS: usize = 100;

/// Byte spans of a term and, for compound terms, of each argument (list cells: head and tail).
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct TermSpans {
    pub span: Span,
    pub args: Vec<TermSpans>,
}

impl Drop for TermSpans {
    fn drop(&mut self) {
        // Spans of a long list nest as deep as the list is long: drop them with a heap stack.
        if self.args.iter().all(|a| a.args.is_empty()) {
            return;
        }
        let mut stack = std::mem::take(&mut self.args);
        while let Some(mut s) = stack.pop() {
            stack.append(&mut s.args);
        }
    }
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
    /// Read GOAL's leniencies (see [`Reader::goal`]).
    goal_compat: bool,
    /// Warnings about leniencies used so far (only in GOAL-compatible mode).
    pub warnings: Vec<Diagnostic>,
}

/// Code of the warning for `name (args)`: a space between a name and its `(`.
pub const SPACED_FUNCTOR: &str = "W0010";
/// Code of the warning for text after a complete term that GOAL ignored.
pub const TRAILING_TEXT: &str = "W0011";

type Spanned = (usize, Tok, usize);

impl Reader {
    /// A reader for text that comes from `file` (used in diagnostics).
    pub fn new(file: impl Into<String>) -> Reader {
        Reader {
            file: file.into(),
            next_anonymous: 0,
            goal_compat: false,
            warnings: Vec::new(),
        }
    }

    /// A reader for KR text of GOAL agent files, which accepts what GOAL's own reader accepted,
    /// each time with a warning in [`Reader::warnings`]: `name (args)` with blanks before the
    /// `(`, and text after a complete single term (`pre { p(X)) }`), which GOAL ignored.
    pub fn goal(file: impl Into<String>) -> Reader {
        Reader {
            goal_compat: true,
            ..Reader::new(file)
        }
    }

    /// Reads one term (priority up to 1200, no final `.`) from `text`, which starts at byte
    /// `offset` of the file: the content of `pre{}`, `bel(...)`, a query, ...
    pub fn term(&mut self, text: &str, offset: usize) -> Result<Located, Diagnostic> {
        let tokens = self.tokens(text, offset)?;
        if tokens.is_empty() {
            return Err(self.empty(offset, text.len()));
        }
        let end = offset + text.len();
        match grammar::TermParser::new().parse(tokens.clone()) {
            Ok(t) => Ok(t),
            Err(e) => match self.term_before_trailing(&tokens, &e) {
                Some(t) => Ok(t),
                None => Err(self.parse_error(e, end)),
            },
        }
    }

    /// In GOAL-compatible mode, when a single term is followed by an unmatched closing bracket
    /// (GOAL's reader stopped after the term and ignored the rest): the term, with a warning
    /// pointing at the ignored text.
    fn term_before_trailing(
        &mut self,
        tokens: &[Spanned],
        e: &ParseError<usize, Tok, item::ItemError>,
    ) -> Option<Located> {
        let at = match e {
            ParseError::UnrecognizedToken { token, .. } | ParseError::ExtraToken { token } => {
                token.0
            }
            _ => return None,
        };
        let cut = tokens.iter().position(|(l, _, _)| *l == at)?;
        // Only an unmatched closing bracket starts ignored text (`p(X))`): other tokens after
        // a term are more likely a missing operator, which the syntax error explains better.
        let closing = matches!(tokens[cut].1, Tok::Close | Tok::RBracket | Tok::RBrace);
        if !self.goal_compat || cut == 0 || !closing {
            return None;
        }
        let t = grammar::TermParser::new()
            .parse(tokens[..cut].to_vec())
            .ok()?;
        let ignored = at..tokens.last().map_or(at, |(_, _, r)| *r);
        self.warnings.push(
            Diagnostic::warning(
                TRAILING_TEXT,
                "text after the end of the term is ignored",
                self.file.clone(),
                ignored,
            )
            .with_hint(
                "GOAL ignored this text without a word; standard Prolog rejects it: remove it",
            ),
        );
        Some(t)
    }

    /// Reads a comma-separated list of terms (priority 999 each): action and module arguments.
    pub fn term_list(&mut self, text: &str, offset: usize) -> Result<Vec<Located>, Diagnostic> {
        let tokens = self.tokens(text, offset)?;
        if tokens.is_empty() {
            return Err(self.empty(offset, text.len()));
        }
        grammar::ArgsParser::new()
            .parse(tokens)
            .map_err(|e| self.parse_error(e, offset + text.len()))
    }

    /// Reads `.`-terminated clauses: `knowledge`, `beliefs`, `goals` blocks and `.pl` files.
    /// Recovers after a syntax error at the next end token, so every error is reported.
    pub fn clauses(&mut self, text: &str, offset: usize) -> (Vec<Located>, Vec<Diagnostic>) {
        let tokens = match self.tokens(text, offset) {
            Ok(t) => t,
            Err(d) => return (Vec::new(), vec![d]),
        };
        let mut clauses = Vec::new();
        let mut errors = Vec::new();
        let mut chunk: Vec<Spanned> = Vec::new();
        for (l, tok, r) in tokens {
            if errors.len() >= MAX_CLAUSE_ERRORS {
                errors.push(
                    Diagnostic::error(
                        SYNTAX_ERROR,
                        format!(
                            "too many syntax errors; stopped reading after {MAX_CLAUSE_ERRORS}"
                        ),
                        self.file.clone(),
                        l..r,
                    )
                    .with_hint("fix the errors above first"),
                );
                return (clauses, errors);
            }
            if tok != Tok::End {
                chunk.push((l, tok, r));
                continue;
            }
            if chunk.is_empty() {
                errors.push(
                    Diagnostic::error(
                        SYNTAX_ERROR,
                        "a `.` with no clause before it",
                        self.file.clone(),
                        l..r,
                    )
                    .with_hint("remove the extra `.`"),
                );
                continue;
            }
            let end = l;
            match grammar::TermParser::new().parse(std::mem::take(&mut chunk)) {
                Ok(t) => clauses.push(t),
                Err(e) => errors.push(self.parse_error(e, end)),
            }
        }
        if let Some((_, _, last_end)) = chunk.last() {
            let last_end = *last_end;
            errors.push(
                Diagnostic::error(
                    SYNTAX_ERROR,
                    "missing `.` at the end of the clause",
                    self.file.clone(),
                    last_end..last_end,
                )
                .with_hint("end every clause with a `.` followed by a space or a new line"),
            );
        }
        (clauses, errors)
    }

    fn tokens(&mut self, text: &str, offset: usize) -> Result<Vec<Spanned>, Diagnostic> {
        let mut spaced = Vec::new();
        let list = self.goal_compat.then_some(&mut spaced);
        let tokens = lexer::tokenize_with(text, offset, &mut self.next_anonymous, list).map_err(
            |e: LexError| {
                let d = Diagnostic::error(SYNTAX_ERROR, e.message, self.file.clone(), e.span);
                match e.hint {
                    Some(h) => d.with_hint(h),
                    None => d,
                }
            },
        )?;
        for span in spaced {
            let name = text[span.start - offset..span.end - offset - 1].trim_end();
            self.warnings.push(
                Diagnostic::warning(
                    SPACED_FUNCTOR,
                    format!("a space between `{name}` and `(`: read as `{name}(...)`, as GOAL did"),
                    self.file.clone(),
                    span,
                )
                .with_hint(format!(
                    "standard Prolog (SWI-Prolog) rejects `{name} (` as a syntax error; write `{name}(` without the space"
                )),
            );
        }
        Ok(tokens)
    }

    fn empty(&self, offset: usize, len: usize) -> Diagnostic {
        Diagnostic::error(
            SYNTAX_ERROR,
            "expected a term, found nothing",
            self.file.clone(),
            offset..offset + len,
        )
        .with_hint("write a Prolog term here")
    }

    fn parse_error(
        &self,
        e: ParseError<usize, Tok, item::ItemError>,
        end_of_text: usize,
    ) -> Diagnostic {
        let file = self.file.clone();
        match e {
            ParseError::User { error } => {
                let d = Diagnostic::error(SYNTAX_ERROR, error.message, file, error.span);
                match error.hint {
                    Some(h) => d.with_hint(h),
                    None => d,
                }
            }
            ParseError::InvalidToken { location } => {
                Diagnostic::error(SYNTAX_ERROR, "invalid token", file, location..location + 1)
            }
            ParseError::UnrecognizedEof { location, expected } => {
                let at = location.min(end_of_text);
                Diagnostic::error(SYNTAX_ERROR, "unexpected end of the term", file, at..at)
                    .with_hint(expected_hint(&expected))
            }
            ParseError::UnrecognizedToken {
                token: (l, tok, r),
                expected,
            } => Diagnostic::error(
                SYNTAX_ERROR,
                format!("unexpected {}", describe(&tok)),
                file,
                l..r,
            )
            .with_hint(expected_hint(&expected)),
            ParseError::ExtraToken { token: (l, tok, r) } => Diagnostic::error(
                SYNTAX_ERROR,
                format!("unexpected {}", describe(&tok)),
                file,
                l..r,
            ),
        }
    }
}

/// A token as a user would name it.
fn describe(tok: &Tok) -> String {
    match tok {
        Tok::Name(s) | Tok::Functor(s) => format!("`{}`", s.name()),
        Tok::Var(v) => format!("variable `{}`", v.name()),
        Tok::Int(i) => format!("number `{i}`"),
        Tok::BigInt(i) => format!("number `{i}`"),
        Tok::Float(f) => format!("number `{f}`"),
        Tok::Str(_) | Tok::BackQuoted(_) => "string".into(),
        Tok::Open => "`(`".into(),
        Tok::Close => "`)`".into(),
        Tok::LBracket => "`[`".into(),
        Tok::RBracket => "`]`".into(),
        Tok::LBrace => "`{`".into(),
        Tok::RBrace => "`}`".into(),
        Tok::Comma => "`,`".into(),
        Tok::Bar => "`|`".into(),
        Tok::End => "end of clause `.`".into(),
    }
}

fn expected_hint(expected: &[String]) -> String {
    let words: Vec<&str> = expected
        .iter()
        .map(|e| match e.trim_matches('"') {
            "name" | "functor" | "var" | "int" | "float" | "string" | "backquoted" | "(" | "["
            | "{" => "a term",
            ")" => "`)`",
            "]" => "`]`",
            "}" => "`}`",
            "," => "`,`",
            "|" => "`|`",
            "." => "`.`",
            _ => "a term",
        })
        .fold(Vec::new(), |mut acc, w| {
            if !acc.contains(&w) {
                acc.push(w)
            }
            acc
        });
    match words.as_slice() {
        [] => "check the syntax here".into(),
        [one] => format!("expected {one} here"),
        many => format!("expected one of: {}", many.join(", ")),
    }
}

#[cfg(test)]
mod tests;
