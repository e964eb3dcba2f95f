//! Modules as an explicit stack of frames: passes in the module's order, rule applications,
//! combos, module calls with parameters and focus, exit conditions and `exit-module`. The
//! stack can be suspended between rule applications (one action per cycle) and resumed.

use super::action::Outcome;
use super::condition::goal_literals;
use super::cycle::Core;
use super::error::{Fault, RuntimeError};
use super::goals::{Goal, GoalBase};
use super::program::{Act, Body, ModuleDef, Program};
use super::rule::{Answer, Answers};
use super::trace::{Event, TraceLevel};
use super::watch::Observed;
use crate::syntax::ast::{ExitCondition, Focus, Order};
use crate::term::{Subst, Term};
use rand::seq::SliceRandom;
use rand::Rng;

/// A module (named or a nested block) being run.
#[derive(Clone, Debug)]
pub struct ModFrame {
    /// The named module, or `None` for a nested block.
    pub module: Option<usize>,
    pub block: usize,
    pub subst: Subst,
    pub order: Vec<u32>,
    pub next: usize,
    pub pass_acted: bool,
    pub acted: bool,
    pub pushed_focus: bool,
    pub exiting: bool,
}

/// A rule application: the answers and the next one to run.
#[derive(Clone, Debug)]
pub struct RuleFrame {
    pub block: usize,
    pub rule: usize,
    pub answers: Answers,
    pub next: usize,
    pub acted: bool,
}

/// A combo being run for one answer.
#[derive(Clone, Debug)]
pub struct ComboFrame {
    pub block: usize,
    pub rule: usize,
    pub answer: Answer,
    pub next: usize,
    pub acted: bool,
}

/// One element of the execution stack.
#[derive(Clone, Debug)]
pub enum Frame {
    Module(ModFrame),
    Rule(RuleFrame),
    Combo(ComboFrame),
}

/// Why a run of the stack returned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunEnd {
    /// A cycle boundary in main context; `acted` tells whether real actions were performed.
    Suspended { acted: bool },
    /// The bottom module exited.
    Finished,
}

/// Bound on nested module calls (modules may call themselves).
pub const MAX_FRAMES: usize = 3_000;

fn is_linear(o: Order) -> bool {
    matches!(o, Order::Linear | Order::Random | Order::Adaptive)
}

/// True when each pass runs the rules in a newly drawn order.
fn is_shuffled(o: Order) -> bool {
    matches!(o, Order::Random | Order::RandomAll | Order::Adaptive)
}

impl Core {
    fn order(&mut self, prog: &Program, block: usize) -> Vec<u32> {
        let b = &prog.blocks[block];
        let mut o: Vec<u32> = (0..b.rules.len() as u32).collect();
        if is_shuffled(b.order) {
            o.shuffle(&mut self.rng);
        }
        o
    }

    /// Enters a named module: focus, beliefs, goals; returns its frame.
    pub fn enter(
        &mut self,
        prog: &Program,
        idx: usize,
        args: &[Term],
        caller: Option<(&Subst, &Answer, &[super::program::Lit])>,
    ) -> Result<ModFrame, Fault> {
        let m: &ModuleDef = &prog.modules[idx];
        let mut subst = Subst::new();
        if let Some((cs, _, _)) = caller {
            for (p, a) in m.params.iter().zip(args) {
                if !subst.unify(p, &cs.apply(a), false) {
                    return Err(Fault::new(format!(
                        "module {} cannot take these arguments",
                        m.name
                    )));
                }
            }
        }
        let pushed_focus = match (m.focus, caller) {
            (Focus::None, _) | (_, None) => false,
            (Focus::New, _) => {
                self.ms.attention.push(GoalBase::default());
                true
            }
            (Focus::Select, Some((_, ans, _))) => {
                // The goal picked may differ next time: not a settled state.
                self.unsettled |= ans.goals.len() > 1;
                let mut base = GoalBase::default();
                if !ans.goals.is_empty() {
                    let i = self.rng.gen_range(0..ans.goals.len());
                    base.add(ans.goals[i].clone());
                }
                self.ms.attention.push(base);
                true
            }
            (Focus::Filter, Some((cs, _, lits))) => {
                let mut base = GoalBase::default();
                for g in goal_literals(lits, cs) {
                    if g.is_ground() && !self.ms.believes(&g)? {
                        base.add(Goal::new(g));
                    }
                }
                self.ms.attention.push(base);
                true
            }
        };
        self.event(Event::ModuleEntered {
            module: m.name.clone(),
        });
        if pushed_focus {
            self.attention_pushed(&m.name, m.focus);
        }
        self.watch(Observed::ModuleEntered(&m.name));
        let mut ev = Vec::new();
        let before = self.ms.beliefs.len();
        for b in &m.beliefs {
            self.ms.update(b, true, &mut ev)?;
        }
        self.unsettled |= self.ms.beliefs.len() != before;
        self.changes(ev);
        for g in &m.goals {
            let g = subst.apply(g);
            if !g.is_ground() {
                return Err(Fault::new(format!(
                    "goal {g} of module {} is not ground",
                    m.name
                )));
            }
            self.adopt(&g, false)?;
        }
        let order = self.order(prog, m.block);
        Ok(ModFrame {
            module: Some(idx),
            block: m.block,
            subst,
            order,
            next: 0,
            pass_acted: false,
            acted: false,
            pushed_focus,
            exiting: false,
        })
    }

    /// Runs the stack until a cycle boundary (main context only) or until it is empty.
    pub fn run(
        &mut self,
        prog: &Program,
        stack: &mut Vec<Frame>,
        main_ctx: bool,
    ) -> Result<RunEnd, RuntimeError> {
        let mut steps: u64 = 0;
        // Set by an iteration that only evaluated a rule which found no answers: the next
        // iteration sees the mental state that rule saw, so kept goal answers stay valid.
        let mut quiet = false;
        // The rules of the top frame's block (bit `i`: rule `i`) that `rule_inapplicable` passed
        // over since the last iteration that could change what it reads (see `Unchanged`).
        let mut passed = Unchanged::default();
        loop {
            if !std::mem::take(&mut quiet) {
                self.ms.goal_memo.get_mut().clear();
            }
            passed.step();
            steps += 1;
            // The clock is read every 64 steps only: a step is cheap, reading the clock not.
            if steps.is_multiple_of(64) {
                self.check_deadline()
                    .map_err(|e| self.error(prog, running_rule(prog, stack), e))?;
            }
            if steps > self.max_steps {
                return Err(self.error(
                    prog,
                    None,
                    Fault::new("step budget exceeded (a module loops without end)"),
                ));
            }
            if stack.len() > MAX_FRAMES {
                return Err(self.error(prog, None, Fault::new("module calls nest too deeply")));
            }
            let Some(top) = stack.last_mut() else {
                return Ok(RunEnd::Finished);
            };
            match top {
                Frame::Module(f) => {
                    if f.exiting {
                        if self.exit_frame(prog, stack)? {
                            return Ok(RunEnd::Finished);
                        }
                        continue;
                    }
                    let block = &prog.blocks[f.block];
                    if f.next < f.order.len() {
                        let ri = f.order[f.next] as usize;
                        f.next += 1;
                        let b = f.block;
                        let rule = &block.rules[ri];
                        if self.why.is_some() {
                            self.why_evaluating(prog, stack, b, ri);
                        }
                        // The module's substitution is lent to the evaluation, not cloned
                        // (`stack` is not `self`'s).
                        let Some(Frame::Module(f)) = stack.last() else {
                            continue;
                        };
                        // Passed over without an evaluation: no answers to make or drop.
                        if passed.again(ri) {
                            self.evaluated(rule, 0);
                            quiet = true;
                            continue;
                        }
                        if self.rule_inapplicable(rule, &f.subst) {
                            passed.mark(ri);
                            quiet = true;
                            continue;
                        }
                        // Kept goal answers are read and made only while `goal why` is off.
                        self.ms.goal_memo.get_mut().live = self.why.is_none();
                        let answers = self.rule_answers(rule, &f.subst, &prog.file);
                        self.ms.goal_memo.get_mut().live = false;
                        let answers =
                            answers.map_err(|e| self.error(prog, Some((b, ri, rule.line)), e))?;
                        quiet = answers.is_empty();
                        if !answers.is_empty() {
                            stack.push(Frame::Rule(RuleFrame {
                                block: b,
                                rule: ri,
                                answers,
                                next: 0,
                                acted: false,
                            }));
                        }
                        continue;
                    }
                    // End of a pass: exit or start another one.
                    let exit = match f.module {
                        None => true,
                        Some(m) => match prog.modules[m].exit {
                            ExitCondition::Always => true,
                            ExitCondition::Never => false,
                            ExitCondition::NoGoals => self.ms.attention.current().is_empty(),
                            ExitCondition::NoAction => !f.pass_acted,
                        },
                    };
                    if exit {
                        f.exiting = true;
                        continue;
                    }
                    let idle = !f.pass_acted;
                    let b = f.block;
                    f.next = 0;
                    f.pass_acted = false;
                    // Another pass of the same frame: nothing `rule_inapplicable` reads changes.
                    passed.keep();
                    // A fixed order stays as it is; a random one is drawn again.
                    if is_shuffled(prog.blocks[b].order) {
                        let order = self.order(prog, b);
                        if let Some(Frame::Module(f)) = stack.last_mut() {
                            f.order = order;
                        }
                    }
                    if main_ctx && idle {
                        return Ok(RunEnd::Suspended { acted: false });
                    }
                }
                Frame::Rule(r) => {
                    let rule = &prog.blocks[r.block].rules[r.rule];
                    let done = (r.acted && rule.kind == super::program::RuleKind::If)
                        || r.next >= r.answers.len();
                    if done {
                        let acted = r.acted;
                        stack.pop();
                        propagate(stack, acted);
                        if let Some(Frame::Module(m)) = stack.last_mut() {
                            if acted && is_linear(prog.blocks[m.block].order) {
                                m.next = m.order.len();
                            }
                        }
                        if main_ctx && acted {
                            return Ok(RunEnd::Suspended { acted: true });
                        }
                        continue;
                    }
                    // Each answer is used once: move it out instead of cloning (the last one
                    // popped: no placeholder left to drop with the frame).
                    let last = r.next + 1 == r.answers.len();
                    let popped = if last { r.answers.pop() } else { None };
                    let answer = popped.unwrap_or_else(|| {
                        std::mem::replace(
                            &mut r.answers[r.next],
                            Answer {
                                subst: Subst::new(),
                                goals: Vec::new(),
                            },
                        )
                    });
                    r.next += 1;
                    let (b, ri) = (r.block, r.rule);
                    self.fired(rule, &answer.subst);
                    if self.why.is_some() {
                        self.why_fired(prog, stack, (b, ri), &answer.subst);
                    }
                    match &rule.body {
                        Body::Combo(_) => stack.push(Frame::Combo(ComboFrame {
                            block: b,
                            rule: ri,
                            answer,
                            next: 0,
                            acted: false,
                        })),
                        Body::Block(inner) => {
                            let order = self.order(prog, *inner);
                            stack.push(Frame::Module(ModFrame {
                                module: None,
                                block: *inner,
                                subst: answer.subst,
                                order,
                                next: 0,
                                pass_acted: false,
                                acted: false,
                                pushed_focus: false,
                                exiting: false,
                            }))
                        }
                    }
                }
                Frame::Combo(c) => {
                    let rule = &prog.blocks[c.block].rules[c.rule];
                    let Body::Combo(actions) = &rule.body else {
                        stack.pop();
                        continue;
                    };
                    if c.next >= actions.len() {
                        let acted = c.acted;
                        self.ms.mailbox.settle();
                        stack.pop();
                        propagate(stack, acted);
                        continue;
                    }
                    let a = &actions[c.next];
                    c.next += 1;
                    let loc = Some((c.block, c.rule, a.line));
                    // Only sends and deletes run with `sent/2` facts held back.
                    if !matches!(a.kind, Act::Send { .. } | Act::Delete(_)) {
                        self.ms.mailbox.settle();
                    }
                    match &a.kind {
                        Act::ExitModule => {
                            self.event(Event::ActionPerformed {
                                action: "exit-module".into(),
                            });
                            exit_module(stack);
                        }
                        Act::Module { module, args } => {
                            // The combo frame is lent, not cloned (`stack` is not `self`'s).
                            let answer = Some((&c.answer.subst, &c.answer, &rule.cond[..]));
                            let f = self
                                .enter(prog, *module, args, answer)
                                .map_err(|e| self.error(prog, loc, e))?;
                            stack.push(Frame::Module(f));
                        }
                        act => {
                            // The answer's substitution is lent to the action, not cloned.
                            let s = &c.answer.subst;
                            let sent = self.out.env_actions.len();
                            let outcome = self
                                .perform(prog, act, s)
                                .and_then(|o| self.check_sizes().map(|_| o))
                                .map_err(|e| {
                                    self.ms.mailbox.settle();
                                    self.error(prog, loc, e)
                                })?;
                            for _ in sent..self.out.env_actions.len() {
                                let at = self.error(prog, loc, Fault::new(""));
                                self.out.env_sites.push(at);
                            }
                            match outcome {
                                Outcome::NotRun => {
                                    if self.why.is_some() {
                                        let (at, s) = ((c.block, c.rule), s.clone());
                                        self.why_not_run(prog, stack, at, act, &s);
                                    }
                                    if let Some(Frame::Combo(c)) = stack.last_mut() {
                                        c.next = usize::MAX;
                                    }
                                }
                                Outcome::Done { real } => {
                                    if let Some(Frame::Combo(c)) = stack.last_mut() {
                                        c.acted |= real;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Pops the exiting module frame on top of `stack` and leaves it; true when it was the
    /// bottom frame. Out of line: the module loop runs it once per module left.
    #[inline(never)]
    fn exit_frame(&mut self, prog: &Program, stack: &mut Vec<Frame>) -> Result<bool, RuntimeError> {
        let Some(Frame::Module(f)) = stack.pop() else {
            return Ok(stack.is_empty());
        };
        self.leave(prog, &f).map_err(|e| match f.module {
            Some(m) => self.module_error(prog, m, e),
            None => self.error(prog, None, e),
        })?;
        if stack.is_empty() {
            return Ok(true);
        }
        propagate(stack, f.acted);
        Ok(false)
    }

    /// Leaves every frame of `stack` from the top (a task stopped from outside): named modules
    /// restore their focus and report their exit.
    pub fn unwind(&mut self, prog: &Program, stack: &mut Vec<Frame>) -> Result<(), Fault> {
        while let Some(f) = stack.pop() {
            if let Frame::Module(m) = f {
                self.leave(prog, &m)?;
            }
        }
        Ok(())
    }

    /// Records the attention set just pushed for `module` (with the goals it starts with).
    fn attention_pushed(&mut self, module: &str, focus: Focus) {
        if self.level < TraceLevel::Changes {
            return;
        }
        let focus = match focus {
            Focus::None => "none",
            Focus::New => "new",
            Focus::Select => "select",
            Focus::Filter => "filter",
        };
        let set = self.ms.attention.current();
        let goals = set.goals().iter().map(|g| g.term.to_string()).collect();
        self.event(Event::AttentionPushed {
            module: module.to_string(),
            focus: focus.to_string(),
            attention: self.ms.attention.depth() - 1,
            goals,
        });
    }

    /// Leaves a named module: defocus and goal check.
    fn leave(&mut self, prog: &Program, f: &ModFrame) -> Result<(), Fault> {
        if let Some(m) = f.module {
            if f.pushed_focus {
                self.event(Event::AttentionPopped {
                    module: prog.modules[m].name.clone(),
                    attention: self.ms.attention.depth() - 1,
                });
                self.ms.attention.pop();
                self.check_goals()?;
            }
            self.event(Event::ModuleExited {
                module: prog.modules[m].name.clone(),
            });
            self.watch(Observed::ModuleExited(&prog.modules[m].name));
        }
        Ok(())
    }

    /// A runtime error located at a module head.
    #[cold]
    #[inline(never)]
    pub fn module_error(&self, prog: &Program, module: usize, f: Fault) -> RuntimeError {
        let mut e = self.error(prog, None, f);
        e.line = prog.modules.get(module).map_or(0, |m| m.line);
        e.rule = prog
            .modules
            .get(module)
            .map(|m| format!("module {}", m.name));
        e
    }

    /// A runtime error with file, line and rule (out of line: the module loop then inlines
    /// less that runs only on an error, and keeps fewer values at hand for every step).
    #[cold]
    #[inline(never)]
    pub fn error(
        &self,
        prog: &Program,
        loc: Option<(usize, usize, usize)>,
        f: Fault,
    ) -> RuntimeError {
        let (rule, line) = match loc {
            Some((b, r, line)) => (Some(prog.blocks[b].rules[r].label.to_string()), line),
            None => (None, 0),
        };
        RuntimeError {
            file: prog.file.clone(),
            line,
            rule,
            message: f.message,
            binding: f.binding,
        }
    }
}

/// The rules of the top frame's block that [`Core::rule_inapplicable`] passed over while
/// nothing it reads changed, so each would be passed over again.
///
/// Exact: `rule_inapplicable` is a function of the mental state, the rule and the frame's
/// substitution alone (it draws no random number, reads no clock, changes nothing). The set is
/// kept only across iterations of the module loop that pass over a rule (which read only) or
/// end a pass of the same frame and start another (which changes the frame's position and,
/// for a shuffled order, draws a new order, neither of which it reads); every other iteration
/// (an evaluation, an action, a frame pushed or popped, a cycle boundary: `run` returns) drops
/// it. `goal why` never sees a rule passed over this way (`rule_inapplicable` passes over
/// nothing while it records, so no bit is set).
#[derive(Default)]
struct Unchanged {
    rules: u64,
    kept: bool,
}

impl Unchanged {
    /// Starts a loop iteration: the set survives only if the last iteration kept it.
    #[inline(always)]
    fn step(&mut self) {
        if !std::mem::take(&mut self.kept) {
            self.rules = 0;
        }
    }

    /// This iteration changes nothing `rule_inapplicable` reads.
    #[inline(always)]
    fn keep(&mut self) {
        self.kept = true;
    }

    /// Records that rule `i` was passed over (rules past the 64th are not remembered).
    #[inline(always)]
    fn mark(&mut self, i: usize) {
        if i < 64 {
            self.rules |= 1 << i;
        }
        self.kept = true;
    }

    /// True when rule `i` was passed over with nothing changed since (and keeps the set).
    #[inline(always)]
    fn again(&mut self, i: usize) -> bool {
        let again = i < 64 && self.rules & (1 << i) != 0;
        self.kept |= again;
        again
    }
}

/// The rule being run on top of `stack` (block, rule, line), for locating an error raised
/// between steps.
fn running_rule(prog: &Program, stack: &[Frame]) -> Option<(usize, usize, usize)> {
    let (b, r) = stack.iter().rev().find_map(|f| match f {
        Frame::Rule(r) => Some((r.block, r.rule)),
        Frame::Combo(c) => Some((c.block, c.rule)),
        Frame::Module(_) => None,
    })?;
    Some((b, r, prog.blocks.get(b)?.rules.get(r)?.line))
}

/// Passes a child's "performed a real action" result to its parent frame.
fn propagate(stack: &mut [Frame], acted: bool) {
    match stack.last_mut() {
        Some(Frame::Combo(c)) => c.acted |= acted,
        Some(Frame::Rule(r)) => r.acted |= acted,
        Some(Frame::Module(m)) => {
            m.pass_acted |= acted;
            m.acted |= acted;
        }
        None => {}
    }
}

/// `exit-module`: unwinds to the innermost named module and marks it as exiting.
fn exit_module(stack: &mut Vec<Frame>) {
    while let Some(top) = stack.last_mut() {
        if let Frame::Module(m) = top {
            if m.module.is_some() {
                m.exiting = true;
                return;
            }
        }
        let acted = match stack.pop() {
            Some(Frame::Combo(c)) => c.acted,
            Some(Frame::Rule(r)) => r.acted,
            Some(Frame::Module(m)) => m.acted,
            None => false,
        };
        propagate(stack, acted);
    }
}

#[cfg(test)]
mod tests {
    use crate::agent::cycle::{Agent, AgentConfig};
    use crate::agent::program::Program;

    /// What the agent of `src` prints in its first cycle.
    fn first_cycle_prints(src: &str) -> Vec<String> {
        let prog = Program::from_source("t.goal", src).expect("compiles");
        let mut a = Agent::new(prog, "a", AgentConfig::default());
        let out = a.step(&[], &[]);
        assert!(a.stopped().is_none(), "{:?}", a.stopped());
        out.printed
    }

    #[test]
    fn a_rule_passed_over_is_looked_at_again_once_an_action_changed_the_state() {
        // The init module runs `m` to its end within one cycle: its first pass passes over
        // the first rule (no `p` yet) and inserts `p`; the next pass must look at the first
        // rule again, not remember it as passed over.
        let out = first_cycle_prints(
            "init module { program { if true then m. } }
             module m [exit=noaction] { program [order=linear] {
                if bel(p) then print(got) + exit-module.
                if not(bel(p)) then insert(p).
             } }
             main module { program { if true then print(main). } }",
        );
        assert_eq!(out.first().map(String::as_str), Some("got"), "{out:?}");
    }

    #[test]
    fn a_forall_rule_runs_its_body_for_each_answer_in_order() {
        // Answers are moved out of the rule frame one by one, the last one popped: the body
        // still runs for each answer once, in the condition's order.
        let out = first_cycle_prints(
            "init module { beliefs { f(1). f(2). f(3). } program [order=linearall] {
                forall bel(f(X)) do print(X).
                if bel(f(1)) then print(last).
             } }
             main module { program { if true then print(main). } }",
        );
        assert_eq!(out, ["1", "2", "3", "last", "main"]);
    }

    #[test]
    fn rules_passed_over_after_an_action_are_passed_over_in_the_next_pass() {
        // The first pass deletes `todo(1)`, then passes over the other two rules; the next
        // pass passes over all three (the last two from what the first pass found) and `m`
        // exits with nothing more done.
        let out = first_cycle_prints(
            "init module { beliefs { todo(1). } program { if true then m + print(back). } }
             module m [exit=noaction] { program [order=linearall] {
                if bel(todo(X)) then delete(todo(X)).
                if bel(q(X)) then print(X).
                if bel(todo(X)) then print(again).
             } }
             main module { program { if true then print(main). } }",
        );
        assert_eq!(out, ["back", "main"]);
    }
}
