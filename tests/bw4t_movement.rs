//! Movement: routes and tick counts (scenario 2), doors and occupancy (3-6), the state machine (11).

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::{Bw4tConfig, RobotState};
use goal::env::{ActionResult, Environment};

/// (target, route length, estimated ticks) from the spawn point (25,65), as the Java BW4T moves.
const TABLE: &[(&str, f64, u64)] = &[
    ("DropZone", 10.0, 43),
    ("RoomC1", 60.0, 246),
    ("RoomC3", 60.0, 246),
    ("RoomC2", 70.0, 287),
    ("RoomB1", 80.0, 327),
    ("RoomB3", 80.0, 327),
    ("RoomB2", 90.0, 368),
    ("RoomA1", 100.0, 408),
    ("RoomA3", 100.0, 408),
    ("RoomA2", 110.0, 449),
];

#[test]
fn routes_from_spawn_match_the_reference_lengths_and_tick_counts() {
    let mut rows = Vec::new();
    for &(room, length, ticks) in TABLE {
        let mut bw = env(
            "banana",
            Bw4tConfig {
                robots: Some(1),
                ..Bw4tConfig::default()
            },
        );
        let n = travel(&mut bw, "Bot1", room);
        let w = bw.world();
        let dist = w.robots[0].stats.distance;
        assert!((dist - length).abs() < 1e-6, "{room}: {dist} vs {length}");
        assert!(n.abs_diff(ticks) <= 2, "{room}: {n} ticks vs {ticks}");
        assert_eq!(at(&bw, "Bot1"), room);
        let route = w.route("FrontDropZone", room).unwrap();
        rows.push(format!(
            "{room}: {} ({dist} units, {n} ticks)",
            route.join(" > ")
        ));
    }
    insta::assert_json_snapshot!("routes_from_spawn", rows);
}

#[test]
fn ties_between_equal_routes_are_broken_by_file_order() {
    let bw = default_env("banana");
    let w = bw.world();
    // Two 70-unit routes lead to RoomC2 and two 90-unit ones to RoomB2: the same one is
    // chosen every time, the one through the earlier zones in the map file.
    for _ in 0..3 {
        assert_eq!(
            w.route("FrontDropZone", "RoomC2").unwrap(),
            [
                "FrontDropZone",
                "LeftHallD",
                "LeftHallC",
                "FrontRoomC1",
                "FrontRoomC2",
                "RoomC2"
            ]
        );
    }
    assert_eq!(w.route("RoomA1", "RoomA1").unwrap(), ["RoomA1"]);
}

#[test]
fn an_occupied_room_stops_the_next_robot_at_its_door() {
    let mut bw = default_env("banana");
    travel(&mut bw, "Bot1", "RoomC1");
    ok(&mut bw, "Bot2", go_to("RoomC1"));
    run_until_stopped(&mut bw, "Bot2", 2000);
    assert_eq!(state(&bw, "Bot2"), RobotState::Collided);
    assert_eq!(at(&bw, "Bot2"), "FrontRoomC1");
    let y = bw.world().robots[1].pos.y;
    assert!((49.5..50.0).contains(&y), "stopped at y = {y}");
    assert_eq!(bw.world().robots[1].collision, Some("hit closed door"));
    // Collided persists without a new movement action.
    for _ in 0..50 {
        bw.tick();
    }
    assert_eq!(state(&bw, "Bot2"), RobotState::Collided);
    // Once Bot1 has left, a new goTo succeeds.
    ok(&mut bw, "Bot1", go_to("DropZone"));
    while at(&bw, "Bot1") == "RoomC1" {
        bw.tick();
    }
    travel(&mut bw, "Bot2", "RoomC1");
    assert_eq!(at(&bw, "Bot2"), "RoomC1");
}

#[test]
fn entering_a_room_through_a_wall_collides() {
    let mut bw = default_env("tiny");
    travel(&mut bw, "Bot1", "RoomA");
    // Scenario 5: leaving a room through its wall into a corridor is allowed.
    travel(&mut bw, "Bot1", "HallSouth");
    assert_eq!(at(&bw, "Bot1"), "HallSouth");
    // Scenario 4: RoomA's door is on its north wall; coming from the south hits the wall.
    ok(&mut bw, "Bot1", go_to("RoomA"));
    run_until_stopped(&mut bw, "Bot1", 500);
    assert_eq!(state(&bw, "Bot1"), RobotState::Collided);
    assert_eq!(bw.world().robots[0].collision, Some("hit wall"));
    assert_eq!(at(&bw, "Bot1"), "HallSouth");
    ok(&mut bw, "Bot1", go_to_xy(6.0, 16.0));
    assert_eq!(state(&bw, "Bot1"), RobotState::Traveling);
    run_until_stopped(&mut bw, "Bot1", 500);
    assert_eq!(state(&bw, "Bot1"), RobotState::Collided);
    assert_eq!(at(&bw, "Bot1"), "HallSouth");
}

#[test]
fn one_bot_per_corridor_zone_blocks_occupied_corridors_only() {
    let cfg = Bw4tConfig {
        one_bot_per_corridor_zone: Some(true),
        ..Bw4tConfig::default()
    };
    let mut bw = env("tiny", cfg);
    ok(&mut bw, "Bot2", go_to("HallA"));
    run_until_stopped(&mut bw, "Bot2", 500);
    assert_eq!(state(&bw, "Bot2"), RobotState::Collided);
    assert_eq!(bw.world().robots[1].collision, Some("hit occupied zone"));
    assert_eq!(at(&bw, "Bot2"), "HallB");
    let x = bw.world().robots[1].pos.x;
    assert!((10.0..10.5).contains(&x), "stopped at x = {x}");
    // Charging zones are exempt: Bot3 may join Bot4 in the charger.
    travel(&mut bw, "Bot3", "Charger");
    // Without the rule the same move works.
    let mut free = default_env("tiny");
    travel(&mut free, "Bot2", "HallA");
    assert_eq!(at(&free, "Bot2"), "HallA");
}

#[test]
fn state_goes_arrived_traveling_arrived_one_tick_after_reaching_the_target() {
    let mut bw = default_env("tiny");
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
    ok(&mut bw, "Bot1", go_to_xy(7.0, 5.0));
    assert_eq!(state(&bw, "Bot1"), RobotState::Traveling);
    for _ in 0..8 {
        bw.tick();
    }
    let p = bw.world().robots[0].pos;
    assert_eq!((p.x, p.y), (7.0, 5.0));
    assert_eq!(state(&bw, "Bot1"), RobotState::Traveling);
    bw.tick();
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
}

#[test]
fn movement_actions_fail_visibly_on_bad_input() {
    let mut bw = default_env("banana");
    let fail = |r: ActionResult| match r {
        ActionResult::Failed(m) => m,
        ActionResult::Ok => panic!("expected a failure"),
    };
    assert!(fail(bw.perform("Bot1", &go_to("Narnia"))).contains("unknown place `Narnia`"));
    let bad = goal::term::Term::compound("goTo", vec![goal::term::Term::Int(1)]);
    assert!(fail(bw.perform("Bot1", &bad)).contains("goTo/1 expects a place name"));
    let bad = goal::term::Term::compound(
        "goTo",
        vec![goal::term::Term::atom("a"), goal::term::Term::Int(1)],
    );
    assert!(fail(bw.perform("Bot1", &bad)).contains("two numbers"));
    assert!(
        fail(bw.perform("Bot1", &goal::term::Term::atom("fly"))).contains("unknown action fly/0")
    );
    assert!(fail(bw.perform("Bot9", &go_to("DropZone"))).contains("unknown entity"));
    assert!(
        fail(bw.perform("Bot1", &goal::term::Term::atom("navigateObstacles")))
            .contains("interrupted by a collision")
    );
    // A point outside every zone is still reachable through free space.
    ok(&mut bw, "Bot1", go_to_xy(2.0, 57.0));
    run_until_stopped(&mut bw, "Bot1", 1000);
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
}
