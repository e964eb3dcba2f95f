//! Spans in the AST nest (term inside literal/action inside rule inside module) and the text at a
//! term's span reads back as the same term.

use goal::diag::Span;
use goal::syntax::ast::*;
use goal::syntax::goal::parse_goal;
use goal::syntax::prolog::Reader;
use std::path::Path;

struct Check<'a> {
    src: &'a str,
    terms: usize,
}

fn inside(inner: &Span, outer: &Span) -> bool {
    outer.start <= inner.start && inner.end <= outer.end && inner.start < inner.end
}

impl Check<'_> {
    fn term(&mut self, t: &Located, outer: &Span) {
        let span = &t.spans.span;
        assert!(
            inside(span, outer),
            "term {} at {span:?} outside {outer:?}",
            t.term
        );
        let text = &self.src[span.clone()];
        let again = Reader::new("again")
            .term(text, span.start)
            .unwrap_or_else(|d| panic!("`{text}` does not read back: {d:?}"));
        // Anonymous variables are numbered per reader: compare the printed forms without them.
        let strip = |s: String| {
            s.split("_G")
                .map(|p| p.trim_start_matches(|c: char| c.is_ascii_digit()))
                .collect::<String>()
        };
        assert_eq!(strip(again.term.to_string()), strip(t.term.to_string()));
        self.terms += 1;
    }

    fn literal(&mut self, l: &Literal, outer: &Span) {
        assert!(
            inside(&l.span, outer),
            "literal {:?} outside {outer:?}",
            l.span
        );
        match &l.kind {
            LiteralKind::True => {}
            LiteralKind::Mental {
                query, selector, ..
            } => {
                self.term(query, &l.span);
                self.selector(selector, &l.span);
            }
            LiteralKind::MacroUse { args, .. } => args.iter().for_each(|a| self.term(a, &l.span)),
        }
    }

    fn selector(&mut self, s: &Selector, outer: &Span) {
        if let (SelectorKind::Agents(ts), Some(span)) = (&s.kind, &s.span) {
            assert!(inside(span, outer));
            ts.iter().for_each(|t| self.term(t, outer));
        }
    }

    fn action(&mut self, a: &Action, outer: &Span) {
        assert!(
            inside(&a.span, outer),
            "action {:?} outside {outer:?}",
            a.span
        );
        let s = &a.span;
        match &a.kind {
            ActionKind::Adopt { selector, content }
            | ActionKind::Drop { selector, content }
            | ActionKind::Insert { selector, content }
            | ActionKind::Delete { selector, content }
            | ActionKind::Send {
                selector, content, ..
            }
            | ActionKind::SendOnce {
                selector, content, ..
            } => {
                self.selector(selector, s);
                self.term(content, s);
            }
            ActionKind::Print(t) | ActionKind::Log(t) => self.term(t, s),
            ActionKind::Call { args, .. } | ActionKind::Timing { args, .. } => {
                args.iter().for_each(|t| self.term(t, s))
            }
            ActionKind::ExitModule | ActionKind::BuiltinModule(_) => {}
        }
    }

    fn rule(&mut self, r: &Rule, outer: &Span) {
        assert!(
            inside(&r.span, outer),
            "rule {:?} outside {outer:?}",
            r.span
        );
        if let RuleKind::Listall { var } = &r.kind {
            self.term(var, &r.span);
        }
        r.condition.iter().for_each(|l| self.literal(l, &r.span));
        match &r.body {
            RuleBody::Combo(actions) => actions.iter().for_each(|a| self.action(a, &r.span)),
            RuleBody::Block(rules) => rules.iter().for_each(|x| self.rule(x, &r.span)),
        }
    }

    fn module(&mut self, m: &Module, outer: &Span) {
        assert!(inside(&m.span, outer));
        assert!(inside(&m.head_span, &m.span));
        for t in m.knowledge.iter().chain(&m.beliefs).chain(&m.goals) {
            assert!(inside(&t.spans.span, &m.span));
            self.terms += 1;
        }
        for a in &m.action_specs {
            assert!(inside(&a.span, &m.span));
            a.params.iter().for_each(|t| self.term(t, &a.span));
            for c in [&a.pre, &a.post] {
                assert!(inside(&c.span, &a.span));
                if !c.empty {
                    self.term(&c.term, &c.span);
                }
            }
        }
        if let Some(p) = &m.program {
            assert!(inside(&p.span, &m.span));
            for mac in &p.macros {
                mac.params.iter().for_each(|t| self.term(t, &mac.span));
                mac.body.iter().for_each(|l| self.literal(l, &mac.span));
            }
            p.rules.iter().for_each(|r| self.rule(r, &p.span));
        }
    }
}

#[test]
fn spans_nest_and_read_back() {
    for rel in [
        "tests/fixtures/goal/every_construct.goal",
        "agents/bw4t/robot.goal",
        "agents/blocksworld/stacker.goal",
        "agents/pingpong/ping.goal",
    ] {
        let src = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(rel))
            .expect("corpus file");
        let (program, diags) = parse_goal(rel, &src);
        assert!(!diags.iter().any(|d| d.is_error()), "{diags:?}");
        let mut c = Check {
            src: &src,
            terms: 0,
        };
        for m in &program.modules {
            c.module(m, &program.span);
        }
        assert!(c.terms > 10, "{rel}: only {} terms checked", c.terms);
    }
}

#[test]
fn send_moods_and_content_spans() {
    let src = "main module { program { if true then (bob).send(!p(1)) + bob.send( ?q(X)) + send(carol, :r). } }";
    let (program, diags) = parse_goal("m.goal", src);
    assert_eq!(diags.len(), 2, "{diags:?}"); // two legacy-form warnings
    let rules = &program.modules[0].program.as_ref().expect("program").rules;
    let RuleBody::Combo(actions) = &rules[0].body else {
        panic!("combo expected")
    };
    let got: Vec<(Mood, String, &str, String)> = actions
        .iter()
        .map(|a| match &a.kind {
            ActionKind::Send {
                selector:
                    Selector {
                        kind: SelectorKind::Agents(to),
                        ..
                    },
                mood,
                content,
            } => (
                *mood,
                to[0].term.to_string(),
                &src[content.spans.span.clone()],
                content.term.to_string(),
            ),
            other => panic!("send expected, got {other:?}"),
        })
        .collect();
    assert_eq!(
        got,
        vec![
            (Mood::Imperative, "bob".into(), "p(1)", "p(1)".into()),
            (Mood::Interrogative, "bob".into(), "q(X)", "q(X)".into()),
            (Mood::Declarative, "carol".into(), "r", "r".into()),
        ]
    );
}

#[test]
fn legacy_send_with_several_receivers() {
    let src =
        "main module { program { if true then send((alice, bob), hi) + send( (carol), :x). } }";
    let (program, _) = parse_goal("m.goal", src);
    let rules = &program.modules[0].program.as_ref().expect("program").rules;
    let RuleBody::Combo(actions) = &rules[0].body else {
        panic!("combo expected")
    };
    let receivers: Vec<Vec<String>> = actions
        .iter()
        .map(|a| match &a.kind {
            ActionKind::Send {
                selector:
                    Selector {
                        kind: SelectorKind::Agents(to),
                        ..
                    },
                ..
            } => to
                .iter()
                .map(|t| src[t.spans.span.clone()].to_string())
                .collect(),
            other => panic!("send expected, got {other:?}"),
        })
        .collect();
    assert_eq!(receivers, vec![vec!["alice", "bob"], vec!["carol"]]);
}
