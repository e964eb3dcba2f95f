//! The robot percepts of the BW4T 3 interface, with its types and term shapes (docs/bw4t.md).

use super::color::Color;
use super::world::{BlockState, World};
use crate::env::{PerceptDecl, PerceptType};
use crate::term::{Sym, Term};
use std::sync::OnceLock;

/// The percept declarations of robot entities, in batch order.
pub fn declarations() -> Vec<PerceptDecl> {
    use PerceptType::*;
    let d = PerceptDecl::new;
    vec![
        d("place", 1, Once),
        d("zone", 5, Once),
        d("robot", 1, Once),
        d("ownName", 1, Once),
        d("sequence", 1, Once),
        d("colorblind", 1, Once),
        d("sequenceIndex", 1, OnChange),
        d("at", 1, OnChange),
        d("location", 2, OnChange),
        d("state", 1, OnChange),
        d("holdingblocks", 1, OnChange),
        d("gripperCapacity", 1, OnChange),
        d("speed", 1, OnChange),
        d("battery", 1, OnChange),
        d("robotSize", 3, OnChange),
        d("oldTargetUnreachable", 2, OnChange),
        d("position", 3, OnChange),
        d("in", 1, OnChangeWithNegation),
        d("atBlock", 1, OnChangeWithNegation),
        d("occupied", 1, OnChangeWithNegation),
        d("holding", 1, OnChangeWithNegation),
        d("player", 1, OnChangeWithNegation),
        d("bumped", 1, OnChangeWithNegation),
        d("color", 2, Always),
        d("epartner", 4, Always),
        d("message", 2, Always),
    ]
}

/// The percept declarations of a robot: human-controlled ones also get the requests.
pub fn robot_declarations(human: bool) -> Vec<PerceptDecl> {
    let mut d = declarations();
    if human {
        d.extend(super::human::declarations());
    }
    d
}

/// Every percept any BW4T entity (robot, human, e-partner) gets, each name/arity once.
pub fn all_declarations() -> Vec<PerceptDecl> {
    let mut all = robot_declarations(true);
    for d in super::epartner::declarations() {
        if !all.iter().any(|a| a.name == d.name && a.arity == d.arity) {
            all.push(d);
        }
    }
    all
}

/// Percept names and constant atoms, interned once (interning takes a lock).
struct Syms {
    place: Sym,
    zone: Sym,
    robot: Sym,
    own_name: Sym,
    sequence: Sym,
    colorblind: Sym,
    sequence_index: Sym,
    at: Sym,
    location: Sym,
    state: Sym,
    holdingblocks: Sym,
    gripper_capacity: Sym,
    speed: Sym,
    battery: Sym,
    robot_size: Sym,
    old_target_unreachable: Sym,
    position: Sym,
    in_: Sym,
    at_block: Sym,
    occupied: Sym,
    holding: Sym,
    player: Sym,
    bumped: Sym,
    color: Sym,
    message: Sym,
    true_: Sym,
    false_: Sym,
    traveling: Sym,
    arrived: Sym,
    collided: Sym,
    colours: Vec<Sym>,
}

fn syms() -> &'static Syms {
    static SYMS: OnceLock<Syms> = OnceLock::new();
    SYMS.get_or_init(|| Syms {
        place: Sym::intern("place"),
        zone: Sym::intern("zone"),
        robot: Sym::intern("robot"),
        own_name: Sym::intern("ownName"),
        sequence: Sym::intern("sequence"),
        colorblind: Sym::intern("colorblind"),
        sequence_index: Sym::intern("sequenceIndex"),
        at: Sym::intern("at"),
        location: Sym::intern("location"),
        state: Sym::intern("state"),
        holdingblocks: Sym::intern("holdingblocks"),
        gripper_capacity: Sym::intern("gripperCapacity"),
        speed: Sym::intern("speed"),
        battery: Sym::intern("battery"),
        robot_size: Sym::intern("robotSize"),
        old_target_unreachable: Sym::intern("oldTargetUnreachable"),
        position: Sym::intern("position"),
        in_: Sym::intern("in"),
        at_block: Sym::intern("atBlock"),
        occupied: Sym::intern("occupied"),
        holding: Sym::intern("holding"),
        player: Sym::intern("player"),
        bumped: Sym::intern("bumped"),
        color: Sym::intern("color"),
        message: Sym::intern("message"),
        true_: Sym::intern("true"),
        false_: Sym::intern("false"),
        traveling: Sym::intern("traveling"),
        arrived: Sym::intern("arrived"),
        collided: Sym::intern("collided"),
        colours: Color::ALL.iter().map(|c| Sym::intern(c.name())).collect(),
    })
}

fn c(name: Sym, args: Vec<Term>) -> Term {
    Term::compound(name, args)
}

fn colour_atom(col: Color) -> Term {
    let i = Color::ALL.iter().position(|c| *c == col).unwrap_or(0);
    Term::Atom(syms().colours[i])
}

/// Percepts of a robot that only change when robots are added; built once, shared by cloning
/// (cloned terms compare by pointer first, which keeps the per-tick filter cheap).
#[derive(Clone, Debug)]
pub(crate) struct FixedPercepts {
    gripper_capacity: Term,
    speed: Term,
    robot_sizes: Vec<Term>,
    players: Vec<Term>,
}

impl World {
    /// Rebuilds every robot's [`FixedPercepts`] (after robots were added).
    pub(crate) fn rebuild_percept_cache(&mut self) {
        let y = syms();
        let robot_sizes: Vec<Term> = self
            .robots
            .iter()
            .map(|o| {
                let s = o.config.size.round() as i64;
                c(
                    y.robot_size,
                    vec![Term::Int(o.id), Term::Int(s), Term::Int(s)],
                )
            })
            .collect();
        self.percept_cache = (0..self.robots.len())
            .map(|r| {
                let robot = &self.robots[r];
                FixedPercepts {
                    gripper_capacity: c(
                        y.gripper_capacity,
                        vec![Term::Int(robot.config.gripper_capacity as i64)],
                    ),
                    speed: c(y.speed, vec![Term::from(robot.config.speed)]),
                    robot_sizes: robot_sizes.clone(),
                    players: self
                        .robots
                        .iter()
                        .enumerate()
                        .filter(|(i, _)| *i != r)
                        .map(|(_, o)| c(y.player, vec![Term::Atom(o.sym)]))
                        .collect(),
                }
            })
            .collect();
    }

    /// The full current truth of robot `r`'s percepts, grouped as [`declarations`]; once-percepts
    /// only when `first`; `position` only when `positions`. Drains the robot's inbox.
    pub(crate) fn current_percepts(
        &mut self,
        r: usize,
        first: bool,
        positions: bool,
    ) -> Vec<Vec<Term>> {
        let y = syms();
        let robot = &self.robots[r];
        let here = self.zone_at(&robot.pos);
        let mut g: Vec<Vec<Term>> = Vec::with_capacity(24);
        if first {
            g.push(
                self.zones
                    .iter()
                    .map(|z| c(y.place, vec![Term::Atom(z.sym)]))
                    .collect(),
            );
            g.push(
                self.zones
                    .iter()
                    .map(|z| {
                        let ctr = z.centre();
                        let nbrs = z.neighbours.iter().map(|&n| Term::Atom(self.zones[n].sym));
                        c(
                            y.zone,
                            vec![
                                Term::Int(z.id),
                                Term::Atom(z.sym),
                                Term::from(ctr.x),
                                Term::from(ctr.y),
                                Term::list(nbrs.collect::<Vec<_>>()),
                            ],
                        )
                    })
                    .collect(),
            );
            g.push(vec![c(y.robot, vec![Term::Int(robot.id)])]);
            g.push(vec![c(y.own_name, vec![Term::Atom(robot.sym)])]);
            let seq: Vec<Term> = self.sequence.iter().map(|&col| colour_atom(col)).collect();
            g.push(vec![c(y.sequence, vec![Term::list(seq)])]);
            let cb = if robot.config.colorblind {
                y.true_
            } else {
                y.false_
            };
            g.push(vec![c(y.colorblind, vec![Term::Atom(cb)])]);
        } else {
            g.resize(6, Vec::new());
        }
        g.push(vec![c(
            y.sequence_index,
            vec![Term::Int(self.sequence_index as i64)],
        )]);
        let at = self
            .nearest_zone(&robot.pos)
            .map(|z| c(y.at, vec![Term::Atom(self.zones[z].sym)]));
        g.push(at.into_iter().collect());
        g.push(vec![c(
            y.location,
            vec![Term::from(robot.pos.x), Term::from(robot.pos.y)],
        )]);
        g.push(vec![c(
            y.state,
            vec![Term::Atom(match robot.state() {
                super::world::RobotState::Traveling => y.traveling,
                super::world::RobotState::Arrived => y.arrived,
                super::world::RobotState::Collided => y.collided,
            })],
        )]);
        let stack: Vec<Term> = robot
            .holding
            .iter()
            .rev()
            .map(|&b| Term::Int(self.blocks[b].id))
            .collect();
        g.push(vec![c(y.holdingblocks, vec![Term::list(stack)])]);
        let fixed = &self.percept_cache[r];
        g.push(vec![fixed.gripper_capacity.clone()]);
        g.push(vec![fixed.speed.clone()]);
        g.push(vec![c(
            y.battery,
            vec![Term::from(robot.battery_percent())],
        )]);
        g.push(fixed.robot_sizes.clone());
        g.push(vec![c(
            y.old_target_unreachable,
            vec![
                Term::Int(robot.id),
                Term::Int(robot.target_unreachable as i64),
            ],
        )]);
        let mut pos_terms = Vec::new();
        if positions {
            let pos = |id: i64, p: &super::geometry::Pos| {
                c(
                    y.position,
                    vec![Term::Int(id), Term::from(p.x), Term::from(p.y)],
                )
            };
            pos_terms.push(pos(robot.id, &robot.pos));
            for z in self
                .zones
                .iter()
                .filter(|z| z.kind == super::map::ZoneKind::Room)
            {
                pos_terms.push(pos(z.id, &z.centre()));
            }
            if let Some(z) = here {
                let rect = self.zones[z].rect;
                for (i, o) in self.robots.iter().enumerate() {
                    if i != r && rect.contains(&o.pos) {
                        pos_terms.push(pos(o.id, &o.pos));
                    }
                }
                for b in self.free_blocks_in(z) {
                    pos_terms.push(pos(self.blocks[b].id, &self.blocks[b].pos));
                }
            }
        }
        g.push(pos_terms);
        let inside = self
            .room_at(&robot.pos)
            .map(|z| c(y.in_, vec![Term::Atom(self.zones[z].sym)]));
        g.push(inside.into_iter().collect());
        let mut at_block = Vec::new();
        let mut colours = Vec::new();
        if let Some(z) = here {
            for b in self.free_blocks_in(z) {
                let block = &self.blocks[b];
                if self.can_pick_up(r, b) {
                    at_block.push(c(y.at_block, vec![Term::Int(block.id)]));
                }
                let col = if robot.config.colorblind {
                    Color::DarkGray
                } else {
                    block.color
                };
                colours.push(c(y.color, vec![Term::Int(block.id), colour_atom(col)]));
            }
        }
        g.push(at_block);
        g.push(
            (0..self.zones.len())
                .filter(|&z| self.zones[z].is_room() && self.occupier(z, None).is_some())
                .map(|z| c(y.occupied, vec![Term::Atom(self.zones[z].sym)]))
                .collect(),
        );
        g.push(
            robot
                .holding
                .iter()
                .filter(|&&b| self.blocks[b].state == BlockState::Held(r))
                .map(|&b| c(y.holding, vec![Term::Int(self.blocks[b].id)]))
                .collect(),
        );
        g.push(fixed.players.clone());
        g.push(if robot.collided {
            robot
                .obstacles
                .iter()
                .map(|&o| c(y.bumped, vec![Term::Atom(self.robots[o].sym)]))
                .collect()
        } else {
            Vec::new()
        });
        g.push(colours);
        g.push(self.visible_epartners(r));
        let inbox = std::mem::take(&mut self.robots[r].inbox);
        g.push(
            inbox
                .into_iter()
                .map(|(from, content)| c(y.message, vec![Term::Atom(from), content]))
                .collect(),
        );
        g
    }

    /// The next percept batch of robot `r` (see [`crate::env::PerceptFilter`]).
    pub fn percept_batch(&mut self, r: usize, positions: bool) -> Vec<Term> {
        let first = self.robots[r].filter.is_first();
        let mut groups = self.current_percepts(r, first, positions);
        if self.robots[r].human {
            groups.extend(self.request_groups(r));
        }
        self.robots[r].filter.batch_grouped(groups)
    }
}

/// Adds BW4T 2's `navpoint(Id, Name, X, Y, Neighbours)` for every `zone/5` of a batch (the
/// BW4T 3 client renamed the percept; its arguments stayed the same).
pub(crate) fn add_navpoints(batch: &mut Vec<Term>) {
    let zone = syms().zone;
    let navpoint = Sym::intern("navpoint");
    let copies: Vec<Term> = batch
        .iter()
        .filter(|t| t.is_functor(zone, 5))
        .map(|t| Term::compound(navpoint, t.args().to_vec()))
        .collect();
    batch.extend(copies);
}
