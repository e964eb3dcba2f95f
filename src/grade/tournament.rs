//! Tournaments: submissions against each other in BW4T, one team per submission on the same
//! map (init parameter `teams`, see [`crate::bw4t::teams`]), scored by the right deliveries
//! of each team.
//!
//! Every pair of runnable submissions meets on every map, team size (`--robots`) and seed,
//! twice: once as team 1 and once as team 2, since team 1 gets the first spawn points. The
//! pairings depend only on the submissions' names and the options, never on timing.

use super::run::RunResult;
use crate::env::EntityInfo;
use crate::mas::environment::{select_environment, Builtin};
use crate::mas::launch::{Launch, Launcher};
use crate::mas::MasSystem;
use crate::syntax::mas2g::ast::{AgentName, EntitySpec, LaunchInstruction, LaunchRule, Spanned};
use crate::term::Term;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};

/// One match: two submissions (indices into the class) as team 1 and team 2.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Match {
    pub teams: [usize; 2],
    pub map: String,
    /// Robots per team.
    pub robots: usize,
    pub seed: u64,
}

/// Every match of `players` (class indices, in class order) on the given maps, team sizes
/// and seeds.
pub fn pairings(players: &[usize], maps: &[String], robots: &[usize], seeds: &[u64]) -> Vec<Match> {
    let mut out = Vec::new();
    for (k, &a) in players.iter().enumerate() {
        for &b in &players[k + 1..] {
            for map in maps {
                for &n in robots {
                    for &seed in seeds {
                        for teams in [[a, b], [b, a]] {
                            out.push(Match {
                                teams,
                                map: map.clone(),
                                robots: n,
                                seed,
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// The entity names of team `t` (0-based) of `n` robots: robots are assigned in spawn order.
fn team_entities(t: usize, n: usize) -> Vec<EntityInfo> {
    (t * n + 1..=(t + 1) * n)
        .map(|i| EntityInfo {
            name: format!("Bot{i}"),
            kind: "bot".into(),
        })
        .collect()
}

/// One system in which each of `teams` controls its own `n` robots of a BW4T world with
/// teams. Each team's launch rules are applied to its own robots only (its agents keep the
/// names they would have alone; a name already taken by an earlier team gets `_2`, `_3`...),
/// its programs run as compiled, and the environment is the plain built-in BW4T with the
/// `teams` parameter (the map and seed come from the run options).
pub fn merge(teams: &[MasSystem], n: usize) -> Result<MasSystem, String> {
    let sizes = Term::list(vec![Term::Int(n as i64); teams.len()]);
    let params = BTreeMap::from([
        ("teams".to_string(), sizes),
        ("robots".to_string(), Term::Int((n * teams.len()) as i64)),
    ]);
    let env = select_environment("bw4t", &params)?;
    let mut merged = MasSystem {
        file: teams
            .iter()
            .map(|t| t.file.as_str())
            .collect::<Vec<_>>()
            .join(" vs "),
        env: Some(env),
        programs: BTreeMap::new(),
        files: BTreeMap::new(),
        rules: Vec::new(),
        warnings: Vec::new(),
        engines: BTreeMap::new(),
    };
    let mut taken = BTreeSet::new();
    for (t, sys) in teams.iter().enumerate() {
        if sys.env.as_ref().map(|e| e.kind) != Some(Builtin::Bw4t) {
            return Err(format!(
                "{} does not run in BW4T: tournaments are played in BW4T only",
                sys.file
            ));
        }
        let prefix = |r: &str| format!("team{}:{r}", t + 1);
        for (r, p) in &sys.programs {
            merged.programs.insert(prefix(r), p.clone());
        }
        for (r, f) in &sys.files {
            merged.files.insert(prefix(r), f.clone());
        }
        for (r, k) in &sys.engines {
            merged.engines.insert(prefix(r), *k);
        }
        let mut launcher = Launcher::new(&sys.rules);
        let mut launches = launcher.unconditional();
        for e in team_entities(t, n) {
            launches.extend(launcher.entity(&e).unwrap_or_default());
        }
        for l in launches {
            let name = unique(&mut taken, &l.name);
            merged
                .rules
                .push(fixed_rule(&name, &prefix(&l.reference), &l));
        }
    }
    Ok(merged)
}

/// `wanted`, or `wanted_2`, `wanted_3`... when it is taken.
fn unique(taken: &mut BTreeSet<String>, wanted: &str) -> String {
    let mut name = wanted.to_string();
    let mut k = 2;
    while taken.contains(&name) {
        name = format!("{wanted}_{k}");
        k += 1;
    }
    taken.insert(name.clone());
    name
}

/// A launch rule that launches exactly this agent (for its entity, if it has one).
fn fixed_rule(name: &str, reference: &str, l: &Launch) -> LaunchRule {
    let spanned = |s: &str| Spanned::new(s.to_string(), 0..0);
    LaunchRule {
        condition: l.entity.as_ref().map(|e| EntitySpec::Constraints {
            name: Some(spanned(e)),
            entity_type: None,
            max: None,
            span: 0..0,
        }),
        instructions: vec![LaunchInstruction {
            name: Some(AgentName::Given(spanned(name))),
            reference: spanned(reference),
            count: None,
            span: 0..0,
        }],
        span: 0..0,
    }
}

/// A submission's record over the tournament.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Standing {
    pub rank: usize,
    pub submission: String,
    pub matches: u64,
    pub wins: u64,
    pub draws: u64,
    pub losses: u64,
    /// Matches that ended on an error, a limit of memory or a kill (not scored as deliveries).
    pub broken: u64,
    /// Right deliveries of its team, over all matches: the score.
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
}

/// The header of the standings' CSV.
pub const CSV_HEADER: &[&str] = &[
    "rank",
    "submission",
    "matches",
    "wins",
    "draws",
    "losses",
    "broken",
    "deliveries_right",
    "deliveries_wrong",
];

impl Standing {
    /// The cells in [`CSV_HEADER`] order.
    pub fn cells(&self) -> Vec<String> {
        vec![
            self.rank.to_string(),
            self.submission.clone(),
            self.matches.to_string(),
            self.wins.to_string(),
            self.draws.to_string(),
            self.losses.to_string(),
            self.broken.to_string(),
            self.deliveries_right.to_string(),
            self.deliveries_wrong.to_string(),
        ]
    }
}

/// The standings of `names` (every player) after `matches` with their results: more right
/// deliveries first, then more wins, fewer wrong deliveries, then the name.
pub fn standings(names: &[String], matches: &[(Match, RunResult)]) -> Vec<Standing> {
    let mut by: BTreeMap<usize, Standing> = BTreeMap::new();
    for (m, r) in matches {
        let score = |t: usize| r.teams.get(t).copied().unwrap_or((0, 0));
        let (a, b) = (score(0), score(1));
        for (side, me, other) in [(0, a, b), (1, b, a)] {
            let s = by.entry(m.teams[side]).or_insert_with(|| Standing {
                rank: 0,
                submission: names[m.teams[side]].clone(),
                matches: 0,
                wins: 0,
                draws: 0,
                losses: 0,
                broken: 0,
                deliveries_right: 0,
                deliveries_wrong: 0,
            });
            s.matches += 1;
            s.deliveries_right += me.0;
            s.deliveries_wrong += me.1;
            if r.teams.is_empty() {
                s.broken += 1;
            } else if me.0 > other.0 {
                s.wins += 1;
            } else if me.0 == other.0 {
                s.draws += 1;
            } else {
                s.losses += 1;
            }
        }
    }
    let mut out: Vec<Standing> = by.into_values().collect();
    out.sort_by(|a, b| {
        b.deliveries_right
            .cmp(&a.deliveries_right)
            .then(b.wins.cmp(&a.wins))
            .then(a.deliveries_wrong.cmp(&b.deliveries_wrong))
            .then_with(|| a.submission.cmp(&b.submission))
    });
    for (i, s) in out.iter_mut().enumerate() {
        s.rank = i + 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pair_meets_on_both_sides() {
        let m = pairings(&[0, 2, 3], &["tiny".into()], &[1], &[1, 2]);
        // 3 pairs x 2 seeds x 2 sides.
        assert_eq!(m.len(), 12);
        assert_eq!(m[0].teams, [0, 2]);
        assert_eq!(m[1].teams, [2, 0]);
        assert_eq!(m[2].seed, 2);
        assert_eq!(m.last().unwrap().teams, [3, 2]);
    }

    #[test]
    fn team_entities_follow_spawn_order() {
        let names: Vec<String> = team_entities(1, 2).into_iter().map(|e| e.name).collect();
        assert_eq!(names, ["Bot3", "Bot4"]);
    }
}
