//! The simulated world: zones, doors, blocks, robots, the drop zone's sequence, built from a map.

use super::color::Color;
use super::geometry::{Pos, Rect};
use super::map::{Map, ZoneKind, DROP_ZONE, MAX_RANDOM_BLOCKS_PER_ROOM};
use super::nav::Nav;
use super::stats::{RobotStats, RunStats};
use crate::env::PerceptFilter;
use crate::term::{Sym, Term};
use rand::Rng;
use rand_chacha::rand_core::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;
use std::collections::VecDeque;

/// Default robot size (side of its square box).
pub const ROBOT_SIZE: f64 = 2.0;
/// Default speed modifier: a step is `0.5 * speed` units per tick.
pub const DEFAULT_SPEED: f64 = 0.5;
/// Messages kept per robot before the oldest are dropped (when nobody perceives them).
pub const MAX_INBOX: usize = 1000;

/// A zone at run time.
#[derive(Clone, Debug)]
pub struct Zone {
    /// Object id (shared counter with doors, blocks and robots).
    pub id: i64,
    pub name: String,
    pub sym: Sym,
    pub kind: ZoneKind,
    /// True for the room named `DropZone`.
    pub is_drop_zone: bool,
    pub rect: Rect,
    pub doors: Vec<Rect>,
    /// Neighbours (undirected), in file order.
    pub neighbours: Vec<usize>,
}

impl Zone {
    /// The zone's centre.
    pub fn centre(&self) -> Pos {
        self.rect.centre()
    }

    /// True for rooms (including the drop zone) and blockades.
    pub fn is_room(&self) -> bool {
        self.kind.is_room()
    }
}

/// Where a block is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BlockState {
    /// Lying in the world (in a room).
    Free,
    /// In a robot's gripper (robot index).
    Held(usize),
    /// Delivered or destroyed.
    Gone,
}

/// A block.
#[derive(Clone, Debug)]
pub struct Block {
    pub id: i64,
    pub color: Color,
    pub pos: Pos,
    pub state: BlockState,
}

/// Per-robot settings (the BW4T bot configuration).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RobotConfig {
    /// Side of the robot's square box; size >= 4 cannot enter rooms.
    pub size: f64,
    /// Speed modifier in (0, 1]: the step per tick is `0.5 * speed`.
    pub speed: f64,
    /// Blocks the gripper holds at once (0 = cannot pick up).
    pub gripper_capacity: usize,
    pub colorblind: bool,
    /// Battery capacity; `None` = no battery (never runs out).
    pub battery: Option<f64>,
    /// BW4T's speed slider value (10..100) used by the discharge formula.
    pub bot_speed: f64,
}

impl Default for RobotConfig {
    fn default() -> Self {
        RobotConfig {
            size: ROBOT_SIZE,
            speed: DEFAULT_SPEED,
            gripper_capacity: 1,
            colorblind: false,
            battery: None,
            bot_speed: 50.0,
        }
    }
}

impl RobotConfig {
    /// Battery used per movement step: `0.0002 * size + 0.0004 * bot_speed` (BW4T's formula).
    pub fn discharge(&self) -> f64 {
        0.0002 * self.size + 0.0004 * self.bot_speed
    }
}

/// The movement state reported by the `state` percept.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum RobotState {
    Traveling,
    Arrived,
    Collided,
}

impl RobotState {
    /// The percept atom: `traveling`, `arrived` or `collided`.
    pub fn name(self) -> &'static str {
        match self {
            RobotState::Traveling => "traveling",
            RobotState::Arrived => "arrived",
            RobotState::Collided => "collided",
        }
    }
}

/// A robot.
#[derive(Clone, Debug)]
pub struct Robot {
    pub id: i64,
    /// Entity name, `Bot1`, `Bot2`, ... (`Human1`, ... for human-controlled robots)
    pub name: String,
    /// Controlled by a person (a HumanBot, entity type `human`): gets the person's requests as
    /// percepts and can carry an e-partner.
    pub human: bool,
    /// The e-partner it carries (index into [`World::epartners`]).
    pub epartner: Option<usize>,
    pub sym: Sym,
    pub pos: Pos,
    pub config: RobotConfig,
    /// Held block indices; the last one is the top of the stack.
    pub holding: Vec<usize>,
    /// Remaining waypoints; the front is the current one.
    pub plan: VecDeque<Pos>,
    pub collided: bool,
    /// Why the last step failed (hit wall, closed door, occupied zone, bumped into a robot).
    pub collision: Option<&'static str>,
    /// Robots this robot bumped into (collisions mode), while collided.
    pub obstacles: Vec<usize>,
    /// The plan that was interrupted by the last collision (for `navigateObstacles`).
    pub interrupted: Vec<Pos>,
    /// Set when `navigateObstacles` found no way to the interrupted plan's target.
    pub target_unreachable: bool,
    /// Current battery level (meaningful only with a battery).
    pub battery: f64,
    pub stats: RobotStats,
    pub(crate) inbox: VecDeque<(Sym, Term)>,
    /// A person's requests not yet perceived (humans only), oldest first.
    pub(crate) requests: VecDeque<Term>,
    pub(crate) filter: PerceptFilter,
    pub(crate) room: Option<usize>,
}

impl Robot {
    /// The `state` percept value.
    pub fn state(&self) -> RobotState {
        if self.collided {
            RobotState::Collided
        } else if self.plan.is_empty() {
            RobotState::Arrived
        } else {
            RobotState::Traveling
        }
    }

    /// Battery level in percent (100 without a battery).
    pub fn battery_percent(&self) -> f64 {
        match self.config.battery {
            Some(cap) if cap > 0.0 => self.battery * 100.0 / cap,
            _ => 100.0,
        }
    }

    /// True when the battery is empty (never without a battery).
    pub fn battery_empty(&self) -> bool {
        self.config.battery.is_some() && self.battery <= 0.0
    }
}

/// The whole simulated state.
#[derive(Clone, Debug)]
pub struct World {
    pub map_name: String,
    pub zones: Vec<Zone>,
    pub blocks: Vec<Block>,
    pub robots: Vec<Robot>,
    /// E-partners (entities of type `epartner`), in id order.
    pub epartners: Vec<super::epartner::EPartner>,
    pub drop_zone: usize,
    pub sequence: Vec<Color>,
    pub sequence_index: usize,
    pub one_bot_per_corridor_zone: bool,
    /// Robots block each other (BW4T's optional collisions; off by default).
    pub collisions: bool,
    /// The map area together with every zone: movement targets must lie inside.
    pub bounds: Rect,
    pub tick: u64,
    pub stats: RunStats,
    /// Spawn points not used yet.
    pub(crate) spawns: VecDeque<Pos>,
    /// Spawn points for humans not used yet (used before `spawns`).
    pub(crate) human_spawns: VecDeque<Pos>,
    pub(crate) next_id: i64,
    pub(crate) rng: ChaCha8Rng,
    pub(crate) nav: Nav,
    pub(crate) percept_cache: Vec<super::percepts::FixedPercepts>,
}

impl World {
    /// Builds the world of a checked `map`; random content comes from the map's seed, else `seed`.
    pub fn new(map: &Map, seed: u64) -> World {
        let mut rng = ChaCha8Rng::seed_from_u64(map.seed.unwrap_or(seed));
        let index_of = |name: &str| map.zones.iter().position(|z| z.name == name);
        let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); map.zones.len()];
        for (i, z) in map.zones.iter().enumerate() {
            for n in z.neighbours.iter().filter_map(|n| index_of(n)) {
                if n != i {
                    neighbours[i].push(n);
                    neighbours[n].push(i);
                }
            }
        }
        for n in &mut neighbours {
            n.sort_unstable();
            n.dedup();
        }
        // Object ids follow BW4T's creation order: corridors, rooms (each followed by its
        // doors), blockades, charging zones, then blocks and robots.
        let mut ids = vec![0i64; map.zones.len()];
        let mut next_id = 0i64;
        for kind in [
            ZoneKind::Corridor,
            ZoneKind::Room,
            ZoneKind::Blockade,
            ZoneKind::Charging,
        ] {
            for (i, z) in map.zones.iter().enumerate().filter(|(_, z)| z.kind == kind) {
                ids[i] = next_id;
                next_id += 1 + z.doors.len() as i64;
            }
        }
        let zones: Vec<Zone> = map
            .zones
            .iter()
            .enumerate()
            .map(|(i, z)| Zone {
                id: ids[i],
                name: z.name.clone(),
                sym: Sym::intern(&z.name),
                kind: z.kind,
                is_drop_zone: z.kind == ZoneKind::Room && z.name == DROP_ZONE,
                rect: Rect::centred(z.x, z.y, z.width, z.height),
                doors: z
                    .doors
                    .iter()
                    .map(|d| {
                        let (w, h) = d.size();
                        Rect::centred(d.x, d.y, w, h)
                    })
                    .collect(),
                neighbours: std::mem::take(&mut neighbours[i]),
            })
            .collect();
        let drop_zone = zones.iter().position(|z| z.is_drop_zone).unwrap_or(0);
        let mut bounds = Rect {
            min: Pos::new(0.0, 0.0),
            max: Pos::new(map.width.max(0.0), map.height.max(0.0)),
        };
        for z in &zones {
            bounds.min = bounds.min.inf(&z.rect.min);
            bounds.max = bounds.max.sup(&z.rect.max);
        }
        let mut sequence: Vec<Color> = map
            .sequence
            .iter()
            .filter_map(|c| Color::parse(c))
            .collect();
        let mut extras = Vec::new();
        for _ in 0..map.random_sequence {
            let c = Color::RANDOM[rng.gen_range(0..Color::RANDOM.len())];
            sequence.push(c);
            extras.push(c);
        }
        for _ in 0..map.random_blocks {
            extras.push(Color::RANDOM[rng.gen_range(0..Color::RANDOM.len())]);
        }
        let rooms: Vec<usize> = (0..zones.len())
            .filter(|&i| zones[i].kind == ZoneKind::Room && !zones[i].is_drop_zone)
            .collect();
        let mut contents: Vec<Vec<Color>> = map
            .zones
            .iter()
            .map(|z| z.blocks.iter().filter_map(|c| Color::parse(c)).collect())
            .collect();
        for c in extras {
            let open: Vec<usize> = rooms
                .iter()
                .copied()
                .filter(|&r| contents[r].len() < MAX_RANDOM_BLOCKS_PER_ROOM)
                .collect();
            // The map check guarantees room; fall back to any room rather than loop forever.
            let pool = if open.is_empty() { &rooms } else { &open };
            if pool.is_empty() {
                break;
            }
            let r = pool[rng.gen_range(0..pool.len())];
            contents[r].push(c);
        }
        let mut world = World {
            map_name: map.name.clone(),
            zones,
            blocks: Vec::new(),
            robots: Vec::new(),
            epartners: Vec::new(),
            drop_zone,
            sequence,
            sequence_index: 0,
            one_bot_per_corridor_zone: map.one_bot_per_corridor_zone,
            collisions: false,
            bounds,
            tick: 0,
            stats: RunStats::default(),
            spawns: map.spawns.iter().map(|s| Pos::new(s[0], s[1])).collect(),
            human_spawns: map
                .human_spawns
                .iter()
                .map(|s| Pos::new(s[0], s[1]))
                .collect(),
            next_id,
            rng,
            nav: Nav::default(),
            percept_cache: Vec::new(),
        };
        world.nav = Nav::new(&world.zones);
        for &r in &rooms {
            for &c in &contents[r] {
                let pos = world.free_spot(r);
                world.blocks.push(Block {
                    id: world.next_id,
                    color: c,
                    pos,
                    state: BlockState::Free,
                });
                world.next_id += 1;
            }
        }
        world
    }

    /// Adds a robot at the next spawn point; `Err` when the map has no spawn point left.
    pub fn spawn(&mut self, config: RobotConfig) -> Result<usize, String> {
        self.spawn_player(config, false)
    }

    /// Adds a human-controlled robot (`Human1`, ...) at the next human spawn point, else at the
    /// next spawn point; `Err` when there is none left.
    pub fn spawn_human(&mut self, config: RobotConfig) -> Result<usize, String> {
        self.spawn_player(config, true)
    }

    fn spawn_player(&mut self, config: RobotConfig, human: bool) -> Result<usize, String> {
        let (prefix, kind) = if human {
            ("Human", "human-controlled robot")
        } else {
            ("Bot", "robot")
        };
        let number = self.robots.iter().filter(|r| r.human == human).count() + 1;
        let from_human = if human {
            self.human_spawns.pop_front()
        } else {
            None
        };
        let pos = from_human
            .or_else(|| self.spawns.pop_front())
            .ok_or_else(|| {
                format!(
                    "map `{}` has no spawn point left for {kind} number {number}",
                    self.map_name
                )
            })?;
        let name = format!("{prefix}{number}");
        let idx = self.robots.len();
        let room = self.zone_at(&pos).filter(|&z| self.zones[z].is_room());
        let decls = super::percepts::robot_declarations(human);
        self.robots.push(Robot {
            id: self.next_id,
            sym: Sym::intern(&name),
            stats: RobotStats {
                human,
                ..RobotStats::new(&name)
            },
            name,
            human,
            epartner: None,
            pos,
            battery: config.battery.unwrap_or(0.0),
            config,
            holding: Vec::new(),
            plan: VecDeque::new(),
            collided: false,
            collision: None,
            obstacles: Vec::new(),
            interrupted: Vec::new(),
            target_unreachable: false,
            inbox: VecDeque::new(),
            requests: VecDeque::new(),
            filter: PerceptFilter::new(&decls),
            room,
        });
        self.next_id += 1;
        self.rebuild_percept_cache();
        Ok(idx)
    }

    /// A random free spot for a block in zone `z` (BW4T's rule: centres at least 2 apart in x or
    /// y from the zone's other free blocks; after 100 tries any spot).
    pub(crate) fn free_spot(&mut self, z: usize) -> Pos {
        let rect = self.zones[z].rect;
        let mut best = rect.centre();
        for attempt in 0..=100 {
            let p = self.random_point_in(&rect);
            best = p;
            if attempt == 100 {
                break;
            }
            let clear = self.blocks.iter().all(|b| {
                b.state != BlockState::Free
                    || !rect.contains(&b.pos)
                    || (b.pos.x - p.x).abs() >= 2.0
                    || (b.pos.y - p.y).abs() >= 2.0
            });
            if clear {
                break;
            }
        }
        best
    }

    /// A uniform block centre inside `rect` (at least 0.5 from its edges when it is wide enough).
    fn random_point_in(&mut self, rect: &Rect) -> Pos {
        let axis = |rng: &mut ChaCha8Rng, lo: f64, hi: f64| {
            if hi - lo > 1.0 {
                rng.gen_range(lo + 0.5..hi - 0.5)
            } else {
                (lo + hi) / 2.0
            }
        };
        let x = axis(&mut self.rng, rect.min.x, rect.max.x);
        let y = axis(&mut self.rng, rect.min.y, rect.max.y);
        Pos::new(x, y)
    }

    /// The index of the robot named `name`.
    pub fn robot_index(&self, name: &str) -> Option<usize> {
        self.robots.iter().position(|r| r.name == name)
    }

    /// The index of the zone named `name`.
    pub fn zone_index(&self, name: &str) -> Option<usize> {
        self.zones.iter().position(|z| z.name == name)
    }

    /// The index of the block with object id `id`.
    pub fn block_index(&self, id: i64) -> Option<usize> {
        self.blocks.iter().position(|b| b.id == id)
    }

    /// The first zone (file order) containing `p`.
    pub fn zone_at(&self, p: &Pos) -> Option<usize> {
        self.zones.iter().position(|z| z.rect.contains(p))
    }

    /// The zone containing `p`, else the nearest non-room zone by centre distance.
    pub fn nearest_zone(&self, p: &Pos) -> Option<usize> {
        self.zone_at(p).or_else(|| {
            let mut best: Option<(usize, f64)> = None;
            for (i, z) in self.zones.iter().enumerate() {
                if z.is_room() {
                    continue;
                }
                let d = (z.centre() - p).norm();
                if best.is_none_or(|(_, bd)| d < bd) {
                    best = Some((i, d));
                }
            }
            best.map(|(i, _)| i)
        })
    }

    /// The room (rooms, drop zone, blockades) containing `p`.
    pub fn room_at(&self, p: &Pos) -> Option<usize> {
        self.zones
            .iter()
            .position(|z| z.is_room() && z.rect.contains(p))
    }

    /// The robot whose centre is inside zone `z`, other than robot `except`.
    pub fn occupier(&self, z: usize, except: Option<usize>) -> Option<usize> {
        let rect = &self.zones[z].rect;
        (0..self.robots.len()).find(|&r| Some(r) != except && rect.contains(&self.robots[r].pos))
    }

    /// The shortest route (zone names, both ends included) between two zones by name.
    pub fn route(&self, from: &str, to: &str) -> Option<Vec<String>> {
        let path = self
            .nav
            .path(self.zone_index(from)?, self.zone_index(to)?)?;
        Some(path.iter().map(|&z| self.zones[z].name.clone()).collect())
    }

    /// True when the whole sequence has been delivered.
    pub fn sequence_done(&self) -> bool {
        self.sequence_index >= self.sequence.len()
    }

    /// Blocks lying free whose centre is inside zone `z`, in id order.
    pub fn free_blocks_in(&self, z: usize) -> impl Iterator<Item = usize> + '_ {
        let rect = self.zones[z].rect;
        (0..self.blocks.len()).filter(move |&b| {
            self.blocks[b].state == BlockState::Free && rect.contains(&self.blocks[b].pos)
        })
    }
}
