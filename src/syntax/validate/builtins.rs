//! The predicate names the validator knows about, kept in one place: the built-ins the KR layer
//! supports (docs/prolog.md), the reserved predicates every agent has, and the protected
//! names that may not appear in KR content.

/// Built-in predicates as `(name, arity)`; arity `None` means any arity.
const BUILTINS: &[(&str, Option<usize>)] = &[
    // control
    ("true", Some(0)),
    ("false", Some(0)),
    ("fail", Some(0)),
    ("!", Some(0)),
    ("not", Some(1)),
    ("\\+", Some(1)),
    (",", Some(2)),
    (";", Some(2)),
    ("->", Some(2)),
    ("*->", Some(2)),
    ("call", None),
    ("once", Some(1)),
    ("ignore", Some(1)),
    ("forall", Some(2)),
    // all-solutions
    ("findall", Some(3)),
    ("findall", Some(4)),
    ("setof", Some(3)),
    ("bagof", Some(3)),
    ("aggregate", Some(3)),
    ("aggregate", Some(4)),
    ("aggregate_all", Some(3)),
    ("aggregate_all", Some(4)),
    // lists
    ("member", Some(2)),
    ("memberchk", Some(2)),
    ("append", Some(2)),
    ("append", Some(3)),
    ("length", Some(2)),
    ("nth0", Some(3)),
    ("nth1", Some(3)),
    ("nth0", Some(4)),
    ("nth1", Some(4)),
    ("last", Some(2)),
    ("reverse", Some(2)),
    ("sort", Some(2)),
    ("sort", Some(4)),
    ("msort", Some(2)),
    ("predsort", Some(3)),
    ("keysort", Some(2)),
    ("permutation", Some(2)),
    ("flatten", Some(2)),
    ("sumlist", Some(2)),
    ("sum_list", Some(2)),
    ("max_list", Some(2)),
    ("min_list", Some(2)),
    ("max_member", Some(2)),
    ("min_member", Some(2)),
    ("numlist", Some(3)),
    ("subtract", Some(3)),
    ("union", Some(3)),
    ("intersection", Some(3)),
    ("delete", Some(3)),
    ("exclude", Some(3)),
    ("include", Some(3)),
    ("partition", Some(4)),
    ("select", Some(3)),
    ("selectchk", Some(3)),
    ("maplist", None),
    ("list_to_set", Some(2)),
    ("is_list", Some(1)),
    ("same_length", Some(2)),
    ("nextto", Some(3)),
    ("sumlist", Some(3)),
    ("list_to_ord_set", Some(2)),
    ("ord_union", Some(3)),
    ("ord_subtract", Some(3)),
    ("ord_memberchk", Some(2)),
    ("ord_insert", Some(3)),
    ("ord_intersection", Some(3)),
    ("ord_subset", Some(2)),
    ("ord_del_element", Some(3)),
    ("ord_add_element", Some(3)),
    ("ord_empty", Some(1)),
    ("pairs_keys_values", Some(3)),
    ("pairs_keys", Some(2)),
    ("pairs_values", Some(2)),
    // type tests
    ("var", Some(1)),
    ("nonvar", Some(1)),
    ("atom", Some(1)),
    ("number", Some(1)),
    ("integer", Some(1)),
    ("float", Some(1)),
    ("atomic", Some(1)),
    ("compound", Some(1)),
    ("callable", Some(1)),
    ("ground", Some(1)),
    ("string", Some(1)),
    // comparison and arithmetic
    ("=", Some(2)),
    ("\\=", Some(2)),
    ("==", Some(2)),
    ("\\==", Some(2)),
    ("@<", Some(2)),
    ("@=<", Some(2)),
    ("@>", Some(2)),
    ("@>=", Some(2)),
    ("=@=", Some(2)),
    ("\\=@=", Some(2)),
    ("=..", Some(2)),
    ("is", Some(2)),
    ("=:=", Some(2)),
    ("=\\=", Some(2)),
    ("<", Some(2)),
    ("=<", Some(2)),
    (">", Some(2)),
    (">=", Some(2)),
    ("compare", Some(3)),
    ("between", Some(3)),
    ("succ", Some(2)),
    ("plus", Some(3)),
    // atoms and strings
    ("atom_codes", Some(2)),
    ("atom_chars", Some(2)),
    ("char_code", Some(2)),
    ("atom_number", Some(2)),
    ("number_codes", Some(2)),
    ("atom_length", Some(2)),
    ("atom_concat", Some(3)),
    ("sub_atom", Some(5)),
    ("upcase_atom", Some(2)),
    ("downcase_atom", Some(2)),
    ("atom_string", Some(2)),
    ("number_string", Some(2)),
    ("atomic_list_concat", Some(2)),
    ("atomic_list_concat", Some(3)),
    ("string_concat", Some(3)),
    ("string_to_atom", Some(2)),
    ("string_length", Some(2)),
    ("string_chars", Some(2)),
    ("string_codes", Some(2)),
    ("sub_string", Some(5)),
    ("term_to_atom", Some(2)),
    ("split_string", Some(4)),
    // time
    ("get_time", Some(1)),
    ("stamp_date_time", Some(3)),
    ("format_time", Some(3)),
    // output
    ("write", Some(1)),
    ("write", Some(2)),
    ("writeln", Some(1)),
    ("writeq", Some(1)),
    ("print", Some(1)),
    ("print", Some(2)),
    ("format", Some(1)),
    ("format", Some(2)),
    ("format", Some(3)),
    ("nl", Some(0)),
    ("print_message", Some(2)),
    // misc
    ("copy_term", Some(2)),
    ("functor", Some(3)),
    ("arg", Some(3)),
    ("tab", Some(1)),
];

/// Predicates every agent has: percepts (`newpercept/1`: the batch of this cycle), mail, the
/// agent's conversations (`session(Id, With, Act, State)`, see docs/communication.md), and the
/// agent facts.
const RESERVED: &[(&str, usize)] = &[
    ("percept", 1),
    ("newpercept", 1),
    ("received", 2),
    ("sent", 2),
    ("session", 4),
    ("agent", 1),
    ("me", 1),
];

/// True if `name/arity` is a built-in predicate of the KR layer.
pub fn is_builtin(name: &str, arity: usize) -> bool {
    BUILTINS
        .iter()
        .any(|(n, a)| *n == name && a.is_none_or(|a| a == arity))
}

/// True if `name/arity` is a reserved predicate every agent has (`percept/1`, `me/1`, ...).
pub fn is_reserved(name: &str, arity: usize) -> bool {
    RESERVED.iter().any(|(n, a)| *n == name && *a == arity)
}

/// Protected and file predicates: one table in the KR layer, shared with the engines.
pub use crate::kr::knowledge::{file_io_reason, protected_reason};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knows_builtins_reserved_and_protected() {
        assert!(is_builtin("member", 2) && is_builtin("call", 4) && is_builtin("maplist", 3));
        assert!(!is_builtin("member", 3) && !is_builtin("on", 2));
        assert!(is_reserved("percept", 1) && !is_reserved("percept", 2));
        assert!(protected_reason("assert").is_some() && protected_reason("member").is_none());
    }
}
