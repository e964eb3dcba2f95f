//! A scripted person plays a HumanBot beside two agent robots until the game is complete: the
//! person's requests go in through `Environment::input` (no browser), the HumanBot's agent
//! (`agents/bw4t/human.goal`) perceives each request and performs it, its e-partner's agent
//! (`agents/bw4t/epartner.goal`) tells it where it is, and the team (`team.goal`) hears what
//! the person says. Agents run in lock-step rounds as `goal run` runs them: every agent steps on
//! the tick's percepts, actions go to the environment in agent-name order, messages arrive in
//! the next round.

use goal::agent::{Agent, AgentConfig, Event, Message};
use goal::bw4t::world::BlockState;
use goal::bw4t::{map, Bw4t, Bw4tConfig, World};
use goal::env::thread::EnvInfo;
use goal::env::{ActionResult, Environment};
use goal::mas::environment::percept_types;
use goal::syntax::prolog::Reader;
use goal::term::Term;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Arc;

const HUMAN: &str = "Human1";
const MAX_ROUNDS: u64 = 30_000;
/// Rounds the person waits after a request before looking again (the agent needs one round
/// to perceive the request and act).
const PATIENCE: u64 = 3;

fn t(text: &str) -> Term {
    Reader::new("t").term(text, 0).expect("term").term
}

/// A person watching the map (as in the browser view) and clicking: carry the e-partner, go
/// to a room with a block of the colour needed now, walk up to it, pick it up, bring it to the
/// drop zone and put it down; say where they are going.
#[derive(Default)]
struct Person {
    wait_until: u64,
    /// Every request taken, and every refusal (with its reason).
    asked: Vec<String>,
    refused: Vec<String>,
}

impl Person {
    fn next(&self, w: &World) -> Vec<String> {
        let h = w.robot_index(HUMAN).expect("Human1 exists");
        let r = &w.robots[h];
        let zone = w.zone_at(&r.pos);
        let zone_name = zone.map(|z| w.zones[z].name.as_str());
        if w.sequence_index >= w.sequence.len() || !r.plan.is_empty() {
            return Vec::new();
        }
        if r.epartner.is_none() && w.epartners[0].holder.is_none() && r.stats.blocks_picked == 0 {
            return vec!["pickUpEPartner".into()];
        }
        if !r.holding.is_empty() {
            return vec![if zone_name == Some("DropZone") {
                "putDown".into()
            } else {
                "goTo('DropZone')".into()
            }];
        }
        let need = w.sequence[w.sequence_index];
        let wanted = |b: &&goal::bw4t::world::Block| {
            b.color == need && b.state == BlockState::Free && w.room_at(&b.pos).is_some()
        };
        let here = w
            .blocks
            .iter()
            .filter(wanted)
            .filter(|b| zone.is_some() && w.zone_at(&b.pos) == zone)
            .min_by(|a, b| (a.pos - r.pos).norm().total_cmp(&(b.pos - r.pos).norm()));
        if let Some(b) = here {
            return vec![if (b.pos - r.pos).norm() <= r.config.size + 1.0 {
                format!("pickUp({})", b.id)
            } else {
                format!("goToBlock({})", b.id)
            }];
        }
        let nearest = w
            .blocks
            .iter()
            .filter(wanted)
            .min_by(|a, b| (a.pos - r.pos).norm().total_cmp(&(b.pos - r.pos).norm()));
        match nearest.and_then(|b| w.room_at(&b.pos)) {
            Some(room) => {
                let name = &w.zones[room].name;
                vec![
                    format!("sendMessage(all, imp(in('{HUMAN}', '{name}')))"),
                    format!("goTo('{name}')"),
                ]
            }
            None => Vec::new(),
        }
    }

    fn play(&mut self, bw: &mut Bw4t, round: u64) {
        if round < self.wait_until {
            return;
        }
        for request in self.next(bw.world()) {
            match bw.input(HUMAN, &t(&request)) {
                Ok(()) => self.asked.push(request),
                Err(why) => self.refused.push(format!("{request}: {why}")),
            }
            self.wait_until = round + PATIENCE;
        }
    }
}

struct Game {
    bw: Bw4t,
    agents: BTreeMap<String, Agent>,
    /// Human1's trace events, as `goal run` writes them.
    human_events: Vec<Event>,
    printed: Vec<String>,
    failures: Vec<String>,
}

/// `agents/bw4t/humans.mas2g`: the programs `robot_team`, `human` and `epartner`.
fn system() -> goal::mas::MasSystem {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("agents/bw4t");
    goal::mas::system::load_mas(&dir.join("humans.mas2g"))
        .unwrap_or_else(|p| panic!("humans.mas2g loads: {:?}", p[0].render()))
}

fn setup() -> Game {
    let system = system();
    let m = map::builtin("banana").unwrap().unwrap();
    let bw = Bw4t::new(
        &m,
        &Bw4tConfig {
            robots: Some(2),
            humans: 1,
            epartners: 1,
            ..Bw4tConfig::default()
        },
    );
    let entities = bw.entities();
    let types = Arc::new(percept_types(&EnvInfo {
        entities: entities.clone(),
        declarations: bw.declarations(),
    }));
    let names: Vec<String> = entities.iter().map(|e| e.name.clone()).collect();
    let mut agents = BTreeMap::new();
    for (i, e) in entities.iter().enumerate() {
        let program = match e.kind.as_str() {
            "bot" => "robot_team",
            "human" => "human",
            "epartner" => "epartner",
            other => panic!("unexpected entity type {other}"),
        };
        let config = AgentConfig {
            seed: i as u64 + 1,
            agents: names.clone(),
            percept_types: types.clone(),
            ..AgentConfig::default()
        };
        let agent = Agent::new(system.programs[program].clone(), &e.name, config);
        agents.insert(e.name.clone(), agent);
    }
    Game {
        bw,
        agents,
        human_events: Vec::new(),
        printed: Vec::new(),
        failures: Vec::new(),
    }
}

impl Game {
    /// One lock-step round; returns the next round's messages.
    fn round(&mut self, inbox: BTreeMap<String, Vec<Message>>) -> BTreeMap<String, Vec<Message>> {
        let mut acted = Vec::new();
        let mut next: BTreeMap<String, Vec<Message>> = BTreeMap::new();
        for (name, agent) in &mut self.agents {
            let percepts = self.bw.percepts(name);
            let mail = inbox.get(name).cloned().unwrap_or_default();
            let out = agent.step(&percepts, &mail);
            if let Some(stop) = &out.stopped {
                panic!("{name} stopped: {stop:?}: {:?}", out.events);
            }
            if name == HUMAN {
                self.human_events.extend(out.events.iter().cloned());
                self.printed.extend(out.printed.iter().cloned());
            }
            for a in out.env_actions {
                acted.push((name.clone(), a));
            }
            for m in out.messages {
                next.entry(m.receiver.name().to_string())
                    .or_default()
                    .push(m);
            }
        }
        for (name, action) in acted {
            if let ActionResult::Failed(why) = self.bw.perform(&name, &action) {
                self.failures.push(format!("{name}: {action}: {why}"));
            }
        }
        next
    }
}

#[test]
fn a_scripted_person_and_two_agents_complete_the_game() {
    let mut game = setup();
    let mut person = Person::default();
    let mut inbox = BTreeMap::new();
    let mut rounds = 0;
    while !game.bw.is_finished() && rounds < MAX_ROUNDS {
        inbox = game.round(inbox);
        person.play(&mut game.bw, rounds);
        game.bw.tick();
        rounds += 1;
    }
    let stats = game.bw.run_stats();
    assert!(
        game.bw.is_finished(),
        "not finished after {rounds} rounds: {stats:?}\nasked {:?}\nrefused {:?}",
        person.asked,
        person.refused
    );
    assert!(game.failures.is_empty(), "{:?}", game.failures);
    // The person played a real part: Human1 delivered blocks.
    let human = stats.robots.iter().find(|r| r.name == HUMAN).unwrap();
    assert!(human.human);
    assert!(human.deliveries_right >= 1, "{stats:?}");

    // The trace of Human1: each request arrived as a percept and became the same action.
    let added: Vec<&str> = game
        .human_events
        .iter()
        .filter_map(|e| match e {
            Event::PerceptAdded { percept } => Some(percept.as_str()),
            _ => None,
        })
        .collect();
    let actions: Vec<&str> = game
        .human_events
        .iter()
        .filter_map(|e| match e {
            Event::EnvAction { action } => Some(action.as_str()),
            _ => None,
        })
        .collect();
    let said: Vec<&Event> = game
        .human_events
        .iter()
        .filter(|e| matches!(e, Event::MessageSent { .. }))
        .collect();
    for kind in [
        "pickUpEPartner",
        "goTo(",
        "goToBlock(",
        "pickUp(",
        "putDown",
    ] {
        assert!(
            actions.iter().any(|a| a.starts_with(kind)),
            "no {kind} action in {actions:?}"
        );
    }
    for a in &actions {
        assert!(
            added.contains(a),
            "{a} performed without its request percept"
        );
        let asked = person.asked.iter().any(|r| t(r).to_string() == *a);
        assert!(asked, "{a} was never asked for");
    }
    assert!(added
        .iter()
        .any(|p| p.starts_with("sendMessage(all,imp(in('Human1',")));
    assert!(!said.is_empty(), "the person's messages reach the team");
    // The GPS e-partner told its holder where it is.
    let from_epartner = added
        .iter()
        .filter(|p| p.starts_with("message('EPartner1',at('EPartner1',"))
        .count();
    assert!(from_epartner >= 1, "{added:?}");
    assert!(
        game.printed.iter().any(|l| l.contains("EPartner1")),
        "{:?}",
        game.printed
    );
    assert_eq!(stats.epartners[0].holder.as_deref(), Some(HUMAN));
}

/// The JSON lines of a trace file.
fn trace_lines(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .expect("trace written")
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

#[test]
fn with_nobody_playing_the_team_completes_the_game_and_the_human_stands_still() {
    let dir = std::env::temp_dir().join(format!("goal-humans-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (trace, stats) = (dir.join("run.jsonl"), dir.join("stats.json"));
    let mas = Path::new(env!("CARGO_MANIFEST_DIR")).join("agents/bw4t/humans.mas2g");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("run")
        .arg(&mas)
        .arg("--trace")
        .arg(&trace)
        .arg("--stats")
        .arg(&stats)
        .output()
        .expect("goal runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let lines = trace_lines(&trace);
    let agents: Vec<(&str, &str)> = lines[0]["agents"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| (a["name"].as_str().unwrap(), a["file"].as_str().unwrap()))
        .collect();
    let runs = |name: &str, file: &str| agents.iter().any(|(n, f)| *n == name && f.ends_with(file));
    assert!(runs("Human1", "agents/bw4t/human.goal"), "{agents:?}");
    assert!(runs("EPartner1", "agents/bw4t/epartner.goal"), "{agents:?}");
    // The scene: Human1 is drawn as a human, the e-partner lies where Human1 started.
    let first = lines.iter().find(|l| l["type"] == "world").unwrap();
    assert_eq!(first["set"]["robots/Human1/kind"], "human");
    assert_eq!(
        first["set"]["epartners/EPartner1/holder"],
        serde_json::Value::Null
    );
    assert_eq!(
        first["set"]["epartners/EPartner1/pos"],
        serde_json::json!([25.0, 61.0])
    );
    // Nobody asked Human1 for anything: it never acted.
    let human_actions = lines
        .iter()
        .filter(|l| l["type"] == "action" && l["agent"] == HUMAN)
        .count();
    assert_eq!(human_actions, 0);
    let stats: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&stats).unwrap()).unwrap();
    assert_eq!(stats["end"], "completed");
    let robots = stats["env"]["robots"].as_array().unwrap();
    let human = robots.iter().find(|r| r["name"] == HUMAN).unwrap();
    assert_eq!(human["human"], true);
    assert_eq!(human["distance"], 0.0);
    assert_eq!(stats["env"]["epartners"][0]["name"], "EPartner1");
    assert_eq!(
        stats["env"]["epartners"][0]["holder"],
        serde_json::Value::Null
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_dropped_epartner_tells_the_person_where_it_was_left_behind() {
    let mut game = setup();
    let mut inbox = BTreeMap::new();
    let mut rounds = |game: &mut Game, n: u64| {
        for _ in 0..n {
            inbox = game.round(std::mem::take(&mut inbox));
            game.bw.tick();
        }
    };
    rounds(&mut game, 2);
    game.bw.input(HUMAN, &t("pickUpEPartner")).unwrap();
    rounds(&mut game, 3);
    game.bw.input(HUMAN, &t("goTo('LeftHallD')")).unwrap();
    rounds(&mut game, 120);
    game.bw.input(HUMAN, &t("dropEPartner")).unwrap();
    rounds(&mut game, 4);
    assert!(game.failures.is_empty(), "{:?}", game.failures);
    let w = game.bw.world();
    assert_eq!(w.epartners[0].holder, None);
    assert!(w.epartners[0].left_behind);
    let told: Vec<&String> = game
        .printed
        .iter()
        .filter(|l| l.contains("leftBehind"))
        .collect();
    assert_eq!(
        told,
        ["message('EPartner1',leftBehind('EPartner1','LeftHallD'))"],
        "{:?}",
        game.printed
    );
}

#[test]
fn the_human_agent_sends_the_persons_messages_with_their_mood() {
    let program = system().programs["human"].clone();
    let config = AgentConfig {
        agents: vec!["Bot1".into(), "Bot2".into(), HUMAN.into()],
        ..AgentConfig::default()
    };
    let mut agent = Agent::new(program, HUMAN, config);
    let out = agent.step(
        &[
            t("sendMessage(all, int(at(_, 'RoomA1')))"),
            t("sendMessage('Bot2', imp(in('Bot2', 'RoomB1')))"),
            t("sendMessage(all, at('Yellow', 'RoomC1'))"),
        ],
        &[],
    );
    let mut sent: Vec<String> = out
        .messages
        .iter()
        .map(|m| format!("{}: {}", m.receiver, m.content))
        .collect();
    sent.sort();
    // Contents are kept mood-wrapped: `!X` is imp(X), `?X` is int(X); the question's open
    // subject stays a variable.
    assert_eq!(sent.len(), 5, "{sent:?}");
    assert_eq!(sent[0], "Bot1: at('Yellow','RoomC1')");
    assert!(sent[1].starts_with("Bot1: int(at(_"), "{sent:?}");
    assert!(sent[1].ends_with(",'RoomA1'))"), "{sent:?}");
    assert_eq!(sent[2], "Bot2: at('Yellow','RoomC1')");
    assert_eq!(sent[3], "Bot2: imp(in('Bot2','RoomB1'))");
    assert!(sent[4].starts_with("Bot2: int(at(_"), "{sent:?}");
}
