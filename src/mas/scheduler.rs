//! The worker pool: each agent is owned by one worker; a round hands every worker the cycles to
//! run for its agents and collects the outputs, returned in agent-index order so the result
//! never depends on thread timing. Worker 0 is the calling (scheduler) thread itself, so with
//! `N` workers there are `N - 1` extra threads and a one-worker pool has no hand-offs at all.

use crate::agent::{Agent, CycleOutput, Message};
use crate::term::Term;
use crossbeam_channel::{unbounded, Receiver, Sender};
use std::thread::JoinHandle;

/// One cycle to run: agent index, percept batch, incoming messages.
pub type Job = (usize, Vec<Term>, Vec<Message>);

type Done = Vec<(usize, CycleOutput)>;

struct Worker {
    tx: Option<Sender<Vec<Job>>>,
    rx: Receiver<Done>,
    join: Option<JoinHandle<()>>,
}

/// A pool of workers owning the agents.
pub struct Pool {
    /// Workers 1.. (threads).
    threads: Vec<Worker>,
    /// Worker of each agent index.
    owner: Vec<usize>,
    /// The agents of worker 0 (run on the caller's thread).
    local: Vec<(usize, Agent)>,
}

/// Why the pool could not run a round.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PoolError(pub String);

impl Pool {
    /// Distributes `agents` (index = position) round-robin over `workers` workers (at least 1,
    /// at most one per agent).
    pub fn new(agents: Vec<Agent>, workers: usize) -> Result<Pool, PoolError> {
        let n = workers.clamp(1, agents.len().max(1));
        let mut owned: Vec<Vec<(usize, Agent)>> = (0..n).map(|_| Vec::new()).collect();
        let mut owner = Vec::with_capacity(agents.len());
        for (i, a) in agents.into_iter().enumerate() {
            owner.push(i % n);
            owned[i % n].push((i, a));
        }
        let mut owned = owned.into_iter();
        let local = owned.next().unwrap_or_default();
        let mut threads = Vec::with_capacity(n.saturating_sub(1));
        for (w, agents) in owned.enumerate() {
            let (job_tx, job_rx) = unbounded::<Vec<Job>>();
            let (done_tx, done_rx) = unbounded::<Done>();
            let join = std::thread::Builder::new()
                .name(format!("agents-{}", w + 1))
                .spawn(move || work(agents, job_rx, done_tx))
                .map_err(|e| PoolError(format!("cannot start a worker thread: {e}")))?;
            threads.push(Worker {
                tx: Some(job_tx),
                rx: done_rx,
                join: Some(join),
            });
        }
        Ok(Pool {
            threads,
            owner,
            local,
        })
    }

    /// The number of workers (including the caller's thread).
    pub fn workers(&self) -> usize {
        self.threads.len() + 1
    }

    /// Runs one cycle for each job (in parallel across workers) and returns the outputs sorted
    /// by agent index.
    pub fn round(&mut self, jobs: Vec<Job>) -> Result<Vec<(usize, CycleOutput)>, PoolError> {
        let mut per: Vec<Vec<Job>> = (0..self.workers()).map(|_| Vec::new()).collect();
        for job in jobs {
            let w = self
                .owner
                .get(job.0)
                .copied()
                .ok_or_else(|| PoolError(format!("no agent with index {}", job.0)))?;
            per[w].push(job);
        }
        let mut per = per.into_iter();
        let mine = per.next().unwrap_or_default();
        let mut busy = Vec::new();
        for (w, jobs) in per.enumerate() {
            if !jobs.is_empty() {
                self.threads[w]
                    .tx
                    .as_ref()
                    .and_then(|tx| tx.send(jobs).ok())
                    .ok_or_else(|| PoolError("a worker thread stopped".into()))?;
                busy.push(w);
            }
        }
        let mut out = step_all(&mut self.local, mine);
        for w in busy {
            let done = self.threads[w]
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
        for w in &mut self.threads {
            // Closing the job channel ends the worker loop.
            w.tx = None;
        }
        for w in &mut self.threads {
            if let Some(j) = w.join.take() {
                let _ = j.join();
            }
        }
    }
}

fn step_all(agents: &mut [(usize, Agent)], jobs: Vec<Job>) -> Done {
    let mut done = Vec::with_capacity(jobs.len());
    for (i, percepts, messages) in jobs {
        // Agents are stored in index order: binary search.
        if let Ok(k) = agents.binary_search_by_key(&i, |(j, _)| *j) {
            done.push((i, agents[k].1.step(&percepts, &messages)));
        }
    }
    done
}

fn work(mut agents: Vec<(usize, Agent)>, rx: Receiver<Vec<Job>>, tx: Sender<Done>) {
    while let Ok(jobs) = rx.recv() {
        if tx.send(step_all(&mut agents, jobs)).is_err() {
            break;
        }
    }
}
