//! The player endpoints of the view server: bad requests (an unknown robot, a robot someone
//! else plays, malformed bodies, requests without a robot, requests in a replay) each get a
//! clear error, nothing crashes, and the run goes on; a request the environment refuses is
//! shown as refused with its reason.

mod view_support;

use serde_json::{json, Value};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::{Duration, Instant};
use view_support::*;

/// `method path` with `body`: (status, JSON answer).
fn send(url: &str, method: &str, path: &str, body: &str) -> (u16, Value) {
    let hostport = url.trim_start_matches("http://").trim_end_matches('/');
    let mut s = TcpStream::connect(hostport).expect("connect to the view");
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.0\r\nHost: {hostport}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut text = String::new();
    let _ = s.read_to_string(&mut text);
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, serde_json::from_str(body).unwrap_or(Value::Null))
}

fn post(url: &str, path: &str, body: Value) -> (u16, Value) {
    send(url, "POST", path, &body.to_string())
}

fn error_of(answer: &(u16, Value)) -> String {
    answer.1["error"].as_str().unwrap_or_default().to_string()
}

/// The live run's tick as its page sees it.
fn tick(url: &str) -> u64 {
    json(url, "/api/info")["control"]["tick"]
        .as_u64()
        .unwrap_or(0)
}

/// Waits until the run has announced its HumanBots.
fn announced(url: &str) -> Value {
    let end = Instant::now() + Duration::from_secs(120);
    loop {
        let v = json(url, "/api/play");
        if v["announced"] == json!(true) {
            return v;
        }
        assert!(Instant::now() < end, "the run never announced its robots");
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn bad_player_requests_get_clear_errors_and_the_run_goes_on() {
    let mut cmd = goal();
    cmd.args([
        "run",
        "--robots",
        "2",
        "--humans",
        "1",
        "--max-ticks",
        "200000",
    ]);
    let served = Served::start(cmd);
    let url = served.url.clone();
    let state = announced(&url);
    assert_eq!(
        state["robots"],
        json!([{"entity": "Human1", "taken": false, "mine": false}])
    );

    // An unknown robot: 404, naming the run's HumanBots.
    let a = post(&url, "/api/play/take", json!({"robot": "Bot1"}));
    assert_eq!(a.0, 404, "{a:?}");
    assert!(error_of(&a).contains("its HumanBots: Human1"), "{a:?}");

    // Taking Human1, then someone else tries: 409, and the robot shows as taken.
    let a = post(&url, "/api/play/take", json!({"robot": "Human1"}));
    assert_eq!(a.0, 200, "{a:?}");
    let mine = a.1["token"].as_str().unwrap().to_string();
    let b = post(&url, "/api/play/take", json!({"robot": "Human1"}));
    assert_eq!(b.0, 409, "{b:?}");
    assert!(error_of(&b).contains("already taken"), "{b:?}");
    let other = json(&url, "/api/play");
    assert_eq!(other["robots"][0]["taken"], true);
    assert_eq!(other["robots"][0]["mine"], false);
    assert_eq!(other["you"], Value::Null);

    // Malformed bodies and requests: 400 each, with what to send.
    for (body, says) in [
        ("not json", "not JSON"),
        ("[1, 2]", "JSON object"),
        ("{\"token\": 5, \"request\": \"putDown\"}", "\"token\""),
        (&format!("{{\"token\": \"{mine}\"}}"), "\"request\""),
        (
            &format!("{{\"token\": \"{mine}\", \"request\": \"goTo(\"}}"),
            "not a term",
        ),
        (&"x".repeat(20_000), "longer than"),
    ] {
        let a = send(&url, "POST", "/api/play/request", body);
        assert_eq!(a.0, 400, "{body:.40}: {a:?}");
        assert!(error_of(&a).contains(says), "{body:.40}: {a:?}");
    }
    // A request without holding a robot: 403.
    let a = post(
        &url,
        "/api/play/request",
        json!({"token": "nobody", "request": "putDown"}),
    );
    assert_eq!(a.0, 403, "{a:?}");
    assert!(error_of(&a).contains("take a free HumanBot"), "{a:?}");
    // An endpoint that does not exist, and a method that does not fit.
    assert_eq!(send(&url, "POST", "/api/play/fly", "{}").0, 404);
    assert_eq!(send(&url, "GET", "/api/play/take", "").0, 405);

    // A request the environment refuses (no such block): taken, then shown as refused.
    let a = post(
        &url,
        "/api/play/request",
        json!({"token": mine, "request": "pickUp(99999)"}),
    );
    assert_eq!(a.0, 202, "{a:?}");
    let end = Instant::now() + Duration::from_secs(60);
    let refused = loop {
        let s = json(&url, &format!("/api/play?token={mine}"));
        let r = s["requests"][0].clone();
        if r["state"] == "refused" {
            break r;
        }
        assert!(Instant::now() < end, "the request was never answered: {s}");
        std::thread::sleep(Duration::from_millis(100));
    };
    assert_eq!(refused["request"], "pickUp(99999)");
    assert!(
        refused["reason"].as_str().unwrap_or("").contains("Human1"),
        "{refused}"
    );

    // The run went on through all of it.
    let before = tick(&url);
    let end = Instant::now() + Duration::from_secs(60);
    while tick(&url) <= before {
        assert!(Instant::now() < end, "the run stopped at tick {before}");
        std::thread::sleep(Duration::from_millis(100));
    }
    // Leaving frees the robot for the next person.
    assert_eq!(post(&url, "/api/play/leave", json!({"token": mine})).0, 200);
    assert_eq!(json(&url, "/api/play")["robots"][0]["taken"], false);
    let code = served.interrupt();
    assert_eq!(code, Some(130), "Ctrl-C ends the run with 128 + SIGINT");
}

#[test]
fn nobody_plays_a_replay() {
    let dir = scratch("play-replay");
    let trace = dir.join("t.jsonl");
    let st = goal()
        .args(["run", "--max-ticks", "20", "--trace"])
        .arg(&trace)
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap();
    assert_eq!(st.code(), Some(3));
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let a = post(&served.url, "/api/play/take", json!({"robot": "Human1"}));
    assert_eq!(a.0, 409, "{a:?}");
    assert!(error_of(&a).contains("replay"), "{a:?}");
    // The message list is there for any page.
    let m = json(&served.url, "/api/play/messages");
    assert!(m["messages"]
        .as_array()
        .unwrap()
        .iter()
        .any(|x| x["pattern"] == "imp(in(Me,Place))"));
    assert_eq!(m["colors"].as_array().unwrap().len(), 9);
}
