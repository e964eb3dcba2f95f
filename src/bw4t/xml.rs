//! Importer for BW4T XML map files (root element `<newMap>`, the JAXB schema of BW4T 3).

use super::map::{
    self, DoorSpec, EPartnerSpec, Functionality, Map, Orientation, SpanStyle, ZoneKind, ZoneSpec,
};
use crate::diag::Diagnostic;
use serde::de::IgnoredAny;
use serde::Deserialize;

#[derive(Deserialize)]
struct NewMap {
    area: Option<Xy>,
    #[serde(default)]
    entities: Vec<XEntity>,
    #[serde(rename = "oneBotPerCorridorZone", default)]
    one_bot: Option<bool>,
    #[serde(rename = "randomBlocks", default)]
    random_blocks: Option<u32>,
    #[serde(rename = "randomSequence", default)]
    random_sequence: Option<u32>,
    #[serde(default)]
    seed: Option<u64>,
    #[serde(default)]
    sequence: Vec<String>,
    #[serde(default)]
    zones: Vec<XZone>,
}

#[derive(Deserialize)]
struct Xy {
    x: f64,
    y: f64,
}

#[derive(Deserialize)]
struct XEntity {
    position: Xy,
    /// `NORMAL` (a robot spawn point, also when absent) or `EPARTNER` (an e-partner).
    #[serde(rename = "type", default)]
    kind: Option<String>,
    /// An e-partner's functionalities (`GPS`, `Forget-me-not`); both when none are listed.
    #[serde(rename = "functionality", default)]
    functionalities: Vec<String>,
}

impl XEntity {
    fn is_epartner(&self) -> bool {
        self.kind
            .as_deref()
            .is_some_and(|k| k.trim().eq_ignore_ascii_case("EPARTNER"))
    }
}

/// An `EPARTNER` entity as a map e-partner; unknown functionality names are errors.
fn epartner(e: &XEntity, file: &str, source: &str) -> Result<EPartnerSpec, Diagnostic> {
    let mut functionalities = Vec::new();
    for f in &e.functionalities {
        let squashed: String = f
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .map(|c| c.to_ascii_lowercase())
            .collect();
        match squashed.as_str() {
            "gps" => functionalities.push(Functionality::Gps),
            "forgetmenot" => functionalities.push(Functionality::ForgetMeNot),
            _ => {
                return Err(Diagnostic::error(
                    "M0012",
                    format!("an e-partner has unknown functionality `{}`", f.trim()),
                    file,
                    map::zone_span(source, "@epartners", SpanStyle::Xml),
                )
                .with_hint("the functionalities are GPS and Forget-me-not"))
            }
        }
    }
    if functionalities.is_empty() {
        functionalities = Functionality::all();
    }
    Ok(EPartnerSpec {
        x: e.position.x,
        y: e.position.y,
        functionalities,
    })
}

#[derive(Deserialize)]
struct XZone {
    #[serde(default)]
    blocks: Vec<String>,
    boundingbox: XBox,
    #[serde(default)]
    doors: Vec<XDoor>,
    name: String,
    #[serde(default)]
    neighbours: Vec<String>,
    #[serde(rename = "renderOptions", default)]
    _render: Option<IgnoredAny>,
    #[serde(rename = "type")]
    kind: String,
}

#[derive(Deserialize)]
struct XBox {
    height: f64,
    width: f64,
    x: f64,
    y: f64,
}

#[derive(Deserialize)]
struct XDoor {
    orientation: String,
    position: Xy,
}

/// Imports a BW4T XML map (`file` names it in diagnostics and gives the map its name).
pub fn import(source: &str, file: &str) -> Result<Map, Vec<Diagnostic>> {
    let raw: NewMap = quick_xml::de::from_str(source).map_err(|e| {
        let at = syntax_error_offset(source).unwrap_or(0);
        vec![
            Diagnostic::error("M0001", format!("invalid BW4T XML map: {e}"), file, at..at)
                .with_hint(
                "a BW4T map is a `<newMap>` element with `<zones>`, `<sequence>` and `<entities>`",
            ),
        ]
    })?;
    let mut errs = Vec::new();
    let mut zones = Vec::new();
    for z in raw.zones {
        let kind = match z.kind.trim() {
            "ROOM" => ZoneKind::Room,
            "CORRIDOR" => ZoneKind::Corridor,
            "CHARGINGZONE" => ZoneKind::Charging,
            "BLOCKADE" => ZoneKind::Blockade,
            other => {
                errs.push(Diagnostic::error(
                    "M0012",
                    format!("zone `{}` has unknown type `{other}`", z.name),
                    file,
                    map::zone_span(source, &z.name, SpanStyle::Xml),
                ));
                continue;
            }
        };
        let mut doors = Vec::new();
        for d in z.doors {
            let orientation = match d.orientation.trim() {
                "HORIZONTAL" => Orientation::Horizontal,
                "VERTICAL" => Orientation::Vertical,
                other => {
                    errs.push(Diagnostic::error(
                        "M0012",
                        format!(
                            "a door of zone `{}` has unknown orientation `{other}`",
                            z.name
                        ),
                        file,
                        map::zone_span(source, &z.name, SpanStyle::Xml),
                    ));
                    continue;
                }
            };
            doors.push(DoorSpec {
                x: d.position.x,
                y: d.position.y,
                orientation,
            });
        }
        zones.push(ZoneSpec {
            name: z.name,
            kind,
            x: z.boundingbox.x,
            y: z.boundingbox.y,
            width: z.boundingbox.width,
            height: z.boundingbox.height,
            neighbours: z.neighbours,
            doors,
            blocks: z.blocks.iter().map(|b| colour_name(b)).collect(),
        });
    }
    let mut epartners = Vec::new();
    for e in raw.entities.iter().filter(|e| e.is_epartner()) {
        match epartner(e, file, source) {
            Ok(spec) => epartners.push(spec),
            Err(d) => errs.push(d),
        }
    }
    let (width, height) = raw.area.map_or((0.0, 0.0), |a| (a.x, a.y));
    let name = std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("imported")
        .to_string();
    let result = Map {
        name,
        width,
        height,
        one_bot_per_corridor_zone: raw.one_bot.unwrap_or(false),
        random_blocks: raw.random_blocks.unwrap_or(0),
        random_sequence: raw.random_sequence.unwrap_or(0),
        seed: raw.seed,
        sequence: raw.sequence.iter().map(|c| colour_name(c)).collect(),
        spawns: raw
            .entities
            .iter()
            .filter(|e| !e.is_epartner())
            .map(|e| [e.position.x, e.position.y])
            .collect(),
        human_spawns: Vec::new(),
        epartners,
        zones,
    };
    errs.extend(map::check(&result, file, source, SpanStyle::Xml));
    if errs.is_empty() {
        Ok(result)
    } else {
        Err(errs)
    }
}

/// The byte offset of the first XML syntax error (the deserializer does not say where it was).
fn syntax_error_offset(source: &str) -> Option<usize> {
    let mut reader = quick_xml::Reader::from_str(source);
    loop {
        match reader.read_event() {
            Ok(quick_xml::events::Event::Eof) => return None,
            Ok(_) => {}
            Err(_) => return Some((reader.error_position() as usize).min(source.len())),
        }
    }
}

/// The project's name for a Java colour name (`DARK_GRAY` -> `DarkGray`); unknown names are kept
/// as they are so that the map check reports them.
fn colour_name(java: &str) -> String {
    super::color::Color::parse(java.trim())
        .map(|c| c.name().to_string())
        .unwrap_or_else(|| java.trim().to_string())
}
