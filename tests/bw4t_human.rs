//! Human-controlled robots (HumanBots, entity type `human`) and e-partners (type `epartner`):
//! a person's requests arrive as the HumanBot's request percepts exactly as the BW4T 3 interface
//! types them, e-partner percepts with their interface types and functionalities,
//! `pickUpEPartner`/`dropEPartner` (nothing happens for agent-controlled robots), and the
//! e-partner's messages to its holder.

mod bw4t_support;

use bw4t_support::*;
use goal::bw4t::map::{self, Functionality};
use goal::bw4t::{epartner, human, Bw4t, Bw4tConfig};
use goal::env::{ActionResult, Environment, PerceptType};
use goal::syntax::prolog::Reader;
use goal::term::Term;

fn t(text: &str) -> Term {
    Reader::new("t").term(text, 0).expect("term").term
}

/// Banana with one agent robot, one HumanBot and one e-partner (lying where Human1 starts).
fn game() -> Bw4t {
    env(
        "banana",
        Bw4tConfig {
            robots: Some(1),
            humans: 1,
            epartners: 1,
            ..Bw4tConfig::default()
        },
    )
}

/// Asks for `request` for `Human1` and returns the next batch of Human1 (after a tick).
fn requested(bw: &mut Bw4t, request: &str) -> Vec<Term> {
    bw.input("Human1", &t(request))
        .unwrap_or_else(|e| panic!("{request} refused: {e}"));
    bw.tick();
    bw.percepts("Human1")
}

/// A map (TOML) with the tiny layout and the given e-partner entries.
fn tiny_with(epartners: &str) -> Bw4t {
    let source = format!(
        "{}\n{epartners}",
        map::builtin_source("tiny").expect("tiny map")
    );
    let m = map::from_toml(&source, "tiny-e.toml").expect("map loads");
    Bw4t::new(
        &m,
        &Bw4tConfig {
            robots: Some(1),
            humans: 1,
            ..Bw4tConfig::default()
        },
    )
}

#[test]
fn entities_are_typed_bot_human_and_epartner_as_in_the_interface() {
    let bw = env(
        "banana",
        Bw4tConfig {
            robots: Some(2),
            humans: 1,
            epartners: 1,
            ..Bw4tConfig::default()
        },
    );
    let entities: Vec<(String, String)> = bw
        .entities()
        .into_iter()
        .map(|e| (e.name, e.kind))
        .collect();
    let expect = [
        ("Bot1", "bot"),
        ("Bot2", "bot"),
        ("Human1", "human"),
        ("EPartner1", "epartner"),
    ];
    let expect: Vec<(String, String)> = expect
        .iter()
        .map(|(n, k)| (n.to_string(), k.to_string()))
        .collect();
    assert_eq!(entities, expect);
    // Human1 starts on the map's first human spawn point, the e-partner where Human1 is.
    let w = bw.world();
    let h = &w.robots[w.robot_index("Human1").unwrap()];
    assert_eq!((h.pos.x, h.pos.y), (25.0, 61.0));
    assert_eq!(w.epartners[0].pos, h.pos);
    assert!(bw.warnings().is_empty(), "{:?}", bw.warnings());
}

#[test]
fn request_percepts_have_the_interface_names_and_are_sent_each_time_the_person_asks() {
    // "Sent every time when user selects the action" / "Sent always": each request is an
    // always-percept of the requests made since the last batch.
    let decls = human::declarations();
    let declared: Vec<String> = decls
        .iter()
        .map(|d| format!("{}/{}", d.name, d.arity))
        .collect();
    for seed_request in [
        "sendMessage/2",
        "goToBlock/1",
        "goTo/1",
        "goTo/2",
        "pickUp/1",
        "putDown/0",
        "getEPartners/0",
    ] {
        assert!(declared.iter().any(|d| d == seed_request), "{seed_request}");
    }
    assert!(decls.iter().all(|d| d.kind == PerceptType::Always));

    let mut bw = game();
    bw.percepts("Human1");
    bw.percepts("Bot1");
    for request in [
        "goTo('RoomC1')",
        "goTo(25.0, 40.0)",
        "getEPartners",
        "sendMessage(all, imp(in('Human1', 'RoomC1')))",
        "sendMessage('Bot1', at('Yellow', 'RoomC1'))",
    ] {
        let batch = requested(&mut bw, request);
        let expected = t(request).to_string();
        assert_eq!(
            batch.iter().filter(|p| p.to_string() == expected).count(),
            1,
            "{request} in {:?}",
            show(&batch)
        );
        // Once only: the next batch no longer has it, and agent robots never get requests.
        bw.tick();
        assert!(!has(&bw.percepts("Human1"), &expected));
        assert!(!has(&bw.percepts("Bot1"), &expected));
    }
    // Two requests between two batches both arrive, in one batch.
    bw.input("Human1", &t("goTo('RoomA1')")).unwrap();
    bw.input("Human1", &t("goTo('RoomA2')")).unwrap();
    bw.tick();
    assert_eq!(
        named(&bw.percepts("Human1"), "goTo"),
        ["goTo('RoomA1')", "goTo('RoomA2')"]
    );
}

#[test]
fn block_requests_are_perceived_where_the_robot_can_do_them() {
    let mut bw = game();
    bw.percepts("Human1");
    travel(&mut bw, "Human1", "RoomC1");
    let id = blocks_in(&bw, "RoomC1", "Yellow")[0];
    // goToBlock needs the block in view, pickUp within reach, putDown a held block.
    let e = bw.input("Human1", &t("putDown")).unwrap_err();
    assert!(e.contains("not holding a block"), "{e}");
    let batch = requested(&mut bw, &format!("goToBlock({id})"));
    assert!(
        has(&batch, &format!("goToBlock({id})")),
        "{:?}",
        show(&batch)
    );
    ok(&mut bw, "Human1", go_to_block(id));
    run_until_stopped(&mut bw, "Human1", 1000);
    let batch = requested(&mut bw, &format!("pickUp({id})"));
    assert!(has(&batch, &format!("pickUp({id})")));
    ok(&mut bw, "Human1", pick_up(id));
    let batch = requested(&mut bw, "putDown");
    assert!(has(&batch, "putDown"));
}

#[test]
fn requests_are_refused_with_the_reason_at_once() {
    let mut bw = game();
    let refused = |bw: &mut Bw4t, entity: &str, request: &str| {
        bw.input(entity, &t(request))
            .expect_err(&format!("{entity}: {request} accepted"))
    };
    let e = refused(&mut bw, "Bot1", "goTo('RoomA1')");
    assert!(e.contains("controlled by an agent"), "{e}");
    assert!(e.contains("Human1"), "{e}");
    let e = refused(&mut bw, "Bot9", "goTo('RoomA1')");
    assert!(
        e.contains("unknown entity `Bot9`") && e.contains("Human1"),
        "{e}"
    );
    let e = refused(&mut bw, "EPartner1", "goTo('RoomA1')");
    assert!(e.contains("unknown entity"), "{e}");
    let e = refused(&mut bw, "Human1", "goto('RoomA1')");
    assert!(e.contains("did you mean goTo/1"), "{e}");
    let e = refused(&mut bw, "Human1", "fly");
    assert!(e.contains("a person can ask for goTo/1"), "{e}");
    let e = refused(&mut bw, "Human1", "goTo(X)");
    assert!(e.contains("unbound variables"), "{e}");
    let e = refused(&mut bw, "Human1", "goTo('Atlantis')");
    assert!(e.contains("unknown place `Atlantis`"), "{e}");
    let e = refused(&mut bw, "Human1", "goToBlock(1)");
    assert!(e.contains("not visible"), "{e}");
    let e = refused(&mut bw, "Human1", "sendMessage(all, hello)");
    assert!(e.contains("not a message of the BW4T message list"), "{e}");
    let e = refused(
        &mut bw,
        "Human1",
        "sendMessage(X, imp(in('Human1', 'RoomA1')))",
    );
    assert!(e.contains("unbound variables"), "{e}");
    // Only a question may leave something open: a statement that does would stop the agents.
    let e = refused(&mut bw, "Human1", "sendMessage(all, in('Human1', _))");
    assert!(e.contains("unbound variables"), "{e}");
    let e = refused(&mut bw, "Human1", "navigateObstacles");
    assert!(e.contains("navigateObstacles needs a goTo"), "{e}");
    // A question of the message list leaves what it asks about open.
    bw.input("Human1", &t("sendMessage(all, int(at(_, 'RoomA1')))"))
        .expect("a question is a request");
    bw.tick();
    assert_eq!(named(&bw.percepts("Human1"), "sendMessage").len(), 1);
    // Nothing refused reached the robot.
    assert!(named(&bw.percepts("Human1"), "goTo").is_empty());
}

#[test]
fn waiting_requests_are_bounded() {
    let mut bw = game();
    for _ in 0..human::MAX_REQUESTS {
        bw.input("Human1", &t("getEPartners")).unwrap();
    }
    let e = bw.input("Human1", &t("getEPartners")).unwrap_err();
    assert!(e.contains("try again later"), "{e}");
    bw.tick();
    assert_eq!(
        named(&bw.percepts("Human1"), "getEPartners").len(),
        human::MAX_REQUESTS
    );
    bw.input("Human1", &t("getEPartners")).unwrap();
}

#[test]
fn epartner_percepts_have_the_interface_types() {
    use PerceptType::*;
    let seed = [
        ("heldBy", OnChangeWithNegation),
        ("getFunctionalities", Once),
        ("isTaken", OnChangeWithNegation),
        ("leftBehind", OnChange),
        ("getAt", OnChange),
        ("getLocation", OnChange),
        ("getRooms", Once),
        ("getRoom", Once),
        // "The initialization and messaging percepts/actions are the same as the robot."
        ("ownName", Once),
        ("message", Always),
    ];
    let decls = epartner::declarations();
    assert_eq!(decls.len(), seed.len());
    for (name, kind) in seed {
        let d = decls.iter().find(|d| d.name == name).expect(name);
        assert_eq!(d.kind, kind, "{name}");
    }
    assert_eq!(epartner::ACTIONS, ["sendMessage/2"]);
}

#[test]
fn an_epartner_with_both_functionalities_perceives_its_place_and_its_holder() {
    let mut bw = game();
    bw.percepts("Human1");
    let first = bw.percepts("EPartner1");
    assert!(has(&first, "ownName('EPartner1')"), "{:?}", show(&first));
    assert!(has(&first, "getFunctionalities(['GPS','Forget-me-not'])"));
    let rooms = named(&first, "getRooms");
    assert_eq!(rooms.len(), 1);
    assert!(rooms[0].contains("'RoomA1'") && rooms[0].contains("'DropZone'"));
    assert!(!rooms[0].contains("FrontDropZone"), "{}", rooms[0]);
    // Lying in a corridor: no room of its own.
    assert!(named(&first, "getRoom").is_empty());
    assert!(has(&first, "getAt('FrontDropZone')"));
    assert!(has(&first, "getLocation(25.0,61.0)"));
    assert!(has(&first, "leftBehind(false)"));
    assert!(named(&first, "heldBy").is_empty() && named(&first, "isTaken").is_empty());
    // Nothing changed: nothing new (once-percepts were in the first batch only).
    bw.tick();
    assert!(bw.percepts("EPartner1").is_empty());

    ok(&mut bw, "Human1", Term::atom("pickUpEPartner"));
    bw.tick();
    let taken = show(&bw.percepts("EPartner1"));
    assert!(taken.contains(&"heldBy('Human1')".to_string()), "{taken:?}");
    assert!(taken.contains(&"isTaken".to_string()), "{taken:?}");
    assert!(
        !taken.iter().any(|p| p.starts_with("leftBehind")),
        "{taken:?}"
    );

    // Carried along: its place changes with its holder's.
    travel(&mut bw, "Human1", "RoomC1");
    let w = bw.world();
    assert_eq!(w.epartners[0].pos, w.robots[idx(&bw, "Human1")].pos);
    let moved = bw.percepts("EPartner1");
    assert!(has(&moved, "getAt('RoomC1')"), "{:?}", show(&moved));
    assert_eq!(named(&moved, "getLocation").len(), 1);

    ok(&mut bw, "Human1", Term::atom("dropEPartner"));
    bw.tick();
    let dropped = show(&bw.percepts("EPartner1"));
    for p in ["not(heldBy('Human1'))", "not(isTaken)", "leftBehind(true)"] {
        assert!(dropped.contains(&p.to_string()), "{p} in {dropped:?}");
    }
    // It stays where it was dropped.
    travel(&mut bw, "Human1", "FrontDropZone");
    let moved = bw.percepts("EPartner1");
    assert!(named(&moved, "getAt").is_empty(), "{:?}", show(&moved));
}

#[test]
fn each_functionality_brings_only_its_own_percepts() {
    // GPS-only at the human's spawn (HallA of tiny), Forget-me-not-only in RoomA.
    let mut bw = tiny_with(
        "[[epartners]]\nx = 15.0\ny = 5.0\nfunctionalities = [\"GPS\"]\n\n\
         [[epartners]]\nx = 5.0\ny = 15.0\nfunctionalities = [\"Forget-me-not\"]\n",
    );
    let names: Vec<String> = bw
        .world()
        .epartners
        .iter()
        .map(|e| e.name.clone())
        .collect();
    assert_eq!(names, ["EPartner1", "EPartner2"]);
    let gps = bw.percepts("EPartner1");
    assert!(has(&gps, "getFunctionalities(['GPS'])"), "{:?}", show(&gps));
    assert!(has(&gps, "getAt('HallB')"));
    assert_eq!(named(&gps, "getRooms").len(), 1);
    for absent in ["leftBehind", "heldBy", "isTaken", "getRoom"] {
        assert!(
            named(&gps, absent).is_empty(),
            "{absent} in {:?}",
            show(&gps)
        );
    }
    let fmn = bw.percepts("EPartner2");
    assert!(has(&fmn, "getFunctionalities(['Forget-me-not'])"));
    assert!(has(&fmn, "getRoom('RoomA')"), "{:?}", show(&fmn));
    assert!(has(&fmn, "leftBehind(false)"));
    assert!(has(&fmn, "getLocation(5.0,15.0)"));
    for absent in ["getAt", "getRooms"] {
        assert!(
            named(&fmn, absent).is_empty(),
            "{absent} in {:?}",
            show(&fmn)
        );
    }
    assert_eq!(
        bw.world().epartners[0].functionalities,
        [Functionality::Gps]
    );
}

#[test]
fn only_humans_pick_up_and_drop_epartners() {
    let mut bw = env(
        "banana",
        Bw4tConfig {
            robots: Some(1),
            humans: 1,
            epartners: 2,
            ..Bw4tConfig::default()
        },
    );
    // EPartner1 lies at Human1, EPartner2 on the next spawn point left (where Bot2 would be).
    let w = bw.world();
    assert_eq!(
        w.epartners[1].pos,
        goal::bw4t::geometry::Pos::new(21.0, 63.0)
    );
    // Bot1 stands in the same zone: for an agent robot nothing happens.
    for action in ["pickUpEPartner", "dropEPartner"] {
        assert_eq!(bw.perform("Bot1", &Term::atom(action)), ActionResult::Ok);
    }
    let w = bw.world();
    assert!(w.epartners.iter().all(|e| e.holder.is_none()));
    assert!(w.robots[idx(&bw, "Bot1")].epartner.is_none());

    let drop = bw.perform("Human1", &Term::atom("dropEPartner"));
    assert_eq!(drop, ActionResult::fail("not carrying an e-partner"));
    ok(&mut bw, "Human1", Term::atom("pickUpEPartner"));
    let again = bw.perform("Human1", &Term::atom("pickUpEPartner"));
    assert!(
        matches!(&again, ActionResult::Failed(m) if m.contains("already carrying e-partner EPartner1")),
        "{again:?}"
    );
    let w = bw.world();
    assert_eq!(w.epartners[0].holder, Some(idx(&bw, "Human1")));
    assert_eq!(w.epartners[1].holder, None);

    // The robot's epartner/4 percept: the one it carries (holder: its id) and the free ones
    // in its zone (holder -1).
    let id = w.robots[idx(&bw, "Human1")].id;
    let e1 = w.epartners[0].id;
    let e2 = w.epartners[1].id;
    bw.tick();
    let seen = named(&bw.percepts("Human1"), "epartner");
    assert_eq!(
        seen,
        [
            format!("epartner({e1},'EPartner1',{id},['GPS','Forget-me-not'])"),
            format!("epartner({e2},'EPartner2',-1,['GPS','Forget-me-not'])"),
        ]
    );
    // Far from any e-partner, a human picks up nothing.
    ok(&mut bw, "Human1", Term::atom("dropEPartner"));
    travel(&mut bw, "Human1", "RoomA1");
    let far = bw.perform("Human1", &Term::atom("pickUpEPartner"));
    assert!(
        matches!(&far, ActionResult::Failed(m) if m.contains("no e-partner within reach")),
        "{far:?}"
    );
    assert!(named(&bw.percepts("Human1"), "epartner").is_empty());
    let stats = bw.run_stats();
    assert_eq!(stats.epartners[0].picked_up, 1);
    assert_eq!(stats.epartners[0].dropped, 1);
}

#[test]
fn an_epartner_messages_its_holder_and_hears_messages_for_it() {
    let mut bw = game();
    bw.percepts("Human1");
    bw.percepts("EPartner1");
    ok(&mut bw, "Human1", Term::atom("pickUpEPartner"));
    let note = t("sendMessage('Human1', at('EPartner1', 'FrontDropZone'))");
    assert_eq!(bw.perform("EPartner1", &note), ActionResult::Ok);
    bw.tick();
    let batch = bw.percepts("Human1");
    assert!(
        has(
            &batch,
            "message('EPartner1',at('EPartner1','FrontDropZone'))"
        ),
        "{:?}",
        show(&batch)
    );
    assert!(named(&bw.percepts("Bot1"), "message").is_empty());
    // The person (through the robot) or anyone can ask it.
    ok(&mut bw, "Human1", t("sendMessage('EPartner1', where)"));
    bw.tick();
    assert!(has(&bw.percepts("EPartner1"), "message('Human1',where)"));
    let bad = bw.perform("EPartner1", &t("goTo('RoomA1')"));
    assert!(
        matches!(&bad, ActionResult::Failed(m) if m.contains("unknown action goTo/1")),
        "{bad:?}"
    );
    let bad = bw.perform("EPartner1", &t("sendMessage('Nobody', hi)"));
    assert_eq!(bad, ActionResult::fail("unknown receiver `Nobody`"));
    assert_eq!(bw.run_stats().epartners[0].messages_sent, 1);
}

#[test]
fn scene_and_stats_show_humans_and_who_holds_which_epartner() {
    let mut bw = game();
    ok(&mut bw, "Human1", Term::atom("pickUpEPartner"));
    bw.tick();
    let scene = bw.scene().expect("a scene");
    assert_eq!(scene["robots"]["Human1"]["kind"], "human");
    assert_eq!(scene["robots"]["Human1"]["epartner"], "EPartner1");
    assert_eq!(scene["robots"]["Bot1"]["kind"], "robot");
    assert!(scene["robots"]["Bot1"].get("epartner").is_none());
    let e = &scene["epartners"]["EPartner1"];
    assert_eq!(e["kind"], "epartner");
    assert_eq!(e["holder"], "Human1");
    assert_eq!(
        e["functionalities"],
        serde_json::json!(["GPS", "Forget-me-not"])
    );
    // What `--stats` writes for the environment.
    let stats = Environment::stats(&bw);
    assert_eq!(stats["robots"][1]["name"], "Human1");
    assert_eq!(stats["robots"][1]["human"], true);
    assert!(stats["robots"][0].get("human").is_none());
    assert_eq!(stats["epartners"][0]["name"], "EPartner1");
    assert_eq!(stats["epartners"][0]["holder"], "Human1");
    assert_eq!(stats["epartners"][0]["picked_up"], 1);
    // Without e-partners, scene and stats have no e-partner part.
    let mut plain = default_env("banana");
    assert!(plain.scene().unwrap().get("epartners").is_none());
    let stats = serde_json::to_value(plain.run_stats()).unwrap();
    assert!(stats.get("epartners").is_none());
}

#[test]
fn humancount_and_init_parameters_create_humans_and_epartners() {
    use goal::env::{FromInitParams, InitParams};
    let mut params = InitParams::new();
    params.insert("map".into(), Term::atom("banana"));
    params.insert("robots".into(), Term::Int(2));
    params.insert("humans".into(), Term::Int(2));
    params.insert("epartners".into(), Term::Int(1));
    let bw = Bw4t::from_init_params(&params).unwrap();
    let kinds: Vec<String> = bw.entities().into_iter().map(|e| e.kind).collect();
    assert_eq!(kinds, ["bot", "bot", "human", "human", "epartner"]);
    params.insert("humans".into(), Term::atom("many"));
    let e = Bw4t::from_params(&params).unwrap_err();
    assert!(e[0].message.contains("`humans`"), "{}", e[0].message);
    // More humans than spawn points: the ones that fit, with a warning.
    let bw = env(
        "tiny",
        Bw4tConfig {
            robots: Some(3),
            humans: 2,
            ..Bw4tConfig::default()
        },
    );
    assert_eq!(bw.entities().len(), 4);
    assert!(
        bw.warnings()
            .iter()
            .any(|w| w.contains("1 human-controlled robot(s) not created")),
        "{:?}",
        bw.warnings()
    );
}

fn map_errors(source: &str) -> Vec<String> {
    match map::from_toml(source, "e.toml") {
        Ok(_) => Vec::new(),
        Err(ds) => ds
            .iter()
            .map(|d| format!("{} {}", d.code, d.message))
            .collect(),
    }
}

#[test]
fn toml_maps_list_epartners_and_human_spawn_points() {
    let tiny = map::builtin_source("tiny").unwrap();
    let source = format!(
        "{tiny}\n[[epartners]]\nx = 15.0\ny = 5.0\n\n\
         [[epartners]]\nx = 5.0\ny = 15.0\nfunctionalities = [\"Forget-me-not\"]\n"
    );
    let m = map::from_toml(&source, "e.toml").unwrap();
    assert_eq!(m.epartners.len(), 2);
    assert_eq!(m.epartners[0].functionalities, Functionality::all());
    assert_eq!(m.epartners[1].functionalities, [Functionality::ForgetMeNot]);
    // Written back and read again, nothing is lost.
    let again = map::from_toml(&map::to_toml(&m), "again.toml").unwrap();
    assert_eq!(again.epartners, m.epartners);
    // Maps without e-partners or human spawn points are written without those keys.
    let plain = map::to_toml(&map::builtin("tiny").unwrap().unwrap());
    assert!(!plain.contains("epartners") && !plain.contains("human_spawns"));
    // Banana's human spawn points are used before the robots' left over.
    let banana = map::builtin("banana").unwrap().unwrap();
    assert_eq!(banana.human_spawns.len(), 3);

    let bad = |extra: &str| map_errors(&format!("{tiny}\n{extra}"));
    let e = bad("[[epartners]]\nx = 95.0\ny = 5.0\n");
    assert!(
        e.iter()
            .any(|d| d.starts_with("M0010")
                && d.contains("e-partner 1 at (95, 5) is outside the map")),
        "{e:?}"
    );
    let e = bad("[[epartners]]\nx = 5.0\ny = 5.0\nfunctionalities = []\n");
    assert!(
        e.iter()
            .any(|d| d.contains("e-partner 1 must list each functionality")),
        "{e:?}"
    );
    let e = bad("[[epartners]]\nx = 5.0\ny = 5.0\nfunctionalities = [\"GPS\", \"GPS\"]\n");
    assert!(e.iter().any(|d| d.contains("at most once")), "{e:?}");
    let e = bad("[[epartners]]\nx = 5.0\ny = 5.0\nfunctionalities = [\"Radar\"]\n");
    assert!(e.iter().any(|d| d.contains("Radar")), "{e:?}");
    let with_humans = tiny.replace(
        "spawns = [[5.0, 5.0]",
        "human_spawns = [[5.0, 15.0], [26.0, 5.0]]\nspawns = [[5.0, 5.0]",
    );
    let e = map_errors(&with_humans);
    assert!(
        e.iter().any(|d| d.starts_with("M0008")
            && d.contains("human spawn point 1 (5, 15) is inside room `RoomA`")),
        "{e:?}"
    );
    assert!(
        e.iter().any(|d| d.starts_with("M0007")
            && d.contains("spawn point 3 (25, 5) and human spawn point 2 (26, 5) overlap")),
        "{e:?}"
    );
    // A human spawn point outside the map is shown at the `human_spawns` line.
    let outside = tiny.replace(
        "spawns = [[5.0, 5.0]",
        "human_spawns = [[500.0, 500.0]]\nspawns = [[5.0, 5.0]",
    );
    let Err(ds) = map::from_toml(&outside, "e.toml") else {
        panic!("a spawn point outside the map is an error")
    };
    let d = ds.iter().find(|d| d.code == "M0015").expect("M0015");
    let shown = d.render(&outside);
    assert!(shown.contains("e.toml:12:1\n"), "{shown}");
    assert!(shown.contains("human_spawns = [[500.0, 500.0]]"), "{shown}");
}

fn shared_banana_xml() -> Option<String> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../shared/bw4t-maps/banana.xml"
    );
    match std::fs::read_to_string(path) {
        Ok(text) => Some(text),
        Err(_) => {
            println!("skipped: {path} is absent");
            None
        }
    }
}

#[test]
fn xml_maps_bring_epartner_entities() {
    use goal::bw4t::xml;
    let Some(banana) = shared_banana_xml() else {
        return;
    };
    let epartner = |body: &str| {
        banana.replacen(
            "<entities>",
            &format!(
                "<entities><name>EPartner1</name><position><x>25.0</x><y>61.0</y></position>\
                 <type>EPARTNER</type>{body}</entities>\n    <entities>"
            ),
            1,
        )
    };
    let m = xml::import(&epartner(""), "banana-e.xml").unwrap();
    // An e-partner entity is no spawn point.
    assert_eq!(m.spawns.len(), 3);
    assert_eq!(m.epartners.len(), 1);
    assert_eq!((m.epartners[0].x, m.epartners[0].y), (25.0, 61.0));
    assert_eq!(m.epartners[0].functionalities, Functionality::all());
    let m = xml::import(
        &epartner("<functionality>GPS</functionality>"),
        "banana-gps.xml",
    )
    .unwrap();
    assert_eq!(m.epartners[0].functionalities, [Functionality::Gps]);
    let e = xml::import(
        &epartner("<functionality>Radar</functionality>"),
        "banana-bad.xml",
    )
    .unwrap_err();
    assert_eq!(e[0].code, "M0012");
    assert!(
        e[0].message.contains("unknown functionality `Radar`"),
        "{}",
        e[0].message
    );
    // The imported e-partner lies where it is and is the world's EPartner1.
    let m = xml::import(&epartner(""), "banana-e.xml").unwrap();
    let bw = Bw4t::new(
        &m,
        &Bw4tConfig {
            robots: Some(1),
            ..Bw4tConfig::default()
        },
    );
    let kinds: Vec<String> = bw.entities().into_iter().map(|e| e.kind).collect();
    assert_eq!(kinds, ["bot", "epartner"]);
}
