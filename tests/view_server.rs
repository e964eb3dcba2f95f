//! The view's server: bad traces are refused with a plain message; a live run goes on when a
//! tab closes mid-stream, serves 20 clients at once, and writes the same trace as without a
//! view; a taken port is said and another one used; the page's controls pause and step the run.

mod view_support;

use std::io::{BufRead, BufReader, Write};
use std::net::{TcpListener, TcpStream};
use std::time::Duration;
use view_support::*;

fn view_fails(content: &str) -> String {
    let dir = scratch(&format!("bad{}", content.len()));
    let trace = dir.join("bad.jsonl");
    std::fs::write(&trace, content).unwrap();
    let out = goal().arg("view").arg(&trace).output().unwrap();
    assert_eq!(out.status.code(), Some(1));
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stderr).unwrap()
}

const HEADER: &str = r#"{"agents":[],"env":null,"file":"x.mas2g","format":"goal-trace","map":null,"seed":0,"type":"header","version":2}"#;

#[test]
fn malformed_traces_are_refused_plainly() {
    let e = view_fails(&format!("{HEADER}\n{{\"type\":\"cycle\",\n"));
    assert!(e.contains("bad.jsonl:2: not a trace record"), "{e}");
    let e = view_fails("hello\n");
    assert!(e.contains("bad.jsonl:1: not a trace record"), "{e}");
    let e = view_fails("{\"type\":\"cycle\"}\n");
    assert!(e.contains("bad.jsonl:1: not a goal trace"), "{e}");
    let e = view_fails("");
    assert!(e.contains("bad.jsonl is empty"), "{e}");
    let e = view_fails(&format!("{HEADER}\n[1,2]\n"));
    assert!(e.contains("bad.jsonl:2: not a trace record"), "{e}");
    let out = goal()
        .args(["view", "/no/such/trace.jsonl"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot open /no/such/trace.jsonl"));
}

#[test]
fn a_trace_of_another_version_is_refused_plainly() {
    let old = HEADER.replace("\"version\":2", "\"version\":1");
    let e = view_fails(&format!("{old}\n"));
    assert!(
        e.contains("trace format version 1, but this goal reads version 2"),
        "{e}"
    );
    assert!(e.contains("goal run --trace"), "says what to do: {e}");
}

/// Reads a server-sent-event stream until its end event: the number of data lines.
fn read_stream(url: &str, limit: Option<usize>) -> usize {
    let hostport = url.trim_start_matches("http://").trim_end_matches('/');
    let mut s = TcpStream::connect(hostport).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(120))).unwrap();
    write!(
        s,
        "GET /api/stream?from=0 HTTP/1.1\r\nHost: {hostport}\r\n\r\n"
    )
    .unwrap();
    let mut n = 0;
    for line in BufReader::new(s).lines() {
        let Ok(line) = line else { break };
        if line.starts_with("data: {\"") {
            n += 1;
            if limit.is_some_and(|l| n >= l) {
                return n; // the tab closes here
            }
        }
        if line == "event: end" {
            break;
        }
    }
    n
}

#[test]
fn a_live_run_survives_closed_tabs_and_many_clients_and_writes_the_same_trace() {
    let dir = scratch("live");
    let plain = dir.join("plain.jsonl");
    let watched = dir.join("watched.jsonl");
    assert_eq!(record(&["--max-ticks", "250"], &plain), Some(3));
    let mut cmd = goal();
    cmd.args([
        "run",
        "--max-ticks",
        "250",
        "--view",
        "127.0.0.1:0",
        "--trace",
    ])
    .arg(&watched);
    let mut served = Served::start(cmd);
    // A tab that closes after a few lines, and one that closes at once.
    assert_eq!(read_stream(&served.url, Some(5)), 5);
    drop(TcpStream::connect(
        served
            .url
            .trim_start_matches("http://")
            .trim_end_matches('/'),
    ));
    // Twenty clients at once, each reading the whole run as it is written.
    let clients: Vec<_> = (0..20)
        .map(|_| {
            let url = served.url.clone();
            std::thread::spawn(move || read_stream(&url, None))
        })
        .collect();
    let counts: Vec<usize> = clients.into_iter().map(|c| c.join().unwrap()).collect();
    served.wait_line(|l| l.contains("the run is over"), Duration::from_secs(120));
    let expected = std::fs::read_to_string(&watched).unwrap();
    assert!(
        expected.ends_with("\"type\":\"end\"}\n"),
        "the run went on to its end"
    );
    let lines = expected.lines().count();
    assert_eq!(counts, vec![lines; 20], "every client got every line");
    assert_eq!(
        expected,
        std::fs::read_to_string(&plain).unwrap(),
        "watching does not change the trace"
    );
    // The page stays until Ctrl-C; the exit code is the run's (tick limit).
    assert_eq!(json(&served.url, "/api/info")["complete"], true);
    assert_eq!(served.interrupt(), Some(3));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_taken_port_is_said_and_another_is_used() {
    let dir = scratch("port");
    let trace = dir.join("t.jsonl");
    std::fs::write(&trace, format!("{HEADER}\n")).unwrap();
    let taken = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port();
    let mut cmd = goal();
    cmd.arg("view")
        .arg(&trace)
        .args(["--addr", &format!("127.0.0.1:{port}")]);
    let served = Served::start(cmd);
    assert!(
        served
            .seen
            .iter()
            .any(|l| l.contains(&format!("address 127.0.0.1:{port} is already in use"))),
        "{:?}",
        served.seen
    );
    assert!(!served.url.contains(&format!(":{port}/")));
    let (status, body) = http("GET", &served.url, "/");
    assert_eq!(status, 200);
    assert!(body.contains("<svg id=\"world\""));
    assert_eq!(served.interrupt(), Some(0));
    let out = goal()
        .arg("view")
        .arg(&trace)
        .args(["--addr", "nowhere:port"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("is not an address to serve on"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_page_pauses_steps_and_paces_a_live_run() {
    let mut cmd = goal();
    cmd.args(["run", "--view", "--max-ticks", "100000"]);
    let served = Served::start(cmd);
    let (status, body) = http("POST", &served.url, "/api/control?speed=20");
    assert_eq!(status, 200, "{body}");
    // The control's tick is the last one the run reached (0 before its first round).
    served.wait_for_tick(5);
    let (status, _) = http("POST", &served.url, "/api/control?pause");
    assert_eq!(status, 200);
    std::thread::sleep(Duration::from_millis(300));
    let t1 = served.tick();
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(served.tick(), t1, "a paused run stands still");
    http("POST", &served.url, "/api/control?step");
    let mut t2 = t1;
    for _ in 0..100 {
        t2 = served.tick();
        if t2 > t1 {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    assert_eq!(t2, t1 + 1, "one step is one tick");
    std::thread::sleep(Duration::from_millis(300));
    let t3 = served.tick();
    assert_eq!(t3, t1 + 1, "and then it waits again (t1 {t1}, t2 {t2})");
    http("POST", &served.url, "/api/control?play");
    // Playing again: the tick moves on (waited for, not timed: the machine may be loaded).
    let moved = (0..500).any(|_| {
        std::thread::sleep(Duration::from_millis(20));
        served.tick() > t1 + 1
    });
    assert!(moved, "playing again");
    let (status, body) = http("POST", &served.url, "/api/control?speed=fast");
    assert_eq!(status, 400);
    assert!(body.contains("speed must be a positive number"));
    // A live run answers why-questions by rerunning the system up to the tick.
    let (status, body) = http("GET", &served.url, "/api/why?agent=Bot1&tick=3");
    assert_eq!(status, 200, "{body}");
    assert!(
        body.contains(r#""agent":"Bot1""#) && body.contains(r#""rules":["#),
        "{body}"
    );
    let (status, _) = http("GET", &served.url, "/nothing-here");
    assert_eq!(status, 404);
    // Ctrl-C ends even a running view: interrupted.
    assert_eq!(served.interrupt(), Some(130));
}
