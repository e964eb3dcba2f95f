//! "Did you mean": the one function every lookup of a name uses to suggest a known name when
//! the one written is unknown (actions, predicates, modules, macros, agents, maps, percepts,
//! test names, command-line values).
//!
//! Names are compared by edit distance where a difference in case costs half an edit (`goto`
//! for `goTo` is the most common slip); a same-name candidate with another arity comes first.

/// Edit distance in half edits: a substitution that only changes case costs 1, every other
/// edit 2.
fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut prev: Vec<usize> = (0..=b.len()).map(|j| j * 2).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut row = Vec::with_capacity(b.len() + 1);
        row.push((i + 1) * 2);
        for (j, cb) in b.iter().enumerate() {
            let subst = if ca == cb {
                0
            } else if ca.to_lowercase().eq(cb.to_lowercase()) {
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

/// Longest name compared (names are identifiers; this bounds the work on hostile input).
const MAX_NAME: usize = 64;

/// Most half edits for a typo in a name of `len` characters: 1 edit up to 3 characters, 2 up
/// to 7, 3 beyond (a name entirely in another case always qualifies).
fn limit(len: usize) -> usize {
    2 * match len {
        0..=3 => 1,
        4..=7 => 2,
        _ => 3,
    }
}

/// The known name closest to `name`, if one is close enough to be a likely typo; `None` when
/// `name` itself is known.
pub fn closest<'k>(name: &str, known: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    closest_arity(name, 0, known.into_iter().map(|k| (k, 0))).map(|(k, _)| k)
}

/// The known `name/arity` closest to `name/arity`: the same name with another arity or in
/// another case, or a near name (same arity preferred). `None` when nothing is close or the
/// name/arity itself is known.
pub fn closest_arity<'k>(
    name: &str,
    arity: usize,
    known: impl IntoIterator<Item = (&'k str, usize)>,
) -> Option<(&'k str, usize)> {
    let n = name.chars().count();
    if n > MAX_NAME {
        return None;
    }
    let max = limit(n).max(n);
    let mut best: Option<(usize, bool, &'k str, usize)> = None;
    for (k, a) in known {
        if k == name && a == arity {
            return None;
        }
        if k.chars().count() > MAX_NAME {
            continue;
        }
        let d = distance(name, k);
        let case_only = d <= n && k.to_lowercase() == name.to_lowercase();
        if d > limit(n) && !case_only || d > max {
            continue;
        }
        let key = (d, a != arity, k, a);
        if best.is_none_or(|b| (key.0, key.1, key.2, key.3) < (b.0, b.1, b.2, b.3)) {
            best = Some(key);
        }
    }
    best.map(|(_, _, k, a)| (k, a))
}

/// `" (did you mean `x`?)"` for the closest known name, or the empty string.
pub fn hint<'k>(name: &str, known: impl IntoIterator<Item = &'k str>) -> String {
    closest(name, known)
        .map(|k| format!(" (did you mean `{k}`?)"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn case_slips_and_typos_are_found() {
        assert_eq!(closest("goto", ["goTo", "pickUp"]), Some("goTo"));
        assert_eq!(closest("banan", ["banana", "rainbow"]), Some("banana"));
        assert_eq!(closest("RAINBOW", ["banana", "rainbow"]), Some("rainbow"));
        assert_eq!(closest("xyz", ["banana", "rainbow"]), None);
        assert_eq!(
            closest("banana", ["banana"]),
            None,
            "a known name needs no hint"
        );
    }

    #[test]
    fn the_same_name_with_another_arity_comes_first() {
        let known = [("goTo", 1), ("goTo", 2), ("goto_", 1)];
        assert_eq!(closest_arity("goTo", 3, known), Some(("goTo", 1)));
        assert_eq!(closest_arity("goto", 1, known), Some(("goTo", 1)));
    }

    #[test]
    fn long_names_are_not_compared() {
        let long = "a".repeat(10_000);
        assert_eq!(closest(&long, [long.as_str()]), None);
    }
}
