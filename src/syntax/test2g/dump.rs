//! A compact, indented text form of a `.test2g` AST for snapshots (spans as `@line:col`).

use super::ast::*;
use crate::diag::{line_col, Span};
use crate::syntax::ast::{Action, ActionKind, Literal, LiteralKind, Mood, Selector, SelectorKind};
use crate::syntax::prolog::Located;
use std::fmt::Write;

/// Writes `t` as indented text; `source` is the file text (for line/column).
pub fn mas_test(t: &MasTest, source: &str) -> String {
    let at = |s: &Span| {
        let (l, c) = line_col(source, s.start);
        format!("@{l}:{c}")
    };
    let mut o = String::new();
    let _ = writeln!(o, "masTest {} {}", t.file, at(&t.span));
    let _ = writeln!(o, "  mas {:?} {}", t.mas.value, at(&t.mas.span));
    if let Some(n) = &t.timeout {
        let _ = writeln!(o, "  timeout {} {}", n.value, at(&n.span));
    }
    for a in &t.agents {
        let names: Vec<&str> = a.agents.iter().map(|i| i.name.name()).collect();
        let _ = writeln!(o, "  agents {} {}", names.join(", "), at(&a.span));
        for test in &a.tests {
            let _ = writeln!(o, "    test {} {}", test.name.name.name(), at(&test.span));
            for s in &test.sections {
                match s {
                    TestSection::Do { combo, span } => {
                        let _ = writeln!(o, "      do {} {}", combo_text(combo), at(span));
                    }
                    TestSection::Assert {
                        condition,
                        message,
                        span,
                    } => {
                        let m = message
                            .as_ref()
                            .map(|m| format!(" : {:?}", m.value))
                            .unwrap_or_default();
                        let _ = writeln!(o, "      assert {}{m} {}", literals(condition), at(span));
                    }
                    TestSection::Evaluate {
                        conditions,
                        combo,
                        boundary,
                        span,
                    } => {
                        let _ = writeln!(o, "      evaluate {}", at(span));
                        for c in conditions {
                            let _ = writeln!(o, "        {}", temporal(c));
                        }
                        let b = boundary
                            .as_ref()
                            .map(|b| {
                                format!(
                                    " {} {}",
                                    if b.until { "until" } else { "while" },
                                    condition(&b.condition)
                                )
                            })
                            .unwrap_or_default();
                        let _ = writeln!(o, "      in do {}{b}", combo_text(combo));
                    }
                }
            }
        }
    }
    o
}

fn temporal(c: &TemporalCondition) -> String {
    match c {
        TemporalCondition::Chain { parts, .. } => parts
            .iter()
            .map(|p| format!("{:?} {}", p.op, condition(&p.condition)).to_lowercase_op())
            .collect::<Vec<_>>()
            .join(" -> "),
        TemporalCondition::ReactTo {
            trigger, reaction, ..
        } => {
            format!("reactTo({}; {})", condition(trigger), condition(reaction))
        }
    }
}

trait LowerOp {
    fn to_lowercase_op(self) -> String;
}

impl LowerOp for String {
    /// Lower-cases the leading operator word (`Always p` -> `always p`).
    fn to_lowercase_op(self) -> String {
        match self.split_once(' ') {
            Some((op, rest)) => format!("{} {rest}", op.to_lowercase()),
            None => self.to_lowercase(),
        }
    }
}

fn condition(c: &TestCondition) -> String {
    let mut parts: Vec<String> = c.literals.iter().map(literal).collect();
    if let Some(d) = &c.done {
        let a = action(&d.action);
        parts.push(if d.negated {
            format!("not(do({a}))")
        } else {
            format!("do({a})")
        });
    }
    parts.join(", ")
}

fn literals(ls: &[Literal]) -> String {
    ls.iter().map(literal).collect::<Vec<_>>().join(", ")
}

fn terms(ts: &[Located]) -> String {
    ts.iter()
        .map(|t| t.term.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

fn selector(s: &Selector) -> String {
    if s.span.is_none() {
        return String::new();
    }
    match &s.kind {
        SelectorKind::This => "this.".into(),
        SelectorKind::SelfAgent => "self.".into(),
        SelectorKind::All => "all.".into(),
        SelectorKind::AllOther => "allother.".into(),
        SelectorKind::Some => "some.".into(),
        SelectorKind::SomeOther => "someother.".into(),
        SelectorKind::Agents(ts) => format!("({}).", terms(ts)),
    }
}

fn literal(l: &Literal) -> String {
    match &l.kind {
        LiteralKind::True => "true".into(),
        LiteralKind::Mental {
            negated,
            selector: s,
            op,
            query,
        } => {
            let op = op.keyword();
            let inner = format!("{}{op}({})", selector(s), query.term);
            if *negated {
                format!("not({inner})")
            } else {
                inner
            }
        }
        LiteralKind::MacroUse { name, args } if args.is_empty() => name.name.name().to_string(),
        LiteralKind::MacroUse { name, args } => format!("{}({})", name.name.name(), terms(args)),
    }
}

fn combo_text(c: &[Action]) -> String {
    c.iter().map(action).collect::<Vec<_>>().join(" + ")
}

fn action(a: &Action) -> String {
    let mood = |m: &Mood| match m {
        Mood::Declarative => ":",
        Mood::Imperative => "!",
        Mood::Interrogative => "?",
    };
    match &a.kind {
        ActionKind::Adopt {
            selector: s,
            content,
        } => format!("{}adopt({})", selector(s), content.term),
        ActionKind::Drop {
            selector: s,
            content,
        } => format!("{}drop({})", selector(s), content.term),
        ActionKind::Insert {
            selector: s,
            content,
        } => format!("{}insert({})", selector(s), content.term),
        ActionKind::Delete {
            selector: s,
            content,
        } => format!("{}delete({})", selector(s), content.term),
        ActionKind::Send {
            selector: s,
            mood: m,
            content,
        } => {
            format!("{}send({}{})", selector(s), mood(m), content.term)
        }
        ActionKind::SendOnce {
            selector: s,
            mood: m,
            content,
        } => {
            format!("{}sendonce({}{})", selector(s), mood(m), content.term)
        }
        ActionKind::Print(t) => format!("print({})", t.term),
        ActionKind::Log(t) => format!("log({})", t.term),
        ActionKind::ExitModule => "exit-module".into(),
        ActionKind::Call { name, args } if args.is_empty() => name.name.name().to_string(),
        ActionKind::Call { name, args } => format!("{}({})", name.name.name(), terms(args)),
        ActionKind::BuiltinModule(m) => format!("{m:?}").to_lowercase(),
        ActionKind::Timing { op, args } => format!("{}({})", op.name(), terms(args)),
    }
}
