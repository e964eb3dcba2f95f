//! Terms to scryer text and back. Everything scryer reads is printed here from a [`Term`] (scryer
//! 0.10 panics on some malformed texts), after two rewrites of every goal position:
//! - the sandbox: a goal or closure that is not known when the text is written (a variable
//!   under `call/N`, `findall/3`, `maplist/N`, ...) runs under `'$goal_call'`, which refuses
//!   file, process, network and database built-ins at run time; such built-ins written as goals
//!   are refused before anything reaches scryer;
//! - GOAL's meaning where scryer's differs: SWI arithmetic (`/` of integers is exact when it can
//!   be, `**` of integers is an integer), `*->` (not an operator in scryer 0.10), and the
//!   condition of if-then-else runs under `call/1` (scryer 0.10 lets a cut there cut the else
//!   branch).

use crate::kr::KrError;
use crate::term::Style;
use crate::term::{Float, Sym, Term};

/// Nesting deeper than this is refused (the rewrites and conversions recurse).
pub const MAX_DEPTH: usize = 2_000;

/// Predicates agent code may not call on the scryer engine (any arity): files, processes,
/// network, the database, flags and the machine. GOAL's protected names are added.
const DENIED: &[&str] = &[
    "open",
    "close",
    "consult",
    "load",
    "load_files",
    "use_module",
    "ensure_loaded",
    "halt",
    "shell",
    "system",
    "getenv",
    "setenv",
    "unsetenv",
    "delete_file",
    "rename_file",
    "make_directory",
    "delete_directory",
    "directory_files",
    "working_directory",
    "file_exists",
    "directory_exists",
    "set_input",
    "set_output",
    "set_stream_position",
    "see",
    "tell",
    "socket_client_open",
    "socket_server_open",
    "socket_server_accept",
    "http_open",
    "process_create",
    "op",
    "set_prolog_flag",
    "assert",
    "asserta",
    "assertz",
    "retract",
    "retractall",
    "abolish",
    "bb_put",
    "bb_b_put",
    "bb_get",
    "call_with_inference_limit",
    "setup_call_cleanup",
    "call_cleanup",
    "foreign",
    "use_foreign_module",
    ":",
];

/// True when agent code on the scryer engine may not call `name`.
pub fn denied(name: &str) -> bool {
    (DENIED.contains(&name) || name.starts_with('$') || crate::kr::knowledge::is_protected(name))
        && !matches!(name, "catch" | "throw")
}

/// Built-ins that run as a predicate of the prelude: SWI's meaning where scryer's differs
/// (arithmetic, the standard order of terms, text given as a string) and bounds on work
/// scryer does in one inference (`length/2`). The arithmetic comparisons go to
/// `'$goal_cmp'(Op, A, B)`, the others to the name given. Written goals are renamed here;
/// closures naming them (`maplist(is, ...)`) and goals built at run time are renamed by the
/// prelude's `'$goal_safe'`, from the same table.
const RENAMED: &[(&str, usize, &str)] = &[
    ("is", 2, "$goal_is"),
    ("<", 2, "$goal_cmp"),
    (">", 2, "$goal_cmp"),
    ("=<", 2, "$goal_cmp"),
    (">=", 2, "$goal_cmp"),
    ("=:=", 2, "$goal_cmp"),
    ("=\\=", 2, "$goal_cmp"),
    ("length", 2, "$goal_length"),
    ("compare", 3, "$goal_compare"),
    ("@<", 2, "$goal_before"),
    ("@>", 2, "$goal_after"),
    ("@=<", 2, "$goal_not_after"),
    ("@>=", 2, "$goal_not_before"),
    ("sort", 2, "$goal_sort"),
    ("keysort", 2, "$goal_keysort"),
    ("setof", 3, "$goal_setof"),
    ("number_codes", 2, "$goal_number_codes"),
    ("arg", 3, "$goal_arg"),
    ("between", 3, "$goal_between"),
    ("format", 3, "$goal_format"),
];

/// The prelude's name for a built-in of [`RENAMED`].
fn renamed(name: &str, arity: usize) -> Option<&'static str> {
    RENAMED
        .iter()
        .find(|(n, a, _)| *n == name && *a == arity)
        .map(|(_, _, r)| *r)
}

/// `name(args)` as the prelude's predicate of [`RENAMED`] (the comparisons get the operator as
/// first argument); `None` when `name/arity` is not renamed.
fn rename(name: Sym, args: &[Term]) -> Option<Term> {
    let to = renamed(name.name(), args.len())?;
    Some(if to == "$goal_cmp" {
        Term::compound(to, vec![Term::Atom(name), args[0].clone(), args[1].clone()])
    } else {
        Term::compound(to, args.to_vec())
    })
}

/// The `'$goal_renamed'/3` and `'$goal_meta'/4` facts for the prelude: the tables the
/// run-time rewriting (`'$goal_safe'`) shares with [`query`] and [`clause`].
pub fn table_facts() -> String {
    let mut out = String::new();
    for (n, a, r) in RENAMED {
        let fact = Term::compound(
            "$goal_renamed",
            vec![Term::atom(n), Term::Int(*a as i64), Term::atom(r)],
        );
        out.push_str(&format!("{} .\n", canonical(&fact)));
    }
    for (n, a) in META {
        for &(p, x) in meta_args(n, *a) {
            let fact = Term::compound(
                "$goal_meta",
                vec![
                    Term::atom(n),
                    Term::Int(*a as i64),
                    Term::Int(p as i64),
                    Term::Int(x as i64),
                ],
            );
            out.push_str(&format!("{} .\n", canonical(&fact)));
        }
    }
    out
}

/// A term as text scryer reads back as the same term: quoted atoms and no operators (scryer
/// 0.10 panics on operators it does not know, such as `xor` and `=@=`).
pub fn canonical(t: &Term) -> String {
    t.to_text(Style::CANONICAL)
}

/// Meta-predicates with goal or closure arguments (`meta_args` gives the positions; `call/N`
/// is handled apart, by arity).
const META: &[(&str, usize)] = &[
    ("findall", 3),
    ("findall", 4),
    ("aggregate_all", 3),
    ("aggregate_all", 4),
    ("forall", 2),
    ("\\+", 1),
    ("not", 1),
    ("once", 1),
    ("ignore", 1),
    ("catch", 3),
    ("maplist", 2),
    ("maplist", 3),
    ("maplist", 4),
    ("maplist", 5),
    ("maplist", 6),
    ("maplist", 7),
    ("foldl", 4),
    ("foldl", 5),
    ("foldl", 6),
    ("include", 3),
    ("exclude", 3),
    ("partition", 4),
    ("phrase", 2),
    ("phrase", 3),
];

/// The `'$goal_denied'/2` facts for the prelude.
pub fn denied_facts() -> String {
    let mut out = String::new();
    let names = DENIED
        .iter()
        .copied()
        .chain(crate::kr::knowledge::protected_names())
        .filter(|n| denied(n));
    for n in names {
        // Quoted always: `:` alone is an operator.
        out.push_str(&format!("'$goal_denied'('{n}', _).\n"));
    }
    out.push_str(
        "'$goal_denied'(N, _) :- atom(N), N \\== '$goal_call', sub_atom(N, 0, 1, _, '$').\n",
    );
    out
}

fn refused(name: Sym, arity: usize) -> KrError {
    KrError::iso(
        Term::compound(
            "permission_error",
            vec![
                Term::atom("access"),
                Term::atom("private_procedure"),
                Term::compound("/", vec![Term::Atom(name), Term::Int(arity as i64)]),
            ],
        ),
        None,
    )
}

fn too_deep() -> KrError {
    KrError::Resource {
        resource: "memory",
        predicate: "scryer".into(),
        limit: MAX_DEPTH as u64,
    }
}

/// The positions of goal (0) and closure (n extra arguments) arguments of meta-predicates.
fn meta_args(name: &str, arity: usize) -> &'static [(usize, usize)] {
    match (name, arity) {
        ("call", _) => &[(0, 0)],
        ("findall", 3) | ("findall", 4) | ("bagof", 3) | ("setof", 3) | ("aggregate_all", 3) => {
            &[(1, 0)]
        }
        ("aggregate_all", 4) => &[(2, 0)],
        ("forall", 2) => &[(0, 0), (1, 0)],
        ("\\+", 1) | ("not", 1) | ("once", 1) | ("ignore", 1) => &[(0, 0)],
        ("catch", 3) => &[(0, 0), (2, 0)],
        ("maplist", 2..=7)
        | ("foldl", 4..=6)
        | ("include", 3)
        | ("exclude", 3)
        | ("partition", 4) => &[(0, 1)],
        ("phrase", 2) | ("phrase", 3) => &[(0, 2)],
        _ => &[],
    }
}

/// A clause as scryer text (`.` and a newline), with its bodies rewritten.
pub fn clause(t: &Term) -> Result<String, KrError> {
    check_depth(t)?;
    let c = if t.is_functor(Sym::intern(":-"), 2) {
        let head = t.args()[0].clone();
        if let Some((n, a)) = head.functor() {
            if denied(n.name()) {
                return Err(refused(n, a));
            }
        }
        Term::compound(":-", vec![head, goal(&t.args()[1], 0)?])
    } else if t.is_functor(Sym::intern("-->"), 2) {
        Term::compound("-->", vec![t.args()[0].clone(), dcg_body(&t.args()[1], 0)?])
    } else {
        t.clone()
    };
    Ok(format!("{} .\n", canonical(&c)))
}

/// A query as scryer text (without the final `.`), its goal rewritten.
pub fn query(t: &Term) -> Result<Term, KrError> {
    check_depth(t)?;
    goal(t, 0)
}

/// Refuses terms nested deeper than [`MAX_DEPTH`] (an explicit stack: no recursion).
fn check_depth(t: &Term) -> Result<(), KrError> {
    let mut stack = vec![(t, 0usize)];
    while let Some((t, d)) = stack.pop() {
        if d > MAX_DEPTH {
            return Err(too_deep());
        }
        if let Term::Compound(c) = t {
            stack.extend(c.args.iter().map(|a| (a, d + 1)));
        }
    }
    Ok(())
}

fn wrap(t: &Term) -> Term {
    Term::compound("$goal_call", vec![t.clone()])
}

/// A closure argument: a variable runs under the sandbox; a callable term is checked by name.
fn closure(t: &Term, extra: usize) -> Result<Term, KrError> {
    match t {
        Term::Var(_) => Ok(wrap(t)),
        _ => match t.functor() {
            Some((n, a)) if denied(n.name()) => Err(refused(n, a + extra)),
            Some((n, a)) if extra > 0 && renamed(n.name(), a + extra).is_some() => Ok(wrap(t)),
            Some(_) if extra == 0 => goal(t, 0),
            Some(_) => Ok(t.clone()),
            None => Ok(wrap(t)),
        },
    }
}

/// Rewrites one goal (see the module documentation).
fn goal(t: &Term, depth: usize) -> Result<Term, KrError> {
    if depth > MAX_DEPTH {
        return Err(too_deep());
    }
    let Some((name, arity)) = t.functor() else {
        return Ok(match t {
            Term::Var(_) => wrap(t),
            other => other.clone(),
        });
    };
    let n = name.name();
    if denied(n) {
        return Err(refused(name, arity));
    }
    let args = t.args();
    let sub = |i: usize| goal(&args[i], depth + 1);
    Ok(match (n, arity) {
        ("," | ";", 2) => {
            if n == ";" && args[0].is_functor(Sym::intern("*->"), 2) {
                let c = &args[0].args();
                Term::compound(
                    "$goal_softcut",
                    vec![goal(&c[0], depth + 1)?, goal(&c[1], depth + 1)?, sub(1)?],
                )
            } else {
                Term::compound(name, vec![sub(0)?, sub(1)?])
            }
        }
        ("->", 2) => Term::compound(name, vec![Term::compound("call", vec![sub(0)?]), sub(1)?]),
        ("*->", 2) => Term::compound(",", vec![sub(0)?, sub(1)?]),
        ("bagof" | "setof", 3) => {
            let mut g = &args[1];
            let mut vars = Vec::new();
            while g.is_functor(Sym::intern("^"), 2) {
                vars.push(g.args()[0].clone());
                g = &g.args()[1];
            }
            let mut inner = goal(g, depth + 1)?;
            for v in vars.into_iter().rev() {
                inner = Term::compound("^", vec![v, inner]);
            }
            let g = [args[0].clone(), inner, args[2].clone()];
            rename(name, &g).unwrap_or_else(|| Term::compound(name, g.to_vec()))
        }
        _ if renamed(n, arity).is_some() => rename(name, args).unwrap_or_else(|| t.clone()),
        _ => {
            let meta = meta_args(n, arity);
            if meta.is_empty() {
                return Ok(t.clone());
            }
            let mut out = args.to_vec();
            for &(i, extra) in meta {
                out[i] = if extra == 0 && !matches!(args[i], Term::Var(_)) {
                    goal(&args[i], depth + 1)?
                } else {
                    closure(&args[i], extra + if n == "call" { arity - 1 } else { 0 })?
                };
            }
            Term::compound(name, out)
        }
    })
}

/// Rewrites the `{}` goals of a DCG body (and refuses denied non-terminals).
fn dcg_body(t: &Term, depth: usize) -> Result<Term, KrError> {
    if depth > MAX_DEPTH {
        return Err(too_deep());
    }
    let Some((name, arity)) = t.functor() else {
        return Ok(t.clone());
    };
    let args = t.args();
    Ok(match (name.name(), arity) {
        ("," | ";" | "->" | "|", 2) => Term::compound(
            name,
            vec![
                dcg_body(&args[0], depth + 1)?,
                dcg_body(&args[1], depth + 1)?,
            ],
        ),
        ("\\+", 1) => Term::compound(name, vec![dcg_body(&args[0], depth + 1)?]),
        ("{}", 1) => Term::compound(name, vec![goal(&args[0], depth + 1)?]),
        ("call", _) => Term::compound(
            name,
            std::iter::once(closure(&args[0], arity - 1 + 2)?)
                .chain(args[1..].iter().cloned())
                .collect(),
        ),
        ("[]" | "!", 0) => t.clone(),
        (".", 2) => t.clone(),
        (n, a) if denied(n) => return Err(refused(name, a + 2)),
        _ => t.clone(),
    })
}

/// Converts a scryer answer term to a [`Term`] (strings come back as lists of one-character
/// atoms: scryer's `double_quotes` flag is `chars`).
pub fn from_scryer(t: &scryer_prolog::Term, depth: usize) -> Result<Term, KrError> {
    use scryer_prolog::Term as S;
    if depth > MAX_DEPTH {
        return Err(too_deep());
    }
    Ok(match t {
        S::Integer(i) => match i64::try_from(i.clone()) {
            Ok(n) => Term::Int(n),
            Err(_) => match i.to_string().parse::<num_bigint::BigInt>() {
                Ok(b) => Term::integer(b),
                Err(_) => Term::atom(&i.to_string()),
            },
        },
        S::Rational(r) => Term::atom(&r.to_string()),
        S::Float(f) => Term::Float(Float(*f)),
        S::Atom(a) => Term::atom(a),
        S::String(s) => Term::list(
            s.chars()
                .map(|c| Term::atom(c.encode_utf8(&mut [0; 4])))
                .collect::<Vec<_>>(),
        ),
        S::List(items) => Term::list(
            items
                .iter()
                .map(|i| from_scryer(i, depth + 1))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        S::Compound(name, args) => Term::compound(
            Sym::intern(name),
            args.iter()
                .map(|a| from_scryer(a, depth + 1))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        S::Var(v) => Term::var(&format!("_S{v}")),
        _ => Term::atom("$unknown"),
    })
}
