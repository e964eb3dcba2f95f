//! The semantic actions of the modular grammar: token spans to AST nodes. Conditions and actions
//! of (A) and (B) are lowered here to the 2014 AST forms they mean:
//! `percept(p, not(q))` → `bel(percept(p), newpercept(not(q)))`, `(S).sent!(m)` →
//! `bel(received(S, imp(m)))`, a (B) plain literal `l` → `bel(l)`.

use super::ast::*;
use super::token::MTok;
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::*;
use crate::syntax::goal::build::{Builder, UpdateKw};
use crate::syntax::goal::errors::{syntax_error_in, ErrorStyle};
use crate::syntax::prolog::TermSpans;
use crate::term::{Sym, Term};
use lalrpop_util::{ErrorRecovery, ParseError};
use std::collections::BTreeSet;

/// A mental operator as written in an (A) condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Op {
    Mental(MentalOp),
    Percept,
    Sent(Mood),
}

/// A file-level item before the `module` keyword.
pub enum Item {
    Use(UseClause),
    Option(Ident, Ident, Span),
    Macro(Macro),
    Learn(Span),
}

/// The post-condition forms of an `.act2g` spec.
pub enum Post {
    Plain(SpecCondition),
    Split(Option<SpecCondition>, SpecCondition),
}

/// State shared by the semantic actions while one file is parsed.
pub struct MBuilder<'s> {
    pub inner: Builder<'s>,
    /// Macros defined so far (name/arity): a (B) literal with such a name is a macro use.
    macros: BTreeSet<(String, usize)>,
}

/// A term with the same span for every part (for terms the lowering builds).
pub fn located(term: Term, span: Span) -> Located {
    let spans = spans_like(&term, &span, 0);
    Located { term, spans }
}

fn spans_like(t: &Term, span: &Span, depth: usize) -> TermSpans {
    let args = if depth < 8 {
        t.args()
            .iter()
            .map(|a| spans_like(a, span, depth + 1))
            .collect()
    } else {
        Vec::new()
    };
    TermSpans {
        span: span.clone(),
        args,
    }
}

/// The conjuncts of a `,`-term, left to right (iterative).
pub fn conjuncts(l: &Located) -> Vec<Located> {
    let comma = Sym::intern(",");
    let mut out = Vec::new();
    let mut cur = l.clone();
    loop {
        match cur.term.functor() {
            Some((f, 2)) if f == comma => {
                let span_of = |i: usize| {
                    cur.spans.args.get(i).cloned().unwrap_or_else(|| TermSpans {
                        span: cur.spans.span.clone(),
                        args: Vec::new(),
                    })
                };
                out.push(Located {
                    term: cur.term.args()[0].clone(),
                    spans: span_of(0),
                });
                let next = Located {
                    term: cur.term.args()[1].clone(),
                    spans: span_of(1),
                };
                cur = next;
            }
            _ => {
                out.push(cur);
                return out;
            }
        }
    }
}

/// Joins terms into one conjunction (right-nested), `true` when empty.
pub fn conjunction(items: Vec<Term>) -> Term {
    let mut it = items.into_iter().rev();
    let Some(mut acc) = it.next() else {
        return Term::atom("true");
    };
    for t in it {
        acc = Term::compound(",", vec![t, acc]);
    }
    acc
}

fn unary(name: &str, t: Term) -> Term {
    Term::compound(name, vec![t])
}

impl<'s> MBuilder<'s> {
    /// A builder over `src` (spans are positions in `src`), diagnostics naming `file`.
    pub fn new(src: &'s str, file: &str) -> MBuilder<'s> {
        MBuilder {
            inner: Builder::new(src, file),
            macros: BTreeSet::new(),
        }
    }

    fn src(&self) -> &'s str {
        self.inner.src
    }

    /// Adds an error.
    pub fn error(&mut self, code: &str, msg: impl Into<String>, span: Span, hint: &str) {
        let d = Diagnostic::error(code, msg, self.inner.file.clone(), span);
        self.inner.diagnostics.push(d.with_hint(hint));
    }

    /// Adds a warning.
    pub fn warning(&mut self, code: &str, msg: impl Into<String>, span: Span, hint: &str) {
        let d = Diagnostic::warning(code, msg, self.inner.file.clone(), span);
        self.inner.diagnostics.push(d.with_hint(hint));
    }

    /// Records a syntax error the parser recovered from.
    pub fn recover(&mut self, e: ErrorRecovery<usize, MTok, Diagnostic>) {
        if self.inner.diagnostics.len() < crate::syntax::goal::MAX_DIAGNOSTICS {
            let d = syntax_error(e.error, self.src(), &self.inner.file);
            self.inner.diagnostics.push(d);
        }
    }

    /// The name at `span`.
    pub fn ident(&self, span: Span) -> Ident {
        self.inner.ident(span)
    }

    /// A quoted reference (strings joined by `+`) without its quotes.
    pub fn ref_string(&self, span: Span) -> Spanned<String> {
        Spanned {
            value: super::mas::joined_strings(&self.src()[span.clone()]),
            span,
        }
    }

    /// An unquoted reference `a.b.c` (dots are directory separators).
    pub fn ref_path(&self, span: Span) -> Spanned<String> {
        Spanned {
            value: self.src()[span.clone()].replace('.', "/"),
            span,
        }
    }

    /// `use refs [as case].`
    pub fn use_clause(
        &mut self,
        refs: Vec<Spanned<String>>,
        case: Option<Spanned<UseCase>>,
        span: Span,
    ) -> UseClause {
        UseClause { refs, case, span }
    }

    /// `define name(params) as condition.`
    pub fn macro_def(
        &mut self,
        name: Ident,
        params: Vec<Located>,
        body: Vec<Literal>,
        span: Span,
    ) -> Macro {
        self.macros
            .insert((name.name.name().to_string(), params.len()));
        Macro {
            name,
            params,
            body,
            span,
        }
    }

    /// Assembles a `.mod2g` file from its items and its module.
    pub fn mod_file(
        &mut self,
        items: Vec<Item>,
        (name, params, head): (Ident, Vec<Located>, Span),
        rules: Vec<Rule>,
        span: Span,
    ) -> (Vec<UseClause>, Module) {
        let mut uses = Vec::new();
        let mut options = ModuleOptions::default();
        let mut order: Option<Spanned<Order>> = None;
        let mut macros = Vec::new();
        for item in items {
            match item {
                Item::Use(u) => uses.push(u),
                Item::Macro(m) => macros.push(m),
                Item::Learn(s) => self.warning(
                    "W0601",
                    "adaptive learning clauses are ignored by this runtime",
                    s,
                    "remove the clause, or keep it for GOAL's learning runtime",
                ),
                Item::Option(key, value, s) => self.option(&mut options, &mut order, key, value, s),
            }
        }
        // Nested blocks inherit an explicit `order` of the file (as GOAL's validator copies it).
        let nested_order = order.as_ref().map(|o| o.value);
        let program = ProgramSection {
            order,
            nested_order,
            macros,
            rules,
            span: span.clone(),
        };
        let module = Module {
            kind: ModuleKind::User { name, params },
            options,
            knowledge: Vec::new(),
            beliefs: Vec::new(),
            goals: Vec::new(),
            program: Some(program),
            action_specs: Vec::new(),
            imports: Vec::new(),
            sections: Vec::new(),
            head_span: head,
            span,
        };
        (uses, module)
    }

    fn option(
        &mut self,
        options: &mut ModuleOptions,
        order: &mut Option<Spanned<Order>>,
        key: Ident,
        value: Ident,
        span: Span,
    ) {
        let v = value.name.name();
        let k = key.name.name();
        let dup = |b: &mut Self| {
            b.warning(
                "W0004",
                format!("duplicate option `{k}`: the first one is used"),
                span.clone(),
                "remove this option",
            )
        };
        options.written.push(ModuleOption {
            key: key.clone(),
            value: value.clone(),
            span: span.clone(),
        });
        match k {
            "exit" => {
                let e = match v {
                    "always" => ExitCondition::Always,
                    "never" => ExitCondition::Never,
                    "nogoals" => ExitCondition::NoGoals,
                    "noaction" => ExitCondition::NoAction,
                    _ => return self.bad_value(k, &value, "always, never, nogoals, noaction"),
                };
                if options.exit.is_some() {
                    return dup(self);
                }
                options.exit = Some(Spanned { value: e, span });
            }
            "focus" => {
                let f = match v {
                    "none" => Focus::None,
                    "new" => Focus::New,
                    "select" => Focus::Select,
                    "filter" => Focus::Filter,
                    _ => return self.bad_value(k, &value, "none, new, select, filter"),
                };
                if options.focus.is_some() {
                    return dup(self);
                }
                options.focus = Some(Spanned { value: f, span });
            }
            "order" => {
                // linearrandom and linearallrandom have no documented meaning of their own:
                // `linear`/`linearall` already pick a random answer of a rule (seeded).
                let o = match v {
                    "linear" | "linearrandom" => Order::Linear,
                    "linearall" | "linearallrandom" => Order::LinearAll,
                    "random" => Order::Random,
                    "randomall" => Order::RandomAll,
                    "adaptive" => Order::Adaptive,
                    _ => {
                        return self.bad_value(
                            k,
                            &value,
                            "linear, linearall, linearrandom, linearallrandom, random, randomall, adaptive",
                        )
                    }
                };
                if order.is_some() {
                    return dup(self);
                }
                *order = Some(Spanned { value: o, span });
            }
            _ => {} // `timeout` only means something in test files
        }
    }

    fn bad_value(&mut self, key: &str, value: &Ident, allowed: &str) {
        self.error(
            "E0020",
            format!("`{}` is not a value of `{key}`", value.name.name()),
            value.span.clone(),
            &format!("use one of {allowed}"),
        );
    }

    /// One term at `span`.
    pub fn term(&mut self, span: Span) -> Located {
        self.inner.term(span)
    }

    /// Terms of an argument list (inside the parentheses).
    pub fn args(&mut self, span: Span) -> Vec<Located> {
        self.inner.term_list(span.start + 1..span.end - 1)
    }

    /// `( ... ).` selector.
    pub fn selector(&mut self, span: Span) -> Selector {
        self.inner.selector_terms(span)
    }

    /// An (A) mental literal: `[not(] [sel.] op(query) [)]`.
    pub fn literal(
        &mut self,
        negated: bool,
        selector: Option<Selector>,
        op: Op,
        qspan: Span,
        span: Span,
    ) -> Literal {
        let query = self.term(qspan.start + 1..qspan.end - 1);
        let (selector, op, query) = match op {
            Op::Mental(m) => (selector.unwrap_or_else(Selector::default_this), m, query),
            Op::Percept => (
                selector.unwrap_or_else(Selector::default_this),
                MentalOp::Bel,
                percept_query(&query),
            ),
            Op::Sent(mood) => {
                let sender = match selector.map(|s| s.kind) {
                    Some(SelectorKind::Agents(mut ts)) if ts.len() == 1 => ts.pop().map(|t| t.term),
                    _ => None,
                }
                .unwrap_or_else(|| Term::var("_"));
                let content = match mood {
                    Mood::Declarative => query.term.clone(),
                    Mood::Imperative => unary("imp", query.term.clone()),
                    Mood::Interrogative => unary("int", query.term.clone()),
                };
                let t = Term::compound("received", vec![sender, content]);
                (
                    Selector::default_this(),
                    MentalOp::Bel,
                    located(t, query.spans.span.clone()),
                )
            }
        };
        Literal {
            kind: LiteralKind::Mental {
                negated,
                selector,
                op,
                query,
            },
            span,
        }
    }

    /// (B) a raw condition: Prolog literals separated by top-level commas.
    pub fn raw_condition(&mut self, span: Span) -> Vec<Literal> {
        let whole = self.term(span);
        conjuncts(&whole)
            .into_iter()
            .map(|l| self.plain_literal(l))
            .collect()
    }

    /// (B) one plain literal: `true`, a mental operator kept for compatibility, a macro use,
    /// or a Prolog literal queried on the database (`bel(l)`).
    fn plain_literal(&mut self, l: Located) -> Literal {
        let span = l.spans.span.clone();
        let (negated, inner) = match l.term.functor() {
            Some((f, 1)) if f.name() == "not" && is_mental(&l.term.args()[0]) => (true, sub(&l, 0)),
            _ => (false, l.clone()),
        };
        let mental = |op: MentalOp, q: Located| LiteralKind::Mental {
            negated,
            selector: Selector::default_this(),
            op,
            query: q,
        };
        let kind = match inner.term.functor() {
            Some((f, 0)) if f.name() == "true" && !negated => LiteralKind::True,
            Some((f, 1)) if f.name() == "bel" => mental(MentalOp::Bel, sub(&inner, 0)),
            Some((f, 1)) if f.name() == "goal" => mental(MentalOp::Goal, sub(&inner, 0)),
            Some((f, 1)) if f.name() == "percept" => {
                mental(MentalOp::Bel, percept_query(&sub(&inner, 0)))
            }
            Some((f, 2)) if f.name() == "-" && is_goal_op(&inner.term) => {
                let (op, q) = goal_op(&inner);
                mental(op, q)
            }
            Some((f, n)) if !negated && self.macros.contains(&(f.name().to_string(), n)) => {
                LiteralKind::MacroUse {
                    name: Ident {
                        name: f,
                        span: span.clone(),
                    },
                    args: (0..n).map(|i| sub(&inner, i)).collect(),
                }
            }
            _ => mental(MentalOp::Bel, l.clone()),
        };
        Literal { kind, span }
    }

    /// `[sel.]adopt/drop/insert/delete(content)`.
    pub fn update(
        &mut self,
        kw: UpdateKw,
        sel: Option<Selector>,
        cspan: Span,
        span: Span,
    ) -> Action {
        self.inner
            .update_action(kw, sel, cspan.start + 1..cspan.end - 1, span)
    }

    /// `sel.send[:?!](content)`: the mood is in the keyword, the selector is required.
    pub fn send(&mut self, sel: Option<Selector>, mood: Mood, cspan: Span, span: Span) -> Action {
        let content = self.term(cspan.start + 1..cspan.end - 1);
        let selector = match sel {
            Some(s) if s.kind != SelectorKind::This => s,
            _ => {
                self.error(
                    "E0602",
                    "a message needs receivers: `send` to `this` is not allowed",
                    span.clone(),
                    "put the receivers in front: `allother.send(...)`, `(bob).send(...)`",
                );
                Selector::default_this()
            }
        };
        Action {
            kind: ActionKind::Send {
                selector,
                mood,
                content,
            },
            span,
        }
    }

    /// `sendonce(...)`, removed in (A): an error.
    pub fn sendonce(&mut self, span: Span) -> Action {
        self.error(
            "E0601",
            "`sendonce` was removed in modular GOAL",
            span.clone(),
            "use `send` and remember in a belief that the message was sent",
        );
        Action {
            kind: ActionKind::ExitModule,
            span,
        }
    }

    /// `print(T)` / `log(T)`.
    pub fn print(&mut self, log: bool, cspan: Span, span: Span) -> Action {
        let inner = cspan.start + 1..cspan.end - 1;
        let kind = if log {
            ActionKind::Log(self.inner.log_term(inner))
        } else {
            ActionKind::Print(self.term(inner))
        };
        Action { kind, span }
    }

    /// `sleep`, `subscribe`, `unsubscribe`, `starttimer`, `canceltimer`.
    pub fn timing(&mut self, op: TimingOp, cspan: Span, span: Span) -> Action {
        let args = self.args(cspan);
        let (min, max) = match op {
            TimingOp::Sleep | TimingOp::CancelTimer => (1, 1),
            TimingOp::StartTimer => (3, 3),
            TimingOp::Subscribe | TimingOp::Unsubscribe => (1, usize::MAX),
        };
        if args.len() < min || args.len() > max {
            self.error(
                "E0603",
                format!("`{}` with {} arguments", op.name(), args.len()),
                span.clone(),
                if min == max {
                    "check the number of arguments"
                } else {
                    "give at least one argument"
                },
            );
        }
        Action {
            kind: ActionKind::Timing { op, args },
            span,
        }
    }

    /// `name[(args)]`: a user action or module call.
    pub fn call(&mut self, name: Ident, args: Option<Span>, span: Span) -> Action {
        let args = args.map(|a| self.args(a)).unwrap_or_default();
        Action {
            kind: ActionKind::Call { name, args },
            span,
        }
    }

    /// An `.act2g` spec.
    #[allow(clippy::too_many_arguments)]
    pub fn spec(
        &mut self,
        name: Ident,
        params: Option<Span>,
        kind: Option<Spanned<ActionSpecKind>>,
        pre: SpecCondition,
        post: Post,
        span: Span,
    ) -> ActionSpec {
        let params = params.map(|a| self.args(a)).unwrap_or_default();
        let post = match post {
            Post::Plain(p) => p,
            Post::Split(del, add) => self.split_post(del, add),
        };
        ActionSpec {
            name,
            params,
            kind: kind.as_ref().map_or(ActionSpecKind::Env, |k| k.value),
            kind_span: kind.map(|k| k.span),
            pre,
            post,
            span,
        }
    }

    /// `pre{...}` / `post{...}` block content.
    pub fn block(&mut self, kspan: Span, span: Span) -> SpecCondition {
        self.inner
            .spec_condition(kspan.start + 1..kspan.end - 1, span)
    }

    /// `post-{D} post+{A}` as the 2014 update `not(d1), ..., a1, ...`.
    fn split_post(&mut self, del: Option<SpecCondition>, add: SpecCondition) -> SpecCondition {
        let mut items = Vec::new();
        let span = del.as_ref().map_or(add.span.start, |d| d.span.start)..add.span.end;
        if let Some(d) = &del {
            for c in conjuncts(&d.term).into_iter().filter(|_| !d.empty) {
                if matches!(c.term.functor(), Some((f, 1)) if f.name() == "not") {
                    self.error(
                        "E0604",
                        "`not(...)` inside `post-`",
                        c.spans.span.clone(),
                        "`post-` lists the facts to delete: write them without `not`",
                    );
                }
                items.push(unary("not", c.term));
            }
        }
        if !add.empty {
            items.extend(conjuncts(&add.term).into_iter().map(|c| c.term));
        }
        let empty = items.is_empty();
        SpecCondition {
            term: located(conjunction(items), span.clone()),
            empty,
            span,
        }
    }

    /// The listall variable.
    pub fn listall_var(&mut self, span: Span) -> Located {
        self.inner.listall_var(span)
    }

    /// A nested rule block.
    pub fn rule_block(&mut self, rules: Vec<Rule>, span: Span) -> RuleBody {
        self.inner.block(rules, span)
    }
}

fn sub(l: &Located, i: usize) -> Located {
    Located {
        term: l.term.args()[i].clone(),
        spans: l.spans.args.get(i).cloned().unwrap_or_else(|| TermSpans {
            span: l.spans.span.clone(),
            args: Vec::new(),
        }),
    }
}

fn is_mental(t: &Term) -> bool {
    match t.functor() {
        Some((f, 1)) => matches!(f.name(), "bel" | "goal" | "percept"),
        Some((f, 2)) => f.name() == "-" && is_goal_op(t),
        _ => false,
    }
}

/// `a-goal(x)` reads as `-(a, goal(x))`, `goal-a(x)` as `-(goal, a(x))`.
fn is_goal_op(t: &Term) -> bool {
    let a = &t.args()[0];
    let b = &t.args()[1];
    let name = |x: &Term, n: &str, ar: usize| matches!(x.functor(), Some((f, k)) if f.name() == n && k == ar);
    (name(a, "a", 0) && name(b, "goal", 1)) || (name(a, "goal", 0) && name(b, "a", 1))
}

fn goal_op(l: &Located) -> (MentalOp, Located) {
    let op = if matches!(l.term.args()[0].functor(), Some((f, 0)) if f.name() == "a") {
        MentalOp::AGoal
    } else {
        MentalOp::GoalA
    };
    (op, sub(&sub(l, 1), 0))
}

/// `percept(φ)`: each conjunct `p` becomes `percept(p)` (the typed percept base), each `not(p)`
/// becomes `newpercept(not(p))` (a negated percept of this cycle's batch, which binds variables).
pub fn percept_query(q: &Located) -> Located {
    let parts = conjuncts(q)
        .into_iter()
        .map(|c| match c.term.functor() {
            Some((f, 1)) if f.name() == "not" => unary("newpercept", c.term),
            _ => unary("percept", c.term),
        })
        .collect();
    located(conjunction(parts), q.spans.span.clone())
}

/// A lalrpop error as a diagnostic (`E0014` unexpected token, `E0015` unexpected end).
pub fn syntax_error(e: ParseError<usize, MTok, Diagnostic>, src: &str, file: &str) -> Diagnostic {
    let style = ErrorStyle {
        found: &|src: &str, l, r, _: &MTok| shown(src, l, r),
        hint: &|_: &MTok, expected: &[String]| hint(expected).map(String::from),
        eof_hint: &|expected: &[String]| {
            hint(expected)
                .unwrap_or("a module or rule is not finished: check for a missing `}` or `.`")
                .to_string()
        },
    };
    syntax_error_in(e, src, file, &style)
}

fn hint(expected: &[String]) -> Option<&'static str> {
    let has = |s: &str| expected.iter().any(|e| e.trim_matches('"') == s);
    if has(".") && has("+") {
        Some("end the rule with `.` (or join actions with `+`)")
    } else if has("post+") && !has("post") {
        Some("`post-{...}` is followed by `post+{...}`")
    } else if has("then") || has("do") {
        Some("a condition is followed by `then` (for `if`) or `do` (for `forall`/`listall`)")
    } else if has("module") {
        Some("a module file is: use clauses, options, macros, then `module name { rules }`")
    } else {
        None
    }
}

fn shown(src: &str, l: usize, r: usize) -> String {
    let text = src.get(l..r).unwrap_or("?");
    let first = text.lines().next().unwrap_or("");
    let short: String = first.chars().take(30).collect();
    if short.len() < text.len() {
        format!("`{short}...`")
    } else {
        format!("`{short}`")
    }
}
