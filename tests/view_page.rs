//! The view's page in a real headless browser: a replayed trace and a live run are drawn
//! (rooms, blocks, robots, the colour sequence's progress, an agent's beliefs) and the drawing
//! changes when the timeline moves; runs without an environment show the minds only; the why
//! panel shows a provider's answer, or says plainly that there is none.

mod view_support;

use goal::view::{serve, Site, WhyProvider};
use std::sync::Arc;
use view_support::*;

/// A trace of the default team's first `ticks` ticks.
fn default_trace(dir: &std::path::Path, ticks: u64) -> std::path::PathBuf {
    let trace = dir.join("team.jsonl");
    let code = record(&["--max-ticks", &ticks.to_string()], &trace);
    assert_eq!(code, Some(3), "the run stops at its tick limit");
    trace
}

fn robots(dom: &str) -> Vec<(String, String, String)> {
    tags(dom, "robot")
        .iter()
        .map(|t| {
            let a = |n| attr(t, n).unwrap_or("").to_string();
            (a("data-name"), a("data-x"), a("data-y"))
        })
        .collect()
}

/// What every drawn default game shows.
fn assert_world(dom: &str) {
    let rs = robots(dom);
    let names: Vec<&str> = rs.iter().map(|r| r.0.as_str()).collect();
    assert_eq!(names, ["Bot1", "Bot2", "Bot3"], "{dom}");
    assert!(tags(dom, "zone room").len() >= 9, "rooms drawn");
    assert_eq!(tags(dom, "zone dropzone").len(), 1, "the drop zone");
    assert!(tags(dom, "door").len() >= 9, "doors drawn");
    assert!(tags(dom, "block").len() >= 10, "blocks drawn");
    let seq = tags(dom, "c")
        .iter()
        .filter(|t| attr(t, "data-color").is_some())
        .count();
    assert_eq!(seq, 6, "the colour sequence has six colours");
    assert!(
        dom.contains("id=\"sequence\" data-done=\""),
        "sequence progress"
    );
    assert!(dom.contains(" of 6 delivered"), "sequence progress text");
}

#[test]
fn a_replay_is_drawn_and_follows_the_timeline() {
    let Some(browser) = browser() else { return };
    let dir = scratch("replay");
    let trace = default_trace(&dir, 400);
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let early = dump_dom(
        &browser,
        &dir.join("p1"),
        &format!("{}?tick=5&agent=Bot1", served.url),
    );
    let late = dump_dom(
        &browser,
        &dir.join("p2"),
        &format!("{}?tick=390&agent=Bot1", served.url),
    );
    assert_world(&early);
    assert_world(&late);
    assert!(early.contains("data-tick=\"5\""));
    assert!(late.contains("data-tick=\"390\""));
    assert_ne!(robots(&early), robots(&late), "the robots moved");
    let (b1, b2) = (list(&early, "beliefs"), list(&late, "beliefs"));
    assert!(
        !b1.is_empty() && !b2.is_empty(),
        "Bot1's beliefs are listed"
    );
    assert_ne!(b1, b2, "Bot1's beliefs changed over 385 ticks");
    assert!(list(&late, "percepts").iter().any(|p| p.starts_with("at(")));
    assert!(late.contains("class=\"robot selected\" data-name=\"Bot1\""));
    assert!(
        late.contains("<ol id=\"messages\"><li>"),
        "messages are listed"
    );
    assert!(late.contains("class=\"act\">"), "with their speech act");
    let png = dir.join("replay.png");
    screenshot(
        &browser,
        &dir.join("p3"),
        &format!("{}?tick=390&agent=Bot2", served.url),
        &png,
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_live_run_is_drawn_as_it_goes() {
    let Some(browser) = browser() else { return };
    let dir = scratch("live");
    let mut cmd = goal();
    cmd.args(["run", "--view", "--max-ticks", "3000"]);
    let served = Served::start(cmd);
    // Wait until the run (paced at 100 ticks per second) is past tick 150.
    served.wait_for_tick(150);
    let a = dump_dom(
        &browser,
        &dir.join("p1"),
        &format!("{}?tick=3&agent=Bot2", served.url),
    );
    let b = dump_dom(
        &browser,
        &dir.join("p2"),
        &format!("{}?tick=140&agent=Bot2", served.url),
    );
    assert_world(&a);
    assert_world(&b);
    assert!(a.contains("<span id=\"mode\">live run</span>"));
    let fired = b
        .split("data-key=\"last rule fired\">")
        .nth(1)
        .and_then(|s| s.split('<').next())
        .unwrap_or("");
    assert!(
        fired.contains(':') && fired.contains("tick"),
        "the last rule fired: {fired}"
    );
    assert_ne!(robots(&a), robots(&b), "the robots moved");
    assert_ne!(list(&a, "beliefs"), list(&b, "beliefs"));
    // Following the run: the page shows the newest tick, later than before.
    let now = dump_dom(&browser, &dir.join("p3"), &served.url);
    let shown: u64 = now
        .split("data-tick=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!(
        shown >= 150,
        "a live page opens at the newest tick ({shown})"
    );
    screenshot(
        &browser,
        &dir.join("p4"),
        &format!("{}?agent=Bot1", served.url),
        &dir.join("live.png"),
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_without_environment_shows_minds_only() {
    let Some(browser) = browser() else { return };
    let dir = scratch("minds");
    let trace = dir.join("ring.jsonl");
    let agent = concat!(env!("CARGO_MANIFEST_DIR"), "/agents/counter/counter.goal");
    assert_eq!(record(&[agent], &trace), Some(0));
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let dom = dump_dom(&browser, &dir.join("p1"), &format!("{}?tick=3", served.url));
    assert!(
        dom.contains("<p id=\"nomap\">"),
        "the no-environment note is shown"
    );
    assert!(tags(&dom, "robot").is_empty());
    let beliefs = list(&dom, "beliefs");
    assert!(
        beliefs.iter().any(|b| b.starts_with("count(")),
        "{beliefs:?}"
    );
    let later = dump_dom(&browser, &dir.join("p2"), &format!("{}?tick=8", served.url));
    assert_ne!(list(&later, "beliefs"), beliefs, "the count goes on");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_bw4t_xml_map_is_drawn() {
    let Some(browser) = browser() else { return };
    let maps = concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/bw4t-maps");
    let map = std::path::Path::new(maps).join("Rainbow.xml");
    if !map.is_file() {
        eprintln!("{} not found: skipping the XML map check", map.display());
        return;
    }
    let dir = scratch("xml");
    let trace = dir.join("xml.jsonl");
    let _ = record(
        &["--max-ticks", "50", "--map", map.to_str().unwrap()],
        &trace,
    );
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let dom = dump_dom(
        &browser,
        &dir.join("p1"),
        &format!("{}?tick=40", served.url),
    );
    assert!(tags(&dom, "zone room").len() >= 4, "the XML map's rooms");
    assert!(!tags(&dom, "robot").is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Answers with one rule of each outcome, naming the agent and tick it was asked about.
struct TestWhy;

impl WhyProvider for TestWhy {
    fn why(&self, agent: &str, tick: u64) -> Result<serde_json::Value, String> {
        if agent == "Nobody" {
            return Err("no agent Nobody".into());
        }
        Ok(serde_json::json!({
            "agent": agent, "tick": tick, "cycle": 7, "module": "main",
            "rules": [
                {"rule": "main:10", "text": "if bel(a) then x.", "outcome": "fired",
                 "bindings": "X=1", "failed_literal": null, "failed_action": null},
                {"rule": "main:11", "text": "if bel(a), bel(b) then y.", "outcome": "failed",
                 "bindings": "", "failed_literal": "bel(b)", "failed_action": null},
                {"rule": "main:12", "text": "if true then goTo(r).", "outcome": "precondition_failed",
                 "bindings": "", "failed_literal": null, "failed_action": "goTo(r)"}
            ]
        }))
    }
}

#[test]
fn the_why_panel_shows_the_answer_or_says_there_is_none() {
    let Some(browser) = browser() else { return };
    let dir = scratch("why");
    let trace = default_trace(&dir, 30);
    let site = |why: Option<Arc<dyn WhyProvider>>| Site {
        feed: Arc::new(goal::view::replay::load(&trace).unwrap()),
        control: None,
        why,
        title: "why test".into(),
    };
    let mut notes = Vec::new();
    let with = serve("127.0.0.1:0", site(Some(Arc::new(TestWhy))), &mut notes).unwrap();
    let dom = dump_dom(
        &browser,
        &dir.join("p1"),
        &format!("{}?tick=12&agent=Bot2&why=1", with.url()),
    );
    assert!(
        dom.contains("Bot2 at tick 12, cycle 7, module main:"),
        "{dom}"
    );
    assert_eq!(tags(&dom, "rule fired").len(), 1);
    assert_eq!(tags(&dom, "rule failed").len(), 1);
    assert_eq!(tags(&dom, "rule precondition_failed").len(), 1);
    assert!(dom.contains("<td>bel(b)</td>") && dom.contains("<td>goTo(r)</td>"));
    let without = serve("127.0.0.1:0", site(None), &mut notes).unwrap();
    let dom = dump_dom(
        &browser,
        &dir.join("p2"),
        &format!("{}?tick=12&agent=Bot2&why=1", without.url()),
    );
    assert!(
        dom.contains("The why answer is unavailable for this run"),
        "{dom}"
    );
    // The real provider: the trace's run is rerun up to the tick and explained.
    let real = goal::why::Why::for_trace(&trace).unwrap();
    let real = serve("127.0.0.1:0", site(Some(Arc::new(real))), &mut notes).unwrap();
    let dom = dump_dom(
        &browser,
        &dir.join("p3"),
        &format!("{}?tick=12&agent=Bot2&why=1", real.url()),
    );
    assert!(dom.contains("Bot2 at tick 12, cycle"), "{dom}");
    let explained = tags(&dom, "rule fired").len() + tags(&dom, "rule failed").len();
    assert!(explained > 0, "{dom}");
    assert!(notes.is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_page_measures_its_load_and_timeline_moves() {
    let Some(browser) = browser() else { return };
    let dir = scratch("measure");
    let trace = dir.join("endless.jsonl");
    let map = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/view/endless.toml"
    );
    assert_eq!(
        record(&["--max-ticks", "300", "--map", map], &trace),
        Some(3)
    );
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let dom = dump_dom(
        &browser,
        &dir.join("p1"),
        &format!("{}?measure=1", served.url),
    );
    let at = dom
        .find("<div id=\"measure\"")
        .expect("the measure element");
    let m = &dom[at..at + dom[at..].find('>').unwrap()];
    for key in [
        "data-load-ms",
        "data-seek-median-ms",
        "data-seek-p95-ms",
        "data-seek-max-ms",
        "data-state-max-ms",
    ] {
        let v: f64 = attr(m, key)
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{key} in {m}"));
        assert!(v >= 0.0);
    }
    assert_eq!(
        attr(m, "data-ticks"),
        Some("300"),
        "the world after the last round is tick 300"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
