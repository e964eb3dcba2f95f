//! SWI-Prolog library predicates added beyond the core built-ins (`random`, `strings`), and
//! the list of every predicate the engine knows, with "did you mean" suggestions for names
//! that are not among them.

pub(crate) mod random;
pub(crate) mod strings;

use super::builtins::{Flow, B};
use super::machine::Solver;
use crate::kr::error::KrResult;
use crate::term::Sym;

/// The library built-ins; `None` when `b` is not one of them.
pub(crate) fn det(s: &mut Solver, b: B, p: u32) -> KrResult<Option<Flow>> {
    Ok(Some(match b {
        B::RandomSelect => random::random_select(s, p)?,
        B::Randseq => random::randseq(s, p)?,
        B::Randset => random::randset(s, p)?,
        B::CharType => strings::char_type(s, p)?,
        B::CodeType => strings::code_type(s, p)?,
        B::TextToString => strings::text_to_string(s, p)?,
        _ => return Ok(None),
    }))
}

/// True when the engine defines `name/arity` (a built-in or a library predicate).
pub fn is_known(name: &str, arity: usize) -> bool {
    let lib = super::builtins::library();
    u32::try_from(arity).is_ok_and(|a| lib.table.contains_key(&(Sym::intern(name), a)))
}

/// Every predicate the engine defines, as `(name, arity)`, sorted by name (internal helper
/// predicates, whose names start with `$`, left out).
pub fn known_predicates() -> Vec<(&'static str, usize)> {
    let lib = super::builtins::library();
    let mut out: Vec<(&'static str, usize)> = lib
        .table
        .keys()
        .map(|(s, a)| (s.name(), *a as usize))
        .filter(|(n, _)| !n.starts_with('$'))
        .collect();
    out.sort_unstable();
    out
}

/// "Did you mean" for an undefined `name/arity`: the closest of the engine's predicates and
/// `others` (say, the program's own), by edit distance on the name, preferring the same arity.
/// `None` when nothing is close enough to be a likely typo.
pub fn suggest<'a>(
    name: &str,
    arity: usize,
    others: impl IntoIterator<Item = (&'a str, usize)>,
) -> Option<String> {
    let known = known_predicates();
    let candidates = known.iter().copied().chain(others);
    crate::suggest::closest_arity(name, arity, candidates).map(|(n, a)| format!("{n}/{a}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_find_near_names() {
        assert_eq!(suggest("lenght", 2, []).as_deref(), Some("length/2"));
        assert_eq!(suggest("apend", 3, []).as_deref(), Some("append/3"));
        assert_eq!(suggest("membr", 2, []).as_deref(), Some("member/2"));
        assert_eq!(
            suggest("at_room", 1, [("at_rom", 1)]).as_deref(),
            Some("at_rom/1")
        );
        assert_eq!(suggest("completely_unrelated_name", 2, []), None);
        assert!(is_known("char_type", 2) && is_known("append", 3) && !is_known("lenght", 2));
    }
}
