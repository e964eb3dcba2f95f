//! BW4T benchmark: robot-ticks per second of the bare simulation (10 robots moving, no agents,
//! no percepts), the same with every robot's percept batch each tick, and the wall time of the
//! scripted greedy single-bot game on the default map through the lock-step channel.
//! Run with `cargo bench --bench bw4t`.

use goal::bw4t::{greedy, map, Bw4t, Bw4tConfig, RobotState};
use goal::env::thread::{EnvHandle, Mode};
use goal::env::Environment;
use goal::term::Term;
use std::time::Instant;

const TARGET_ROBOT_TICKS_PER_S: f64 = 1_000_000.0;
/// BW4T's Java server runs at most ~100 ticks per second by default (10 ms per tick).
const JAVA_TICKS_PER_S: f64 = 100.0;

const ROOMS: [&str; 10] = [
    "RoomA1", "RoomA2", "RoomA3", "RoomB1", "RoomB2", "RoomB3", "RoomC1", "RoomC2", "RoomC3",
    "DropZone",
];

fn ten_robots() -> Bw4t {
    let m = map::builtin("super-random")
        .expect("built-in")
        .expect("loads");
    Bw4t::new(
        &m,
        &Bw4tConfig {
            seed: 1,
            ..Bw4tConfig::default()
        },
    )
}

/// Keeps every robot busy: a robot that stopped gets the next room as target.
fn keep_moving(bw: &mut Bw4t, next: &mut [usize]) {
    for r in 0..bw.world().robots.len() {
        if bw.world().robots[r].state() != RobotState::Traveling {
            next[r] = (next[r] + 1) % ROOMS.len();
            let name = bw.world().robots[r].name.clone();
            let goal = Term::compound("goTo", vec![Term::atom(ROOMS[(next[r] + r) % ROOMS.len()])]);
            let _ = bw.perform(&name, &goal);
        }
    }
}

fn bare(ticks: u64, with_percepts: bool) -> (f64, f64) {
    let mut bw = ten_robots();
    let robots = bw.world().robots.len();
    let names: Vec<String> = bw.entities().into_iter().map(|e| e.name).collect();
    let mut next = vec![0usize; robots];
    let mut moved = 0.0;
    let start = Instant::now();
    for _ in 0..ticks {
        keep_moving(&mut bw, &mut next);
        bw.tick();
        if with_percepts {
            for n in &names {
                std::hint::black_box(bw.percepts(n));
            }
        }
    }
    let secs = start.elapsed().as_secs_f64();
    for r in &bw.world().robots {
        moved += r.stats.distance;
    }
    ((ticks as f64 * robots as f64) / secs, moved)
}

fn main() {
    println!("BW4T benchmark (release build)\n");
    let (rate, moved) = bare(200_000, false);
    let (prate, _) = bare(20_000, true);
    let m = map::builtin(map::DEFAULT_MAP)
        .expect("built-in")
        .expect("loads");
    let mut game_times = Vec::new();
    let mut game_ticks = 0;
    for _ in 0..5 {
        let bw = Bw4t::new(
            &m,
            &Bw4tConfig {
                robots: Some(1),
                ..Bw4tConfig::default()
            },
        );
        let start = Instant::now();
        let handle = EnvHandle::spawn(Box::new(bw), Mode::LockStep);
        let report = greedy::play(&handle, "Bot1", 50_000).expect("environment runs");
        handle.stop();
        game_times.push(start.elapsed().as_secs_f64());
        assert!(report.finished, "{report:?}");
        game_ticks = report.ticks;
    }
    game_times.sort_by(f64::total_cmp);
    let game = game_times[game_times.len() / 2];
    let game_tps = game_ticks as f64 / game;
    println!("| figure | value | target | ratio |");
    println!("|---|---|---|---|");
    println!(
        "| bare simulation, 10 robots moving (robot-ticks/s) | {:.0} | {:.0} | {:.1}x |",
        rate,
        TARGET_ROBOT_TICKS_PER_S,
        rate / TARGET_ROBOT_TICKS_PER_S
    );
    println!(
        "| with all 10 percept batches per tick (robot-ticks/s) | {:.0} | {:.0} | {:.2}x |",
        prate,
        TARGET_ROBOT_TICKS_PER_S,
        prate / TARGET_ROBOT_TICKS_PER_S
    );
    println!(
        "| greedy game on {} via channel: wall time (ms, median of 5) | {:.2} | - | - |",
        map::DEFAULT_MAP,
        game * 1000.0
    );
    println!("| greedy game: ticks to finish | {} | - | - |", game_ticks);
    println!(
        "| greedy game: ticks/s vs Java's 100 ticks/s | {:.0} | {:.0} | {:.0}x |",
        game_tps,
        JAVA_TICKS_PER_S,
        game_tps / JAVA_TICKS_PER_S
    );
    println!("\n(robots travelled {moved:.0} units in the bare run)");
}
