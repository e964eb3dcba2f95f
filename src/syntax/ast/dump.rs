//! A compact, indented text form of the AST for snapshots: terms as Prolog text (`writeq`),
//! spans as `@line:col`.

use super::*;
use crate::diag::line_col;
use std::fmt::Write;

/// Writes an agent program as indented text; `source` is the file text (for line/column).
pub fn agent_program(p: &AgentProgram, source: &str) -> String {
    let mut d = Dumper {
        src: source,
        out: String::new(),
    };
    d.line(0, &format!("program {}", p.file), &p.span);
    for i in &p.imports {
        d.import(1, i);
    }
    for m in &p.modules {
        d.module(1, m);
    }
    d.out
}

/// Writes one module as indented text.
pub fn module(m: &Module, source: &str) -> String {
    let mut d = Dumper {
        src: source,
        out: String::new(),
    };
    d.module(0, m);
    d.out
}

struct Dumper<'a> {
    src: &'a str,
    out: String,
}

fn terms(ts: &[Located]) -> String {
    ts.iter()
        .map(|t| t.term.to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

fn call(name: &Ident, args: &[Located]) -> String {
    if args.is_empty() {
        name.name.name().to_string()
    } else {
        format!("{}({})", name.name.name(), terms(args))
    }
}

impl Dumper<'_> {
    fn at(&self, span: &Span) -> String {
        let (l, c) = line_col(self.src, span.start);
        format!("@{l}:{c}")
    }

    fn line(&mut self, indent: usize, text: &str, span: &Span) {
        let at = self.at(span);
        let _ = writeln!(self.out, "{:w$}{text} {at}", "", w = indent * 2);
    }

    fn import(&mut self, ind: usize, i: &Import) {
        let kind = match i.kind {
            ImportKind::Module => "module",
            ImportKind::Prolog => "prolog",
        };
        self.line(ind, &format!("import {kind} {:?}", i.path), &i.span);
    }

    fn module(&mut self, ind: usize, m: &Module) {
        let head = match &m.kind {
            ModuleKind::User { name, params } if params.is_empty() => {
                format!("module {}", name.name.name())
            }
            ModuleKind::User { name, params } => format!("module {}", call(name, params)),
            _ => format!("module {}", m.name()),
        };
        let mut opts = Vec::new();
        if let Some(e) = &m.options.exit {
            opts.push(format!("exit={:?}", e.value));
        }
        if let Some(f) = &m.options.focus {
            opts.push(format!("focus={:?}", f.value));
        }
        let head = if opts.is_empty() {
            head
        } else {
            format!("{head} [{}]", opts.join(", "))
        };
        self.line(ind, &head, &m.span);
        for s in &m.sections {
            if !s.used {
                self.line(ind + 1, &format!("ignored duplicate {:?}", s.kind), &s.span);
            }
        }
        for i in &m.imports {
            self.import(ind + 1, i);
        }
        for (title, list) in [
            ("knowledge", &m.knowledge),
            ("beliefs", &m.beliefs),
            ("goals", &m.goals),
        ] {
            if !list.is_empty() {
                let _ = writeln!(self.out, "{:w$}{title}", "", w = (ind + 1) * 2);
                for t in list {
                    self.line(ind + 2, &format!("{}.", t.term), &t.spans.span);
                }
            }
        }
        if !m.action_specs.is_empty() {
            let _ = writeln!(self.out, "{:w$}actionspec", "", w = (ind + 1) * 2);
            for a in &m.action_specs {
                let kind = match a.kind {
                    ActionSpecKind::Env => "@env",
                    ActionSpecKind::Int => "@int",
                };
                self.line(
                    ind + 2,
                    &format!("{} {kind}", call(&a.name, &a.params)),
                    &a.span,
                );
                for (w, c) in [("pre", &a.pre), ("post", &a.post)] {
                    let e = if c.empty { " (empty)" } else { "" };
                    self.line(ind + 3, &format!("{w} {}{e}", c.term.term), &c.span);
                }
            }
        }
        if let Some(p) = &m.program {
            let order = p
                .order
                .as_ref()
                .map(|o| format!(" [order={:?}]", o.value))
                .unwrap_or_default();
            self.line(ind + 1, &format!("program{order}"), &p.span);
            for mac in &p.macros {
                self.line(
                    ind + 2,
                    &format!("#define {}", call(&mac.name, &mac.params)),
                    &mac.span,
                );
                for l in &mac.body {
                    self.literal(ind + 3, l);
                }
            }
            for r in &p.rules {
                self.rule(ind + 2, r);
            }
        }
    }

    fn rule(&mut self, ind: usize, r: &Rule) {
        let head = match &r.kind {
            RuleKind::If => "if".to_string(),
            RuleKind::Forall => "forall".to_string(),
            RuleKind::Listall { var } => format!("listall {} <-", var.term),
        };
        self.line(ind, &head, &r.span);
        for l in &r.condition {
            self.literal(ind + 1, l);
        }
        match &r.body {
            RuleBody::Combo(actions) => {
                let _ = writeln!(self.out, "{:w$}do", "", w = ind * 2);
                for a in actions {
                    self.action(ind + 1, a);
                }
            }
            RuleBody::Block(rules) => {
                let _ = writeln!(self.out, "{:w$}do {{", "", w = ind * 2);
                for r in rules {
                    self.rule(ind + 1, r);
                }
                let _ = writeln!(self.out, "{:w$}}}", "", w = ind * 2);
            }
        }
    }

    fn literal(&mut self, ind: usize, l: &Literal) {
        let text = match &l.kind {
            LiteralKind::True => "true".to_string(),
            LiteralKind::Mental {
                negated,
                selector,
                op,
                query,
            } => {
                let op = op.keyword();
                let inner = format!("{}{op}({})", selector_prefix(selector), query.term);
                if *negated {
                    format!("not({inner})")
                } else {
                    inner
                }
            }
            LiteralKind::MacroUse { name, args } => format!("macro {}", call(name, args)),
        };
        self.line(ind, &text, &l.span);
    }

    fn action(&mut self, ind: usize, a: &Action) {
        let upd =
            |w: &str, s: &Selector, c: &Located| format!("{}{w}({})", selector_prefix(s), c.term);
        let msg = |w: &str, s: &Selector, m: &Mood, c: &Located| {
            let mood = match m {
                Mood::Declarative => ":",
                Mood::Imperative => "!",
                Mood::Interrogative => "?",
            };
            format!("{}{w}({mood}{})", selector_prefix(s), c.term)
        };
        let text = match &a.kind {
            ActionKind::Adopt { selector, content } => upd("adopt", selector, content),
            ActionKind::Drop { selector, content } => upd("drop", selector, content),
            ActionKind::Insert { selector, content } => upd("insert", selector, content),
            ActionKind::Delete { selector, content } => upd("delete", selector, content),
            ActionKind::Send {
                selector,
                mood,
                content,
            } => msg("send", selector, mood, content),
            ActionKind::SendOnce {
                selector,
                mood,
                content,
            } => msg("sendonce", selector, mood, content),
            ActionKind::Print(t) => format!("print({})", t.term),
            ActionKind::Log(t) => format!("log({})", t.term),
            ActionKind::ExitModule => "exit-module".to_string(),
            ActionKind::Call { name, args } => format!("call {}", call(name, args)),
            ActionKind::BuiltinModule(m) => format!("module {m:?}"),
            ActionKind::Timing { op, args } => {
                let ts: Vec<String> = args.iter().map(|a| a.term.to_string()).collect();
                format!("{}({})", op.name(), ts.join(", "))
            }
        };
        self.line(ind, &text, &a.span);
    }
}

fn selector_prefix(s: &Selector) -> String {
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
