//! The player endpoints of the view server: bad requests (an unknown robot, a robot someone
//! else plays, malformed bodies, requests without a robot, requests in a replay) each get a
//! clear error, nothing crashes, and the run goes on; a request the environment refuses is
//! shown as refused with its reason. Two people play a robot each; with nobody playing, a
//! HumanBot stands still and the run does not wait for anyone.

mod view_support;

use serde_json::{json, Value};
use std::time::{Duration, Instant};
use view_support::*;

/// `method path` with `body`: (status, JSON answer).
fn send(url: &str, method: &str, path: &str, body: &str) -> (u16, Value) {
    let (status, text) = http_with(method, url, path, body);
    (status, serde_json::from_str(&text).unwrap_or(Value::Null))
}

fn post(url: &str, path: &str, body: Value) -> (u16, Value) {
    send(url, "POST", path, &body.to_string())
}

fn error_of(answer: &(u16, Value)) -> String {
    answer.1["error"].as_str().unwrap_or_default().to_string()
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
    let cmd = team_with_humans(2, 1, 200000);
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
        (
            &format!("{{\"token\": \"{mine}\", \"request\": \"goTo(_)\"}}"),
            "leaves something open",
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
    served.wait_for_tick(served.tick() + 1);
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
    assert_eq!(record(&["--max-ticks", "20"], &trace), Some(3));
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

#[test]
fn a_humanbot_nobody_plays_stands_still_and_the_run_waits_for_nobody() {
    let dir = scratch("play-nobody");
    let trace = dir.join("t.jsonl");
    let mut cmd = team_with_humans(2, 1, 300);
    cmd.arg("--trace").arg(&trace);
    let mut served = Served::start(cmd);
    // Nobody opens the page: the run plays to its tick limit all the same.
    served.wait_line(|l| l.contains("the run is over"), Duration::from_secs(300));
    assert_eq!(served.interrupt(), Some(3), "the tick limit ended the run");
    let recs = records(&trace);
    assert!(
        recs.iter().any(|r| r["tick"] == 300),
        "the run reached tick 300"
    );
    assert!(
        recs.iter().all(|r| r["type"] != "input"),
        "no request taken"
    );
    let human_actions: Vec<&Value> = recs
        .iter()
        .filter(|r| r["type"] == "action" && r["agent"] == "Human1")
        .collect();
    assert!(human_actions.is_empty(), "{human_actions:?}");
    // Human1 is where it started; the agents' robots moved.
    let moves = |robot: &str| {
        let key = format!("robots/{robot}/pos");
        recs.iter()
            .filter(|r| r["type"] == "world")
            .filter(|r| !r["set"][&key].is_null())
            .count()
    };
    assert_eq!(moves("Human1"), 1, "placed once, never moved");
    assert!(moves("Bot1") > 1 && moves("Bot2") > 1);
}

/// Waits until the request with id `id` of the player `token` is answered: its state.
fn answered(url: &str, token: &str, id: &Value) -> Value {
    let end = Instant::now() + Duration::from_secs(60);
    loop {
        let s = json(url, &format!("/api/play?token={token}"));
        let r = s["requests"]
            .as_array()
            .and_then(|rs| rs.iter().find(|r| r["id"] == *id).cloned());
        if let Some(r) = r.filter(|r| r["state"] != "waiting") {
            return r;
        }
        assert!(Instant::now() < end, "request {id} never answered: {s}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

#[test]
fn two_people_play_a_robot_each() {
    let dir = scratch("play-two");
    let trace = dir.join("t.jsonl");
    let mut cmd = team_with_humans(1, 2, 200000);
    cmd.arg("--trace").arg(&trace);
    let served = Served::start(cmd);
    let url = served.url.clone();
    announced(&url);
    let a = post(&url, "/api/play/take", json!({"robot": "Human1"}));
    let b = post(&url, "/api/play/take", json!({"robot": "Human2"}));
    assert_eq!((a.0, b.0), (200, 200), "{a:?} {b:?}");
    let (ta, tb) = (
        a.1["token"].as_str().unwrap(),
        b.1["token"].as_str().unwrap(),
    );
    assert_ne!(ta, tb);
    // Each sees their own robot, and the other's as taken.
    let sa = json(&url, &format!("/api/play?token={ta}"));
    assert_eq!(sa["you"], "Human1");
    assert_eq!(
        sa["robots"][1],
        json!({"entity": "Human2", "taken": true, "mine": false})
    );
    let sb = json(&url, &format!("/api/play?token={tb}"));
    assert_eq!(sb["you"], "Human2");
    // A question of the message list that names everything, and one with an open subject
    // (the agents receive it with a variable, and forget it like any other message).
    for question in [
        "sendMessage(all, int(willBeLong('Human2')))",
        "sendMessage(all, int(at(_, 'RoomA1')))",
    ] {
        let qa = post(
            &url,
            "/api/play/request",
            json!({"token": ta, "request": question}),
        );
        assert_eq!(qa.0, 202, "{qa:?}");
        assert_eq!(answered(&url, ta, &qa.1["id"])["state"], "applied");
    }
    let ra = post(
        &url,
        "/api/play/request",
        json!({"token": ta, "request": "goTo('RoomA1')"}),
    );
    let rb = post(
        &url,
        "/api/play/request",
        json!({"token": tb, "request": "goTo('RoomC3')"}),
    );
    assert_eq!((ra.0, rb.0), (202, 202), "{ra:?} {rb:?}");
    let (xa, xb) = (
        answered(&url, ta, &ra.1["id"]),
        answered(&url, tb, &rb.1["id"]),
    );
    assert_eq!(
        (&xa["state"], &xb["state"]),
        (&json!("applied"), &json!("applied"))
    );
    // The agents act on them in the rounds after.
    let then = xa["tick"]
        .as_u64()
        .unwrap()
        .max(xb["tick"].as_u64().unwrap());
    served.wait_for_tick(then + 5);
    // Each page lists only its own robot's requests.
    let sa = json(&url, &format!("/api/play?token={ta}"));
    let mine: Vec<&str> = sa["requests"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["request"].as_str().unwrap())
        .collect();
    assert_eq!(mine.len(), 3, "{mine:?}");
    assert_eq!(mine[0], "goTo('RoomA1')");
    assert!(mine[1].starts_with("sendMessage(all,int(at(_"), "{mine:?}");
    assert_eq!(mine[2], "sendMessage(all,int(willBeLong('Human2')))");
    assert_eq!(served.interrupt(), Some(130));

    // The trace has each request for its own robot, and each robot's agent acted on it.
    let recs = records(&trace);
    let asked: Vec<&Value> = recs
        .iter()
        .filter(|r| r["type"] == "message" && r["from"] == "Human1")
        .collect();
    assert!(!asked.is_empty(), "Human1 asked the team");
    let end = recs.last().unwrap();
    assert_eq!(end["errors"], json!({}), "no agent stopped: {end}");
    for (robot, goal) in [("Human1", "goTo('RoomA1')"), ("Human2", "goTo('RoomC3')")] {
        assert!(
            recs.iter().any(|r| r["type"] == "input"
                && r["entity"] == robot
                && r["request"] == goal
                && r["result"] == "ok"),
            "{robot}'s request in the trace"
        );
        assert!(
            recs.iter()
                .any(|r| r["type"] == "action" && r["agent"] == robot && r["action"] == goal),
            "{robot} went"
        );
    }
}
