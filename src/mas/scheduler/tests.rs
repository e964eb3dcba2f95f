//! The worker pool's tests.

use super::*;
use crate::agent::{AgentConfig, Directory, Program, TraceLevel};

/// `n` agents that print their name and a random number each cycle.
fn agents(n: usize) -> Vec<Agent> {
    let text = "main module {\n program {\n \
                if bel(me(Me), X is random(1000)) then print(Me-X).\n }\n}\n";
    let prog = Program::from_source("t.goal", text).expect("compiles");
    let names: Vec<String> = (0..n).map(|i| format!("a{i:02}")).collect();
    let directory = Directory::new(&names);
    names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let config = AgentConfig {
                seed: i as u64,
                directory: Some(directory.clone()),
                trace: TraceLevel::Off,
                ..AgentConfig::default()
            };
            Agent::new(prog.clone(), name, config)
        })
        .collect()
}

fn printed(out: Done) -> Vec<(usize, Vec<String>)> {
    out.into_iter().map(|(i, o)| (i, o.printed)).collect()
}

#[test]
fn a_cycle_written_over_a_used_output_gives_what_a_fresh_output_gets() {
    let (mut fresh, mut reused) = (agents(1), agents(1));
    let mut out = CycleOutput::default();
    for _ in 0..3 {
        // What the output held before goes to the agent, which must not carry it into
        // its next cycle.
        out.printed.push("stale".into());
        out.actions = 7;
        let want = fresh[0].step(&[], &[]);
        reused[0].step_into(&[], &[], &mut out);
        assert_eq!(out.printed, want.printed);
        assert_eq!(out.printed.len(), 1, "{:?}", out.printed);
        assert_eq!(out.actions, want.actions);
    }
}

#[test]
fn an_agent_keeps_its_emptied_inbox_for_its_next_outgoing_messages() {
    let agents: Vec<Mutex<Agent>> = agents(1).into_iter().map(Mutex::new).collect();
    let mut inbox = Vec::with_capacity(4);
    inbox.push(Message {
        sender: crate::term::Sym::intern("a00"),
        receiver: crate::term::Sym::intern("a00"),
        content: Term::atom("hi"),
    });
    let mut out = CycleOutput::default();
    run_one_into(&agents, None, (0, Vec::new(), inbox), &mut out).expect("cycle");
    // The next cycle sends nothing: its output carries the kept buffer, and a run of it
    // through the pool hands the buffer back to the agent.
    let mut a = agents[0].lock().expect("agent");
    let mut next = CycleOutput::default();
    a.step_into(&[], &[], &mut next);
    assert!(next.messages.is_empty());
    assert_eq!(next.messages.capacity(), 4);
    a.keep_buffer(Vec::new(), &mut next);
    assert_eq!(next.messages.capacity(), 0);
}

#[test]
fn a_round_shared_between_threads_gives_what_one_thread_gives() {
    let n = 23;
    let alone = Pool::new(agents(n), 1).expect("pool");
    let shared = Pool::new(agents(n), 3).expect("pool");
    assert_eq!(shared.workers(), 3);
    for round in 0..8 {
        // Every agent, or (odd rounds) a sparse set that leaves some threads' parts empty.
        let jobs = || {
            (0..n)
                .filter(|i| round % 2 == 0 || i % 3 == 1 || *i > 17)
                .map(|i| (i, Vec::new(), Vec::new()))
                .collect::<Vec<Job>>()
        };
        let mut a = Vec::new();
        step(&alone.agents, None, jobs(), &mut a).expect("round");
        let mut b = Vec::new();
        shared.shared(&mut jobs(), None, &mut b).expect("round");
        let (a, b) = (printed(a), printed(b));
        assert_eq!(a, b, "round {round}");
        assert_eq!(b.len(), jobs().len());
        assert!(b.iter().all(|(_, p)| p.len() == 1), "{b:?}");
    }
}

#[test]
fn each_thread_owns_a_contiguous_range_and_the_parts_cover_every_job_once() {
    let jobs =
        |ids: &[usize]| -> Vec<Job> { ids.iter().map(|&i| (i, Vec::new(), Vec::new())).collect() };
    let bounds = |p: &[Part]| -> Vec<(usize, usize)> {
        p.iter()
            .map(|p| (p.next.load(Ordering::Relaxed), p.end))
            .collect()
    };
    // 10 agents on 3 threads: agents 0-3, 4-6 and 7-9.
    assert_eq!(
        (0..10).map(|i| owner(i, 10, 3)).collect::<Vec<_>>(),
        [0, 0, 0, 0, 1, 1, 1, 2, 2, 2]
    );
    let p = parts(&jobs(&[1, 2, 5, 8, 9]), 10, 3);
    assert_eq!(bounds(&p), [(0, 2), (2, 3), (3, 5)]);
    // A thread with nothing of its own this round has an empty part.
    let p = parts(&jobs(&[7, 8]), 10, 3);
    assert_eq!(bounds(&p), [(0, 0), (0, 0), (0, 2)]);
    // Jobs out of order still give parts covering each job once.
    let p = parts(&jobs(&[9, 0, 5]), 10, 3);
    let b = bounds(&p);
    assert_eq!((b[0].0, b[2].1), (0, 3));
    assert!(b.windows(2).all(|w| w[0].1 == w[1].0), "{b:?}");
}

/// One job without input for each of agents `0..n`.
fn every_job(n: usize) -> Vec<Job> {
    (0..n).map(|i| (i, Vec::new(), Vec::new())).collect()
}

/// What the cycles of `jobs` print on `n` fresh agents run on one thread.
fn printed_alone(n: usize, jobs: Vec<Job>) -> Vec<(usize, Vec<String>)> {
    let alone = Pool::new(agents(n), 1).expect("pool");
    let mut a = Vec::new();
    step(&alone.agents, None, jobs, &mut a).expect("round");
    printed(a)
}

#[test]
fn a_thread_done_with_its_part_runs_the_parts_of_threads_that_never_came() {
    let n = 9;
    let pool = Pool::new(agents(n), 1).expect("pool");
    // A round split for three threads, of which only the calling thread (0) ever runs.
    let round = Round::new(&mut every_job(n), None, n, 3);
    round.work(&pool.agents, 0);
    let mut b = Vec::new();
    round.wait(&mut b).expect("round");
    assert_eq!(printed(b), printed_alone(n, every_job(n)));
    // A thread that comes late finds nothing left and changes nothing.
    round.work(&pool.agents, 2);
    assert_eq!(round.finished.load(Ordering::Relaxed), n);
}

#[test]
fn a_thread_leaves_the_part_of_a_thread_that_has_come_to_its_owner() {
    let n = 8;
    let pool = Pool::new(agents(n), 1).expect("pool");
    // Split for two threads (agents 0-3 and 4-7); thread 1 has come to the round.
    let round = Round::new(&mut every_job(n), None, n, 2);
    round.parts[1].started.store(true, Ordering::Relaxed);
    round.work(&pool.agents, 0);
    assert_eq!(
        round.finished.load(Ordering::Relaxed),
        4,
        "thread 0 ran only its own"
    );
    assert_eq!(
        round.parts[1].next.load(Ordering::Relaxed),
        4,
        "part 1 untouched"
    );
    round.work(&pool.agents, 1);
    let mut b = Vec::new();
    round.wait(&mut b).expect("round");
    assert_eq!(printed(b), printed_alone(n, every_job(n)));
}

/// Runs part 0 of `round` on this thread and part 1 on another, which comes after
/// `late`; returns what [`Round::wait`] gives after `before` (already in the output).
fn wait_for_a_late_thread(
    round: Round,
    pool: &Pool,
    late: Duration,
    before: Done,
) -> (Result<(), PoolError>, Done) {
    // Thread 1 counts as come: this thread leaves its part to it.
    round.parts[1].started.store(true, Ordering::Relaxed);
    let round = Arc::new(round);
    let other = {
        let (round, agents) = (round.clone(), pool.agents.clone());
        std::thread::spawn(move || {
            std::thread::sleep(late);
            round.work(&agents, 1);
        })
    };
    round.work(&pool.agents, 0);
    let mut out = before;
    let r = round.wait(&mut out);
    other.join().expect("thread");
    (r, out)
}

#[test]
fn outputs_are_taken_in_job_order_while_another_thread_still_runs_its_part() {
    let n = 8;
    let pool = Pool::new(agents(n), 1).expect("pool");
    // Part 1 comes at once (its outputs are taken as they come), after the spinning
    // (taken once all have finished), or in between.
    for late in [0, 30, 2_000] {
        let round = Round::new(&mut every_job(n), None, n, 2);
        let late = Duration::from_micros(late);
        let (r, out) = wait_for_a_late_thread(round, &pool, late, Vec::new());
        r.expect("round");
        let alone = printed_alone(n, every_job(n));
        // The agents ran once before in each earlier pass: compare names and order.
        let names = |p: Vec<(usize, Vec<String>)>| -> Vec<(usize, usize)> {
            p.into_iter().map(|(i, l)| (i, l.len())).collect()
        };
        assert_eq!(names(printed(out)), names(alone), "late {late:?}");
    }
}

#[test]
fn a_failure_in_another_threads_part_leaves_the_output_as_it_was() {
    // Six agents split for two threads of eight: parts 0-3 and 4-7; agent 6 does not exist.
    let pool = Pool::new(agents(6), 1).expect("pool");
    let mut jobs: Vec<Job> = [0, 1, 4, 6].map(|i| (i, Vec::new(), Vec::new())).into();
    let round = Round::new(&mut jobs, None, 8, 2);
    let before = vec![(99, CycleOutput::default())];
    let late = Duration::from_micros(500);
    let (r, out) = wait_for_a_late_thread(round, &pool, late, before);
    let err = r.expect_err("agent 6 fails");
    assert!(err.0.contains("index 6"), "{}", err.0);
    assert_eq!(out.len(), 1);
    assert_eq!(out[0].0, 99);
}

#[test]
fn a_round_with_several_failures_reports_the_lowest_agent_whichever_thread_ran_it() {
    // Five agents; jobs for agents 7 and 12 fail (no such agent). Split for three threads
    // of 16 agents, the parts are 0-5, 6-10 and 11-15.
    let pool = Pool::new(agents(5), 1).expect("pool");
    let jobs = || -> Vec<Job> { [0, 7, 12].map(|i| (i, Vec::new(), Vec::new())).into() };
    for first in 0..3 {
        let round = Round::new(&mut jobs(), None, 16, 3);
        // Thread `first` comes first and runs every part, its own first.
        round.work(&pool.agents, first);
        let err = round.wait(&mut Vec::new()).expect_err("two jobs fail");
        assert!(err.0.contains("index 7"), "thread {first} first: {}", err.0);
    }
}

#[test]
fn rounds_are_shared_only_while_sharing_is_faster() {
    let c = Costs::default();
    // Running alone is measured first.
    assert!(!c.share());
    c.record(false, Duration::from_micros(100), 10);
    // Then sharing, in a try of several rounds in a row: waking the workers makes the
    // first one slow, and it is not measured.
    for k in 0..TRY_ROUNDS {
        assert!(c.share(), "round {k} of the try");
        let took = if k == 0 { 4000 } else { 400 };
        c.record(true, Duration::from_micros(took), 10);
    }
    assert_eq!(c.shared.get(), 40_000.0);
    // Sharing is slower: rounds run alone, but sharing is tried again now and then, again
    // for several rounds in a row.
    let calls = EXPLORE_EVERY + TRY_ROUNDS - 1;
    let shared: Vec<u32> = (1..=calls).filter(|_| c.share()).collect();
    let tried: Vec<u32> = (EXPLORE_EVERY..=calls).collect();
    assert_eq!(shared, tried);
    // Once sharing has become the faster way, it is the one taken; running alone is tried
    // now and then, several rounds in a row.
    for _ in 0..40 {
        c.record(true, Duration::from_micros(20), 10);
    }
    let alone: Vec<u32> = (1..=calls).filter(|_| !c.share()).collect();
    assert_eq!(alone, tried);
}

#[test]
fn the_first_round_after_a_change_of_way_is_not_measured() {
    let c = Costs::default();
    c.record(false, Duration::from_micros(100), 10);
    // It woke the workers: left out.
    c.record(true, Duration::from_millis(10), 10);
    assert_eq!(c.shared.get(), 0.0);
    c.record(true, Duration::from_micros(50), 10);
    assert_eq!(c.shared.get(), 5_000.0);
    // It fetched the agents the workers ran: left out.
    c.record(false, Duration::from_millis(10), 10);
    assert_eq!(c.inline.get(), 10_000.0);
    c.record(true, Duration::from_millis(10), 10);
    assert_eq!(c.shared.get(), 5_000.0);
}
