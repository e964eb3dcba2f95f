//! Whole games through the channel interface: spawning (scenario 14), the scripted greedy game
//! (15), and the thread protocol in both modes.

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::{greedy, map, Bw4t, Bw4tConfig};
use goal::env::thread::{EnvError, EnvHandle, Mode};
use goal::env::{ActionResult, Environment, InitParams};
use goal::term::Term;

#[test]
fn spawning_stops_at_the_maps_spawn_points() {
    let bw = env(
        "banana",
        Bw4tConfig {
            robots: Some(4),
            ..Bw4tConfig::default()
        },
    );
    let names: Vec<String> = bw.entities().into_iter().map(|e| e.name).collect();
    assert_eq!(names, ["Bot1", "Bot2", "Bot3"]);
    assert!(bw.entities().iter().all(|e| e.kind == "bot"));
    assert_eq!(bw.warnings().len(), 1);
    assert!(
        bw.warnings()[0].contains("no spawn point left"),
        "{:?}",
        bw.warnings()
    );
    let p = &bw.world().robots;
    assert_eq!((p[1].pos.x, p[1].pos.y), (21.0, 63.0));
    assert_eq!(default_env("super-random").entities().len(), 10);
}

#[test]
fn init_parameters_configure_a_run_and_bad_ones_are_diagnostics() {
    let mut params = InitParams::new();
    params.insert("map".into(), Term::atom("tiny"));
    params.insert("robots".into(), Term::Int(2));
    params.insert("gripperCapacity".into(), Term::Int(2));
    params.insert("colorblind".into(), Term::list(vec![Term::atom("Bot2")]));
    let mut bw = <Bw4t as goal::env::FromInitParams>::from_init_params(&params).unwrap();
    assert_eq!(bw.entities().len(), 2);
    assert!(has(&bw.percepts("Bot2"), "colorblind(true)"));
    assert!(has(&bw.percepts("Bot1"), "gripperCapacity(2)"));
    params.insert("robots".into(), Term::atom("many"));
    let e = Bw4t::from_params(&params).unwrap_err();
    assert!(e[0].message.contains("`robots`"), "{}", e[0].message);
    let mut params = InitParams::new();
    params.insert("mapp".into(), Term::atom("tiny"));
    let e = Bw4t::from_params(&params).unwrap_err();
    assert!(e[0].message.contains("unknown init parameter `mapp`"));
    let mut params = InitParams::new();
    params.insert("map".into(), Term::atom("atlantis"));
    assert!(Bw4t::from_params(&params).is_err());
}

#[test]
fn a_scripted_greedy_robot_completes_banana_through_the_channel() {
    let m = map::builtin("banana").unwrap().unwrap();
    let bw = Bw4t::new(
        &m,
        &Bw4tConfig {
            robots: Some(1),
            ..Bw4tConfig::default()
        },
    );
    let handle = EnvHandle::spawn(Box::new(bw), Mode::LockStep);
    let info = handle.info().unwrap();
    assert_eq!(info.entities.len(), 1);
    let report = greedy::play(&handle, "Bot1", 20_000).unwrap();
    assert!(report.finished, "{report:?}");
    assert_eq!(report.delivered, 6);
    assert!(report.failures.is_empty(), "{report:?}");
    // The game is over but the simulation keeps running.
    let status = handle.status().unwrap();
    assert!(status.finished);
    assert_eq!(status.stats["sequence_index"], 6);
    assert_eq!(status.stats["deliveries_right"], 6);
    let r = handle.round(vec![]).unwrap();
    assert!(r.finished);
    assert_eq!(r.tick, report.ticks + 1);
    insta::assert_json_snapshot!("greedy_banana", (report.ticks, &status.stats));
    handle.stop();
}

#[test]
fn lock_step_rounds_apply_actions_in_order_and_advance_one_tick() {
    let handle = EnvHandle::spawn(Box::new(default_env("tiny")), Mode::LockStep);
    let first = handle.perceive(&[]).unwrap();
    assert_eq!(first.len(), 4);
    assert!(has(&first[0].1, "ownName('Bot1')"));
    let r = handle
        .round(vec![
            ("Bot2".into(), go_to("RoomB")),
            ("Bot1".into(), Term::atom("jump")),
            ("Nobody".into(), go_to("RoomB")),
        ])
        .unwrap();
    assert_eq!(r.tick, 1);
    assert_eq!(r.results[0], ("Bot2".to_string(), ActionResult::Ok));
    assert!(
        matches!(&r.results[1].1, ActionResult::Failed(m) if m.contains("unknown action jump/0"))
    );
    assert!(matches!(&r.results[2].1, ActionResult::Failed(m) if m.contains("unknown entity")));
    assert_eq!(r.percepts.len(), 4);
    assert!(has(&r.percepts[1].1, "state(traveling)"));
    assert_eq!(handle.round(vec![]).unwrap().tick, 2);
    assert!(matches!(
        handle.act("Bot1", go_to("RoomA")),
        Err(EnvError::WrongMode(_))
    ));
    drop(handle);
}

#[test]
fn real_time_mode_ticks_by_itself_and_applies_submitted_actions() {
    let handle = EnvHandle::spawn(
        Box::new(default_env("tiny")),
        Mode::RealTime {
            ticks_per_second: 2000.0,
        },
    );
    assert_eq!(
        handle.act("Bot1", go_to("RoomA")).unwrap(),
        ActionResult::Ok
    );
    let bad = handle.act("Bot1", go_to("Nowhere")).unwrap();
    assert!(matches!(bad, ActionResult::Failed(_)));
    assert_eq!(
        handle.act("Bot1", go_to("RoomA")).unwrap(),
        ActionResult::Ok
    );
    // Wait (by ticks, not by wall-clock assertions) until the robot is in the room.
    let mut seen = false;
    for _ in 0..100_000 {
        let batch = handle.perceive(&["Bot1".into()]).unwrap();
        if has(&batch[0].1, "in('RoomA')") {
            seen = true;
            break;
        }
        std::thread::yield_now();
    }
    assert!(seen);
    let s1 = handle.status().unwrap().ticks;
    assert!(s1 >= 21, "{s1}");
    assert!(matches!(handle.round(vec![]), Err(EnvError::WrongMode(_))));
    handle.stop();
}

#[test]
fn a_stopped_environment_answers_with_errors_not_panics() {
    let handle = EnvHandle::spawn(Box::new(default_env("tiny")), Mode::LockStep);
    let rx = {
        // Submitting in lock-step mode gives a value, not a hang.
        handle.submit("Bot1", go_to("RoomA")).unwrap()
    };
    assert!(matches!(rx.recv().unwrap(), Err(EnvError::WrongMode(_))));
    handle.stop();
}

#[test]
fn odd_actions_and_unchecked_maps_never_panic() {
    let mut bw = default_env("banana");
    let odd = [
        Term::compound("goTo", vec![Term::from(1.0e308), Term::from(-1.0e308)]),
        Term::compound("goTo", vec![Term::from(f64::NAN), Term::Int(3)]),
        Term::compound("goTo", vec![Term::Int(i64::MAX), Term::Int(i64::MIN)]),
        Term::compound("pickUp", vec![Term::Int(-1)]),
        Term::compound("goToBlock", vec![Term::from(1.5)]),
        Term::compound("sendMessage", vec![Term::Int(1), Term::Int(2)]),
        Term::compound("goTo", vec![Term::var("X")]),
        Term::string("goTo"),
        Term::Int(7),
        Term::var("A"),
    ];
    for a in &odd {
        let r = bw.perform("Bot1", a);
        assert!(matches!(r, ActionResult::Failed(_)), "{a}: {r:?}");
        for _ in 0..20 {
            bw.tick();
        }
        let _ = bw.percepts("Bot1");
    }
    let p = bw.world().robots[0].pos;
    assert_eq!((p.x, p.y), (25.0, 65.0));
    let empty = map::Map {
        name: "empty".into(),
        width: 10.0,
        height: 10.0,
        one_bot_per_corridor_zone: false,
        random_blocks: 3,
        random_sequence: 2,
        seed: None,
        sequence: vec!["Red".into()],
        spawns: vec![[1.0, 1.0]],
        human_spawns: Vec::new(),
        epartners: Vec::new(),
        zones: Vec::new(),
    };
    assert!(map::from_toml(&map::to_toml(&empty), "empty.toml").is_err());
    let mut bw = Bw4t::new(&empty, &Bw4tConfig::default());
    for a in odd.iter().chain([go_to("DropZone"), put_down()].iter()) {
        let _ = bw.perform("Bot1", a);
        bw.tick();
        let _ = bw.percepts("Bot1");
    }
    assert!(!bw.is_finished());
}
