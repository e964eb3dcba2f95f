//! The parser's semantic actions: turn token spans into AST nodes, read KR spans into terms with
//! one `prolog::Reader` per file, and collect diagnostics (duplicate sections, legacy send forms,
//! unknown options, ...).

use super::errors::syntax_error;
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::*;
use crate::syntax::lexer::{kr, Tok};
use crate::syntax::prolog::Reader;
use crate::term::{Sym, Term};
use lalrpop_util::ErrorRecovery;
use std::cell::Cell;
use std::rc::Rc;

/// A top-level item of a `.goal` file (short-lived: moved into the program at once).
#[allow(clippy::large_enum_variant)]
pub enum TopItem {
    Module(Module),
    Import(Import),
    Error,
}

/// A section of a module, as parsed.
pub enum SectionItem {
    Knowledge(Vec<Located>, Vec<Import>, Span),
    Beliefs(Vec<Located>, Span),
    Goals(Vec<Located>, Span),
    Program(ProgramSection),
    ActionSpecs(Vec<ActionSpec>, Span),
    Import(Import),
    Error,
}

/// The built-in actions that take KR update content.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UpdateKw {
    Adopt,
    Drop,
    Insert,
    Delete,
    Send,
    SendOnce,
}

/// State shared by the semantic actions while one file is parsed.
pub struct Builder<'s> {
    pub src: &'s str,
    pub file: String,
    reader: Reader,
    pub diagnostics: Vec<Diagnostic>,
    /// Shared with the lexer: set when there are too many errors to go on.
    pub give_up: Rc<Cell<bool>>,
}

/// True when `text` holds only whitespace and comments.
pub fn only_comments(text: &str) -> bool {
    let mut t = text;
    loop {
        t = t.trim_start();
        if t.is_empty() {
            return true;
        }
        if t.starts_with('%') {
            t = t.find('\n').map_or("", |i| &t[i..]);
        } else if let Some(rest) = t.strip_prefix("/*") {
            match rest.find("*/") {
                Some(i) => t = &rest[i + 2..],
                None => return true,
            }
        } else {
            return false;
        }
    }
}

fn placeholder(span: Span) -> Located {
    Located {
        term: Term::atom("true"),
        spans: TermSpans { span, args: vec![] },
    }
}

impl<'s> Builder<'s> {
    /// A builder for `src`, the text of `file`.
    pub fn new(src: &'s str, file: &str) -> Builder<'s> {
        Builder {
            src,
            file: file.to_string(),
            reader: Reader::goal(file),
            diagnostics: Vec::new(),
            give_up: Rc::new(Cell::new(false)),
        }
    }

    /// The warnings of the KR reader (GOAL leniencies it accepted), moved to the diagnostics.
    pub fn take_reader_warnings(&mut self) {
        let w = std::mem::take(&mut self.reader.warnings);
        self.diagnostics.extend(w);
    }

    fn text(&self, span: &Span) -> &'s str {
        self.src.get(span.clone()).unwrap_or("")
    }

    pub(super) fn error(
        &mut self,
        code: &str,
        msg: impl Into<String>,
        span: Span,
    ) -> &mut Diagnostic {
        self.diagnostics
            .push(Diagnostic::error(code, msg, self.file.clone(), span));
        self.diagnostics.last_mut().expect("just pushed")
    }

    pub(super) fn warning(
        &mut self,
        code: &str,
        msg: impl Into<String>,
        span: Span,
    ) -> &mut Diagnostic {
        self.diagnostics
            .push(Diagnostic::warning(code, msg, self.file.clone(), span));
        self.diagnostics.last_mut().expect("just pushed")
    }

    /// Records a syntax error the parser recovered from.
    pub fn recover(&mut self, e: ErrorRecovery<usize, Tok, Diagnostic>) {
        // Past the cap, later errors are mostly consequences of earlier ones.
        if self.diagnostics.len() < super::MAX_DIAGNOSTICS {
            let d = syntax_error(e.error, self.src, &self.file);
            self.diagnostics.push(d);
        } else {
            self.give_up.set(true);
        }
    }

    /// The name written at `span`.
    pub fn ident(&self, span: Span) -> Ident {
        Ident {
            name: Sym::intern(self.text(&span)),
            span,
        }
    }

    /// One term (KR content of `bel(...)`, `insert(...)`, `pre{...}`, ...) at `span`.
    pub fn term(&mut self, span: Span) -> Located {
        let text = self.text(&span);
        if only_comments(text) {
            self.error(
                "E0030",
                "empty KR content: a term is expected here",
                span.clone(),
            );
            return placeholder(span);
        }
        match self.reader.term(text, span.start) {
            Ok(t) => t,
            Err(d) => {
                self.diagnostics.push(d);
                placeholder(span)
            }
        }
    }

    /// A comma-separated list of terms (arguments) at `span`.
    pub fn term_list(&mut self, span: Span) -> Vec<Located> {
        let text = self.text(&span);
        if only_comments(text) {
            self.error(
                "E0030",
                "empty argument list",
                span.start.saturating_sub(1)..span.end + 1,
            )
            .hint = Some("leave out the parentheses for a name without arguments".into());
            return Vec::new();
        }
        match self.reader.term_list(text, span.start) {
            Ok(ts) => ts,
            Err(d) => {
                self.diagnostics.push(d);
                Vec::new()
            }
        }
    }

    /// `.`-terminated clauses at `span`.
    pub fn clauses(&mut self, span: Span) -> Vec<Located> {
        let text = self.text(&span);
        if only_comments(text) {
            return Vec::new();
        }
        let (clauses, diags) = self.reader.clauses(text, span.start);
        self.diagnostics.extend(diags);
        clauses
    }

    /// A `knowledge{...}` block: its clauses and the legacy `#import "x".` lines inside it.
    pub fn knowledge(&mut self, inner: Span, span: Span) -> SectionItem {
        let found = kr::legacy_imports(self.src, inner.start, inner.end);
        if found.is_empty() {
            return SectionItem::Knowledge(self.clauses(inner), Vec::new(), span);
        }
        // Blank the directives out (same length, so spans stay file-absolute).
        let mut text = self.text(&inner).to_string();
        let mut imports = Vec::new();
        for (start, end, ps, pe) in found {
            text.replace_range(
                start - inner.start..end - inner.start,
                &" ".repeat(end - start),
            );
            imports.push(self.import(ImportKind::Prolog, ps - 1..pe + 1, start..end));
        }
        let (clauses, diags) = if only_comments(&text) {
            (Vec::new(), Vec::new())
        } else {
            self.reader.clauses(&text, inner.start)
        };
        self.diagnostics.extend(diags);
        SectionItem::Knowledge(clauses, imports, span)
    }

    /// `#import "path".` with the string token at `string` (quotes included).
    pub fn import(&mut self, expected: ImportKind, string: Span, span: Span) -> Import {
        let quoted = self.text(&string);
        let path = quoted
            .get(1..quoted.len().saturating_sub(1))
            .unwrap_or("")
            .replace("\\\"", "\"");
        // A path without an extension means the kind expected here (`.mod2g` at the top level,
        // a Prolog file in a module); the file is found by trying the known extensions.
        let has_extension = std::path::Path::new(&path).extension().is_some();
        let kind = if !has_extension {
            expected
        } else if path.ends_with(".mod2g") {
            ImportKind::Module
        } else {
            ImportKind::Prolog
        };
        // A Prolog file imported at the top level joins the knowledge, like one imported in a
        // module; a module file can only be imported at the top level.
        if kind == ImportKind::Module && expected == ImportKind::Prolog {
            self.error(
                "E0031",
                format!("a module file ({quoted}) can only be imported at the top level"),
                span.clone(),
            )
            .hint = Some("move this `#import` out of the module".into());
        }
        Import { kind, path, span }
    }

    /// A top-level `#import`.
    pub fn import_item(&mut self, expected: ImportKind, string: Span, span: Span) -> TopItem {
        TopItem::Import(self.import(expected, string, span))
    }

    /// `program[order=...]`.
    pub fn order(&mut self, key: Ident, value: Ident) -> Option<Spanned<Order>> {
        if key.name.name() != "order" {
            self.error(
                "E0020",
                format!("unknown program option `{}`", key.name.name()),
                key.span,
            )
            .hint = Some("the only program option is `order=...`".into());
            return None;
        }
        let order = match value.name.name() {
            "linear" => Order::Linear,
            "linearall" => Order::LinearAll,
            "random" => Order::Random,
            "randomall" => Order::RandomAll,
            "adaptive" => Order::Adaptive,
            other => {
                self.error("E0020", format!("unknown rule order `{other}`"), value.span)
                    .hint =
                    Some("use one of linear, linearall, random, randomall, adaptive".into());
                return None;
            }
        };
        Some(Spanned {
            value: order,
            span: key.span.start..value.span.end,
        })
    }

    /// A nested rule block.
    pub fn block(&mut self, rules: Vec<Rule>, span: Span) -> RuleBody {
        if rules.is_empty() {
            self.warning("W0006", "empty rule block: it does nothing", span);
        }
        RuleBody::Block(rules)
    }

    /// A mental literal, possibly negated.
    pub fn mental(
        &mut self,
        negated: bool,
        (selector, op, query): (Option<Selector>, MentalOp, Located),
        span: Span,
    ) -> Literal {
        Literal {
            kind: LiteralKind::Mental {
                negated,
                selector: selector.unwrap_or_else(Selector::default_this),
                op,
                query,
            },
            span,
        }
    }

    /// A `( ... ).` selector; `span` covers the parentheses.
    pub fn selector_terms(&mut self, span: Span) -> Selector {
        let agents = self.term_list(span.start + 1..span.end - 1);
        Selector {
            kind: SelectorKind::Agents(agents),
            span: Some(span),
        }
    }

    /// A bare agent-name selector `bob.`.
    pub fn selector_name(&mut self, span: Span) -> Selector {
        let t = self.term(span.clone());
        Selector {
            kind: SelectorKind::Agents(vec![t]),
            span: Some(span),
        }
    }

    /// `log(...)`: a term, or the raw text as a string when it is not a term.
    pub fn log_term(&mut self, span: Span) -> Located {
        let text = self.text(&span);
        match self.reader.term(text, span.start) {
            Ok(t) => t,
            Err(_) => Located {
                term: Term::string(text.trim()),
                spans: TermSpans { span, args: vec![] },
            },
        }
    }

    /// The variable of a `listall` rule.
    pub fn listall_var(&mut self, span: Span) -> Located {
        let before = self.diagnostics.len();
        let t = self.term(span.clone());
        if self.diagnostics.len() == before && !t.term.is_var() {
            self.error(
                "E0022",
                format!("`listall` needs a variable, found `{}`", self.text(&span)),
                span,
            )
            .hint = Some("variables start with an upper-case letter or `_`".into());
        }
        t
    }

    /// A `pre{...}` / `post{...}` block; `inner` is the text between the braces.
    pub fn spec_condition(&mut self, inner: Span, span: Span) -> SpecCondition {
        if only_comments(self.text(&inner)) {
            return SpecCondition {
                term: placeholder(inner),
                empty: true,
                span,
            };
        }
        SpecCondition {
            term: self.term(inner),
            empty: false,
            span,
        }
    }
}
