//! BW4T maps in the project's own TOML format: the model, built-in maps, loading and checks.
//!
//! A map is an area, spawn points (used in order), a colour sequence, optional random content and
//! a list of zones. A zone is a rectangle given by its centre and size, of kind `room`,
//! `corridor`, `charging` or `blockade`; the room named `DropZone` is the drop zone. Rooms have
//! doors (4x1 horizontal or 1x4 vertical, centred on `x`, `y`) and blocks (colour names).
//! Neighbour links are listed per zone and used undirected for path planning.

use super::color::Color;
use crate::diag::{Diagnostic, Span};
use serde::{Deserialize, Serialize};

/// Name of the map used when none is given.
pub const DEFAULT_MAP: &str = "banana";

/// Name of the room that is the drop zone.
pub const DROP_ZONE: &str = "DropZone";

/// Rooms never receive more random blocks than this (BW4T's limit).
pub const MAX_RANDOM_BLOCKS_PER_ROOM: usize = 10;

/// Longest colour sequence a map may ask for (agents hold the sequence as one list term).
pub const MAX_SEQUENCE: usize = 1000;

const BUILTIN: &[(&str, &str)] = &[
    ("banana", include_str!("../../maps/banana.toml")),
    ("rainbow", include_str!("../../maps/rainbow.toml")),
    ("dutch-flag", include_str!("../../maps/dutch-flag.toml")),
    ("random", include_str!("../../maps/random.toml")),
    ("super-random", include_str!("../../maps/super-random.toml")),
    ("tiny", include_str!("../../maps/tiny.toml")),
];

/// A BW4T map.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Map {
    pub name: String,
    pub width: f64,
    pub height: f64,
    #[serde(default)]
    pub one_bot_per_corridor_zone: bool,
    /// Extra random blocks placed in rooms (not in the sequence).
    #[serde(default)]
    pub random_blocks: u32,
    /// Random colours appended to the sequence, each also placed as a block in a room.
    #[serde(default)]
    pub random_sequence: u32,
    /// Seed for the map's random content; the run seed is used when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Colour names, in delivery order.
    #[serde(default)]
    pub sequence: Vec<String>,
    /// Robot spawn points `[x, y]`, used in order.
    #[serde(default)]
    pub spawns: Vec<[f64; 2]>,
    /// Spawn points of human-controlled robots (`Human1`, ...), used in order before the
    /// robots' spawn points left over.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub human_spawns: Vec<[f64; 2]>,
    /// E-partners lying on the map at the start.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub epartners: Vec<EPartnerSpec>,
    #[serde(default)]
    pub zones: Vec<ZoneSpec>,
}

/// An e-partner of a map: where it lies at the start and what it can do.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EPartnerSpec {
    pub x: f64,
    pub y: f64,
    /// Its functionalities; both when absent.
    #[serde(default = "Functionality::all")]
    pub functionalities: Vec<Functionality>,
}

/// What an e-partner can do (the BW4T 3 interface's two functionalities).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Functionality {
    /// Helps its holder navigate: knows the rooms and the zone it is in.
    #[serde(rename = "GPS")]
    Gps,
    /// Makes sure its holder does not forget it: knows who holds it and when it is left behind.
    #[serde(rename = "Forget-me-not")]
    ForgetMeNot,
}

impl Functionality {
    /// Both functionalities.
    pub fn all() -> Vec<Functionality> {
        vec![Functionality::Gps, Functionality::ForgetMeNot]
    }

    /// The name used in maps and percepts: `GPS`, `Forget-me-not`.
    pub fn name(self) -> &'static str {
        match self {
            Functionality::Gps => "GPS",
            Functionality::ForgetMeNot => "Forget-me-not",
        }
    }
}

/// The kind of a zone.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ZoneKind {
    /// Entered only through a door, by one robot at a time (the drop zone is a room too).
    Room,
    /// Free to walk (one robot at a time with `one_bot_per_corridor_zone`).
    Corridor,
    /// Free to walk; refills batteries.
    Charging,
    /// A room without doors: never enterable.
    Blockade,
}

impl ZoneKind {
    /// True for kinds with the room entry rule (rooms and blockades).
    pub fn is_room(self) -> bool {
        matches!(self, ZoneKind::Room | ZoneKind::Blockade)
    }
}

/// One zone of a map.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZoneSpec {
    pub name: String,
    pub kind: ZoneKind,
    /// Centre x.
    pub x: f64,
    /// Centre y (y grows downwards).
    pub y: f64,
    pub width: f64,
    pub height: f64,
    #[serde(default)]
    pub neighbours: Vec<String>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub doors: Vec<DoorSpec>,
    /// Colour names of the blocks initially in this room.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blocks: Vec<String>,
}

/// A door on a room wall.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoorSpec {
    pub x: f64,
    pub y: f64,
    pub orientation: Orientation,
}

/// Door orientation: horizontal doors are 4 wide and 1 high, vertical ones 1 wide and 4 high.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Orientation {
    Horizontal,
    Vertical,
}

impl DoorSpec {
    /// Width and height of the door rectangle.
    pub fn size(&self) -> (f64, f64) {
        match self.orientation {
            Orientation::Horizontal => (4.0, 1.0),
            Orientation::Vertical => (1.0, 4.0),
        }
    }
}

/// The names of the built-in maps.
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

/// The TOML text of the built-in map `name`.
pub fn builtin_source(name: &str) -> Option<&'static str> {
    BUILTIN.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// The built-in map `name` (`None` if there is no such map).
pub fn builtin(name: &str) -> Option<Result<Map, Vec<Diagnostic>>> {
    let (n, src) = BUILTIN.iter().find(|(n, _)| *n == name)?;
    Some(from_toml(src, &format!("maps/{n}.toml")))
}

/// Loads a map by built-in name or from a file (`.xml` files are imported as BW4T XML maps).
pub fn load(name_or_path: &str) -> Result<Map, Vec<Diagnostic>> {
    if let Some(m) = builtin(name_or_path) {
        return m;
    }
    let text = std::fs::read_to_string(name_or_path).map_err(|e| {
        vec![Diagnostic::error(
            "M0000",
            format!("cannot read map `{name_or_path}`: {e}"),
            name_or_path,
            0..0,
        )
        .with_hint(
            match crate::suggest::closest(name_or_path, builtin_names()) {
                Some(m) => format!("did you mean the built-in map `{m}`?"),
                None => format!("built-in maps: {}", builtin_names().join(", ")),
            },
        )]
    })?;
    if name_or_path.to_ascii_lowercase().ends_with(".xml") {
        super::xml::import(&text, name_or_path)
    } else {
        from_toml(&text, name_or_path)
    }
}

/// Parses and checks a TOML map.
pub fn from_toml(source: &str, file: &str) -> Result<Map, Vec<Diagnostic>> {
    let map: Map = toml::from_str(source).map_err(|e| {
        let span = e.span().unwrap_or(0..0);
        vec![Diagnostic::error(
            "M0001",
            format!("invalid map: {}", e.message()),
            file,
            span,
        )]
    })?;
    let errors = check(&map, file, source, SpanStyle::Toml);
    if errors.is_empty() {
        Ok(map)
    } else {
        Err(errors)
    }
}

/// Prints a map as TOML.
pub fn to_toml(map: &Map) -> String {
    toml::to_string(map).unwrap_or_default()
}

/// How to find a zone's text in the source for diagnostics.
#[derive(Clone, Copy)]
pub(crate) enum SpanStyle {
    Toml,
    Xml,
}

/// The span of the zone named `name` in `source` (empty span at 0 when not found); `@key`
/// names a top-level entry instead (`@sequence`, `@spawns`).
pub(crate) fn zone_span(source: &str, name: &str, style: SpanStyle) -> Span {
    if let Some(key) = name.strip_prefix('@') {
        let needle = match (style, key) {
            (SpanStyle::Toml, "epartners") => "[[epartners]]".to_string(),
            (SpanStyle::Toml, k) => format!("{k} ="),
            (SpanStyle::Xml, "spawns") => "<entities>".to_string(),
            (SpanStyle::Xml, "epartners") => "<type>EPARTNER</type>".to_string(),
            (SpanStyle::Xml, k) => format!("<{k}>"),
        };
        return source
            .find(needle.as_str())
            .map_or(0..0, |i| i..i + needle.len());
    }
    let needles = match style {
        SpanStyle::Toml => vec![
            format!("name = \"{name}\""),
            format!("name = '{name}'"),
            format!("\"{name}\""),
        ],
        SpanStyle::Xml => vec![format!("<name>{name}</name>")],
    };
    needles
        .iter()
        .find_map(|n| source.find(n.as_str()).map(|i| i..i + n.len()))
        .unwrap_or(0..0)
}

fn finite_pos(v: f64) -> bool {
    v.is_finite() && v > 0.0
}

/// Checks a map's consistency; every error names the zone it is about.
pub(crate) fn check(map: &Map, file: &str, source: &str, style: SpanStyle) -> Vec<Diagnostic> {
    let mut errs = Vec::new();
    let err = |code: &str, zone: Option<&str>, msg: String| {
        let span = zone.map_or(0..0, |z| zone_span(source, z, style));
        Diagnostic::error(code, msg, file, span)
    };
    if !finite_pos(map.width) || !finite_pos(map.height) {
        errs.push(err(
            "M0010",
            None,
            format!("bad map size {} x {}", map.width, map.height),
        ));
    }
    let mut seen: Vec<&str> = Vec::new();
    for z in &map.zones {
        if seen.contains(&z.name.as_str()) {
            errs.push(err(
                "M0011",
                Some(&z.name),
                format!("zone `{}` is defined twice", z.name),
            ));
        }
        seen.push(&z.name);
        let nums = [z.x, z.y, z.width, z.height];
        if nums.iter().any(|v| !v.is_finite()) || !finite_pos(z.width) || !finite_pos(z.height) {
            errs.push(err(
                "M0010",
                Some(&z.name),
                format!(
                    "zone `{}` has bad numbers: centre ({}, {}), size {} x {}",
                    z.name, z.x, z.y, z.width, z.height
                ),
            ));
        }
        for n in &z.neighbours {
            if !map.zones.iter().any(|o| &o.name == n) {
                errs.push(
                    err(
                        "M0002",
                        Some(&z.name),
                        format!("zone `{}` names an unknown neighbour `{n}`", z.name),
                    )
                    .with_hint("remove the neighbour or define a zone with that name"),
                );
            }
        }
        for c in &z.blocks {
            if Color::parse(c).is_none() {
                errs.push(err(
                    "M0006",
                    Some(&z.name),
                    format!("zone `{}` has a block of unknown colour `{c}`", z.name),
                ));
            }
        }
        if !z.blocks.is_empty() && (z.kind != ZoneKind::Room || z.name == DROP_ZONE) {
            errs.push(
                err(
                    "M0004",
                    Some(&z.name),
                    format!(
                        "zone `{}` is not a blocks room but lists blocks ({})",
                        z.name,
                        z.blocks.join(", ")
                    ),
                )
                .with_hint("blocks can only be placed in rooms other than the drop zone"),
            );
        }
        if !z.doors.is_empty() && z.kind != ZoneKind::Room {
            errs.push(err(
                "M0005",
                Some(&z.name),
                format!("zone `{}` is not a room but has doors", z.name),
            ));
        }
        for d in &z.doors {
            let inside = d.x.is_finite()
                && d.y.is_finite()
                && d.x >= z.x - z.width / 2.0 - 0.5
                && d.x <= z.x + z.width / 2.0 + 0.5
                && d.y >= z.y - z.height / 2.0 - 0.5
                && d.y <= z.y + z.height / 2.0 + 0.5;
            if !inside {
                errs.push(
                    err(
                        "M0005",
                        Some(&z.name),
                        format!(
                            "door at ({}, {}) is outside its room `{}`",
                            d.x, d.y, z.name
                        ),
                    )
                    .with_hint("put the door centre on the room's wall"),
                );
            }
        }
    }
    if map.sequence.len() + map.random_sequence as usize > MAX_SEQUENCE {
        errs.push(
            err(
                "M0017",
                Some("@sequence"),
                format!(
                    "the sequence has {} colours; at most {MAX_SEQUENCE} are allowed",
                    map.sequence.len() + map.random_sequence as usize
                ),
            )
            .with_hint("a game delivers one block per colour; shorten the sequence"),
        );
        return errs;
    }
    for c in &map.sequence {
        if Color::parse(c).is_none() {
            errs.push(err(
                "M0006",
                Some("@sequence"),
                format!("the sequence has an unknown colour `{c}`"),
            ));
        }
    }
    let drops = map
        .zones
        .iter()
        .filter(|z| z.name == DROP_ZONE && z.kind == ZoneKind::Room)
        .count();
    if drops == 0 {
        errs.push(
            err(
                "M0003",
                None,
                format!("the map has no drop zone (a room named `{DROP_ZONE}`)"),
            )
            .with_hint("add a room named DropZone with a door"),
        );
    }
    errs.extend(check_spawns(map, &err));
    errs.extend(check_epartners(map, &err));
    errs.extend(super::layout::check(map, &err));
    let rooms = map
        .zones
        .iter()
        .filter(|z| z.kind == ZoneKind::Room && z.name != DROP_ZONE)
        .count();
    let random = map.random_blocks as usize + map.random_sequence as usize;
    if random > 0 && rooms == 0 {
        errs.push(err(
            "M0009",
            None,
            "the map asks for random blocks but has no blocks room".into(),
        ));
    } else if random > rooms * MAX_RANDOM_BLOCKS_PER_ROOM {
        errs.push(err(
            "M0009",
            None,
            format!(
                "{random} random blocks do not fit in {rooms} rooms of at most {MAX_RANDOM_BLOCKS_PER_ROOM}"
            ),
        ));
    }
    errs
}

/// Every spawn point (robots' first, then humans'), named as diagnostics say it.
fn spawn_points(map: &Map) -> Vec<(String, [f64; 2])> {
    let robots = map
        .spawns
        .iter()
        .enumerate()
        .map(|(i, s)| (format!("spawn point {}", i + 1), *s));
    let humans = map
        .human_spawns
        .iter()
        .enumerate()
        .map(|(i, s)| (format!("human spawn point {}", i + 1), *s));
    robots.chain(humans).collect()
}

/// Spawn points must be numbers, apart from each other and outside rooms.
fn check_spawns(
    map: &Map,
    err: &dyn Fn(&str, Option<&str>, String) -> Diagnostic,
) -> Vec<Diagnostic> {
    let mut errs = Vec::new();
    let points = spawn_points(map);
    for (i, (label, s)) in points.iter().enumerate() {
        let key = if label.starts_with("human") {
            "@human_spawns"
        } else {
            "@spawns"
        };
        if s.iter().any(|v| !v.is_finite()) {
            errs.push(err("M0010", Some(key), format!("{label} has bad numbers")));
            continue;
        }
        for (other, o) in points.iter().take(i) {
            if (s[0] - o[0]).abs() < 2.0 && (s[1] - o[1]).abs() < 2.0 {
                errs.push(err(
                    "M0007",
                    Some(key),
                    format!(
                        "{other} ({}, {}) and {label} ({}, {}) overlap (robots are 2 x 2)",
                        o[0], o[1], s[0], s[1]
                    ),
                ));
            }
        }
        if let Some(z) = map.zones.iter().find(|z| {
            z.kind.is_room()
                && (s[0] - z.x).abs() * 2.0 < z.width
                && (s[1] - z.y).abs() * 2.0 < z.height
        }) {
            errs.push(err(
                "M0008",
                Some(&z.name),
                format!("{label} ({}, {}) is inside room `{}`", s[0], s[1], z.name),
            ));
        }
    }
    errs
}

/// E-partners must lie inside the map, each with at least one functionality, listed once.
fn check_epartners(
    map: &Map,
    err: &dyn Fn(&str, Option<&str>, String) -> Diagnostic,
) -> Vec<Diagnostic> {
    let mut errs = Vec::new();
    for (i, e) in map.epartners.iter().enumerate() {
        let inside = e.x.is_finite()
            && e.y.is_finite()
            && (0.0..=map.width).contains(&e.x)
            && (0.0..=map.height).contains(&e.y);
        if !inside {
            errs.push(err(
                "M0010",
                Some("@epartners"),
                format!(
                    "e-partner {} at ({}, {}) is outside the map ({} x {})",
                    i + 1,
                    e.x,
                    e.y,
                    map.width,
                    map.height
                ),
            ));
        }
        let mut f = e.functionalities.clone();
        f.sort();
        f.dedup();
        if f.is_empty() || f.len() != e.functionalities.len() {
            errs.push(
                err(
                    "M0010",
                    Some("@epartners"),
                    format!(
                        "e-partner {} must list each functionality at most once, and at least one",
                        i + 1
                    ),
                )
                .with_hint("functionalities = [\"GPS\", \"Forget-me-not\"]"),
            );
        }
    }
    errs
}
