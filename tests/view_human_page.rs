//! A person plays a HumanBot in a real headless browser (Debian's chromium, driven over the
//! DevTools protocol with real mouse clicks on the page) while two agents play: they take the
//! robot (another browser then sees it taken), click a room, a block, pick it up and put it
//! down, click the drop zone, and send a message from the BW4T list; the team completes the
//! game. The trace shows the HumanBot's requests, percepts and actions, and `goal why` reruns
//! the game with the recorded requests and finds the same cycles. The page shows humans,
//! e-partners and who holds which, in the live run and in the replay of its trace.

mod cdp_support;
mod view_support;

use cdp_support::{Browser, Tab};
use serde_json::Value;
use std::time::{Duration, Instant};
use view_support::*;

const MINUTE: Duration = Duration::from_secs(60);

/// The HumanBot as the page's world has it now.
const ME: &str = "nest(view.model.head.world).robots.Human1";

/// True when point `p` (a JS expression) lies in zone `zone`'s rectangle.
fn inside(p: &str, zone: &str) -> String {
    format!(
        "(() => {{ const z = view.model.layout.zones.find((z) => z.name === {zone:?});
           const p = {p}; return !!p && p[0] >= z.rect[0] && p[0] <= z.rect[2]
           && p[1] >= z.rect[1] && p[1] <= z.rect[3]; }})()"
    )
}

/// The HumanBot's percepts (as its agent's mind on the page has them) include `percept`.
fn perceives(percept: &str) -> String {
    format!(
        "(() => {{ const m = view.model.head.minds.get('Human1');
           return !!m && m.percepts.has({percept:?}); }})()"
    )
}

/// The state of the latest of one's requests in the panel, e.g. `goTo('RoomB2'): applied ...`.
fn latest_request(tab: &mut Tab) -> String {
    tab.eval("(document.querySelector('#myrequests li') || {}).textContent || ''")
        .as_str()
        .unwrap_or("")
        .to_string()
}

/// Waits until the latest request `request` was applied; false when it was refused.
fn applied(tab: &mut Tab, request: &str) -> bool {
    let end = Instant::now() + MINUTE;
    loop {
        let last = latest_request(tab);
        if last.starts_with(&format!("{request}: applied")) {
            return true;
        }
        if last.starts_with(&format!("{request}: refused")) {
            eprintln!("refused (tried again): {last}");
            return false;
        }
        assert!(Instant::now() < end, "{request} never answered: {last}");
        std::thread::sleep(Duration::from_millis(100));
    }
}

/// Waits up to `limit` for `js`; false when it did not come true.
fn within(tab: &mut Tab, js: &str, limit: Duration) -> bool {
    let end = Instant::now() + limit;
    while Instant::now() < end {
        if tab.holds(js) {
            return true;
        }
        std::thread::sleep(Duration::from_millis(150));
    }
    false
}

/// Rooms with free blocks nobody is in, most blocks first.
fn free_rooms(tab: &mut Tab) -> Vec<String> {
    let v = tab.eval(
        "(() => { const w = nest(view.model.head.world); const occ = new Set(w.occupied || []);
           const out = [];
           for (const z of view.model.layout.zones) {
             if (z.kind !== 'room' || occ.has(z.name)) continue;
             let n = 0;
             for (const id in w.blocks || {}) { const b = w.blocks[id]; if (b.holder) continue;
               if (b.pos[0] >= z.rect[0] && b.pos[0] <= z.rect[2] && b.pos[1] >= z.rect[1] && b.pos[1] <= z.rect[3]) n++; }
             if (n) out.push([n, z.name]);
           }
           return out.sort((a, b) => b[0] - a[0]).map((x) => x[1]); })()",
    );
    serde_json::from_value(v).unwrap_or_default()
}

/// The ids of free blocks in `room`.
fn blocks_in(tab: &mut Tab, room: &str) -> Vec<String> {
    let v = tab.eval(&format!(
        "(() => {{ const w = nest(view.model.head.world);
           const z = view.model.layout.zones.find((z) => z.name === {room:?}); const out = [];
           for (const id in w.blocks || {{}}) {{ const b = w.blocks[id]; if (b.holder) continue;
             if (b.pos[0] >= z.rect[0] && b.pos[0] <= z.rect[2] && b.pos[1] >= z.rect[1] && b.pos[1] <= z.rect[3]) out.push(id); }}
           return out; }})()"
    ));
    serde_json::from_value(v).unwrap_or_default()
}

/// Clicks zone `zone` on the map until the HumanBot is in it (another robot may hold it).
fn go_to(tab: &mut Tab, zone: &str) -> bool {
    for _ in 0..4 {
        tab.click(&format!("#static rect.zone[data-name=\"{zone}\"]"));
        if applied(tab, &format!("goTo('{zone}')"))
            && within(
                tab,
                &format!(
                    "{} && {ME}.state === 'arrived'",
                    inside(&format!("{ME}.pos"), zone)
                ),
                MINUTE,
            )
        {
            return true;
        }
        std::thread::sleep(Duration::from_secs(2));
    }
    false
}

/// In a room: goes to one of its blocks, picks it up and puts it down again (in the room, so
/// the block stays in the game).
fn handle_a_block(tab: &mut Tab, room: &str) -> bool {
    for id in blocks_in(tab, room) {
        // A block under a robot cannot be seen, nor clicked.
        if !tab.try_click(&format!("#blocks rect.block[data-id=\"{id}\"]")) {
            continue;
        }
        if !applied(tab, &format!("goToBlock({id})"))
            || !within(tab, &perceives(&format!("atBlock({id})")), MINUTE)
        {
            continue;
        }
        tab.click("#pickup");
        if !applied(tab, &format!("pickUp({id})"))
            || !within(tab, &format!("{ME}.holding.includes({id})"), MINUTE)
        {
            continue;
        }
        tab.click("#putdown");
        assert!(applied(tab, "putDown"), "putting the block down");
        assert!(
            within(tab, &format!("{ME}.holding.length === 0"), MINUTE),
            "the block is put down"
        );
        return true;
    }
    false
}

#[test]
fn a_person_plays_a_humanbot_while_two_agents_play_and_the_team_completes_the_game() {
    let Some(chromium) = browser() else { return };
    let dir = scratch("play-page");
    let trace = dir.join("game.jsonl");
    let stats = dir.join("stats.json");
    let mut cmd = team_with_humans(2, 1, 40000);
    cmd.arg("--trace").arg(&trace).arg("--stats").arg(&stats);
    let mut served = Served::start(cmd);
    let url = served.url.clone();

    let mut person = Browser::launch(&chromium, &dir.join("person"));
    let mut tab = person.open(&url);
    let panel = "document.body.dataset.ready === '1' \
                 && document.querySelector('#humans button[data-entity=\"Human1\"]')";
    tab.wait_for(panel, "the player panel", MINUTE);
    tab.click("#humans button[data-entity=\"Human1\"]");
    tab.wait_for(
        "document.querySelector('#humans li.mine[data-entity=\"Human1\"]')",
        "Human1 taken",
        MINUTE,
    );

    // Somebody else, in another browser, sees Human1 taken and cannot take it.
    {
        let mut other = Browser::launch(&chromium, &dir.join("other"));
        let mut t2 = other.open(&url);
        t2.wait_for(panel, "the other player's panel", MINUTE);
        t2.wait_for(
            "document.querySelector('#humans li.taken[data-entity=\"Human1\"] button:disabled')",
            "Human1 shown as taken",
            MINUTE,
        );
    }

    // A room, a block in it (picked up and put down), the drop zone, out again.
    let mut done = false;
    for room in free_rooms(&mut tab) {
        if go_to(&mut tab, &room) && handle_a_block(&mut tab, &room) {
            done = true;
            break;
        }
    }
    assert!(done, "the person never handled a block");
    assert!(
        go_to(&mut tab, "DropZone"),
        "the person reached the drop zone"
    );
    assert!(
        go_to(&mut tab, "FrontDropZone"),
        "and left it for the agents"
    );

    // A message of the BW4T list to everybody.
    tab.choose("#msgpattern", "in(Me,Room)");
    tab.choose("#msgslots select[data-slot=\"Room\"]", "RoomA1");
    tab.click("#sendmsg");
    assert!(applied(&mut tab, "sendMessage(all,in('Human1','RoomA1'))"));
    tab.wait_for(
        "view.model.messages.some((m) => m.from === 'Human1')",
        "Human1's message",
        MINUTE,
    );
    tab.screenshot(&dir.join("play.png"));
    drop(tab);
    drop(person);

    // The agents finish the game (fast now: the person is done).
    let (status, _) = http("POST", &url, "/api/control?speed=100000");
    assert_eq!(status, 200);
    served.wait_line(|l| l.contains("the run is over"), 10 * MINUTE);
    assert_eq!(served.interrupt(), Some(0), "the game was completed");
    let st: Value = serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(st["completed"], true, "{st}");

    // The trace: the requests taken, the HumanBot's request percepts, its actions, its message.
    let recs = records(&trace);
    let inputs: Vec<&Value> = recs.iter().filter(|r| r["type"] == "input").collect();
    let requests: Vec<&str> = inputs
        .iter()
        .filter(|r| r["result"] == "ok")
        .map(|r| r["request"].as_str().unwrap())
        .collect();
    for want in [
        "goTo('DropZone')",
        "putDown",
        "sendMessage(all,in('Human1','RoomA1'))",
    ] {
        assert!(requests.contains(&want), "{want} in {requests:?}");
    }
    assert!(requests.iter().any(|r| r.starts_with("pickUp(")));
    let percepts: Vec<&str> = recs
        .iter()
        .filter(|r| r["type"] == "cycle" && r["agent"] == "Human1")
        .flat_map(|r| r["events"].as_array().unwrap())
        .filter(|e| e["event"] == "percept_added")
        .map(|e| e["percept"].as_str().unwrap())
        .collect();
    assert!(percepts.contains(&"goTo('DropZone')"), "{percepts:?}");
    let actions: Vec<(&str, u64)> = recs
        .iter()
        .filter(|r| r["type"] == "action" && r["agent"] == "Human1" && r["result"] == "ok")
        .map(|r| (r["action"].as_str().unwrap(), r["tick"].as_u64().unwrap()))
        .collect();
    assert!(
        actions.iter().any(|a| a.0 == "goTo('DropZone')"),
        "{actions:?}"
    );
    let picked = actions
        .iter()
        .find(|a| a.0.starts_with("pickUp("))
        .expect("Human1 picked up a block");
    assert!(recs
        .iter()
        .any(|r| r["type"] == "message" && r["from"] == "Human1"));

    // goal why reruns the game with the recorded requests: Human1's cycle that picked the
    // block up is there again, firing the rules the trace recorded.
    let why = goal()
        .args(["why"])
        .arg(&trace)
        .args(["--agent", "Human1", "--tick", &picked.1.to_string()])
        .output()
        .unwrap();
    let (out, err) = (
        String::from_utf8_lossy(&why.stdout),
        String::from_utf8_lossy(&why.stderr),
    );
    assert_eq!(why.status.code(), Some(0), "{out}{err}");
    assert!(out.contains("FIRED"), "{out}");
    assert!(out.contains("pickUp"), "the rule that picked up: {out}");
    assert!(!err.contains("other rules"), "{err}");
}

/// The people list's entry for `name`, as the page shows it.
fn person(tab: &mut Tab, name: &str) -> String {
    tab.eval(&format!(
        "(document.querySelector('#people li[data-name=\"{name}\"]') || {{}}).textContent || ''"
    ))
    .as_str()
    .unwrap_or("")
    .to_string()
}

#[test]
fn the_page_shows_who_holds_which_e_partner_live_and_in_the_replay() {
    let Some(chromium) = browser() else { return };
    let dir = scratch("play-epartner");
    let trace = dir.join("game.jsonl");
    let mas = concat!(env!("CARGO_MANIFEST_DIR"), "/agents/bw4t/humans.mas2g");
    let mut cmd = goal();
    cmd.args(["run", mas, "--view", "127.0.0.1:0", "--max-ticks", "3000"])
        .arg("--trace")
        .arg(&trace);
    let mut served = Served::start(cmd);
    let url = served.url.clone();

    let mut person_browser = Browser::launch(&chromium, &dir.join("person"));
    let mut tab = person_browser.open(&url);
    tab.wait_for(
        "document.querySelector('#humans button[data-entity=\"Human1\"]') \
         && document.querySelector('#people li[data-name=\"EPartner1\"]')",
        "the player panel and the e-partner",
        MINUTE,
    );
    assert!(person(&mut tab, "EPartner1").contains("lying free"));
    assert!(person(&mut tab, "EPartner1").contains("GPS"));
    assert!(person(&mut tab, "Human1").contains("human"));
    tab.click("#humans button[data-entity=\"Human1\"]");
    tab.wait_for(
        "document.querySelector('#humans li.mine[data-entity=\"Human1\"]')",
        "Human1 taken",
        MINUTE,
    );
    tab.click("#eppick");
    assert!(applied(&mut tab, "pickUpEPartner"));
    tab.wait_for(
        "document.querySelector('#people li[data-name=\"EPartner1\"][data-holder=\"Human1\"]')",
        "EPartner1 held by Human1",
        MINUTE,
    );
    assert!(person(&mut tab, "EPartner1").contains("held by Human1"));
    assert!(person(&mut tab, "Human1").contains("carries e-partner EPartner1"));
    assert!(tab
        .holds("document.querySelector('#dynamic circle.epartner-mark[data-name=\"EPartner1\"]')"));
    drop(tab);
    drop(person_browser);
    let (status, _) = http("POST", &url, "/api/control?speed=100000");
    assert_eq!(status, 200);
    served.wait_line(|l| l.contains("the run is over"), 10 * MINUTE);
    drop(served);

    let recs = records(&trace);
    assert!(
        recs.iter().any(|r| r["type"] == "action"
            && r["agent"] == "Human1"
            && r["action"] == "pickUpEPartner"
            && r["result"] == "ok"),
        "Human1 picked the e-partner up"
    );

    // The trace replays: at its end the page shows the same holder and the request taken.
    let mut cmd = goal();
    cmd.arg("view").arg(&trace);
    let replay = Served::start(cmd);
    let mut viewer = Browser::launch(&chromium, &dir.join("viewer"));
    let mut tab = viewer.open(&format!("{}?tick=1000000", replay.url));
    tab.wait_for(
        "document.querySelector('#people li[data-name=\"EPartner1\"][data-holder=\"Human1\"]')",
        "EPartner1 held by Human1 in the replay",
        MINUTE,
    );
    assert!(person(&mut tab, "Human1").contains("carries e-partner EPartner1"));
    tab.wait_for(
        "Array.from(document.querySelectorAll('#inputs li')).some((l) => l.textContent.includes('Human1: pickUpEPartner'))",
        "the request in the replay's list",
        MINUTE,
    );
    assert!(
        tab.holds("document.querySelector('#playlive').hidden"),
        "nobody plays a replay"
    );
}
