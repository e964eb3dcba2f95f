//! "Did you mean" for action and percept names written `name/arity`, through the shared
//! [`crate::suggest`].

/// The known `name/arity` closest to `name/arity`: same name in another case or arity, or a
/// name within a small edit distance. `None` when nothing is close.
pub fn did_you_mean<'k>(name: &str, arity: usize, known: &[&'k str]) -> Option<&'k str> {
    let split = |k: &'k str| -> (&'k str, usize) {
        match k.rsplit_once('/') {
            Some((n, a)) => (n, a.parse().unwrap_or(0)),
            None => (k, 0),
        }
    };
    let (n, a) = crate::suggest::closest_arity(name, arity, known.iter().map(|k| split(k)))?;
    known.iter().copied().find(|k| split(k) == (n, a))
}

/// The name among `known` closest to `name` (a place, a robot), within a small edit distance.
pub fn closest<'k>(name: &str, known: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    crate::suggest::closest(name, known)
}

/// The failure reason for an action the environment does not know, with a suggestion.
pub fn unknown_action(action: &crate::term::Term, known: &[&str]) -> String {
    let Some((name, arity)) = action.functor() else {
        return format!(
            "`{action}` is not an action; the entity understands {}",
            known.join(", ")
        );
    };
    match did_you_mean(name.name(), arity, known) {
        Some(k) => format!("unknown action {}/{arity} (did you mean {k}?)", name.name()),
        None => format!(
            "unknown action {}/{arity}; the entity understands {}",
            name.name(),
            known.join(", ")
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BW: &[&str] = &["goTo/1", "goTo/2", "goToBlock/1", "pickUp/1", "putDown/0"];

    #[test]
    fn suggests_case_and_arity_slips() {
        assert_eq!(did_you_mean("goto", 1, BW), Some("goTo/1"));
        assert_eq!(did_you_mean("pickup", 1, BW), Some("pickUp/1"));
        assert_eq!(did_you_mean("putDown", 1, BW), Some("putDown/0"));
        assert_eq!(did_you_mean("gotoblock", 1, BW), Some("goToBlock/1"));
        assert_eq!(did_you_mean("fly", 3, BW), None);
        assert_eq!(closest("roomA1", ["RoomA1", "RoomB1"]), Some("RoomA1"));
        assert_eq!(closest("Kitchen", ["RoomA1"]), None);
    }
}
