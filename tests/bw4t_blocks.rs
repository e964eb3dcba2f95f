//! Blocks: reach (scenario 7), gripper stack (8), drops everywhere (9), battery (12),
//! colour-blindness and size (13).

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::world::BlockState;
use goal::bw4t::{Bw4tConfig, RobotConfig, RobotState};
use goal::env::{ActionResult, Environment};

fn fail_msg(r: ActionResult) -> String {
    match r {
        ActionResult::Failed(m) => m,
        ActionResult::Ok => panic!("expected a failure"),
    }
}

#[test]
fn pick_up_needs_reach_and_a_free_gripper() {
    let mut bw = default_env("tiny");
    travel(&mut bw, "Bot1", "RoomA");
    let red = blocks_in(&bw, "RoomA", "Red")[0];
    let blue = blocks_in(&bw, "RoomA", "Blue")[0];
    let w = bw.world();
    let bpos = w.blocks[w.block_index(red).unwrap()].pos;
    let centre = w.zones[w.zone_index("RoomA").unwrap()].centre();
    let dir = {
        let d = centre - bpos;
        if d.norm() < 1e-6 {
            goal::bw4t::geometry::Vec2::new(1.0, 0.0)
        } else {
            d / d.norm()
        }
    };
    let stand = |dist: f64| bpos + dir * dist;
    let p = stand(3.01);
    ok(&mut bw, "Bot1", go_to_xy(p.x, p.y));
    run_until_stopped(&mut bw, "Bot1", 1000);
    let m = fail_msg(bw.perform("Bot1", &pick_up(red)));
    assert!(m.contains("out of reach"), "{m}");
    let p = stand(2.99);
    ok(&mut bw, "Bot1", go_to_xy(p.x, p.y));
    run_until_stopped(&mut bw, "Bot1", 1000);
    ok(&mut bw, "Bot1", pick_up(red));
    // The gripper (capacity 1) is full: no atBlock, pickUp fails with a message.
    ok(&mut bw, "Bot1", go_to_block(blue));
    run_until_stopped(&mut bw, "Bot1", 1000);
    let batch = bw.percepts("Bot1");
    assert!(named(&batch, "atBlock").is_empty(), "{:?}", show(&batch));
    let m = fail_msg(bw.perform("Bot1", &pick_up(blue)));
    assert!(m.contains("gripper is full"), "{m}");
    // A block that is held, or not in the robot's zone, is not visible.
    let m = fail_msg(bw.perform("Bot1", &pick_up(red)));
    assert!(m.contains("not visible"), "{m}");
    let other = blocks_in(&bw, "RoomB", "Red")[0];
    assert!(fail_msg(bw.perform("Bot1", &go_to_block(other))).contains("not visible"));
    assert!(fail_msg(bw.perform("Bot1", &pick_up(9999))).contains("not visible"));
}

#[test]
fn the_gripper_is_a_stack() {
    let cfg = Bw4tConfig {
        robot: RobotConfig {
            gripper_capacity: 3,
            ..RobotConfig::default()
        },
        ..Bw4tConfig::default()
    };
    let mut bw = env("tiny", cfg);
    let mut base = Base::default();
    base.apply(&bw.percepts("Bot2"));
    assert!(base.has("gripperCapacity(3)"));
    let a = fetch(&mut bw, "Bot2", "RoomB", "Red");
    let b = fetch(&mut bw, "Bot2", "RoomB", "Green");
    let c = fetch(&mut bw, "Bot2", "RoomB", "Yellow");
    base.apply(&bw.percepts("Bot2"));
    assert!(
        base.has(&format!("holdingblocks([{c},{b},{a}])")),
        "{:?}",
        base.facts
    );
    for id in [a, b, c] {
        assert!(base.has(&format!("holding({id})")));
    }
    assert!(base.named("color").is_empty());
    ok(&mut bw, "Bot2", put_down());
    base.apply(&bw.percepts("Bot2"));
    assert!(
        base.has(&format!("holdingblocks([{b},{a}])")),
        "{:?}",
        base.facts
    );
    assert!(!base.has(&format!("holding({c})")));
    // Put down in a room: the block is back, near the robot, visible again.
    let w = bw.world();
    let block = &w.blocks[w.block_index(c).unwrap()];
    assert_eq!(block.state, BlockState::Free);
    assert!((block.pos - w.robots[1].pos).norm() <= 0.75);
    assert!(
        base.has(&format!("color({c},'Yellow')")),
        "{:?}",
        base.facts
    );
    assert_eq!(bw.run_stats().dropped_in_rooms, 1);
}

#[test]
fn drops_in_corridors_the_drop_zone_and_after_completion() {
    let mut bw = default_env("tiny");
    // A red block put down on the drop zone's door band, centre still in the corridor: lost.
    let lost = fetch(&mut bw, "Bot2", "RoomB", "Red");
    travel(&mut bw, "Bot2", "HallC");
    ok(&mut bw, "Bot2", go_to_xy(25.0, 9.75));
    run_until_stopped(&mut bw, "Bot2", 1000);
    ok(&mut bw, "Bot2", put_down());
    let w = bw.world();
    assert_eq!(
        w.blocks[w.block_index(lost).unwrap()].state,
        BlockState::Gone
    );
    assert_eq!((w.sequence_index, bw.run_stats().dropped_elsewhere), (0, 1));
    // The right colour in the drop zone advances the sequence.
    fetch(&mut bw, "Bot1", "RoomA", "Red");
    travel(&mut bw, "Bot1", "DropZone");
    ok(&mut bw, "Bot1", put_down());
    assert_eq!(bw.world().sequence_index, 1);
    travel(&mut bw, "Bot1", "HallA");
    // A wrong colour is lost and counted.
    let green = fetch(&mut bw, "Bot2", "RoomB", "Green");
    travel(&mut bw, "Bot2", "DropZone");
    ok(&mut bw, "Bot2", put_down());
    let w = bw.world();
    assert_eq!(
        w.blocks[w.block_index(green).unwrap()].state,
        BlockState::Gone
    );
    assert_eq!(w.sequence_index, 1);
    assert_eq!(bw.run_stats().deliveries_wrong, 1);
    travel(&mut bw, "Bot2", "HallB");
    // The last colour completes the game.
    fetch(&mut bw, "Bot1", "RoomA", "Blue");
    travel(&mut bw, "Bot1", "DropZone");
    assert!(!bw.is_finished());
    ok(&mut bw, "Bot1", put_down());
    assert!(bw.is_finished());
    let done_at = bw.run_stats().finished_at_tick;
    assert_eq!(done_at, Some(bw.ticks()));
    travel(&mut bw, "Bot1", "HallC");
    // After completion further drops vanish; the index stays at the length.
    fetch(&mut bw, "Bot2", "RoomB", "Yellow");
    travel(&mut bw, "Bot2", "DropZone");
    ok(&mut bw, "Bot2", put_down());
    let s = bw.run_stats();
    assert_eq!(s.sequence_index, 2);
    assert_eq!(s.dropped_after_completion, 1);
    assert_eq!(s.deliveries_right, 2);
    assert_eq!(s.finished_at_tick, done_at);
    // Empty gripper.
    assert!(fail_msg(bw.perform("Bot2", &put_down())).contains("not holding"));
}

#[test]
fn battery_drains_per_step_stops_the_robot_and_refills_when_charging() {
    let cfg = |cap: f64| Bw4tConfig {
        robot: RobotConfig {
            battery: Some(cap),
            ..RobotConfig::default()
        },
        ..Bw4tConfig::default()
    };
    let mut bw = env("tiny", cfg(10.0));
    travel(&mut bw, "Bot1", "HallC");
    let r = &bw.world().robots[0];
    let expected = 10.0 - 80.0 * 0.0204;
    assert!((r.battery - expected).abs() < 1e-9, "{}", r.battery);
    let batch = bw.percepts("Bot1");
    let pct = batch
        .iter()
        .find(|t| t.functor().is_some_and(|(n, _)| n.name() == "battery"))
        .map(|t| match &t.args()[0] {
            goal::term::Term::Float(f) => f.0,
            other => panic!("battery({other})"),
        })
        .expect("a battery percept");
    assert!((pct - expected * 10.0).abs() < 1e-9, "{pct}");
    // Charging refills to the maximum.
    travel(&mut bw, "Bot1", "Charger");
    assert_eq!(bw.world().robots[0].battery_percent(), 100.0);
    // An empty battery stops the robot where it is; its plan runs out (state arrived).
    let mut bw = env("tiny", cfg(0.5));
    ok(&mut bw, "Bot1", go_to("HallC"));
    run_until_stopped(&mut bw, "Bot1", 1000);
    let r = &bw.world().robots[0];
    assert_eq!(r.battery, 0.0);
    assert_eq!(r.state(), RobotState::Arrived);
    assert!((r.pos.x - (5.0 + 25.0 * 0.25)).abs() < 1e-9, "{}", r.pos.x);
    assert!(has(&bw.percepts("Bot1"), "battery(0.0)"));
    // Without a battery the percentage is always 100.
    let mut plain = default_env("tiny");
    assert!(has(&plain.percepts("Bot1"), "battery(100.0)"));
}

#[test]
fn colour_blind_robots_see_dark_gray_and_big_robots_stay_out_of_rooms() {
    let cfg = Bw4tConfig {
        colorblind: vec!["Bot1".into()],
        ..Bw4tConfig::default()
    };
    let mut bw = env("tiny", cfg);
    assert!(has(&bw.percepts("Bot1"), "colorblind(true)"));
    assert!(has(&bw.percepts("Bot2"), "colorblind(false)"));
    travel(&mut bw, "Bot1", "RoomA");
    let colours = named(&bw.percepts("Bot1"), "color");
    assert_eq!(colours.len(), 2);
    assert!(
        colours.iter().all(|c| c.ends_with("'DarkGray')")),
        "{colours:?}"
    );
    travel(&mut bw, "Bot2", "RoomB");
    let colours = named(&bw.percepts("Bot2"), "color");
    assert_eq!(colours.len(), 3);
    assert!(!colours.iter().any(|c| c.contains("DarkGray")));

    let big = Bw4tConfig {
        robot: RobotConfig {
            size: 4.0,
            ..RobotConfig::default()
        },
        ..Bw4tConfig::default()
    };
    let mut bw = env("tiny", big);
    let sizes = named(&bw.percepts("Bot1"), "robotSize");
    assert_eq!(sizes.len(), 4);
    assert!(sizes.iter().all(|s| s.ends_with(",4,4)")), "{sizes:?}");
    for (bot, room) in [("Bot1", "RoomA"), ("Bot2", "RoomB"), ("Bot3", "DropZone")] {
        ok(&mut bw, bot, go_to(room));
        run_until_stopped(&mut bw, bot, 1000);
        assert_eq!(state(&bw, bot), RobotState::Collided, "{bot}");
    }
    // Corridors are fine.
    travel(&mut bw, "Bot4", "HallC");
}
