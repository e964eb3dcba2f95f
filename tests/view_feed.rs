//! The live feed's memory stays bounded however long the run (older trace lines go to disk),
//! and a client that joins late still gets every line and draws the same state as a replay
//! of the whole trace.

mod view_support;

use goal::mas::trace::TraceWriter;
use goal::mas::{Observer, RunOptions};
use goal::view::{serve, Feed, FeedWriter, Site};
use std::io::Write;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use view_support::*;

/// The memory budget of the test's feed: a small fraction of the run's trace.
const BUDGET: usize = 64 << 10;

/// Watches the feed's memory after every round.
struct Gauge {
    feed: Arc<Feed>,
    most: usize,
    rounds: u64,
}

impl Observer for Gauge {
    fn pace(&mut self, _round: u64, _tick: u64) {
        self.most = self.most.max(self.feed.held_bytes());
        self.rounds += 1;
    }
}

/// Everything written, also kept whole (what a `--trace` file would hold).
#[derive(Clone, Default)]
struct Copy(Arc<Mutex<Vec<u8>>>);

impl Write for Copy {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Runs the default team for `ticks` ticks into a feed of [`BUDGET`] bytes: the feed, the
/// whole trace, and the most memory the feed held after any round.
fn long_run(ticks: u64) -> (Arc<Feed>, String, usize) {
    let feed = Arc::new(Feed::with_budget(BUDGET));
    let copy = Copy::default();
    let sink = goal::view::feed::Tee {
        first: copy.clone(),
        second: FeedWriter::new(feed.clone()),
    };
    let sys = goal::mas::default_team::system().unwrap_or_else(|_| panic!("the default team"));
    let opts = RunOptions {
        max_ticks: ticks,
        trace_rules: true,
        ..RunOptions::default()
    };
    let mut gauge = Gauge {
        feed: feed.clone(),
        most: 0,
        rounds: 0,
    };
    let (_, err) = goal::mas::run(
        &sys,
        &opts,
        Some(TraceWriter::new(Box::new(sink))),
        &mut gauge,
    )
    .unwrap_or_else(|_| panic!("the run starts"));
    assert!(err.is_none(), "{err:?}");
    assert!(gauge.rounds >= ticks / 2, "rounds seen: {}", gauge.rounds);
    feed.close();
    let text = String::from_utf8(copy.0.lock().unwrap().clone()).unwrap();
    (feed, text, gauge.most)
}

#[test]
fn a_long_live_run_holds_bounded_memory_and_a_late_client_sees_everything() {
    let (feed, whole, most) = long_run(600);
    let longest = whole.lines().map(str::len).max().unwrap_or(0);
    assert!(
        whole.len() > 20 * BUDGET,
        "the run is long next to the budget: {} bytes",
        whole.len()
    );
    // The newest lines up to the budget, the one line that crossed it, and the disk index.
    let bound = BUDGET + longest + 32 + (64 << 10);
    assert!(
        most <= bound,
        "the feed held {most} bytes at most; bound {bound}"
    );
    assert!(feed.held_bytes() <= bound);
    // A client that joins now gets every line, the spilled ones read back from disk.
    let site = Site {
        feed: feed.clone(),
        control: None,
        why: None,
        title: "late".into(),
    };
    let server = serve("127.0.0.1:0", site, &mut Vec::new()).unwrap();
    let (status, body) = http("GET", server.url(), "/api/trace");
    assert_eq!(status, 200);
    assert!(body == whole, "the late client's trace is the whole trace");
    let info = json(server.url(), "/api/info");
    assert_eq!(info["lines"], whole.lines().count());
    assert!(info["feed_bytes"].as_u64().unwrap() as usize <= bound);
    // Streaming from any line, too.
    let from = whole.lines().count() / 3;
    let streamed = sse_lines(server.url(), from);
    let expected: Vec<&str> = whole.lines().skip(from).collect();
    assert!(streamed == expected, "the stream from line {from}");
}

/// The `data:` lines of the event stream from line `from` until its end event.
fn sse_lines(url: &str, from: usize) -> Vec<String> {
    use std::io::{BufRead, BufReader};
    let hostport = url.trim_start_matches("http://").trim_end_matches('/');
    let mut s = std::net::TcpStream::connect(hostport).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    write!(
        s,
        "GET /api/stream?from={from} HTTP/1.1\r\nHost: {hostport}\r\n\r\n"
    )
    .unwrap();
    let mut out = Vec::new();
    for line in BufReader::new(s).lines() {
        let line = line.unwrap();
        if line == "event: end" {
            break;
        }
        if let Some(d) = line.strip_prefix("data: ") {
            out.push(d.to_string());
        }
    }
    out
}

#[test]
fn a_late_page_draws_the_same_state_as_a_replay_of_the_whole_trace() {
    let Some(browser) = browser() else { return };
    let (feed, whole, _) = long_run(400);
    let dir = scratch("late");
    let site = |feed| Site {
        feed,
        control: None,
        why: None,
        title: "same".into(),
    };
    let late = serve("127.0.0.1:0", site(feed), &mut Vec::new()).unwrap();
    let lines = whole.lines().map(str::to_string).collect();
    let full = serve(
        "127.0.0.1:0",
        site(Arc::new(Feed::complete(lines))),
        &mut Vec::new(),
    )
    .unwrap();
    for (i, tick) in [20, 390].into_iter().enumerate() {
        let query = format!("?tick={tick}&agent=Bot2");
        let a = dump_dom(
            &browser,
            &dir.join(format!("a{i}")),
            &format!("{}{query}", late.url()),
        );
        let b = dump_dom(
            &browser,
            &dir.join(format!("b{i}")),
            &format!("{}{query}", full.url()),
        );
        assert!(a.contains(&format!("data-tick=\"{tick}\"")), "{a}");
        assert!(!list(&a, "beliefs").is_empty());
        assert_eq!(a, b, "tick {tick}: the late page and the replay differ");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn goal_run_view_keeps_its_feed_within_its_budget() {
    let dir = scratch("budget");
    let trace = dir.join("run.jsonl");
    // A team that never completes its sequence, so the run lasts all its ticks.
    let map = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/view/endless.toml"
    );
    let mut cmd = goal();
    cmd.args(["run", "--view", "127.0.0.1:0", "--map", map])
        .args(["--max-ticks", "10000", "--trace"])
        .arg(&trace);
    let mut served = Served::start(cmd);
    let (status, _) = http("POST", &served.url, "/api/control?speed=100000");
    assert_eq!(status, 200);
    served.wait_line(|l| l.contains("the run is over"), Duration::from_secs(600));
    let written = std::fs::read_to_string(&trace).unwrap();
    let budget = goal::view::feed::DEFAULT_BUDGET;
    assert!(
        written.len() > budget + budget / 4,
        "the run outgrew the budget: {} bytes",
        written.len()
    );
    let info = json(&served.url, "/api/info");
    let held = info["feed_bytes"].as_u64().unwrap() as usize;
    assert!(
        held <= budget + (1 << 20),
        "held {held} bytes, budget {budget}"
    );
    let (status, body) = http("GET", &served.url, "/api/trace");
    assert_eq!(status, 200);
    assert!(body == written, "a late client gets the whole trace");
    assert_eq!(served.interrupt(), Some(3));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn reading_from_past_the_end_gives_nothing_and_no_panic() {
    let feed = Feed::with_budget(16);
    for i in 0..10 {
        feed.push(&format!("{{\"line\":{i}}}"));
    }
    let (lines, closed) = feed.read_from(50, Duration::ZERO).unwrap();
    assert!(lines.is_empty() && !closed);
    let (lines, _) = feed.read_from(3, Duration::ZERO).unwrap();
    assert_eq!(
        &*lines[0], "{\"line\":3}",
        "an early line, read back from disk"
    );
    feed.close();
    let (lines, closed) = feed.read_from(50, Duration::ZERO).unwrap();
    assert!(lines.is_empty() && closed);
}
