//! A scripted greedy player for one robot, driven only by percepts through the lock-step channel
//! interface: it explores the nearest unvisited room, remembers the colours it saw, fetches the
//! next needed colour and delivers it. Used as a smoke test and benchmark baseline.

use crate::env::thread::{EnvError, EnvHandle};
use crate::env::ActionResult;
use crate::term::Term;
use serde::Serialize;

/// The outcome of a scripted game.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GreedyReport {
    /// Ticks (rounds) played.
    pub ticks: u64,
    /// Blocks delivered in sequence.
    pub delivered: usize,
    /// True when the whole sequence was delivered.
    pub finished: bool,
    /// Actions that failed (with their messages).
    pub failures: Vec<String>,
}

struct Player<'a> {
    env: &'a EnvHandle,
    bot: String,
    ticks: u64,
    max_ticks: u64,
    state: String,
    location: (f64, f64),
    seq: Vec<String>,
    index: usize,
    zones: Vec<(String, f64, f64, usize)>,
    visible: Vec<(i64, String)>,
    known: Vec<(String, i64, String)>,
    visited: Vec<String>,
    failures: Vec<String>,
}

fn num(t: &Term) -> f64 {
    match t {
        Term::Int(i) => *i as f64,
        Term::Float(f) => f.0,
        _ => 0.0,
    }
}

fn name(t: &Term) -> String {
    match t {
        Term::Atom(s) => s.name().to_string(),
        other => other.to_string(),
    }
}

impl Player<'_> {
    fn absorb(&mut self, batch: &[Term]) {
        self.visible.clear();
        for t in batch {
            let Some((f, _)) = t.functor() else { continue };
            let a = t.args();
            match (f.name(), a.len()) {
                ("state", 1) => self.state = name(&a[0]),
                ("location", 2) => self.location = (num(&a[0]), num(&a[1])),
                ("sequenceIndex", 1) => self.index = num(&a[0]) as usize,
                ("sequence", 1) => {
                    self.seq = a[0]
                        .list_items()
                        .unwrap_or_default()
                        .iter()
                        .map(name)
                        .collect()
                }
                ("zone", 5) => {
                    let n = a[4].list_items().map_or(0, |l| l.len());
                    self.zones.push((name(&a[1]), num(&a[2]), num(&a[3]), n));
                }
                ("color", 2) => self.visible.push((num(&a[0]) as i64, name(&a[1]))),
                _ => {}
            }
        }
    }

    /// One lock-step round with at most one action for our robot.
    fn round(&mut self, action: Option<Term>) -> Result<ActionResult, EnvError> {
        let actions: Vec<(String, Term)> =
            action.map(|a| (self.bot.clone(), a)).into_iter().collect();
        let reply = self.env.round(actions)?;
        self.ticks = reply.tick;
        let result = reply
            .results
            .into_iter()
            .next()
            .map_or(ActionResult::Ok, |(_, r)| r);
        if let ActionResult::Failed(m) = &result {
            self.failures.push(m.clone());
        }
        if let Some((_, batch)) = reply.percepts.iter().find(|(n, _)| *n == self.bot) {
            self.absorb(batch);
        }
        Ok(result)
    }

    fn over(&self) -> bool {
        self.ticks >= self.max_ticks
    }

    /// Performs a movement action and waits until the robot stops; true when it arrived.
    fn travel(&mut self, action: Term) -> Result<bool, EnvError> {
        if !self.round(Some(action))?.is_ok() {
            return Ok(false);
        }
        while self.state == "traveling" && !self.over() {
            self.round(None)?;
        }
        Ok(self.state == "arrived")
    }

    fn go(&mut self, place: &str) -> Result<bool, EnvError> {
        for _ in 0..20 {
            if self.travel(Term::compound("goTo", vec![Term::atom(place)]))? {
                return Ok(true);
            }
            // Collided: try a detour around robots in the way (fails quietly without
            // collisions or when the way is shut), else wait a little and retry.
            if self.state == "collided" {
                let failures = self.failures.len();
                let detour = self.travel(Term::atom("navigateObstacles"))?;
                self.failures.truncate(failures);
                if detour {
                    return Ok(true);
                }
            }
            for _ in 0..10 {
                self.round(None)?;
            }
            if self.over() {
                break;
            }
        }
        Ok(false)
    }

    fn distance_to(&self, zone: &str) -> f64 {
        self.zones
            .iter()
            .find(|z| z.0 == zone)
            .map_or(f64::MAX, |z| {
                ((z.1 - self.location.0).powi(2) + (z.2 - self.location.1).powi(2)).sqrt()
            })
    }

    fn nearest<'b>(&self, rooms: impl Iterator<Item = &'b String>) -> Option<String> {
        let mut best: Option<(f64, &String)> = None;
        for r in rooms {
            let d = self.distance_to(r);
            if best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, r));
            }
        }
        best.map(|(_, r)| r.clone())
    }

    fn look(&mut self, room: &str) {
        self.known.retain(|k| k.0 != room);
        for (id, c) in &self.visible {
            self.known.push((room.to_string(), *id, c.clone()));
        }
        if !self.visited.iter().any(|v| v == room) {
            self.visited.push(room.to_string());
        }
    }

    fn play(&mut self) -> Result<(), EnvError> {
        let rooms: Vec<String> = self
            .zones
            .iter()
            .filter(|z| z.3 == 1 && z.0 != "DropZone")
            .map(|z| z.0.clone())
            .collect();
        while self.index < self.seq.len() && !self.over() {
            let needed = self.seq[self.index].clone();
            let candidates: Vec<String> = self
                .known
                .iter()
                .filter(|k| k.2 == needed)
                .map(|k| k.0.clone())
                .collect();
            if let Some(room) = self.nearest(candidates.iter()) {
                if !self.go(&room)? {
                    continue;
                }
                self.look(&room);
                let Some(&(id, _)) = self.visible.iter().find(|(_, c)| *c == needed) else {
                    continue;
                };
                if !self.travel(Term::compound("goToBlock", vec![Term::Int(id)]))? {
                    continue;
                }
                if !self
                    .round(Some(Term::compound("pickUp", vec![Term::Int(id)])))?
                    .is_ok()
                {
                    continue;
                }
                self.known.retain(|k| k.1 != id);
                while !self.go("DropZone")? && !self.over() {}
                self.round(Some(Term::atom("putDown")))?;
            } else {
                let unvisited = rooms.iter().filter(|r| !self.visited.contains(r));
                let Some(room) = self.nearest(unvisited) else {
                    break;
                };
                if self.go(&room)? {
                    self.look(&room);
                } else {
                    self.visited.push(room);
                }
            }
        }
        Ok(())
    }
}

/// Plays the game with robot `bot` through a lock-step `env` until the sequence is delivered
/// (or `max_ticks` have passed).
pub fn play(env: &EnvHandle, bot: &str, max_ticks: u64) -> Result<GreedyReport, EnvError> {
    let mut p = Player {
        env,
        bot: bot.to_string(),
        ticks: 0,
        max_ticks,
        state: "arrived".into(),
        location: (0.0, 0.0),
        seq: Vec::new(),
        index: 0,
        zones: Vec::new(),
        visible: Vec::new(),
        known: Vec::new(),
        visited: Vec::new(),
        failures: Vec::new(),
    };
    let first = env.perceive(&[bot.to_string()])?;
    if let Some((_, batch)) = first.first() {
        p.absorb(batch);
    }
    p.play()?;
    Ok(GreedyReport {
        ticks: p.ticks,
        delivered: p.index,
        finished: !p.seq.is_empty() && p.index >= p.seq.len(),
        failures: p.failures,
    })
}
