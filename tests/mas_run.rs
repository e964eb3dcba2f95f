//! Running systems through the library: launch names, determinism (seed, workers, idle
//! skipping), failing agents, message routing and moods.

use goal::mas::run::{run, Observer, RunOptions};
use goal::mas::system::{load_agent, load_mas};
use goal::mas::trace::TraceWriter;
use goal::mas::{EndReason, RunSummary};
use std::io::Write;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/mas")
        .join(name)
}

/// A `Write` into a shared buffer, so the test can read the trace after the run.
#[derive(Clone, Default)]
struct Buf(Arc<Mutex<Vec<u8>>>);

impl Write for Buf {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

#[derive(Default)]
struct Collect {
    printed: Vec<(String, String)>,
    warnings: Vec<String>,
}

impl Observer for Collect {
    fn printed(&mut self, agent: &str, line: &str) {
        self.printed.push((agent.to_string(), line.to_string()));
    }
    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_string());
    }
}

fn run_file(name: &str, opts: &RunOptions) -> (RunSummary, String, Collect) {
    let sys = load_mas(&fixture(name)).unwrap_or_else(|p| {
        panic!(
            "{}",
            p.iter().map(|p| p.render()).collect::<Vec<_>>().join("\n")
        )
    });
    let buf = Buf::default();
    let mut obs = Collect::default();
    let (summary, err) = run(
        &sys,
        opts,
        Some(TraceWriter::new(Box::new(buf.clone()))),
        &mut obs,
    )
    .unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None);
    let text = String::from_utf8(buf.0.lock().unwrap().clone()).unwrap();
    (summary, text, obs)
}

fn opts(workers: usize, max_ticks: u64) -> RunOptions {
    RunOptions {
        workers,
        max_ticks,
        ..RunOptions::default()
    }
}

fn records(trace: &str) -> Vec<serde_json::Value> {
    trace
        .lines()
        .map(|l| serde_json::from_str(l).expect("each trace line is one JSON object"))
        .collect()
}

#[test]
fn launch_rules_names_entities_and_max() {
    let (s, trace, _) = run_file("launch.mas2g", &opts(2, 50));
    let got: Vec<(String, Option<String>)> = s
        .agents
        .iter()
        .map(|(n, a)| (n.clone(), a.entity.clone()))
        .collect();
    let e = |x: &str| Some(x.to_string());
    assert_eq!(
        got,
        vec![
            ("Bot1".into(), e("Bot1")),
            ("Bot2".into(), e("Bot2")),
            ("boss".into(), None),
            ("helper1".into(), e("Bot3")),
            ("helper2".into(), e("Bot3")),
            ("spare".into(), e("Bot4")),
        ]
    );
    let header = &records(&trace)[0];
    assert_eq!(header["type"], "header");
    assert_eq!(header["format"], "goal-trace");
    assert_eq!(header["version"], 2);
    assert_eq!(header["seed"], 3);
    assert_eq!(header["map"], "tiny");
    assert_eq!(header["agents"].as_array().map(|a| a.len()), Some(6));
}

#[test]
fn same_seed_gives_identical_trace_and_workers_do_not_matter() {
    let (a, ta, _) = run_file("robots.mas2g", &opts(1, 150));
    let (b, tb, _) = run_file("robots.mas2g", &opts(1, 150));
    let (c, tc, _) = run_file("robots.mas2g", &opts(2, 150));
    assert!(ta.lines().count() > 100, "the robots do something");
    assert!(
        ta.contains("\"type\":\"action\""),
        "robots act in the world"
    );
    assert_eq!(ta, tb);
    assert_eq!(ta, tc, "one worker or two: the same trace");
    assert_eq!(a, b);
    assert_eq!(a, c);
}

#[test]
fn a_token_ring_gives_the_same_trace_on_one_two_and_three_workers() {
    // 31 agents and 10 tokens: most rounds have 10-20 cycles, enough to be shared between
    // threads (each owning a range of the agents) whenever the pool finds sharing faster,
    // and it tries sharing now and then in any case.
    let (a, ta, oa) = run_file("ring.mas2g", &opts(1, 1000));
    assert_eq!(
        oa.printed,
        [("counter".to_string(), "all_arrived(10)".to_string())]
    );
    assert_eq!(
        a.messages,
        10 * 60 + 10,
        "every hop, and each token's arrival"
    );
    for workers in [2, 3] {
        let (b, tb, ob) = run_file("ring.mas2g", &opts(workers, 1000));
        assert_eq!(ta, tb, "{workers} workers: the same trace as one");
        assert_eq!(a, b);
        assert_eq!(oa.printed, ob.printed);
    }
}

#[test]
fn stepping_idle_agents_does_not_change_the_trace() {
    let skip = opts(2, 150);
    let every = RunOptions {
        skip_idle: false,
        ..opts(2, 150)
    };
    let (a, ta, _) = run_file("robots.mas2g", &skip);
    let (b, tb, _) = run_file("robots.mas2g", &every);
    assert_eq!(ta, tb);
    // A waiting agent stepped without new input runs no cycle: the figures agree too.
    assert_eq!(a, b);
    assert!(a.agents.values().any(|s| s.cycles < a.rounds));
    assert!(b
        .agents
        .values()
        .all(|s| s.stopped || s.cycles + s.idle_ticks == b.rounds));
}

#[test]
fn other_seed_other_trace() {
    let sys = load_mas(&fixture("robots.mas2g")).expect("loads");
    let mut traces = Vec::new();
    for seed in [1, 2] {
        let buf = Buf::default();
        let o = RunOptions {
            seed: Some(seed),
            ..opts(1, 60)
        };
        run(
            &sys,
            &o,
            Some(TraceWriter::new(Box::new(buf.clone()))),
            &mut Collect::default(),
        )
        .expect("runs");
        let t = String::from_utf8(buf.0.lock().unwrap().clone()).unwrap();
        assert_eq!(records(&t)[0]["seed"], seed);
        traces.push(t);
    }
    assert_ne!(traces[0], traces[1]);
}

#[test]
fn a_failing_agent_stops_alone() {
    let (s, trace, obs) = run_file("failing.mas2g", &opts(2, 1000));
    let crasher = &s.agents["crasher"];
    let err = crasher.error.as_deref().expect("crasher has an error");
    assert!(err.contains("1/0"), "{err}");
    assert!(crasher.stopped);
    for w in ["worker1", "worker2"] {
        let a = &s.agents[w];
        assert_eq!(a.error, None);
        assert!(a.stopped, "{w} ran to its end");
        let lines: Vec<&str> = obs
            .printed
            .iter()
            .filter(|(n, _)| n == w)
            .map(|(_, l)| l.as_str())
            .collect();
        let want: Vec<String> = (1..=20).map(|i| i.to_string()).collect();
        assert_eq!(lines, want, "{w} printed 1..20 after crasher failed");
    }
    assert_eq!(s.end, EndReason::AllStopped);
    assert!(obs.warnings.iter().any(|w| w.contains("crasher stopped")));
    let end = records(&trace).pop().expect("an end record");
    assert_eq!(end["type"], "end");
    assert!(end["errors"]["crasher"]
        .as_str()
        .is_some_and(|e| e.contains("1/0")));
    let stats = s.to_json();
    assert!(stats["agents"]["crasher"]["error"].is_string());
    assert!(stats["agents"]["worker1"].get("error").is_none());
}

#[test]
fn messages_keep_order_and_moods_and_unknown_receivers_are_reported() {
    let (s, trace, obs) = run_file("moods.mas2g", &opts(2, 100));
    let msgs: Vec<(String, String, String)> = records(&trace)
        .into_iter()
        .filter(|r| r["type"] == "message")
        .map(|r| {
            (
                r["to"].as_str().unwrap_or("").to_string(),
                r["content"].as_str().unwrap_or("").to_string(),
                r["act"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect();
    let m = |to: &str, c: &str, a: &str| (to.to_string(), c.to_string(), a.to_string());
    assert_eq!(
        msgs,
        vec![
            m("listener", "hello(1)", "Inform"),
            m("listener", "imp(fetch(red))", "Request"),
            m("listener", "int(where(red))", "Query"),
        ]
    );
    let mut got: Vec<String> = obs.printed.iter().map(|(_, l)| l.clone()).collect();
    got.sort();
    assert_eq!(
        got,
        [
            "got(talker,hello(1))",
            "got(talker,imp(fetch(red)))",
            "got(talker,int(where(red)))"
        ]
    );
    assert!(
        obs.warnings.iter().any(|w| w.contains("nobody")),
        "{:?}",
        obs.warnings
    );
    assert_eq!(s.messages, 3);
    assert_eq!(s.agents["talker"].messages_sent, 3);
    assert_eq!(s.end, EndReason::AllStopped);
}

#[test]
fn single_agent_without_environment() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("agents/counter/counter.goal");
    let sys = load_agent(&path).expect("counter loads");
    let mut obs = Collect::default();
    let (s, _) = run(&sys, &opts(1, 10_000), None, &mut obs).expect("runs");
    let lines: Vec<&str> = obs.printed.iter().map(|(_, l)| l.as_str()).collect();
    assert_eq!(lines.len(), 101);
    assert_eq!(lines[0], "1");
    assert_eq!(lines[99], "100");
    assert_eq!(lines[100], "counted to 100");
    assert_eq!(s.end, EndReason::AllStopped);
    assert!(s.agents["counter"].stopped);
    assert_eq!(s.map, None);
}

#[test]
fn cycle_limit_stops_a_single_agent() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("agents/counter/counter.goal");
    let sys = load_agent(&path).expect("counter loads");
    let mut obs = Collect::default();
    let (s, _) = run(&sys, &opts(1, 10), None, &mut obs).expect("runs");
    assert_eq!(s.end, EndReason::CycleLimit);
    assert_eq!(s.ticks, 10);
    assert_eq!(obs.printed.len(), 10);
}

#[test]
fn summary_table_of_a_failing_system() {
    let (s, _, _) = run_file("failing.mas2g", &opts(3, 1000));
    let root = env!("CARGO_MANIFEST_DIR");
    let table = goal::mas::summary::table(&s).replace(root, "<root>");
    insta::assert_snapshot!(table);
}

#[test]
fn copies_get_numbered_names_and_every_agent_knows_all_agents() {
    let (s, _, obs) = run_file("whoami.mas2g", &opts(2, 100));
    let names: Vec<&String> = s.agents.keys().collect();
    assert_eq!(names, ["who1", "who2", "who3", "whoami"]);
    let mut got: Vec<String> = obs.printed.iter().map(|(_, l)| l.clone()).collect();
    got.sort();
    let all = "[who1,who2,who3,whoami]";
    assert_eq!(
        got,
        [
            format!("who1-{all}"),
            format!("who2-{all}"),
            format!("who3-{all}"),
            format!("whoami-{all}"),
        ]
    );
}
