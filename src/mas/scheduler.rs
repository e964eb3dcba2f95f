//! The worker pool: each thread owns a contiguous range of the agents (the calling thread
//! included) and runs their cycles of a shared round, claiming them a few at a time; a thread
//! done with its own part claims what is left of the parts of threads that have not come to
//! the round yet. The outputs are returned in agent-index order, so the result never depends
//! on thread timing. Owning keeps an agent's state (its engine heap, fact base, mailbox) in the
//! cache of the core that ran it last, and a token ring's messages mostly stay within one
//! thread's range; claiming from the others keeps a round moving when the machine is busy: a
//! worker thread that waits for a core only takes work once it runs, and until then the others
//! take its part; once it has come, its part is its own. Rounds with very few cycles
//! (a token ring moves one agent per round) run entirely on the calling thread: waking a
//! thread costs more than such a cycle. Between rounds both sides wait by spinning briefly
//! before they block: rounds are often shorter than putting a thread to sleep and waking it.
//!
//! Whether sharing a round pays depends on the machine: on a busy one a worker thread may wait
//! milliseconds for a core while the round's cycles take a fraction of that. The pool measures
//! the time per cycle of both ways and shares a round only while sharing is the faster one,
//! trying the other way now and then. Only timing depends on this choice, never a result.

use crate::agent::{Agent, CycleOutput, Message};
use crate::term::Term;
use crossbeam_channel::{unbounded, Receiver, RecvError, Sender, TryRecvError};
use std::cell::Cell;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long a thread waiting for the other side of a round spins before it blocks.
const SPIN: Duration = Duration::from_micros(50);

/// How long in all the calling thread spins while taking a shared round's outputs as they
/// come: with more threads than cores, a spinning caller holds a core the others need.
const SPIN_ROUND: Duration = Duration::from_micros(400);

/// The next value on `rx`: polled for up to [`SPIN`], then waited for asleep.
fn wait<T>(rx: &Receiver<T>) -> Result<T, RecvError> {
    let start = Instant::now();
    loop {
        for _ in 0..64 {
            match rx.try_recv() {
                Ok(v) => return Ok(v),
                Err(TryRecvError::Disconnected) => return Err(RecvError),
                Err(TryRecvError::Empty) => std::hint::spin_loop(),
            }
        }
        if start.elapsed() >= SPIN {
            return rx.recv();
        }
    }
}

/// One cycle to run: agent index, percept batch, incoming messages.
pub type Job = (usize, Vec<Term>, Vec<Message>);

type Done = Vec<(usize, CycleOutput)>;

/// Cycles a thread claims at a time from a shared round: few, so that the last claims end
/// close together, but enough to keep the claiming itself cheap.
const CHUNK: usize = 4;

/// One thread's part of a shared round: the jobs `next..end` not claimed yet.
struct Part {
    next: AtomicUsize,
    end: usize,
    /// Its owner has come to the round: from then on only the owner claims its jobs.
    started: AtomicBool,
}

/// A round shared between threads: its cycles (in agent-index order), each thread's part of
/// them, and how far it got.
struct Round {
    clock: Option<f64>,
    /// Each cycle of the round: its job until a thread claims it, then its output. Outputs stay
    /// in place, so the round's result is read in job order without collecting or sorting.
    cells: Vec<Slot>,
    /// Part `t` holds the jobs of the agents thread `t` owns (see [`owner`]).
    parts: Vec<Part>,
    /// Jobs finished (mirrors `ended.finished`, read while spinning).
    finished: AtomicUsize,
    ended: Mutex<Ended>,
    all_done: Condvar,
}

/// A cycle's place in a shared round: the cycle, and whether it has ended (its output, or
/// its failure, is in place), so that the calling thread can take the outputs in job order
/// while the other threads still run their last cycles.
struct Slot {
    cycle: Mutex<Cycle>,
    ended: AtomicBool,
}

/// One cycle of a shared round.
enum Cycle {
    Job(Job),
    Done(usize, CycleOutput),
    /// Claimed, or its output taken (or its agent failed: see [`Ended::error`]).
    Empty,
}

impl Cycle {
    fn take(&mut self) -> Cycle {
        std::mem::replace(self, Cycle::Empty)
    }
}

/// The thread (of `threads`) that owns agent `i` of `agents`: contiguous ranges of agents.
fn owner(i: usize, agents: usize, threads: usize) -> usize {
    (i * threads / agents.max(1)).min(threads - 1)
}

/// The parts of `jobs` (sorted by agent index) owned by each of `threads` threads.
fn parts(jobs: &[Job], agents: usize, threads: usize) -> Vec<Part> {
    let mut start = 0;
    (0..threads)
        .map(|t| {
            let end = if t + 1 == threads {
                jobs.len()
            } else {
                // `max`: unsorted jobs still give parts that cover every job once.
                jobs.partition_point(|j| owner(j.0, agents, threads) <= t)
                    .max(start)
            };
            let p = Part {
                next: AtomicUsize::new(start),
                end,
                started: AtomicBool::new(false),
            };
            start = end;
            p
        })
        .collect()
}

/// How many cycles of a shared round have finished, and the failure of the agent with the
/// lowest index (the same whichever thread ran which agent).
#[derive(Default)]
struct Ended {
    finished: usize,
    error: Option<(usize, PoolError)>,
}

/// Keeps in `slot` the failure of the lower agent index of it and `(i, e)`.
fn keep_lowest(slot: &mut Option<(usize, PoolError)>, i: usize, e: PoolError) {
    if slot.as_ref().is_none_or(|(j, _)| i < *j) {
        *slot = Some((i, e));
    }
}

/// Locks `m`, also after a panic while it was held: nothing here panics holding these locks
/// (agent panics are caught inside [`run_one`]), and the data stays whole either way.
fn lock<T>(m: &Mutex<T>) -> std::sync::MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

impl Round {
    /// A round of the `jobs` (sorted by agent index, taken out) for `threads` threads over
    /// `agents` agents, with the agents' clocks at `clock`.
    fn new(jobs: &mut Vec<Job>, clock: Option<f64>, agents: usize, threads: usize) -> Round {
        let parts = parts(jobs, agents, threads);
        let slot = |j| Slot {
            cycle: Mutex::new(Cycle::Job(j)),
            ended: AtomicBool::new(false),
        };
        let cells = jobs.drain(..).map(slot).collect();
        Round {
            clock,
            cells,
            parts,
            finished: AtomicUsize::new(0),
            ended: Mutex::new(Ended::default()),
            all_done: Condvar::new(),
        }
    }

    /// Thread `me` runs claimed chunks of its own part of the round, then of the other parts,
    /// until none is left; each output goes back into its job's cell.
    fn work(&self, agents: &[Mutex<Agent>], me: usize) {
        let mut error = None;
        let mut count = 0;
        let n = self.parts.len();
        if let Some(own) = self.parts.get(me) {
            own.started.store(true, Ordering::Relaxed);
        }
        for (k, part) in (0..n).map(|k| (k, &self.parts[(me + k) % n])) {
            loop {
                // Another thread's part is left to it once it has come: running an agent on
                // another core moves its state (fact base, engine heap, mailbox) there and
                // back, which costs more than the cycle. Only the part of a thread that has
                // not come yet (waiting for a core) is taken.
                if k > 0 && part.started.load(Ordering::Relaxed) {
                    break;
                }
                let from = part.next.fetch_add(CHUNK, Ordering::Relaxed);
                if from >= part.end {
                    break;
                }
                let to = (from + CHUNK).min(part.end);
                for slot in &self.cells[from..to] {
                    let Cycle::Job(job) = lock(&slot.cycle).take() else {
                        continue;
                    };
                    let i = job.0;
                    match run_one(agents, self.clock, job) {
                        Ok(out) => *lock(&slot.cycle) = Cycle::Done(i, out),
                        Err(e) => keep_lowest(&mut error, i, e),
                    }
                    slot.ended.store(true, Ordering::Release);
                }
                count += to - from;
            }
        }
        if count == 0 {
            return;
        }
        let mut e = lock(&self.ended);
        if let Some((i, err)) = error {
            keep_lowest(&mut e.error, i, err);
        }
        e.finished += count;
        self.finished.store(e.finished, Ordering::Release);
        if e.finished == self.cells.len() {
            self.all_done.notify_all();
        }
    }

    /// Waits (spinning first) until every job of the round has finished, and appends the
    /// outputs, in job order, to `out`. While spinning it takes each output as soon as its
    /// cycle has ended: the outputs of the thread's own part at once, those of the others
    /// while they still run their last cycles. Reading another core's outputs (cache misses)
    /// then overlaps with that core's work instead of following it.
    fn wait(&self, out: &mut Done) -> Result<(), PoolError> {
        let n = self.cells.len();
        let before = out.len();
        out.reserve(n);
        let mut taken = 0;
        // When the thread began waiting, and when the output waited for stopped coming (the
        // clock is read only while waiting): it spins while outputs come less than SPIN apart,
        // for SPIN_ROUND at most.
        let (mut began, mut since): (Option<Instant>, Option<Instant>) = (None, None);
        while taken < n {
            if self.cells[taken].ended.load(Ordering::Acquire) {
                Self::take(&self.cells[taken], out);
                taken += 1;
                since = None;
                continue;
            }
            let now = Instant::now();
            let (began, since) = (*began.get_or_insert(now), *since.get_or_insert(now));
            if now - since >= SPIN || now - began >= SPIN_ROUND {
                break;
            }
            for _ in 0..64 {
                std::hint::spin_loop();
            }
        }
        let mut e = lock(&self.ended);
        while e.finished < n {
            e = self.all_done.wait(e).unwrap_or_else(|e| e.into_inner());
        }
        if let Some((_, err)) = e.error.take() {
            out.truncate(before);
            return Err(err);
        }
        drop(e);
        for slot in &self.cells[taken..] {
            Self::take(slot, out);
        }
        Ok(())
    }

    /// Appends the output in `slot` (none when its agent failed) to `out`.
    fn take(slot: &Slot, out: &mut Done) {
        if let Cycle::Done(i, o) = lock(&slot.cycle).take() {
            out.push((i, o));
        }
    }
}

/// Rounds with fewer cycles than this run on the calling thread only.
const INLINE_BELOW: usize = 4;

/// The agents, each behind its own lock (a round never runs one agent twice, so the locks
/// are never contended; they make sharing the agents between threads safe).
type Agents = Arc<Vec<Mutex<Agent>>>;

struct Worker {
    tx: Sender<Arc<Round>>,
    join: Option<JoinHandle<()>>,
}

/// Rounds between two tries of the way of running rounds that is currently the slower one.
const EXPLORE_EVERY: u32 = 128;

/// Rounds in a row that make one try of the slower way. The first round after a change of
/// way is not measured: a shared one pays for waking the workers, asleep since the rounds run
/// alone, and one run alone for fetching the state of the agents the workers ran from their
/// cores' caches; a try of one round would only ever measure that.
const TRY_ROUNDS: u32 = 8;

/// Weight of the newest round in the running mean of the time per cycle.
const NEWEST: f64 = 0.1;

/// The running mean time per cycle (nanoseconds) of rounds run on the calling thread alone
/// and of rounds shared with the workers; 0 until measured.
#[derive(Default)]
struct Costs {
    inline: Cell<f64>,
    shared: Cell<f64>,
    /// Rounds that could be shared since the slower way was last tried.
    since_try: Cell<u32>,
    /// Rounds still to come in the current try.
    trying: Cell<u32>,
    /// The way being tried (true: shared).
    trying_shared: Cell<bool>,
    /// The way the last round ran (true: shared).
    last: Cell<Option<bool>>,
}

impl Costs {
    /// True when the next round of enough cycles should be shared.
    fn share(&self) -> bool {
        let left = self.trying.get();
        if left > 0 {
            self.trying.set(left - 1);
            return self.trying_shared.get();
        }
        let (i, s) = (self.inline.get(), self.shared.get());
        if i == 0.0 {
            // Measure running alone first, then sharing.
            return false;
        }
        let n = self.since_try.get() + 1;
        let explore = s == 0.0 || n == EXPLORE_EVERY;
        self.since_try.set(if explore { 0 } else { n });
        let faster = s != 0.0 && s < i;
        if explore {
            self.trying.set(TRY_ROUNDS - 1);
            self.trying_shared.set(!faster);
        }
        faster != explore
    }

    /// Takes the time `took` of a round of `cycles` cycles run one way into its mean; the
    /// first round after a change of way is left out (see [`TRY_ROUNDS`]).
    fn record(&self, shared: bool, took: Duration, cycles: usize) {
        let changed = self.last.replace(Some(shared)).is_some_and(|l| l != shared);
        if changed {
            return;
        }
        let per = took.as_nanos() as f64 / cycles.max(1) as f64;
        let mean = if shared { &self.shared } else { &self.inline };
        let old = mean.get();
        mean.set(if old == 0.0 {
            per
        } else {
            old + NEWEST * (per - old)
        });
    }
}

/// A pool of threads running agent cycles.
pub struct Pool {
    agents: Agents,
    workers: Vec<Worker>,
    costs: Costs,
    /// The last round that could have been shared, while its time is still running.
    open: Cell<Option<Open>>,
}

/// A round whose time is taken when the next round that could be shared starts.
#[derive(Clone, Copy)]
struct Open {
    shared: bool,
    start: Instant,
    cycles: usize,
}

/// Why the pool could not run a round.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PoolError(pub String);

/// Runs `jobs` on this thread with the agents' clocks at `clock`; outputs go to `done`.
fn step(
    agents: &[Mutex<Agent>],
    clock: Option<f64>,
    jobs: impl IntoIterator<Item = Job>,
    done: &mut Done,
) -> Result<(), PoolError> {
    for job in jobs {
        // Built in place: the output is not moved through `run_one`'s result and the push.
        done.push((job.0, CycleOutput::default()));
        let Some((_, out)) = done.last_mut() else {
            continue;
        };
        if let Err(e) = run_one_into(agents, clock, job, out) {
            done.pop();
            return Err(e);
        }
    }
    Ok(())
}

/// [`run_one`] writing the cycle's output over `out`.
#[inline]
fn run_one_into(
    agents: &[Mutex<Agent>],
    clock: Option<f64>,
    (i, percepts, messages): Job,
    out: &mut CycleOutput,
) -> Result<(), PoolError> {
    let cell = agents
        .get(i)
        .ok_or_else(|| PoolError(format!("no agent with index {i}")))?;
    let mut a = cell
        .lock()
        .map_err(|_| PoolError("an agent panicked in an earlier round".into()))?;
    // A panic in an agent is a bug; report it as a failed round instead of unwinding
    // through the run loop.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        a.set_clock(clock);
        a.step_into(&percepts, &messages, out);
        a.keep_buffer(messages, out);
    }))
    .map_err(|_| PoolError(format!("agent {i} panicked")))
}

/// Runs one cycle of `job` on this thread with the agent's clock at `clock`.
#[inline]
fn run_one(
    agents: &[Mutex<Agent>],
    clock: Option<f64>,
    job: Job,
) -> Result<CycleOutput, PoolError> {
    let mut out = CycleOutput::default();
    run_one_into(agents, clock, job, &mut out)?;
    Ok(out)
}

impl Pool {
    /// A pool running `agents` (index = position) on `workers` threads in all (at least 1, at
    /// most one per agent), the calling thread included.
    pub fn new(agents: Vec<Agent>, workers: usize) -> Result<Pool, PoolError> {
        let n = workers.clamp(1, agents.len().max(1));
        let agents: Agents = Arc::new(agents.into_iter().map(Mutex::new).collect());
        let mut ws = Vec::with_capacity(n - 1);
        for w in 1..n {
            let (job_tx, job_rx) = unbounded::<Arc<Round>>();
            let shared = agents.clone();
            let join = std::thread::Builder::new()
                .name(format!("agents-{w}"))
                .spawn(move || work(shared, job_rx, w))
                .map_err(|e| PoolError(format!("cannot start a worker thread: {e}")))?;
            ws.push(Worker {
                tx: job_tx,
                join: Some(join),
            });
        }
        Ok(Pool {
            agents,
            workers: ws,
            costs: Costs::default(),
            open: Cell::new(None),
        })
    }

    /// Stops agent `i` with a runtime error (between rounds).
    pub fn halt(&self, i: usize, e: crate::agent::RuntimeError) {
        self.with_agent(i, |a| a.halt(e));
    }

    /// Runs `f` on agent `i` (between rounds); `None` when there is no such agent.
    pub fn with_agent<T>(&self, i: usize, f: impl FnOnce(&mut Agent) -> T) -> Option<T> {
        let mut a = self.agents.get(i)?.lock().ok()?;
        Some(f(&mut a))
    }

    /// The number of threads running agents (the calling thread included).
    pub fn workers(&self) -> usize {
        self.workers.len() + 1
    }

    /// Runs one cycle for each job (in parallel across threads) and returns the outputs sorted
    /// by agent index; `clock` is the simulated time `get_time/1` answers (`None`: wall clock).
    pub fn round(
        &self,
        mut jobs: Vec<Job>,
        clock: Option<f64>,
    ) -> Result<Vec<(usize, CycleOutput)>, PoolError> {
        let mut out = Vec::with_capacity(jobs.len());
        self.round_into(&mut jobs, clock, &mut out)?;
        Ok(out)
    }

    /// [`Pool::round`] with the caller's buffers, kept from round to round: takes the jobs out
    /// of `jobs` and appends the outputs, sorted by agent index, to the empty `out`.
    pub fn round_into(
        &self,
        jobs: &mut Vec<Job>,
        clock: Option<f64>,
        out: &mut Vec<(usize, CycleOutput)>,
    ) -> Result<(), PoolError> {
        let cycles = jobs.len();
        let shareable = cycles >= INLINE_BELOW && !self.workers.is_empty();
        let now = Instant::now();
        // The last round's time runs up to now: it includes the run loop's work on its
        // outputs, which costs more when they were made on another core (ring50: 3.7 µs
        // between rounds run alone, 6-8 µs between shared ones, in a round of 25-45 µs).
        let last = self.open.take();
        if !shareable {
            // Rounds this short are never shared; the open round's time would include this
            // one, so it is not taken.
            step(&self.agents, clock, jobs.drain(..), out)?;
        } else {
            if let Some(o) = last {
                self.costs.record(o.shared, now - o.start, o.cycles);
            }
            let shared = self.costs.share();
            if shared {
                self.shared(jobs, clock, out)?;
            } else {
                step(&self.agents, clock, jobs.drain(..), out)?;
            }
            self.open.set(Some(Open {
                shared,
                start: now,
                cycles,
            }));
        }
        // Usually in order already (jobs come in agent order): then a single pass.
        out.sort_by_key(|(i, _)| *i);
        Ok(())
    }

    /// Runs a round on every thread: each takes cycles until none is left. The outputs are
    /// appended to `out` in job order.
    fn shared(
        &self,
        jobs: &mut Vec<Job>,
        clock: Option<f64>,
        out: &mut Done,
    ) -> Result<(), PoolError> {
        let round = Arc::new(Round::new(jobs, clock, self.agents.len(), self.workers()));
        // A worker that stopped only leaves more of the round to the calling thread.
        for w in &self.workers {
            let _ = w.tx.send(round.clone());
        }
        round.work(&self.agents, 0);
        round.wait(out)
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

/// Worker thread `me`: runs its part of each round it is handed (and helps with the others).
fn work(agents: Agents, rx: Receiver<Arc<Round>>, me: usize) {
    while let Ok(round) = wait(&rx) {
        round.work(&agents, me);
    }
}

#[cfg(test)]
mod tests;
