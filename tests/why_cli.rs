//! `goal why` on the built binary and through its library API: small programs where a rule
//! fires, a rule's second literal fails, an action's precondition fails and a rule of a linear
//! module is not evaluated; the default BW4T team; modular and MARBEL systems; traces; errors.

use goal::mas::run::RunOptions;
use goal::mas::system;
use goal::why::Why;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

const SHOP: &str = "tests/fixtures/why/shop.mas2g";
const DICE: &str = "tests/fixtures/why/dice.mas2g";

/// A fresh empty directory under the system temp dir.
fn temp_dir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-why-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn goal_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_goal"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn goal(args: &[&str]) -> Output {
    goal_in(&root(), args)
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// `goal why ARGS`, which must succeed; its standard output.
fn why_ok(args: &[&str]) -> String {
    let mut all = vec!["why"];
    all.extend_from_slice(args);
    let out = goal(&all);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    text(&out.stdout)
}

fn why_json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.push("--json");
    serde_json::from_str(&why_ok(&all)).expect("--json prints JSON")
}

/// `goal why ARGS`, which must fail with `code`; its standard error.
fn why_err(args: &[&str], code: i32) -> String {
    let mut all = vec!["why"];
    all.extend_from_slice(args);
    let out = goal(&all);
    assert_eq!(out.status.code(), Some(code), "{}", text(&out.stdout));
    assert_eq!(text(&out.stdout), "", "nothing on stdout when failing");
    text(&out.stderr)
}

fn outcomes(r: &Value) -> Vec<String> {
    r["rules"]
        .as_array()
        .expect("rules")
        .iter()
        .map(|x| {
            format!(
                "{} {}",
                x["rule"].as_str().unwrap(),
                x["outcome"].as_str().unwrap()
            )
        })
        .collect()
}

#[test]
fn fired_failed_literal_failed_precondition_and_not_evaluated() {
    let out = why_ok(&[SHOP, "--agent", "shopper", "--tick", "0"]);
    insta::assert_snapshot!("why_shop_tick_0", out);
    let r = why_json(&[SHOP, "--agent", "shopper", "--tick", "0"]);
    assert_eq!(
        outcomes(&r),
        [
            "main:30 failed",
            "main:31 precondition_failed",
            "main:32 fired",
            "main:33 not_evaluated"
        ]
    );
    let rules = &r["rules"];
    // The second literal failed, for both bindings of the first.
    assert_eq!(rules[0]["failed_literal"], "goal(eat(X))");
    assert_eq!(rules[0]["literals"][0]["status"], "held");
    assert_eq!(rules[0]["literals"][1]["status"], "failed");
    assert_eq!(rules[0]["bindings"], "X=apple");
    assert_eq!(rules[0]["answers"], 2);
    // The condition held, the action's precondition did not (money 4 < price 5).
    assert_eq!(rules[1]["failed_action"], "buy(pear)");
    assert_eq!(rules[1]["failed_precondition"], "4>=5");
    assert_eq!(rules[2]["bindings"], "X=apple, P=3");
    assert_eq!(rules[2]["failed_literal"], Value::Null);
    assert!(rules[3]["reason"].as_str().unwrap().contains("main:32"));
    assert_eq!(rules[3]["file"], "tests/fixtures/why/shop.goal");
    assert_eq!(rules[3]["line"], 33);
}

#[test]
fn the_json_form_has_the_fields_the_view_reads() {
    let r = why_json(&[SHOP, "--agent", "shopper", "--tick", "0"]);
    insta::assert_json_snapshot!("why_shop_tick_0_json", r);
    for k in ["agent", "tick", "cycle", "module", "rules"] {
        assert!(r.get(k).is_some(), "{k} missing");
    }
    for rule in r["rules"].as_array().unwrap() {
        for k in [
            "rule",
            "text",
            "outcome",
            "bindings",
            "failed_literal",
            "failed_action",
        ] {
            assert!(rule.get(k).is_some(), "{k} missing in {rule}");
        }
    }
}

#[test]
fn a_failed_conjunct_of_a_belief_query_is_named() {
    let r = why_json(&[SHOP, "--agent", "shopper", "--tick", "6"]);
    let count = &r["rules"][3];
    assert_eq!(count["outcome"], "failed");
    assert_eq!(count["failed_literal"], "bel(count(N),N<5,M is N+1)");
    assert_eq!(count["failed_conjunct"], "5<5");
    assert_eq!(count["conjunct_bindings"], "N=5");
    // A negated literal that failed.
    assert_eq!(r["rules"][2]["failed_literal"], "not(bel(have(X)))");
    assert_eq!(r["rules"][2]["bindings"], "X=apple, P=3");
}

#[test]
fn a_waiting_agent_is_explained_by_its_last_cycle() {
    let out = why_ok(&[SHOP, "--agent", "shopper", "--tick", "8"]);
    insta::assert_snapshot!("why_shop_waiting", out);
    let r = why_json(&[SHOP, "--agent", "shopper", "--tick", "8"]);
    assert_eq!(r["tick"], 8);
    assert_eq!(r["ran_at"], 6);
    assert!(r["note"].as_str().unwrap().contains("waiting"));
}

#[test]
fn errors_are_plain_messages_with_a_failing_exit_code() {
    let e = why_err(&[SHOP, "--agent", "nobody", "--tick", "0"], 1);
    assert!(
        e.contains("no agent named nobody") && e.contains("quitter, shopper, ticker"),
        "{e}"
    );
    let e = why_err(&[SHOP, "--agent", "shopper", "--tick", "13"], 1);
    assert!(e.contains("tick 13 is past the end of the run"), "{e}");
    assert!(e.contains("ticks 0 to 12"), "{e}");
    let e = why_err(&[SHOP, "--agent", "quitter", "--tick", "3"], 1);
    assert!(
        e.contains("quitter was not running at tick 3: it stopped at tick 1"),
        "{e}"
    );
    assert!(e.contains("main module exited"), "{e}");
    // The run's tick limit ends it, as in `goal run`.
    let e = why_err(
        &[SHOP, "--agent", "ticker", "--tick", "5", "--max-ticks", "5"],
        1,
    );
    assert!(e.contains("past the end"), "{e}");
    let e = why_err(&["missing.mas2g", "--agent", "a", "--tick", "0"], 1);
    assert!(e.contains("missing.mas2g"), "{e}");
}

#[test]
fn trace_errors_are_plain_messages() {
    let dir = temp_dir("bad-traces");
    std::fs::write(dir.join("junk.jsonl"), "this is not json\n").unwrap();
    std::fs::write(dir.join("empty.jsonl"), "").unwrap();
    let other =
        r#"{"type":"header","format":"goal-trace","version":99,"file":"x.mas2g","agents":[]}"#;
    std::fs::write(dir.join("v99.jsonl"), format!("{other}\n")).unwrap();
    let foreign = r#"{"type":"header","format":"other","version":1}"#;
    std::fs::write(dir.join("foreign.jsonl"), format!("{foreign}\n")).unwrap();
    let gone = r#"{"type":"header","format":"goal-trace","version":1,"file":"gone.mas2g","agents":[{"name":"a"}],"seed":0}"#;
    std::fs::write(dir.join("gone.jsonl"), format!("{gone}\n")).unwrap();
    let cases = [
        ("junk.jsonl", "not a goal trace"),
        ("empty.jsonl", "empty"),
        ("v99.jsonl", "version 99"),
        ("foreign.jsonl", "not a goal trace"),
        ("nothere.jsonl", "cannot read it"),
        ("gone.jsonl", "cannot be loaded"),
    ];
    for (file, says) in cases {
        let out = goal_in(&dir, &["why", file, "--agent", "a", "--tick", "0"]);
        let e = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{file}: {e}");
        assert!(e.contains(says), "{file}: {e}");
    }
    // Flags of a rerun do not go with a trace.
    let out = goal_in(
        &dir,
        &[
            "why",
            "junk.jsonl",
            "--agent",
            "a",
            "--tick",
            "0",
            "--seed",
            "3",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("a trace names its own"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_trace_gives_the_same_answer_as_its_system() {
    let dir = temp_dir("trace");
    let trace = dir.join("shop.jsonl");
    let t = trace.to_str().unwrap();
    let out = goal(&["run", SHOP, "--trace", t]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    for tick in ["0", "1", "8"] {
        let a = why_ok(&[t, "--agent", "shopper", "--tick", tick]);
        let b = why_ok(&[SHOP, "--agent", "shopper", "--tick", tick]);
        assert_eq!(a, b, "tick {tick}");
    }
    let r = why_json(&[t, "--agent", "shopper", "--tick", "1"]);
    assert_eq!(r["matches_trace"], true);
    // Asked of the trace, past its end and an unknown agent are refused without a rerun.
    let e = why_err(&[t, "--agent", "shopper", "--tick", "40"], 1);
    assert!(e.contains("past the end"), "{e}");
    let e = why_err(&[t, "--agent", "Bot1", "--tick", "0"], 1);
    assert!(e.contains("no agent named Bot1"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_trace_of_changed_files_is_reported_as_not_matching() {
    let dir = temp_dir("changed");
    for f in ["shop.mas2g", "shop.goal", "quitter.goal", "ticker.goal"] {
        std::fs::copy(root().join("tests/fixtures/why").join(f), dir.join(f)).unwrap();
    }
    let out = goal_in(&dir, &["run", "shop.mas2g", "--trace", "t.jsonl"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let src = std::fs::read_to_string(dir.join("shop.goal")).unwrap();
    std::fs::write(dir.join("shop.goal"), src.replace("N < 5", "N < 3")).unwrap();
    let out = goal_in(
        &dir,
        &["why", "t.jsonl", "--agent", "shopper", "--tick", "4"],
    );
    assert_eq!(out.status.code(), Some(0));
    assert!(
        text(&out.stderr).contains("changed since the trace was written"),
        "{}",
        text(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn explaining_does_not_change_the_run() {
    // The agent draws random numbers in a failing precondition and in a firing rule: if
    // explaining drew any more, the rerun would fire with other numbers than the trace.
    let dir = temp_dir("dice");
    let trace = dir.join("dice.jsonl");
    let t = trace.to_str().unwrap();
    let out = goal(&["run", DICE, "--max-cycles", "8", "--trace", t]);
    assert_eq!(out.status.code(), Some(3), "{}", text(&out.stderr));
    for tick in ["0", "3", "7"] {
        let r = why_json(&[t, "--agent", "dice", "--tick", tick]);
        assert_eq!(r["matches_trace"], true, "tick {tick}");
        assert_eq!(r["rules"][0]["outcome"], "precondition_failed");
        assert_eq!(r["rules"][1]["outcome"], "fired");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_default_bw4t_team() {
    let out = why_ok(&["--agent", "Bot2", "--tick", "40"]);
    insta::assert_snapshot!("why_bw4t_bot2_tick_40", out);
    let r = why_json(&["--agent", "Bot2", "--tick", "40"]);
    let phases: Vec<&str> = r["rules"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["phase"].as_str().unwrap())
        .collect();
    assert!(phases.contains(&"event") && phases.contains(&"main"));
}

/// The modular and MARBEL teams lower to the same program: rules are located in their own
/// module files.
#[test]
fn modular_and_marbel_systems() {
    for mas in [
        "agents/bw4t/modular/team.mas2g",
        "agents/bw4t/marbel/team.mas2g",
    ] {
        let r = why_json(&[mas, "--agent", "Bot1", "--tick", "5"]);
        let rules = r["rules"].as_array().unwrap();
        assert!(
            rules
                .iter()
                .any(|x| x["file"].as_str().unwrap().ends_with(".mod2g")),
            "{mas}"
        );
        assert!(rules.iter().any(|x| x["outcome"] == "fired"), "{mas}");
        assert!(rules.iter().any(|x| x["outcome"] == "failed"), "{mas}");
        assert!(
            rules
                .iter()
                .all(|x| !x["text"].as_str().unwrap().is_empty()),
            "{mas}"
        );
    }
}

#[test]
fn the_library_api_answers_again_and_again() {
    let sys = system::load_mas(&root().join(SHOP)).expect("loads");
    let why = Why::for_system(sys, RunOptions::default());
    let a = why.why("shopper", 0).expect("explained");
    assert_eq!(a["agent"], "shopper");
    assert_eq!(a["cycle"], 1);
    assert_eq!(a["module"], "main");
    assert_eq!(a["rules"][2]["outcome"], "fired");
    assert_eq!(why.why("shopper", 0).expect("again"), a);
    let b = why.why("shopper", 1).expect("explained");
    assert_eq!(b["rules"][3]["outcome"], "fired");
    let e = why.why("nobody", 0).unwrap_err();
    assert!(e.contains("no agent named nobody"), "{e}");
}

#[test]
fn nested_blocks_and_called_modules_are_explained_in_place() {
    let args = [
        "tests/fixtures/goal2014/scope.goal",
        "--agent",
        "scope",
        "--tick",
        "0",
    ];
    insta::assert_snapshot!("why_scope_nested", why_ok(&args));
    let r = why_json(&args);
    let rules = r["rules"].as_array().unwrap();
    let depths: Vec<u64> = rules.iter().map(|x| x["depth"].as_u64().unwrap()).collect();
    assert_eq!(depths, [1, 2, 3, 3]);
    assert_eq!(rules[1]["block_of"], "main:8");
    assert_eq!(rules[2]["module"], "show");
    assert_eq!(r["module"], "show");
}

/// The view server holds a `Why` and may answer from any thread.
#[test]
fn a_why_can_be_shared_between_threads() {
    fn shared<T: Send + Sync>() {}
    shared::<Why>();
}
