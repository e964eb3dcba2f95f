//! Compiling the AST into a [`Program`]: module options and defaults, macro expansion with
//! variable renaming, name/arity resolution of actions and module calls, action specs renamed
//! apart from rule variables.

use super::kr_bridge::load_knowledge;
use super::program::*;
use crate::diag::{line_col, Diagnostic, Span};
use crate::syntax::ast::{self, ExitCondition, Focus, Order};
use crate::term::{Subst, Sym, Term};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Compiles a parsed program with extra knowledge clauses.
pub(crate) fn compile(
    ast: &ast::AgentProgram,
    source: &str,
    extra_knowledge: &[Term],
) -> Result<Arc<Program>, Vec<Diagnostic>> {
    let c = Compiler {
        file: ast.file.clone(),
        source,
        errors: Vec::new(),
        warnings: Vec::new(),
        macros: BTreeMap::new(),
        fresh: 0,
        blocks: Vec::new(),
        modules: Vec::new(),
        specs: Vec::new(),
        callables: BTreeMap::new(),
        select_modules: Vec::new(),
    };
    c.run(ast, extra_knowledge)
}

type MacroDef = (Vec<Term>, Vec<ast::Literal>);

pub(crate) struct Compiler<'s> {
    file: String,
    source: &'s str,
    errors: Vec<Diagnostic>,
    warnings: Vec<Diagnostic>,
    macros: BTreeMap<(String, usize), MacroDef>,
    fresh: u64,
    blocks: Vec<Block>,
    modules: Vec<ModuleDef>,
    specs: Vec<SpecDef>,
    callables: BTreeMap<(String, usize), Callable>,
    select_modules: Vec<usize>,
}

#[derive(Clone, Copy)]
enum Callable {
    Module(usize),
    Spec(usize),
}

const MAX_MACRO_DEPTH: usize = 32;

impl Compiler<'_> {
    fn line(&self, span: &Span) -> usize {
        line_col(self.source, span.start).0
    }
    fn error(&mut self, code: &str, msg: impl Into<String>, span: Span) {
        self.errors
            .push(Diagnostic::error(code, msg.into(), self.file.clone(), span));
    }
    fn warn(&mut self, code: &str, msg: impl Into<String>, span: Span) {
        self.warnings.push(Diagnostic::warning(
            code,
            msg.into(),
            self.file.clone(),
            span,
        ));
    }

    fn run(
        mut self,
        ast: &ast::AgentProgram,
        extra: &[Term],
    ) -> Result<Arc<Program>, Vec<Diagnostic>> {
        // Knowledge of every module forms one base; macros and action specs are global.
        let mut clauses = extra.to_vec();
        for m in &ast.modules {
            clauses.extend(m.knowledge.iter().map(|l| l.term.clone()));
            if let Some(p) = &m.program {
                for d in &p.macros {
                    let key = (d.name.name.name().to_string(), d.params.len());
                    let params = d.params.iter().map(|l| l.term.clone()).collect();
                    self.macros.entry(key).or_insert((params, d.body.clone()));
                }
            }
            for s in &m.action_specs {
                self.add_spec(s);
            }
        }
        let knowledge = match load_knowledge(&clauses) {
            Ok(k) => k,
            Err(e) => {
                self.error(
                    "E0400",
                    format!("knowledge cannot be loaded: {e}"),
                    ast.span.clone(),
                );
                return Err(self.errors);
            }
        };
        // Register module names first so that calls resolve regardless of order.
        for m in &ast.modules {
            let idx = self.modules.len();
            let (kind, params) = match &m.kind {
                ast::ModuleKind::Init => (ModuleKind::Init, Vec::new()),
                ast::ModuleKind::Main => (ModuleKind::Main, Vec::new()),
                ast::ModuleKind::Event => (ModuleKind::Event, Vec::new()),
                ast::ModuleKind::User { params, .. } => (
                    ModuleKind::User,
                    params.iter().map(|l| l.term.clone()).collect(),
                ),
            };
            let (exit, focus) = self.options(m, kind);
            if focus == Focus::Select {
                self.select_modules.push(idx);
            }
            if kind == ModuleKind::User {
                let key = (m.name().to_string(), params.len());
                if self.callables.contains_key(&key) {
                    self.error(
                        "E0401",
                        format!("{}/{} is defined twice (module or action)", key.0, key.1),
                        m.head_span.clone(),
                    );
                }
                self.callables.insert(key, Callable::Module(idx));
            }
            self.modules.push(ModuleDef {
                name: m.name().to_string(),
                kind,
                params,
                exit,
                focus,
                beliefs: m.beliefs.iter().map(|l| l.term.clone()).collect(),
                goals: m.goals.iter().map(|l| l.term.clone()).collect(),
                block: 0,
                line: self.line(&m.head_span),
            });
        }
        for (idx, m) in ast.modules.iter().enumerate() {
            let kind = self.modules[idx].kind;
            let default = match kind {
                ModuleKind::Init | ModuleKind::Event => Order::LinearAll,
                _ => Order::Linear,
            };
            let (order, rules) = match &m.program {
                Some(p) => (p.order.as_ref().map_or(default, |o| o.value), &p.rules[..]),
                None => (default, &[][..]),
            };
            if order == Order::Adaptive {
                let span = m
                    .program
                    .as_ref()
                    .map_or(m.head_span.clone(), |p| p.span.clone());
                self.warn("W0402", "order=adaptive runs as order=random", span);
            }
            let name = self.modules[idx].name.clone();
            let block = self.block(&name, rules, order);
            self.modules[idx].block = block;
        }
        let find = |k: ModuleKind, mods: &[ModuleDef]| mods.iter().position(|m| m.kind == k);
        let init = find(ModuleKind::Init, &self.modules);
        let event = find(ModuleKind::Event, &self.modules);
        let main = match find(ModuleKind::Main, &self.modules) {
            Some(m) => m,
            None => {
                if event.is_none() {
                    self.error(
                        "E0403",
                        "a program needs a main or an event module",
                        ast.span.clone(),
                    );
                }
                let block = self.blocks.len();
                self.blocks.push(Block {
                    rules: Vec::new(),
                    order: Order::Linear,
                });
                self.modules.push(ModuleDef {
                    name: "main".into(),
                    kind: ModuleKind::Main,
                    params: Vec::new(),
                    exit: ExitCondition::Never,
                    focus: Focus::None,
                    beliefs: Vec::new(),
                    goals: Vec::new(),
                    block,
                    line: 0,
                });
                self.modules.len() - 1
            }
        };
        if !self.errors.is_empty() {
            let mut all = self.errors;
            all.extend(self.warnings);
            return Err(all);
        }
        Ok(Arc::new(Program {
            file: self.file,
            source: Arc::from(self.source),
            knowledge,
            modules: self.modules,
            blocks: self.blocks,
            specs: self.specs,
            init,
            main,
            event,
            warnings: self.warnings,
            uses_newpercept: mentions_newpercept(&ast.modules),
        }))
    }

    fn options(&mut self, m: &ast::Module, kind: ModuleKind) -> (ExitCondition, Focus) {
        let exit = m.options.exit.as_ref();
        let focus = m.options.focus.as_ref();
        match kind {
            ModuleKind::Init | ModuleKind::Event => {
                if let Some(e) = exit {
                    self.warn(
                        "W0404",
                        "exit is ignored for init and event modules",
                        e.span.clone(),
                    );
                }
                if let Some(f) = focus {
                    self.warn(
                        "W0405",
                        "focus is only allowed on user modules",
                        f.span.clone(),
                    );
                }
                (ExitCondition::Always, Focus::None)
            }
            ModuleKind::Main => {
                if let Some(f) = focus {
                    self.warn(
                        "W0405",
                        "focus is only allowed on user modules",
                        f.span.clone(),
                    );
                }
                (exit.map_or(ExitCondition::Never, |e| e.value), Focus::None)
            }
            ModuleKind::User => (
                exit.map_or(ExitCondition::Always, |e| e.value),
                focus.map_or(Focus::None, |f| f.value),
            ),
        }
    }

    fn add_spec(&mut self, s: &ast::ActionSpec) {
        // Rename the spec's variables apart from rule variables.
        let mut ren = Subst::new();
        let mut vars = Vec::new();
        for t in s.params.iter().chain([&s.pre.term, &s.post.term]) {
            vars.extend(t.term.vars());
        }
        for v in vars {
            ren.bind(v, Term::Var(Sym::intern(&format!("_A_{}", v.name()))));
        }
        let key = (s.name.name.name().to_string(), s.params.len());
        if self.callables.contains_key(&key) {
            self.error(
                "E0401",
                format!("{}/{} is defined twice (module or action)", key.0, key.1),
                s.span.clone(),
            );
            return;
        }
        self.callables.insert(key, Callable::Spec(self.specs.len()));
        self.specs.push(SpecDef {
            name: s.name.name,
            params: s.params.iter().map(|p| ren.apply(&p.term)).collect(),
            env: s.kind == ast::ActionSpecKind::Env,
            pre: ren.apply(&s.pre.term.term),
            post: ren.apply(&s.post.term.term),
        });
    }

    fn block(&mut self, module: &str, rules: &[ast::Rule], order: Order) -> usize {
        let idx = self.blocks.len();
        self.blocks.push(Block {
            rules: Vec::new(),
            order,
        });
        let mut out = Vec::new();
        for r in rules {
            if let Some(rd) = self.rule(module, r) {
                out.push(rd);
            }
        }
        self.blocks[idx].rules = out;
        idx
    }

    fn rule(&mut self, module: &str, r: &ast::Rule) -> Option<RuleDef> {
        let line = self.line(&r.span);
        let kind = match &r.kind {
            ast::RuleKind::If => RuleKind::If,
            ast::RuleKind::Forall => RuleKind::Forall,
            ast::RuleKind::Listall { var } => match var.term {
                Term::Var(v) => RuleKind::Listall(v),
                _ => {
                    self.error("E0406", "listall needs a variable", r.span.clone());
                    return None;
                }
            },
        };
        let mut cond = Vec::new();
        self.literals(&r.condition, &Subst::new(), 0, &mut cond);
        let body = match &r.body {
            ast::RuleBody::Combo(actions) => {
                Body::Combo(actions.iter().filter_map(|a| self.action(a)).collect())
            }
            ast::RuleBody::Block(rules) => Body::Block(self.block(module, rules, Order::LinearAll)),
        };
        let per_goal = match &body {
            Body::Combo(acts) => acts.iter().any(|a| {
                matches!(a.kind, Act::Module { module, .. } if self.select_modules.contains(&module))
            }),
            Body::Block(_) => false,
        };
        Some(RuleDef {
            kind,
            cond,
            body,
            label: format!("{module}:{line}").into(),
            line,
            per_goal,
        })
    }

    fn literals(&mut self, lits: &[ast::Literal], s: &Subst, depth: usize, out: &mut Vec<Lit>) {
        for l in lits {
            match &l.kind {
                ast::LiteralKind::True => out.push(Lit::True),
                ast::LiteralKind::Mental {
                    negated,
                    selector,
                    op,
                    query,
                } => {
                    let top_level = match selector.kind {
                        ast::SelectorKind::This => false,
                        ast::SelectorKind::SelfAgent => true,
                        _ => {
                            self.error(
                                "E0407",
                                "only the selectors this and self are supported on conditions",
                                l.span.clone(),
                            );
                            false
                        }
                    };
                    out.push(Lit::Mental {
                        negated: *negated,
                        top_level,
                        op: *op,
                        query: s.apply(&query.term),
                    });
                }
                ast::LiteralKind::MacroUse { name, args } => {
                    let key = (name.name.name().to_string(), args.len());
                    let Some((params, body)) = self.macros.get(&key).cloned() else {
                        self.error(
                            "E0408",
                            format!("{}/{} is not a macro", key.0, key.1),
                            l.span.clone(),
                        );
                        continue;
                    };
                    if depth >= MAX_MACRO_DEPTH {
                        self.error("E0409", "macros nest too deeply", l.span.clone());
                        continue;
                    }
                    // Rename the definition apart, then unify its head with the call.
                    self.fresh += 1;
                    let mut ren = Subst::new();
                    let mut vars = Vec::new();
                    for p in &params {
                        vars.extend(p.vars());
                    }
                    for b in &body {
                        if let ast::LiteralKind::Mental { query, .. } = &b.kind {
                            vars.extend(query.term.vars());
                        }
                        if let ast::LiteralKind::MacroUse { args, .. } = &b.kind {
                            for a in args {
                                vars.extend(a.term.vars());
                            }
                        }
                    }
                    for v in vars {
                        let fresh = format!("_M{}_{}", self.fresh, v.name());
                        ren.bind(v, Term::Var(Sym::intern(&fresh)));
                    }
                    let mut m = Subst::new();
                    let mut ok = true;
                    for (p, a) in params.iter().zip(args) {
                        ok &= m.unify(&ren.apply(p), &s.apply(&a.term), false);
                    }
                    if !ok {
                        self.error(
                            "E0410",
                            "macro arguments do not match its parameters",
                            l.span.clone(),
                        );
                        continue;
                    }
                    let mut expanded = Vec::new();
                    let body: Vec<ast::Literal> =
                        body.iter().map(|b| rename_literal(b, &ren)).collect();
                    self.literals(&body, &m, depth + 1, &mut expanded);
                    out.extend(expanded);
                }
            }
        }
    }

    fn action(&mut self, a: &ast::Action) -> Option<ActionDef> {
        use ast::ActionKind as K;
        let line = self.line(&a.span);
        let this_only = |c: &mut Self, sel: &ast::Selector, what: &str| {
            if !matches!(sel.kind, ast::SelectorKind::This) {
                c.error("E0411", format!("{what} takes no selector"), a.span.clone());
            }
        };
        let kind = match &a.kind {
            K::Adopt { selector, content } => {
                let top_level = match selector.kind {
                    ast::SelectorKind::This => false,
                    ast::SelectorKind::SelfAgent => true,
                    _ => {
                        self.error("E0411", "adopt takes only this or self", a.span.clone());
                        false
                    }
                };
                Act::Adopt {
                    top_level,
                    content: content.term.clone(),
                }
            }
            K::Drop { selector, content } => {
                this_only(self, selector, "drop");
                Act::Drop(content.term.clone())
            }
            K::Insert { selector, content } => {
                this_only(self, selector, "insert");
                Act::Insert(content.term.clone())
            }
            K::Delete { selector, content } => {
                this_only(self, selector, "delete");
                Act::Delete(content.term.clone())
            }
            K::Send {
                selector,
                mood,
                content,
            }
            | K::SendOnce {
                selector,
                mood,
                content,
            } => {
                let to = match &selector.kind {
                    ast::SelectorKind::All => Receivers::All,
                    ast::SelectorKind::AllOther => Receivers::AllOther,
                    ast::SelectorKind::SelfAgent => Receivers::SelfAgent,
                    ast::SelectorKind::Agents(ts) => {
                        Receivers::Agents(ts.iter().map(|t| t.term.clone()).collect())
                    }
                    _ => {
                        self.error(
                            "E0412",
                            "send needs a receiver: all, allother, self or agent names",
                            a.span.clone(),
                        );
                        return None;
                    }
                };
                Act::Send {
                    to,
                    mood: *mood,
                    content: content.term.clone(),
                    once: matches!(a.kind, K::SendOnce { .. }),
                }
            }
            K::Print(t) => Act::Print(t.term.clone()),
            K::Log(t) => Act::Log(t.term.clone()),
            K::ExitModule => Act::ExitModule,
            K::Call { name, args } => {
                let key = (name.name.name().to_string(), args.len());
                let args = args.iter().map(|l| l.term.clone()).collect();
                match self.callables.get(&key) {
                    Some(Callable::Module(m)) => Act::Module { module: *m, args },
                    Some(Callable::Spec(s)) => Act::Spec { spec: *s, args },
                    None => {
                        self.error(
                            "E0413",
                            format!("{}/{} is neither a module nor an action", key.0, key.1),
                            a.span.clone(),
                        );
                        return None;
                    }
                }
            }
            K::BuiltinModule(b) => {
                let want = match b {
                    ast::BuiltinModule::Init => ModuleKind::Init,
                    ast::BuiltinModule::Main => ModuleKind::Main,
                    ast::BuiltinModule::Event => ModuleKind::Event,
                };
                match self.modules.iter().position(|m| m.kind == want) {
                    Some(m) => Act::Module {
                        module: m,
                        args: Vec::new(),
                    },
                    None => {
                        self.error("E0413", "that module does not exist", a.span.clone());
                        return None;
                    }
                }
            }
        };
        Some(ActionDef { kind, line })
    }
}

fn rename_literal(l: &ast::Literal, ren: &Subst) -> ast::Literal {
    let mut l = l.clone();
    match &mut l.kind {
        ast::LiteralKind::Mental { query, .. } => query.term = ren.apply(&query.term),
        ast::LiteralKind::MacroUse { args, .. } => {
            for a in args {
                a.term = ren.apply(&a.term);
            }
        }
        ast::LiteralKind::True => {}
    }
    l
}

/// True when any term of the program mentions the name `newpercept`.
fn mentions_newpercept(modules: &[ast::Module]) -> bool {
    let target = Sym::intern("newpercept");
    let mut work: Vec<Term> = Vec::new();
    for m in modules {
        work.extend(m.knowledge.iter().map(|l| l.term.clone()));
        for s in &m.action_specs {
            work.push(s.pre.term.term.clone());
        }
        if let Some(p) = &m.program {
            let mut rules: Vec<&ast::Rule> = p.rules.iter().collect();
            for d in &p.macros {
                for l in &d.body {
                    if let ast::LiteralKind::Mental { query, .. } = &l.kind {
                        work.push(query.term.clone());
                    }
                }
            }
            while let Some(r) = rules.pop() {
                for l in &r.condition {
                    if let ast::LiteralKind::Mental { query, .. } = &l.kind {
                        work.push(query.term.clone());
                    }
                }
                if let ast::RuleBody::Block(inner) = &r.body {
                    rules.extend(inner.iter());
                }
            }
        }
    }
    while let Some(t) = work.pop() {
        match &t {
            Term::Atom(a) if *a == target => return true,
            Term::Compound(c) => {
                if c.name == target {
                    return true;
                }
                work.extend(c.args.iter().cloned());
            }
            _ => {}
        }
    }
    false
}
