//! The shipped default system of `goal run` without a file: the reference BW4T team
//! (`agents/bw4t/bw4t.mas2g` and the agent files it names) on the default map, built into the
//! binary so it runs from any directory.

use super::system::{from_mas_text, MasSystem, Origin, Problem};

/// The `.mas2g` text of the default team.
pub const MAS: &str = include_str!("../../agents/bw4t/bw4t.mas2g");

/// The agent files the default `.mas2g` names (path relative to it, text).
pub const FILES: &[(&str, &str)] = &[
    ("team.goal", include_str!("../../agents/bw4t/team.goal")),
    ("robot.goal", include_str!("../../agents/bw4t/robot.goal")),
    ("human.goal", include_str!("../../agents/bw4t/human.goal")),
];

/// The default system (parsed and compiled from the built-in text).
pub fn system() -> Result<MasSystem, Vec<Problem>> {
    from_mas_text("<built-in>/bw4t.mas2g", MAS, Origin::Embedded(FILES))
}
