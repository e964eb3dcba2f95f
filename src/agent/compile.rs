//! Compiling the AST into a [`Program`]: module options and defaults, macro expansion with
//! variable renaming, name/arity resolution of actions and module calls, action specs renamed
//! apart from rule variables.

use super::kr_bridge::{load_knowledge, Knowledge};
use super::mentions::{uses_sessions, Parts};
use super::program::*;
use crate::diag::{line_col, Diagnostic, Span};
use crate::syntax::ast::{self, ExitCondition, Focus, Order};
use crate::term::{Subst, Sym, Term};
use std::collections::BTreeMap;
use std::sync::Arc;

#[derive(Clone, Copy)]
/// One module to compile with the file it was read from (its spans refer to `source`).
pub(crate) struct Unit<'s> {
    pub file: &'s str,
    pub source: &'s str,
    pub module: &'s ast::Module,
}

/// Compiles a parsed program with the modules of its imported `.mod2g` files and extra
/// knowledge clauses (from imported `.pl` files).
pub(crate) fn compile<'s>(
    ast: &'s ast::AgentProgram,
    source: &'s str,
    imported: &[Unit<'s>],
    extra_knowledge: &[Term],
) -> Result<Arc<Program>, Vec<Diagnostic>> {
    let c = Compiler {
        file: ast.file.clone(),
        source,
        errors: Vec::new(),
        warnings: Vec::new(),
        macros: BTreeMap::new(),
        local_macros: BTreeMap::new(),
        fresh: 0,
        blocks: Vec::new(),
        modules: Vec::new(),
        specs: Vec::new(),
        callables: BTreeMap::new(),
        select_modules: Vec::new(),
        nested_order: Order::LinearAll,
    };
    let mut units: Vec<Unit<'s>> = ast
        .modules
        .iter()
        .map(|module| Unit {
            file: &ast.file,
            source,
            module,
        })
        .collect();
    units.extend(imported.iter().copied());
    c.run(ast, &units, extra_knowledge)
}

type MacroDef = (Vec<Term>, Vec<ast::Literal>);

pub(crate) struct Compiler<'s> {
    file: String,
    source: &'s str,
    errors: Vec<Diagnostic>,
    warnings: Vec<Diagnostic>,
    /// Macros of all modules: the first definition of each name/arity.
    macros: BTreeMap<(String, usize), MacroDef>,
    /// Macros of the module being compiled: they come before those of other modules.
    local_macros: BTreeMap<(String, usize), MacroDef>,
    fresh: u64,
    blocks: Vec<Block>,
    modules: Vec<ModuleDef>,
    specs: Vec<SpecDef>,
    callables: BTreeMap<(String, usize), Callable>,
    select_modules: Vec<usize>,
    /// Order of nested blocks in the module being compiled.
    nested_order: Order,
}

/// The program's macros and callables (modules and action specs by name/arity), kept in the
/// program to compile code from outside it ([`extend`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Names {
    macros: BTreeMap<(String, usize), MacroDef>,
    callables: BTreeMap<(String, usize), Callable>,
}

#[derive(Clone, Copy, Debug)]
enum Callable {
    Module(usize),
    Spec(usize),
}

const MAX_MACRO_DEPTH: usize = 32;

impl<'s> Compiler<'s> {
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

    /// Makes diagnostics and line numbers refer to the file of `u`.
    fn enter(&mut self, u: &Unit<'s>) {
        self.file = u.file.to_string();
        self.source = u.source;
    }

    /// Makes diagnostics refer to the program's own file again.
    fn leave(&mut self, ast: &ast::AgentProgram, source: &'s str) {
        self.file = ast.file.clone();
        self.source = source;
    }

    /// The macros of one module, first definition of each name/arity.
    fn module_macros(m: &ast::Module) -> BTreeMap<(String, usize), MacroDef> {
        let mut out = BTreeMap::new();
        if let Some(p) = &m.program {
            for d in &p.macros {
                let key = (d.name.name.name().to_string(), d.params.len());
                let params = d.params.iter().map(|l| l.term.clone()).collect();
                out.entry(key).or_insert((params, d.body.clone()));
            }
        }
        out
    }

    fn run(
        mut self,
        ast: &ast::AgentProgram,
        units: &[Unit<'s>],
        extra: &[Term],
    ) -> Result<Arc<Program>, Vec<Diagnostic>> {
        // Knowledge of every module forms one base; action specs are global; a macro is looked
        // up in its own module first, then in the others (first definition wins).
        let main_source = self.source;
        let mut clauses = extra.to_vec();
        for u in units {
            self.enter(u);
            let m = u.module;
            clauses.extend(m.knowledge.iter().map(|l| l.term.clone()));
            for (k, v) in Self::module_macros(m) {
                self.macros.entry(k).or_insert(v);
            }
            for s in &m.action_specs {
                self.add_spec(s);
            }
        }
        self.leave(ast, main_source);
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
        for u in units {
            self.enter(u);
            self.register(u.module);
        }
        for (idx, u) in units.iter().enumerate() {
            self.enter(u);
            self.local_macros = Self::module_macros(u.module);
            self.module_block(idx, u.module);
        }
        self.local_macros.clear();
        self.leave(ast, main_source);
        self.finish(ast, knowledge)
    }

    /// Adds module `m` (not yet its rules) and its name/arity.
    fn register(&mut self, m: &ast::Module) {
        let idx = self.modules.len();
        let (kind, params) = match &m.kind {
            ast::ModuleKind::Init => (ModuleKind::Init, Vec::new()),
            ast::ModuleKind::Main => (ModuleKind::Main, Vec::new()),
            ast::ModuleKind::Event => (ModuleKind::Event, Vec::new()),
            ast::ModuleKind::Shutdown => (ModuleKind::Shutdown, Vec::new()),
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

    /// Compiles the rules of module number `idx`.
    fn module_block(&mut self, idx: usize, m: &ast::Module) {
        let kind = self.modules[idx].kind;
        let default = match kind {
            ModuleKind::Init | ModuleKind::Event | ModuleKind::Shutdown => Order::LinearAll,
            _ => Order::Linear,
        };
        let (order, rules) = match &m.program {
            Some(p) => (p.order.as_ref().map_or(default, |o| o.value), &p.rules[..]),
            None => (default, &[][..]),
        };
        self.nested_order = m
            .program
            .as_ref()
            .and_then(|p| p.nested_order)
            .unwrap_or(Order::LinearAll);
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

    fn finish(
        mut self,
        ast: &ast::AgentProgram,
        knowledge: Arc<Knowledge>,
    ) -> Result<Arc<Program>, Vec<Diagnostic>> {
        let find = |k: ModuleKind, mods: &[ModuleDef]| mods.iter().position(|m| m.kind == k);
        let init = find(ModuleKind::Init, &self.modules);
        let event = find(ModuleKind::Event, &self.modules);
        let shutdown = find(ModuleKind::Shutdown, &self.modules);
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
        let uses_models = uses_models(&self.blocks);
        let uses_sessions = uses_sessions(&Parts {
            modules: &self.modules,
            blocks: &self.blocks,
            specs: &self.specs,
            knowledge: knowledge.source(),
            conditions: &[],
        });
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
            shutdown,
            warnings: self.warnings,
            names: Names {
                macros: self.macros,
                callables: self.callables,
            },
            uses_newpercept: mentions_newpercept(&ast.modules),
            uses_models,
            uses_sessions,
            channels: false,
        }))
    }

    /// The exit condition and focus of a module. Options that do not apply to the kind of
    /// module are ignored here; the validator warns about them (W0108, W0109).
    fn options(&mut self, m: &ast::Module, kind: ModuleKind) -> (ExitCondition, Focus) {
        let exit = m.options.exit.as_ref();
        let focus = m.options.focus.as_ref();
        match kind {
            ModuleKind::Init | ModuleKind::Event | ModuleKind::Shutdown => {
                (ExitCondition::Always, Focus::None)
            }
            ModuleKind::Main => (exit.map_or(ExitCondition::Never, |e| e.value), Focus::None),
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
                let mut acts: Vec<_> = actions.iter().filter_map(|a| self.action(a)).collect();
                super::message::link_sent_deletes(&mut acts);
                Body::Combo(acts)
            }
            ast::RuleBody::Block(rules) => {
                Body::Block(self.block(module, rules, self.nested_order))
            }
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
            file: self.file.as_str().into(),
            text: super::why::rule_text(self.source, r).into(),
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
                    let top_level = selector.kind == ast::SelectorKind::SelfAgent;
                    let about = match &selector.kind {
                        ast::SelectorKind::This | ast::SelectorKind::SelfAgent => None,
                        ast::SelectorKind::All => Some(About::All),
                        ast::SelectorKind::AllOther => Some(About::AllOther),
                        ast::SelectorKind::Some => Some(About::Some),
                        ast::SelectorKind::SomeOther => Some(About::SomeOther),
                        ast::SelectorKind::Agents(ts) => {
                            Some(About::Agents(ts.iter().map(|t| s.apply(&t.term)).collect()))
                        }
                    };
                    out.push(Lit::Mental {
                        negated: *negated,
                        top_level,
                        about,
                        op: *op,
                        query: s.apply(&query.term),
                        plan: Default::default(),
                    });
                }
                ast::LiteralKind::MacroUse { name, args } => {
                    let key = (name.name.name().to_string(), args.len());
                    let found = self.local_macros.get(&key).or(self.macros.get(&key));
                    let Some((params, body)) = found.cloned() else {
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
                Act::Delete(Deletion::new(content.term.clone()))
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
            K::Timing { op, args } => Act::Timing {
                op: *op,
                args: args.iter().map(|l| l.term.clone()).collect(),
            },
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

/// True when some rule condition queries other agents' mental models.
fn uses_models(blocks: &[Block]) -> bool {
    blocks
        .iter()
        .flat_map(|b| b.rules.iter())
        .any(|r| about_others(&r.cond))
}

/// True when a condition queries other agents' mental models.
fn about_others(cond: &[Lit]) -> bool {
    cond.iter()
        .any(|l| matches!(l, Lit::Mental { about: Some(_), .. }))
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

/// Compiles action sequences (one extra block each) and conditions from outside `prog` (see
/// [`Program::extend`]).
pub(crate) fn extend(
    prog: &Program,
    file: &str,
    source: &str,
    combos: &[Vec<ast::Action>],
    conditions: &[Vec<ast::Literal>],
) -> Result<Extension, Vec<Diagnostic>> {
    let mut c = Compiler {
        file: file.to_string(),
        source,
        errors: Vec::new(),
        warnings: Vec::new(),
        macros: prog.names.macros.clone(),
        local_macros: BTreeMap::new(),
        // Renamed macro variables must not meet the program's own.
        fresh: 1 << 32,
        blocks: prog.blocks.clone(),
        modules: prog.modules.clone(),
        specs: prog.specs.clone(),
        callables: prog.names.callables.clone(),
        select_modules: Vec::new(),
        nested_order: Order::LinearAll,
    };
    let mut blocks = Vec::new();
    for combo in combos {
        let mut rules = Vec::new();
        for a in combo {
            let line = c.line(&a.span);
            if let Some(def) = c.action(a) {
                rules.push(RuleDef {
                    kind: RuleKind::If,
                    cond: vec![Lit::True],
                    body: Body::Combo(vec![def]),
                    label: format!("test:{line}").into(),
                    line,
                    file: file.into(),
                    text: super::why::one_line(source.get(a.span.clone()).unwrap_or("")).into(),
                    per_goal: false,
                });
            }
        }
        blocks.push(c.blocks.len());
        c.blocks.push(Block {
            rules,
            order: Order::LinearAll,
        });
    }
    let mut conds = Vec::new();
    for lits in conditions {
        let mut out = Vec::new();
        c.literals(lits, &Subst::new(), 0, &mut out);
        conds.push(out);
    }
    if !c.errors.is_empty() {
        return Err(c.errors);
    }
    let uses_sessions = prog.uses_sessions
        || uses_sessions(&Parts {
            modules: &c.modules,
            blocks: &c.blocks,
            specs: &c.specs,
            knowledge: &[],
            conditions: &conds,
        });
    Ok(Extension {
        program: Arc::new(Program {
            file: prog.file.clone(),
            source: prog.source.clone(),
            knowledge: prog.knowledge.clone(),
            modules: c.modules,
            blocks: c.blocks,
            specs: c.specs,
            init: prog.init,
            main: prog.main,
            event: prog.event,
            shutdown: prog.shutdown,
            warnings: Vec::new(),
            uses_newpercept: prog.uses_newpercept,
            channels: prog.channels,
            // A test condition about other agents needs their models kept too.
            uses_models: prog.uses_models || conds.iter().any(|c| about_others(c)),
            uses_sessions,
            names: prog.names.clone(),
        }),
        blocks,
        conditions: conds,
    })
}
