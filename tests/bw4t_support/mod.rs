//! Helpers shared by the BW4T integration tests.
#![allow(dead_code)]

use goal::bw4t::{map, Bw4t, Bw4tConfig, RobotState};
use goal::env::{ActionResult, Environment};
use goal::term::Term;

/// A run on the built-in map `name` with `cfg`.
pub fn env(name: &str, cfg: Bw4tConfig) -> Bw4t {
    let m = map::builtin(name)
        .expect("built-in map exists")
        .expect("built-in map loads");
    Bw4t::new(&m, &cfg)
}

/// A run on the built-in map `name` with the default configuration.
pub fn default_env(name: &str) -> Bw4t {
    env(name, Bw4tConfig::default())
}

pub fn go_to(place: &str) -> Term {
    Term::compound("goTo", vec![Term::atom(place)])
}

pub fn go_to_xy(x: f64, y: f64) -> Term {
    Term::compound("goTo", vec![Term::from(x), Term::from(y)])
}

pub fn go_to_block(id: i64) -> Term {
    Term::compound("goToBlock", vec![Term::Int(id)])
}

pub fn pick_up(id: i64) -> Term {
    Term::compound("pickUp", vec![Term::Int(id)])
}

pub fn put_down() -> Term {
    Term::atom("putDown")
}

/// Performs `action` for `bot` and asserts it was accepted.
pub fn ok(bw: &mut Bw4t, bot: &str, action: Term) {
    let r = bw.perform(bot, &action);
    assert_eq!(r, ActionResult::Ok, "{bot}: {action}");
}

/// The robot index of `bot`.
pub fn idx(bw: &Bw4t, bot: &str) -> usize {
    bw.world().robot_index(bot).expect("robot exists")
}

/// The state of `bot`.
pub fn state(bw: &Bw4t, bot: &str) -> RobotState {
    bw.world().robots[idx(bw, bot)].state()
}

/// Ticks until `bot` is no longer traveling (at most `max` ticks); returns the ticks taken.
pub fn run_until_stopped(bw: &mut Bw4t, bot: &str, max: u64) -> u64 {
    for n in 1..=max {
        bw.tick();
        if state(bw, bot) != RobotState::Traveling {
            return n;
        }
    }
    panic!("{bot} still traveling after {max} ticks");
}

/// Goes to `place` and waits until arrived; returns the ticks taken.
pub fn travel(bw: &mut Bw4t, bot: &str, place: &str) -> u64 {
    ok(bw, bot, go_to(place));
    let n = run_until_stopped(bw, bot, 5000);
    assert_eq!(state(bw, bot), RobotState::Arrived, "{bot} -> {place}");
    n
}

/// The zone name `bot` is in (or nearest to).
pub fn at(bw: &Bw4t, bot: &str) -> String {
    let w = bw.world();
    let z = w.nearest_zone(&w.robots[idx(bw, bot)].pos).expect("zone");
    w.zones[z].name.clone()
}

/// Ids of free blocks in zone `zone` with colour `colour`, in id order.
pub fn blocks_in(bw: &Bw4t, zone: &str, colour: &str) -> Vec<i64> {
    let w = bw.world();
    let z = w.zone_index(zone).expect("zone exists");
    w.free_blocks_in(z)
        .filter(|&b| w.blocks[b].color.name() == colour)
        .map(|b| w.blocks[b].id)
        .collect()
}

/// Printed terms of a batch.
pub fn show(batch: &[Term]) -> Vec<String> {
    batch.iter().map(|t| t.to_string()).collect()
}

/// True if the batch contains the printed term `text`.
pub fn has(batch: &[Term], text: &str) -> bool {
    batch.iter().any(|t| t.to_string() == text)
}

/// The printed terms of the batch with functor `name`.
pub fn named(batch: &[Term], name: &str) -> Vec<String> {
    batch
        .iter()
        .filter(|t| t.functor().is_some_and(|(n, _)| n.name() == name))
        .map(|t| t.to_string())
        .collect()
}

/// A typed percept base as the agent runtime keeps it: once-percepts stay, on-change percepts
/// replace the predicate's previous instances, `not(p)` deletes `p`, always-percepts are replaced
/// by each batch.
#[derive(Default)]
pub struct Base {
    pub facts: Vec<Term>,
}

impl Base {
    pub fn apply(&mut self, batch: &[Term]) {
        use goal::env::PerceptType;
        let decls = goal::bw4t::percepts::declarations();
        let kind = |t: &Term| {
            let (n, a) = t.functor()?;
            decls
                .iter()
                .find(|d| d.name == n.name() && d.arity == a)
                .map(|d| d.kind)
        };
        let same = |a: &Term, b: &Term| a.functor() == b.functor();
        self.facts.retain(|f| kind(f) != Some(PerceptType::Always));
        let mut replaced: Vec<Term> = Vec::new();
        for t in batch {
            if t.functor()
                .is_some_and(|(n, a)| n.name() == "not" && a == 1)
            {
                let p = &t.args()[0];
                self.facts.retain(|f| f != p);
                continue;
            }
            if kind(t) == Some(PerceptType::OnChange) && !replaced.iter().any(|r| same(r, t)) {
                self.facts.retain(|f| !same(f, t));
                replaced.push(t.clone());
            }
            if !self.facts.contains(t) {
                self.facts.push(t.clone());
            }
        }
    }

    pub fn has(&self, text: &str) -> bool {
        has(&self.facts, text)
    }

    pub fn named(&self, name: &str) -> Vec<String> {
        named(&self.facts, name)
    }
}

/// Travels to `room`, walks to a free block of `colour` there and picks it up; returns its id.
pub fn fetch(bw: &mut Bw4t, bot: &str, room: &str, colour: &str) -> i64 {
    travel(bw, bot, room);
    let id = *blocks_in(bw, room, colour)
        .first()
        .unwrap_or_else(|| panic!("no {colour} block in {room}"));
    ok(bw, bot, go_to_block(id));
    run_until_stopped(bw, bot, 1000);
    ok(bw, bot, pick_up(id));
    id
}
