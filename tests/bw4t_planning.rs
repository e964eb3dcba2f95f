//! Route plans of `goTo(X, Y)` on a 3x3 grid (BW4T's NavigatingRobotPathPlanningTest): zone
//! centres at 5/10/15, the middle cell a room reachable only from the top-middle cell.

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::map::{DoorSpec, Map, Orientation, ZoneKind, ZoneSpec};
use goal::bw4t::{Bw4t, Bw4tConfig, RobotState};
use goal::env::{ActionResult, Environment};

fn zone(name: &str, kind: ZoneKind, x: f64, y: f64, w: f64, nbrs: &[&str]) -> ZoneSpec {
    ZoneSpec {
        name: name.into(),
        kind,
        x,
        y,
        width: w,
        height: w,
        neighbours: nbrs.iter().map(|s| s.to_string()).collect(),
        doors: Vec::new(),
        blocks: Vec::new(),
    }
}

fn grid() -> Bw4t {
    let mut zones = Vec::new();
    for row in 0..3 {
        for col in 0..3 {
            let name = format!("Z{col}{row}");
            let mut nbrs = Vec::new();
            for (dc, dr) in [(-1i32, 0i32), (1, 0), (0, -1), (0, 1)] {
                let (c, r) = (col + dc, row + dr);
                if (0..3).contains(&c) && (0..3).contains(&r) && (c, r) != (1, 1) {
                    nbrs.push(format!("Z{c}{r}"));
                }
            }
            let (x, y) = (5.0 + 5.0 * col as f64, 5.0 + 5.0 * row as f64);
            let names: Vec<&str> = nbrs.iter().map(String::as_str).collect();
            if (col, row) == (1, 1) {
                let mut room = zone(&name, ZoneKind::Room, x, y, 5.0, &["Z10"]);
                room.doors.push(DoorSpec {
                    x,
                    y: y - 2.5,
                    orientation: Orientation::Horizontal,
                });
                zones.push(room);
            } else {
                let names: Vec<&str> = names.into_iter().filter(|n| *n != "Z11").collect();
                zones.push(zone(&name, ZoneKind::Corridor, x, y, 5.0, &names));
            }
        }
    }
    // A drop zone that nothing links to.
    let mut dz = zone("DropZone", ZoneKind::Room, 30.0, 30.0, 5.0, &[]);
    dz.doors.push(DoorSpec {
        x: 30.0,
        y: 27.5,
        orientation: Orientation::Horizontal,
    });
    zones.push(dz);
    let m = Map {
        name: "grid".into(),
        width: 40.0,
        height: 40.0,
        one_bot_per_corridor_zone: false,
        random_blocks: 0,
        random_sequence: 0,
        seed: None,
        sequence: Vec::new(),
        spawns: vec![[5.0, 5.0]],
        human_spawns: Vec::new(),
        epartners: Vec::new(),
        zones,
    };
    let text = goal::bw4t::map::to_toml(&m);
    let checked = goal::bw4t::map::from_toml(&text, "grid.toml").expect("grid map is valid");
    Bw4t::new(&checked, &Bw4tConfig::default())
}

fn plan(bw: &Bw4t) -> Vec<(f64, f64)> {
    bw.world().robots[0]
        .plan
        .iter()
        .map(|p| (p.x, p.y))
        .collect()
}

#[test]
fn go_to_point_plans_follow_bw4t() {
    let mut bw = grid();
    // Same zone: straight to the point.
    ok(&mut bw, "Bot1", go_to_xy(6.0, 6.0));
    assert_eq!(plan(&bw), [(6.0, 6.0)]);
    // Adjacent zone from the exact centre, point before that zone's centre: only the point.
    ok(&mut bw, "Bot1", go_to_xy(9.0, 5.0));
    assert_eq!(plan(&bw), [(9.0, 5.0)]);
    // Two hops into the room: top-middle centre, room centre, point.
    ok(&mut bw, "Bot1", go_to_xy(11.0, 11.0));
    assert_eq!(plan(&bw), [(10.0, 5.0), (10.0, 10.0), (11.0, 11.0)]);
    run_until_stopped(&mut bw, "Bot1", 500);
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
    assert_eq!(at(&bw, "Bot1"), "Z11");
    // Starting inside the room: room centre, next centre, point.
    ok(&mut bw, "Bot1", go_to_xy(6.0, 5.0));
    assert_eq!(plan(&bw), [(10.0, 10.0), (10.0, 5.0), (6.0, 5.0)]);
    run_until_stopped(&mut bw, "Bot1", 500);
    // The long way round to the bottom-left corner (the room is not a shortcut).
    ok(&mut bw, "Bot1", go_to("Z02"));
    assert_eq!(
        plan(&bw),
        [(5.0, 5.0), (5.0, 10.0), (5.0, 15.0), (5.0, 15.0)]
    );
    // A disconnected room: an error the agent sees, and no plan left.
    match bw.perform("Bot1", &go_to("DropZone")) {
        ActionResult::Failed(m) => assert!(m.contains("no route"), "{m}"),
        ActionResult::Ok => panic!("DropZone is unreachable"),
    }
    assert!(plan(&bw).is_empty());
}
