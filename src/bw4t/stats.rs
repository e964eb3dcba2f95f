//! Run statistics: deliveries, drops and per-robot figures, serializable for a `--stats` file.

use serde::Serialize;

/// Statistics of one robot.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RobotStats {
    pub name: String,
    /// Controlled by a person (entity type `human`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub human: bool,
    /// Units travelled.
    pub distance: f64,
    /// Times the robot's centre entered a room (including the drop zone).
    pub rooms_entered: u64,
    /// Ticks without a plan to follow (arrived or collided).
    pub idle_ticks: u64,
    pub blocks_picked: u64,
    pub deliveries_right: u64,
    pub deliveries_wrong: u64,
    pub messages_sent: u64,
}

impl RobotStats {
    /// Empty statistics for the robot `name`.
    pub fn new(name: &str) -> RobotStats {
        RobotStats {
            name: name.to_string(),
            ..RobotStats::default()
        }
    }
}

/// Statistics of a run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RunStats {
    pub map: String,
    pub ticks: u64,
    /// Blocks of the needed colour put down in the drop zone.
    pub deliveries_right: u64,
    /// Blocks of another colour put down in the drop zone (they are lost).
    pub deliveries_wrong: u64,
    /// Blocks put down in the drop zone after the sequence was complete.
    pub dropped_after_completion: u64,
    /// Blocks put down in rooms (they stay there).
    pub dropped_in_rooms: u64,
    /// Blocks put down outside rooms and the drop zone (they are lost).
    pub dropped_elsewhere: u64,
    pub sequence_length: usize,
    pub sequence_index: usize,
    /// The tick at which the last block of the sequence was delivered.
    pub finished_at_tick: Option<u64>,
    pub robots: Vec<RobotStats>,
    /// The e-partners, when the map has any.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub epartners: Vec<EPartnerStats>,
    /// Deliveries per team, when the run has teams (init `teams`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub teams: Vec<super::teams::TeamStats>,
}

/// Statistics of one e-partner.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct EPartnerStats {
    pub name: String,
    /// `GPS`, `Forget-me-not`.
    pub functionalities: Vec<&'static str>,
    /// Times a human picked it up.
    pub picked_up: u64,
    /// Times a human dropped it.
    pub dropped: u64,
    pub messages_sent: u64,
    /// Who holds it at the end (`None`: lying on the map).
    pub holder: Option<String>,
}
