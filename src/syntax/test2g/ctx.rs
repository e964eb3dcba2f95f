//! The parser context of the `.test2g` grammar: the source text, the Prolog reader for KR
//! content, and the diagnostics and recovered errors collected while parsing.

use super::ast::{CondItem, DoTest, TestCondition};
use super::lexer::T2;
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::{
    Action, ActionKind, Ident, Literal, Mood, Selector, SelectorKind, Spanned,
};
use crate::syntax::lexer::kr::top_level_commas;
use crate::syntax::prolog::{Located, Reader, TermSpans};
use crate::term::{Sym, Term};
use lalrpop_util::ErrorRecovery;

/// State shared by the grammar actions.
pub struct Ctx<'s> {
    pub src: &'s str,
    pub file: String,
    pub reader: Reader,
    pub diags: Vec<Diagnostic>,
    pub recovered: Vec<ErrorRecovery<usize, T2, Diagnostic>>,
}

/// The built-in updates that take KR content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Update {
    Adopt,
    Drop,
    Insert,
    Delete,
}

impl<'s> Ctx<'s> {
    /// A context for `src` read from `file`.
    pub fn new(src: &'s str, file: &str) -> Ctx<'s> {
        Ctx {
            src,
            file: file.to_string(),
            // GOAL's leniencies in KR text, with warnings, as in `.goal` files.
            reader: Reader::goal(file),
            diags: Vec::new(),
            recovered: Vec::new(),
        }
    }

    fn placeholder(span: Span) -> Located {
        Located {
            term: Term::atom("true"),
            spans: TermSpans {
                span,
                args: Vec::new(),
            },
        }
    }

    /// The term inside the brackets at `l..r` (a KR parameter list of one term).
    pub fn term(&mut self, l: usize, r: usize) -> Located {
        let (a, b) = (l + 1, r.saturating_sub(1).max(l + 1));
        let text = self.src.get(a..b).unwrap_or("");
        match self.reader.term(text, a) {
            Ok(t) => t,
            Err(d) => {
                self.diags.push(d);
                Self::placeholder(a..b)
            }
        }
    }

    /// The comma-separated terms inside the brackets at `l..r`.
    pub fn terms(&mut self, l: usize, r: usize) -> Vec<Located> {
        let (a, b) = (l + 1, r.saturating_sub(1).max(l + 1));
        let text = self.src.get(a..b).unwrap_or("");
        match self.reader.term_list(text, a) {
            Ok(t) => t,
            Err(d) => {
                self.diags.push(d);
                vec![Self::placeholder(a..b)]
            }
        }
    }

    /// The name at `l..r` read as a term (a bare agent-name selector).
    pub fn name_term(&mut self, l: usize, r: usize) -> Located {
        let text = self.src.get(l..r).unwrap_or("");
        match self.reader.term(text, l) {
            Ok(t) => t,
            Err(d) => {
                self.diags.push(d);
                Self::placeholder(l..r)
            }
        }
    }

    /// The name written at `l..r`.
    pub fn ident(&self, l: usize, r: usize) -> Ident {
        Ident {
            name: Sym::intern(self.src.get(l..r).unwrap_or("")),
            span: l..r,
        }
    }

    /// The string literal at `l..r` without quotes and escapes.
    pub fn string(&self, l: usize, r: usize) -> Spanned<String> {
        let raw = self.src.get(l..r).unwrap_or("\"\"");
        let value = if raw.len() >= 2 {
            crate::syntax::mas2g::lexer::unescape(raw)
        } else {
            String::new()
        };
        Spanned { value, span: l..r }
    }

    /// The non-negative integer at `l..r` (an error when it does not fit).
    pub fn int(&mut self, l: usize, r: usize) -> u64 {
        match self.src.get(l..r).unwrap_or("").parse::<u64>() {
            Ok(n) => n,
            Err(_) => {
                self.diags.push(
                    Diagnostic::error("E0302", "number out of range", self.file.clone(), l..r)
                        .with_hint("use a smaller number"),
                );
                0
            }
        }
    }

    /// An `adopt`/`drop`/`insert`/`delete` action with content in the brackets at `cl..cr`.
    pub fn update(
        &mut self,
        u: Update,
        sel: Option<Selector>,
        cl: usize,
        cr: usize,
        l: usize,
    ) -> Action {
        let selector = sel.unwrap_or_else(Selector::default_this);
        let content = self.term(cl, cr);
        let kind = match u {
            Update::Adopt => ActionKind::Adopt { selector, content },
            Update::Drop => ActionKind::Drop { selector, content },
            Update::Insert => ActionKind::Insert { selector, content },
            Update::Delete => ActionKind::Delete { selector, content },
        };
        Action { kind, span: l..cr }
    }

    /// A `send`/`sendonce` action: the mood marker, and the legacy `send(bob, p)` form.
    pub fn send(
        &mut self,
        once: bool,
        sel: Option<Selector>,
        cl: usize,
        cr: usize,
        l: usize,
    ) -> Action {
        let (mut a, b) = (cl + 1, cr.saturating_sub(1).max(cl + 1));
        let mut selector = sel.clone().unwrap_or_else(Selector::default_this);
        if sel.is_none() {
            if let Some(&comma) = top_level_commas(self.src, a, b).first() {
                let receiver = self.src.get(a..comma).unwrap_or("");
                match self.reader.term(receiver, a) {
                    Ok(t) => {
                        let span = t.spans.span.clone();
                        selector = Selector {
                            kind: SelectorKind::Agents(vec![t]),
                            span: Some(span),
                        };
                    }
                    Err(d) => self.diags.push(d),
                }
                a = comma + 1;
            }
        }
        let text = self.src.get(a..b).unwrap_or("");
        let skipped = text.len() - text.trim_start().len();
        let mood = match text.trim_start().chars().next() {
            Some(':') => Some(Mood::Declarative),
            Some('!') => Some(Mood::Imperative),
            Some('?') => Some(Mood::Interrogative),
            _ => None,
        };
        if mood.is_some() {
            a += skipped + 1;
        }
        let content = match self.reader.term(self.src.get(a..b).unwrap_or(""), a) {
            Ok(t) => t,
            Err(d) => {
                self.diags.push(d);
                Self::placeholder(a..b)
            }
        };
        let mood = mood.unwrap_or(Mood::Declarative);
        let kind = if once {
            ActionKind::SendOnce {
                selector,
                mood,
                content,
            }
        } else {
            ActionKind::Send {
                selector,
                mood,
                content,
            }
        };
        Action { kind, span: l..cr }
    }

    /// A test condition from its items; more than one `do(...)` test is an error.
    pub fn condition(&mut self, items: Vec<CondItem>, l: usize, r: usize) -> TestCondition {
        let mut literals: Vec<Literal> = Vec::new();
        let mut done: Option<DoTest> = None;
        for item in items {
            match item {
                CondItem::Literal(lit) => literals.push(lit),
                CondItem::Done(d) => {
                    if done.is_some() {
                        self.diags.push(
                            Diagnostic::error(
                                "E0303",
                                "a test condition may contain only one `do(...)` test",
                                self.file.clone(),
                                d.span.clone(),
                            )
                            .with_hint("split the condition into two conditions"),
                        );
                    } else {
                        done = Some(d);
                    }
                }
            }
        }
        TestCondition {
            literals,
            done,
            span: l..r,
        }
    }
}
