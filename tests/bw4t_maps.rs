//! Map loading: built-in maps (scenario 1), map errors, and the BW4T XML importer.

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::map::{self, Map, ZoneKind};
use goal::bw4t::world::BlockState;
use goal::bw4t::{xml, Bw4tConfig};
use std::path::PathBuf;

fn counts(name: &str) -> (usize, usize, Vec<(String, Vec<String>)>) {
    let bw = default_env(name);
    let w = bw.world();
    let doors = w.zones.iter().map(|z| z.doors.len()).sum();
    let per_room = w
        .zones
        .iter()
        .enumerate()
        .filter(|(_, z)| z.kind == ZoneKind::Room)
        .map(|(i, z)| {
            let cols = w
                .free_blocks_in(i)
                .map(|b| w.blocks[b].color.name().to_string())
                .collect();
            (z.name.clone(), cols)
        })
        .collect();
    (w.zones.len(), doors, per_room)
}

#[test]
fn fixed_maps_have_the_standard_layout_and_contents() {
    for (name, seq, blocks) in [
        ("banana", "Yellow,Yellow,Yellow,Yellow,Yellow,Yellow", 27),
        ("dutch-flag", "Red,Red,White,White,Blue,Blue", 23),
        ("rainbow", "Blue,Green,Yellow,Pink,Orange,Red", 22),
    ] {
        let (zones, doors, per_room) = counts(name);
        assert_eq!(zones, 28, "{name}");
        assert_eq!(doors, 10, "{name}");
        let bw = default_env(name);
        let w = bw.world();
        assert_eq!(w.blocks.len(), blocks, "{name}");
        let s: Vec<&str> = w.sequence.iter().map(|c| c.name()).collect();
        assert_eq!(s.join(","), seq, "{name}");
        assert_eq!(w.robots.len(), 3, "{name}");
        assert!(!w.one_bot_per_corridor_zone);
        let rooms = w.zones.iter().filter(|z| z.kind == ZoneKind::Room).count();
        let corridors = w
            .zones
            .iter()
            .filter(|z| z.kind == ZoneKind::Corridor)
            .count();
        assert_eq!((rooms, corridors), (10, 18), "{name}");
        if name == "banana" {
            insta::assert_json_snapshot!("banana_blocks_per_room", per_room);
        }
    }
}

#[test]
fn random_maps_fill_rooms_within_limits() {
    for (name, spawns) in [("random", 3), ("super-random", 10)] {
        for seed in [1, 2, 3] {
            let bw = env(
                name,
                Bw4tConfig {
                    seed,
                    ..Bw4tConfig::default()
                },
            );
            let w = bw.world();
            assert_eq!(w.sequence.len(), 6);
            assert_eq!(w.blocks.len(), 28);
            assert_eq!(w.robots.len(), spawns);
            let dz = w.drop_zone;
            assert_eq!(w.free_blocks_in(dz).count(), 0);
            for (i, z) in w.zones.iter().enumerate() {
                let n = w.free_blocks_in(i).count();
                assert!(n <= 10, "{name} seed {seed}: {} has {n}", z.name);
                if z.kind != ZoneKind::Room {
                    assert_eq!(n, 0);
                }
            }
            // Every sequence colour exists as a block.
            for c in &w.sequence {
                assert!(w.blocks.iter().any(|b| b.color == *c));
            }
        }
    }
    // Different run seeds give different random maps; the same seed the same map.
    let a = env(
        "random",
        Bw4tConfig {
            seed: 1,
            ..Bw4tConfig::default()
        },
    );
    let b = env(
        "random",
        Bw4tConfig {
            seed: 2,
            ..Bw4tConfig::default()
        },
    );
    let c = env(
        "random",
        Bw4tConfig {
            seed: 1,
            ..Bw4tConfig::default()
        },
    );
    let key = |bw: &goal::bw4t::Bw4t| {
        bw.world()
            .blocks
            .iter()
            .map(|b| format!("{}{:?}{:.3},{:.3}", b.id, b.color, b.pos.x, b.pos.y))
            .collect::<Vec<_>>()
    };
    assert_ne!(key(&a), key(&b));
    assert_eq!(key(&a), key(&c));
}

#[test]
fn blocks_are_placed_inside_their_rooms_apart() {
    let bw = default_env("banana");
    let w = bw.world();
    for b in &w.blocks {
        assert_eq!(b.state, BlockState::Free);
        let z = w.zone_at(&b.pos).expect("block in a zone");
        assert_eq!(w.zones[z].kind, ZoneKind::Room);
        let r = w.zones[z].rect;
        assert!(b.pos.x >= r.min.x + 0.5 && b.pos.x <= r.max.x - 0.5);
    }
}

#[test]
fn builtin_names_and_default_map() {
    let names = map::builtin_names();
    for n in ["banana", "rainbow", "dutch-flag", "random"] {
        assert!(names.contains(&n));
        assert!(map::builtin(n).unwrap().is_ok());
    }
    assert!(names.contains(&map::DEFAULT_MAP));
    assert!(map::builtin("nope").is_none());
    let err = map::load("no/such/map.toml").unwrap_err();
    assert!(err[0].message.contains("cannot read map"));
}

fn banana_toml() -> String {
    map::to_toml(&map::builtin("banana").unwrap().unwrap())
}

fn errors_of(source: &str) -> Vec<String> {
    match map::from_toml(source, "test.toml") {
        Ok(_) => Vec::new(),
        Err(ds) => ds
            .iter()
            .map(|d| format!("{} {}", d.code, d.message))
            .collect(),
    }
}

#[test]
fn map_errors_are_diagnostics_naming_the_zone() {
    let base = banana_toml();
    assert!(errors_of(&base).is_empty(), "{:?}", errors_of(&base));

    let unknown = base.replacen(
        "\"FrontRoomA1\", \"LeftHallB\"",
        "\"FrontRoomA1\", \"Nowhere\"",
        1,
    );
    let e = errors_of(&unknown);
    assert!(
        e.iter()
            .any(|m| m.contains("M0002") && m.contains("`LeftHallA`") && m.contains("`Nowhere`")),
        "{e:?}"
    );
    let d = &map::from_toml(&unknown, "test.toml").unwrap_err()[0];
    assert!(unknown[d.span.clone()].contains("LeftHallA"));

    let no_drop = base.replace("\"DropZone\"", "\"DropZone2\"");
    assert!(errors_of(&no_drop)
        .iter()
        .any(|m| m.contains("M0003") && m.contains("no drop zone")));

    let mut m: Map = map::builtin("banana").unwrap().unwrap();
    m.zones[0].blocks = vec!["Red".into()];
    let e = errors_of(&map::to_toml(&m));
    assert!(
        e.iter()
            .any(|m| m.contains("M0004") && m.contains("`LeftHallA`")),
        "{e:?}"
    );

    let mut m: Map = map::builtin("banana").unwrap().unwrap();
    m.spawns.push([25.5, 65.5]);
    let e = errors_of(&map::to_toml(&m));
    assert!(
        e.iter()
            .any(|m| m.contains("M0007") && m.contains("overlap")),
        "{e:?}"
    );

    let mut m: Map = map::builtin("banana").unwrap().unwrap();
    let room = m.zones.iter_mut().find(|z| z.name == "RoomB2").unwrap();
    room.doors[0].y = 70.0;
    let e = errors_of(&map::to_toml(&m));
    assert!(
        e.iter()
            .any(|m| m.contains("M0005") && m.contains("`RoomB2`")),
        "{e:?}"
    );

    let mut m: Map = map::builtin("banana").unwrap().unwrap();
    m.zones
        .iter_mut()
        .find(|z| z.name == "RoomC2")
        .unwrap()
        .blocks[0] = "Purple".into();
    let e = errors_of(&map::to_toml(&m));
    assert!(
        e.iter()
            .any(|m| m.contains("M0006") && m.contains("`RoomC2`") && m.contains("Purple")),
        "{e:?}"
    );

    let mut m: Map = map::builtin("banana").unwrap().unwrap();
    m.zones[3].width = -1.0;
    let e = errors_of(&map::to_toml(&m));
    assert!(
        e.iter()
            .any(|m| m.contains("M0010") && m.contains("bad numbers")),
        "{e:?}"
    );

    let e = errors_of("name = \"x\"\nwidth = \"wide\"\nheight = 3.0\n");
    assert!(e.iter().any(|m| m.contains("M0001")), "{e:?}");
}

fn shared_maps() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/bw4t-maps");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("skipped: {} is absent", dir.display());
        None
    }
}

/// A map with zones sorted by name and neighbour lists sorted, for comparing layouts.
fn normalised(mut m: Map) -> Map {
    m.name = String::new();
    // BW4T XML maps say nothing about where humans start; the built-in maps do.
    m.human_spawns.clear();
    for z in &mut m.zones {
        z.neighbours.sort();
    }
    m.zones.sort_by(|a, b| a.name.cmp(&b.name));
    m
}

#[test]
fn importer_reads_every_shared_xml_map() {
    let Some(dir) = shared_maps() else { return };
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    let mut summary = Vec::new();
    for f in &files {
        let name = f.file_name().unwrap().to_string_lossy().to_string();
        let text = std::fs::read_to_string(f).unwrap();
        match xml::import(&text, &name) {
            Ok(m) => {
                // Every imported map also runs.
                let bw = goal::bw4t::Bw4t::new(&m, &Bw4tConfig::default());
                let w = bw.world();
                summary.push(format!(
                    "{name}: ok, {} zones, {} spawns, {} blocks, sequence {}",
                    m.zones.len(),
                    m.spawns.len(),
                    w.blocks.len(),
                    w.sequence.len()
                ));
            }
            Err(ds) => {
                for d in ds {
                    let (l, c) = d.line_col(&text);
                    summary.push(format!("{name}:{l}:{c}: {} {}", d.code, d.message));
                }
            }
        }
    }
    insta::assert_json_snapshot!("xml_import_summary", summary);
    let dangling: Vec<&String> = summary
        .iter()
        .filter(|s| s.starts_with("rainbow-charging-blockade") && s.contains("M0002"))
        .collect();
    assert_eq!(dangling.len(), 2, "{summary:?}");
}

#[test]
fn imported_banana_equals_builtin_banana() {
    let Some(dir) = shared_maps() else { return };
    let text = std::fs::read_to_string(dir.join("banana.xml")).unwrap();
    let imported = xml::import(&text, "banana.xml").unwrap();
    let builtin = map::builtin("banana").unwrap().unwrap();
    assert_eq!(normalised(imported), normalised(builtin));
    for name in ["rainbow", "dutch-flag"] {
        let text = std::fs::read_to_string(dir.join(format!("{name}.xml"))).unwrap();
        let imported = xml::import(&text, "x.xml").unwrap();
        let builtin = map::builtin(name).unwrap().unwrap();
        assert_eq!(normalised(imported), normalised(builtin), "{name}");
    }
}

#[test]
fn importer_reports_broken_xml() {
    let e = xml::import("<newMap><zones><name>A</name>", "broken.xml").unwrap_err();
    assert_eq!(e[0].code, "M0001");
    let e = xml::import(
        "<newMap><area><x>10</x><y>10</y></area><zones><boundingbox><height>5</height><width>5</width><x>2.5</x><y>2.5</y></boundingbox><name>A</name><type>SWAMP</type></zones></newMap>",
        "bad.xml",
    )
    .unwrap_err();
    assert!(
        e.iter().any(|d| d.message.contains("unknown type `SWAMP`")),
        "{e:?}"
    );
}

#[test]
fn charging_zones_and_blockades_of_the_rainbow_variant() {
    let Some(dir) = shared_maps() else { return };
    let text = std::fs::read_to_string(dir.join("rainbow-charging-blockade.xml")).unwrap();
    // Repair the two dangling references (in memory) by pointing them at the blockade.
    let fixed = text.replace(
        "<neighbours>RightHallA</neighbours>",
        "<neighbours>BlockadeA</neighbours>",
    );
    let m = xml::import(&fixed, "repaired.xml").expect("repaired map imports");
    let kind = |n: &str| m.zones.iter().find(|z| z.name == n).map(|z| z.kind);
    assert_eq!(kind("LeftHallA"), Some(ZoneKind::Charging));
    assert_eq!(kind("BlockadeA"), Some(ZoneKind::Blockade));
    let cfg = Bw4tConfig {
        robots: Some(2),
        robot: goal::bw4t::RobotConfig {
            battery: Some(10.0),
            ..Default::default()
        },
        ..Bw4tConfig::default()
    };
    let mut bw = goal::bw4t::Bw4t::new(&m, &cfg);
    // The shortest route to RoomA3 runs through the blockade, which cannot be entered.
    assert_eq!(
        bw.world().route("FrontDropZone", "RoomA3").unwrap(),
        [
            "FrontDropZone",
            "RightHallD",
            "RightHallC",
            "RightHallB",
            "BlockadeA",
            "FrontRoomA3",
            "RoomA3"
        ]
    );
    ok(&mut bw, "Bot1", go_to("RoomA3"));
    run_until_stopped(&mut bw, "Bot1", 2000);
    assert_eq!(state(&bw, "Bot1"), goal::bw4t::RobotState::Collided);
    assert_eq!(bw.world().robots[0].collision, Some("hit wall"));
    assert_eq!(at(&bw, "Bot1"), "RightHallB");
    // The route to RoomA1 passes the charging zone: the battery is refilled on the way.
    travel(&mut bw, "Bot2", "RoomA1");
    let pct = bw.world().robots[1].battery_percent();
    assert!(pct > 80.0 && pct < 100.0, "{pct}");
}
