//! Writing terms as Prolog text, as SWI-Prolog's `writeq`/`write`/`print` do: atoms are quoted
//! only where they must be, operators are written in operator form with brackets only where the
//! text would otherwise read back as another term. The writer is iterative (an explicit job
//! stack), so a term nested a million deep prints without recursion, and it has a depth-limited
//! mode (SWI's `max_depth`) that writes `...` for what lies deeper.

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
    /// `write/1`: unquoted, with operators.
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

/// Everything that decides how a term is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// Quoting and operators.
    pub style: Style,
    /// Nesting depth (and list length) beyond which `...` is written; 0 for no limit.
    pub max_depth: usize,
    /// The context priority: a term whose operator binds looser is bracketed (1200: none; an
    /// answer `X = V` writes `V` at 699, so `X = (a:-b)` and `X = (>)`).
    pub priority: u16,
    /// Write every variable as `_` (answers of `goal prolog` do).
    pub anonymous_vars: bool,
}

impl Options {
    /// Options with this style, no depth limit and priority 1200.
    pub fn new(style: Style) -> Options {
        Options {
            style,
            max_depth: 0,
            priority: 1200,
            anonymous_vars: false,
        }
    }
}

/// The depth limit for terms quoted inside error messages (like SWI's messages).
pub const MESSAGE_DEPTH: usize = 10;

impl Term {
    /// The term as text in the given style.
    pub fn to_text(&self, style: Style) -> String {
        self.to_text_with(Options::new(style))
    }

    /// The term as text with the given options.
    pub fn to_text_with(&self, options: Options) -> String {
        let mut w = Writer {
            out: String::new(),
            o: options,
        };
        w.run(self);
        w.out
    }

    /// `writeq` text cut off at depth `max_depth` with `...` (for messages about big terms).
    pub fn to_text_limited(&self, max_depth: usize) -> String {
        self.to_text_with(Options {
            max_depth,
            ..Options::new(Style::WRITEQ)
        })
    }

    /// The text GOAL's `print/1` action writes: an atom or string without its quotes, any other
    /// term as `writeq` writes it (so inner atoms keep their quotes).
    pub fn to_print_text(&self) -> String {
        match self {
            Term::Atom(a) => a.name().to_string(),
            Term::Str(s) => s.to_string(),
            other => other.to_text(Style::WRITEQ),
        }
    }
}

impl fmt::Display for Term {
    /// Writes the term as `writeq/1` would.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text(Style::WRITEQ))
    }
}

/// The symbol characters: runs of them form atoms like `+`, `=..` or `-->`.
fn is_symbol_char(c: char) -> bool {
    "+-*/\\^<>=~:.?@#&$".contains(c)
}

fn is_alnum(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// True when `name` can be written without quotes and reads back as the same atom (SWI's
/// rules: solo atoms, symbol-character atoms, and letter-digit atoms starting with a lowercase
/// letter, Unicode included).
pub fn atom_needs_no_quotes(name: &str) -> bool {
    if matches!(name, "[]" | "{}" | "!" | ";") {
        return true;
    }
    let mut chars = name.chars();
    match chars.next() {
        Some(c) if c.is_lowercase() => chars.all(is_alnum),
        Some(c) if is_symbol_char(c) => {
            name.chars().all(is_symbol_char) && name != "." && !name.starts_with("/*")
        }
        _ => false,
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

/// Formats a float as SWI-Prolog does: the shortest text that reads back as the same float,
/// always with a `.` before any exponent, and an exponent from 1.0e15 up.
pub fn format_float(f: f64) -> String {
    if f.is_nan() {
        return "nan".into();
    }
    if f.is_infinite() {
        return if f > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let s = if f.abs() >= 1e15 {
        format!("{f:e}")
    } else {
        format!("{f:?}")
    };
    match s.find('e') {
        Some(pos) if !s[..pos].contains('.') => format!("{}.0{}", &s[..pos], &s[pos..]),
        _ => s,
    }
}

/// How the text of an operand begins, as far as a prefix operator before it cares.
#[derive(PartialEq, Eq)]
enum Lead {
    Digit,
    /// An opening bracket around a term of this priority (0 for an operator atom).
    Paren(u16),
    Other,
}

/// How the text of `t`, written at priority `prio`, begins.
fn lead(mut t: &Term, mut prio: u16) -> Lead {
    loop {
        match t {
            Term::Int(i) => return if *i >= 0 { Lead::Digit } else { Lead::Other },
            Term::BigInt(b) => {
                return match b.sign() {
                    num_bigint::Sign::Minus => Lead::Other,
                    _ => Lead::Digit,
                }
            }
            Term::Float(f) if f.0 >= 0.0 && f.0.is_finite() => return Lead::Digit,
            Term::Atom(a) if prio < 1200 && ops::is_operator(a.name()) => return Lead::Paren(0),
            Term::Compound(c) if c.args.len() == 2 && c.name != wk::DOT && c.name != wk::BAR => {
                let Some(op) = ops::infix(c.name.name()) else {
                    return Lead::Other;
                };
                if op.priority > prio {
                    return Lead::Paren(op.priority);
                }
                prio = op.operand_priorities().0;
                t = &c.args[0];
            }
            Term::Compound(c) if c.args.len() == 1 => {
                return match ops::prefix(c.name.name()) {
                    Some(op) if op.priority > prio => Lead::Paren(op.priority),
                    _ => Lead::Other,
                };
            }
            _ => return Lead::Other,
        }
    }
}

/// One step of the writer.
enum Job<'t> {
    /// A term at a context priority and depth; `arg` for arguments of `f(...)` and list items.
    Term(&'t Term, u16, usize, bool),
    /// A token that may need a space before it so it does not glue onto the previous one.
    Tok(&'static str),
    /// Text written as it is.
    Raw(&'static str),
    /// A word operator (`is`, `mod`) with a space on either side.
    Word(&'static str),
    /// The rest of a list after item `index`.
    Tail(&'t Term, usize, usize),
}

struct Writer {
    out: String,
    o: Options,
}

impl Writer {
    fn run(&mut self, t: &Term) {
        let mut jobs = vec![Job::Term(t, self.o.priority, 1, false)];
        while let Some(job) = jobs.pop() {
            match job {
                Job::Term(t, prio, depth, arg) => self.term(t, prio, depth, arg, &mut jobs),
                Job::Tok(s) => self.token(s),
                Job::Raw(s) => self.out.push_str(s),
                Job::Word(s) => {
                    self.out.push(' ');
                    self.out.push_str(s);
                    self.out.push(' ');
                }
                Job::Tail(t, depth, index) => self.tail(t, depth, index, &mut jobs),
            }
        }
    }

    fn too_deep(&self, depth: usize) -> bool {
        self.o.max_depth > 0 && depth > self.o.max_depth
    }

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

    fn atom_text(&self, name: &str) -> String {
        if self.o.style.quoted && !atom_needs_no_quotes(name) {
            quote_atom(name)
        } else {
            name.to_string()
        }
    }

    fn term<'t>(
        &mut self,
        t: &'t Term,
        prio: u16,
        depth: usize,
        arg: bool,
        jobs: &mut Vec<Job<'t>>,
    ) {
        if self.too_deep(depth) {
            return self.token("...");
        }
        match t {
            Term::Var(_) if self.o.anonymous_vars => self.token("_"),
            Term::Var(v) => self.token(v.name()),
            Term::Int(i) => self.token(&i.to_string()),
            Term::BigInt(b) => self.token(&b.to_string()),
            Term::Float(f) => self.token(&format_float(f.0)),
            Term::Str(s) => {
                if self.o.style.quoted {
                    let mut q = String::from("\"");
                    escape_into(&mut q, s, '"');
                    q.push('"');
                    self.token(&q)
                } else {
                    self.token(s)
                }
            }
            Term::Atom(a) => {
                let text = self.atom_text(a.name());
                // An operator as an operand is bracketed, so `- (-)` does not read as `- -`.
                if self.o.style.operators && !arg && prio < 1200 && ops::is_operator(a.name()) {
                    self.token("(");
                    self.out.push_str(&text);
                    self.out.push(')');
                } else {
                    self.token(&text)
                }
            }
            Term::Compound(c) => self.compound(c.name, &c.args, prio, depth, jobs),
        }
    }

    fn compound<'t>(
        &mut self,
        name: Sym,
        args: &'t [Term],
        prio: u16,
        depth: usize,
        jobs: &mut Vec<Job<'t>>,
    ) {
        if name == wk::DOT && args.len() == 2 {
            self.token("[");
            jobs.push(Job::Tail(&args[1], depth, 0));
            jobs.push(Job::Term(&args[0], 999, depth + 1, true));
            return;
        }
        if self.o.style.operators {
            if name == wk::CURLY && args.len() == 1 {
                self.token("{");
                jobs.push(Job::Raw("}"));
                jobs.push(Job::Term(&args[0], 1200, depth + 1, false));
                return;
            }
            let text = name.name();
            if args.len() == 2 && name != wk::BAR {
                if let Some(op) = ops::infix(text) {
                    return self.infix(op, args, prio, depth, jobs);
                }
            }
            if args.len() == 1 {
                if let Some(op) = ops::prefix(text) {
                    let (_, rp) = op.operand_priorities();
                    let lead = lead(&args[0], rp);
                    let numeric = (text == "-" || text == "+") && lead == Lead::Digit;
                    if !matches!(lead, Lead::Paren(_)) && !numeric {
                        return self.prefix(op, &args[0], prio, depth, jobs);
                    }
                }
            }
        }
        let functor = match name.name() {
            "[]" | "{}" if self.o.style.quoted => quote_atom(name.name()),
            other => self.atom_text(other),
        };
        self.token(&functor);
        self.out.push('(');
        jobs.push(Job::Raw(")"));
        for (i, a) in args.iter().enumerate().rev() {
            jobs.push(Job::Term(a, 999, depth + 1, true));
            if i > 0 {
                jobs.push(Job::Raw(","));
            }
        }
    }

    fn infix<'t>(
        &mut self,
        op: ops::Op,
        args: &'t [Term],
        prio: u16,
        depth: usize,
        jobs: &mut Vec<Job<'t>>,
    ) {
        let (lp, rp) = op.operand_priorities();
        let paren = op.priority > prio;
        if paren {
            self.token("(");
            jobs.push(Job::Raw(")"));
        }
        jobs.push(Job::Term(&args[1], rp, depth + 1, false));
        // `a-(b:-c)` would read as the functor `-` applied to `b:-c`, an argument too loose
        // for functional notation; a space keeps the operator infix.
        if matches!(lead(&args[1], rp), Lead::Paren(p) if p > 999) && op.name != "," {
            jobs.push(Job::Raw(" "));
        }
        jobs.push(if op.name == "," {
            Job::Raw(",")
        } else if op.name.chars().all(is_alnum) {
            Job::Word(op.name)
        } else {
            Job::Tok(op.name)
        });
        jobs.push(Job::Term(&args[0], lp, depth + 1, false));
    }

    fn prefix<'t>(
        &mut self,
        op: ops::Op,
        arg: &'t Term,
        prio: u16,
        depth: usize,
        jobs: &mut Vec<Job<'t>>,
    ) {
        let (_, rp) = op.operand_priorities();
        if op.priority > prio {
            self.token("(");
            jobs.push(Job::Raw(")"));
        }
        self.token(op.name);
        jobs.push(Job::Term(arg, rp, depth + 1, false));
    }

    /// Writes the rest of a list: `,Item` cells, then `|Tail` or `]`.
    fn tail<'t>(&mut self, t: &'t Term, depth: usize, index: usize, jobs: &mut Vec<Job<'t>>) {
        match t {
            Term::Compound(c) if c.name == wk::DOT && c.args.len() == 2 => {
                // SWI shows `max_depth - depth + 1` items of a list at `depth`.
                if self.o.max_depth > 0 && depth + index + 1 > self.o.max_depth {
                    self.out.push_str("|...]");
                    return;
                }
                self.out.push(',');
                jobs.push(Job::Tail(&c.args[1], depth, index + 1));
                jobs.push(Job::Term(&c.args[0], 999, depth + 1, true));
            }
            Term::Atom(a) if *a == wk::NIL => self.out.push(']'),
            other => {
                self.out.push('|');
                jobs.push(Job::Raw("]"));
                jobs.push(Job::Term(other, 999, depth + 1, true));
            }
        }
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
    fn atoms_are_quoted_only_where_swi_quotes_them() {
        assert_eq!(a("foo").to_string(), "foo");
        assert_eq!(a("RoomA1").to_string(), "'RoomA1'");
        assert_eq!(a("Bot_1").to_string(), "'Bot_1'");
        assert_eq!(a("[]").to_string(), "[]");
        assert_eq!(a("it's").to_string(), "'it\\'s'");
        assert_eq!(a("").to_string(), "''");
        assert_eq!(a("RoomA1").to_text(Style::WRITE), "RoomA1");
        for bare in [
            "+", "is", ";", ">", "\\", "-", "-->", "ü", "straße", "---", "!", "{}", "=..",
        ] {
            assert_eq!(a(bare).to_string(), bare);
        }
        for (atom, quoted) in [
            (",", "','"),
            ("|", "'|'"),
            (".", "'.'"),
            ("/*", "'/*'"),
            ("Über", "'Über'"),
            ("_x", "'_x'"),
            ("a b", "'a b'"),
        ] {
            assert_eq!(a(atom).to_string(), quoted);
        }
    }

    #[test]
    fn operators_are_written_in_operator_form() {
        let x = Term::var("X");
        let i = Term::Int;
        assert_eq!(c("=", vec![x.clone(), a("a")]).to_string(), "X=a");
        assert_eq!(
            c("is", vec![x.clone(), c("+", vec![i(1), i(2)])]).to_string(),
            "X is 1+2"
        );
        assert_eq!(c("-", vec![a("a"), i(-1)]).to_string(), "a- -1");
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
            "a-(b-c)"
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
            "-((a,b))"
        );
    }

    #[test]
    fn prefix_minus_never_reads_back_as_a_negative_number() {
        let i = Term::Int;
        let pow = c("^", vec![i(2), i(2)]);
        assert_eq!(c("-", vec![i(1)]).to_string(), "-(1)");
        assert_eq!(c("-", vec![Term::from(1.5)]).to_string(), "-(1.5)");
        assert_eq!(c("-", vec![pow.clone()]).to_string(), "-(2^2)");
        assert_eq!(c("-", vec![c("^", vec![a("a"), i(2)])]).to_string(), "-a^2");
        assert_eq!(c("-", vec![c("-", vec![i(1)])]).to_string(), "- -(1)");
        assert_eq!(c("-", vec![i(-1)]).to_string(), "- -1");
        assert_eq!(c("^", vec![i(-1), i(2)]).to_string(), "-1^2");
        assert_eq!(
            c("-", vec![c("+", vec![a("a"), a("b")])]).to_string(),
            "-(a+b)"
        );
    }

    #[test]
    fn operator_atoms_are_bracketed_as_operands_only() {
        assert_eq!(c("f", vec![a("-"), a(":-")]).to_string(), "f(-,:-)");
        assert_eq!(Term::list(vec![a("-"), a(";")]).to_string(), "[-,;]");
        assert_eq!(c("-", vec![a("-")]).to_string(), "-(-)");
        assert_eq!(c("-", vec![a("-"), a("-")]).to_string(), "(-)-(-)");
        let answer = |t: &Term| {
            t.to_text_with(Options {
                priority: 699,
                ..Options::new(Style::WRITEQ)
            })
        };
        assert_eq!(answer(&a(">")), "(>)");
        assert_eq!(answer(&c(":-", vec![a("a"), a("b")])), "(a:-b)");
        assert_eq!(answer(&c("-", vec![a("a"), a("b")])), "a-b");
    }

    #[test]
    fn lists_strings_and_floats() {
        let l = Term::list_with_tail(vec![a("a"), Term::Int(1)], Term::var("T"));
        assert_eq!(l.to_string(), "[a,1|T]");
        assert_eq!(Term::list(vec![]).to_string(), "[]");
        assert_eq!(Term::string("say \"hi\"").to_string(), "\"say \\\"hi\\\"\"");
        assert_eq!(Term::from(25.0).to_string(), "25.0");
        assert_eq!(Term::from(1e22).to_string(), "1.0e22");
        assert_eq!(Term::from(1e15).to_string(), "1.0e15");
        assert_eq!(
            Term::from(123456789012345.0).to_string(),
            "123456789012345.0"
        );
        assert_eq!(
            c("{}", vec![c(",", vec![a("a"), a("b")])]).to_string(),
            "{a,b}"
        );
        assert_eq!(c("mod", vec![a("a")]).to_string(), "mod(a)");
        assert_eq!(c("[]", vec![a("a")]).to_string(), "'[]'(a)");
        assert_eq!(c(",", vec![a("a")]).to_string(), "','(a)");
    }

    #[test]
    fn print_text_strips_only_the_outer_quotes() {
        assert_eq!(a("hello world").to_print_text(), "hello world");
        assert_eq!(Term::string("hi").to_print_text(), "hi");
        assert_eq!(c("f", vec![a("A b"), a("c")]).to_print_text(), "f('A b',c)");
        assert_eq!(
            Term::list(vec![a("A"), a("b c")]).to_print_text(),
            "['A','b c']"
        );
    }

    #[test]
    fn huge_terms_print_without_recursion_and_limited_when_asked() {
        let mut deep = a("z");
        for _ in 0..1_000_000 {
            deep = c("f", vec![deep]);
        }
        let text = deep.to_string();
        assert_eq!(text.len(), 1_000_000 * 3 + 1);
        assert_eq!(deep.to_text_limited(3), "f(f(f(...)))");
        let long = Term::list((0..1_000_000).map(Term::Int));
        assert!(long.to_string().ends_with(",999999]"));
        assert_eq!(long.to_text_limited(5), "[0,1,2,3,4|...]");
        // SWI's documented example.
        let s = |t: Term| c("s", vec![t]);
        let example = c(
            "a",
            vec![
                s(s(s(s(Term::Int(0))))),
                Term::list(["a", "b", "c", "d", "e", "f"].map(a)),
            ],
        );
        assert_eq!(example.to_text_limited(3), "a(s(s(...)),[a,b|...])");
        let mut ops = a("z");
        for _ in 0..100_000 {
            ops = c("-", vec![a("a"), ops]);
        }
        assert!(ops.to_string().starts_with("a-(a-(a-"));
    }
}
