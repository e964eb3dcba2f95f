//! Running a `.test2g` file: parse and check it, load its MAS, then for each test index launch
//! the MAS afresh with the tested agents under [`Controller`]s, on the same round driver as
//! `goal run` (`mas::run`, the controllers take part as its observer), until all tests are
//! over or a bound runs out.
//!
//! Every named test block runs (decision 7): the i-th test of every agent block runs in the
//! i-th launch. Blocks named `before` and `after` are not tests; their sections run before and
//! after each test of that agent.

use super::controller::Controller;
use super::report::{Outcome, TestReport};
use crate::agent::{Agent, AgentConfig, Program, TraceLevel};
use crate::diag::Diagnostic;
use crate::mas::run::{Observer, RunOptions};
use crate::mas::{system, EndReason, MasSystem};
use crate::syntax::test2g::ast::{MasTest, NamedTest, TestSection};
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;
use std::time::Duration;

/// Options of `goal test`.
#[derive(Clone, Debug)]
pub struct TestOptions {
    /// Bound on simulated time: environment ticks (rounds without an environment) per test.
    pub max_ticks: u64,
    /// Replaces the MAS file's seed.
    pub seed: Option<u64>,
    /// Do not step agents waiting for new input (the outcome is the same either way).
    pub skip_idle: bool,
    /// The KR engine of agents whose `.mas2g` entry does not choose one.
    pub kr: crate::kr::KrKind,
}

impl Default for TestOptions {
    fn default() -> Self {
        TestOptions {
            max_ticks: 10_000,
            seed: None,
            skip_idle: true,
            kr: crate::kr::KrKind::Native,
        }
    }
}

/// One agent's part of a launch: its name, the test's name and the sections to run.
#[derive(Clone)]
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

/// What every launch of a test file shares.
struct Ctx<'a> {
    system: &'a MasSystem,
    test: &'a MasTest,
    file: &'a str,
    source: &'a str,
}

/// The test controllers of one launch, taking part in the run as its observer: they create
/// the tested agents, step them while a section runs, and end the run when every test is over.
struct Tests<'a, 'j> {
    ctx: &'a Ctx<'a>,
    /// The planned jobs, then one per agent launched from a definition a job names.
    jobs: Vec<Job<'j>>,
    /// Per agent index: the job it runs and its controller.
    controllers: BTreeMap<usize, (usize, Controller)>,
    /// Reports decided before the run (compile errors).
    reports: Vec<Option<TestReport>>,
    launched: Vec<bool>,
    /// The last warning of the run (says why the environment failed).
    last_warning: String,
    timeout: Option<Duration>,
    max_ticks: u64,
}

impl Tests<'_, '_> {
    /// (A) test files name agent definitions (`robot { do main. }`): an agent launched from
    /// a definition that a job names gets its own copy of that job.
    fn definition_job(&mut self, name: &str, program: &Arc<Program>) -> Option<usize> {
        if crate::syntax::modular::test2g::is_classic(self.ctx.source) {
            return None;
        }
        let programs = &self.ctx.system.programs;
        let t = self.jobs.iter().position(|j| {
            programs
                .get(&j.agent)
                .is_some_and(|p| Arc::ptr_eq(p, program))
        })?;
        let mut job = self.jobs[t].clone();
        job.agent = name.to_string();
        // The definition's own job is covered by the agents launched from it.
        self.launched[t] = true;
        self.jobs.push(job);
        self.reports.push(None);
        self.launched.push(false);
        Some(self.jobs.len() - 1)
    }
}

impl Observer for Tests<'_, '_> {
    fn warning(&mut self, text: &str) {
        self.last_warning = text.to_string();
    }
    fn agent(
        &mut self,
        i: usize,
        name: &str,
        program: &Arc<Program>,
        config: &AgentConfig,
    ) -> Option<Agent> {
        let k = match self.jobs.iter().position(|j| j.agent == name) {
            Some(k) => k,
            None => self.definition_job(name, program)?,
        };
        self.launched[k] = true;
        let (file, source) = (self.ctx.file, self.ctx.source);
        let config = AgentConfig {
            trace: TraceLevel::Changes,
            ..config.clone()
        };
        match Controller::compile(program, file, source, &self.jobs[k].sections) {
            Ok((p, c)) => {
                let mut a = Agent::new(p, name, config);
                c.attach(&mut a);
                self.controllers.insert(i, (k, c));
                Some(a)
            }
            Err(ds) => {
                let j = &self.jobs[k];
                let m = render(&ds, source);
                self.reports[k] = Some(error_report(file, &j.agent, &j.test, m));
                None
            }
        }
    }
    fn steers(&self) -> Vec<usize> {
        self.controllers.keys().copied().collect()
    }
    fn busy(&self, i: usize, agent: &Agent) -> bool {
        self.controllers.get(&i).is_some_and(|(_, c)| c.busy(agent))
    }
    fn before_step(&mut self, i: usize, agent: &Agent) {
        if let Some((_, c)) = self.controllers.get(&i) {
            c.before_step(agent);
        }
    }
    fn after_step(&mut self, i: usize, agent: &mut Agent) {
        if let Some((_, c)) = self.controllers.get_mut(&i) {
            c.after_step(agent);
        }
    }
    fn done(&self) -> bool {
        self.controllers
            .values()
            .all(|(_, c)| c.outcome().is_some())
    }
    fn ended(&mut self, i: usize, agent: &mut Agent, end: EndReason) {
        let reason = match end {
            EndReason::TimeLimit => format!(
                "the timeout of {}s ran out",
                self.timeout.map_or(0, |t| t.as_secs())
            ),
            EndReason::TickLimit | EndReason::CycleLimit => {
                format!("the limit of {} ticks was reached", self.max_ticks)
            }
            EndReason::Failure => format!("the environment failed: {}", self.last_warning),
            _ => return,
        };
        if let Some((_, c)) = self.controllers.get_mut(&i) {
            c.time_out(agent, &reason);
        }
    }
}

/// Launches the MAS once and runs `jobs` on the round driver of `goal run`; one report per
/// job.
fn launch(ctx: &Ctx<'_>, jobs: &[Job<'_>], opts: &TestOptions) -> Vec<TestReport> {
    let (file, test) = (ctx.file, ctx.test);
    let timeout = test
        .timeout
        .as_ref()
        .filter(|t| t.value > 0)
        .map(|t| Duration::from_secs(t.value));
    let run_opts = RunOptions {
        seed: opts.seed,
        max_ticks: opts.max_ticks,
        skip_idle: opts.skip_idle,
        time_limit: timeout,
        trace_rules: false,
        kr: opts.kr,
        ..RunOptions::default()
    };
    let mut tests = Tests {
        ctx,
        jobs: jobs.to_vec(),
        controllers: BTreeMap::new(),
        reports: vec![None; jobs.len()],
        launched: vec![false; jobs.len()],
        last_warning: String::new(),
        timeout,
        max_ticks: opts.max_ticks,
    };
    let summary = match crate::mas::run(ctx.system, &run_opts, None, &mut tests) {
        Ok((summary, _)) => summary,
        Err(ps) => {
            let m: String = ps.iter().map(|p| p.render()).collect();
            return jobs
                .iter()
                .map(|j| error_report(file, &j.agent, &j.test, m.clone()))
                .collect();
        }
    };
    let mut reports = std::mem::take(&mut tests.reports);
    let jobs = std::mem::take(&mut tests.jobs);
    for (k, j) in jobs.iter().enumerate() {
        if reports[k].is_none() && !tests.launched[k] {
            let m = format!("agent `{}` was not launched by {}", j.agent, test.mas.value);
            reports[k] = Some(error_report(file, &j.agent, &j.test, m));
        }
    }
    for (_, (k, c)) in std::mem::take(&mut tests.controllers) {
        let outcome = c.outcome().cloned().unwrap_or(Outcome::Error {
            message: "the test did not finish".into(),
        });
        let cycles = summary.agents.get(&jobs[k].agent).map_or(0, |a| a.cycles);
        reports[k] = Some(TestReport {
            file: file.to_string(),
            agent: jobs[k].agent.clone(),
            test: jobs[k].test.clone(),
            outcome,
            cycles,
            ticks: summary.ticks,
            watch: c.watch.clone(),
        });
    }
    reports.into_iter().flatten().collect()
}
