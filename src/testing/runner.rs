//! Running a `.test2g` file: parse and check it, load its MAS, then for each test index launch
//! the MAS afresh (lock-step, seeded) with the tested agents under [`Controller`]s, and step
//! every agent in name order until all tests are over or a bound runs out.
//!
//! Every named test block runs (decision 7): the i-th test of every agent block runs in the
//! i-th launch. Blocks named `before` and `after` are not tests; their sections run before and
//! after each test of that agent.

use super::blocks::BlocksWorld;
use super::controller::Controller;
use super::report::{Outcome, TestReport};
use crate::agent::{Agent, AgentConfig, Message, StopReason, TraceLevel};
use crate::bw4t::Bw4t;
use crate::diag::Diagnostic;
use crate::env::thread::{EnvHandle, Mode};
use crate::mas::launch::{Launch, Launcher};
use crate::mas::routing::Router;
use crate::mas::run::{agent_seed, env_params, percept_types, Quiet, RunOptions, TICK_SECONDS};
use crate::mas::{system, MasSystem};
use crate::syntax::mas2g::ast::MasFile;
use crate::syntax::test2g::ast::{MasTest, NamedTest, TestSection};
use crate::term::Term;
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Options of `goal test`.
#[derive(Clone, Debug)]
pub struct TestOptions {
    /// Bound on simulated time: environment ticks (rounds without an environment) per test.
    pub max_ticks: u64,
    /// Replaces the MAS file's seed.
    pub seed: Option<u64>,
    /// Do not step agents waiting for new input (the outcome is the same either way).
    pub skip_idle: bool,
}

impl Default for TestOptions {
    fn default() -> Self {
        TestOptions {
            max_ticks: 10_000,
            seed: None,
            skip_idle: true,
        }
    }
}

/// One agent's part of a launch: its name, the test's name and the sections to run.
struct Job<'a> {
    agent: String,
    test: String,
    sections: Vec<&'a TestSection>,
}

fn error_report(file: &str, agent: &str, test: &str, message: String) -> TestReport {
    TestReport {
        file: file.to_string(),
        agent: agent.to_string(),
        test: test.to_string(),
        outcome: Outcome::Error { message },
        cycles: 0,
        ticks: 0,
        watch: Vec::new(),
    }
}

fn render(diags: &[Diagnostic], source: &str) -> String {
    diags.iter().map(|d| d.render(source)).collect()
}

/// Runs every named test of the `.test2g` file at `path`.
pub fn run_file(path: &Path, opts: &TestOptions) -> Vec<TestReport> {
    let file = path.display().to_string();
    let source = match crate::syntax::check::read_source(path) {
        Ok(s) => s,
        Err(d) => return vec![error_report(&file, "-", "-", d.render(""))],
    };
    let (test, mut diags) = crate::syntax::test2g::parse(&source, &file);
    let Some(test) = test else {
        return vec![error_report(&file, "-", "-", render(&diags, &source))];
    };
    let base = path.parent().unwrap_or(Path::new(".")).to_path_buf();
    diags.extend(crate::syntax::test2g::check_files(&test, &base));
    let errors: Vec<Diagnostic> = diags.into_iter().filter(|d| d.is_error()).collect();
    if !errors.is_empty() {
        return vec![error_report(&file, "-", "-", render(&errors, &source))];
    }
    let mas_path = base.join(&test.mas.value);
    // A blocks world is not a `goal run` environment: find it in the MAS file here.
    let blocks = crate::syntax::check::read_source(&mas_path)
        .ok()
        .map(|text| crate::syntax::mas2g::parse(&text, &mas_path.display().to_string()).0)
        .filter(|m| BlocksWorld::from_mas(m).is_some());
    let system = match system::load_mas(&mas_path) {
        Ok(s) => s,
        Err(ps) => {
            let text = ps.iter().map(|p| p.render()).collect();
            return vec![error_report(&file, "-", "-", text)];
        }
    };
    let mut reports = Vec::new();
    for jobs in plan(&test) {
        let ctx = Ctx {
            system: &system,
            blocks: blocks.as_ref(),
            test: &test,
            file: &file,
            source: &source,
        };
        reports.extend(launch(&ctx, &jobs, opts));
    }
    reports
}

fn is_fixture(t: &NamedTest) -> bool {
    matches!(t.name.name.name(), "before" | "after")
}

/// The launches: the i-th holds the i-th test of every agent.
fn plan(test: &MasTest) -> Vec<Vec<Job<'_>>> {
    let mut launches: Vec<Vec<Job<'_>>> = Vec::new();
    for block in &test.agents {
        let fixture = |n: &str| block.tests.iter().find(|t| t.name.name.name() == n);
        let (before, after) = (fixture("before"), fixture("after"));
        let tests: Vec<&NamedTest> = block.tests.iter().filter(|t| !is_fixture(t)).collect();
        for (i, t) in tests.iter().enumerate() {
            let mut sections: Vec<&TestSection> = Vec::new();
            sections.extend(before.iter().flat_map(|b| b.sections.iter()));
            sections.extend(t.sections.iter());
            sections.extend(after.iter().flat_map(|b| b.sections.iter()));
            if launches.len() <= i {
                launches.push(Vec::new());
            }
            for a in &block.agents {
                launches[i].push(Job {
                    agent: a.name.name().to_string(),
                    test: t.name.name.name().to_string(),
                    sections: sections.clone(),
                });
            }
        }
    }
    launches
}

struct Slot {
    name: String,
    entity: Option<String>,
    agent: Agent,
    control: Option<(usize, Controller)>,
    stopped: bool,
    percepts: Vec<Term>,
    inbox: Vec<Message>,
}

/// What every launch of a test file shares.
struct Ctx<'a> {
    system: &'a MasSystem,
    /// The MAS file when it asks for the blocks world.
    blocks: Option<&'a MasFile>,
    test: &'a MasTest,
    file: &'a str,
    source: &'a str,
}

/// Launches the MAS once and runs `jobs`; one report per job.
fn launch(ctx: &Ctx<'_>, jobs: &[Job<'_>], opts: &TestOptions) -> Vec<TestReport> {
    let (system, test, file, source) = (ctx.system, ctx.test, ctx.file, ctx.source);
    let fail_all = |m: String| -> Vec<TestReport> {
        jobs.iter()
            .map(|j| error_report(file, &j.agent, &j.test, m.clone()))
            .collect()
    };
    let mut launcher = Launcher::new(&system.rules);
    let mut launches: Vec<Launch> = launcher.unconditional();
    let run_opts = RunOptions {
        seed: opts.seed,
        ..RunOptions::default()
    };
    let (env, info, seed) = match &system.env {
        Some(params) => {
            let (p, seed, _) = env_params(params, &run_opts, &mut Quiet);
            let world = match Bw4t::from_params(&p) {
                Ok(w) => w,
                Err(ds) => return fail_all(render(&ds, "")),
            };
            let handle = EnvHandle::spawn(Box::new(world), Mode::LockStep);
            match handle.info() {
                Ok(info) => (Some(handle), Some(info), seed),
                Err(e) => return fail_all(format!("environment: {e}")),
            }
        }
        None => match ctx.blocks.and_then(BlocksWorld::from_mas) {
            Some(Ok(world)) => {
                let handle = EnvHandle::spawn(Box::new(world), Mode::LockStep);
                match handle.info() {
                    Ok(info) => (Some(handle), Some(info), opts.seed.unwrap_or(0)),
                    Err(e) => return fail_all(format!("environment: {e}")),
                }
            }
            Some(Err(e)) => return fail_all(format!("blocks world: {e}")),
            None => (None, None, opts.seed.unwrap_or(0)),
        },
    };
    if let Some(info) = &info {
        for e in &info.entities {
            if let Some(l) = launcher.entity(e) {
                launches.extend(l);
            }
        }
    }
    launches.sort_by(|a, b| a.name.cmp(&b.name));
    let names: Vec<String> = launches.iter().map(|l| l.name.clone()).collect();
    let types = Arc::new(info.as_ref().map(percept_types).unwrap_or_default());
    let mut reports: Vec<Option<TestReport>> = vec![None; jobs.len()];
    let mut slots = Vec::new();
    for l in &launches {
        let Some(prog) = system.programs.get(&l.reference) else {
            return fail_all(format!(
                "launch of {}: no agent file `{}`",
                l.name, l.reference
            ));
        };
        let config = AgentConfig {
            seed: agent_seed(seed, &l.name),
            agents: names.clone(),
            percept_types: types.clone(),
            trace: TraceLevel::Changes,
            cycle_time: Some(crate::agent::DEFAULT_CYCLE_TIME),
            ..AgentConfig::default()
        };
        let job = jobs.iter().position(|j| j.agent == l.name);
        let (agent, control) = match job {
            Some(k) => match Controller::compile(prog, file, source, &jobs[k].sections) {
                Ok((p, c)) => {
                    let mut a = Agent::new(p, &l.name, config);
                    c.attach(&mut a);
                    (a, Some((k, c)))
                }
                Err(ds) => {
                    let j = &jobs[k];
                    reports[k] = Some(error_report(file, &j.agent, &j.test, render(&ds, source)));
                    (Agent::new(prog.clone(), &l.name, config), None)
                }
            },
            None => (Agent::new(prog.clone(), &l.name, config), None),
        };
        slots.push(Slot {
            name: l.name.clone(),
            entity: l.entity.clone(),
            agent,
            control,
            stopped: false,
            percepts: Vec::new(),
            inbox: Vec::new(),
        });
    }
    for (k, j) in jobs.iter().enumerate() {
        if reports[k].is_none() && !slots.iter().any(|s| s.name == j.agent) {
            let m = format!("agent `{}` was not launched by {}", j.agent, test.mas.value);
            reports[k] = Some(error_report(file, &j.agent, &j.test, m));
        }
    }
    let router = Router::new(&names);
    let deliver = |slots: &mut [Slot], batches: Vec<(String, Vec<Term>)>| {
        for (entity, batch) in batches {
            for s in slots.iter_mut() {
                if s.entity.as_deref() == Some(entity.as_str()) && !s.stopped {
                    s.percepts.extend(batch.iter().cloned());
                }
            }
        }
    };
    if let Some(h) = &env {
        match h.perceive(&[]) {
            Ok(b) => deliver(&mut slots, b),
            Err(e) => return fail_all(format!("environment: {e}")),
        }
    }
    let timeout = test
        .timeout
        .as_ref()
        .filter(|t| t.value > 0)
        .map(|t| Duration::from_secs(t.value));
    let start = Instant::now();
    let mut tick: u64 = 0;
    let mut rounds: u64 = 0;
    let mut env_done = false;
    let open = |slots: &[Slot]| {
        slots.iter().any(|s| {
            s.control
                .as_ref()
                .is_some_and(|(_, c)| c.outcome().is_none())
        })
    };
    while open(&slots) {
        let bound = if timeout.is_some_and(|t| start.elapsed() >= t) {
            Some(format!(
                "the timeout of {}s ran out",
                timeout.map_or(0, |t| t.as_secs())
            ))
        } else if rounds >= opts.max_ticks {
            Some(format!("the limit of {} ticks was reached", opts.max_ticks))
        } else {
            None
        };
        if let Some(reason) = bound {
            for s in slots.iter_mut() {
                if let Some((_, c)) = s.control.as_mut() {
                    c.time_out(&mut s.agent, &reason);
                }
            }
            break;
        }
        let mut actions: Vec<(String, Term)> = Vec::new();
        let mut sent: Vec<Message> = Vec::new();
        for s in slots.iter_mut() {
            if s.stopped {
                s.percepts.clear();
                s.inbox.clear();
                continue;
            }
            let busy = s.control.as_ref().is_some_and(|(_, c)| c.busy(&s.agent));
            let idle = s.agent.waiting() && s.percepts.is_empty() && s.inbox.is_empty();
            if !busy && idle && opts.skip_idle {
                continue;
            }
            if let Some((_, c)) = &s.control {
                c.before_step(&s.agent);
            }
            let percepts = std::mem::take(&mut s.percepts);
            let inbox = std::mem::take(&mut s.inbox);
            s.agent.set_clock(Some(tick as f64 * TICK_SECONDS));
            let out = s.agent.step(&percepts, &inbox);
            if let Some((_, c)) = s.control.as_mut() {
                c.after_step(&mut s.agent);
            }
            // An agent without an entity has no environment to act on: the action's
            // postcondition is its whole effect (e.g. the blocks-world stacker).
            if let Some(e) = &s.entity {
                actions.extend(out.env_actions.into_iter().map(|a| (e.clone(), a)));
            }
            sent.extend(out.messages);
            match out.stopped {
                Some(StopReason::Error(_)) | Some(StopReason::MainExited) => s.stopped = true,
                None => {}
            }
        }
        sent.sort_by(|a, b| a.sender.cmp(&b.sender));
        let mut inboxes: Vec<Vec<Message>> = vec![Vec::new(); slots.len()];
        let _undelivered = router.route(sent, &mut inboxes);
        for (s, b) in slots.iter_mut().zip(inboxes) {
            if !s.stopped {
                s.inbox.extend(b);
            }
        }
        match &env {
            Some(h) if !env_done => match h.round(actions) {
                Ok(reply) => {
                    tick = reply.tick;
                    env_done = reply.finished;
                    deliver(&mut slots, reply.percepts);
                }
                Err(e) => {
                    let reason = format!("the environment failed: {e}");
                    for s in slots.iter_mut() {
                        if let Some((_, c)) = s.control.as_mut() {
                            c.time_out(&mut s.agent, &reason);
                        }
                    }
                    break;
                }
            },
            _ => tick += 1,
        }
        rounds += 1;
    }
    if let Some(h) = env {
        h.stop();
    }
    for s in slots {
        if let Some((k, c)) = s.control {
            let outcome = c.outcome().cloned().unwrap_or(Outcome::Error {
                message: "the test did not finish".into(),
            });
            reports[k] = Some(TestReport {
                file: file.to_string(),
                agent: jobs[k].agent.clone(),
                test: jobs[k].test.clone(),
                outcome,
                cycles: s.agent.cycles(),
                ticks: tick,
                watch: c.watch.clone(),
            });
        }
    }
    reports.into_iter().flatten().collect()
}
