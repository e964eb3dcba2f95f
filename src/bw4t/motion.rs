//! Movement: route plans for the movement actions, the zone entry rules and the per-tick step.

use super::geometry::Pos;
use super::map::ZoneKind;
use super::world::World;

/// Distance below which a waypoint counts as reached.
pub const ARRIVAL_TOLERANCE: f64 = 0.001;
/// Step per tick at speed modifier 1 (the default modifier 0.5 gives 0.25 units per tick).
pub const MAX_STEP: f64 = 0.5;

/// Why a step was refused.
pub const HIT_WALL: &str = "hit wall";
/// A room is occupied by another robot.
pub const HIT_CLOSED_DOOR: &str = "hit closed door";
/// A corridor is occupied by another robot (with `one_bot_per_corridor_zone`).
pub const HIT_OCCUPIED_ZONE: &str = "hit occupied zone";
/// Another robot is in the way (collisions mode).
pub const BUMPED: &str = "bumped into a robot";

impl World {
    fn centres(&self, path: &[usize]) -> Vec<Pos> {
        path.iter().map(|&z| self.zones[z].centre()).collect()
    }

    /// The waypoints to walk from robot `r`'s position to `target` inside zone `tz`
    /// (`goTo(Place)` and `goToBlock`): every zone centre of the route, then the target.
    pub(crate) fn plan_to_zone(
        &self,
        r: usize,
        tz: usize,
        target: Pos,
    ) -> Result<Vec<Pos>, String> {
        let pos = self.robots[r].pos;
        let sz = self
            .nearest_zone(&pos)
            .ok_or_else(|| "the map has no zone to start from".to_string())?;
        let path = self.nav.path(sz, tz).ok_or_else(|| {
            format!(
                "no route from {} to {}",
                self.zones[sz].name, self.zones[tz].name
            )
        })?;
        let mut plan = self.centres(&path);
        plan.push(target);
        Ok(plan)
    }

    /// The waypoints for `goTo(X, Y)` (BW4T's rules, including skipping the target zone's
    /// centre when the point lies on the way).
    pub(crate) fn plan_to_point(&self, r: usize, target: Pos) -> Result<Vec<Pos>, String> {
        let pos = self.robots[r].pos;
        let (Some(sz), Some(tz)) = (self.nearest_zone(&pos), self.nearest_zone(&target)) else {
            return Err("the map has no zone to plan with".into());
        };
        if sz == tz {
            return Ok(vec![target]);
        }
        let path = self.nav.path(sz, tz).ok_or_else(|| {
            format!(
                "no route from {} to {}",
                self.zones[sz].name, self.zones[tz].name
            )
        })?;
        let start = self.zones[sz].centre();
        let mut plan = Vec::new();
        if self.zones[sz].is_room() || (start - pos).norm() >= ARRIVAL_TOLERANCE {
            plan.push(start);
        }
        plan.extend(self.centres(&path[1..path.len() - 1]));
        let tc = self.zones[tz].centre();
        let prev = if path.len() >= 2 {
            self.zones[path[path.len() - 2]].centre()
        } else {
            start
        };
        let aligned = (prev.x - tc.x).abs() <= 2.0 || (prev.y - tc.y).abs() <= 2.0;
        let room_hop = self.zones[sz].is_room() && path.len() == 2;
        let skip = !self.zones[tz].is_room()
            && !room_hop
            && aligned
            && (target - prev).norm() < (tc - prev).norm();
        if !skip {
            plan.push(tc);
        }
        plan.push(target);
        Ok(plan)
    }

    /// Checks whether robot `r` may step from `p` to `q`: entering a room needs the step to
    /// start on one of its doors and the room to be empty; entering an occupied corridor fails
    /// with `one_bot_per_corridor_zone`. Leaving a zone is always allowed.
    pub(crate) fn entry_check(&self, r: usize, p: &Pos, q: &Pos) -> Result<(), &'static str> {
        let mut worst: Option<&'static str> = None;
        for (zi, z) in self.zones.iter().enumerate() {
            if !z.rect.contains(q) || z.rect.contains(p) {
                continue;
            }
            let problem = match z.kind {
                ZoneKind::Room | ZoneKind::Blockade => {
                    if self.robots[r].config.size >= 4.0 || !z.doors.iter().any(|d| d.contains(p)) {
                        Some(HIT_WALL)
                    } else if self.occupier(zi, Some(r)).is_some() {
                        Some(HIT_CLOSED_DOOR)
                    } else {
                        None
                    }
                }
                ZoneKind::Corridor
                    if self.one_bot_per_corridor_zone && self.occupier(zi, Some(r)).is_some() =>
                {
                    Some(HIT_OCCUPIED_ZONE)
                }
                _ => None,
            };
            // "Worst result wins": a wall beats a closed door beats an occupied corridor.
            if let Some(pb) = problem {
                if worst.is_none() || pb == HIT_WALL {
                    worst = Some(pb);
                }
            }
        }
        worst.map_or(Ok(()), Err)
    }

    /// The robot that robot `r` would bump into by stepping from `p` to `q`: one whose box
    /// overlaps the box of side `size + 1` around `q`, unless the step moves away from it
    /// (so robots that start close together can always separate).
    pub(crate) fn blocking_robot(&self, r: usize, p: &Pos, q: &Pos) -> Option<usize> {
        let me = &self.robots[r];
        (0..self.robots.len()).find(|&o| {
            if o == r {
                return false;
            }
            let other = &self.robots[o];
            let lim = (me.config.size + 1.0) / 2.0 + other.config.size / 2.0;
            let d = other.pos - q;
            d.x.abs() < lim && d.y.abs() < lim && d.norm() < (other.pos - p).norm()
        })
    }

    /// Advances every robot by one tick, in entity order.
    pub(crate) fn step_robots(&mut self) {
        for r in 0..self.robots.len() {
            self.step_robot(r);
        }
    }

    fn step_robot(&mut self, r: usize) {
        let pos = self.robots[r].pos;
        if let Some(cap) = self.robots[r].config.battery {
            let charging = self
                .zones
                .iter()
                .any(|z| z.kind == ZoneKind::Charging && z.rect.contains(&pos));
            if charging {
                self.robots[r].battery = cap;
            }
        }
        let robot = &self.robots[r];
        let Some(&wp) = robot.plan.front() else {
            self.robots[r].stats.idle_ticks += 1;
            return;
        };
        if robot.collided {
            self.robots[r].stats.idle_ticks += 1;
            return;
        }
        if robot.battery_empty() {
            // As in BW4T: without power the robot "stops" at every waypoint without moving,
            // so its plan runs out and it ends up `arrived` where it stands.
            self.robots[r].plan.pop_front();
            self.robots[r].stats.idle_ticks += 1;
            return;
        }
        let d = (wp - pos).norm();
        if d < ARRIVAL_TOLERANCE {
            self.robots[r].plan.pop_front();
            return;
        }
        let step = d.min(MAX_STEP * robot.config.speed);
        let q = if step >= d {
            wp
        } else {
            pos + (wp - pos) * (step / d)
        };
        let blocker = if self.collisions {
            self.blocking_robot(r, &pos, &q)
        } else {
            None
        };
        let check = match blocker {
            Some(_) => Err(BUMPED),
            None => self.entry_check(r, &pos, &q),
        };
        match check {
            Err(why) => {
                let robot = &mut self.robots[r];
                robot.collided = true;
                robot.collision = Some(why);
                robot.obstacles = blocker.into_iter().collect();
                robot.interrupted = robot.plan.drain(..).collect();
            }
            Ok(()) => {
                let room = self.room_at(&q);
                let robot = &mut self.robots[r];
                robot.pos = q;
                robot.stats.distance += step;
                if robot.config.battery.is_some() {
                    robot.battery = (robot.battery - robot.config.discharge()).max(0.0);
                }
                if room.is_some() && room != robot.room {
                    robot.stats.rooms_entered += 1;
                }
                robot.room = room;
            }
        }
    }
}
