//! Atoms and strings: conversion between atoms, strings, numbers, code and char lists;
//! concatenation and splitting (nondeterministic modes enumerate through `member/2`).

use super::budget::new_atom;
use super::builtins::{goal, inst, type_error, Flow, B};
use super::machine::Solver;
use super::store::{Cell, Store};
use crate::kr::error::{KrError, KrResult};
use crate::term::print::format_float;
use crate::term::{well_known as wk, Style, Sym, Term};
use std::sync::Arc;

/// The text of an atom, string, number, or code/char list.
pub(crate) fn text_of(s: &Solver, c: Cell) -> Option<String> {
    match s.m.st.deref(c) {
        Cell::Atom(a) => Some(a.name().to_string()),
        Cell::Str(i) => Some(s.m.st.strs[i as usize].to_string()),
        Cell::Int(i) => Some(i.to_string()),
        Cell::Big(i) => Some(s.m.st.strs[i as usize].to_string()),
        Cell::Flt(f) => Some(format_float(f)),
        c @ Cell::Ptr(_) => {
            let (items, end) = s.m.st.list_items(c);
            if !matches!(end, Cell::Atom(n) if n == wk::NIL) {
                return None;
            }
            let mut out = String::new();
            for it in items {
                match s.m.st.deref(it) {
                    Cell::Int(code) => out.push(char::from_u32(u32::try_from(code).ok()?)?),
                    Cell::Atom(a) => {
                        let mut ch = a.name().chars();
                        match (ch.next(), ch.next()) {
                            (Some(x), None) => out.push(x),
                            _ => return None,
                        }
                    }
                    _ => return None,
                }
            }
            Some(out)
        }
        _ => None,
    }
}

/// Why a code or char list argument has no text: the ISO error for its first bad element.
fn list_text_error(s: &Solver, l: Cell, as_codes: bool, name: &str) -> KrError {
    let (items, end) = s.m.st.list_items(l);
    for it in items {
        match s.m.st.deref(it) {
            Cell::Ref(_) => return inst(name, 2),
            Cell::Int(c) if u32::try_from(c).ok().and_then(char::from_u32).is_some() => {}
            Cell::Int(_) => {
                return KrError::iso(
                    Term::compound("representation_error", vec![Term::atom("character_code")]),
                    Some((Sym::intern(name), 2)),
                )
            }
            Cell::Atom(a) if a.name().chars().count() == 1 => {}
            other => {
                let ty = if as_codes && !matches!(other, Cell::Atom(_)) {
                    "integer"
                } else {
                    "character"
                };
                return type_error(s, ty, other, name, 2);
            }
        }
    }
    match end {
        Cell::Ref(_) => inst(name, 2),
        _ => type_error(s, "list", l, name, 2),
    }
}

/// Parses a Prolog number (`12`, `-3`, `2.5e3`, `0x1f`, `0'a`).
pub(crate) fn parse_number(st: &mut Store, text: &str) -> Option<Cell> {
    let t = text.trim();
    let (neg, body) = match t.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    if body.is_empty() || !body.starts_with(|c: char| c.is_ascii_digit()) {
        return None;
    }
    let sign = if neg { -1 } else { 1 };
    if let Some(h) = body.strip_prefix("0x") {
        return i64::from_str_radix(h, 16).ok().map(|v| Cell::Int(sign * v));
    }
    if let Some(o) = body.strip_prefix("0o") {
        return i64::from_str_radix(o, 8).ok().map(|v| Cell::Int(sign * v));
    }
    if let Some(b) = body.strip_prefix("0b") {
        return i64::from_str_radix(b, 2).ok().map(|v| Cell::Int(sign * v));
    }
    if let Some(c) = body.strip_prefix("0'") {
        let mut ch = c.chars();
        return match (ch.next(), ch.next()) {
            (Some(x), None) => Some(Cell::Int(sign * x as i64)),
            _ => None,
        };
    }
    let clean: String = body.chars().filter(|c| *c != '_').collect();
    if clean.chars().all(|c| c.is_ascii_digit()) {
        let v: num_bigint::BigInt = clean.parse().ok()?;
        let v = if neg { -v } else { v };
        return Some(match i64::try_from(&v) {
            Ok(i) => Cell::Int(i),
            Err(_) => st.new_big(&v),
        });
    }
    // A float needs digits on both sides of the dot (Prolog syntax), or an exponent.
    let ok = {
        let mut parts = clean.splitn(2, ['e', 'E']);
        let mant = parts.next().unwrap_or("");
        let exp_ok = parts.next().is_none_or(|e| {
            let e = e.strip_prefix(['+', '-']).unwrap_or(e);
            !e.is_empty() && e.chars().all(|c| c.is_ascii_digit())
        });
        let mant_ok = match mant.split_once('.') {
            Some((a, b)) => {
                !a.is_empty()
                    && !b.is_empty()
                    && a.chars().all(|c| c.is_ascii_digit())
                    && b.chars().all(|c| c.is_ascii_digit())
            }
            None => mant.chars().all(|c| c.is_ascii_digit()) && clean.contains(['e', 'E']),
        };
        mant_ok && exp_ok
    };
    if !ok {
        return None;
    }
    let v: f64 = clean.parse().ok()?;
    Some(Cell::Flt(if neg { -v } else { v }))
}

fn codes(s: &mut Solver, text: &str) -> Cell {
    let items: Vec<Cell> = text.chars().map(|c| Cell::Int(c as i64)).collect();
    s.m.st.new_list(&items, Cell::Atom(wk::NIL))
}

fn chars(s: &mut Solver, text: &str, name: &str) -> KrResult<Cell> {
    let mut buf = [0u8; 4];
    let items = text
        .chars()
        .map(|c| new_atom(s, c.encode_utf8(&mut buf), name, 2))
        .collect::<KrResult<Vec<Cell>>>()?;
    Ok(s.m.st.new_list(&items, Cell::Atom(wk::NIL)))
}

fn string(s: &mut Solver, text: &str) -> Cell {
    s.m.st.new_str(Arc::from(text))
}

fn unify_flow(s: &mut Solver, a: Cell, b: Cell) -> Flow {
    if s.unify(a, b) {
        Flow::True
    } else {
        Flow::Fail
    }
}

/// The text of argument `i`, or an instantiation/type error naming `name/arity`.
fn need_text(s: &Solver, p: u32, i: u32, name: &str, arity: usize) -> KrResult<String> {
    match s.ad(p, i) {
        Cell::Ref(_) => Err(inst(name, arity)),
        c => text_of(s, c).ok_or_else(|| type_error(s, "atomic", c, name, arity)),
    }
}

fn is_var(s: &Solver, p: u32, i: u32) -> bool {
    matches!(s.ad(p, i), Cell::Ref(_))
}

/// Enumerates the given alternatives for the arguments listed: `member(Args, [Alt...])`.
pub(crate) fn enumerate(s: &mut Solver, args: &[Cell], alts: Vec<Vec<Cell>>) -> Flow {
    let f = Sym::intern("$alt");
    let target = s.m.st.new_struct(f, args);
    let items: Vec<Cell> = alts.into_iter().map(|a| s.m.st.new_struct(f, &a)).collect();
    let list = s.m.st.new_list(&items, Cell::Atom(wk::NIL));
    Flow::Call(goal(s, "member", &[target, list]))
}

/// How a text result is made: as an atom or as a string.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Atom,
    Str,
}

/// The result `text` of the built-in `name/arity` as kind `k`.
fn make(s: &mut Solver, k: Kind, text: &str, name: &str, arity: usize) -> KrResult<Cell> {
    match k {
        Kind::Atom => new_atom(s, text, name, arity),
        Kind::Str => Ok(string(s, text)),
    }
}

fn concat(s: &mut Solver, p: u32, k: Kind, name: &str) -> KrResult<Flow> {
    if !is_var(s, p, 0) && !is_var(s, p, 1) {
        let a = need_text(s, p, 0, name, 3)?;
        let b = need_text(s, p, 1, name, 3)?;
        super::budget::text_len(s, (a.len() + b.len()) as u64, name, 3)?;
        let r = make(s, k, &(a + &b), name, 3)?;
        let z = s.a(p, 2);
        return Ok(unify_flow(s, z, r));
    }
    let whole = need_text(s, p, 2, name, 3)?;
    if let Some((i, part)) = known_part(s, p) {
        // As in SWI-Prolog: the other part is what remains of the whole, made only once (the
        // usual mode, `atom_concat(room, N, R)`, made every prefix and suffix an atom before).
        let rest = match i {
            0 => whole.strip_prefix(part.as_str()),
            _ => whole.strip_suffix(part.as_str()),
        };
        let Some(rest) = rest else {
            return Ok(Flow::Fail);
        };
        let r = make(s, k, rest, name, 3)?;
        let other = s.a(p, 1 - i);
        return Ok(unify_flow(s, other, r));
    }
    // Every split is made: quadratic in the length.
    let n = whole.len() as u64;
    super::budget::text_len(s, n * (n + 1) / 2, name, 3)?;
    let mut alts = Vec::new();
    for (i, _) in whole
        .char_indices()
        .chain(std::iter::once((whole.len(), ' ')))
    {
        let (x, y) = whole.split_at(i);
        alts.push(vec![make(s, k, x, name, 3)?, make(s, k, y, name, 3)?]);
    }
    let args = [s.a(p, 0), s.a(p, 1)];
    Ok(enumerate(s, &args, alts))
}

/// The first or the second argument of a concatenation when it is atomic (a number, atom or
/// string), with its text: the argument given.
fn known_part(s: &Solver, p: u32) -> Option<(u32, String)> {
    (0..2).find_map(|i| match s.ad(p, i) {
        Cell::Ref(_) | Cell::Ptr(_) => None,
        c => Some((i, text_of(s, c)?)),
    })
}

/// `sub_atom/5` and `sub_string/5`.
fn sub_text(s: &mut Solver, p: u32, k: Kind, name: &str) -> KrResult<Flow> {
    let whole = need_text(s, p, 0, name, 5)?;
    let chars: Vec<char> = whole.chars().collect();
    let n = chars.len();
    let args = [s.a(p, 1), s.a(p, 2), s.a(p, 3), s.a(p, 4)];
    let mut alts = Vec::new();
    let sub_known = if is_var(s, p, 4) {
        None
    } else {
        Some(need_text(s, p, 4, name, 5)?)
    };
    let fixed = |i: u32| match s.ad(p, i) {
        Cell::Int(v) => Some(v),
        _ => None,
    };
    let (fb, fl, fa) = (fixed(1), fixed(2), fixed(3));
    if let Some(sub) = sub_known {
        let sc: Vec<char> = sub.chars().collect();
        let l = sc.len();
        for b in 0..=n.saturating_sub(l) {
            if n >= l && chars[b..b + l] == sc[..] {
                alts.push(vec![
                    Cell::Int(b as i64),
                    Cell::Int(l as i64),
                    Cell::Int((n - b - l) as i64),
                    s.a(p, 4),
                ]);
            }
        }
        return Ok(enumerate(s, &args, alts));
    }
    for b in 0..=n {
        if fb.is_some_and(|v| v != b as i64) {
            continue;
        }
        for l in 0..=(n - b) {
            if fl.is_some_and(|v| v != l as i64) || fa.is_some_and(|v| v != (n - b - l) as i64) {
                continue;
            }
            let text: String = chars[b..b + l].iter().collect();
            let t = make(s, k, &text, name, 5)?;
            alts.push(vec![
                Cell::Int(b as i64),
                Cell::Int(l as i64),
                Cell::Int((n - b - l) as i64),
                t,
            ]);
        }
    }
    Ok(enumerate(s, &args, alts))
}

fn number_from(s: &mut Solver, text: &str, name: &str, arity: usize) -> KrResult<Cell> {
    parse_number(&mut s.m.st, text).ok_or_else(|| {
        KrError::iso(
            Term::compound("syntax_error", vec![Term::atom("illegal_number")]),
            Some((Sym::intern(name), arity)),
        )
    })
}

/// Text built-ins; `None` when `b` is not one of them.
pub(crate) fn det(s: &mut Solver, b: B, p: u32, arity: u32) -> KrResult<Option<Flow>> {
    Ok(Some(match b {
        B::AtomCodes
        | B::AtomChars
        | B::StringChars
        | B::StringCodes
        | B::NumberCodes
        | B::NumberChars => {
            let (name, as_codes, kind) = match b {
                B::AtomCodes => ("atom_codes", true, 0),
                B::AtomChars => ("atom_chars", false, 0),
                B::StringChars => ("string_chars", false, 1),
                B::StringCodes => ("string_codes", true, 1),
                B::NumberCodes => ("number_codes", true, 2),
                _ => ("number_chars", false, 2),
            };
            if !is_var(s, p, 0) {
                let t = need_text(s, p, 0, name, 2)?;
                let l = if as_codes {
                    codes(s, &t)
                } else {
                    chars(s, &t, name)?
                };
                let y = s.a(p, 1);
                unify_flow(s, y, l)
            } else {
                let l = s.ad(p, 1);
                let Some(t) = text_of(s, l) else {
                    return Err(list_text_error(s, l, as_codes, name));
                };
                let v = match kind {
                    0 => new_atom(s, &t, name, 2)?,
                    1 => string(s, &t),
                    _ => number_from(s, &t, name, 2)?,
                };
                let x = s.a(p, 0);
                unify_flow(s, x, v)
            }
        }
        B::CharCode => match (s.ad(p, 0), s.ad(p, 1)) {
            (Cell::Atom(a), y) => {
                let mut ch = a.name().chars();
                match (ch.next(), ch.next()) {
                    (Some(c), None) => unify_flow(s, y, Cell::Int(c as i64)),
                    _ => return Err(type_error(s, "character", Cell::Atom(a), "char_code", 2)),
                }
            }
            (x @ Cell::Ref(_), Cell::Int(c)) => {
                let Some(ch) = u32::try_from(c).ok().and_then(char::from_u32) else {
                    return Err(type_error(
                        s,
                        "character_code",
                        Cell::Int(c),
                        "char_code",
                        2,
                    ));
                };
                let c = new_atom(s, &ch.to_string(), "char_code", 2)?;
                unify_flow(s, x, c)
            }
            (Cell::Ref(_), Cell::Ref(_)) => return Err(inst("char_code", 2)),
            (x, _) => return Err(type_error(s, "character", x, "char_code", 2)),
        },
        B::AtomLength | B::StringLength => {
            let name = if b == B::AtomLength {
                "atom_length"
            } else {
                "string_length"
            };
            let t = need_text(s, p, 0, name, 2)?;
            match s.ad(p, 1) {
                Cell::Ref(_) | Cell::Int(_) => {}
                other => return Err(type_error(s, "integer", other, name, 2)),
            }
            let y = s.a(p, 1);
            unify_flow(s, y, Cell::Int(t.chars().count() as i64))
        }
        B::AtomConcat => concat(s, p, Kind::Atom, "atom_concat")?,
        B::StringConcat => concat(s, p, Kind::Str, "string_concat")?,
        B::TextConcat => {
            let k = if matches!(s.ad(p, 0), Cell::Str(_)) || matches!(s.ad(p, 1), Cell::Str(_)) {
                Kind::Str
            } else {
                Kind::Atom
            };
            concat(s, p, k, "text_concat")?
        }
        B::SubAtom => sub_text(s, p, Kind::Atom, "sub_atom")?,
        B::SubString => sub_text(s, p, Kind::Str, "sub_string")?,
        B::AtomNumber | B::NumberString => {
            // atom_number(Atom, Number) / number_string(Number, String)
            let (ti, ni, name) = if b == B::AtomNumber {
                (0, 1, "atom_number")
            } else {
                (1, 0, "number_string")
            };
            if !is_var(s, p, ti) {
                let t = need_text(s, p, ti, name, 2)?;
                match parse_number(&mut s.m.st, &t) {
                    Some(v) => {
                        let y = s.a(p, ni);
                        unify_flow(s, y, v)
                    }
                    None if b == B::NumberString => {
                        return Err(number_from(s, &t, name, 2).err().unwrap_or(inst(name, 2)))
                    }
                    None => Flow::Fail,
                }
            } else {
                match s.ad(p, ni) {
                    Cell::Ref(_) => return Err(inst(name, 2)),
                    n @ (Cell::Int(_) | Cell::Flt(_)) => {
                        let t = text_of(s, n).unwrap_or_default();
                        let v = if b == B::AtomNumber {
                            new_atom(s, &t, name, 2)?
                        } else {
                            string(s, &t)
                        };
                        let x = s.a(p, ti);
                        unify_flow(s, x, v)
                    }
                    other => return Err(type_error(s, "number", other, name, 2)),
                }
            }
        }
        B::AtomString | B::StringToAtom => {
            let (ai, si, name) = if b == B::AtomString {
                (0, 1, "atom_string")
            } else {
                (1, 0, "string_to_atom")
            };
            if !is_var(s, p, ai) {
                let t = need_text(s, p, ai, name, 2)?;
                let v = string(s, &t);
                let y = s.a(p, si);
                unify_flow(s, y, v)
            } else {
                let t = need_text(s, p, si, name, 2)?;
                let x = s.a(p, ai);
                let a = new_atom(s, &t, name, 2)?;
                unify_flow(s, x, a)
            }
        }
        B::UpcaseAtom | B::DowncaseAtom | B::StringLower | B::StringUpper => {
            let (name, up, k) = match b {
                B::UpcaseAtom => ("upcase_atom", true, Kind::Atom),
                B::DowncaseAtom => ("downcase_atom", false, Kind::Atom),
                B::StringUpper => ("string_upper", true, Kind::Str),
                _ => ("string_lower", false, Kind::Str),
            };
            let t = need_text(s, p, 0, name, 2)?;
            let r = change_case(&t, up);
            let v = make(s, k, &r, name, 2)?;
            let y = s.a(p, 1);
            unify_flow(s, y, v)
        }
        B::StringCode => {
            let i = super::builtins::int_arg(s, p, 0, "string_code", 3)?;
            let t = need_text(s, p, 1, "string_code", 3)?;
            match (i >= 1).then(|| t.chars().nth(i as usize - 1)).flatten() {
                Some(c) => {
                    let y = s.a(p, 2);
                    unify_flow(s, y, Cell::Int(c as i64))
                }
                None => Flow::Fail,
            }
        }
        B::SplitString => {
            let t = need_text(s, p, 0, "split_string", 4)?;
            let seps: Vec<char> = need_text(s, p, 1, "split_string", 4)?.chars().collect();
            let pad: Vec<char> = need_text(s, p, 2, "split_string", 4)?.chars().collect();
            let parts: Vec<&str> = if seps.is_empty() {
                vec![t.as_str()]
            } else {
                t.split(|c| seps.contains(&c)).collect()
            };
            let items: Vec<Cell> = parts
                .into_iter()
                .map(|x| {
                    let x = x.trim_matches(|c| pad.contains(&c)).to_string();
                    string(s, &x)
                })
                .collect();
            let l = s.m.st.new_list(&items, Cell::Atom(wk::NIL));
            let y = s.a(p, 3);
            unify_flow(s, y, l)
        }
        B::AtomicListConcat => {
            let sep = if arity == 3 {
                need_text(s, p, 1, "atomic_list_concat", 3)?
            } else {
                String::new()
            };
            let out_i = if arity == 3 { 2 } else { 1 };
            let (items, end) = s.m.st.list_items(s.a(p, 0));
            let mut parts = Vec::new();
            let mut complete = matches!(end, Cell::Atom(n) if n == wk::NIL);
            for it in &items {
                match s.m.st.deref(*it) {
                    Cell::Ref(_) => complete = false,
                    c => match text_of(s, c) {
                        Some(t) if !matches!(c, Cell::Ptr(_)) => parts.push(t),
                        _ => {
                            return Err(type_error(
                                s,
                                "atomic",
                                c,
                                "atomic_list_concat",
                                arity as usize,
                            ))
                        }
                    },
                }
            }
            if complete {
                let v = new_atom(s, &parts.join(&sep), "atomic_list_concat", arity as usize)?;
                let y = s.a(p, out_i);
                unify_flow(s, y, v)
            } else if arity == 3 && !sep.is_empty() && !is_var(s, p, 2) {
                let whole = need_text(s, p, 2, "atomic_list_concat", 3)?;
                let cells = whole
                    .split(sep.as_str())
                    .map(|t| new_atom(s, t, "atomic_list_concat", 3))
                    .collect::<KrResult<Vec<Cell>>>()?;
                let l = s.m.st.new_list(&cells, Cell::Atom(wk::NIL));
                let x = s.a(p, 0);
                unify_flow(s, x, l)
            } else {
                return Err(inst("atomic_list_concat", arity as usize));
            }
        }
        B::TermToAtom | B::TermString => {
            let (name, k) = if b == B::TermToAtom {
                ("term_to_atom", Kind::Atom)
            } else {
                ("term_string", Kind::Str)
            };
            if !is_var(s, p, 0) {
                let t = super::output::text(s, s.a(p, 0), Style::WRITEQ)?;
                let v = make(s, k, &t, name, 2)?;
                let y = s.a(p, 1);
                unify_flow(s, y, v)
            } else {
                let t = need_text(s, p, 1, name, 2)?;
                let (c, _) = read_term(s, &t, name, 2)?;
                let x = s.a(p, 0);
                unify_flow(s, x, c)
            }
        }
        B::AtomToTerm => {
            let t = need_text(s, p, 0, "atom_to_term", 3)?;
            let (c, vars) = read_term(s, &t, "atom_to_term", 3)?;
            let eq = Sym::intern("=");
            let pairs: Vec<Cell> = vars
                .into_iter()
                .map(|(n, v)| s.m.st.new_struct(eq, &[Cell::Atom(n), v]))
                .collect();
            let l = s.m.st.new_list(&pairs, Cell::Atom(wk::NIL));
            let (x, y) = (s.a(p, 1), s.a(p, 2));
            if s.unify(x, c) && s.unify(y, l) {
                Flow::True
            } else {
                Flow::Fail
            }
        }
        _ => return Ok(None),
    }))
}

/// Reads Prolog text into a heap term with its named variables.
fn read_term(
    s: &mut Solver,
    text: &str,
    name: &str,
    arity: usize,
) -> KrResult<(Cell, Vec<(Sym, Cell)>)> {
    let mut reader = crate::syntax::prolog::Reader::new("<atom>");
    let t = reader
        .term(text.trim().trim_end_matches('.'), 0)
        .map_err(|d| {
            KrError::iso(
                Term::compound("syntax_error", vec![Term::string(&d.message)]),
                Some((Sym::intern(name), arity)),
            )
        })?;
    let mut vars = Vec::new();
    let c = s.m.st.put_term(&t.term, &mut vars);
    let named = vars
        .into_iter()
        .filter(|(v, _)| !v.name().starts_with('_'))
        .collect();
    Ok((c, named))
}

/// Maps each character to its upper or lower case as C's `towupper`/`towlower` (and so SWI)
/// do: one character for one, keeping those whose case form is longer (`ß` stays `ß`).
fn change_case(text: &str, up: bool) -> String {
    text.chars()
        .map(|c| {
            let mut mapped: Vec<char> = if up {
                c.to_uppercase().collect()
            } else {
                c.to_lowercase().collect()
            };
            match mapped.len() {
                1 => mapped.pop().unwrap_or(c),
                _ => c,
            }
        })
        .collect()
}
