//! E-partners: devices a human-controlled robot can carry (entities `EPartner1`, ... of type
//! `epartner`, each with its own agent). Their functionalities are GPS (helps the holder navigate:
//! knows the rooms and the zone it is in) and Forget-me-not (knows who holds it and when it is
//! left behind). Humans pick them up and drop them with `pickUpEPartner`/`dropEPartner`; a held
//! e-partner moves with its holder. Their percepts and action follow the BW4T 3 interface
//! (docs/bw4t.md, "E-partners").

use super::geometry::Pos;
use super::map::{EPartnerSpec, Functionality};
use super::stats::EPartnerStats;
use super::world::World;
use crate::env::{ActionResult, PerceptDecl, PerceptFilter, PerceptType};
use crate::term::{Sym, Term};
use std::collections::VecDeque;

/// The actions e-partners understand, as `name/arity`.
pub const ACTIONS: &[&str] = &["sendMessage/2"];

/// The percept declarations of e-partner entities, in batch order.
pub fn declarations() -> Vec<PerceptDecl> {
    use PerceptType::*;
    let d = PerceptDecl::new;
    vec![
        d("ownName", 1, Once),
        d("getFunctionalities", 1, Once),
        d("getRooms", 1, Once),
        d("getRoom", 1, Once),
        d("getAt", 1, OnChange),
        d("getLocation", 2, OnChange),
        d("leftBehind", 1, OnChange),
        d("heldBy", 1, OnChangeWithNegation),
        d("isTaken", 0, OnChangeWithNegation),
        d("message", 2, Always),
    ]
}

/// An e-partner.
#[derive(Clone, Debug)]
pub struct EPartner {
    pub id: i64,
    /// Entity name, `EPartner1`, `EPartner2`, ...
    pub name: String,
    pub sym: Sym,
    pub pos: Pos,
    pub functionalities: Vec<Functionality>,
    /// The robot carrying it.
    pub holder: Option<usize>,
    /// Dropped by its holder and not picked up since.
    pub left_behind: bool,
    pub stats: EPartnerStats,
    pub(crate) inbox: VecDeque<(Sym, Term)>,
    pub(crate) filter: PerceptFilter,
    /// The room it lay in at the start (`getRoom` is sent once).
    start_room: Option<usize>,
}

impl EPartner {
    /// True when it has functionality `f`.
    pub fn has(&self, f: Functionality) -> bool {
        self.functionalities.contains(&f)
    }
}

impl World {
    /// Places the map's e-partners (after the robots, so their ids follow the robots' as in BW4T).
    pub fn place_epartners(&mut self, specs: &[EPartnerSpec]) {
        for spec in specs {
            let name = format!("EPartner{}", self.epartners.len() + 1);
            let pos = Pos::new(spec.x, spec.y);
            let mut functionalities = spec.functionalities.clone();
            functionalities.sort();
            functionalities.dedup();
            self.epartners.push(EPartner {
                id: self.next_id,
                sym: Sym::intern(&name),
                stats: EPartnerStats {
                    name: name.clone(),
                    functionalities: functionalities.iter().map(|f| f.name()).collect(),
                    ..EPartnerStats::default()
                },
                name,
                pos,
                functionalities,
                holder: None,
                left_behind: false,
                inbox: VecDeque::new(),
                filter: PerceptFilter::new(&declarations()),
                start_room: self.room_at(&pos),
            });
            self.next_id += 1;
        }
    }

    /// Adds `n` e-partners with both functionalities, as BW4T spawns them: at the position of
    /// each human-controlled robot in turn, then at the spawn points left; `Err` says how many
    /// found no place.
    pub fn add_epartners(&mut self, n: usize) -> Result<(), String> {
        let mut places: VecDeque<Pos> = self
            .robots
            .iter()
            .filter(|r| r.human)
            .map(|r| r.pos)
            .collect();
        places.extend(self.spawns.iter().copied());
        let mut specs = Vec::new();
        for _ in 0..n {
            let Some(p) = places.pop_front() else { break };
            if self.spawns.front() == Some(&p) {
                self.spawns.pop_front();
            }
            specs.push(EPartnerSpec {
                x: p.x,
                y: p.y,
                functionalities: Functionality::all(),
            });
        }
        self.place_epartners(&specs);
        match n - specs.len() {
            0 => Ok(()),
            missing => Err(format!(
                "map `{}` has no place left for {missing} e-partner(s) (they go to the humans, then to free spawn points): not created",
                self.map_name
            )),
        }
    }

    /// The index of the e-partner named `name`.
    pub fn epartner_index(&self, name: &str) -> Option<usize> {
        self.epartners.iter().position(|e| e.name == name)
    }

    /// Held e-partners move with their holders (after the robots stepped).
    pub(crate) fn carry_epartners(&mut self) {
        for e in &mut self.epartners {
            if let Some(r) = e.holder {
                e.pos = self.robots[r].pos;
            }
        }
    }

    /// `pickUpEPartner` for robot `r`: a human takes the nearest free e-partner within reach in
    /// its zone; for other robots nothing happens (as the interface says).
    pub(crate) fn pick_up_epartner(&mut self, r: usize) -> ActionResult {
        let robot = &self.robots[r];
        if !robot.human {
            return ActionResult::Ok;
        }
        if let Some(e) = robot.epartner {
            return ActionResult::fail(format!(
                "already carrying e-partner {} (drop it first with dropEPartner)",
                self.epartners[e].name
            ));
        }
        let zone = self.zone_at(&robot.pos);
        let reach = robot.config.size + 1.0;
        let nearest = (0..self.epartners.len())
            .filter(|&e| self.epartners[e].holder.is_none())
            .filter(|&e| self.zone_at(&self.epartners[e].pos) == zone)
            .map(|e| (e, (self.epartners[e].pos - robot.pos).norm()))
            .filter(|&(_, d)| d <= reach)
            .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
        let Some((e, _)) = nearest else {
            return ActionResult::fail(format!("no e-partner within reach ({reach} units)"));
        };
        let ep = &mut self.epartners[e];
        ep.holder = Some(r);
        ep.left_behind = false;
        ep.pos = self.robots[r].pos;
        ep.stats.picked_up += 1;
        self.robots[r].epartner = Some(e);
        ActionResult::Ok
    }

    /// `dropEPartner` for robot `r`: a human puts its e-partner down where it stands; for other
    /// robots nothing happens.
    pub(crate) fn drop_epartner(&mut self, r: usize) -> ActionResult {
        if !self.robots[r].human {
            return ActionResult::Ok;
        }
        let Some(e) = self.robots[r].epartner.take() else {
            return ActionResult::fail("not carrying an e-partner");
        };
        let ep = &mut self.epartners[e];
        ep.holder = None;
        ep.left_behind = true;
        ep.pos = self.robots[r].pos;
        ep.stats.dropped += 1;
        ActionResult::Ok
    }

    /// Performs `action` for e-partner `e` now.
    pub fn perform_epartner(&mut self, e: usize, action: &Term) -> ActionResult {
        match action.functor().map(|(n, a)| (n.name(), a)) {
            Some(("sendMessage", 2)) => {
                let args = action.args();
                match super::actions::name_arg(&args[0]) {
                    Some(to) => {
                        let from = self.epartners[e].sym;
                        let sent = self.deliver_message(from, None, to, &args[1]);
                        if sent.is_ok() {
                            self.epartners[e].stats.messages_sent += 1;
                        }
                        sent
                    }
                    None => ActionResult::fail(format!(
                        "sendMessage/2 expects a player name or `all`, got `{}`",
                        args[0]
                    )),
                }
            }
            _ => ActionResult::fail(crate::env::unknown_action(action, ACTIONS)),
        }
    }

    /// The full current truth of e-partner `e`'s percepts, grouped as [`declarations`];
    /// once-percepts only when `first`. Drains its inbox.
    fn epartner_percepts(&mut self, e: usize, first: bool) -> Vec<Vec<Term>> {
        let ep = &self.epartners[e];
        let gps = ep.has(Functionality::Gps);
        let fmn = ep.has(Functionality::ForgetMeNot);
        let c = |name: &str, args: Vec<Term>| Term::compound(name, args);
        let mut g: Vec<Vec<Term>> = Vec::with_capacity(10);
        if first {
            g.push(vec![c("ownName", vec![Term::Atom(ep.sym)])]);
            let fs = ep.functionalities.iter().map(|f| Term::atom(f.name()));
            g.push(vec![c(
                "getFunctionalities",
                vec![Term::list(fs.collect::<Vec<_>>())],
            )]);
            let rooms = self
                .zones
                .iter()
                .filter(|z| z.kind == super::map::ZoneKind::Room)
                .map(|z| Term::Atom(z.sym));
            g.push(if gps {
                vec![c("getRooms", vec![Term::list(rooms.collect::<Vec<_>>())])]
            } else {
                Vec::new()
            });
            let room = ep.start_room.map(|z| Term::Atom(self.zones[z].sym));
            g.push(room.map(|t| c("getRoom", vec![t])).into_iter().collect());
        } else {
            g.resize(4, Vec::new());
        }
        let at = self
            .nearest_zone(&ep.pos)
            .filter(|_| gps)
            .map(|z| c("getAt", vec![Term::Atom(self.zones[z].sym)]));
        g.push(at.into_iter().collect());
        g.push(vec![c(
            "getLocation",
            vec![Term::from(ep.pos.x), Term::from(ep.pos.y)],
        )]);
        let holder = ep.holder.map(|r| Term::Atom(self.robots[r].sym));
        if fmn {
            g.push(vec![c(
                "leftBehind",
                vec![Term::atom(bool_name(ep.left_behind))],
            )]);
            g.push(holder.map(|h| c("heldBy", vec![h])).into_iter().collect());
            g.push(if ep.holder.is_some() {
                vec![Term::atom("isTaken")]
            } else {
                Vec::new()
            });
        } else {
            g.resize(g.len() + 3, Vec::new());
        }
        let inbox = std::mem::take(&mut self.epartners[e].inbox);
        g.push(
            inbox
                .into_iter()
                .map(|(from, content)| c("message", vec![Term::Atom(from), content]))
                .collect(),
        );
        g
    }

    /// The next percept batch of e-partner `e`.
    pub fn epartner_batch(&mut self, e: usize) -> Vec<Term> {
        let first = self.epartners[e].filter.is_first();
        let groups = self.epartner_percepts(e, first);
        self.epartners[e].filter.batch_grouped(groups)
    }

    /// The `epartner(Id, Name, HolderId, Functionalities)` percepts of robot `r`: the
    /// e-partners lying in its zone and the one it carries (holder -1: nobody).
    pub(crate) fn visible_epartners(&self, r: usize) -> Vec<Term> {
        let robot = &self.robots[r];
        let zone = self.zone_at(&robot.pos);
        self.epartners
            .iter()
            .filter(|e| match e.holder {
                Some(h) => h == r,
                None => zone.is_some() && self.zone_at(&e.pos) == zone,
            })
            .map(|e| {
                let holder = e.holder.map_or(-1, |h| self.robots[h].id);
                let fs = e.functionalities.iter().map(|f| Term::atom(f.name()));
                Term::compound(
                    "epartner",
                    vec![
                        Term::Int(e.id),
                        Term::Atom(e.sym),
                        Term::Int(holder),
                        Term::list(fs.collect::<Vec<_>>()),
                    ],
                )
            })
            .collect()
    }
}

fn bool_name(b: bool) -> &'static str {
    if b {
        "true"
    } else {
        "false"
    }
}
