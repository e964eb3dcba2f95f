//! The people playing a live run: which HumanBots the run has, which browser holds which (one
//! robot per browser, known by a token the server hands out), the requests waiting for the
//! next tick boundary, and what became of each (applied, or refused and why) for the page.

use crate::mas::input::{parse_request, Input};
use serde_json::{json, Value};
use std::collections::VecDeque;
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

/// The entity type of robots people play (BW4T's HumanBots).
pub const HUMAN_KIND: &str = "human";
/// A browser that has not asked for the state this long has left: its robot is free again.
pub const HOLD_TIMEOUT: Duration = Duration::from_secs(30);
/// Requests of one robot waiting for the next tick boundary at most (more: refused, busy).
pub const MAX_PENDING: usize = 32;
/// Outcomes kept for the pages (the latest).
const MAX_OUTCOMES: usize = 200;
/// Outcomes of its robot a page is sent at most.
const SHOWN_OUTCOMES: usize = 20;

/// Why the server refused a player's request, with its HTTP status.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Refusal {
    pub status: u16,
    pub message: String,
}

fn refuse(status: u16, message: impl Into<String>) -> Refusal {
    Refusal {
        status,
        message: message.into(),
    }
}

struct Robot {
    entity: String,
    /// The holder's token and when the holder was last heard of.
    holder: Option<(String, Instant)>,
}

/// What became of a request.
struct Outcome {
    id: u64,
    entity: String,
    request: String,
    /// `None` while waiting; then the tick it was taken at and the environment's answer.
    done: Option<(u64, Result<(), String>)>,
}

#[derive(Default)]
struct Roster {
    robots: Vec<Robot>,
    /// The run announced its entities (before: nothing to play yet).
    announced: bool,
    /// Requests waiting for the run, oldest first, with their ids.
    pending: VecDeque<(u64, Input)>,
    /// Ids of requests handed to the run and not yet answered, in order.
    taken: VecDeque<u64>,
    outcomes: VecDeque<Outcome>,
    next_id: u64,
}

impl Roster {
    /// Frees robots whose holder went away.
    fn expire(&mut self, now: Instant) {
        for r in &mut self.robots {
            if r.holder
                .as_ref()
                .is_some_and(|(_, seen)| now.duration_since(*seen) > HOLD_TIMEOUT)
            {
                r.holder = None;
            }
        }
    }

    fn held_by(&mut self, token: &str) -> Option<&mut Robot> {
        self.robots
            .iter_mut()
            .find(|r| r.holder.as_ref().is_some_and(|(t, _)| t == token))
    }

    fn names(&self) -> String {
        if self.robots.is_empty() {
            return "none".into();
        }
        let names: Vec<&str> = self.robots.iter().map(|r| r.entity.as_str()).collect();
        names.join(", ")
    }

    fn outcome_mut(&mut self, id: u64) -> Option<&mut Outcome> {
        self.outcomes.iter_mut().find(|o| o.id == id)
    }
}

/// The people of a live run (shared by the server's clients and the run's observer).
#[derive(Default)]
pub struct Players {
    roster: Mutex<Roster>,
}

/// A token nobody can guess from another one.
fn new_token() -> String {
    format!(
        "{:016x}{:016x}",
        rand::random::<u64>(),
        rand::random::<u64>()
    )
}

impl Players {
    /// Nobody plays yet; no robots until the run announces them.
    pub fn new() -> Players {
        Players::default()
    }

    // Each change under the lock leaves the roster consistent: a poisoned lock is usable.
    fn lock(&self) -> MutexGuard<'_, Roster> {
        self.roster.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The run's HumanBots (entity names), once at its start.
    pub fn announce(&self, robots: Vec<String>) {
        let mut r = self.lock();
        r.robots = robots
            .into_iter()
            .map(|entity| Robot {
                entity,
                holder: None,
            })
            .collect();
        r.announced = true;
    }

    /// The run's HumanBots.
    pub fn robots(&self) -> Vec<String> {
        self.lock()
            .robots
            .iter()
            .map(|r| r.entity.clone())
            .collect()
    }

    /// The browser with `token` (a new one when `None`) takes `robot`, leaving the robot it
    /// held; the token is returned.
    pub fn take(&self, robot: &str, token: Option<&str>) -> Result<String, Refusal> {
        let now = Instant::now();
        let mut r = self.lock();
        r.expire(now);
        let names = r.names();
        let Some(i) = r.robots.iter().position(|x| x.entity == robot) else {
            return Err(refuse(
                404,
                format!("no HumanBot named `{robot}` in this run (its HumanBots: {names})"),
            ));
        };
        let token = token.map_or_else(new_token, str::to_string);
        match &r.robots[i].holder {
            Some((t, _)) if *t == token => return Ok(token),
            Some(_) => {
                return Err(refuse(
                    409,
                    format!("{robot} is already taken by another player; choose a free robot"),
                ))
            }
            None => {}
        }
        if let Some(old) = r.held_by(&token) {
            old.holder = None;
        }
        r.robots[i].holder = Some((token.clone(), now));
        Ok(token)
    }

    /// The browser with `token` leaves its robot (nothing when it holds none).
    pub fn leave(&self, token: &str) {
        if let Some(robot) = self.lock().held_by(token) {
            robot.holder = None;
        }
    }

    /// A request of the browser with `token` for its robot, queued for the next tick
    /// boundary: its id.
    pub fn request(&self, token: &str, text: &str) -> Result<u64, Refusal> {
        let now = Instant::now();
        let mut r = self.lock();
        r.expire(now);
        let Some(robot) = r.held_by(token) else {
            return Err(refuse(
                403,
                "you hold no robot in this run (or left it): take a free HumanBot first",
            ));
        };
        robot.holder = Some((token.to_string(), now));
        let entity = robot.entity.clone();
        let request = parse_request(text).map_err(|e| refuse(400, e))?;
        // Only a question (`sendMessage(To, int(at(_, 'RoomA1')))`) may leave its subject open,
        // as an agent's interrogative send may; every other request names everything.
        if !request.is_ground() && !crate::bw4t::human::may_stay_open(&request) {
            return Err(refuse(
                400,
                format!(
                    "the request `{}` leaves something open (`_` or a variable): name everything, e.g. goTo('RoomA1')",
                    text.trim()
                ),
            ));
        }
        let waiting = r.pending.iter().filter(|(_, i)| i.entity == entity).count();
        if waiting >= MAX_PENDING {
            return Err(refuse(
                429,
                format!(
                    "{entity} has {waiting} requests waiting for the next tick already; wait a moment"
                ),
            ));
        }
        let id = r.next_id;
        r.next_id += 1;
        let input = Input { entity, request };
        r.outcomes.push_back(Outcome {
            id,
            entity: input.entity.clone(),
            request: input.request_text(),
            done: None,
        });
        if r.outcomes.len() > MAX_OUTCOMES {
            r.outcomes.pop_front();
        }
        r.pending.push_back((id, input));
        Ok(id)
    }

    /// The run takes every waiting request (at a tick boundary), oldest first.
    pub fn drain(&self) -> Vec<Input> {
        let mut r = self.lock();
        let pending = std::mem::take(&mut r.pending);
        let mut out = Vec::with_capacity(pending.len());
        for (id, input) in pending {
            r.taken.push_back(id);
            out.push(input);
        }
        out
    }

    /// The run's answer to the oldest request it took (taken at `tick`).
    pub fn applied(&self, tick: u64, result: &Result<(), String>) {
        let mut r = self.lock();
        if let Some(id) = r.taken.pop_front() {
            if let Some(o) = r.outcome_mut(id) {
                o.done = Some((tick, result.clone()));
            }
        }
    }

    /// What the page of the browser with `token` shows: the robots (taken or free, which is
    /// its own), and what became of its robot's latest requests. Asking counts as being there.
    pub fn state(&self, token: Option<&str>) -> Value {
        let now = Instant::now();
        let mut r = self.lock();
        r.expire(now);
        let mut mine = None;
        if let Some(robot) = token.and_then(|t| r.held_by(t)) {
            if let Some((_, seen)) = &mut robot.holder {
                *seen = now;
            }
            mine = Some(robot.entity.clone());
        }
        let robots: Vec<Value> = r
            .robots
            .iter()
            .map(|x| {
                json!({
                    "entity": x.entity,
                    "taken": x.holder.is_some(),
                    "mine": mine.as_deref() == Some(x.entity.as_str()),
                })
            })
            .collect();
        let outcomes: Vec<Value> = match &mine {
            Some(m) => r
                .outcomes
                .iter()
                .rev()
                .filter(|o| o.entity == *m)
                .take(SHOWN_OUTCOMES)
                .map(outcome_json)
                .collect(),
            None => Vec::new(),
        };
        json!({
            "announced": r.announced,
            "robots": robots,
            "you": mine,
            "requests": outcomes,
        })
    }
}

fn outcome_json(o: &Outcome) -> Value {
    let (state, tick, reason) = match &o.done {
        None => ("waiting", None, None),
        Some((t, Ok(()))) => ("applied", Some(*t), None),
        Some((t, Err(e))) => ("refused", Some(*t), Some(e.as_str())),
    };
    json!({"id": o.id, "request": o.request, "state": state, "tick": tick, "reason": reason})
}

#[cfg(test)]
mod tests {
    use super::*;

    fn players() -> Players {
        let p = Players::new();
        p.announce(vec!["Human1".into(), "Human2".into()]);
        p
    }

    #[test]
    fn one_robot_per_browser_and_a_taken_robot_stays_taken() {
        let p = players();
        let a = p.take("Human1", None).unwrap();
        assert_eq!(
            p.take("Human1", Some(&a)).unwrap(),
            a,
            "taking it again is fine"
        );
        let e = p.take("Human1", None).unwrap_err();
        assert_eq!(e.status, 409, "{e:?}");
        let e = p.take("Bot1", None).unwrap_err();
        assert_eq!(e.status, 404);
        assert!(e.message.contains("Human1, Human2"), "{}", e.message);
        // Switching robots frees the first.
        p.take("Human2", Some(&a)).unwrap();
        let b = p.take("Human1", None).unwrap();
        assert_ne!(a, b);
        let s = p.state(Some(&b));
        assert_eq!(s["you"], "Human1");
        assert_eq!(s["robots"][1]["taken"], true);
        assert_eq!(s["robots"][1]["mine"], false);
        p.leave(&a);
        assert_eq!(p.state(None)["robots"][1]["taken"], false);
    }

    #[test]
    fn requests_wait_for_the_run_and_their_outcome_is_shown() {
        let p = players();
        assert_eq!(p.request("nobody", "putDown").unwrap_err().status, 403);
        let t = p.take("Human2", None).unwrap();
        assert_eq!(p.request(&t, "goTo(").unwrap_err().status, 400);
        let open = p.request(&t, "goTo(_)");
        assert!(open.unwrap_err().message.contains("leaves something open"));
        let question = p.request(&t, "sendMessage(all, int(at(_, 'RoomA1')))");
        assert!(question.is_ok(), "{question:?}");
        assert_eq!(p.drain().len(), 1);
        p.applied(5, &Ok(()));
        let a = p.request(&t, "goTo('RoomA1')").unwrap();
        let b = p.request(&t, "pickUp(3)").unwrap();
        assert!(b > a);
        let taken = p.drain();
        assert_eq!(taken.len(), 2);
        assert_eq!(taken[0].entity, "Human2");
        assert!(p.drain().is_empty());
        p.applied(12, &Ok(()));
        p.applied(12, &Err("not at a block".into()));
        let s = p.state(Some(&t));
        let reqs = s["requests"].as_array().unwrap();
        assert_eq!(reqs[0]["request"], "pickUp(3)");
        assert_eq!(reqs[0]["state"], "refused");
        assert_eq!(reqs[0]["reason"], "not at a block");
        assert_eq!(reqs[1]["state"], "applied");
        assert_eq!(reqs[1]["tick"], 12);
        for _ in 0..MAX_PENDING {
            p.request(&t, "putDown").unwrap();
        }
        assert_eq!(p.request(&t, "putDown").unwrap_err().status, 429);
    }
}
