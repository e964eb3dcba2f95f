//! Full BW4T games played by the reference team (`agents/bw4t/bw4t.mas2g`, `team.goal`) and by
//! the course-style robot (`agents/bw4t/robot.mas2g`), through the runtime's lock-step loop.
//!
//! Every shipped fixed map (banana, rainbow, dutch-flag) is played with 1 and with 3 robots, the
//! random map with 3 robots, dutch-flag with 2 robots (twice, for determinism) and the small
//! `tiny` map with 2 robots. Each game must deliver the whole sequence, without wrong
//! deliveries or agent errors, within a tick budget; the summary is snapshotted.

use goal::mas::run::{run, Quiet, RunOptions};
use goal::mas::system::load_mas;
use goal::mas::trace::TraceWriter;
use goal::mas::RunSummary;
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

fn mas(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("agents/bw4t")
        .join(file)
}

/// A `Write` into a shared buffer, to read a run's trace afterwards.
#[derive(Clone, Default)]
struct Buf(Arc<Mutex<Vec<u8>>>);

impl Write for Buf {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().expect("buffer").extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Plays `file` on `map` with `robots` robots; stops at `budget` ticks at the latest.
fn play(
    file: &str,
    map: &str,
    robots: usize,
    seed: u64,
    budget: u64,
    workers: usize,
) -> RunSummary {
    play_traced(file, map, robots, seed, budget, workers, None)
}

/// [`play`], writing the trace into `trace` when given.
fn play_traced(
    file: &str,
    map: &str,
    robots: usize,
    seed: u64,
    budget: u64,
    workers: usize,
    trace: Option<Buf>,
) -> RunSummary {
    let sys = load_mas(&mas(file)).unwrap_or_else(|p| {
        panic!(
            "{}",
            p.iter().map(|p| p.render()).collect::<Vec<_>>().join("\n")
        )
    });
    let opts = RunOptions {
        seed: Some(seed),
        map: Some(map.to_string()),
        robots: Some(robots),
        max_ticks: budget,
        workers,
        trace_rules: false,
        ..RunOptions::default()
    };
    let writer = trace.map(|b| TraceWriter::new(Box::new(b)));
    let (summary, err) =
        run(&sys, &opts, writer, &mut Quiet).unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None, "{map} with {robots} robot(s): runtime failure");
    summary
}

/// Asserts a complete, clean game within `budget` ticks and returns its snapshot figures.
fn check(s: &RunSummary, map: &str, robots: usize, budget: u64) -> serde_json::Value {
    let what = format!("{map} with {robots} robot(s)");
    assert!(s.completed, "{what}: not completed after {} ticks", s.ticks);
    assert!(
        s.ticks <= budget,
        "{what}: {} ticks > budget {budget}",
        s.ticks
    );
    assert_eq!(s.deliveries.wrong, 0, "{what}: wrong deliveries");
    assert_eq!(s.agents.len(), robots, "{what}: one agent per robot");
    for (name, a) in &s.agents {
        assert_eq!(a.error, None, "{what}: {name} stopped on an error");
        assert!(a.env_actions > 0, "{what}: {name} never acted");
    }
    let agents: serde_json::Map<String, serde_json::Value> = s
        .agents
        .iter()
        .map(|(n, a)| {
            (
                n.clone(),
                json!({ "cycles": a.cycles, "env_actions": a.env_actions, "messages_sent": a.messages_sent }),
            )
        })
        .collect();
    json!({
        "map": map,
        "robots": robots,
        "seed": s.seed,
        "completed": s.completed,
        "ticks": s.ticks,
        "deliveries": s.deliveries,
        "messages": s.messages,
        "agents": agents,
    })
}

/// Tick budgets: a single robot explores and fetches alone; a team shares the work.
fn budget(robots: usize) -> u64 {
    match robots {
        1 => 6_000,
        2 => 4_000,
        _ => 3_000,
    }
}

fn team_game(map: &str, robots: usize, seed: u64) -> serde_json::Value {
    let b = budget(robots);
    let s = play("bw4t.mas2g", map, robots, seed, b, 2);
    if robots == 1 {
        assert_eq!(s.messages, 0, "a lone robot has nobody to talk to");
    } else {
        assert!(s.messages > 0, "{map}: a team coordinates by messages");
    }
    check(&s, map, robots, b)
}

#[test]
fn team_banana_1_robot() {
    insta::assert_json_snapshot!(team_game("banana", 1, 1));
}

/// Three robots on banana (six yellow blocks in six rooms): besides the figures, the trace shows
/// the team talking in the seed's message vocabulary and getting past closed doors.
#[test]
fn team_banana_3_robots() {
    let b = budget(3);
    let buf = Buf::default();
    let s = play_traced("bw4t.mas2g", "banana", 3, 1, b, 2, Some(buf.clone()));
    let figures = check(&s, "banana", 3, b);
    let text = String::from_utf8(buf.0.lock().expect("buffer").clone()).expect("utf-8");
    let records: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON object per line"))
        .collect();
    // Every kind of message the team uses is sent, and each is in the BW4T vocabulary.
    let messages: Vec<&serde_json::Value> =
        records.iter().filter(|r| r["type"] == "message").collect();
    for kind in [
        "imp(in(",
        "imp(pickedUpFrom(",
        "pickedUpFrom(",
        "putDown(",
        "at(",
        "checked(",
    ] {
        assert!(
            messages
                .iter()
                .any(|m| m["content"].as_str().is_some_and(|c| c.starts_with(kind))),
            "no {kind}...) message"
        );
    }
    for m in &messages {
        assert!(
            m["english"].is_string(),
            "not in the vocabulary: {}",
            m["content"]
        );
    }
    // Robots met closed doors (an occupied drop zone or room) and still finished.
    assert!(
        text.contains("\"percept\":\"state(collided)\""),
        "no robot was ever stopped by a closed door"
    );
    insta::assert_json_snapshot!(figures);
}

#[test]
fn team_rainbow_1_robot() {
    insta::assert_json_snapshot!(team_game("rainbow", 1, 1));
}

#[test]
fn team_rainbow_3_robots() {
    insta::assert_json_snapshot!(team_game("rainbow", 3, 1));
}

#[test]
fn team_dutch_flag_1_robot() {
    insta::assert_json_snapshot!(team_game("dutch-flag", 1, 1));
}

#[test]
fn team_dutch_flag_3_robots() {
    insta::assert_json_snapshot!(team_game("dutch-flag", 3, 1));
}

#[test]
fn team_random_3_robots() {
    insta::assert_json_snapshot!(team_game("random", 3, 5));
}

/// A small map unlike the standard layout: one room has two doors' worth of neighbours and the
/// drop zone's neighbour is a plain hall. The team finds rooms by name and needs no fixed
/// place names besides `DropZone`.
#[test]
fn team_tiny_2_robots() {
    let b = 1_000;
    let s = play("bw4t.mas2g", "tiny", 2, 1, b, 2);
    insta::assert_json_snapshot!(check(&s, "tiny", 2, b));
}

/// The same seed gives the same game, whether the agents run on one worker thread or two.
#[test]
fn team_is_deterministic() {
    let b = budget(2);
    let one = play("bw4t.mas2g", "dutch-flag", 2, 3, b, 1);
    let two = play("bw4t.mas2g", "dutch-flag", 2, 3, b, 2);
    assert_eq!(one.to_json(), two.to_json());
    insta::assert_json_snapshot!(check(&one, "dutch-flag", 2, b));
}

/// The course-style robot finishes the default map on its own.
#[test]
fn course_robot_finishes_banana_alone() {
    let b = 7_000;
    let s = play("robot.mas2g", "banana", 1, 1, b, 1);
    insta::assert_json_snapshot!(check(&s, "banana", 1, b));
}
