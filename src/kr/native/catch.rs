//! ISO exceptions: `catch/3`, `throw/1`, and handing errors raised by built-ins to the
//! innermost active `catch/3`. Budget, depth, memory and interruption errors are not
//! catchable: a program must not be able to loop on them.

use super::machine::{Alt, Choice, Goal, Solver};
use super::store::{Cell, VarNames};
use crate::kr::error::{KrError, KrResult};
use crate::term::Sym;

impl Solver<'_, '_> {
    /// `catch(Goal, Catcher, Recovery)` at goal `p`: a catch choicepoint, then `Goal` (opaque
    /// to cut), then a marker that deactivates the catch once `Goal` exits.
    pub(crate) fn catch(&mut self, p: u32, next: u32, cut: u32, depth: u32) {
        let b = self.m.cps.len() as u32;
        let alt = Alt::Catch {
            catcher: self.a(p, 1),
            recovery: self.a(p, 2),
            active: true,
        };
        self.push_choice(alt, next, cut, depth);
        let exit = self.push_frame(Goal::CatchExit(b), next, cut, depth);
        self.cont = self.push_frame(Goal::Call(self.a(p, 0)), exit, b + 1, depth);
    }

    /// `throw(Ball)`: the error that carries a copy of `Ball`.
    pub(crate) fn throw(&self, p: u32) -> KrError {
        let ball = self.ad(p, 0);
        if let Cell::Ref(_) = ball {
            return super::builtins::inst("throw", 1);
        }
        if self.m.st.is_cyclic(ball) {
            return super::machine::cyclic();
        }
        let t = self.m.st.to_term(ball, &mut VarNames::new(&[]));
        if t.is_functor(Sym::intern("error"), 2) {
            KrError::Iso(t)
        } else {
            KrError::Uncaught(t)
        }
    }

    /// The goal of the catch at choicepoint `b` exited: without choicepoints left by the goal,
    /// the catch is removed; otherwise it is deactivated until backtracking re-enters the goal.
    pub(crate) fn catch_exit(&mut self, b: u32) {
        let b = b as usize;
        if self.m.cps.len() == b + 1 {
            self.m.cps.pop();
            return;
        }
        if let Some(Choice {
            alt: Alt::Catch { active, .. },
            ..
        }) = self.m.cps.get_mut(b)
        {
            *active = false;
            self.push_choice(Alt::CatchReactivate(b as u32), super::machine::NONE, 0, 0);
        }
    }

    /// Hands error `e` to the innermost active `catch/3` whose catcher unifies with it:
    /// `Ok(true)` with the recovery goal scheduled, or `Err(e)` when none catches it.
    pub(crate) fn recover(&mut self, e: KrError) -> KrResult<bool> {
        // A pending first body goal belongs to the computation the error abandons.
        self.direct = super::clauses::Direct::NONE;
        let ball = match &e {
            KrError::Iso(t) | KrError::Uncaught(t) => t.clone(),
            _ => return Err(e),
        };
        while let Some(i) = self
            .m
            .cps
            .iter()
            .rposition(|c| matches!(c.alt, Alt::Catch { active: true, .. }))
        {
            let ch = self.m.cps[i];
            self.m.cps.truncate(i);
            self.restore(&ch);
            self.m.st.cyclic.set(false);
            self.m.st.oversize.set(false);
            let Alt::Catch {
                catcher, recovery, ..
            } = ch.alt
            else {
                break;
            };
            let mark = self.m.st.trail.len();
            let thrown = self.m.st.put_term(&ball, &mut Vec::new());
            if self.unify(catcher, thrown) {
                let barrier = self.m.cps.len() as u32;
                self.cont = self.push_frame(Goal::Call(recovery), ch.next, barrier, ch.depth);
                return Ok(true);
            }
            self.m.st.undo(mark);
        }
        Err(e)
    }
}
