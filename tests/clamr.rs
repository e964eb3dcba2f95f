//! CLAMR conversations end to end: the seed's temperature example as GOAL agents (session trace
//! snapshotted, frames compared byte for byte with the seed's figures), every session protocol
//! and its violations, every content-language form, frames under fuzzing, the token ring with
//! a failed member and with loss, and the reference BW4T team over both transports.

use goal::agent::Message;
use goal::clamr::act::{classify, SpeechAct};
use goal::clamr::frame::{encode_message, round_trip, Assembler, Frame, FRAME_LEN};
use goal::clamr::ring::{Faults, Ring};
use goal::clamr::transport::Kind;
use goal::clamr::CommOptions;
use goal::mas::routing::Transport;
use goal::mas::run::{run, Observer, RunOptions};
use goal::mas::system::load_mas;
use goal::mas::trace::TraceWriter;
use goal::mas::RunSummary;
use goal::term::Term;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::Write;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

fn fixture(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/clamr")
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

/// Collects warnings and printed lines.
#[derive(Default)]
struct Seen {
    warnings: Vec<String>,
    printed: Vec<String>,
}

impl Observer for Seen {
    fn warning(&mut self, text: &str) {
        self.warnings.push(text.to_string());
    }
    fn printed(&mut self, agent: &str, line: &str) {
        self.printed.push(format!("{agent}: {line}"));
    }
}

struct Ran {
    summary: RunSummary,
    trace: Vec<serde_json::Value>,
    seen: Seen,
}

fn term(text: &str) -> Term {
    goal::syntax::prolog::Reader::new("t")
        .term(text, 0)
        .expect("term")
        .term
}

fn comm(kind: Kind, faults: Faults) -> CommOptions {
    CommOptions {
        kind,
        faults,
        sessions: true,
        trace_sessions: true,
    }
}

fn run_mas(path: PathBuf, opts: RunOptions) -> Ran {
    let sys = load_mas(&path).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let buf = Buf::default();
    let mut seen = Seen::default();
    let writer = TraceWriter::new(Box::new(buf.clone()));
    let (summary, err) =
        run(&sys, &opts, Some(writer), &mut seen).unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None);
    let text = String::from_utf8(buf.0.lock().expect("buffer").clone()).expect("utf-8");
    let trace = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("json line"))
        .collect();
    Ran {
        summary,
        trace,
        seen,
    }
}

fn small_opts(kind: Kind) -> RunOptions {
    RunOptions {
        max_ticks: 200,
        workers: 1,
        trace_rules: false,
        comm: comm(kind, Faults::default()),
        ..RunOptions::default()
    }
}

fn records<'a>(trace: &'a [serde_json::Value], kind: &str) -> Vec<&'a serde_json::Value> {
    trace.iter().filter(|r| r["type"] == kind).collect()
}

/// Figure 7: the first 8 bytes of Robot 2's request to Robot 3 to sense the temperature:
/// sender 2, receiver 3, session token `0 1`, CL 0 (no complex act, no constraint), CA with
/// SAT Request (2) and action Sense (5), the parameter byte with the temperature bit, no data.
const FIGURE_7: [u8; 8] = [0x02, 0x03, 0x00, 0x01, 0x00, 0b010_00101, 0b1000_0000, 0x00];

/// Figure 8: the first 11 bytes of Robot 3's acknowledgement with DONE: SAT Acknowledge (6),
/// performative Report (8), the last parameter bit set (done), the reading 25 in 4 data bytes.
const FIGURE_8: [u8; 11] = [
    0x03,
    0x02,
    0x00,
    0x01,
    0x00,
    0b110_01000,
    0b0000_0001,
    0x00,
    0x00,
    0x00,
    25,
];

#[test]
fn temperature_example_sessions_and_frames() {
    for kind in [Kind::InProcess, Kind::Ring] {
        let ran = run_mas(fixture("temperature.mas2g"), small_opts(kind));
        assert_eq!(ran.seen.printed, ["robot2: 25"], "{kind:?}");
        assert!(ran.seen.warnings.is_empty(), "{:?}", ran.seen.warnings);
        let s = ran.summary.sessions.as_ref().expect("sessions");
        assert_eq!((s.opened, s.completed, s.violations), (1, 1, 0));
        // The frames of the messages the agents sent, with their ring addresses.
        let address = |n: &serde_json::Value| match n.as_str() {
            Some("robot1") => 1,
            Some("robot2") => 2,
            _ => 3,
        };
        let frames: Vec<[u8; FRAME_LEN]> = records(&ran.trace, "message")
            .iter()
            .flat_map(|m| {
                let content = term(m["content"].as_str().expect("content"));
                let sender = m["from"].as_str().expect("from");
                encode_message(address(&m["from"]), address(&m["to"]), sender, &content)
                    .expect("frames")
            })
            .collect();
        assert_eq!(frames.len(), 3, "request, accept, done: one frame each");
        assert_eq!(frames[0][..8], FIGURE_7);
        assert!(frames[0][8..].iter().all(|b| *b == 0));
        assert_eq!(frames[2][..11], FIGURE_8);
        let sessions: Vec<String> = records(&ran.trace, "session")
            .iter()
            .map(|r| r.to_string())
            .collect();
        if kind == Kind::InProcess {
            insta::assert_snapshot!("temperature_sessions", sessions.join("\n"));
        } else {
            insta::assert_snapshot!("temperature_sessions_ring", sessions.join("\n"));
            assert_eq!(ran.summary.comm.as_ref().expect("comm")["lost"], 0);
        }
    }
}

#[test]
fn every_protocol_and_its_violations() {
    let ran = run_mas(fixture("protocols.mas2g"), small_opts(Kind::InProcess));
    let sessions: Vec<String> = records(&ran.trace, "session")
        .iter()
        .map(|r| r.to_string())
        .collect();
    insta::assert_snapshot!("protocol_sessions", sessions.join("\n"));
    let s = ran.summary.sessions.as_ref().expect("sessions");
    assert_eq!(s.by_act.get("requestWhen"), Some(&1));
    assert_eq!(s.by_act.get("query"), Some(&1));
    assert_eq!(s.by_act.get("offer"), Some(&1));
    assert_eq!(s.by_act.get("request"), Some(&1));
    assert_eq!(s.refused, 1, "bob refused the request to stop");
    assert_eq!(s.violations, 2);
    let v: Vec<&String> = ran
        .seen
        .warnings
        .iter()
        .filter(|w| w.starts_with("protocol violation"))
        .collect();
    assert_eq!(v.len(), 2, "{:?}", ran.seen.warnings);
    // A double answer names the second report and the first.
    assert!(
        v[0].contains("double answer") && v[0].contains("ack(done,1)"),
        "{}",
        v[0]
    );
    assert!(v[0].contains("requestWhen(move(north),go)"), "{}", v[0]);
    // A report without request names the report and what its receiver last said.
    assert!(
        v[1].contains("bob sent the report ack(done,2) to carol"),
        "{}",
        v[1]
    );
    assert!(v[1].contains("carol never sent bob a message"), "{}", v[1]);
}

#[test]
fn content_forms_are_read_checked_and_tested() {
    let ran = run_mas(fixture("content.mas2g"), small_opts(Kind::InProcess));
    let english: Vec<String> = records(&ran.trace, "message")
        .iter()
        .filter(|m| m["from"] == "forms")
        .map(|m| format!("{} | {} | {}", m["content"], m["act"], m["english"]))
        .collect();
    insta::assert_snapshot!("content_english", english.join("\n"));
    assert_eq!(
        ran.seen.printed,
        ["forms: [greater(2),range(1,5),and(greater(1),smaller(5)),3]"]
    );
    let stopped = ran.summary.agents["badrange"]
        .error
        .clone()
        .expect("stopped");
    assert!(stopped.contains("badrange.goal:4"), "{stopped}");
    assert!(stopped.contains("swap them"), "{stopped}");
}

#[test]
fn frames_round_trip_on_generated_acts() {
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let atoms = [
        "temperature",
        "pressure",
        "light",
        "north",
        "'RoomA1'",
        "red",
    ];
    for _ in 0..500 {
        let a = atoms[rng.gen_range(0..atoms.len())];
        let n: i32 = rng.gen();
        let text = match rng.gen_range(0..9) {
            0 => format!("imp(sense({a}))"),
            1 => format!("int(sense({a}))"),
            2 => format!("offer(sense({a}))"),
            3 => format!("ack(done, {n})"),
            4 => format!("ack(failed, {n})"),
            5 => format!("ack(accept, sense({a}))"),
            6 => format!("requestWhen(goTo({a}), go{n})"),
            7 => format!(
                "imp(sequence([goTo({a}), pickup(range({}, {n}))]))",
                i64::from(n) - 1
            ),
            _ => format!("at({a}, \"text {n}\", [1, 2.5, f(X, Y)])"),
        };
        let t = term(&text);
        let back = round_trip(2, 3, "Bot2", &t).unwrap_or_else(|e| panic!("{text}: {e}"));
        // Variables come back renamed: compare the printed forms with numbered variables.
        assert_eq!(
            goal::term::Term::compare(&back, &t) == std::cmp::Ordering::Equal || !t.is_ground(),
            true,
            "{text} came back as {back}"
        );
        if !t.is_ground() {
            assert_eq!(back.vars().len(), t.vars().len(), "{text}");
        }
    }
    // Long content takes several extension frames.
    let long = term(&format!("info({})", "x".repeat(400)));
    assert!(encode_message(1, 2, "a", &long).expect("frames").len() > 20);
    assert_eq!(round_trip(1, 2, "a", &long).expect("back"), long);
}

#[test]
fn decoding_arbitrary_bytes_never_panics() {
    let mut rng = ChaCha8Rng::seed_from_u64(4242);
    let mut asm = Assembler::default();
    let mut decoded = 0;
    for i in 0..20_000 {
        let len = if i % 10 == 0 {
            rng.gen_range(0..64)
        } else {
            FRAME_LEN
        };
        let mut b: Vec<u8> = (0..len).map(|_| rng.gen()).collect();
        if len == FRAME_LEN && i % 2 == 0 {
            // Valid token and codes, so decoding goes deeper.
            (b[2], b[3]) = (0, 1);
            b[5] = (rng.gen_range(1..7) << 5) | [0, 5, 8, 6, 31][rng.gen_range(0..5)];
            b[9] = rng.gen_range(0..3);
            b[10] = rng.gen_range(0..20);
            b[7] = 0;
            b[8] = 0;
        }
        decoded += usize::from(Frame::decode(&b).is_ok());
        let _ = asm.push(&b);
    }
    assert!(decoded > 1000, "the fuzz must reach past the header checks");
}

fn msg(from: &str, to: &str, content: &str) -> Message {
    Message {
        sender: from.into(),
        receiver: to.into(),
        content: term(content),
    }
}

/// Runs `ring` for `rounds` rounds, sending `plan[r]` in round r; returns the arrivals.
fn drive(ring: &mut Ring, plan: &[Vec<Message>], rounds: u64) -> (Vec<Message>, Vec<Message>) {
    let (mut arrived, mut lost) = (Vec::new(), Vec::new());
    for r in 0..rounds {
        let sent = plan.get(r as usize).cloned().unwrap_or_default();
        let c = ring.carry(r, sent);
        arrived.extend(c.arrived);
        lost.extend(c.lost);
    }
    (arrived, lost)
}

fn names(n: usize) -> Vec<String> {
    (1..=n).map(|i| format!("Bot{i}")).collect()
}

#[test]
fn ring_reforms_around_a_failed_member() {
    let faults = Faults {
        fail: vec![("Bot2".into(), 5)],
        loss: 0.0,
    };
    let mut ring = Ring::new(&names(5), &faults, 1).expect("ring");
    // After Bot2 fails, every live robot sends to every other live robot.
    let live = ["Bot1", "Bot3", "Bot4", "Bot5"];
    let mut plan = vec![Vec::new(); 10];
    for a in live {
        for b in live.iter().filter(|b| **b != a) {
            plan.push(vec![msg(a, b, &format!("hello({})", a.to_lowercase()))]);
        }
    }
    let (arrived, lost) = drive(&mut ring, &plan, 200);
    assert!(lost.is_empty(), "{lost:?}");
    assert_eq!(
        arrived.len(),
        12,
        "every message between live robots arrives"
    );
    let stats = ring.stats();
    assert_eq!(stats["reformed"], 1, "{stats}");
    assert_eq!(stats["failed"], serde_json::json!(["Bot2"]));
    // Messages to the failed robot are lost.
    let (_, lost) = drive(&mut ring, &[vec![msg("Bot1", "Bot2", "ping")]], 20);
    assert_eq!(lost.len(), 1);
}

#[test]
fn ring_counts_lost_messages() {
    let faults = Faults {
        fail: Vec::new(),
        loss: 0.25,
    };
    let mut ring = Ring::new(&names(3), &faults, 7).expect("ring");
    let plan: Vec<Vec<Message>> = (0..400)
        .map(|i| vec![msg("Bot1", "Bot3", &format!("n({i})"))])
        .collect();
    let (arrived, lost) = drive(&mut ring, &plan, 1400);
    assert_eq!(arrived.len() + lost.len(), 400);
    assert!((50..150).contains(&lost.len()), "{} lost", lost.len());
    assert_eq!(ring.stats()["lost"], lost.len());
    // Seeded: the same faults and seed lose the same messages.
    let mut again = Ring::new(&names(3), &faults, 7).expect("ring");
    assert_eq!(drive(&mut again, &plan, 1400).1, lost);
}

#[test]
fn speech_acts_of_the_bw4t_vocabulary() {
    for m in goal::bw4t::messages::MESSAGES {
        let text = m
            .pattern
            .replace("Me", "'Bot1'")
            .replace("Player", "'Bot2'")
            .replace("Room", "r1")
            .replace("Place", "r2")
            .replace("Color", "'Red'")
            .replace("Block", "3")
            .replace('N', "2");
        let t = term(&text);
        let act = classify("Bot1", &t);
        let expected = if m.pattern == "ok(Room)" {
            SpeechAct::Acknowledge
        } else {
            m.act
        };
        assert_eq!(act.sat, expected, "{}", m.pattern);
        assert_eq!(
            goal::mas::vocabulary::act("Bot1", &t).sat,
            m.act,
            "{}",
            m.pattern
        );
    }
    // The wishes of the vocabulary name BW4T's actions.
    let go = goal::mas::vocabulary::act("Bot1", &term("imp(in('Bot2', 'RoomA1'))"));
    assert_eq!(
        (go.sat, go.action.map(|p| p.name)),
        (SpeechAct::Request, Some("goTo"))
    );
    assert_eq!(go.params, [term("'Bot2'"), term("'RoomA1'")]);
    let get = goal::mas::vocabulary::act("Bot1", &term("imp(holding('Bot2', 'Red'))"));
    assert_eq!(get.action.map(|p| p.name), Some("pickUp"));
}

fn bw4t_team(kind: Kind) -> RunSummary {
    let maps = concat!(env!("CARGO_MANIFEST_DIR"), "/agents/bw4t/bw4t.mas2g");
    let sys = load_mas(std::path::Path::new(maps)).unwrap_or_else(|p| panic!("{}", p[0].render()));
    let opts = RunOptions {
        seed: Some(1),
        map: Some("tiny".into()),
        robots: Some(2),
        max_ticks: 3000,
        workers: 1,
        trace_rules: false,
        comm: CommOptions {
            kind,
            sessions: true,
            ..CommOptions::default()
        },
        ..RunOptions::default()
    };
    let mut seen = Seen::default();
    let (s, err) =
        run(&sys, &opts, None, &mut seen).unwrap_or_else(|p| panic!("{}", p[0].render()));
    assert_eq!(err, None);
    s
}

#[test]
fn bw4t_team_completes_over_both_transports_with_sessions() {
    for kind in [Kind::InProcess, Kind::Ring] {
        let s = bw4t_team(kind);
        assert!(
            s.completed,
            "{kind:?}: not completed after {} ticks",
            s.ticks
        );
        assert_eq!(s.deliveries.wrong, 0);
        let sessions = s.sessions.as_ref().expect("sessions");
        assert!(sessions.opened > 0, "{kind:?}: {sessions:?}");
        assert_eq!(
            sessions.violations, 0,
            "{kind:?}: the team keeps to the protocols"
        );
        assert_eq!(
            sessions.opened,
            sessions.by_act.values().sum::<u64>(),
            "{kind:?}"
        );
        let json = s.to_json();
        assert!(json["sessions"]["response_ticks"].is_object(), "{json}");
        if kind == Kind::Ring {
            assert_eq!(json["comm"]["lost"], 0);
            assert!(json["comm"]["frames"].as_u64() > Some(0));
        }
    }
}

#[test]
fn following_sessions_leaves_the_default_trace_unchanged() {
    let pingpong = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("agents/pingpong/pingpong.mas2g");
    let base = RunOptions {
        max_ticks: 200,
        workers: 1,
        ..RunOptions::default()
    };
    let plain = run_mas(pingpong.clone(), base.clone());
    let followed = run_mas(
        pingpong,
        RunOptions {
            comm: CommOptions {
                sessions: true,
                ..CommOptions::default()
            },
            ..base
        },
    );
    assert_eq!(plain.trace, followed.trace);
    assert!(plain.summary.sessions.is_none() && plain.summary.comm.is_none());
    let s = followed.summary.sessions.expect("sessions");
    assert_eq!(s.by_act.get("query"), Some(&1), "{s:?}");
    // Pong answers the score question, but never acknowledges ping's `!play`.
    assert_eq!((s.completed, s.abandoned), (s.opened - 1, 1), "{s:?}");
    assert_eq!(s.response_ticks.answered, 1, "{s:?}");
}

fn goal_run(args: &[&str]) -> (Option<i32>, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("run")
        .args(args)
        .output()
        .expect("goal runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn cli_ring_faults_and_stats() {
    let mas = fixture("temperature.mas2g");
    let mas = mas.to_str().expect("path");
    let (code, err) = goal_run(&[mas, "--comm-loss", "0.1"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("add --comm ring"), "{err}");
    let (code, err) = goal_run(&[mas, "--comm", "ring", "--comm-fail", "nobody@3"]);
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("there is no agent nobody"), "{err}");
    let dir = std::env::temp_dir().join(format!("clamr-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let stats = dir.join("s.json");
    let (code, err) = goal_run(&[
        mas,
        "--comm",
        "ring",
        "--comm-fail",
        "robot1@0",
        "--stats",
        stats.to_str().expect("path"),
    ]);
    assert!(err.contains("robot1's link failed at tick 0"), "{err}");
    assert!(err.contains("ring re-formed"), "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).expect("stats")).expect("json");
    assert_eq!(s["sessions"]["completed"], 1, "{s}");
    assert_eq!(s["comm"]["failed"], serde_json::json!(["robot1"]), "{s}");
    assert_eq!(s["comm"]["lost"], 0, "{s}");
    assert_eq!(code, Some(0), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_session_token_keeps_the_conversation_with_one_partner() {
    let mut ring = Ring::new(&names(4), &Faults::default(), 1).expect("ring");
    // Bot1 holds the token first and requests something of Bot3: Bot3 gets a session token.
    let c = ring.carry(0, vec![msg("Bot1", "Bot3", "imp(stop)")]);
    assert!(c.arrived.is_empty(), "two hops to Bot3");
    // Bot3 has a message for Bot4 (one hop) and its answer for Bot1 (two hops): under the
    // session token only the answer leaves; the message to Bot4 waits for the general token.
    let plan = vec![vec![
        msg("Bot3", "Bot4", "x"),
        msg("Bot3", "Bot1", "ack(refuse,stop)"),
    ]];
    let (arrived, lost) = drive(&mut ring, &plan, 12);
    assert!(lost.is_empty());
    let order: Vec<String> = arrived.iter().map(|m| m.content.to_string()).collect();
    assert_eq!(order, ["imp(stop)", "ack(refuse,stop)", "x"]);
}
