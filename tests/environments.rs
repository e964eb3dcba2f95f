//! The environments named in real `.mas2g` files, through the `goal` binary: BW4T client jars
//! and blocks-world jars select the built-in environments, BW4T client init parameters, the
//! 2012-13 environment form, `goal check` against the environment's actions and percepts, and
//! map layout errors with their map line.

use std::path::{Path, PathBuf};
use std::process::Output;

fn fixtures() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/envs")
}

fn goal(dir: &Path, args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// A fresh copy of the fixture system `system/mas` (with its agent file `agent`) in a temp
/// directory, with `from` replaced by `to` in the `.mas2g` text.
fn variant(tag: &str, system: &str, mas: &str, agent: &str, from: &str, to: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-envs-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let src = fixtures().join(system);
    std::fs::copy(src.join(agent), dir.join(agent)).unwrap();
    let text = std::fs::read_to_string(src.join(mas)).unwrap();
    assert!(text.contains(from), "{from}");
    std::fs::write(dir.join(mas), text.replace(from, to)).unwrap();
    dir
}

#[test]
fn a_2015_course_team_on_the_bw4t_client_jar_completes_the_game() {
    let out = goal(&fixtures().join("bw4t2015"), &["run", "team.mas2g"]);
    let err = text(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert_eq!(
        err.matches("environment: built-in bw4t").count(),
        1,
        "the environment is named once: {err}"
    );
    assert!(err.contains("completed"), "{err}");
    insta::assert_snapshot!("bw4t2015_team_summary", err);
}

#[test]
fn blocks_world_programs_in_goal_example_style_pass_goal_test() {
    let out = goal(&fixtures().join("blocksworld"), &["test", "bw.test2g"]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(out.status.success(), "{all}");
    assert!(all.contains("stackbuilder/buildTowers ... passed"), "{all}");
}

#[test]
fn blocks_world_runs_under_goal_run_and_its_agent_stops_when_done() {
    let out = goal(&fixtures().join("blocksworld"), &["run", "bw.mas2g"]);
    let err = text(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(
            "environment: built-in blocksworld for `../blocksworld-1.1.0-blocksworld.jar`"
        ),
        "{err}"
    );
    assert!(err.contains("all agents stopped"), "{err}");
}

#[test]
fn a_bad_blocks_world_start_list_is_refused() {
    let dir = variant(
        "bw",
        "blocksworld",
        "bw.mas2g",
        "stackBuilder.goal",
        "start = [2, 0, 0, 3, 4, 0]",
        "start = [2, 1, 0, 3, 4, 0]",
    );
    let out = goal(&dir, &["run", "bw.mas2g"]);
    let err = text(&out.stderr);
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("loops back on itself"), "{err}");
    assert!(
        err.contains("bw.mas2g:4:10"),
        "points at the start list: {err}"
    );
}

#[test]
fn the_2012_environment_form_loads_and_programs_get_bw4t2_navpoints() {
    let out = goal(&fixtures().join("bw4t2012"), &["test", "explorer.test2g"]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(out.status.success(), "{all}");
    assert!(all.contains("explorer/reachesARoom ... passed"), "{all}");
}

#[test]
fn an_environment_nobody_built_in_is_an_error_naming_the_built_in_ones() {
    let dir = fixtures().join("check");
    for cmd in ["run", "check"] {
        let out = goal(&dir, &[cmd, "tictactoe.mas2g"]);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{cmd}: {all}");
        assert!(all.contains("error[E0208]"), "{cmd}: {all}");
        assert!(
            all.contains("the built-in environments are bw4t and blocksworld"),
            "{all}"
        );
        assert!(all.contains("tictactoe.mas2g:2:8"), "{all}");
    }
}

#[test]
fn goal_check_compares_env_actions_and_percepts_with_the_environment() {
    let out = goal(&fixtures().join("check"), &["check", "team.mas2g"]);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "warnings only: {stdout}");
    assert!(stdout.contains("action goto/1 is not an action of the built-in bw4t environment (did you mean goTo/1?)"), "{stdout}");
    assert!(stdout.contains("(did you mean atBlock/1?)"), "{stdout}");
    assert!(
        stdout.contains("(did you mean holdingblocks/1?)"),
        "{stdout}"
    );
    // Percept queries in action preconditions count too.
    assert!(stdout.contains("percept holdng/1 is never sent by the built-in bw4t environment (did you mean holding/1?)"), "{stdout}");
    insta::assert_snapshot!("check_slips", stdout);
}

#[test]
fn client_settings_are_warned_about_once() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/mas2g/invalid");
    let out = goal(
        &dir,
        &["run", "W0207_client_config.mas2g", "--max-ticks", "3"],
    );
    let err = text(&out.stderr);
    assert_eq!(
        err.matches("configuration files are not supported").count(),
        1,
        "{err}"
    );
    assert!(err.contains("BW4T client version 3.8.0"), "{err}");
    // `agentcount = "1"`: one robot entity, so one agent, although the map has three spawns.
    let agents = err.lines().skip_while(|l| !l.starts_with("agent ")).skip(1);
    assert_eq!(agents.count(), 1, "{err}");
}

#[test]
fn map_layout_errors_name_the_map_line() {
    let bw4t = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("agents/bw4t/bw4t.mas2g");
    let dir = fixtures().join("maps");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml") || n.ends_with(".xml"))
        .collect();
    names.sort();
    assert!(names.len() >= 9, "{names:?}");
    for name in names {
        let map = std::fs::read_to_string(dir.join(&name)).unwrap();
        // `# expect: CODE LINE` (TOML) or `<!-- expect: CODE LINE -->` (XML).
        let at = map.find("expect: ").unwrap() + "expect: ".len();
        let spec = map[at..].lines().next().unwrap().trim_end_matches(" -->");
        let (code, line) = spec.split_once(' ').unwrap();
        let out = goal(
            &dir,
            &[
                "run",
                bw4t.to_str().unwrap(),
                "--map",
                &name,
                "--max-ticks",
                "3",
            ],
        );
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains(&format!("error[{code}]")), "{name}: {err}");
        assert!(
            err.contains(&format!("{name}:{line}:")),
            "{name}: want line {line}: {err}"
        );
    }
}

#[test]
fn bw4t_server_map_names_in_any_case_and_xml_paths_are_accepted() {
    let dir = std::env::temp_dir().join(format!("goal-envs-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        fixtures().join("bw4t2015/robot.goal"),
        dir.join("robot.goal"),
    )
    .unwrap();
    let mas = std::fs::read_to_string(fixtures().join("bw4t2015/team.mas2g")).unwrap();
    let shared = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/bw4t-maps/rainbow.xml");
    let mut maps = vec![
        "SuperRandom".to_string(),
        "BANANA".to_string(),
        "dutch_flag".to_string(),
    ];
    if shared.is_file() {
        std::fs::copy(&shared, dir.join("Rainbow.xml")).unwrap();
        maps.push("maps\\..\\Rainbow.xml".to_string());
        std::fs::create_dir_all(dir.join("maps")).unwrap();
    } else {
        eprintln!("shared BW4T maps not found; the XML path case is skipped");
    }
    for m in maps {
        std::fs::write(
            dir.join("team.mas2g"),
            mas.replace("map = \"Random\"", &format!("map = \"{m}\"")),
        )
        .unwrap();
        let out = goal(&dir, &["run", "team.mas2g", "--max-ticks", "5"]);
        let err = text(&out.stderr);
        // Exit code 3: the map loaded and the run stopped at the tick limit.
        assert_eq!(out.status.code(), Some(3), "{m}: {err}");
        assert!(!err.contains("warning"), "{m}: {err}");
    }
}

#[test]
fn failing_actions_say_why() {
    use goal::env::{ActionResult, Environment, InitParams};
    use goal::term::Term;
    let params = InitParams::from([
        ("map".to_string(), Term::atom("banana")),
        ("robots".to_string(), Term::Int(1)),
    ]);
    let mut bw4t = goal::bw4t::Bw4t::from_params(&params).unwrap();
    let fail = |r: ActionResult| match r {
        ActionResult::Failed(m) => m,
        ActionResult::Ok => panic!("the action should fail"),
    };
    let act = |name: &str, args: Vec<Term>| Term::compound(name, args);
    let goto = fail(bw4t.perform("Bot1", &act("goto", vec![Term::atom("RoomA1")])));
    assert_eq!(goto, "unknown action goto/1 (did you mean goTo/1?)");
    let nowhere = fail(bw4t.perform("Bot1", &act("goTo", vec![Term::atom("Nowhere")])));
    assert_eq!(nowhere, "unknown place `Nowhere`");
    let lower = fail(bw4t.perform("Bot1", &act("goTo", vec![Term::atom("roomA1")])));
    assert_eq!(lower, "unknown place `roomA1` (did you mean `RoomA1`?)");
    let pick = fail(bw4t.perform("Bot1", &Term::atom("pickUp")));
    assert!(pick.contains("no block within reach"), "{pick}");
    let fly = fail(bw4t.perform("Bot1", &act("fly", vec![Term::Int(1)])));
    assert!(
        fly.starts_with("unknown action fly/1; the entity understands goTo/1"),
        "{fly}"
    );

    let start = Term::list(vec![Term::Int(2), Term::Int(0), Term::Int(0)]);
    let params = InitParams::from([("start".to_string(), start)]);
    let mut bw = goal::blocksworld::BlocksWorld::from_params(&params).unwrap();
    let mv = |x: Term, y: Term| act("move", vec![x, y]);
    let covered = fail(bw.perform("gripper", &mv(Term::Int(2), Term::Int(3))));
    assert_eq!(
        covered,
        "move(2, 3) is not possible: block 2 is not clear: 1 is on it"
    );
    let typo = fail(bw.perform("gripper", &act("mvoe", vec![Term::Int(1), Term::Int(3)])));
    assert_eq!(typo, "unknown action mvoe/2 (did you mean move/2?)");
    assert_eq!(
        bw.perform("gripper", &mv(Term::Int(1), Term::Int(3))),
        ActionResult::Ok
    );
    let percepts: Vec<String> = bw
        .percepts("gripper")
        .iter()
        .map(|t| t.to_string())
        .collect();
    assert_eq!(
        percepts,
        [
            "block(1)",
            "block(2)",
            "block(3)",
            "on(1,3)",
            "on(2,table)",
            "on(3,table)"
        ]
    );
}

#[test]
fn goal_check_of_a_mas_file_checks_the_map_it_names() {
    let dir = variant(
        "check-map",
        "bw4t2015",
        "team.mas2g",
        "robot.goal",
        "map = \"Random\"",
        "map = \"doorless.toml\"",
    );
    let maps = fixtures().join("maps");
    std::fs::copy(
        maps.join("room_without_door.toml"),
        dir.join("doorless.toml"),
    )
    .unwrap();
    let out = goal(&dir, &["check", "team.mas2g"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("error[M0014]"), "{stdout}");
    assert!(stdout.contains("doorless.toml:60:1"), "{stdout}");
}

#[test]
fn a_bad_bw4t_init_value_points_at_its_place_in_the_mas_file() {
    let dir = variant(
        "bad-init",
        "bw4t2015",
        "team.mas2g",
        "robot.goal",
        "agentcount = \"3\"",
        "agentcount = \"lots\"",
    );
    for cmd in ["run", "check"] {
        let out = goal(&dir, &[cmd, "team.mas2g"]);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{cmd}: {all}");
        assert!(
            all.contains("init parameter `agentcount` must be an integer 0..1000, got `\"lots\"`"),
            "{cmd}: {all}"
        );
        assert!(all.contains("team.mas2g:5:31"), "{cmd}: {all}");
    }
}
