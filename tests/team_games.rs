//! Full BW4T games played by the reference team in `agents/bw4t/`.

mod team_support;

use team_support::play;

#[test]
fn dev_play() {
    let file = std::env::var("TEAM_FILE").unwrap_or("team.goal".into());
    let map = std::env::var("TEAM_MAP").unwrap_or("banana".into());
    let robots: usize = std::env::var("TEAM_ROBOTS").ok().and_then(|s| s.parse().ok()).unwrap_or(1);
    let max: u64 = std::env::var("TEAM_MAX").ok().and_then(|s| s.parse().ok()).unwrap_or(8000);
    let t = std::time::Instant::now();
    let seed: u64 = std::env::var("TEAM_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(1);
    let g = play(&file, &map, robots, seed, max);
    eprintln!("{} {:?}", serde_json::to_string(&g).unwrap(), t.elapsed());
}

#[test]
fn dev_solo() {
    let Ok(path) = std::env::var("TEAM_SOLO") else { return };
    let src = std::fs::read_to_string(&path).unwrap();
    let prog = match goal::agent::Program::from_source(&path, &src) {
        Ok(p) => p,
        Err(d) => panic!("{:?}", d),
    };
    let mut a = goal::agent::Agent::new(prog, "solo", goal::agent::AgentConfig::default());
    for _ in 0..12 {
        let out = a.step(&[], &[]);
        for e in &out.events { eprintln!("{e:?}"); }
        for l in &out.printed { eprintln!("PRINT {l}"); }
    }
}
