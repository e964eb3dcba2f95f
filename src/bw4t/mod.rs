//! The Blocks World for Teams environment: maps, world, navigation, percepts and actions.
//!
//! Robots (entities `Bot1`, `Bot2`, ... in spawn order) walk between zones, pick up coloured
//! blocks in rooms and deliver them to the drop zone in the order of the map's colour sequence.
//! [`Bw4t`] implements [`crate::env::Environment`]; run it in lock-step or real time with
//! [`crate::env::thread::EnvHandle`]. Maps are TOML files ([`map`]), built in by name
//! ([`map::builtin`]) or imported from BW4T XML ([`xml::import`]). Behaviour follows the BW4T 3
//! agent-environment interface; users read docs/bw4t.md and docs/environments.md.
//!
//! Also here: [`greedy`], a scripted percept-driven player used as a smoke test and benchmark,
//! and [`messages`], the message vocabulary with speech acts and English sentences.
//!
//! Time is ticks. Within a tick, robots move in entity order: 0.25 units per tick at the
//! default speed, one idle tick at every waypoint, arrival tolerance 0.001. Actions take effect
//! between ticks (the caller decides when: see [`crate::env::thread`]).
//!
//! Robot collisions are optional (init parameter `collisions`, off by default as in BW4T):
//! a robot whose next step would bring its box (grown by 1) onto another robot's box stops,
//! `collided`, with `bumped(Name)`; `navigateObstacles` then plans a detour on the unit grid
//! ([`obstacles`]) or fails and sets `oldTargetUnreachable(Id, 1)`.
//!
//! Human-controlled robots (`Human1`, ... of type `human`, init `humans`/`humancount`) get a
//! person's requests as percepts ([`human`], through [`Environment::input`]) and can carry the
//! map's e-partners ([`epartner`], entities `EPartner1`, ... of type `epartner`).
//!
//! ## Not there yet
//! * the size-overload/speed handicaps are plain settings ([`RobotConfig`]) rather than BW4T
//!   bot-configuration files.
//!
//! ## Deliberate deviations from the Java implementation (BW4T 3.10.1), also in docs/bw4t.md
//! * Percept types follow the interface: `in`, `atBlock`, `occupied`, `holding`, `player` are
//!   on-change-with-negation and produce `not(p)` when `p` stops holding; once-percepts only in
//!   the first batch; on-change percepts re-send all instances of the predicate on any change.
//! * `message(Sender, Content)` has the interface's two arguments (Java: one list) and is an
//!   always-percept of the messages received since the last batch (drained on reading);
//!   `sendMessage(all, M)` reaches every *other* robot; content may be any term.
//! * Colours: the interface's nine plus `DarkGray` (Java: `Dark_gray`) (colour-blind view).
//! * Entities are `Bot1, Bot2, ...` (Java: `Bot_1`); asking for more robots than spawn points
//!   creates none of the extra ones (a warning), instead of killing the spawn thread.
//! * A block put down in a room lands within 0.5 of the robot (Java: anywhere in the room).
//! * Delivery needs the robot's centre in the drop zone (Java: any overlap of the robot's box).
//! * `pickUp` out of reach, with a full gripper or without grippers fails with a message (Java:
//!   silently nothing); `atBlock` only lists blocks in the robot's own zone (Java: through walls).
//! * Visibility for `pickUp`/`goToBlock` uses the current position (Java: the position at the
//!   last perceive call).
//! * `position` percepts are off by default for every robot (init parameter
//!   `positionPercepts`), and list the robot itself, every room (drop zone included), and the
//!   robots and free blocks in the robot's zone.
//! * Robots update in entity order (Java: Repast's shuffle); shortest routes with equal length
//!   are chosen by map file order; random content comes from one ChaCha generator per run, and
//!   blocks get ids in map file order (Java: `HashMap` order).
//! * The end of the game is reported ([`crate::env::Environment::is_finished`], statistics);
//!   the simulation keeps running afterwards as in Java.
//! * `zone/5` lists neighbours undirected (declared in either direction), in map file order
//!   (Java: the declared ones, in hash-set order).
//! * Actions are applied between ticks, never during one (Java: at any time on RMI threads).
//! * As in Java, a robot with an empty battery does not move and its plan runs out (`arrived`).
//! * Collisions: only the moving robot stops (Java also freezes the robot it bumped into); a
//!   step that moves away from a robot is never blocked (Java has a start-up allowance tied to
//!   integer coordinates instead); the detour grid includes charging zones and free space and is searched
//!   breadth-first with the zone entry rules (Java's grid has an inverted room margin).
//! * `goTo(X, Y)` to a point outside the map area and its zones fails (Java: accepted).
//! * `sendMessage` also accepts `allother` (GOAL's name) for `all`.
//! * `pickUp` without an argument (clients up to 3.8) picks up the nearest block within reach.
//! * BW4T 2's `navpoint/5` is sent as a copy of `zone/5` when asked for (init `navpoints`).
//! * Maps with dangling neighbour names, blocks outside rooms, overlapping spawn points or doors
//!   off their room are rejected with diagnostics (Java: ignores or crashes).

pub mod actions;
pub mod client;
pub mod color;
pub mod epartner;
pub mod geometry;
pub mod greedy;
pub mod human;
pub mod layout;
pub mod map;
pub mod messages;
pub mod motion;
pub mod nav;
pub mod obstacles;
pub mod percepts;
pub mod scene;
pub mod stats;
pub mod teams;
pub mod world;
pub mod xml;

pub use color::Color;
pub use map::Map;
pub use stats::{RobotStats, RunStats};
pub use world::{RobotConfig, RobotState, World};

use crate::diag::Diagnostic;
use crate::env::{ActionResult, EntityInfo, Environment, FromInitParams, InitParams, PerceptDecl};
use crate::term::Term;

/// How to set up a run besides the map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bw4tConfig {
    /// Seed for random content (maps without their own seed, drop placement).
    pub seed: u64,
    /// Number of robots; `None` = one per spawn point (those humans need left aside).
    pub robots: Option<usize>,
    /// Number of human-controlled robots (`Human1`, ...).
    pub humans: usize,
    /// E-partners to add besides the map's (at the humans' positions, then at spawn points).
    pub epartners: usize,
    /// Settings of every robot.
    pub robot: RobotConfig,
    /// Names of robots that are colour-blind (besides `robot.colorblind`).
    pub colorblind: Vec<String>,
    /// Overrides the map's `one_bot_per_corridor_zone`.
    pub one_bot_per_corridor_zone: Option<bool>,
    /// Send `position` percepts.
    pub position_percepts: bool,
    /// Robots block each other (`bumped`, `navigateObstacles`); off by default as in BW4T.
    pub collisions: bool,
    /// Also send BW4T 2's `navpoint/5` (a copy of each `zone/5`), for programs of that client.
    pub navpoints: bool,
    /// Team sizes, robots assigned in spawn order (init `teams`; see [`teams`]); empty: no teams.
    pub teams: Vec<usize>,
}

/// The init parameters [`Bw4t::from_params`] understands.
pub const INIT_PARAMS: &[&str] = &[
    "map",
    "seed",
    "robots",
    "humans",
    "epartners",
    "gripperCapacity",
    "colorblind",
    "battery",
    "speed",
    "size",
    "oneBotPerCorridorZone",
    "positionPercepts",
    "collisions",
    "navpoints",
    "teams",
];

/// The BW4T environment.
#[derive(Clone, Debug)]
pub struct Bw4t {
    world: World,
    positions: bool,
    navpoints: bool,
    teams: Vec<usize>,
    warnings: Vec<String>,
    headings: scene::Headings,
}

impl Bw4t {
    /// A run on `map` (already checked) with `config`.
    pub fn new(map: &Map, config: &Bw4tConfig) -> Bw4t {
        let mut world = World::new(map, config.seed);
        world.collisions = config.collisions;
        if let Some(v) = config.one_bot_per_corridor_zone {
            world.one_bot_per_corridor_zone = v;
        }
        let team_robots: usize = config.teams.iter().sum();
        // Humans beyond the map's human spawn points take ordinary ones.
        let humans_on_spawns = config.humans.saturating_sub(map.human_spawns.len());
        let wanted = match config.robots {
            Some(n) => n,
            None if team_robots > 0 => team_robots,
            None => map.spawns.len().saturating_sub(humans_on_spawns),
        };
        let mut warnings = Vec::new();
        for i in 0..wanted {
            let mut rc = config.robot.clone();
            if config
                .colorblind
                .iter()
                .any(|n| *n == format!("Bot{}", i + 1))
            {
                rc.colorblind = true;
            }
            if let Err(e) = world.spawn(rc) {
                warnings.push(format!("{e}: {} robot(s) not created", wanted - i));
                break;
            }
        }
        for i in 0..config.humans {
            if let Err(e) = world.spawn_human(config.robot.clone()) {
                warnings.push(format!(
                    "{e}: {} human-controlled robot(s) not created",
                    config.humans - i
                ));
                break;
            }
        }
        world.place_epartners(&map.epartners);
        if let Err(e) = world.add_epartners(config.epartners) {
            warnings.push(e);
        }
        world.stats.map = map.name.clone();
        world.stats.sequence_length = world.sequence.len();
        Bw4t {
            world,
            positions: config.position_percepts,
            navpoints: config.navpoints,
            teams: config.teams.clone(),
            warnings,
            headings: scene::Headings::default(),
        }
    }

    /// A run set up from init parameters (`map` = built-in name or file, `seed`, `robots`,
    /// `gripperCapacity`, `colorblind` = true/false or a list of names, `battery` = capacity,
    /// `speed`, `size`, `oneBotPerCorridorZone`, `positionPercepts`).
    pub fn from_params(params: &InitParams) -> Result<Bw4t, Vec<Diagnostic>> {
        let bad = |key: &str, want: &str, got: &Term| {
            vec![Diagnostic::error(
                "M0020",
                format!("init parameter `{key}` must be {want}, got `{got}`"),
                "init",
                0..0,
            )]
        };
        let mut cfg = Bw4tConfig::default();
        let mut map_name = map::DEFAULT_MAP.to_string();
        for (key, v) in params {
            let num = match v {
                Term::Int(i) => Some(*i as f64),
                Term::Float(f) if f.0.is_finite() => Some(f.0),
                _ => None,
            };
            let flag = match v {
                Term::Atom(s) if s.name() == "true" => Some(true),
                Term::Atom(s) if s.name() == "false" => Some(false),
                _ => None,
            };
            match key.as_str() {
                "map" => match v {
                    Term::Atom(s) => map_name = s.name().to_string(),
                    Term::Str(s) => map_name = s.to_string(),
                    _ => return Err(bad(key, "a map name or file", v)),
                },
                "seed" => match v {
                    Term::Int(i) => cfg.seed = *i as u64,
                    _ => return Err(bad(key, "an integer", v)),
                },
                "robots" => match v {
                    Term::Int(i) if (0..=1000).contains(i) => cfg.robots = Some(*i as usize),
                    _ => return Err(bad(key, "an integer 0..1000", v)),
                },
                "humans" => match v {
                    Term::Int(i) if (0..=1000).contains(i) => cfg.humans = *i as usize,
                    _ => return Err(bad(key, "an integer 0..1000", v)),
                },
                "epartners" => match v {
                    Term::Int(i) if (0..=1000).contains(i) => cfg.epartners = *i as usize,
                    _ => return Err(bad(key, "an integer 0..1000", v)),
                },
                "gripperCapacity" => match v {
                    Term::Int(i) if (0..=100).contains(i) => {
                        cfg.robot.gripper_capacity = *i as usize
                    }
                    _ => return Err(bad(key, "an integer 0..100", v)),
                },
                "colorblind" => match (flag, v.list_items()) {
                    (Some(b), _) => cfg.robot.colorblind = b,
                    (None, Some(items)) => {
                        cfg.colorblind = items
                            .iter()
                            .map(|t| t.to_text(crate::term::Style::WRITE))
                            .collect()
                    }
                    _ => return Err(bad(key, "true, false or a list of robot names", v)),
                },
                "battery" => match num {
                    Some(n) if n > 0.0 => cfg.robot.battery = Some(n),
                    _ => return Err(bad(key, "a positive number", v)),
                },
                "speed" => match num {
                    Some(n) if n > 0.0 && n <= 1.0 => cfg.robot.speed = n,
                    _ => return Err(bad(key, "a number in (0, 1]", v)),
                },
                "size" => match num {
                    Some(n) if (1.0..=5.0).contains(&n) => cfg.robot.size = n,
                    _ => return Err(bad(key, "a number in 1..5", v)),
                },
                "oneBotPerCorridorZone" => match flag {
                    Some(b) => cfg.one_bot_per_corridor_zone = Some(b),
                    None => return Err(bad(key, "true or false", v)),
                },
                "positionPercepts" => match flag {
                    Some(b) => cfg.position_percepts = b,
                    None => return Err(bad(key, "true or false", v)),
                },
                "collisions" => match flag {
                    Some(b) => cfg.collisions = b,
                    None => return Err(bad(key, "true or false", v)),
                },
                "navpoints" => match flag {
                    Some(b) => cfg.navpoints = b,
                    None => return Err(bad(key, "true or false", v)),
                },
                "teams" => match team_sizes(v) {
                    Some(sizes) => cfg.teams = sizes,
                    None => return Err(bad(key, "a list of team sizes (1..1000)", v)),
                },
                other => {
                    return Err(vec![Diagnostic::error(
                        "M0021",
                        format!("unknown init parameter `{other}`"),
                        "init",
                        0..0,
                    )
                    .with_hint(format!("known parameters: {}", INIT_PARAMS.join(", ")))])
                }
            }
        }
        let m = map::load(&map_name)?;
        Ok(Bw4t::new(&m, &cfg))
    }

    /// The simulated world (read-only).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Problems met while setting up (e.g. robots that could not be spawned).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The run statistics so far.
    pub fn run_stats(&self) -> RunStats {
        let mut s = self.world.stats.clone();
        s.ticks = self.world.tick;
        s.sequence_index = self.world.sequence_index;
        s.robots = self.world.robots.iter().map(|r| r.stats.clone()).collect();
        s.epartners = self
            .world
            .epartners
            .iter()
            .map(|e| stats::EPartnerStats {
                holder: e.holder.map(|r| self.world.robots[r].name.clone()),
                ..e.stats.clone()
            })
            .collect();
        s.teams = teams::team_stats(&self.teams, &s.robots);
        s
    }
}

/// The sizes in a `teams` parameter: a non-empty list of integers 1..1000.
fn team_sizes(v: &Term) -> Option<Vec<usize>> {
    let items = v.list_items()?;
    let sizes: Option<Vec<usize>> = items
        .iter()
        .map(|t| match t {
            Term::Int(i) if (1..=1000).contains(i) => Some(*i as usize),
            _ => None,
        })
        .collect();
    sizes.filter(|s| !s.is_empty())
}

impl Environment for Bw4t {
    fn entities(&self) -> Vec<EntityInfo> {
        let robots = self.world.robots.iter().map(|r| EntityInfo {
            name: r.name.clone(),
            kind: if r.human { "human" } else { "bot" }.into(),
        });
        let epartners = self.world.epartners.iter().map(|e| EntityInfo {
            name: e.name.clone(),
            kind: "epartner".into(),
        });
        robots.chain(epartners).collect()
    }

    fn declarations(&self) -> Vec<PerceptDecl> {
        let mut d = percepts::all_declarations();
        if self.navpoints {
            d.push(PerceptDecl::new(
                "navpoint",
                5,
                crate::env::PerceptType::Once,
            ));
        }
        d
    }

    fn perform(&mut self, entity: &str, action: &Term) -> ActionResult {
        if let Some(r) = self.world.robot_index(entity) {
            return self.world.perform(r, action);
        }
        match self.world.epartner_index(entity) {
            Some(e) => self.world.perform_epartner(e, action),
            None => ActionResult::fail(format!("unknown entity `{entity}`")),
        }
    }

    fn tick(&mut self) {
        self.world.step_robots();
        self.world.carry_epartners();
        self.world.tick += 1;
    }

    fn ticks(&self) -> u64 {
        self.world.tick
    }

    fn percepts(&mut self, entity: &str) -> Vec<Term> {
        if let Some(r) = self.world.robot_index(entity) {
            let mut batch = self.world.percept_batch(r, self.positions);
            if self.navpoints {
                percepts::add_navpoints(&mut batch);
            }
            return batch;
        }
        match self.world.epartner_index(entity) {
            Some(e) => self.world.epartner_batch(e),
            None => Vec::new(),
        }
    }

    fn is_finished(&self) -> bool {
        self.world.sequence_done()
    }

    fn stats(&self) -> serde_json::Value {
        serde_json::to_value(self.run_stats()).unwrap_or(serde_json::Value::Null)
    }

    fn layout(&self) -> Option<serde_json::Value> {
        Some(scene::layout(&self.world))
    }

    fn scene(&mut self) -> Option<serde_json::Value> {
        Some(scene::scene(&self.world, &mut self.headings))
    }

    fn input(&mut self, entity: &str, request: &Term) -> Result<(), String> {
        match self.world.robot_index(entity) {
            Some(r) => self.world.request(r, request),
            None => {
                let humans = self.world.human_names();
                Err(if humans.is_empty() {
                    format!("unknown entity `{entity}`; this run has no human-controlled robots")
                } else {
                    format!(
                        "unknown entity `{entity}`; the human-controlled robots are {}",
                        humans.join(", ")
                    )
                })
            }
        }
    }
}

impl FromInitParams for Bw4t {
    fn init_param_names() -> &'static [&'static str] {
        INIT_PARAMS
    }

    fn from_init_params(params: &InitParams) -> Result<Self, Vec<Diagnostic>> {
        Bw4t::from_params(params)
    }
}
