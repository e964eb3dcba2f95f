//! Semantic actions that assemble larger nodes: actions with selectors and moods (including the
//! legacy send forms) and modules (options, sections in any order, duplicates).

use super::build::{Builder, SectionItem, UpdateKw};
use crate::diag::Span;
use crate::syntax::ast::*;
use crate::syntax::lexer::kr;

impl Builder<'_> {
    /// `[selector.]adopt/drop/insert/delete/send/sendonce(content)`; `content` is inside the parens.
    pub fn update_action(
        &mut self,
        kw: UpdateKw,
        selector: Option<Selector>,
        content: Span,
        span: Span,
    ) -> Action {
        let kind = match kw {
            UpdateKw::Send | UpdateKw::SendOnce => {
                let (selector, mood, content) = self.message(kw, selector, content, &span);
                if kw == UpdateKw::Send {
                    ActionKind::Send {
                        selector,
                        mood,
                        content,
                    }
                } else {
                    ActionKind::SendOnce {
                        selector,
                        mood,
                        content,
                    }
                }
            }
            _ => {
                let selector = selector.unwrap_or_else(Selector::default_this);
                let content = self.term(content);
                match kw {
                    UpdateKw::Adopt => ActionKind::Adopt { selector, content },
                    UpdateKw::Drop => ActionKind::Drop { selector, content },
                    UpdateKw::Insert => ActionKind::Insert { selector, content },
                    _ => ActionKind::Delete { selector, content },
                }
            }
        };
        Action { kind, span }
    }

    /// The receiver, mood and content of a send; handles `(bob).send(:p)`, `bob.send(!p)` and
    /// `send(bob, ?p)` (the last two with a style warning).
    fn message(
        &mut self,
        kw: UpdateKw,
        selector: Option<Selector>,
        content: Span,
        span: &Span,
    ) -> (Selector, Mood, Located) {
        let word = if kw == UpdateKw::Send {
            "send"
        } else {
            "sendonce"
        };
        let (selector, content) = match selector {
            Some(sel) => {
                let bare = sel.span.as_ref().is_some_and(|s| {
                    matches!(sel.kind, SelectorKind::Agents(_))
                        && !self.src[s.clone()].starts_with('(')
                });
                if bare {
                    let s = sel.span.clone().unwrap_or_default();
                    let name = self.src[s.clone()].to_string();
                    self.warning(
                        "W0002",
                        format!("legacy selector form `{name}.{word}(...)`"),
                        s,
                    )
                    .hint = Some(format!(
                        "write the receiver in parentheses: `({name}).{word}(...)`"
                    ));
                }
                (sel, content)
            }
            None => {
                let commas = kr::top_level_commas(self.src, content.start, content.end);
                match commas.first() {
                    Some(&comma) => {
                        let receiver = self.src[content.start..comma].trim().to_string();
                        let receiver_span = content.start..comma;
                        let t = self.term(receiver_span.clone());
                        let kind = match t.term.to_string().as_str() {
                            "all" => SelectorKind::All,
                            "allother" => SelectorKind::AllOther,
                            "self" => SelectorKind::SelfAgent,
                            "this" => SelectorKind::This,
                            "some" => SelectorKind::Some,
                            "someother" => SelectorKind::SomeOther,
                            // `send((a, b), p)`: several receivers.
                            _ if receiver.starts_with('(') && receiver.ends_with(')') => {
                                let inner = self.src[..comma].rfind(')').unwrap_or(comma);
                                let open = content.start
                                    + (self.src[content.clone()].len()
                                        - self.src[content.clone()].trim_start().len());
                                SelectorKind::Agents(self.term_list(open + 1..inner))
                            }
                            _ => SelectorKind::Agents(vec![t]),
                        };
                        self.warning(
                            "W0002",
                            format!("legacy two-argument form `{word}({receiver}, ...)`"),
                            span.clone(),
                        )
                        .hint = Some(if matches!(kind, SelectorKind::Agents(_)) {
                            format!("write `({receiver}).{word}(...)`")
                        } else {
                            format!("write `{receiver}.{word}(...)`")
                        });
                        let sel = Selector {
                            kind,
                            span: Some(receiver_span),
                        };
                        (sel, comma + 1..content.end)
                    }
                    None => {
                        self.error("E0021", format!("`{word}` without a receiver"), span.clone())
                            .hint = Some(format!(
                            "put the receivers in front: `allother.{word}(...)`, `(bob).{word}(...)`"
                        ));
                        (Selector::default_this(), content)
                    }
                }
            }
        };
        // The mood marker is the first non-blank character of the content.
        let text = &self.src[content.clone()];
        let lead = text.len() - text.trim_start().len();
        let marker = text.trim_start().chars().next();
        let (mood, skip) = match marker {
            Some(':') if !text.trim_start().starts_with(":-") => (Mood::Declarative, 1),
            Some('!') => (Mood::Imperative, 1),
            Some('?') => (Mood::Interrogative, 1),
            _ => (Mood::Declarative, 0),
        };
        let start = content.start + lead + skip;
        let content = self.term(start.min(content.end)..content.end);
        (selector, mood, content)
    }

    /// Assembles a module from its head, options and sections (any order; the first of
    /// duplicated sections is used, with a warning for the others).
    pub fn module(
        &mut self,
        (kind, head_span): (ModuleKind, Span),
        written: Vec<ModuleOption>,
        sections: Vec<SectionItem>,
        span: Span,
    ) -> Module {
        let options = self.options(written);
        let mut m = Module {
            kind,
            options,
            knowledge: Vec::new(),
            beliefs: Vec::new(),
            goals: Vec::new(),
            program: None,
            action_specs: Vec::new(),
            imports: Vec::new(),
            sections: Vec::new(),
            head_span,
            span,
        };
        for s in sections {
            let (kind, sspan) = match &s {
                SectionItem::Knowledge(_, _, sp) => (SectionKind::Knowledge, sp.clone()),
                SectionItem::Beliefs(_, sp) => (SectionKind::Beliefs, sp.clone()),
                SectionItem::Goals(_, sp) => (SectionKind::Goals, sp.clone()),
                SectionItem::Program(p) => (SectionKind::Program, p.span.clone()),
                SectionItem::ActionSpecs(_, sp) => (SectionKind::ActionSpec, sp.clone()),
                SectionItem::Import(i) => {
                    m.imports.push(i.clone());
                    continue;
                }
                SectionItem::Error => continue,
            };
            let first = m
                .sections
                .iter()
                .find(|h| h.kind == kind)
                .map(|h| h.span.start);
            let used = first.is_none();
            if let Some(first) = first {
                let (line, _) = crate::diag::line_col(self.src, first);
                let name = section_name(kind);
                self.warning(
                    "W0001",
                    format!("duplicate `{name}` section: only the first one (line {line}) is used"),
                    sspan.start..sspan.start + name.len(),
                )
                .hint = Some(format!("merge the two `{name}` sections"));
            }
            m.sections.push(SectionHeader {
                kind,
                span: sspan,
                used,
            });
            if !used {
                continue;
            }
            match s {
                SectionItem::Knowledge(k, imports, _) => {
                    m.knowledge = k;
                    m.imports.extend(imports);
                }
                SectionItem::Beliefs(b, _) => m.beliefs = b,
                SectionItem::Goals(g, _) => m.goals = g,
                SectionItem::Program(p) => m.program = Some(p),
                SectionItem::ActionSpecs(a, _) => m.action_specs = a,
                SectionItem::Import(_) | SectionItem::Error => {}
            }
        }
        m
    }

    /// Reads `[exit=..., focus=...]`: unknown keys and duplicates are warnings, unknown values errors.
    fn options(&mut self, written: Vec<ModuleOption>) -> ModuleOptions {
        let mut o = ModuleOptions::default();
        for opt in &written {
            let (key, value) = (opt.key.name.name(), opt.value.name.name());
            match key {
                "exit" => {
                    let v = match value {
                        "always" => ExitCondition::Always,
                        "never" => ExitCondition::Never,
                        "nogoals" => ExitCondition::NoGoals,
                        "noaction" => ExitCondition::NoAction,
                        _ => {
                            self.bad_value(opt, "always, never, nogoals, noaction");
                            continue;
                        }
                    };
                    if o.exit.is_some() {
                        self.duplicate_option(opt);
                    } else {
                        o.exit = Some(Spanned {
                            value: v,
                            span: opt.span.clone(),
                        });
                    }
                }
                "focus" => {
                    let v = match value {
                        "none" => Focus::None,
                        "new" => Focus::New,
                        "select" => Focus::Select,
                        "filter" => Focus::Filter,
                        _ => {
                            self.bad_value(opt, "none, new, select, filter");
                            continue;
                        }
                    };
                    if o.focus.is_some() {
                        self.duplicate_option(opt);
                    } else {
                        o.focus = Some(Spanned {
                            value: v,
                            span: opt.span.clone(),
                        });
                    }
                }
                _ => {
                    self.warning(
                        "W0003",
                        format!("unknown module option `{key}` (ignored)"),
                        opt.key.span.clone(),
                    )
                    .hint = Some("module options are `exit=...` and `focus=...`".into());
                }
            }
        }
        o.written = written;
        o
    }

    fn bad_value(&mut self, opt: &ModuleOption, allowed: &str) {
        let (key, value) = (opt.key.name.name(), opt.value.name.name());
        self.error(
            "E0020",
            format!("unknown value `{value}` for module option `{key}`"),
            opt.value.span.clone(),
        )
        .hint = Some(format!("use one of {allowed}"));
    }

    fn duplicate_option(&mut self, opt: &ModuleOption) {
        let key = opt.key.name.name();
        self.warning(
            "W0004",
            format!("duplicate module option `{key}`: the first one is used"),
            opt.span.clone(),
        );
    }
}

fn section_name(k: SectionKind) -> &'static str {
    match k {
        SectionKind::Knowledge => "knowledge",
        SectionKind::Beliefs => "beliefs",
        SectionKind::Goals => "goals",
        SectionKind::Program => "program",
        SectionKind::ActionSpec => "actionspec",
    }
}
