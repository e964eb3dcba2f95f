//! Writing terms as Prolog text: `writeq` style (reads back as the same term) and `write` style.

use super::ops;
use super::sym::{well_known as wk, Sym};
use super::term::Term;
use std::fmt::{self, Write};

/// How a term is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Style {
    /// Quote atoms and strings where needed so the text reads back as the same term (`writeq`).
    pub quoted: bool,
    /// Write operators in operator form (`a+b`) rather than canonical form (`+(a,b)`).
    pub operators: bool,
}

impl Style {
    /// `writeq/1`: quoted, with operators.
    pub const WRITEQ: Style = Style {
        quoted: true,
        operators: true,
    };
    /// `write/1` and `print/1`: unquoted, with operators.
    pub const WRITE: Style = Style {
        quoted: false,
        operators: true,
    };
    /// `write_canonical/1`: quoted, without operators.
    pub const CANONICAL: Style = Style {
        quoted: true,
        operators: false,
    };
}

impl Term {
    /// The term as text in the given style.
    pub fn to_text(&self, style: Style) -> String {
        let mut w = Writer {
            out: String::new(),
            style,
        };
        w.term(self, 1200);
        w.out
    }
}

impl fmt::Display for Term {
    /// Writes the term as `writeq/1` would.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text(Style::WRITEQ))
    }
}

fn is_symbol_char(c: char) -> bool {
    "+-*/\\^<>=~:.?@#&$".contains(c)
}

fn is_alnum(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// True when `name` can be written without quotes and reads back as the same atom.
pub fn atom_needs_no_quotes(name: &str) -> bool {
    if matches!(name, "[]" | "{}" | "!") {
        return true;
    }
    let mut chars = name.chars();
    match chars.next() {
        Some(c) if c.is_ascii_lowercase() => {
            chars.all(|c| c.is_ascii_alphanumeric() || c == '_') && !ops::is_operator(name)
        }
        _ => false,
    }
}

/// True when `name` written right before `(` reads back as that functor without quotes.
fn functor_needs_no_quotes(name: &str) -> bool {
    let mut chars = name.chars();
    match chars.next() {
        Some(c) if c.is_ascii_lowercase() => chars.all(|c| c.is_ascii_alphanumeric() || c == '_'),
        Some(_) => {
            matches!(name, "!" | ";") || (name.chars().all(is_symbol_char) && !name.contains("/*"))
        }
        None => false,
    }
}

/// Writes `name` as a quoted atom body with escapes.
pub fn quote_atom(name: &str) -> String {
    let mut s = String::with_capacity(name.len() + 2);
    s.push('\'');
    escape_into(&mut s, name, '\'');
    s.push('\'');
    s
}

fn escape_into(out: &mut String, text: &str, quote: char) {
    for c in text.chars() {
        match c {
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            '\r' => out.push_str("\\r"),
            c if c == quote => {
                out.push('\\');
                out.push(c)
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7f => {
                let _ = write!(out, "\\x{:x}\\", c as u32);
            }
            c => out.push(c),
        }
    }
}

/// Formats a float so that it reads back as a float (always with a `.` before any exponent).
pub fn format_float(f: f64) -> String {
    if f.is_nan() {
        return "nan".into();
    }
    if f.is_infinite() {
        return if f > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let s = format!("{f:?}");
    match s.find('e') {
        Some(pos) if !s[..pos].contains('.') => format!("{}.0{}", &s[..pos], &s[pos..]),
        _ => s,
    }
}

struct Writer {
    out: String,
    style: Style,
}

impl Writer {
    /// Appends a token, inserting a space when it would otherwise glue onto the previous token.
    fn token(&mut self, tok: &str) {
        if let (Some(prev), Some(next)) = (self.out.chars().last(), tok.chars().next()) {
            let glue = (is_symbol_char(prev) && is_symbol_char(next))
                || (is_alnum(prev) && is_alnum(next));
            if glue {
                self.out.push(' ');
            }
        }
        self.out.push_str(tok);
    }

    fn atom_text(&self, name: Sym) -> String {
        let text = name.name();
        if self.style.quoted && !atom_needs_no_quotes(text) {
            quote_atom(text)
        } else {
            text.to_string()
        }
    }

    fn term(&mut self, t: &Term, max_priority: u16) {
        match t {
            Term::Var(v) => self.token(v.name()),
            Term::Int(i) => self.token(&i.to_string()),
            Term::Float(f) => self.token(&format_float(f.0)),
            Term::Str(s) => {
                if self.style.quoted {
                    let mut q = String::from("\"");
                    escape_into(&mut q, s, '"');
                    q.push('"');
                    self.token(&q)
                } else {
                    self.token(s)
                }
            }
            Term::Atom(a) => {
                let text = self.atom_text(*a);
                self.token(&text)
            }
            Term::Compound(c) => self.compound(c.name, &c.args, max_priority),
        }
    }

    fn compound(&mut self, name: Sym, args: &[Term], max_priority: u16) {
        if name == wk::DOT && args.len() == 2 {
            return self.list(args);
        }
        if name == wk::CURLY && args.len() == 1 && self.style.operators {
            self.token("{");
            self.term(&args[0], 1200);
            self.token("}");
            return;
        }
        if self.style.operators {
            let text = name.name();
            if args.len() == 2 && text != "|" {
                if let Some(op) = ops::infix(text) {
                    let (lp, rp) = op.operand_priorities();
                    let paren = op.priority > max_priority;
                    if paren {
                        self.token("(");
                    }
                    self.operand(&args[0], lp);
                    if text == "," {
                        self.out.push(',');
                    } else if text.chars().all(is_alnum) {
                        self.out.push(' ');
                        self.out.push_str(text);
                        self.out.push(' ');
                    } else {
                        self.token(text);
                    }
                    self.operand_after_operator(&args[1], rp);
                    if paren {
                        self.token(")");
                    }
                    return;
                }
            }
            if args.len() == 1 {
                if let Some(op) = ops::prefix(text) {
                    let (_, rp) = op.operand_priorities();
                    let paren = op.priority > max_priority;
                    if paren {
                        self.token("(");
                    }
                    self.token(text);
                    let arg = &args[0];
                    let numeric = matches!(arg, Term::Int(_) | Term::Float(_));
                    if numeric && text == "-" || text.chars().all(is_alnum) {
                        self.out.push(' ');
                    }
                    self.operand_after_operator(arg, rp);
                    if paren {
                        self.token(")");
                    }
                    return;
                }
            }
        }
        let functor = if self.style.quoted && !functor_needs_no_quotes(name.name()) {
            quote_atom(name.name())
        } else {
            name.name().to_string()
        };
        self.token(&functor);
        self.out.push('(');
        for (i, a) in args.iter().enumerate() {
            if i > 0 {
                self.out.push(',');
            }
            self.term(a, 999);
        }
        self.out.push(')');
    }

    /// Writes an operand that follows an operator; an opening bracket right after a symbolic
    /// operator would turn the operator into a functor, so a space separates them.
    fn operand_after_operator(&mut self, arg: &Term, priority: u16) {
        let start = self.out.len();
        self.operand(arg, priority);
        if self.out[start..].starts_with('(') && start > 0 {
            let prev = self.out[..start].chars().last().unwrap_or(' ');
            if prev != ' ' && prev != ',' && prev != '(' {
                self.out.insert(start, ' ');
            }
        }
    }

    /// Writes an operand of an operator; an operator atom there is bracketed, so `(-)-a` does
    /// not read back as `-(-(a))`.
    fn operand(&mut self, arg: &Term, priority: u16) {
        match arg {
            Term::Atom(a) if ops::is_operator(a.name()) => {
                self.token("(");
                self.term(arg, 1200);
                self.token(")");
            }
            _ => self.term(arg, priority),
        }
    }

    fn list(&mut self, args: &[Term]) {
        self.token("[");
        self.term(&args[0], 999);
        let mut tail = &args[1];
        loop {
            match tail {
                Term::Compound(c) if c.name == wk::DOT && c.args.len() == 2 => {
                    self.out.push(',');
                    self.term(&c.args[0], 999);
                    tail = &c.args[1];
                }
                Term::Atom(a) if *a == wk::NIL => break,
                other => {
                    self.out.push('|');
                    self.term(other, 999);
                    break;
                }
            }
        }
        self.out.push(']');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(name: &str, args: Vec<Term>) -> Term {
        Term::compound(name, args)
    }
    fn a(name: &str) -> Term {
        Term::atom(name)
    }

    #[test]
    fn atoms_are_quoted_when_needed() {
        assert_eq!(a("foo").to_string(), "foo");
        assert_eq!(a("RoomA1").to_string(), "'RoomA1'");
        assert_eq!(a("Bot_1").to_string(), "'Bot_1'");
        assert_eq!(a("[]").to_string(), "[]");
        assert_eq!(a("it's").to_string(), "'it\\'s'");
        assert_eq!(a("+").to_string(), "'+'");
        assert_eq!(a("is").to_string(), "'is'");
        assert_eq!(a("").to_string(), "''");
        assert_eq!(a("RoomA1").to_text(Style::WRITE), "RoomA1");
    }

    #[test]
    fn operators_are_written_in_operator_form() {
        let x = Term::var("X");
        assert_eq!(c("=", vec![x.clone(), a("a")]).to_string(), "X=a");
        assert_eq!(
            c(
                "is",
                vec![x.clone(), c("+", vec![Term::Int(1), Term::Int(2)])]
            )
            .to_string(),
            "X is 1+2"
        );
        assert_eq!(c("-", vec![a("a"), Term::Int(-1)]).to_string(), "a- -1");
        assert_eq!(c("-", vec![Term::Int(1)]).to_string(), "- 1");
        assert_eq!(c("-", vec![a("a")]).to_string(), "-a");
        assert_eq!(
            c("\\+", vec![c("p", vec![x.clone()])]).to_string(),
            "\\+p(X)"
        );
        assert_eq!(
            c("*", vec![c("+", vec![a("a"), a("b")]), a("c")]).to_string(),
            "(a+b)*c"
        );
        assert_eq!(
            c("-", vec![a("a"), c("-", vec![a("b"), a("c")])]).to_string(),
            "a- (b-c)"
        );
        assert_eq!(
            c("f", vec![c(",", vec![a("a"), a("b")])]).to_string(),
            "f((a,b))"
        );
        assert_eq!(
            c(":-", vec![a("h"), c(",", vec![a("a"), a("b")])]).to_string(),
            "h:-a,b"
        );
        assert_eq!(
            c("-", vec![c(",", vec![a("a"), a("b")])]).to_string(),
            "- (a,b)"
        );
    }

    #[test]
    fn lists_strings_and_floats() {
        let l = Term::list_with_tail(vec![a("a"), Term::Int(1)], Term::var("T"));
        assert_eq!(l.to_string(), "[a,1|T]");
        assert_eq!(Term::list(vec![]).to_string(), "[]");
        assert_eq!(Term::string("say \"hi\"").to_string(), "\"say \\\"hi\\\"\"");
        assert_eq!(Term::from(25.0).to_string(), "25.0");
        assert_eq!(Term::from(1e22).to_string(), "1.0e22");
        assert_eq!(
            c("{}", vec![c(",", vec![a("a"), a("b")])]).to_string(),
            "{a,b}"
        );
        assert_eq!(c("mod", vec![a("a")]).to_string(), "mod(a)");
        assert_eq!(c("[]", vec![a("a")]).to_string(), "'[]'(a)");
        assert_eq!(c(",", vec![a("a")]).to_string(), "','(a)");
    }
}
