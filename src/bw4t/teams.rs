//! Teams of robots for tournaments: which robots play for which team, and the deliveries
//! credited to each team.
//!
//! The init parameter `teams = [N1, N2, ...]` splits the robots in spawn order: the first `N1`
//! robots (`Bot1` .. `BotN1`) play for team 1, the next `N2` for team 2, and so on. All teams
//! play on the same map towards the same colour sequence; a block delivered by a robot is
//! credited to that robot's team (right or wrong, as for the robot itself). Without the
//! parameter there are no teams and nothing changes.

use super::stats::RobotStats;
use serde::Serialize;

/// The figures of one team.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct TeamStats {
    /// 1-based team number, in the order of the `teams` parameter.
    pub team: usize,
    /// Its robots' entity names.
    pub robots: Vec<String>,
    /// Blocks of the needed colour its robots delivered.
    pub deliveries_right: u64,
    /// Blocks of another colour its robots delivered.
    pub deliveries_wrong: u64,
}

/// The 1-based team of the robot at spawn index `robot`, given the team sizes.
pub fn team_of(sizes: &[usize], robot: usize) -> Option<usize> {
    let mut end = 0;
    for (t, n) in sizes.iter().enumerate() {
        end += n;
        if robot < end {
            return Some(t + 1);
        }
    }
    None
}

/// The statistics of every team, summed from its robots' statistics (in spawn order).
pub fn team_stats(sizes: &[usize], robots: &[RobotStats]) -> Vec<TeamStats> {
    let mut teams: Vec<TeamStats> = (1..=sizes.len())
        .map(|team| TeamStats {
            team,
            ..TeamStats::default()
        })
        .collect();
    for (i, r) in robots.iter().enumerate() {
        if let Some(t) = team_of(sizes, i) {
            let ts = &mut teams[t - 1];
            ts.robots.push(r.name.clone());
            ts.deliveries_right += r.deliveries_right;
            ts.deliveries_wrong += r.deliveries_wrong;
        }
    }
    teams
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn robots_are_split_in_spawn_order() {
        let sizes = [2, 1];
        assert_eq!(team_of(&sizes, 0), Some(1));
        assert_eq!(team_of(&sizes, 1), Some(1));
        assert_eq!(team_of(&sizes, 2), Some(2));
        assert_eq!(team_of(&sizes, 3), None);
    }

    #[test]
    fn deliveries_are_credited_to_the_robots_team() {
        let mut bots: Vec<RobotStats> = ["Bot1", "Bot2", "Bot3"]
            .iter()
            .map(|n| RobotStats::new(n))
            .collect();
        bots[0].deliveries_right = 2;
        bots[1].deliveries_wrong = 1;
        bots[2].deliveries_right = 3;
        let t = team_stats(&[2, 1], &bots);
        assert_eq!(t[0].robots, ["Bot1", "Bot2"]);
        assert_eq!((t[0].deliveries_right, t[0].deliveries_wrong), (2, 1));
        assert_eq!((t[1].deliveries_right, t[1].deliveries_wrong), (3, 0));
    }
}
