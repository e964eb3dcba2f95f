//! The pieces the grammar hands to operator resolution, and how located terms are built.

use super::{Located, TermSpans};
use crate::diag::Span;
use crate::syntax::prolog::lexer::Tok;
use crate::term::{well_known as wk, Sym, Term};
use lalrpop_util::ParseError;

/// One item of a flat operator sequence.
#[derive(Clone, Debug)]
pub enum Item {
    /// A primary term: number, string, variable, list, curly term or bracketed term.
    Operand(Located),
    /// A name: an atom, or an operator if the table says so.
    Name(Sym, Span),
    /// Functional notation `f(args)`: functor, arguments, whole span.
    Call(Sym, Vec<Located>, Span),
    /// A comma at priority 1000 (only inside brackets or at the top).
    Comma(Span),
    /// A bar at priority 1100 (read as `;`).
    Bar(Span),
}

impl Item {
    /// The byte span of the item.
    pub fn span(&self) -> Span {
        match self {
            Item::Operand(o) => o.spans.span.clone(),
            Item::Name(_, s) | Item::Comma(s) | Item::Bar(s) => s.clone(),
            Item::Call(_, _, s) => s.clone(),
        }
    }
}

/// A syntax error found while building a term.
#[derive(Clone, Debug, PartialEq)]
pub struct ItemError {
    pub message: String,
    pub hint: Option<String>,
    pub span: Span,
}

impl ItemError {
    /// An error at `span`.
    pub fn new(message: impl Into<String>, span: Span) -> ItemError {
        ItemError {
            message: message.into(),
            hint: None,
            span,
        }
    }

    /// Adds a hint.
    pub fn hint(mut self, hint: impl Into<String>) -> ItemError {
        self.hint = Some(hint.into());
        self
    }
}

impl Located {
    /// A term with no sub-term spans.
    pub fn leaf(term: Term, span: Span) -> Located {
        Located {
            term,
            spans: TermSpans {
                span,
                args: Vec::new(),
            },
        }
    }

    /// `name(args)` spanning `span`.
    pub fn compound(name: Sym, args: Vec<Located>, span: Span) -> Located {
        let (terms, spans): (Vec<Term>, Vec<TermSpans>) =
            args.into_iter().map(|a| (a.term, a.spans)).unzip();
        Located {
            term: Term::compound(name, terms),
            spans: TermSpans { span, args: spans },
        }
    }

    pub(crate) fn int(i: i64, span: Span) -> Located {
        Located::leaf(Term::Int(i), span)
    }

    pub(crate) fn float(f: f64, span: Span) -> Located {
        Located::leaf(Term::from(f), span)
    }

    pub(crate) fn string(s: &str, span: Span) -> Located {
        Located::leaf(Term::string(s), span)
    }

    /// A back-quoted string: the list of its character codes.
    pub(crate) fn codes(s: &str, span: Span) -> Located {
        let items = s
            .chars()
            .map(|c| Located::leaf(Term::Int(c as i64), span.clone()))
            .collect();
        Located::list(items, None, span)
    }

    pub(crate) fn var(v: Sym, span: Span) -> Located {
        Located::leaf(Term::Var(v), span)
    }

    pub(crate) fn nil(span: Span) -> Located {
        Located::leaf(Term::nil(), span)
    }

    pub(crate) fn curly_atom(span: Span) -> Located {
        Located::leaf(Term::Atom(wk::CURLY), span)
    }

    pub(crate) fn curly(inner: Located, span: Span) -> Located {
        Located::compound(wk::CURLY, vec![inner], span)
    }

    /// A bracketed term keeps its own spans; brackets only matter for operator priorities.
    pub(crate) fn bracketed(self, _span: Span) -> Located {
        self
    }

    /// A list literal; each cell spans from its element to the closing bracket.
    pub(crate) fn list(items: Vec<Located>, tail: Option<Located>, span: Span) -> Located {
        let mut acc = tail.unwrap_or_else(|| Located::nil(span.end.saturating_sub(1)..span.end));
        for item in items.into_iter().rev() {
            let cell_span = item.spans.span.start..span.end;
            acc = Located::compound(wk::DOT, vec![item, acc], cell_span);
        }
        acc.spans.span = span.start..span.end;
        acc
    }

    /// Resolves a flat item sequence into a term of at most `max` priority (grammar action).
    pub(crate) fn resolve(
        items: Vec<Item>,
        max: u16,
        span: Span,
    ) -> Result<Located, ParseError<usize, Tok, ItemError>> {
        super::resolve::resolve(items, max, span).map_err(|error| ParseError::User { error })
    }
}
