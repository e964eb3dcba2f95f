//! Block colours: the nine of the BW4T 3 interface and `DarkGray`, which colour-blind robots see.

use serde::{Deserialize, Serialize};

/// A block colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
pub enum Color {
    Blue,
    Cyan,
    Magenta,
    Orange,
    Red,
    White,
    Green,
    Yellow,
    Pink,
    DarkGray,
}

impl Color {
    /// Every colour, in declaration order.
    pub const ALL: [Color; 10] = [
        Color::Blue,
        Color::Cyan,
        Color::Magenta,
        Color::Orange,
        Color::Red,
        Color::White,
        Color::Green,
        Color::Yellow,
        Color::Pink,
        Color::DarkGray,
    ];

    /// The colours random maps draw from (those of BW4T's map generator).
    pub const RANDOM: [Color; 7] = [
        Color::Red,
        Color::Orange,
        Color::Yellow,
        Color::Green,
        Color::Blue,
        Color::Pink,
        Color::White,
    ];

    /// The name used in percepts and TOML maps, e.g. `Red`, `DarkGray`.
    pub fn name(self) -> &'static str {
        match self {
            Color::Blue => "Blue",
            Color::Cyan => "Cyan",
            Color::Magenta => "Magenta",
            Color::Orange => "Orange",
            Color::Red => "Red",
            Color::White => "White",
            Color::Green => "Green",
            Color::Yellow => "Yellow",
            Color::Pink => "Pink",
            Color::DarkGray => "DarkGray",
        }
    }

    /// Parses a colour name in any case, with or without `_` (`Red`, `RED`, `DARK_GRAY`, `Dark_gray`).
    pub fn parse(text: &str) -> Option<Color> {
        let key: String = text
            .chars()
            .filter(|c| *c != '_' && *c != ' ')
            .flat_map(char::to_lowercase)
            .collect();
        let key = if key == "darkgrey" {
            "darkgray".to_string()
        } else {
            key
        };
        Color::ALL
            .into_iter()
            .find(|c| c.name().to_lowercase() == key)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_java_and_project_spellings() {
        assert_eq!(Color::parse("RED"), Some(Color::Red));
        assert_eq!(Color::parse("DARK_GRAY"), Some(Color::DarkGray));
        assert_eq!(Color::parse("Dark_gray"), Some(Color::DarkGray));
        assert_eq!(Color::parse("Magenta"), Some(Color::Magenta));
        assert_eq!(Color::parse("Purple"), None);
    }
}
