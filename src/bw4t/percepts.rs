//! The robot percepts of the BW4T interface with the seed's types and term shapes.

use super::color::Color;
use super::world::{BlockState, World};
use crate::env::{PerceptDecl, PerceptType};
use crate::term::Term;

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
        d("color", 2, Always),
        d("message", 2, Always),
    ]
}

fn c(name: &str, args: Vec<Term>) -> Term {
    Term::compound(name, args)
}

fn colour_atom(col: Color) -> Term {
    Term::atom(col.name())
}

impl World {
    /// The full current truth of robot `r`'s percepts, grouped as [`declarations`]; once-percepts
    /// only when `first`; `position` only when `positions`. Drains the robot's inbox.
    pub(crate) fn current_percepts(
        &mut self,
        r: usize,
        first: bool,
        positions: bool,
    ) -> Vec<Vec<Term>> {
        let robot = &self.robots[r];
        let here = self.zone_at(&robot.pos);
        let mut g: Vec<Vec<Term>> = Vec::with_capacity(24);
        if first {
            g.push(
                self.zones
                    .iter()
                    .map(|z| c("place", vec![Term::Atom(z.sym)]))
                    .collect(),
            );
            g.push(
                self.zones
                    .iter()
                    .map(|z| {
                        let ctr = z.centre();
                        let nbrs = z.neighbours.iter().map(|&n| Term::Atom(self.zones[n].sym));
                        c(
                            "zone",
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
            g.push(vec![c("robot", vec![Term::Int(robot.id)])]);
            g.push(vec![c("ownName", vec![Term::Atom(robot.sym)])]);
            let seq: Vec<Term> = self.sequence.iter().map(|&col| colour_atom(col)).collect();
            g.push(vec![c("sequence", vec![Term::list(seq)])]);
            let cb = if robot.config.colorblind {
                "true"
            } else {
                "false"
            };
            g.push(vec![c("colorblind", vec![Term::atom(cb)])]);
        } else {
            g.resize(6, Vec::new());
        }
        g.push(vec![c(
            "sequenceIndex",
            vec![Term::Int(self.sequence_index as i64)],
        )]);
        let at = self
            .nearest_zone(&robot.pos)
            .map(|z| c("at", vec![Term::Atom(self.zones[z].sym)]));
        g.push(at.into_iter().collect());
        g.push(vec![c(
            "location",
            vec![Term::from(robot.pos.x), Term::from(robot.pos.y)],
        )]);
        g.push(vec![c("state", vec![Term::atom(robot.state().name())])]);
        let stack: Vec<Term> = robot
            .holding
            .iter()
            .rev()
            .map(|&b| Term::Int(self.blocks[b].id))
            .collect();
        g.push(vec![c("holdingblocks", vec![Term::list(stack)])]);
        g.push(vec![c(
            "gripperCapacity",
            vec![Term::Int(robot.config.gripper_capacity as i64)],
        )]);
        g.push(vec![c("speed", vec![Term::from(robot.config.speed)])]);
        g.push(vec![c(
            "battery",
            vec![Term::from(robot.battery_percent())],
        )]);
        g.push(
            self.robots
                .iter()
                .map(|o| {
                    let s = o.config.size.round() as i64;
                    c(
                        "robotSize",
                        vec![Term::Int(o.id), Term::Int(s), Term::Int(s)],
                    )
                })
                .collect(),
        );
        g.push(vec![c(
            "oldTargetUnreachable",
            vec![Term::Int(robot.id), Term::Int(0)],
        )]);
        let mut pos_terms = Vec::new();
        if positions {
            let pos = |id: i64, p: &super::geometry::Pos| {
                c(
                    "position",
                    vec![Term::Int(id), Term::from(p.x), Term::from(p.y)],
                )
            };
            pos_terms.push(pos(robot.id, &robot.pos));
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
            .map(|z| c("in", vec![Term::Atom(self.zones[z].sym)]));
        g.push(inside.into_iter().collect());
        let mut at_block = Vec::new();
        let mut colours = Vec::new();
        if let Some(z) = here {
            for b in self.free_blocks_in(z) {
                let block = &self.blocks[b];
                if self.can_pick_up(r, b) {
                    at_block.push(c("atBlock", vec![Term::Int(block.id)]));
                }
                let col = if robot.config.colorblind {
                    Color::DarkGray
                } else {
                    block.color
                };
                colours.push(c("color", vec![Term::Int(block.id), colour_atom(col)]));
            }
        }
        g.push(at_block);
        g.push(
            (0..self.zones.len())
                .filter(|&z| self.zones[z].is_room() && self.occupier(z, None).is_some())
                .map(|z| c("occupied", vec![Term::Atom(self.zones[z].sym)]))
                .collect(),
        );
        g.push(
            robot
                .holding
                .iter()
                .filter(|&&b| self.blocks[b].state == BlockState::Held(r))
                .map(|&b| c("holding", vec![Term::Int(self.blocks[b].id)]))
                .collect(),
        );
        g.push(
            self.robots
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != r)
                .map(|(_, o)| c("player", vec![Term::Atom(o.sym)]))
                .collect(),
        );
        g.push(colours);
        let inbox = std::mem::take(&mut self.robots[r].inbox);
        g.push(
            inbox
                .into_iter()
                .map(|(from, content)| c("message", vec![Term::Atom(from), content]))
                .collect(),
        );
        g
    }

    /// The next percept batch of robot `r` (see [`crate::env::PerceptFilter`]).
    pub fn percept_batch(&mut self, r: usize, positions: bool) -> Vec<Term> {
        let first = self.robots[r].filter.is_first();
        let groups = self.current_percepts(r, first, positions);
        self.robots[r].filter.batch_grouped(groups)
    }
}
