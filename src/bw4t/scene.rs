//! What a viewer draws of the world: the map's fixed layout once, and the moving parts (robots,
//! blocks, occupied rooms, sequence progress) each tick, as JSON for the trace and the view.
//! Numbers are rounded to hundredths of a map unit so traces stay small and stable.

use super::geometry::{Pos, Rect};
use super::world::{BlockState, World};
use serde_json::{json, Map, Value};

/// A coordinate rounded to hundredths (what the view needs; keeps trace lines short).
fn round(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

fn point(p: &Pos) -> Value {
    json!([round(p.x), round(p.y)])
}

fn rect(r: &Rect) -> Value {
    json!([
        round(r.min.x),
        round(r.min.y),
        round(r.max.x),
        round(r.max.y)
    ])
}

/// The fixed layout: bounds, zones (name, kind, rectangle, doors), the drop zone and the colour
/// sequence.
pub fn layout(w: &World) -> Value {
    let zones: Vec<Value> = w
        .zones
        .iter()
        .map(|z| {
            let kind = if z.is_drop_zone {
                "dropzone"
            } else {
                match z.kind {
                    super::map::ZoneKind::Room => "room",
                    super::map::ZoneKind::Corridor => "corridor",
                    super::map::ZoneKind::Charging => "charging",
                    super::map::ZoneKind::Blockade => "blockade",
                }
            };
            json!({
                "name": z.name,
                "kind": kind,
                "rect": rect(&z.rect),
                "doors": z.doors.iter().map(rect).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "env": "bw4t",
        "name": w.map_name,
        "bounds": rect(&w.bounds),
        "zones": zones,
        "sequence": w.sequence.iter().map(|c| c.name()).collect::<Vec<_>>(),
    })
}

/// Remembers each robot's last heading, so a robot standing still keeps facing where it went.
#[derive(Clone, Debug, Default)]
pub struct Headings {
    last: Vec<(Pos, f64)>,
}

impl Headings {
    /// The heading of robot `i` at `pos` (degrees, 0 = east, 90 = south as y grows downwards):
    /// toward its next waypoint, else the direction of its last move, else east.
    fn of(&mut self, i: usize, pos: Pos, next: Option<&Pos>) -> f64 {
        if self.last.len() <= i {
            self.last.resize(i + 1, (pos, 0.0));
        }
        let (before, heading) = self.last[i];
        let toward = next.copied().filter(|n| *n != pos).or_else(|| {
            // Moved since last time: face the way it went.
            Some(pos + (pos - before)).filter(|_| before != pos)
        });
        let h = match toward {
            Some(t) => round((t.y - pos.y).atan2(t.x - pos.x).to_degrees()),
            None => heading,
        };
        self.last[i] = (pos, h);
        h
    }
}

/// The moving parts now: `robots` (`kind` `robot` or `human`, position, heading, held block
/// ids, remaining path, state, battery percent when batteries are on, the `epartner` a human
/// carries), free and held `blocks` (colour, position, holder), `occupied` rooms, the
/// `sequence_index` (colours delivered) and, when the map has any, the `epartners`.
pub fn scene(w: &World, headings: &mut Headings) -> Value {
    let mut robots = Map::new();
    for (i, r) in w.robots.iter().enumerate() {
        let mut o = Map::new();
        o.insert(
            "kind".into(),
            json!(if r.human { "human" } else { "robot" }),
        );
        o.insert("pos".into(), point(&r.pos));
        o.insert(
            "heading".into(),
            json!(headings.of(i, r.pos, r.plan.front())),
        );
        let held: Vec<i64> = r.holding.iter().map(|&b| w.blocks[b].id).collect();
        o.insert("holding".into(), json!(held));
        o.insert(
            "path".into(),
            Value::Array(r.plan.iter().map(point).collect()),
        );
        o.insert("state".into(), json!(r.state().name()));
        if r.config.battery.is_some() {
            o.insert("battery".into(), json!(round(r.battery_percent())));
        }
        if let Some(e) = r.epartner {
            o.insert("epartner".into(), json!(w.epartners[e].name));
        }
        robots.insert(r.name.clone(), Value::Object(o));
    }
    let mut blocks = Map::new();
    for b in &w.blocks {
        let holder = match b.state {
            BlockState::Free => Value::Null,
            BlockState::Held(r) => json!(w.robots[r].name),
            BlockState::Gone => continue,
        };
        blocks.insert(
            b.id.to_string(),
            json!({"color": b.color.name(), "pos": point(&b.pos), "holder": holder}),
        );
    }
    let mut occupied: Vec<&str> = w
        .zones
        .iter()
        .enumerate()
        .filter(|(z, zone)| zone.is_room() && w.occupier(*z, None).is_some())
        .map(|(_, zone)| zone.name.as_str())
        .collect();
    occupied.sort_unstable();
    let mut scene = json!({
        "robots": robots,
        "blocks": blocks,
        "occupied": occupied,
        "sequence_index": w.sequence_index,
    });
    if !w.epartners.is_empty() {
        scene["epartners"] = epartners(w);
    }
    scene
}

/// The e-partners keyed by name: `kind` `epartner`, position, holder (a robot name or null)
/// and functionalities.
fn epartners(w: &World) -> Value {
    let mut out = Map::new();
    for e in &w.epartners {
        let holder = e.holder.map(|r| w.robots[r].name.clone());
        out.insert(
            e.name.clone(),
            json!({
                "kind": "epartner",
                "pos": point(&e.pos),
                "holder": holder,
                "functionalities": e.functionalities.iter().map(|f| f.name()).collect::<Vec<_>>(),
            }),
        );
    }
    Value::Object(out)
}
