//! "Did you mean" for action and percept names: the closest known `name/arity`.

/// Edit distance between two short names (case differences count half, as a typo in case is
/// the most common slip: `goto` for `goTo`).
fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut prev: Vec<usize> = (0..=b.len()).map(|j| j * 2).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut row = vec![(i + 1) * 2];
        for (j, cb) in b.iter().enumerate() {
            let subst = if ca == cb {
                0
            } else if ca.eq_ignore_ascii_case(cb) {
                1
            } else {
                2
            };
            let v = (prev[j] + subst).min(prev[j + 1] + 2).min(row[j] + 2);
            row.push(v);
        }
        prev = row;
    }
    prev[b.len()]
}

/// The known `name/arity` closest to `name/arity`: same name in another case or arity, or a
/// name within a small edit distance. `None` when nothing is close.
pub fn did_you_mean<'k>(name: &str, arity: usize, known: &[&'k str]) -> Option<&'k str> {
    let split = |k: &'k str| -> (&'k str, usize) {
        match k.rsplit_once('/') {
            Some((n, a)) => (n, a.parse().unwrap_or(0)),
            None => (k, 0),
        }
    };
    // Only short names are compared (the table is tiny and names are identifiers).
    if name.len() > 64 {
        return None;
    }
    let limit = 2 * (1 + name.len() / 4);
    known
        .iter()
        .map(|k| {
            let (n, a) = split(k);
            let arity_cost = usize::from(a != arity);
            (distance(name, n) * 2 + arity_cost, *k)
        })
        .filter(|(d, _)| *d <= limit * 2 + 1)
        .min_by(|x, y| x.0.cmp(&y.0).then(x.1.cmp(y.1)))
        .map(|(_, k)| k)
}

/// The name among `known` closest to `name` (a place, a robot), within a small edit distance.
pub fn closest<'k>(name: &str, known: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    if name.len() > 64 {
        return None;
    }
    let limit = 2 * (1 + name.len() / 4);
    known
        .into_iter()
        .map(|k| (distance(name, k), k))
        .filter(|(d, _)| *d <= limit)
        .min_by(|x, y| x.0.cmp(&y.0).then(x.1.cmp(y.1)))
        .map(|(_, k)| k)
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
