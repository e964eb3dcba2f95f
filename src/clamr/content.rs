//! The content language (the seed's Table 4): complex acts `sequence([A, ...])`, `and(A, B)`,
//! `or(A, B)`, `if(C, A)`; value constraints `greater(V)`, `smaller(V)`, `range(Lo, Hi)`,
//! `outOfRange(Lo, Hi)`; and constraints of time `when(A, T)` and location `where(A, Place)`.
//! Forms are checked when a message is sent, put into English, and summed up in a frame's CL byte.

use crate::term::{Style, Sym, Term};
use std::sync::OnceLock;

/// The complex-act types with their 4-bit code in the CL byte (0: a simple act).
pub const FORMS: &[(&str, usize, u8)] = &[
    ("sequence", 1, 1),
    ("and", 2, 2),
    ("or", 2, 3),
    ("greater", 1, 4),
    ("smaller", 1, 5),
    ("range", 2, 6),
    ("outOfRange", 2, 7),
    ("if", 2, 8),
];

/// CL constraint bit: the act has a time constraint (`when/2`).
pub const TIME: u8 = 0x08;
/// CL constraint bit: the act has a location constraint (`where/2`).
pub const LOCATION: u8 = 0x04;

/// Most nodes looked at when checking or rendering one message (bounds the walks).
const MAX_NODES: usize = 100_000;

fn form(t: &Term) -> Option<(&'static str, u8)> {
    let (f, n) = t.functor()?;
    FORMS
        .iter()
        .find(|(name, arity, _)| *name == f.name() && *arity == n)
        .map(|(name, _, code)| (*name, *code))
}

fn is_number(t: &Term) -> bool {
    matches!(t, Term::Int(_) | Term::BigInt(_) | Term::Float(_))
}

fn as_f64(t: &Term) -> Option<f64> {
    match t {
        Term::Int(i) => Some(*i as f64),
        Term::Float(f) => Some(f.0),
        _ => None,
    }
}

/// The functors [`check_node`] looks at, interned: every other node of a message is passed
/// by comparing integers (sending checks every message).
fn checked(f: Sym) -> bool {
    static NAMES: OnceLock<Vec<Sym>> = OnceLock::new();
    NAMES
        .get_or_init(|| {
            [
                "greater",
                "smaller",
                "range",
                "outOfRange",
                "sequence",
                "when",
                "where",
            ]
            .iter()
            .map(|n| Sym::intern(n))
            .collect()
        })
        .contains(&f)
}

/// True when [`validate`] may reject a compound with functor name `f`: one of the forms it
/// checks, or `ack` (checked at the top). A message with no such compound passes unlooked-at.
pub fn may_reject(f: Sym) -> bool {
    static ACK: OnceLock<Sym> = OnceLock::new();
    checked(f) || f == *ACK.get_or_init(|| Sym::intern("ack"))
}

/// Checks one node; `Err` says what is wrong with it and how to write it.
fn check_node(t: &Term) -> Result<(), String> {
    let Some((f, n)) = t.functor().filter(|(f, _)| checked(*f)) else {
        return Ok(());
    };
    let a = t.args();
    let number = |x: &Term| x.is_var() || is_number(x);
    match (f.name(), n) {
        ("greater" | "smaller", 1) if !number(&a[0]) => Err(format!(
            "{t}: {}/1 compares numbers; write e.g. {}(20)",
            f.name(),
            f.name()
        )),
        ("range" | "outOfRange", 2) => {
            if !number(&a[0]) || !number(&a[1]) {
                return Err(format!(
                    "{t}: {}/2 takes two numbers, the low and the high end, e.g. {}(10, 20)",
                    f.name(),
                    f.name()
                ));
            }
            match (as_f64(&a[0]), as_f64(&a[1])) {
                (Some(lo), Some(hi)) if lo > hi => Err(format!(
                    "{t}: the low end {} is above the high end {}; swap them",
                    a[0], a[1]
                )),
                _ => Ok(()),
            }
        }
        ("sequence", 1) => match a[0].list_items() {
            Some(items) if !items.is_empty() => Ok(()),
            _ if a[0].is_var() => Ok(()),
            _ => Err(format!(
                "{t}: sequence/1 takes a non-empty list of acts, e.g. sequence([goTo(a), goTo(b)])"
            )),
        },
        ("when", 2) => {
            let ok = a[1].is_var()
                || matches!(&a[1], Term::Int(i) if *i >= 0)
                || matches!(form(&a[1]), Some((_, 4..=7)));
            if ok {
                Ok(())
            } else {
                Err(format!(
                    "{t}: when/2 takes a tick (an integer of at least 0) or a constraint on ticks \
                     (greater(T), smaller(T), range(T1, T2), outOfRange(T1, T2))"
                ))
            }
        }
        ("where", 2) if !matches!(&a[1], Term::Atom(_) | Term::Str(_) | Term::Var(_)) => Err(
            format!("{t}: where/2 takes a place name (an atom), e.g. where(A, 'RoomA1')"),
        ),
        _ => Ok(()),
    }
}

/// Checks the content-language forms anywhere in `content` and the acknowledgement form at its
/// top; `Err` says what is wrong, for the sending agent.
pub fn validate(content: &Term) -> Result<(), String> {
    static ACK: OnceLock<Sym> = OnceLock::new();
    if let Some((f, n @ (1 | 2))) = content.functor() {
        if f == *ACK.get_or_init(|| Sym::intern("ack")) {
            let first = &content.args()[0];
            let known = first
                .functor()
                .is_some_and(|(g, n)| n == 0 && super::act::answer_named(g.name()).is_some());
            if !known && !first.is_var() {
                return Err(format!(
                    "{content}: ack/{n} starts with ok, accept, refuse, admit, done, failed or \
                     status, e.g. ack(accept, Act) or ack(done, 25)"
                ));
            }
        }
    }
    // Every message is checked on send: the work list of a usual (small) message stays inline.
    let mut stack: smallvec::SmallVec<[&Term; 16]> = smallvec::smallvec![content];
    let mut seen = 0usize;
    while let Some(t) = stack.pop() {
        seen += 1;
        if seen > MAX_NODES {
            break;
        }
        check_node(t)?;
        // Atomic arguments pass `check_node` by construction: counted, not stacked.
        for a in t.args() {
            if matches!(a, Term::Compound(_)) {
                stack.push(a);
            } else {
                seen += 1;
            }
        }
    }
    Ok(())
}

/// The CL byte of an act's term: the outermost complex form's code (high nibble) and the
/// constraint bits (low nibble) of `when/2` and `where/2` wrappers around it.
pub fn cl_byte(t: &Term) -> u8 {
    let mut bits = 0u8;
    let mut t = t;
    loop {
        match t.functor() {
            Some((f, 2)) if f.name() == "when" => bits |= TIME,
            Some((f, 2)) if f.name() == "where" => bits |= LOCATION,
            _ => break,
        }
        t = &t.args()[0];
    }
    let kind = form(t).map_or(0, |(_, code)| code);
    let kind = if kind == 0 {
        // A simple act whose parameter is a value constraint, e.g. pickup(range(1, 3)).
        t.args().iter().find_map(form).map_or(0, |(_, c)| c)
    } else {
        kind
    };
    (kind << 4) | bits
}

/// True when `t` uses a content-language form anywhere (bounded look).
pub fn uses_forms(t: &Term) -> bool {
    let mut stack = vec![t];
    let mut seen = 0usize;
    while let Some(t) = stack.pop() {
        seen += 1;
        if seen > MAX_NODES {
            return false;
        }
        let constraint =
            matches!(t.functor(), Some((f, 2)) if f.name() == "when" || f.name() == "where");
        if form(t).is_some() || constraint {
            return true;
        }
        stack.extend(t.args().iter());
    }
    false
}

/// The English reading of a whole message (mood-wrapped content), when it uses the content
/// language.
pub fn english_message(content: &Term) -> Option<String> {
    if !uses_forms(content) {
        return None;
    }
    let a = content.args();
    Some(match content.functor() {
        Some((f, 1)) if f == crate::term::well_known::IMP => format!("please {}", english(&a[0])),
        Some((f, 1)) if f == crate::term::well_known::INT => format!("{}?", english(&a[0])),
        Some((f, 1)) if f.name() == "offer" => format!("I offer to {}", english(&a[0])),
        Some((f, 2)) if f.name() == "requestWhen" => {
            format!("when I signal {}, {}", plain(&a[1]), english(&a[0]))
        }
        _ => english(content),
    })
}

/// Text of a term that is not a form (unquoted).
fn plain(t: &Term) -> String {
    t.to_text(Style::WRITE)
}

/// The English reading of a term using the content language (recursion bounded by `depth`).
pub fn english(t: &Term) -> String {
    say(t, 64)
}

fn say(t: &Term, depth: usize) -> String {
    if depth == 0 {
        return plain(t);
    }
    let d = depth - 1;
    let a = t.args();
    let Some((f, n)) = t.functor() else {
        return plain(t);
    };
    match (f.name(), n) {
        ("sequence", 1) => match a[0].list_items() {
            Some(items) if !items.is_empty() => {
                let parts: Vec<String> = items.iter().map(|x| say(x, d)).collect();
                format!("first {}", parts.join(", then "))
            }
            _ => plain(t),
        },
        ("and", 2) => format!("{} and {}", say(&a[0], d), say(&a[1], d)),
        ("or", 2) => format!("either {} or {}", say(&a[0], d), say(&a[1], d)),
        ("if", 2) => format!("if {}, then {}", say(&a[0], d), say(&a[1], d)),
        ("greater", 1) => format!("more than {}", plain(&a[0])),
        ("smaller", 1) => format!("less than {}", plain(&a[0])),
        ("range", 2) => format!("between {} and {}", plain(&a[0]), plain(&a[1])),
        ("outOfRange", 2) => format!("outside {} to {}", plain(&a[0]), plain(&a[1])),
        ("when", 2) => format!("{} {}", say(&a[0], d), when(&a[1])),
        ("where", 2) => format!("{} in {}", say(&a[0], d), plain(&a[1])),
        _ if a.iter().any(uses_forms) => {
            let args: Vec<String> = a.iter().map(|x| say(x, d)).collect();
            format!("{} {}", f.name(), args.join(", "))
        }
        _ => plain(t),
    }
}

/// A time constraint in words.
fn when(t: &Term) -> String {
    let a = t.args();
    match t.functor() {
        Some((f, 1)) if f.name() == "greater" => format!("after tick {}", plain(&a[0])),
        Some((f, 1)) if f.name() == "smaller" => format!("before tick {}", plain(&a[0])),
        Some((f, 2)) if f.name() == "range" => {
            format!("between ticks {} and {}", plain(&a[0]), plain(&a[1]))
        }
        Some((f, 2)) if f.name() == "outOfRange" => {
            format!("outside ticks {} to {}", plain(&a[0]), plain(&a[1]))
        }
        _ => format!("at tick {}", plain(t)),
    }
}

/// The library predicates agents use to test a value against a constraint (Prolog text,
/// compiled with the engine's library; documented in `docs/communication.md`).
pub const LIBRARY: &str = r#"
satisfies(V, C) :- var(C), !, V = C.
satisfies(V, greater(X)) :- !, number(V), number(X), V > X.
satisfies(V, smaller(X)) :- !, number(V), number(X), V < X.
satisfies(V, range(L, H)) :- !, number(V), number(L), number(H), V >= L, V =< H.
satisfies(V, outOfRange(L, H)) :- !, number(V), number(L), number(H), ( V < L -> true ; V > H ).
satisfies(V, and(A, B)) :- !, satisfies(V, A), satisfies(V, B).
satisfies(V, or(A, B)) :- !, ( satisfies(V, A) -> true ; satisfies(V, B) ).
satisfies(V, V).
"#;

#[cfg(test)]
mod tests {
    use super::*;

    fn t(text: &str) -> Term {
        crate::syntax::prolog::Reader::new("t")
            .term(text, 0)
            .expect("term")
            .term
    }

    #[test]
    fn forms_are_checked() {
        for ok in [
            "imp(sequence([goTo(a), goTo(b)]))",
            "imp(pickup(range(1, 3)))",
            "imp(when(goTo(a), smaller(500)))",
            "imp(where(sense(temperature), 'RoomA1'))",
            "ack(done, 25)",
            "int(at(X, range(1, Y)))",
        ] {
            assert_eq!(validate(&t(ok)), Ok(()), "{ok}");
        }
        for (bad, says) in [
            ("imp(pickup(range(5, 1)))", "swap them"),
            ("imp(pickup(range(a, 1)))", "two numbers"),
            ("imp(sense(greater(hot)))", "compares numbers"),
            ("imp(sequence([]))", "non-empty list"),
            ("imp(when(goTo(a), soon))", "tick"),
            ("imp(where(goTo(a), 3))", "place name"),
            ("ack(maybe, x)", "starts with ok"),
        ] {
            let e = validate(&t(bad)).expect_err(bad);
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn cl_byte_and_english() {
        assert_eq!(cl_byte(&t("sense(temperature)")), 0);
        assert_eq!(cl_byte(&t("sequence([a, b])")), 0x10);
        assert_eq!(cl_byte(&t("when(where(or(a, b), r), 5)")), 0x3C);
        assert_eq!(cl_byte(&t("pickup(range(1, 3))")), 0x60);
        assert_eq!(
            english(&t("sequence([goTo(a), if(holding(red), putDown)])")),
            "first goTo(a), then if holding(red), then putDown"
        );
        assert_eq!(
            english(&t("when(goTo('RoomA1'), smaller(500))")),
            "goTo(RoomA1) before tick 500"
        );
        assert_eq!(
            english(&t("pickup(outOfRange(1, 3))")),
            "pickup outside 1 to 3"
        );
    }
}
