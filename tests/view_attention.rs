//! The agent panel shows goals per attention set in a real headless browser (chromium over the
//! DevTools protocol, real clicks): a picker works in a module with `focus=new` while alice
//! counts beside it. After clicking the picker, the panel shows two goal sets (pickUp's, the
//! current one, first; then the top-level base) at ticks inside the module and one after it
//! returns, whichever way the timeline moves, in a replay and in a live run.

mod cdp_support;
mod view_support;

use cdp_support::{Browser, Tab};
use serde_json::{json, Value};
use std::time::Duration;
use view_support::*;

const MINUTE: Duration = Duration::from_secs(60);
const MAS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/attention/attention.mas2g"
);

/// The goal sets the panel shows, top to bottom: `[label, current, [goals]]`.
fn goal_sets(tab: &mut Tab) -> Value {
    tab.eval(
        "Array.from(document.querySelectorAll('#goals .goalset')).map((s) => [
           s.querySelector('h4 span').textContent, s.classList.contains('current'),
           Array.from(s.querySelectorAll('li')).map((l) => l.textContent)])",
    )
}

/// Moves the timeline to `tick` with the tick box, as a person types it, and waits for the page.
fn seek(tab: &mut Tab, tick: u64) {
    tab.choose("#tick", &tick.to_string());
    tab.wait_for(
        &format!("document.body.dataset.tick === '{tick}'"),
        "the page at the tick",
        MINUTE,
    );
}

/// What the picker's panel shows at ticks inside pickUp (0 to 2) and after it (3, 4).
fn expected(tick: u64) -> Value {
    let base = |goals: Value| json!(["main (base)", false, goals]);
    match tick {
        0 => json!([
            ["pickUp [focus=new]", true, ["near(box)"]],
            base(json!(["delivered(box)"]))
        ]),
        1 => json!([
            ["pickUp [focus=new]", true, ["holding(box)"]],
            base(json!(["delivered(box)"]))
        ]),
        2 => json!([
            ["pickUp [focus=new]", true, []],
            base(json!(["delivered(box)"]))
        ]),
        _ => json!([["main (base)", true, ["delivered(box)"]]]),
    }
}

/// Clicks the picker in the agent list and moves the timeline back and forth over pickUp.
fn check_panel(tab: &mut Tab) {
    tab.wait_for("document.body.dataset.ready === '1'", "the page", MINUTE);
    assert_eq!(
        tab.eval("document.getElementById('mindname').textContent"),
        json!("alice"),
        "the first agent is shown first"
    );
    assert_eq!(
        goal_sets(tab),
        json!([["main (base)", true, ["count(1000000)"]]]),
        "alice has the top-level base only"
    );
    assert!(
        tab.holds("document.getElementById('world').getBoundingClientRect().height === 0"),
        "a run without environment draws no empty world"
    );
    tab.click("#agents li[data-name=picker]");
    tab.wait_for(
        "document.getElementById('mindname').textContent === 'picker'",
        "the picker's panel",
        MINUTE,
    );
    for tick in [4, 1, 0, 3, 2, 4, 1] {
        seek(tab, tick);
        assert_eq!(goal_sets(tab), expected(tick), "at tick {tick}");
    }
    assert_eq!(
        tab.eval("document.getElementById('ngoals').textContent"),
        json!("(2)"),
        "two goals in all at tick 1"
    );
}

#[test]
fn the_panel_shows_the_attention_stack_in_a_replay() {
    let Some(chromium) = browser() else { return };
    let dir = scratch("attention-replay");
    let trace = dir.join("attention.jsonl");
    let code = record(&[MAS, "--max-cycles", "30"], &trace);
    assert_eq!(code, Some(3), "the run stops at its cycle limit");
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let served = Served::start(cmd);
    let mut b = Browser::launch(&chromium, &dir.join("profile"));
    let mut tab = b.open(&format!("{}?tick=6", served.url));
    check_panel(&mut tab);
    tab.screenshot(&dir.join("attention.png"));
    drop(tab);
    drop(b);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_panel_shows_the_attention_stack_in_a_live_run() {
    let Some(chromium) = browser() else { return };
    let dir = scratch("attention-live");
    let mut cmd = goal();
    cmd.args(["run", MAS, "--max-cycles", "3000", "--view"]);
    let served = Served::start(cmd);
    // The run is paced for watching; the picker is done by round 6.
    served.wait_for_tick(10);
    let mut b = Browser::launch(&chromium, &dir.join("profile"));
    let mut tab = b.open(&served.url);
    // The agent list stays put while the run goes on: an element replaced between a press
    // and its release loses the click.
    tab.wait_for("document.body.dataset.ready === '1'", "the page", MINUTE);
    tab.eval("window.before = [document.body.dataset.tick, document.querySelector('#agents li')]");
    tab.wait_for(
        "document.body.dataset.tick !== window.before[0]",
        "a new tick drawn",
        MINUTE,
    );
    assert!(
        tab.holds("document.querySelector('#agents li') === window.before[1]"),
        "the agent list was drawn anew although it shows the same"
    );
    check_panel(&mut tab);
    assert_eq!(
        tab.eval("view.info.mode"),
        json!("live"),
        "the page follows the live run"
    );
    drop(tab);
    drop(b);
    let _ = std::fs::remove_dir_all(&dir);
}
