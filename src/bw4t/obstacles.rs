//! `navigateObstacles`: after a collision, a detour on the unit grid around the robots in the
//! way to the target of the interrupted plan (BW4T's idea, without its grid quirks).
//!
//! Grid points are the integer points of the map outside rooms (corridors, charging zones, free
//! space), plus those of the robot's own zone and the target's zone, away from other robots' boxes; steps between neighbouring points must pass
//! the zone entry rules (so walls and occupied rooms are respected). A breadth-first search gives
//! the shortest detour; ties go to the first neighbour in a fixed order (deterministic).

use super::geometry::Pos;
use super::world::World;
use crate::env::ActionResult;
use std::collections::VecDeque;

/// Largest grid searched (points); larger maps refuse the action rather than stall.
const MAX_GRID_POINTS: i64 = 400_000;

impl World {
    fn grid_usable(&self, r: usize, p: &Pos, here: Option<usize>, there: Option<usize>) -> bool {
        let zone_ok = match self.zone_at(p) {
            None => true,
            Some(z) => !self.zones[z].is_room() || Some(z) == here || Some(z) == there,
        };
        let me = self.robots[r].config.size;
        zone_ok
            && self.robots.iter().enumerate().all(|(o, other)| {
                let lim = (me + 1.0) / 2.0 + other.config.size / 2.0 + 0.5;
                let d = other.pos - p;
                o == r || d.x.abs() >= lim || d.y.abs() >= lim
            })
    }

    /// True when robot `r` may walk the straight unit segment `a -> b` (in half steps, as the
    /// door rule needs a step that starts on the door band).
    fn grid_step_ok(&self, r: usize, a: &Pos, b: &Pos) -> bool {
        let mid = nalgebra::center(a, b);
        self.entry_check(r, a, &mid).is_ok() && self.entry_check(r, &mid, b).is_ok()
    }

    /// Plans a detour for robot `r` to the target of its interrupted plan.
    pub(crate) fn navigate_obstacles(&mut self, r: usize) -> ActionResult {
        let Some(&goal) = self.robots[r].interrupted.last() else {
            return ActionResult::fail(
                "navigateObstacles needs a goTo that was interrupted by a collision",
            );
        };
        let start = self.robots[r].pos;
        let here = self.zone_at(&start);
        let there = self.nearest_zone(&goal);
        let b = self.bounds;
        let (x0, y0) = (b.min.x.floor() as i64, b.min.y.floor() as i64);
        let (w, h) = (
            b.max.x.ceil() as i64 - x0 + 1,
            b.max.y.ceil() as i64 - y0 + 1,
        );
        if w <= 0 || h <= 0 || w.saturating_mul(h) > MAX_GRID_POINTS {
            return ActionResult::fail("the map is too large for navigateObstacles");
        }
        let n = (w * h) as usize;
        let index = |x: i64, y: i64| -> Option<usize> {
            ((x0..x0 + w).contains(&x) && (y0..y0 + h).contains(&y))
                .then(|| ((y - y0) * w + (x - x0)) as usize)
        };
        let point = |i: usize| {
            let i = i as i64;
            Pos::new((x0 + i % w) as f64, (y0 + i / w) as f64)
        };
        let corners = |p: &Pos| {
            let (fx, fy) = (p.x.floor() as i64, p.y.floor() as i64);
            [(fx, fy), (fx + 1, fy), (fx, fy + 1), (fx + 1, fy + 1)]
        };
        // Sources: usable grid corners around the robot that it can step to directly.
        const NONE: u32 = u32::MAX;
        let mut prev = vec![NONE; n];
        let mut queue = VecDeque::new();
        for (x, y) in corners(&start) {
            let Some(i) = index(x, y) else { continue };
            let p = point(i);
            if prev[i] == NONE
                && self.grid_usable(r, &p, here, there)
                && self.grid_step_ok(r, &start, &p)
            {
                prev[i] = i as u32;
                queue.push_back(i);
            }
        }
        // Targets: usable grid corners around the goal that step to it directly.
        let targets: Vec<usize> = corners(&goal)
            .into_iter()
            .filter_map(|(x, y)| index(x, y))
            .filter(|&i| {
                let p = point(i);
                self.grid_usable(r, &p, here, there) && self.grid_step_ok(r, &p, &goal)
            })
            .collect();
        let mut found = None;
        while let Some(i) = queue.pop_front() {
            if targets.contains(&i) {
                found = Some(i);
                break;
            }
            let p = point(i);
            let (x, y) = (p.x as i64, p.y as i64);
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                let Some(j) = index(x + dx, y + dy) else {
                    continue;
                };
                if prev[j] != NONE {
                    continue;
                }
                let q = point(j);
                if self.grid_usable(r, &q, here, there) && self.grid_step_ok(r, &p, &q) {
                    prev[j] = i as u32;
                    queue.push_back(j);
                }
            }
        }
        let Some(end) = found else {
            self.robots[r].target_unreachable = true;
            return ActionResult::fail(format!(
                "no way around the obstacles to ({}, {})",
                goal.x, goal.y
            ));
        };
        let mut path = vec![goal];
        let mut i = end;
        loop {
            path.push(point(i));
            let p = prev[i] as usize;
            if p == i {
                break;
            }
            i = p;
        }
        path.reverse();
        let robot = &mut self.robots[r];
        robot.plan = path.into();
        robot.collided = false;
        robot.collision = None;
        robot.obstacles.clear();
        robot.interrupted.clear();
        robot.target_unreachable = false;
        ActionResult::Ok
    }
}
