//! The goal mark: what the last goal check saw, kept current by the agent's own belief
//! updates, so that the next check queries only the goals those updates can have achieved.

use super::*;

/// What a goal check saw: the change counts of the bases goal facts can be found in (beliefs,
/// percepts and this cycle's percept batch), the attention stack's moves, and the predicates
/// inserted into the beliefs since (by this agent's updates).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct GoalMark {
    beliefs: u64,
    percepts: u64,
    batch: u64,
    moves: u64,
    inserted: SmallVec<[Inserted; 8]>,
    /// The predicates of the goals' facts that are not plain (see
    /// [`MentalState::plain_goal_predicate`]), as of `new_predicates` of the goal base.
    impure: SmallVec<[(Sym, u32); 4]>,
    new_predicates: u64,
}

/// The predicate and first-argument key of a fact inserted since the last goal check (`None`:
/// no first argument, or one without a key): only goals with a fact of both can be achieved by it.
type Inserted = (Sym, u32, Option<Key>);

/// The most predicates a goal mark records; more updates between two goal checks make the
/// next check look at every goal.
const MARKED: usize = 16;

impl MentalState {
    /// Keeps the goal mark in step with a belief update of this agent (`inserted`: the
    /// fact inserted; a deletion achieves no goal of facts alone).
    pub(super) fn mark_belief_edit(&mut self, inserted: Option<&Term>) {
        let Some(mark) = self.goal_mark.as_mut() else {
            return;
        };
        mark.beliefs += 1;
        if let Some((name, arity)) = inserted.and_then(|f| f.functor()) {
            let first = inserted
                .and_then(|f| f.args().first())
                .and_then(Key::of_term);
            let key = (name, arity as u32, first);
            if !mark.inserted.contains(&key) {
                if mark.inserted.len() == MARKED {
                    self.goal_mark = None;
                    return;
                }
                mark.inserted.push(key);
            }
        }
    }

    /// The change counts a goal mark keeps: beliefs, percepts, percept batch, attention moves.
    fn goal_stamps(&self) -> [u64; 4] {
        [
            self.beliefs.edits(),
            self.percepts.facts().edits(),
            self.percepts.batch().edits(),
            self.attention.moves(),
        ]
    }

    /// The predicates of the current goals that are not plain (see
    /// [`MentalState::plain_goal_predicate`]).
    fn impure_goal_predicates(&self) -> SmallVec<[(Sym, u32); 4]> {
        self.attention
            .current()
            .predicates()
            .filter(|&(name, arity)| !self.plain_goal_predicate(name, arity))
            .collect()
    }

    /// Notes again which predicates of the goals are not plain, when the goal base has
    /// predicates the goal mark did not note (a goal adopted with a new predicate).
    fn renote_goal_predicates(&mut self) {
        let new_predicates = self.attention.current().new_predicates();
        if self
            .goal_mark
            .as_ref()
            .is_none_or(|m| m.new_predicates == new_predicates)
        {
            return;
        }
        let impure = self.impure_goal_predicates();
        if let Some(mark) = self.goal_mark.as_mut() {
            mark.impure = impure;
            mark.new_predicates = new_predicates;
        }
    }

    /// Notes that every goal of the current attention set is not believed now: the goal mark
    /// starts again from the current state (its predicates noted again after `full`, a check
    /// of every goal).
    fn set_goal_mark(&mut self, full: bool) {
        let [beliefs, percepts, batch, moves] = self.goal_stamps();
        let new_predicates = self.attention.current().new_predicates();
        match self.goal_mark.as_mut() {
            Some(mark) if !full => {
                (mark.beliefs, mark.percepts, mark.batch, mark.moves) =
                    (beliefs, percepts, batch, moves);
                mark.inserted.clear();
            }
            _ => {
                self.goal_mark = Some(GoalMark {
                    beliefs,
                    percepts,
                    batch,
                    moves,
                    inserted: SmallVec::new(),
                    impure: self.impure_goal_predicates(),
                    new_predicates,
                })
            }
        }
    }

    /// True when a goal fact of predicate `name/arity` is found by a lookup in the beliefs and
    /// percepts alone: knowledge does not resolve it (no rule, built-in or control construct)
    /// and it is not a fact of the mailbox, the agent directory or `me/1`.
    fn plain_goal_predicate(&self, name: Sym, arity: u32) -> bool {
        !self.knowledge.resolves(name, arity as usize)
            && !is_mail_predicate(name, arity as usize)
            && !matches!((name, arity), (wk::AGENT, 1) | (wk::ME, 1))
    }

    /// The positions of the goals of the current attention set that the changes since the
    /// last goal check can have achieved, ascending; `None`: every goal. A goal whose facts
    /// are all of plain predicates (see [`MentalState::plain_goal_predicate`]) was not
    /// believed at the last check (or when adopted, which also checks), and only an inserted
    /// fact of one of its predicates can make it believed; any other goal is always looked at.
    fn goals_to_check(&self) -> Option<SmallVec<[u32; 16]>> {
        let mark = self.goal_mark.as_ref()?;
        let base = self.attention.current();
        let same = [mark.beliefs, mark.percepts, mark.batch, mark.moves] == self.goal_stamps();
        if !same || base.unchecked() || !self.native_roomy() {
            return None;
        }
        let mut at: SmallVec<[u32; 16]> = SmallVec::new();
        for &(name, arity, first) in &mark.inserted {
            at.extend_from_slice(match first {
                Some(key) => base.positions_with_key(name, arity, key),
                None => base.positions(name, arity),
            });
        }
        for &(name, arity) in &mark.impure {
            at.extend_from_slice(base.positions(name, arity));
        }
        at.sort_unstable();
        at.dedup();
        Some(at)
    }

    /// The positions (ascending) of the goals of the current attention set that may be
    /// believed now: every other goal is known not to be, as the goal mark is current (see
    /// [`MentalState::goals_to_check`]). `None`: any goal may be.
    pub(crate) fn goals_maybe_believed(&self) -> Option<SmallVec<[u32; 16]>> {
        let mark = self.goal_mark.as_ref()?;
        if mark.new_predicates != self.attention.current().new_predicates() {
            return None;
        }
        self.goals_to_check()
    }

    /// Blind commitment: removes every goal of the current attention set that is believed.
    /// Only the goals that the changes since the last check can have achieved are queried
    /// (see [`MentalState::goals_to_check`]); the others are not believed, so the goals
    /// removed, their order and the events are those of a check of every goal. `events` gets
    /// one per goal removed, when `report` (the goal printed: not made for a trace that
    /// shows none).
    pub fn goal_check(&mut self, events: &mut Vec<Event>, report: bool) -> Result<(), Fault> {
        self.renote_goal_predicates();
        let mut achieved: SmallVec<[u32; 4]> = SmallVec::new();
        let goals = self.attention.current().goals();
        let to_check = self.goals_to_check();
        let full = to_check.is_none();
        match to_check {
            Some(at) => {
                for p in at {
                    if self.believes(&goals[p as usize].term)? {
                        achieved.push(p);
                    }
                }
            }
            None => {
                for (p, g) in goals.iter().enumerate() {
                    if self.believes(&g.term)? {
                        achieved.push(p as u32);
                    }
                }
            }
        }
        let base = self.attention.current_mut();
        base.checked();
        let removed = base.remove_at(&achieved);
        self.set_goal_mark(full);
        let attention = self.attention.depth() - 1;
        for g in removed.into_iter().filter(|_| report) {
            events.push(Event::GoalAchieved {
                goal: g.term.to_string(),
                attention,
            });
        }
        Ok(())
    }
}
