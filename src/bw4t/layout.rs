//! Layout checks of a map that would otherwise only show as a game that never ends: rooms that
//! overlap each other or the drop zone, rooms without a door, rooms the game needs that no robot
//! can reach from a spawn point, and spawn points outside the map. Each diagnostic names the zone it is about.

use super::map::{Map, ZoneKind, ZoneSpec, DROP_ZONE};
use crate::diag::Diagnostic;
use std::collections::VecDeque;

/// True when the two zone rectangles share an area (touching edges do not count).
fn overlap(a: &ZoneSpec, b: &ZoneSpec) -> bool {
    const EPS: f64 = 1e-9;
    (a.x - b.x).abs() * 2.0 < a.width + b.width - EPS
        && (a.y - b.y).abs() * 2.0 < a.height + b.height - EPS
}

fn contains(z: &ZoneSpec, p: [f64; 2]) -> bool {
    (p[0] - z.x).abs() * 2.0 <= z.width && (p[1] - z.y).abs() * 2.0 <= z.height
}

/// The layout problems of `map`; `err(code, zone, message, hint)` builds a diagnostic.
pub(crate) fn check(
    map: &Map,
    err: &dyn Fn(&str, Option<&str>, String) -> Diagnostic,
) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let rooms: Vec<&ZoneSpec> = map
        .zones
        .iter()
        .filter(|z| z.kind == ZoneKind::Room)
        .collect();
    for (i, a) in rooms.iter().enumerate() {
        for b in rooms.iter().skip(i + 1) {
            if overlap(a, b) {
                let what = if b.name == DROP_ZONE {
                    format!("room `{}` overlaps the drop zone", a.name)
                } else if a.name == DROP_ZONE {
                    format!("room `{}` overlaps the drop zone", b.name)
                } else {
                    format!("rooms `{}` and `{}` overlap", a.name, b.name)
                };
                out.push(
                    err("M0013", Some(&b.name), what)
                        .with_hint("move or shrink one of them; rooms may touch but not overlap"),
                );
            }
        }
        if a.doors.is_empty() {
            let what = if a.name == DROP_ZONE {
                "the drop zone has no door; no block can be delivered".to_string()
            } else {
                format!("room `{}` has no door; no robot can enter it", a.name)
            };
            out.push(
                err("M0014", Some(&a.name), what)
                    .with_hint("add a door on its wall, or make it a blockade"),
            );
        }
    }
    for (i, s) in map.spawns.iter().chain(&map.human_spawns).enumerate() {
        let (label, key, n) = match i.checked_sub(map.spawns.len()) {
            Some(h) => ("human spawn point", "@human_spawns", h),
            None => ("spawn point", "@spawns", i),
        };
        let inside = s[0] >= 0.0 && s[1] >= 0.0 && s[0] <= map.width && s[1] <= map.height;
        if s.iter().all(|v| v.is_finite()) && !inside {
            out.push(
                err(
                    "M0015",
                    Some(key),
                    format!(
                        "{label} {} ({}, {}) is outside the map ({} x {})",
                        n + 1,
                        s[0],
                        s[1],
                        map.width,
                        map.height
                    ),
                )
                .with_hint("spawn points must lie in a corridor of the map"),
            );
        }
    }
    out.extend(unreachable(map, err));
    out
}

/// Rooms the game needs (the drop zone of a non-empty sequence, rooms with blocks or that may
/// get random blocks) that no path of neighbours leads to from any spawn point's zone
/// (breadth-first, so large maps cost time linear in their links). An empty room nobody can
/// reach does no harm.
fn unreachable(
    map: &Map,
    err: &dyn Fn(&str, Option<&str>, String) -> Diagnostic,
) -> Vec<Diagnostic> {
    let index = |name: &str| map.zones.iter().position(|z| z.name == name);
    let mut links: Vec<Vec<usize>> = vec![Vec::new(); map.zones.len()];
    for (i, z) in map.zones.iter().enumerate() {
        for j in z.neighbours.iter().filter_map(|n| index(n)) {
            links[i].push(j);
            links[j].push(i);
        }
    }
    let mut seen = vec![false; map.zones.len()];
    let mut queue: VecDeque<usize> = VecDeque::new();
    for s in &map.spawns {
        if let Some(i) = map.zones.iter().position(|z| contains(z, *s)) {
            if !seen[i] {
                seen[i] = true;
                queue.push_back(i);
            }
        }
    }
    if queue.is_empty() {
        // No spawn point in a zone: nothing to measure reachability from.
        return Vec::new();
    }
    while let Some(i) = queue.pop_front() {
        for &j in &links[i] {
            // Robots walk through corridors and charging zones, and into rooms, not through them.
            if !seen[j] {
                seen[j] = true;
                if map.zones[j].kind != ZoneKind::Room {
                    queue.push_back(j);
                }
            }
        }
    }
    let random = map.random_blocks + map.random_sequence > 0;
    let needed = |z: &ZoneSpec| {
        if z.name == DROP_ZONE {
            !map.sequence.is_empty() || map.random_sequence > 0
        } else {
            !z.blocks.is_empty() || random
        }
    };
    map.zones
        .iter()
        .zip(&seen)
        .filter(|(z, s)| z.kind == ZoneKind::Room && !**s && needed(z))
        .map(|(z, _)| {
            err(
                "M0016",
                Some(&z.name),
                format!("room `{}` cannot be reached from any spawn point", z.name),
            )
            .with_hint("link it (`neighbours`) to a corridor the robots can walk to")
        })
        .collect()
}
