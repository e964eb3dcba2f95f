//! A person's requests for a human-controlled robot (a HumanBot, entity type `human`).
//!
//! In BW4T a person steers a HumanBot through a GUI; each choice reaches the GOAL agent coupled
//! to that robot as a percept ("sent every time the user selects the action"), and the agent
//! performs the action (the shipped `agents/bw4t/human.goal`). Here a request comes in through
//! [`crate::env::Environment::input`], is checked against the world now (so a person hears at
//! once why it cannot be done), queued, and delivered in the robot's next percept batch only.

use super::world::World;
use crate::env::{PerceptDecl, PerceptType};
use crate::term::{Sym, Term};

/// Requests that may wait for the next batch per robot; more are refused.
pub const MAX_REQUESTS: usize = 100;

/// The request percepts of human-controlled robots as `name/arity`: the interface's HumanBot
/// percepts (`goTo`, `goToBlock`, `pickUp`, `putDown`, `sendMessage`, `getEPartners`) and the
/// further choices of BW4T's human GUI (`navigateObstacles`, `pickUpEPartner`, `dropEPartner`).
pub const REQUESTS: &[&str] = &[
    "goTo/1",
    "goTo/2",
    "goToBlock/1",
    "pickUp/1",
    "putDown/0",
    "sendMessage/2",
    "getEPartners/0",
    "navigateObstacles/0",
    "pickUpEPartner/0",
    "dropEPartner/0",
];

/// True for the one request that may keep variables: a question of the message list to a named
/// receiver (`sendMessage(all, int(at(_, Room)))`), as an agent's interrogative send may leave
/// what it asks about open. Everything else a person asks for names its things.
pub fn may_stay_open(request: &Term) -> bool {
    request.is_functor(Sym::intern("sendMessage"), 2)
        && request.args()[0].is_ground()
        && request.args()[1].is_functor(Sym::intern("int"), 1)
}

/// The declarations of the request percepts: each request is in exactly one batch (the next),
/// which is an always-percept of the requests made since the last batch.
pub fn declarations() -> Vec<PerceptDecl> {
    REQUESTS
        .iter()
        .filter_map(|r| r.split_once('/'))
        .map(|(name, arity)| {
            PerceptDecl::new(name, arity.parse().unwrap_or(0), PerceptType::Always)
        })
        .collect()
}

impl World {
    /// Queues `request` for robot `r`, to be perceived in its next batch; `Err` says why not.
    pub fn request(&mut self, r: usize, request: &Term) -> Result<(), String> {
        let robot = &self.robots[r];
        if !robot.human {
            return Err(format!(
                "`{}` is a robot controlled by an agent; only human-controlled robots ({}) take requests",
                robot.name,
                self.human_names().join(", ")
            ));
        }
        let Some((name, arity)) = request.functor() else {
            return Err(unknown_request(request));
        };
        let key = format!("{}/{arity}", name.name());
        if !REQUESTS.contains(&key.as_str()) {
            return Err(unknown_request(request));
        }
        if !request.is_ground() && !may_stay_open(request) {
            return Err(format!("request `{request}` has unbound variables"));
        }
        if robot.requests.len() >= MAX_REQUESTS {
            return Err(format!(
                "{} has {MAX_REQUESTS} requests waiting for its agent; try again later",
                robot.name
            ));
        }
        self.check_request(r, key.as_str(), request)?;
        self.robots[r].requests.push_back(request.clone());
        Ok(())
    }

    /// Whether the action a request asks for can be done now: the request is tried on a copy of
    /// the world, so a request is refused for exactly the reasons the action would be.
    fn check_request(&self, r: usize, key: &str, request: &Term) -> Result<(), String> {
        match key {
            "getEPartners/0" => return Ok(()),
            "sendMessage/2" => {
                let content = &request.args()[1];
                if super::messages::describe_from(Some(&self.robots[r].name), content).is_none() {
                    return Err(format!(
                        "`{content}` is not a message of the BW4T message list"
                    ));
                }
            }
            _ => {}
        }
        let mut probe = self.clone();
        match probe.perform(r, request) {
            crate::env::ActionResult::Ok => Ok(()),
            crate::env::ActionResult::Failed(why) => Err(format!("{}: {why}", self.robots[r].name)),
        }
    }

    /// The names of the human-controlled robots.
    pub fn human_names(&self) -> Vec<&str> {
        self.robots
            .iter()
            .filter(|r| r.human)
            .map(|r| r.name.as_str())
            .collect()
    }

    /// Robot `r`'s waiting requests grouped as [`declarations`] (drained).
    pub(crate) fn request_groups(&mut self, r: usize) -> Vec<Vec<Term>> {
        let decls = declarations();
        let mut groups = vec![Vec::new(); decls.len()];
        for t in std::mem::take(&mut self.robots[r].requests) {
            let at = t.functor().and_then(|(n, a)| {
                decls
                    .iter()
                    .position(|d| d.name == n.name() && d.arity == a)
            });
            if let Some(i) = at {
                groups[i].push(t);
            }
        }
        groups
    }
}

fn unknown_request(request: &Term) -> String {
    let known = REQUESTS.join(", ");
    match request.functor() {
        Some((name, arity)) => match crate::env::did_you_mean(name.name(), arity, REQUESTS) {
            Some(k) => format!(
                "unknown request {}/{arity} (did you mean {k}?)",
                name.name()
            ),
            None => format!(
                "unknown request {}/{arity}; a person can ask for {known}",
                name.name()
            ),
        },
        None => format!("`{request}` is not a request; a person can ask for {known}"),
    }
}
