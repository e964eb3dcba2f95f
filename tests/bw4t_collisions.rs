//! Optional robot collisions: `bumped`, `navigateObstacles` and `oldTargetUnreachable`.

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::{Bw4tConfig, RobotState};
use goal::env::{ActionResult, Environment};
use goal::term::Term;

fn colliding(robots: usize) -> goal::bw4t::Bw4t {
    env(
        "tiny",
        Bw4tConfig {
            collisions: true,
            robots: Some(robots),
            ..Bw4tConfig::default()
        },
    )
}

#[test]
fn robots_pass_through_each_other_without_collisions() {
    let mut bw = default_env("tiny");
    travel(&mut bw, "Bot1", "HallC");
    assert_eq!(at(&bw, "Bot1"), "HallC");
}

#[test]
fn a_robot_in_the_way_stops_the_mover_and_navigate_obstacles_goes_around() {
    let mut bw = colliding(2);
    let mut base = Base::default();
    base.apply(&bw.percepts("Bot1"));
    ok(&mut bw, "Bot1", go_to("HallC"));
    run_until_stopped(&mut bw, "Bot1", 500);
    assert_eq!(state(&bw, "Bot1"), RobotState::Collided);
    let w = bw.world();
    assert_eq!(w.robots[0].collision, Some("bumped into a robot"));
    let x = w.robots[0].pos.x;
    assert!((12.0..=12.5).contains(&x), "stopped at x = {x}");
    // Bot2 is not frozen.
    assert_eq!(w.robots[1].state(), RobotState::Arrived);
    base.apply(&bw.percepts("Bot1"));
    assert!(base.has("bumped('Bot2')"), "{:?}", base.facts);
    assert!(base.has("state(collided)"));
    ok(&mut bw, "Bot1", Term::atom("navigateObstacles"));
    assert_eq!(state(&bw, "Bot1"), RobotState::Traveling);
    run_until_stopped(&mut bw, "Bot1", 2000);
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
    assert_eq!(at(&bw, "Bot1"), "HallC");
    let p = bw.world().robots[0].pos;
    assert_eq!((p.x, p.y), (25.0, 5.0));
    let b = bw.percepts("Bot1");
    base.apply(&b);
    assert!(has(&b, "not(bumped('Bot2'))"), "{:?}", show(&b));
    assert!(!base.has("bumped('Bot2')"));
    // navigateObstacles without an interrupted plan is refused.
    assert!(matches!(
        bw.perform("Bot1", &Term::atom("navigateObstacles")),
        ActionResult::Failed(m) if m.contains("interrupted")
    ));
}

#[test]
fn no_way_around_sets_old_target_unreachable() {
    let mut bw = colliding(3);
    ok(&mut bw, "Bot1", go_to("HallC"));
    run_until_stopped(&mut bw, "Bot1", 500);
    assert_eq!(state(&bw, "Bot1"), RobotState::Collided);
    let _ = bw.percepts("Bot1");
    // Bot3 stands on the target (HallC's centre): there is no way to it.
    let r = bw.perform("Bot1", &Term::atom("navigateObstacles"));
    assert!(
        matches!(&r, ActionResult::Failed(m) if m.contains("no way around")),
        "{r:?}"
    );
    let id = bw.world().robots[0].id;
    let b = bw.percepts("Bot1");
    assert!(
        has(&b, &format!("oldTargetUnreachable({id},1)")),
        "{:?}",
        show(&b)
    );
    // Once Bot3 has moved on, the detour exists.
    travel(&mut bw, "Bot3", "Charger");
    ok(&mut bw, "Bot1", Term::atom("navigateObstacles"));
    run_until_stopped(&mut bw, "Bot1", 2000);
    assert_eq!(state(&bw, "Bot1"), RobotState::Arrived);
    assert_eq!(at(&bw, "Bot1"), "HallC");
    let b = bw.percepts("Bot1");
    assert!(
        has(&b, &format!("oldTargetUnreachable({id},0)")),
        "{:?}",
        show(&b)
    );
}

#[test]
fn the_greedy_game_still_completes_with_collisions() {
    let m = goal::bw4t::map::builtin("banana").unwrap().unwrap();
    let bw = goal::bw4t::Bw4t::new(
        &m,
        &Bw4tConfig {
            collisions: true,
            ..Bw4tConfig::default()
        },
    );
    let handle =
        goal::env::thread::EnvHandle::spawn(Box::new(bw), goal::env::thread::Mode::LockStep);
    let report = goal::bw4t::greedy::play(&handle, "Bot1", 20_000).unwrap();
    assert!(report.finished, "{report:?}");
}
