//! The one term type shared by the parser, the KR engines, percepts, actions, messages and traces.

use super::sym::{well_known as wk, Sym};
use smallvec::{smallvec, SmallVec};
use std::cmp::Ordering;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// The work stack of a walk over a term: inline for the usual shallow terms (no allocation on
/// the hot paths of hashing and comparison), on the heap only for deep ones.
type Stack<T> = SmallVec<[T; 16]>;

/// A Prolog term. Cheap to clone: compound terms share their arguments.
///
/// Equality, hashing, ordering and dropping walk the last argument in a loop rather than by
/// recursion, so long lists (and other right-nested terms) never overflow the stack.
#[derive(Clone, Debug)]
pub enum Term {
    /// An atom such as `foo`, `[]` or `'RoomA1'`.
    Atom(Sym),
    /// A 64-bit integer.
    Int(i64),
    /// An integer outside the 64-bit range (never one that fits: see [`Term::integer`]).
    BigInt(Arc<num_bigint::BigInt>),
    /// A floating-point number.
    Float(Float),
    /// A string literal `"..."`.
    Str(Arc<str>),
    /// A variable, identified by its name (`_G<n>` for anonymous variables after parsing).
    Var(Sym),
    /// A compound term `f(a1, ..., an)` with n >= 1; lists are `'.'(Head, Tail)` cells ending in `[]`.
    Compound(Arc<Compound>),
}

/// The functor and arguments of a compound term.
#[derive(Clone, Debug)]
pub struct Compound {
    /// The functor name.
    pub name: Sym,
    /// The arguments; never empty.
    pub args: Box<[Term]>,
}

impl Drop for Compound {
    fn drop(&mut self) {
        // Without an argument that is a unique compound holding unique compounds in turn, the
        // arguments are dropped in place: a unique compound argument's own drop then finds no
        // unique compound among its arguments and returns here, so this recurses one level at
        // most (a message `imp(token(T, K))` is freed without the work stack's bookkeeping).
        if !self.args.iter().any(holds_unique) {
            return;
        }
        // Argument lists whose uniquely owned compounds own compounds in turn wait on a heap
        // stack, so dropping a long list does not recurse. Most terms are shallow: their
        // sub-terms are dropped in place and the stack is never allocated.
        let mut stack = vec![];
        release(std::mem::take(&mut self.args), &mut stack);
        while let Some(args) = stack.pop() {
            release(args, &mut stack);
        }
    }
}

/// True for a compound term nothing else shares (dropping it frees it).
fn unique(t: &Term) -> bool {
    matches!(t, Term::Compound(c) if Arc::strong_count(c) == 1)
}

/// True for a compound term nothing else shares that holds such a compound itself.
fn holds_unique(t: &Term) -> bool {
    matches!(t, Term::Compound(c) if Arc::strong_count(c) == 1 && c.args.iter().any(unique))
}

/// Drops `args`, setting aside the argument lists of unique sub-terms that hold unique
/// compounds themselves.
fn release(args: Box<[Term]>, stack: &mut Vec<Box<[Term]>>) {
    for t in args.into_vec() {
        if let Term::Compound(arc) = t {
            if let Ok(mut c) = Arc::try_unwrap(arc) {
                if c.args.iter().any(unique) {
                    stack.push(std::mem::take(&mut c.args));
                }
            }
        }
    }
}

impl PartialEq for Term {
    fn eq(&self, other: &Term) -> bool {
        eq_shallow(self, other, SHALLOW)
    }
}

/// Nesting depth up to which equality and hashing recurse (into all but the last argument;
/// the last is followed by a loop, so long lists never count). Deeper parts are walked with an
/// explicit stack.
const SHALLOW: u32 = 48;

/// Equality by recursion while shallow, the iterative [`eq_deep`] beyond.
fn eq_shallow(mut a: &Term, mut b: &Term, budget: u32) -> bool {
    loop {
        return match (a, b) {
            (Term::Compound(x), Term::Compound(y)) => {
                if Arc::ptr_eq(x, y) {
                    return true;
                }
                if x.name != y.name || x.args.len() != y.args.len() {
                    return false;
                }
                if budget == 0 {
                    return eq_deep(a, b);
                }
                let n = x.args.len();
                for (p, q) in x.args[..n - 1].iter().zip(&y.args[..n - 1]) {
                    if !eq_shallow(p, q, budget - 1) {
                        return false;
                    }
                }
                a = &x.args[n - 1];
                b = &y.args[n - 1];
                continue;
            }
            (Term::Atom(x), Term::Atom(y)) | (Term::Var(x), Term::Var(y)) => x == y,
            (Term::Int(x), Term::Int(y)) => x == y,
            (Term::BigInt(x), Term::BigInt(y)) => x == y,
            (Term::Float(x), Term::Float(y)) => x == y,
            (Term::Str(x), Term::Str(y)) => x == y,
            _ => false,
        };
    }
}

/// Equality with an explicit stack (any nesting).
fn eq_deep(a: &Term, b: &Term) -> bool {
    let mut stack: Stack<(&Term, &Term)> = smallvec![(a, b)];
    while let Some((a, b)) = stack.pop() {
        let same = match (a, b) {
            (Term::Compound(x), Term::Compound(y)) => {
                if !Arc::ptr_eq(x, y) {
                    if x.name != y.name || x.args.len() != y.args.len() {
                        return false;
                    }
                    stack.extend(x.args.iter().zip(y.args.iter()).rev());
                }
                true
            }
            (Term::Atom(x), Term::Atom(y)) | (Term::Var(x), Term::Var(y)) => x == y,
            (Term::Int(x), Term::Int(y)) => x == y,
            (Term::BigInt(x), Term::BigInt(y)) => x == y,
            (Term::Float(x), Term::Float(y)) => x == y,
            (Term::Str(x), Term::Str(y)) => x == y,
            _ => false,
        };
        if !same {
            return false;
        }
    }
    true
}

impl Eq for Term {}

impl Hash for Term {
    fn hash<H: Hasher>(&self, state: &mut H) {
        hash_shallow(self, state, SHALLOW);
    }
}

/// Hashing depth-first, left to right: by recursion while shallow, with an explicit stack
/// beyond (both write the same sequence, so the hash does not depend on the path taken).
fn hash_shallow<H: Hasher>(mut t: &Term, state: &mut H, budget: u32) {
    loop {
        if budget == 0 {
            return hash_deep(t, state);
        }
        std::mem::discriminant(t).hash(state);
        match t {
            Term::Atom(s) | Term::Var(s) => s.hash(state),
            Term::Int(i) => i.hash(state),
            Term::BigInt(b) => b.hash(state),
            Term::Float(f) => f.hash(state),
            Term::Str(s) => s.hash(state),
            Term::Compound(c) => {
                c.name.hash(state);
                c.args.len().hash(state);
                let n = c.args.len();
                for a in &c.args[..n - 1] {
                    hash_shallow(a, state, budget - 1);
                }
                t = &c.args[n - 1];
                continue;
            }
        }
        return;
    }
}

/// Hashing with an explicit stack (any nesting).
fn hash_deep<H: Hasher>(t: &Term, state: &mut H) {
    let mut stack: Stack<&Term> = smallvec![t];
    while let Some(t) = stack.pop() {
        std::mem::discriminant(t).hash(state);
        match t {
            Term::Atom(s) | Term::Var(s) => s.hash(state),
            Term::Int(i) => i.hash(state),
            Term::BigInt(b) => b.hash(state),
            Term::Float(f) => f.hash(state),
            Term::Str(s) => s.hash(state),
            Term::Compound(c) => {
                c.name.hash(state);
                c.args.len().hash(state);
                stack.extend(c.args.iter().rev());
            }
        }
    }
}

impl PartialEq for Compound {
    fn eq(&self, other: &Compound) -> bool {
        self.name == other.name && self.args == other.args
    }
}

impl Eq for Compound {}

/// A float that is `Eq` and `Hash` by its bit pattern (with `-0.0` equal to `0.0`).
#[derive(Clone, Copy, Debug)]
pub struct Float(pub f64);

impl Float {
    fn key(self) -> u64 {
        if self.0 == 0.0 {
            0
        } else {
            self.0.to_bits()
        }
    }
}

impl PartialEq for Float {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}
impl Eq for Float {}
impl Hash for Float {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.key().hash(state)
    }
}

impl Term {
    /// An atom with the given name.
    pub fn atom(name: &str) -> Term {
        Term::Atom(Sym::intern(name))
    }

    /// A variable with the given name.
    pub fn var(name: &str) -> Term {
        Term::Var(Sym::intern(name))
    }

    /// A string term.
    pub fn string(text: &str) -> Term {
        Term::Str(Arc::from(text))
    }

    /// `name(args...)`, or the atom `name` when `args` is empty.
    pub fn compound(name: impl Into<Sym>, args: Vec<Term>) -> Term {
        let name = name.into();
        if args.is_empty() {
            Term::Atom(name)
        } else {
            Term::Compound(Arc::new(Compound {
                name,
                args: args.into_boxed_slice(),
            }))
        }
    }

    /// The empty list `[]`.
    pub fn nil() -> Term {
        Term::Atom(wk::NIL)
    }

    /// The list cell `[head | tail]`.
    pub fn cons(head: Term, tail: Term) -> Term {
        Term::compound(wk::DOT, vec![head, tail])
    }

    /// A proper list of the given items.
    pub fn list(items: impl IntoIterator<Item = Term, IntoIter: DoubleEndedIterator>) -> Term {
        Self::list_with_tail(items, Term::nil())
    }

    /// A list of the given items ending in `tail` (a partial list when `tail` is a variable).
    pub fn list_with_tail(
        items: impl IntoIterator<Item = Term, IntoIter: DoubleEndedIterator>,
        tail: Term,
    ) -> Term {
        items
            .into_iter()
            .rev()
            .fold(tail, |acc, item| Term::cons(item, acc))
    }

    /// An integer term: `Int` when it fits in 64 bits, `BigInt` otherwise.
    pub fn integer(n: num_bigint::BigInt) -> Term {
        match i64::try_from(&n) {
            Ok(i) => Term::Int(i),
            Err(_) => Term::BigInt(Arc::new(n)),
        }
    }

    /// The name and arity of an atom or compound (`None` for numbers, strings and variables).
    pub fn functor(&self) -> Option<(Sym, usize)> {
        match self {
            Term::Atom(s) => Some((*s, 0)),
            Term::Compound(c) => Some((c.name, c.args.len())),
            _ => None,
        }
    }

    /// The arguments of a compound term (empty for everything else).
    pub fn args(&self) -> &[Term] {
        match self {
            Term::Compound(c) => &c.args,
            _ => &[],
        }
    }

    /// True for `name/arity`.
    pub fn is_functor(&self, name: Sym, arity: usize) -> bool {
        self.functor() == Some((name, arity))
    }

    /// True when the term is an atom or a number.
    pub fn is_atomic(&self) -> bool {
        matches!(
            self,
            Term::Atom(_) | Term::Int(_) | Term::BigInt(_) | Term::Float(_) | Term::Str(_)
        )
    }

    /// True when the term is a variable.
    pub fn is_var(&self) -> bool {
        matches!(self, Term::Var(_))
    }

    /// True when the term is a list cell `[_|_]`.
    pub fn is_cons(&self) -> bool {
        self.is_functor(wk::DOT, 2)
    }

    /// True when the term contains no variables.
    pub fn is_ground(&self) -> bool {
        /// Recursion while shallow; `None` when too deep for it.
        fn shallow(t: &Term, budget: u32) -> Option<bool> {
            match t {
                Term::Var(_) => Some(false),
                Term::Compound(_) if budget == 0 => None,
                Term::Compound(c) => {
                    for a in c.args.iter() {
                        if !shallow(a, budget - 1)? {
                            return Some(false);
                        }
                    }
                    Some(true)
                }
                _ => Some(true),
            }
        }
        if let Some(g) = shallow(self, 64) {
            return g;
        }
        let mut stack: Stack<&Term> = smallvec![self];
        while let Some(t) = stack.pop() {
            match t {
                Term::Var(_) => return false,
                Term::Compound(c) => stack.extend(c.args.iter()),
                _ => {}
            }
        }
        true
    }

    /// True when `self` and `other` are equal up to a consistent renaming of variables (an
    /// open question stored in the mailbox and the term a query answer made of it).
    pub fn is_variant(&self, other: &Term) -> bool {
        let mut renamed: Vec<(Sym, Sym)> = Vec::new();
        let mut stack: Stack<(&Term, &Term)> = smallvec![(self, other)];
        while let Some(pair) = stack.pop() {
            match pair {
                (Term::Var(x), Term::Var(y)) => {
                    match renamed.iter().find(|(a, b)| a == x || b == y) {
                        Some((a, b)) if a != x || b != y => return false,
                        Some(_) => {}
                        None => renamed.push((*x, *y)),
                    }
                }
                (Term::Compound(c), Term::Compound(d)) => {
                    if c.name != d.name || c.args.len() != d.args.len() {
                        return false;
                    }
                    stack.extend(c.args.iter().zip(d.args.iter()));
                }
                (Term::Var(_), _) | (_, Term::Var(_)) => return false,
                (a, b) if a != b => return false,
                _ => {}
            }
        }
        true
    }

    /// A copy of the term for messages: parts nested deeper than `max_depth`, and everything
    /// after the first `max_nodes` sub-terms, are replaced by the atom `...` (built without
    /// recursion, so the result is small and shallow whatever the input).
    pub fn truncated(&self, max_depth: usize, max_nodes: usize) -> Term {
        enum W<'a> {
            Visit(&'a Term, usize),
            Build(Sym, usize),
        }
        let ellipsis = || Term::Atom(Sym::intern("..."));
        let mut nodes = 0usize;
        let mut work = vec![W::Visit(self, 0)];
        let mut out: Vec<Term> = Vec::new();
        while let Some(w) = work.pop() {
            match w {
                W::Visit(t, d) => {
                    nodes += 1;
                    match t {
                        Term::Compound(_) if d >= max_depth || nodes > max_nodes => {
                            out.push(ellipsis())
                        }
                        Term::Compound(c) => {
                            work.push(W::Build(c.name, c.args.len()));
                            work.extend(c.args.iter().rev().map(|a| W::Visit(a, d + 1)));
                        }
                        other => out.push(other.clone()),
                    }
                }
                W::Build(name, n) => {
                    let args = out.split_off(out.len() - n);
                    out.push(Term::compound(name, args));
                }
            }
        }
        out.pop().unwrap_or_else(ellipsis)
    }

    /// The items of a proper list, or `None` if the term is not a proper list.
    pub fn list_items(&self) -> Option<Vec<Term>> {
        let mut items = Vec::new();
        let mut cur = self;
        loop {
            match cur {
                Term::Atom(s) if *s == wk::NIL => return Some(items),
                Term::Compound(c) if c.name == wk::DOT && c.args.len() == 2 => {
                    items.push(c.args[0].clone());
                    cur = &c.args[1];
                }
                _ => return None,
            }
        }
    }

    /// Calls `f` on every variable occurrence, left to right (depth-first).
    pub fn for_each_var(&self, f: &mut impl FnMut(Sym)) {
        let mut stack = vec![self];
        while let Some(t) = stack.pop() {
            match t {
                Term::Var(v) => f(*v),
                Term::Compound(c) => stack.extend(c.args.iter().rev()),
                _ => {}
            }
        }
    }

    /// The distinct variables of the term in order of first appearance.
    pub fn vars(&self) -> Vec<Sym> {
        let mut out = Vec::new();
        self.for_each_var(&mut |v| {
            if !out.contains(&v) {
                out.push(v)
            }
        });
        out
    }

    /// Splits a conjunction `(a, b, c)` into its conjuncts `[a, b, c]` (inline up to four: most
    /// updates and conditions are short, and this runs for every one).
    pub fn conjuncts(&self) -> SmallVec<[&Term; 4]> {
        let mut out = SmallVec::new();
        let mut cur = self;
        while let Term::Compound(c) = cur {
            if c.name == wk::COMMA && c.args.len() == 2 {
                out.push(&c.args[0]);
                cur = &c.args[1];
            } else {
                break;
            }
        }
        out.push(cur);
        out
    }

    /// Builds the conjunction of `terms` (`true` when empty).
    pub fn conjunction(terms: Vec<Term>) -> Term {
        let mut iter = terms.into_iter().rev();
        match iter.next() {
            None => Term::Atom(wk::TRUE),
            Some(last) => iter.fold(last, |acc, t| Term::compound(wk::COMMA, vec![t, acc])),
        }
    }

    /// Depth of the deepest nesting (an atom has depth 1); computed without recursion.
    pub fn depth(&self) -> usize {
        let mut max = 0;
        let mut stack = vec![(self, 1usize)];
        while let Some((t, d)) = stack.pop() {
            max = max.max(d);
            if let Term::Compound(c) = t {
                stack.extend(c.args.iter().map(|a| (a, d + 1)));
            }
        }
        max
    }

    fn order_class(&self) -> u8 {
        match self {
            Term::Var(_) => 0,
            Term::Float(_) | Term::Int(_) | Term::BigInt(_) => 1,
            Term::Atom(_) => 3,
            Term::Str(_) => 4,
            Term::Compound(_) => 5,
        }
    }

    /// Compares two terms in the standard order of terms:
    /// Var < Number < Atom < String < Compound; numbers by value (Float before Int when equal);
    /// atoms alphabetically; compounds by arity, then name, then arguments left to right.
    pub fn compare(&self, other: &Term) -> Ordering {
        let mut stack: Stack<(&Term, &Term)> = smallvec![(self, other)];
        while let Some((a, b)) = stack.pop() {
            let class = a.order_class().cmp(&b.order_class());
            if class != Ordering::Equal {
                return class;
            }
            let o = match (a, b) {
                (Term::Var(x), Term::Var(y)) => x.name().cmp(y.name()),
                (Term::Int(x), Term::Int(y)) => x.cmp(y),
                (Term::Float(x), Term::Float(y)) => x.0.total_cmp(&y.0),
                (Term::Int(x), Term::Float(y)) => compare_int_float(*x, y.0),
                (Term::Float(x), Term::Int(y)) => compare_int_float(*y, x.0).reverse(),
                (Term::BigInt(_), _) | (_, Term::BigInt(_)) => compare_big(a, b),
                (Term::Atom(x), Term::Atom(y)) => x.name().cmp(y.name()),
                (Term::Str(x), Term::Str(y)) => x.cmp(y),
                (Term::Compound(x), Term::Compound(y)) => {
                    if Arc::ptr_eq(x, y) {
                        continue;
                    }
                    let head = x
                        .args
                        .len()
                        .cmp(&y.args.len())
                        .then_with(|| x.name.name().cmp(y.name.name()));
                    if head == Ordering::Equal {
                        stack.extend(x.args.iter().zip(y.args.iter()).rev());
                    }
                    head
                }
                _ => Ordering::Equal,
            };
            if o != Ordering::Equal {
                return o;
            }
        }
        Ordering::Equal
    }
}

/// Standard order between an integer and a float: by value, and the float first when equal.
fn compare_int_float(i: i64, f: f64) -> Ordering {
    match (i as f64).partial_cmp(&f) {
        Some(Ordering::Equal) | None => Ordering::Greater,
        Some(o) => o,
    }
}

/// Standard order of two numbers at least one of which is a big integer: by value, a float
/// first when equal.
fn compare_big(a: &Term, b: &Term) -> Ordering {
    use num_bigint::BigInt;
    use num_traits::ToPrimitive;
    let big = |t: &Term| match t {
        Term::Int(i) => Some(BigInt::from(*i)),
        Term::BigInt(b) => Some((**b).clone()),
        _ => None,
    };
    match (big(a), big(b)) {
        (Some(x), Some(y)) => x.cmp(&y),
        (Some(x), None) => float_order(x.to_f64().unwrap_or(f64::NAN), b),
        (None, Some(y)) => float_order(y.to_f64().unwrap_or(f64::NAN), a).reverse(),
        (None, None) => Ordering::Equal,
    }
}

/// A big integer (as the float `x`) against the float term `f`.
fn float_order(x: f64, f: &Term) -> Ordering {
    let Term::Float(f) = f else {
        return Ordering::Equal;
    };
    match x.partial_cmp(&f.0) {
        Some(Ordering::Equal) | None => Ordering::Greater,
        Some(o) => o,
    }
}

impl From<Sym> for Term {
    fn from(s: Sym) -> Term {
        Term::Atom(s)
    }
}

impl From<i64> for Term {
    fn from(i: i64) -> Term {
        Term::Int(i)
    }
}

impl From<f64> for Term {
    fn from(f: f64) -> Term {
        Term::Float(Float(f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_round_trip_through_items() {
        let l = Term::list(vec![Term::atom("a"), Term::Int(1)]);
        assert_eq!(l.list_items().unwrap(), vec![Term::atom("a"), Term::Int(1)]);
        assert!(Term::list_with_tail(vec![Term::atom("a")], Term::var("T"))
            .list_items()
            .is_none());
    }

    #[test]
    fn standard_order_of_terms() {
        let mut ts = [
            Term::compound("f", vec![Term::atom("a")]),
            Term::atom("b"),
            Term::Int(3),
            Term::var("X"),
            Term::from(2.5),
            Term::string("s"),
            Term::atom("a"),
            Term::compound("a", vec![Term::Int(1), Term::Int(2)]),
        ];
        ts.sort_by(|a, b| a.compare(b));
        let shown: Vec<String> = ts.iter().map(|t| t.to_string()).collect();
        assert_eq!(
            shown,
            ["X", "2.5", "3", "a", "b", "\"s\"", "f(a)", "a(1,2)"]
        );
        assert_eq!(Term::from(1.0).compare(&Term::Int(1)), Ordering::Less);
    }

    #[test]
    fn conjunctions_split_and_join() {
        let c = Term::conjunction(vec![Term::atom("a"), Term::atom("b"), Term::atom("c")]);
        let parts: Vec<String> = c.conjuncts().iter().map(|t| t.to_string()).collect();
        assert_eq!(parts, ["a", "b", "c"]);
        assert_eq!(Term::conjunction(vec![]), Term::atom("true"));
    }

    #[test]
    fn long_lists_compare_hash_and_drop_without_recursion() {
        let big = || Term::list((0..1_000_000).map(Term::Int));
        let (a, b) = (big(), big());
        assert_eq!(a, b);
        assert_eq!(a.compare(&b), Ordering::Equal);
        let mut h = std::collections::hash_map::DefaultHasher::new();
        a.hash(&mut h);
        drop(a);
        drop(b);
        // Nesting in a first argument, with lists inside: dropped without recursion too.
        let mut deep = Term::atom("z");
        for i in 0..1_000_000 {
            deep = Term::compound("f", vec![deep, Term::list([Term::Int(i)])]);
        }
        drop(deep);
        // One-argument nesting, and nesting whose every other level is shared elsewhere (each
        // drop then meets a unique compound holding a unique compound a level further down).
        let mut unary = Term::atom("z");
        for _ in 0..1_000_000 {
            unary = Term::compound("g", vec![unary]);
        }
        drop(unary);
        let (mut mixed, mut kept) = (Term::atom("z"), Vec::new());
        for i in 0..1_000_000 {
            mixed = Term::compound("h", vec![mixed, Term::Int(i)]);
            if i % 2 == 0 {
                kept.push(mixed.clone());
            }
        }
        drop(mixed);
        drop(kept);
    }

    #[test]
    fn big_integers_are_normalised_and_ordered_by_value() {
        use num_bigint::BigInt;
        assert_eq!(Term::integer(BigInt::from(5)), Term::Int(5));
        let big = Term::integer(BigInt::from(i64::MAX) + 1);
        assert!(matches!(big, Term::BigInt(_)));
        assert_eq!(big, Term::integer(BigInt::from(i64::MAX) + 1));
        assert_eq!(big.compare(&Term::Int(i64::MAX)), Ordering::Greater);
        assert_eq!(big.compare(&Term::from(1e30)), Ordering::Less);
        assert_eq!(
            Term::from(9.223372036854775808e18).compare(&big),
            Ordering::Less
        );
        let neg = Term::integer(BigInt::from(i64::MIN) * 2);
        assert_eq!(neg.compare(&Term::Int(i64::MIN)), Ordering::Less);
        assert_eq!(big.to_string(), "9223372036854775808");
    }

    #[test]
    fn ground_vars_and_depth() {
        let t = Term::compound(
            "f",
            vec![
                Term::var("X"),
                Term::compound("g", vec![Term::var("Y"), Term::var("X")]),
            ],
        );
        assert!(!t.is_ground());
        assert_eq!(t.vars(), vec![Sym::intern("X"), Sym::intern("Y")]);
        assert_eq!(t.depth(), 3);
    }
}
