//! Mental-state conditions: `bel`, `goal`, `a-goal`, `goal-a`, `not(...)` and `true`, evaluated
//! left to right into a duplicate-free list of answers (macros are expanded at compile time).

use super::error::Fault;
use super::goals::Goal;
use super::mental_state::{GoalQuery, MentalState};
use super::program::Lit;
use crate::syntax::ast::MentalOp;
use crate::term::{well_known as wk, Subst, Sym, Term};
use smallvec::{smallvec, SmallVec};
use std::sync::Arc;

/// Extends `base` with the bindings of `answer`.
pub fn compose(base: &Subst, answer: &Subst) -> Subst {
    base.extended(answer)
}

/// The answers of a literal or a condition: mostly none or one, kept inline.
pub type Found = super::conjunction::Answers;

mod answer_set;

use answer_set::AnswerSet;

/// Evaluation context of a condition.
pub struct CondCtx<'a> {
    pub ms: &'a MentalState,
    /// Restrict `this`-goals to this single goal (focus=select evaluation).
    pub only: Option<&'a Goal>,
}

/// All answers of the condition `lits` extending `base`.
pub fn eval(cx: &CondCtx<'_>, lits: &[Lit], base: &Subst) -> Result<Vec<Subst>, Fault> {
    Ok(eval_upto(cx, lits, base, usize::MAX)?.0)
}

/// The first `cap` answers of the condition `lits` extending `base`, and whether the
/// evaluation stopped at `cap` (each literal's queries stop there too, so a generator with
/// infinitely many answers ends cheaply).
pub fn eval_upto(
    cx: &CondCtx<'_>,
    lits: &[Lit],
    base: &Subst,
    cap: usize,
) -> Result<(Vec<Subst>, bool), Fault> {
    let e = evaluate(cx, lits, base, cap)?;
    Ok((e.answers.into_vec(), e.cut))
}

/// A condition evaluated: its answers, whether `cap` cut them, and where it failed.
pub struct Evaluation {
    pub answers: Found,
    pub cut: bool,
    /// The first literal without answers (its index) and the answers of the literals before
    /// it; `None` when the condition holds. Those answers are left out (empty) when they were
    /// kept goal answers, which are kept only while `goal why` does not record.
    pub failed: Option<(usize, Found)>,
}

/// [`eval_upto`], also telling which literal failed (`goal why` shows it; costs nothing more:
/// the answers before the failing literal are handed back instead of dropped).
pub fn evaluate(
    cx: &CondCtx<'_>,
    lits: &[Lit],
    base: &Subst,
    cap: usize,
) -> Result<Evaluation, Fault> {
    if let ([lit], true) = (lits, base.is_empty()) {
        return evaluate_one(cx, lit, base, cap);
    }
    let mut cut = false;
    let mut answers = Found::new();
    let mut start = 0;
    if let Some(kept) = kept_first(cx, lits, base) {
        // The first level is the kept answers (the first `cap`), read in place.
        let level = &kept[..kept.len().min(cap)];
        cut |= kept.len() > cap;
        if level.is_empty() {
            return Ok(Evaluation {
                answers: Found::new(),
                cut,
                failed: Some((0, smallvec![base.clone()])),
            });
        }
        let next = next_level(cx, &lits[1], Thetas::Kept(level), cap, &mut cut)?;
        if next.items.is_empty() {
            return Ok(Evaluation {
                answers: Found::new(),
                cut,
                failed: Some((1, Found::new())),
            });
        }
        answers = next.items;
        start = 2;
    }
    // The first literal's only theta: `base` (mostly empty, so a copy costs nothing).
    let mut first = [base.clone()];
    for (i, lit) in lits.iter().enumerate().skip(start) {
        let level: &mut [Subst] = match i {
            0 => &mut first,
            _ => &mut answers,
        };
        let next = next_level(cx, lit, Thetas::Own(level), cap, &mut cut)?;
        if next.items.is_empty() {
            let before = match i {
                0 => smallvec![base.clone()],
                _ => answers,
            };
            return Ok(Evaluation {
                answers: Found::new(),
                cut,
                failed: Some((i, before)),
            });
        }
        answers = next.items;
    }
    if lits.is_empty() {
        answers.push(base.clone());
    }
    Ok(Evaluation {
        answers,
        cut,
        failed: None,
    })
}

/// The answers of the first literal of `lits` (of two or more) kept in, or now put into, the
/// goal memo: when the memo is live, `base` is empty and the literal is a positive `a-goal` or
/// `goal-a` about this agent's goals (no single-goal restriction) that its goal facts decide
/// (see `GoalMemo` for why the kept answers are exact). `None`: evaluate it as usual.
fn kept_first(cx: &CondCtx<'_>, lits: &[Lit], base: &Subst) -> Option<Arc<Found>> {
    let [Lit::Mental {
        negated: false,
        top_level,
        about: None,
        op: op @ (MentalOp::AGoal | MentalOp::GoalA),
        query,
        ..
    }, _, ..] = lits
    else {
        return None;
    };
    let ms = cx.ms;
    if !base.is_empty() || cx.only.is_some() || !ms.goal_memo.borrow().live {
        return None;
    }
    if let Some(kept) = ms.goal_memo.borrow().get(*op, *top_level, query) {
        return Some(kept);
    }
    // As `literal` under the empty substitution, when `goal_fact_answers` decides.
    let gq = GoalQuery::new(&ms.knowledge, query);
    let b = match top_level {
        true => ms.attention.top_level(),
        false => ms.attention.current(),
    };
    let mut raw = AnswerSet::default();
    if !goal_fact_answers(ms, b, &gq, *op == MentalOp::GoalA, &mut raw) {
        return None;
    }
    let kept = Arc::new(raw.items);
    ms.goal_memo
        .borrow_mut()
        .put(*op, *top_level, query, kept.clone());
    Some(kept)
}

/// The thetas of a condition level.
enum Thetas<'a> {
    /// The condition's own: the last answer under a theta may take that theta.
    Own(&'a mut [Subst]),
    /// Kept goal answers (the goal memo's), read in place.
    Kept(&'a [Subst]),
}

impl Thetas<'_> {
    fn all(&self) -> &[Subst] {
        match self {
            Thetas::Own(l) => l,
            Thetas::Kept(l) => l,
        }
    }

    /// Theta `k` taken, when it is the condition's own (it is not needed again).
    fn take(&mut self, k: usize) -> Option<Subst> {
        match self {
            Thetas::Own(l) => Some(std::mem::take(&mut l[k])),
            Thetas::Kept(_) => None,
        }
    }
}

/// The distinct answers of `lit` under each theta of `level`, each extending its theta, at
/// most `cap` (`cut` is set when more were found or a query stopped there).
fn next_level(
    cx: &CondCtx<'_>,
    lit: &Lit,
    mut level: Thetas<'_>,
    cap: usize,
    cut: &mut bool,
) -> Result<AnswerSet, Fault> {
    let mut next = AnswerSet::default();
    let bound = bound_by_any(level.all());
    // A planned `bel` literal runs its plan under each theta into one buffer.
    let batch = planned(cx, lit);
    let mut found = Found::new();
    'each: for k in 0..level.all().len() {
        let theta = &level.all()[k];
        match batch
            .as_ref()
            .and_then(|b| b.answers_into(theta, cap, &mut found))
        {
            Some(stopped) => {
                *cut |= stopped;
                distinct(&mut found);
            }
            None => found = literal(cx, lit, theta, cap, cut)?,
        }
        let count = found.len();
        next.items.reserve(count);
        for (j, a) in found.drain(..).enumerate() {
            if next.items.len() >= cap {
                *cut = true;
                break 'each;
            }
            // Answers of one theta are distinct, and answers that only bind variables
            // no theta binds differ from those of every other theta: no search needed.
            let fresh = a.iter().all(|(v, _)| !bound.contains(&v));
            let full = if level.all()[k].is_empty() {
                // Under an empty theta (a condition's first literal, mostly) the answer
                // is the full answer already: no copy.
                a
            } else if let Some(mut t) = (j + 1 == count).then(|| level.take(k)).flatten() {
                // The last answer under a theta extends that theta itself (a level that
                // ends empty took none).
                t.extend(&a);
                t
            } else {
                compose(&level.all()[k], &a)
            };
            if fresh {
                next.push_new(full);
            } else {
                next.push(full);
            }
        }
    }
    Ok(next)
}

/// True when the condition `lits` provably has no answer under `theta` without running it:
/// its first literal is a positive `bel` of a fact pattern (a predicate no knowledge clause or
/// built-in answers) and no fact base holds a fact of that predicate.
///
/// Exact: nothing runs before the first literal, so no error of a later literal is hidden,
/// and the first literal would be answered by its plan (the limits are roomy, `theta` binds
/// only atoms, integers and strings, so the plan neither bails on a float nor hands a
/// non-ground binding to the engine), whose first step matches facts of that predicate base
/// by base, finding none: no answer, no error, no cut, no random draw.
pub fn first_lookup_fails(ms: &MentalState, lits: &[Lit], theta: &Subst) -> bool {
    let Some(Lit::Mental {
        negated: false,
        about: None,
        op: MentalOp::Bel,
        query,
        plan,
        ..
    }) = lits.first()
    else {
        return false;
    };
    let Some((name, arity)) = plan.get(query, &ms.knowledge).and_then(|p| p.first_fact()) else {
        return false;
    };
    // The messages waiting aside in the mailbox first, which the plan reads as `received/2`
    // facts: in the cycle a message arrives, they answer at once.
    let ([b0, b1, b2, b3, b4, b5], arrived) = ms.plan_bases();
    if (name, arity) == (wk::RECEIVED, 2) && !arrived.received.is_empty() {
        return false;
    }
    // Base by base, written out: no closure call per base (all six are looked at when the
    // condition is skipped).
    !(b0.has_pred(name, arity)
        || b1.has_pred(name, arity)
        || b2.has_pred(name, arity)
        || b3.has_pred(name, arity)
        || b4.has_pred(name, arity)
        || b5.has_pred(name, arity))
        && theta
            .iter()
            .all(|(_, t)| matches!(t, Term::Atom(_) | Term::Int(_) | Term::Str(_)))
        && ms.native_roomy()
}

/// [`evaluate`] of a condition of one literal under the empty substitution: the literal's
/// answers are the condition's (distinct, as a literal's are), the first `cap` of them.
fn evaluate_one(
    cx: &CondCtx<'_>,
    lit: &Lit,
    base: &Subst,
    cap: usize,
) -> Result<Evaluation, Fault> {
    let mut cut = false;
    let mut answers = literal(cx, lit, base, cap, &mut cut)?;
    cut |= cut_to(&mut answers, cap);
    let failed = answers.is_empty().then(|| (0, smallvec![base.clone()]));
    Ok(Evaluation {
        answers,
        cut,
        failed,
    })
}

/// The variables some answer of `answers` binds (usually all bind the same ones).
fn bound_by_any(answers: &[Subst]) -> SmallVec<[Sym; 8]> {
    let mut vars = SmallVec::new();
    for (v, _) in answers.iter().flat_map(|a| a.iter()) {
        if !vars.contains(&v) {
            vars.push(v);
        }
    }
    vars
}

/// The distinct answers of one literal under `theta` (the bindings each adds to `theta`), at
/// most `cap` per query (`cut` is set when a query stopped there).
#[inline(never)]
fn literal(
    cx: &CondCtx<'_>,
    lit: &Lit,
    theta: &Subst,
    cap: usize,
    cut: &mut bool,
) -> Result<Found, Fault> {
    let Lit::Mental {
        negated,
        top_level,
        about,
        op,
        query,
        plan,
    } = lit
    else {
        return Ok(smallvec![Subst::new()]);
    };
    let ms = cx.ms;
    let mut raw = AnswerSet::default();
    // A negated literal is decided by all answers (a filter after the query may drop the
    // first ones), as for `forall`.
    let cap = if *negated { usize::MAX } else { cap };
    match (op, about) {
        // Selectors other than this/self query the mental models of other agents.
        (_, Some(others)) => {
            for a in super::models::answers(ms, others, *op, &theta.apply(query), theta)? {
                raw.push(a);
            }
        }
        (MentalOp::Bel, None) => {
            let (found, stopped) = bel_answers(ms, query, plan, theta, cap)?;
            *cut |= stopped;
            // Returned at once: no empty answer set to replace and drop.
            return Ok(finish_found(*negated, found));
        }
        (MentalOp::Goal | MentalOp::AGoal | MentalOp::GoalA, None) => {
            // The query's instance is matched in place when `theta` allows (no copy made).
            let owned;
            let under = match theta.is_empty() {
                true => None,
                false => GoalQuery::under(&ms.knowledge, query, theta),
            };
            let gq = match under {
                Some(gq) => gq,
                None => {
                    owned = theta.apply(query);
                    GoalQuery::new(&ms.knowledge, &owned)
                }
            };
            let base = match (top_level, cx.only) {
                (true, _) => Some(ms.attention.top_level()),
                (false, Some(_)) => None,
                (false, None) => Some(ms.attention.current()),
            };
            if let Some(b) = base.filter(|_| *op != MentalOp::Goal) {
                if goal_fact_answers(ms, b, &gq, *op == MentalOp::GoalA, &mut raw) {
                    return Ok(finish(*negated, raw));
                }
            }
            // When only goal facts answer the query, the goals without a fact of its
            // predicate have no answer: look at the others alone (the base's index).
            let goals: SmallVec<[&Goal; 16]> = match (base, gq.fact_predicate()) {
                (Some(b), Some((name, arity))) => match gq.first_key() {
                    Some(key) => b.with_first_arg(name, arity, key).collect(),
                    None => b.with_predicate(name, arity).collect(),
                },
                (Some(b), None) => b.goals().iter().collect(),
                (None, _) => cx.only.into_iter().collect(),
            };
            // The instance of a query without `_` that matched a goal fact is that fact.
            let plain = !has_anonymous(gq.query);
            for g in goals {
                // Goal facts alone answer: `goal` takes each match, `a-goal`/`goal-a` each
                // whose instance (the fact itself, with no `_`) is (not) believed.
                let by_facts = *op == MentalOp::Goal || plain;
                if by_facts && gq.only_facts {
                    if let Some(found) = gq.matching_facts(g) {
                        for (a, fact) in found {
                            if *op == MentalOp::Goal
                                || ms.believes(fact)? == (*op == MentalOp::GoalA)
                            {
                                raw.push(a);
                            }
                        }
                        continue;
                    }
                }
                let (found, stopped) = ms.in_goal_prepared(g, &gq, cap)?;
                *cut |= stopped;
                for a in found {
                    if *op != MentalOp::Goal {
                        let inst = a.apply(&gq.instance());
                        if !inst.is_ground() {
                            return Err(Fault {
                                message: format!(
                                    "{} query {} is not ground after the goal query",
                                    if *op == MentalOp::AGoal {
                                        "a-goal"
                                    } else {
                                        "goal-a"
                                    },
                                    inst
                                ),
                                binding: Some(show_subst(theta)),
                            });
                        }
                        let believed = ms.believes(&inst)?;
                        if believed != (*op == MentalOp::GoalA) {
                            continue;
                        }
                    }
                    raw.push(a);
                }
            }
        }
    }
    Ok(finish(*negated, raw))
}

/// Truncates `answers` to the first `cap`; true when that dropped some.
#[inline(always)]
fn cut_to(answers: &mut Found, cap: usize) -> bool {
    let over = answers.len() > cap;
    answers.truncate(cap);
    over
}

/// The distinct answers of the belief query `query` (planned in `plan`) under `theta`, at most
/// `cap`, and whether a query stopped there: the plan's when it decides, else the engine's.
#[inline(always)]
fn bel_answers(
    ms: &MentalState,
    query: &Term,
    plan: &super::conjunction::PlanCell,
    theta: &Subst,
    cap: usize,
) -> Result<(Found, bool), Fault> {
    let planned = plan
        .get(query, &ms.knowledge)
        .and_then(|p| p.answers(ms, theta, cap));
    let (mut found, stopped) = match planned {
        Some(r) => r,
        None => {
            let (found, stopped) = ms.bel_upto_in(query, theta, cap)?;
            (Found::from_vec(found), stopped)
        }
    };
    distinct(&mut found);
    Ok((found, stopped))
}

/// [`evaluate`]'s answers and whether `cap` cut them, without the literal that failed (what a
/// rule runs for while `goal why` does not record). A condition of one positive `bel` literal
/// about this agent under the empty substitution is answered by its query at once: exactly
/// what [`evaluate_one`] makes of [`literal`]'s answers for it (the same query, distinct
/// answers, the first `cap`), with no evaluation record made and taken apart.
pub fn answers_upto(
    cx: &CondCtx<'_>,
    lits: &[Lit],
    base: &Subst,
    cap: usize,
) -> Result<(Found, bool), Fault> {
    if let (
        [Lit::Mental {
            negated: false,
            about: None,
            op: MentalOp::Bel,
            query,
            plan,
            ..
        }],
        true,
    ) = (lits, base.is_empty())
    {
        let (mut found, cut) = bel_answers(cx.ms, query, plan, base, cap)?;
        let over = cut_to(&mut found, cap);
        return Ok((found, cut || over));
    }
    let e = evaluate(cx, lits, base, cap)?;
    Ok((e.answers, e.cut))
}

/// A literal's answers from the answers of its query: for a negated literal, one empty answer
/// when the query had none, else none.
fn finish(negated: bool, raw: AnswerSet) -> Found {
    finish_found(negated, raw.items)
}

/// [`finish`] of the distinct answers `found` of a query.
#[inline]
fn finish_found(negated: bool, found: Found) -> Found {
    match negated {
        false => found,
        true if found.is_empty() => smallvec![Subst::new()],
        true => Found::new(),
    }
}

/// The plan of `lit` ready for the thetas of a level, when it is a positive `bel` literal
/// about this agent with a plan.
fn planned<'a>(cx: &CondCtx<'a>, lit: &'a Lit) -> Option<super::conjunction::Batch<'a>> {
    let Lit::Mental {
        negated: false,
        about: None,
        op: MentalOp::Bel,
        query,
        plan,
        ..
    } = lit
    else {
        return None;
    };
    super::conjunction::Batch::new(plan.get(query, &cx.ms.knowledge)?, cx.ms)
}

/// `found` without repeated answers (a plan, as the engine, reports an answer once for each
/// way it was found).
#[inline(always)]
fn distinct(found: &mut Found) {
    // The length check inline: mostly a query has one answer or none.
    if found.len() > 1 {
        distinct_many(found);
    }
}

/// [`distinct`] of two or more answers.
#[inline(never)]
fn distinct_many(found: &mut Found) {
    let mut set = AnswerSet::default();
    for a in found.drain(..) {
        set.push(a);
    }
    *found = set.items;
}

/// The answers of an `a-goal` (`believed` false) or `goal-a` (`believed` true) query over
/// the goals of `base`, read from the goal facts directly when nothing but goal facts
/// answers the query, the query has no `_` (so the instance an answer makes is the goal fact
/// it matched) and a ground fact's belief is a lookup: the goals with a fact of the query's
/// predicate (and first argument) in adoption order, each fact matched and looked up in the
/// belief bases. False (and nothing added): not decided here.
#[inline(never)]
fn goal_fact_answers(
    ms: &MentalState,
    base: &super::goals::GoalBase,
    gq: &GoalQuery<'_>,
    believed: bool,
    raw: &mut AnswerSet,
) -> bool {
    let Some((name, arity)) = gq.fact_predicate() else {
        return false;
    };
    if !base.exactly_indexed() || has_anonymous(gq.query) {
        return false;
    }
    let Some(holders) = ms.fact_holders(name, arity) else {
        return false;
    };
    let positions = match gq.first_key() {
        Some(key) => base.positions_with_key(name, arity as u32, key),
        None => base.positions(name, arity as u32),
    };
    let goals = base.goals();
    // A goal of one fact has at most one answer, and with no `_` in the query the answer
    // decides the fact: goals of one fact each (distinct goals) give distinct answers.
    let distinct = positions
        .iter()
        .all(|&i| goals[i as usize].facts.len() == 1);
    // The fact of a one-fact goal the goal mark knows not believed needs no lookup.
    let maybe = match std::ptr::eq(base, ms.attention.current()) {
        true => ms.goals_maybe_believed(),
        false => None,
    };
    raw.items.reserve(positions.len());
    for &i in positions {
        let goal = &goals[i as usize];
        let unbelieved =
            goal.facts.len() == 1 && maybe.as_ref().is_some_and(|m| m.binary_search(&i).is_err());
        for fact in goal
            .facts
            .iter()
            .filter(|f| f.functor() == Some((name, arity)))
        {
            let mut a = Subst::with_capacity(arity);
            if !gq.match_fact(fact, &mut a)
                || (!unbelieved && holders.iter().any(|b| b.contains(fact))) != believed
            {
                continue;
            }
            match distinct {
                true => raw.push_new(a),
                false => raw.push(a),
            }
        }
    }
    true
}

/// True when `t` has the anonymous variable `_`.
fn has_anonymous(t: &Term) -> bool {
    let anonymous = |a: &Term| matches!(a, Term::Var(v) if *v == wk::UNDERSCORE);
    // A query of atomic arguments (the usual `fib(N)`) is looked at without a work stack.
    if let Term::Compound(c) = t {
        if !c.args.iter().any(|a| matches!(a, Term::Compound(_))) {
            return c.args.iter().any(anonymous);
        }
    }
    let mut stack: SmallVec<[&Term; 16]> = SmallVec::new();
    stack.push(t);
    while let Some(t) = stack.pop() {
        match t {
            Term::Var(v) if *v == crate::term::well_known::UNDERSCORE => return true,
            Term::Compound(c) => stack.extend(c.args.iter()),
            _ => {}
        }
    }
    false
}

/// The positive `goal`/`a-goal` literals of a condition, instantiated (for focus=filter).
pub fn goal_literals(lits: &[Lit], s: &Subst) -> Vec<Term> {
    lits.iter()
        .filter_map(|l| match l {
            Lit::Mental {
                negated: false,
                op: MentalOp::Goal | MentalOp::AGoal,
                query,
                ..
            } => Some(s.apply(query)),
            _ => None,
        })
        .collect()
}

/// A substitution printed as `X=a, Y=f(b)` (internal variables left out).
pub fn show_subst(s: &Subst) -> String {
    let mut parts = Vec::new();
    for (v, t) in s.iter() {
        let name = v.name();
        if name.starts_with('_') {
            continue;
        }
        parts.push(format!("{name}={}", s.apply(t)));
    }
    parts.join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agent::cycle::{Agent, AgentConfig};
    use crate::agent::program::Program;

    /// The program of `src` and its agent after one cycle.
    fn after_one_cycle(src: &str) -> (Arc<Program>, Agent) {
        let prog = Program::from_source("t.goal", src).expect("compiles");
        let mut a = Agent::new(prog.clone(), "a", AgentConfig::default());
        a.step(&[], &[]);
        (prog, a)
    }

    /// For each rule of the main module of `src` after one cycle (in which the first rule
    /// applies, so the others do not run): whether its evaluation is skipped, and what
    /// evaluating it gives (answers or error).
    fn skipped_and_evaluated(src: &str) -> Vec<(bool, Result<usize, String>)> {
        let (prog, a) = after_one_cycle(src);
        assert!(a.stopped().is_none(), "{:?}", a.stopped());
        let ms = a.mental_state();
        let block = prog.modules[prog.main].block;
        let theta = Subst::new();
        prog.blocks[block]
            .rules
            .iter()
            .map(|r| {
                let skip = first_lookup_fails(ms, &r.cond, &theta);
                let cx = CondCtx { ms, only: None };
                let e = evaluate(&cx, &r.cond, &theta, usize::MAX);
                (skip, e.map(|e| e.answers.len()).map_err(|f| f.message))
            })
            .collect()
    }

    #[test]
    fn answers_upto_answers_as_the_evaluation() {
        // Planned (with repeated answers), engine-answered, negated, goal and two-literal
        // conditions, under each cap: the answers and the cut flag are the evaluation's.
        let (prog, a) = after_one_cycle(
            "init module { knowledge { k(X) :- f(X). } beliefs { f(1). f(2). f(3). g(a). g(b). }
               goals { h(1). } }
             main module { program {
                if bel(f(X), g(_)) then print(X).
                if bel(k(X)) then print(X).
                if not(bel(f(9))) then print(no).
                if a-goal(h(X)) then print(X).
                if bel(f(X)), bel(g(Y)) then print(X).
             } }",
        );
        let cx = CondCtx {
            ms: a.mental_state(),
            only: None,
        };
        let theta = Subst::new();
        for rule in &prog.blocks[prog.modules[prog.main].block].rules {
            for cap in [1, 2, 3, 4, usize::MAX] {
                let e = evaluate(&cx, &rule.cond, &theta, cap).expect("evaluates");
                let fast = answers_upto(&cx, &rule.cond, &theta, cap).expect("answers");
                assert_eq!(fast, (e.answers, e.cut), "{} cap {cap}", rule.label);
            }
        }
    }

    #[test]
    fn a_condition_of_one_literal_answers_as_the_general_evaluation() {
        let (prog, a) = after_one_cycle(
            "init module { beliefs { f(1). f(2). f(3). } }
             main module { program {
                if bel(f(X)) then print(X).
                if bel(f(X)), bel(true) then print(X).
                if bel(g(X)) then print(X).
                if bel(g(X)), bel(true) then print(X).
             } }",
        );
        let cx = CondCtx {
            ms: a.mental_state(),
            only: None,
        };
        let rules = &prog.blocks[prog.modules[prog.main].block].rules;
        let theta = Subst::new();
        for (one, general) in [(0, 1), (2, 3)] {
            for cap in [1, 2, 3, 4, usize::MAX] {
                let e1 = evaluate(&cx, &rules[one].cond, &theta, cap).expect("evaluates");
                let e2 = evaluate(&cx, &rules[general].cond, &theta, cap).expect("evaluates");
                assert_eq!((e1.answers, e1.cut), (e2.answers, e2.cut), "cap {cap}");
                let failed = |e: Option<(usize, Found)>| e.map(|(i, before)| (i, before.len()));
                assert_eq!(failed(e1.failed), failed(e2.failed), "cap {cap}");
            }
        }
    }

    #[test]
    fn a_condition_is_skipped_only_when_its_first_lookup_has_no_facts() {
        let found = skipped_and_evaluated(
            "init module { knowledge { k(X) :- f(X). } beliefs { f(1). } }
             main module { program {
                if bel(f(1)) then print(first).
                if bel(none(X), Y is X + Z) then print(a).
                if bel(received(S, hello)) then print(b).
                if bel(f(X), X > 5) then print(c).
                if bel(k(X), X > 5) then print(d).
                if not(bel(none(X))), bel(f(2)) then print(e).
                if bel(f(X), Y is X + Z) then print(g).
             } }",
        );
        // Rules 2 and 3 read a predicate without facts first: skipped, and indeed without
        // answers (rule 1's arithmetic, which would raise an error, is never reached).
        assert_eq!(found[0], (false, Ok(1)));
        assert_eq!(found[1], (true, Ok(0)));
        assert_eq!(found[2], (true, Ok(0)));
        // A first lookup with facts, one knowledge answers, a negation: evaluated.
        assert_eq!(found[3], (false, Ok(0)));
        assert_eq!(found[4], (false, Ok(0)));
        assert_eq!(found[5], (false, Ok(0)));
        // The same arithmetic after a lookup with a fact raises its error: not skipped.
        assert!(!found[6].0);
        assert!(found[6].1.is_err(), "{:?}", found[6]);
    }
}
