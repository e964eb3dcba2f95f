//! The worker pool: each agent is owned by one worker thread; a round hands every worker the
//! cycles to run for its agents and collects the outputs, returned in agent-index order so the
//! result never depends on thread timing.

use crate::agent::{Agent, CycleOutput, Message};
use crate::term::Term;
use crossbeam_channel::{unbounded, Receiver, Sender};
use std::thread::JoinHandle;

/// One cycle to run: agent index, percept batch, incoming messages.
pub type Job = (usize, Vec<Term>, Vec<Message>);

type Done = Vec<(usize, CycleOutput)>;

struct Worker {
    tx: Sender<Vec<Job>>,
    rx: Receiver<Done>,
    join: Option<JoinHandle<()>>,
}

/// A pool of worker threads owning the agents.
pub struct Pool {
    workers: Vec<Worker>,
    owner: Vec<usize>,
}

/// Why the pool could not run a round.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PoolError(pub String);

impl Pool {
    /// Distributes `agents` (index = position) round-robin over `workers` threads (at least 1,
    /// at most one per agent).
    pub fn new(agents: Vec<Agent>, workers: usize) -> Result<Pool, PoolError> {
        let n = workers.clamp(1, agents.len().max(1));
        let mut owned: Vec<Vec<(usize, Agent)>> = (0..n).map(|_| Vec::new()).collect();
        let mut owner = Vec::with_capacity(agents.len());
        for (i, a) in agents.into_iter().enumerate() {
            owner.push(i % n);
            owned[i % n].push((i, a));
        }
        let mut ws = Vec::with_capacity(n);
        for (w, agents) in owned.into_iter().enumerate() {
            let (job_tx, job_rx) = unbounded::<Vec<Job>>();
            let (done_tx, done_rx) = unbounded::<Done>();
            let join = std::thread::Builder::new()
                .name(format!("agents-{w}"))
                .spawn(move || work(agents, job_rx, done_tx))
                .map_err(|e| PoolError(format!("cannot start a worker thread: {e}")))?;
            ws.push(Worker {
                tx: job_tx,
                rx: done_rx,
                join: Some(join),
            });
        }
        Ok(Pool { workers: ws, owner })
    }

    /// The number of worker threads.
    pub fn workers(&self) -> usize {
        self.workers.len()
    }

    /// Runs one cycle for each job (in parallel across workers) and returns the outputs sorted
    /// by agent index.
    pub fn round(&self, jobs: Vec<Job>) -> Result<Vec<(usize, CycleOutput)>, PoolError> {
        let mut per: Vec<Vec<Job>> = (0..self.workers.len()).map(|_| Vec::new()).collect();
        for job in jobs {
            let w = self
                .owner
                .get(job.0)
                .copied()
                .ok_or_else(|| PoolError(format!("no agent with index {}", job.0)))?;
            per[w].push(job);
        }
        let mut busy = Vec::new();
        for (w, jobs) in per.into_iter().enumerate() {
            if !jobs.is_empty() {
                self.workers[w]
                    .tx
                    .send(jobs)
                    .map_err(|_| PoolError("a worker thread stopped".into()))?;
                busy.push(w);
            }
        }
        let mut out = Vec::new();
        for w in busy {
            let done = self.workers[w]
                .rx
                .recv()
                .map_err(|_| PoolError("a worker thread stopped (panic in an agent?)".into()))?;
            out.extend(done);
        }
        out.sort_by_key(|(i, _)| *i);
        Ok(out)
    }
}

impl Drop for Pool {
    fn drop(&mut self) {
        for w in &mut self.workers {
            // Closing the job channel ends the worker loop.
            let (dead, _) = unbounded();
            w.tx = dead;
        }
        for w in &mut self.workers {
            if let Some(j) = w.join.take() {
                let _ = j.join();
            }
        }
    }
}

fn work(mut agents: Vec<(usize, Agent)>, rx: Receiver<Vec<Job>>, tx: Sender<Done>) {
    while let Ok(jobs) = rx.recv() {
        let mut done = Vec::with_capacity(jobs.len());
        for (i, percepts, messages) in jobs {
            if let Some((_, a)) = agents.iter_mut().find(|(j, _)| *j == i) {
                done.push((i, a.step(&percepts, &messages)));
            }
        }
        if tx.send(done).is_err() {
            break;
        }
    }
}
