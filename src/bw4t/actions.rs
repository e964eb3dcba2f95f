//! The robot actions of the BW4T interface: `goTo/1`, `goTo/2`, `goToBlock/1`, `pickUp/1`,
//! `putDown/0`, `sendMessage/2`, `navigateObstacles/0`, and the human-only
//! `pickUpEPartner/0`/`dropEPartner/0` (nothing happens for other robots).

use super::geometry::Pos;
use super::world::{BlockState, World, MAX_INBOX};
use crate::env::ActionResult;
use crate::term::{Sym, Term};

/// The actions robots understand, as `name/arity`.
pub const ACTIONS: &[&str] = &[
    "goTo/1",
    "goTo/2",
    "goToBlock/1",
    "pickUp/1",
    "pickUp/0",
    "putDown/0",
    "sendMessage/2",
    "navigateObstacles/0",
    "pickUpEPartner/0",
    "dropEPartner/0",
];

/// An atom or string argument as text.
pub(crate) fn name_arg(t: &Term) -> Option<&str> {
    match t {
        Term::Atom(s) => Some(s.name()),
        Term::Str(s) => Some(s),
        _ => None,
    }
}

fn number_arg(t: &Term) -> Option<f64> {
    match t {
        Term::Int(i) => Some(*i as f64),
        Term::Float(f) if f.0.is_finite() => Some(f.0),
        _ => None,
    }
}

fn id_arg(t: &Term) -> Option<i64> {
    match t {
        Term::Int(i) => Some(*i),
        Term::Float(f) if f.0.fract() == 0.0 && f.0.abs() < 1e15 => Some(f.0 as i64),
        _ => None,
    }
}

impl World {
    /// Performs `action` for robot `r` now.
    pub fn perform(&mut self, r: usize, action: &Term) -> ActionResult {
        let Some((name, arity)) = action.functor() else {
            return ActionResult::fail(format!("`{action}` is not an action"));
        };
        let args = action.args();
        match (name.name(), arity) {
            ("goTo", 1) => match name_arg(&args[0]) {
                Some(place) => self.go_to_place(r, place),
                None => {
                    ActionResult::fail(format!("goTo/1 expects a place name, got `{}`", args[0]))
                }
            },
            ("goTo", 2) => match (number_arg(&args[0]), number_arg(&args[1])) {
                (Some(x), Some(y)) => self.go_to_point(r, Pos::new(x, y)),
                _ => ActionResult::fail(format!(
                    "goTo/2 expects two numbers, got `{}` and `{}`",
                    args[0], args[1]
                )),
            },
            ("goToBlock", 1) => match id_arg(&args[0]) {
                Some(id) => self.go_to_block(r, id),
                None => {
                    ActionResult::fail(format!("goToBlock/1 expects a block id, got `{}`", args[0]))
                }
            },
            ("pickUp", 1) => match id_arg(&args[0]) {
                Some(id) => self.pick_up(r, id),
                None => {
                    ActionResult::fail(format!("pickUp/1 expects a block id, got `{}`", args[0]))
                }
            },
            ("pickUp", 0) => self.pick_up_here(r),
            ("putDown", 0) => self.put_down(r),
            ("sendMessage", 2) => match name_arg(&args[0]) {
                Some(to) => self.send_message(r, to, &args[1]),
                None => ActionResult::fail(format!(
                    "sendMessage/2 expects a player name or `all`, got `{}`",
                    args[0]
                )),
            },
            ("navigateObstacles", 0) => self.navigate_obstacles(r),
            ("pickUpEPartner", 0) => self.pick_up_epartner(r),
            ("dropEPartner", 0) => self.drop_epartner(r),
            _ => ActionResult::fail(crate::env::unknown_action(action, ACTIONS)),
        }
    }

    fn start_plan(&mut self, r: usize, plan: Result<Vec<Pos>, String>) -> ActionResult {
        let robot = &mut self.robots[r];
        robot.collided = false;
        robot.collision = None;
        robot.obstacles.clear();
        robot.interrupted.clear();
        robot.target_unreachable = false;
        robot.plan.clear();
        match plan {
            Ok(p) => {
                robot.plan.extend(p);
                ActionResult::Ok
            }
            Err(e) => ActionResult::Failed(e),
        }
    }

    fn go_to_place(&mut self, r: usize, place: &str) -> ActionResult {
        let Some(z) = self.zone_index(place) else {
            let names = self.zones.iter().map(|z| z.sym.name());
            return ActionResult::fail(match crate::env::closest(place, names) {
                Some(near) => format!("unknown place `{place}` (did you mean `{near}`?)"),
                None => format!("unknown place `{place}`"),
            });
        };
        let plan = self.plan_to_zone(r, z, self.zones[z].centre());
        self.start_plan(r, plan)
    }

    fn go_to_point(&mut self, r: usize, p: Pos) -> ActionResult {
        let b = &self.bounds;
        if !(b.min.x <= p.x && p.x <= b.max.x && b.min.y <= p.y && p.y <= b.max.y) {
            return ActionResult::fail(format!(
                "point ({}, {}) is outside the map ({}..{} x {}..{})",
                p.x, p.y, b.min.x, b.max.x, b.min.y, b.max.y
            ));
        }
        let plan = self.plan_to_point(r, p);
        self.start_plan(r, plan)
    }

    /// The block with id `id` if robot `r` can see it: free and in the robot's zone.
    fn visible_block(&self, r: usize, id: i64) -> Result<usize, ActionResult> {
        let not_visible = || ActionResult::fail(format!("block {id} is not visible from here"));
        let b = self.block_index(id).ok_or_else(not_visible)?;
        let z = self.zone_at(&self.robots[r].pos).ok_or_else(not_visible)?;
        let block = &self.blocks[b];
        if block.state == BlockState::Free && self.zones[z].rect.contains(&block.pos) {
            Ok(b)
        } else {
            Err(not_visible())
        }
    }

    fn go_to_block(&mut self, r: usize, id: i64) -> ActionResult {
        let b = match self.visible_block(r, id) {
            Ok(b) => b,
            Err(e) => return e,
        };
        let target = self.blocks[b].pos;
        let plan = match self.nearest_zone(&target) {
            Some(z) => self.plan_to_zone(r, z, target),
            None => Err(format!("block {id} is in no zone")),
        };
        self.start_plan(r, plan)
    }

    /// True when robot `r` is within reach of free block `b` and has a free gripper.
    pub fn can_pick_up(&self, r: usize, b: usize) -> bool {
        let robot = &self.robots[r];
        let block = &self.blocks[b];
        block.state == BlockState::Free
            && robot.holding.len() < robot.config.gripper_capacity
            && (block.pos - robot.pos).norm() <= robot.config.size + 1.0
    }

    fn pick_up(&mut self, r: usize, id: i64) -> ActionResult {
        let b = match self.visible_block(r, id) {
            Ok(b) => b,
            Err(e) => return e,
        };
        let robot = &self.robots[r];
        if robot.config.gripper_capacity == 0 {
            return ActionResult::fail("this robot cannot pick up blocks");
        }
        if robot.holding.len() >= robot.config.gripper_capacity {
            return ActionResult::fail(format!(
                "the gripper is full ({} blocks)",
                robot.holding.len()
            ));
        }
        let dist = (self.blocks[b].pos - robot.pos).norm();
        if dist > robot.config.size + 1.0 {
            return ActionResult::fail(format!(
                "block {id} is out of reach ({dist:.2} away, reach {})",
                robot.config.size + 1.0
            ));
        }
        self.blocks[b].state = BlockState::Held(r);
        self.robots[r].holding.push(b);
        self.robots[r].stats.blocks_picked += 1;
        ActionResult::Ok
    }

    /// `pickUp` without an argument (BW4T clients up to 3.8): the nearest block the robot is at.
    fn pick_up_here(&mut self, r: usize) -> ActionResult {
        let pos = self.robots[r].pos;
        let Some(z) = self.zone_at(&pos) else {
            return ActionResult::fail("pickUp: there is no block here (the robot is in no zone)");
        };
        let nearest = self
            .free_blocks_in(z)
            .filter(|&b| self.can_pick_up(r, b))
            .min_by(|&a, &b| {
                let (da, db) = (
                    (self.blocks[a].pos - pos).norm(),
                    (self.blocks[b].pos - pos).norm(),
                );
                da.total_cmp(&db)
                    .then(self.blocks[a].id.cmp(&self.blocks[b].id))
            });
        match nearest {
            Some(b) => self.pick_up(r, self.blocks[b].id),
            None => ActionResult::fail(
                "pickUp: no block within reach (go to a block with goToBlock first)",
            ),
        }
    }

    fn put_down(&mut self, r: usize) -> ActionResult {
        let Some(b) = self.robots[r].holding.pop() else {
            return ActionResult::fail("not holding a block");
        };
        let pos = self.robots[r].pos;
        let dz = self.drop_zone;
        if self
            .zones
            .get(dz)
            .is_some_and(|z| z.is_drop_zone && z.rect.contains(&pos))
        {
            self.blocks[b].state = BlockState::Gone;
            if self.sequence_done() {
                self.stats.dropped_after_completion += 1;
            } else if self.sequence[self.sequence_index] == self.blocks[b].color {
                self.sequence_index += 1;
                self.stats.deliveries_right += 1;
                self.robots[r].stats.deliveries_right += 1;
                if self.sequence_done() {
                    self.stats.finished_at_tick = Some(self.tick);
                }
            } else {
                self.stats.deliveries_wrong += 1;
                self.robots[r].stats.deliveries_wrong += 1;
            }
        } else if let Some(room) = self.room_at(&pos) {
            // The interface's intent: the block lands within a small tolerance of the robot.
            let rect = self.zones[room].rect;
            let dx: f64 = rand::Rng::gen_range(&mut self.rng, -0.5..0.5);
            let dy: f64 = rand::Rng::gen_range(&mut self.rng, -0.5..0.5);
            let clamp = |v: f64, lo: f64, hi: f64| {
                if hi - lo > 1.0 {
                    v.clamp(lo + 0.5, hi - 0.5)
                } else {
                    (lo + hi) / 2.0
                }
            };
            let block = &mut self.blocks[b];
            block.pos = Pos::new(
                clamp(pos.x + dx, rect.min.x, rect.max.x),
                clamp(pos.y + dy, rect.min.y, rect.max.y),
            );
            block.state = BlockState::Free;
            self.stats.dropped_in_rooms += 1;
        } else {
            self.blocks[b].state = BlockState::Gone;
            self.stats.dropped_elsewhere += 1;
        }
        ActionResult::Ok
    }

    fn send_message(&mut self, r: usize, to: &str, content: &Term) -> ActionResult {
        let sent = self.deliver_message(self.robots[r].sym, Some(r), to, content);
        if sent.is_ok() {
            self.robots[r].stats.messages_sent += 1;
        }
        sent
    }

    /// Puts `message(From, Content)` in the inbox of `to` (a robot or an e-partner by name), or
    /// of every robot other than `sender` for `all`/`allother`.
    pub(crate) fn deliver_message(
        &mut self,
        from: Sym,
        sender: Option<usize>,
        to: &str,
        content: &Term,
    ) -> ActionResult {
        let push = |inbox: &mut std::collections::VecDeque<(Sym, Term)>| {
            if inbox.len() >= MAX_INBOX {
                inbox.pop_front();
            }
            inbox.push_back((from, content.clone()));
        };
        if to == "all" || to == "allother" {
            for o in (0..self.robots.len()).filter(|&o| Some(o) != sender) {
                push(&mut self.robots[o].inbox);
            }
        } else if let Some(o) = self.robot_index(to) {
            push(&mut self.robots[o].inbox);
        } else if let Some(e) = self.epartner_index(to) {
            push(&mut self.epartners[e].inbox);
        } else {
            return ActionResult::fail(format!("unknown receiver `{to}`"));
        }
        ActionResult::Ok
    }
}
