//! (A) modular test files (`.test2g` without `masTest`): `use team as mas.`, `timeout = N.`,
//! module tests `test m with pre {..} in { always/never/eventually C. C leadsto D. } post {..}`
//! and agent blocks `robot { do main until C. }`. They are lowered to the 2014 test AST
//! ([`MasTest`]), so the test runner has one path: an agent block becomes one named test
//! `run` of the agents named like the block; each `do` runs as an `evaluate` of the conditions
//! of the module tests whose modules it calls, between their `pre` and `post` asserts.

use super::build::MBuilder;
use super::lexer::ModLexer;
use crate::diag::{Diagnostic, Span};
use crate::syntax::ast::{Action, ActionKind, BuiltinModule, Ident, Literal, Spanned};
use crate::syntax::test2g::ast::*;

/// `test m1, m2 with pre {..} in {..} post {..}`.
pub struct ModuleTest {
    pub modules: Vec<Ident>,
    /// Spans of the `{ ... }` blocks.
    pub pre: Option<Span>,
    pub conds: Vec<InCond>,
    pub post: Option<Span>,
    pub span: Span,
}

/// A condition of an `in { }` block.
pub enum InCond {
    Temporal(TemporalOp, (Vec<CondItem>, Span), Span),
    LeadsTo((Vec<CondItem>, Span), (Vec<CondItem>, Span), Span),
}

/// `do combo [until C].`
pub struct DoItem {
    pub combo: Vec<Action>,
    pub until: Option<(Vec<CondItem>, Span)>,
    pub span: Span,
}

/// `name, name { do ... }`.
pub struct AgentBlock {
    pub names: Vec<Ident>,
    pub items: Vec<DoItem>,
    pub span: Span,
}

/// What the grammar returns for a test file.
pub struct TestParts {
    pub uses: Vec<super::ast::UseClause>,
    pub timeout: Option<Spanned<u64>>,
    pub tests: Vec<ModuleTest>,
    pub agents: Vec<AgentBlock>,
}

impl MBuilder<'_> {
    /// `timeout = N.`
    pub fn timeout(&mut self, span: Span) -> Spanned<u64> {
        let text = &self.inner.src[span.clone()];
        let value = text.parse::<u64>().unwrap_or_else(|_| {
            self.error(
                "E0302",
                "the timeout is a number of seconds that is not negative",
                span.clone(),
                "write `timeout = 600.`",
            );
            0
        });
        Spanned { value, span }
    }
}

/// True for a 2014 test file (its first word is `masTest`).
pub fn is_classic(source: &str) -> bool {
    let mut rest = source;
    loop {
        rest = rest.trim_start();
        if let Some(r) = rest.strip_prefix('%') {
            rest = r.find('\n').map_or("", |i| &r[i..]);
        } else if let Some(r) = rest.strip_prefix("/*") {
            rest = r.find("*/").map_or("", |i| &r[i + 2..]);
        } else {
            return rest.starts_with("masTest");
        }
    }
}

/// Parses an (A) test file into the 2014 test AST.
pub fn parse(source: &str, file: &str) -> (Option<MasTest>, Vec<Diagnostic>) {
    let mut lexer = ModLexer::new(source, 0, source.len(), file, false);
    lexer.test_file = true;
    let mut b = MBuilder::new(source, file);
    let result = super::grammar::TestFileParser::new().parse(&mut b, &mut lexer);
    let mut diags = std::mem::take(&mut b.inner.diagnostics);
    let parts = match result {
        Ok(p) => Some(p),
        Err(e) => {
            diags.push(super::build::syntax_error(e, source, file));
            None
        }
    };
    if lexer.stopped_early {
        diags.retain(|d| d.code != "E0015");
    }
    diags.extend(std::mem::take(&mut lexer.diagnostics));
    let test = parts.and_then(|p| lower(p, source, file, &mut diags));
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    (test, diags)
}

fn lower(p: TestParts, source: &str, file: &str, diags: &mut Vec<Diagnostic>) -> Option<MasTest> {
    use super::ast::UseCase;
    let mas = p
        .uses
        .iter()
        .find_map(|u| match u.case.as_ref().map(|c| c.value) {
            Some(UseCase::Mas) | None => u.refs.first().map(|r| Spanned {
                value: if r.value.ends_with(".mas2g") {
                    r.value.clone()
                } else {
                    format!("{}.mas2g", r.value)
                },
                span: r.span.clone(),
            }),
            _ => None,
        });
    let Some(mas) = mas else {
        diags.push(
            Diagnostic::error("E0305", "the test names no MAS file", file, 0..0)
                .with_hint("start the test file with `use team as mas.` (or `use team.`)"),
        );
        return None;
    };
    let mut agents = Vec::new();
    for block in &p.agents {
        let mut sections = Vec::new();
        for item in &block.items {
            let combo: Vec<Action> = item.combo.iter().map(builtin_module).collect();
            let tests: Vec<&ModuleTest> = p
                .tests
                .iter()
                .filter(|t| t.modules.iter().any(|m| calls(&combo, m.name.name())))
                .collect();
            for t in &tests {
                if let Some(pre) = &t.pre {
                    sections.push(assert(source, file, pre, "pre", diags));
                }
            }
            let mut conditions = Vec::new();
            for t in &tests {
                for c in &t.conds {
                    conditions.push(temporal(c, diags, file));
                }
            }
            let boundary = item.until.as_ref().map(|(items, span)| Boundary {
                until: true,
                condition: condition(items, span, diags, file),
                span: span.clone(),
            });
            sections.push(TestSection::Evaluate {
                conditions,
                combo,
                boundary,
                span: item.span.clone(),
            });
            for t in &tests {
                if let Some(post) = &t.post {
                    sections.push(assert(source, file, post, "post", diags));
                }
            }
        }
        agents.push(AgentTest {
            agents: block.names.clone(),
            tests: vec![NamedTest {
                name: Ident {
                    name: crate::term::Sym::intern("run"),
                    span: block.span.clone(),
                },
                sections,
                span: block.span.clone(),
            }],
            span: block.span.clone(),
        });
    }
    Some(MasTest {
        file: file.to_string(),
        mas,
        timeout: p.timeout,
        agents,
        span: 0..source.len(),
    })
}

/// `init`, `main` and `event` name the role modules of the tested agent.
fn builtin_module(a: &Action) -> Action {
    let kind = match &a.kind {
        ActionKind::Call { name, args } if args.is_empty() => match name.name.name() {
            "init" => Some(BuiltinModule::Init),
            "main" => Some(BuiltinModule::Main),
            "event" => Some(BuiltinModule::Event),
            _ => None,
        },
        _ => None,
    };
    match kind {
        Some(k) => Action {
            kind: ActionKind::BuiltinModule(k),
            span: a.span.clone(),
        },
        None => a.clone(),
    }
}

fn calls(combo: &[Action], module: &str) -> bool {
    combo.iter().any(|a| match &a.kind {
        ActionKind::Call { name, .. } => name.name.name() == module,
        ActionKind::BuiltinModule(k) => {
            let n = match k {
                BuiltinModule::Init => "init",
                BuiltinModule::Main => "main",
                BuiltinModule::Event => "event",
            };
            n == module
        }
        _ => false,
    })
}

/// A `pre {..}`/`post {..}` block as an assert of its condition.
fn assert(
    source: &str,
    file: &str,
    block: &Span,
    what: &str,
    diags: &mut Vec<Diagnostic>,
) -> TestSection {
    let inner = block.start + 1..block.end - 1;
    let mut lexer = ModLexer::new(source, inner.start, inner.end, file, false);
    let mut b = MBuilder::new(&source[..inner.end], file);
    let condition: Vec<Literal> =
        match super::grammar::CondOnlyParser::new().parse(&mut b, &mut lexer) {
            Ok(c) => c,
            Err(e) => {
                diags.push(super::build::syntax_error(e, source, file));
                Vec::new()
            }
        };
    diags.append(&mut b.inner.diagnostics);
    diags.append(&mut lexer.diagnostics);
    TestSection::Assert {
        condition,
        message: Some(Spanned {
            value: format!("the {what}condition of the module test holds"),
            span: block.clone(),
        }),
        span: block.clone(),
    }
}

fn condition(
    items: &[CondItem],
    span: &Span,
    diags: &mut Vec<Diagnostic>,
    file: &str,
) -> TestCondition {
    let mut literals = Vec::new();
    let mut done: Option<DoTest> = None;
    for i in items {
        match i {
            CondItem::Literal(l) => literals.push(l.clone()),
            CondItem::Done(d) => {
                if done.is_some() {
                    diags.push(
                        Diagnostic::error(
                            "E0303",
                            "more than one `done(...)` in one condition",
                            file,
                            d.span.clone(),
                        )
                        .with_hint("a condition tests at most one action"),
                    );
                }
                done = Some(d.clone());
            }
        }
    }
    TestCondition {
        literals,
        done,
        span: span.clone(),
    }
}

fn temporal(c: &InCond, diags: &mut Vec<Diagnostic>, file: &str) -> TemporalCondition {
    match c {
        InCond::Temporal(op, (items, cspan), span) => TemporalCondition::Chain {
            parts: vec![TemporalPart {
                op: *op,
                condition: condition(items, cspan, diags, file),
                span: span.clone(),
            }],
            span: span.clone(),
        },
        InCond::LeadsTo((a, aspan), (r, rspan), span) => TemporalCondition::ReactTo {
            trigger: condition(a, aspan, diags, file),
            reaction: condition(r, rspan, diags, file),
            span: span.clone(),
        },
    }
}
