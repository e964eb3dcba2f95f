//! Character classification (`char_type/2`, `code_type/2`) and `text_to_string/2`, as in
//! SWI-Prolog.

use crate::kr::error::KrResult;
use crate::kr::native::builtins::{inst, type_error, Flow};
use crate::kr::native::machine::Solver;
use crate::kr::native::store::Cell;
use crate::kr::native::text::{enumerate, text_of};
use crate::term::Sym;
use std::sync::Arc;

/// How a character is given and returned: as a one-character atom or as a code.
#[derive(Clone, Copy)]
enum As {
    Char,
    Code,
}

fn char_cell(c: char, how: As) -> Cell {
    match how {
        As::Char => Cell::Atom(Sym::intern(c.encode_utf8(&mut [0; 4]))),
        As::Code => Cell::Int(c as i64),
    }
}

/// The types without an argument that `c` has, by name.
fn plain_types(c: char) -> Vec<&'static str> {
    let tests: [(&str, bool); 18] = [
        ("alnum", c.is_alphanumeric()),
        ("alpha", c.is_alphanumeric() || c == '_'),
        ("csym", c.is_alphanumeric() || c == '_'),
        ("csymf", c.is_alphabetic() || c == '_'),
        ("ascii", c.is_ascii()),
        ("white", c == ' ' || c == '\t'),
        ("cntrl", c.is_control()),
        ("digit", c.is_ascii_digit()),
        ("space", c.is_whitespace()),
        ("end_of_line", c == '\n' || c == '\r'),
        ("newline", c == '\n'),
        ("graph", !c.is_whitespace() && !c.is_control()),
        ("print", !c.is_control()),
        (
            "punct",
            !c.is_alphanumeric() && !c.is_whitespace() && !c.is_control(),
        ),
        ("period", matches!(c, '.' | '!' | '?')),
        ("quote", matches!(c, '\'' | '"' | '`')),
        ("paren", matches!(c, '(' | ')')),
        ("upper", c.is_uppercase()),
    ];
    let mut out: Vec<&str> = tests.iter().filter(|t| t.1).map(|t| t.0).collect();
    if c.is_lowercase() {
        out.push("lower");
    }
    out
}

/// The single-character case mapping of `c`, if it is one character.
fn single(mut it: impl Iterator<Item = char>) -> Option<char> {
    match (it.next(), it.next()) {
        (Some(x), None) => Some(x),
        _ => None,
    }
}

/// All types of `c` as terms, in SWI's order of `char_type(c, T)` answers (close enough for
/// enumeration; each one holds).
fn all_types(s: &mut Solver, c: char, how: As) -> Vec<Cell> {
    let mut out: Vec<Cell> = plain_types(c)
        .into_iter()
        .map(|n| Cell::Atom(Sym::intern(n)))
        .collect();
    let mut unary = |s: &mut Solver, name: &str, arg: Cell| {
        let t = s.m.st.new_struct(Sym::intern(name), &[arg]);
        out.push(t);
    };
    if let Some(w) = c.to_digit(10) {
        unary(s, "digit", Cell::Int(w as i64));
    }
    let lower = single(c.to_lowercase()).unwrap_or(c);
    let upper = single(c.to_uppercase()).unwrap_or(c);
    if c.is_uppercase() {
        unary(s, "upper", char_cell(lower, how));
    }
    if c.is_lowercase() {
        unary(s, "lower", char_cell(upper, how));
    }
    unary(s, "to_lower", char_cell(lower, how));
    unary(s, "to_upper", char_cell(upper, how));
    unary(s, "code", Cell::Int(c as i64));
    out
}

/// The character argument of `char_type/2` or `code_type/2`.
fn the_char(s: &Solver, p: u32, name: &str) -> KrResult<char> {
    let c = s.ad(p, 0);
    let ch = match c {
        Cell::Ref(_) => return Err(inst(name, 2)),
        Cell::Int(i) => u32::try_from(i).ok().and_then(char::from_u32),
        Cell::Atom(a) => single(a.name().chars()),
        _ => None,
    };
    ch.ok_or_else(|| type_error(s, "character", c, name, 2))
}

fn classify(s: &mut Solver, p: u32, name: &str, how: As) -> KrResult<Flow> {
    let c = the_char(s, p, name)?;
    let types = all_types(s, c, how);
    let t = s.a(p, 1);
    Ok(enumerate(
        s,
        &[t],
        types.into_iter().map(|ty| vec![ty]).collect(),
    ))
}

/// `char_type(+Char, ?Type)`.
pub(crate) fn char_type(s: &mut Solver, p: u32) -> KrResult<Flow> {
    classify(s, p, "char_type", As::Char)
}

/// `code_type(+Code, ?Type)`.
pub(crate) fn code_type(s: &mut Solver, p: u32) -> KrResult<Flow> {
    classify(s, p, "code_type", As::Code)
}

/// `text_to_string(+Text, -String)`: an atom, string, number or code/char list as a string.
pub(crate) fn text_to_string(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let x = s.ad(p, 0);
    let Some(text) = text_of(s, x) else {
        return Err(match x {
            Cell::Ref(_) => inst("text_to_string", 2),
            _ => type_error(s, "text", x, "text_to_string", 2),
        });
    };
    let v = s.m.st.new_str(Arc::from(text.as_str()));
    let y = s.a(p, 1);
    Ok(if s.unify(y, v) {
        Flow::True
    } else {
        Flow::Fail
    })
}
