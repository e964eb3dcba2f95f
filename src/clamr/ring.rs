//! The seed's token ring as a simulated transport. The agents sit on a ring in name order
//! (address = position + 1). Only the token holder sends: each round the holder transmits its
//! queued messages as frames, which travel the ring one hop per round; then it passes the token
//! to its neighbour, or, when it opened a conversation, to that partner as a session token (the
//! partner may then answer only the holder). Faults: a robot's link fails at a tick
//! (`--comm-fail Bot2@500`) and every message may be lost (`--comm-loss 0.05`, seeded). Each
//! node knows its next two neighbours, so the neighbour of a failed robot skips it and the ring
//! re-forms without a restart.

use super::act::{classify, SpeechAct};
use super::frame::{encode_message, Assembler, FRAME_LEN};
use crate::agent::Message;
use crate::mas::routing::{Carried, Transport};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::{BTreeMap, VecDeque};

/// Faults to inject into a ring.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Faults {
    /// Robots whose link fails, with the tick it fails at.
    pub fail: Vec<(String, u64)>,
    /// Probability that a message is lost (0 to 1).
    pub loss: f64,
}

/// A message on its way: arrives at round `due`.
#[derive(Debug)]
struct Flight {
    due: u64,
    message: Message,
}

/// The simulated token ring.
pub struct Ring {
    names: Vec<String>,
    index: BTreeMap<String, usize>,
    down: Vec<bool>,
    fail_at: Vec<Option<u64>>,
    /// What each node knows of the ring: its next two neighbours.
    next: Vec<(usize, usize)>,
    holder: usize,
    /// The holder holds a session token from this node: it may answer only it.
    session: Option<usize>,
    queues: Vec<VecDeque<Message>>,
    flights: VecDeque<Flight>,
    round: u64,
    rng: ChaCha8Rng,
    loss: f64,
    broken: bool,
    lost: u64,
    frames: u64,
    reformed: u64,
    notes: Vec<String>,
}

impl Ring {
    /// A ring of agents `names` (in name order) with `faults`, random draws from `seed`.
    pub fn new(names: &[String], faults: &Faults, seed: u64) -> Result<Ring, String> {
        let n = names.len();
        if n == 0 || n > 254 {
            return Err(format!(
                "the token ring takes 1 to 254 agents (one address byte each), not {n}"
            ));
        }
        if !(0.0..=1.0).contains(&faults.loss) {
            return Err(format!(
                "--comm-loss {} is not between 0 and 1",
                faults.loss
            ));
        }
        let index: BTreeMap<String, usize> = names
            .iter()
            .enumerate()
            .map(|(i, s)| (s.clone(), i))
            .collect();
        let mut fail_at = vec![None; n];
        for (who, tick) in &faults.fail {
            let Some(&i) = index.get(who) else {
                return Err(format!(
                    "--comm-fail {who}@{tick}: there is no agent {who} (agents: {})",
                    names.join(", ")
                ));
            };
            fail_at[i] = Some(*tick);
        }
        Ok(Ring {
            names: names.to_vec(),
            index,
            down: vec![false; n],
            fail_at,
            next: (0..n).map(|i| ((i + 1) % n, (i + 2) % n)).collect(),
            holder: 0,
            session: None,
            queues: vec![VecDeque::new(); n],
            flights: VecDeque::new(),
            round: 0,
            rng: ChaCha8Rng::seed_from_u64(seed ^ 0x7269_6e67),
            loss: faults.loss,
            broken: false,
            lost: 0,
            frames: 0,
            reformed: 0,
            notes: Vec::new(),
        })
    }

    /// The node after `x`, re-forming the ring past a failed neighbour (`x` knows the next two).
    fn pass(&mut self, x: usize) -> Option<usize> {
        let (n1, n2) = self.next[x];
        if !self.down[n1] {
            return Some(n1);
        }
        if self.down[n2] {
            if !self.broken {
                self.broken = true;
                self.notes.push(format!(
                    "ring broken: {} found both its next neighbours ({} and {}) failed; \
                     messages are lost from now on",
                    self.names[x], self.names[n1], self.names[n2]
                ));
            }
            return None;
        }
        // Skip the failed neighbour; learn the next-but-one from the new neighbour.
        self.next[x] = (n2, self.next[n2].0);
        self.reformed += 1;
        self.notes.push(format!(
            "ring re-formed: {} skips failed {} and now passes to {}",
            self.names[x], self.names[n1], self.names[n2]
        ));
        Some(n2)
    }

    /// Hops from `from` to `to` along the live ring (each mote forwarding to its neighbour).
    fn hops(&mut self, from: usize, to: usize) -> Option<u64> {
        if from == to {
            return Some(1);
        }
        let mut at = from;
        for h in 1..=self.names.len() as u64 {
            at = self.pass(at)?;
            if at == to {
                return Some(h);
            }
        }
        None
    }

    fn fail_due(&mut self, tick: u64, lost: &mut Vec<Message>) {
        for i in 0..self.names.len() {
            if !self.down[i] && self.fail_at[i].is_some_and(|t| t <= tick) {
                self.down[i] = true;
                self.notes.push(format!(
                    "ring: {}'s link failed at tick {tick}",
                    self.names[i]
                ));
                lost.extend(self.queues[i].drain(..));
            }
        }
    }

    /// Sends one message from the holder `h`: frames out and back in, or lost.
    fn transmit(&mut self, h: usize, m: Message, carried: &mut Carried) {
        let Some(&r) = self.index.get(m.receiver.name()) else {
            // Unknown receivers are the router's to report.
            carried.arrived.push(m);
            return;
        };
        if self.down[r] || self.broken {
            carried.lost.push(m);
            return;
        }
        let frames = match encode_message(h as u8 + 1, r as u8 + 1, m.sender.name(), &m.content) {
            Ok(f) => f,
            Err(e) => {
                self.notes.push(format!(
                    "message {} from {} to {} cannot be framed: {e}",
                    m.content, m.sender, m.receiver
                ));
                carried.lost.push(m);
                return;
            }
        };
        self.frames += frames.len() as u64;
        if self.loss > 0.0 && self.rng.gen::<f64>() < self.loss {
            carried.lost.push(m);
            return;
        }
        let Some(hops) = self.hops(h, r) else {
            carried.lost.push(m);
            return;
        };
        let mut asm = Assembler::default();
        let mut content = None;
        for f in &frames {
            match asm.push(f) {
                Ok(c) => content = c.or(content),
                Err(e) => {
                    self.notes
                        .push(format!("frame of {} unreadable: {e}", m.content));
                    carried.lost.push(m);
                    return;
                }
            }
        }
        let Some(content) = content else {
            carried.lost.push(m);
            return;
        };
        self.flights.push_back(Flight {
            due: self.round + hops - 1,
            message: Message { content, ..m },
        });
    }

    /// The holder's turn: send what it may, then pass the token on.
    fn turn(&mut self, carried: &mut Carried) {
        if self.broken {
            return;
        }
        let mut h = self.holder;
        if self.down[h] {
            // The token died with its holder: the next live node regenerates it.
            let Some(n) = self.pass(h) else { return };
            h = n;
            self.session = None;
        }
        let partner = self.session.take();
        let (send, keep): (Vec<Message>, Vec<Message>) = self.queues[h]
            .drain(..)
            .partition(|m| partner.is_none_or(|p| m.receiver.name() == self.names[p]));
        self.queues[h] = keep.into();
        let mut opened = None;
        for m in send {
            let act = classify(m.sender.name(), &m.content);
            if partner.is_none() && !matches!(act.sat, SpeechAct::Inform | SpeechAct::Acknowledge) {
                opened = self
                    .index
                    .get(m.receiver.name())
                    .copied()
                    .filter(|&r| !self.down[r]);
            }
            self.transmit(h, m, carried);
        }
        match opened.filter(|&r| r != h) {
            Some(r) => {
                // A session token: the partner may answer (only) the holder.
                self.session = Some(h);
                self.holder = r;
            }
            None => self.holder = self.pass(h).unwrap_or(h),
        }
    }
}

impl Transport for Ring {
    fn carry(&mut self, tick: u64, sent: Vec<Message>) -> Carried {
        self.round += 1;
        let mut carried = Carried::default();
        self.fail_due(tick, &mut carried.lost);
        for m in sent {
            match self.index.get(m.sender.name()).copied() {
                Some(s) if !self.down[s] && !self.broken => self.queues[s].push_back(m),
                _ => carried.lost.push(m),
            }
        }
        self.turn(&mut carried);
        while self.flights.front().is_some_and(|f| f.due <= self.round) {
            if let Some(f) = self.flights.pop_front() {
                carried.arrived.push(f.message);
            }
        }
        // Later flights may be due earlier (fewer hops): deliver those too, in order.
        let (now, later): (Vec<Flight>, Vec<Flight>) =
            self.flights.drain(..).partition(|f| f.due <= self.round);
        carried.arrived.extend(now.into_iter().map(|f| f.message));
        self.flights = later.into();
        self.lost += carried.lost.len() as u64;
        carried.notes = std::mem::take(&mut self.notes);
        carried
    }

    fn busy(&self) -> bool {
        !self.flights.is_empty() || self.queues.iter().any(|q| !q.is_empty())
    }

    fn stats(&self) -> serde_json::Value {
        let failed: Vec<&String> = self
            .names
            .iter()
            .zip(&self.down)
            .filter(|(_, d)| **d)
            .map(|(n, _)| n)
            .collect();
        serde_json::json!({
            "transport": "ring",
            "lost": self.lost,
            "frames": self.frames,
            "bytes": self.frames * FRAME_LEN as u64,
            "reformed": self.reformed,
            "failed": failed,
            "broken": self.broken,
        })
    }
}
