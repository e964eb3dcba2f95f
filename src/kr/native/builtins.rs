//! The built-in predicate table and the deterministic built-ins that are not about arithmetic,
//! text, lists or output (those have their own files). Library predicates that are easiest in
//! Prolog live in the prelude (`prelude.rs`).

use super::machine::Solver;
use super::store::{Cell, VarNames};
use super::{arith, lists, output, text};
use crate::kr::error::{KrError, KrResult};
use crate::kr::knowledge::{Knowledge, PredRef};
use crate::term::{well_known as wk, Sym, Term};
use std::cmp::Ordering;
use std::sync::OnceLock;

/// What a deterministic built-in wants the solver to do next.
pub(crate) enum Flow {
    Fail,
    True,
    /// Continue by calling this goal (opaque to cut).
    Call(Cell),
}

macro_rules! builtins {
    ($($v:ident $name:literal [$($arity:literal),*] $lib:literal;)*) => {
        /// A built-in predicate (or control construct).
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub(crate) enum B { $($v),* }
        /// Name, arities and whether a program may redefine it (library predicates may).
        const TABLE: &[(B, &str, &[u32], bool)] = &[$((B::$v, $name, &[$($arity),*], $lib)),*];
    };
}

builtins! {
    True "true" [0] false; Otherwise "otherwise" [0] false; Fail "fail" [0] false; False "false" [0] false;
    Cut "!" [0] false; Comma "," [2] false; Or ";" [2] false; OrBar "|" [2] false;
    IfThen "->" [2] false; SoftIfThen "*->" [2] false; Not "\\+" [1] false; NotWord "not" [1] false;
    Call "call" [1, 2, 3, 4, 5, 6, 7, 8] false; Findall "findall" [3] false; Findall4 "findall" [4] false;
    Catch "catch" [3] false; Throw "throw" [1] false;
    Between "between" [3] false; Member "member" [2] true; Repeat "repeat" [0] false;
    Once "once" [1] false; Ignore "ignore" [1] false; Forall "forall" [2] false; Caret "^" [2] false;
    Unify "=" [2] false; NotUnify "\\=" [2] false; UnifyOc "unify_with_occurs_check" [2] false;
    Eq "==" [2] false; Neq "\\==" [2] false; Lt "@<" [2] false; Le "@=<" [2] false;
    Gt "@>" [2] false; Ge "@>=" [2] false; Compare "compare" [3] false;
    Variant "=@=" [2] false; NotVariant "\\=@=" [2] false;
    Var "var" [1] false; Nonvar "nonvar" [1] false; Atom "atom" [1] false; Number "number" [1] false;
    Integer "integer" [1] false; Float "float" [1] false; Atomic "atomic" [1] false;
    Compound "compound" [1] false; Callable "callable" [1] false; IsList "is_list" [1] false;
    String "string" [1] false; Ground "ground" [1] false; IsDict "is_dict" [1] false;
    Is "is" [2] false; ArEq "=:=" [2] false; ArNe "=\\=" [2] false; ArLt "<" [2] false;
    ArLe "=<" [2] false; ArGt ">" [2] false; ArGe ">=" [2] false; Succ "succ" [2] false;
    Plus "plus" [3] false; RandomBetween "random_between" [3] true; RandomFloat "random" [1] true;
    RandomMember "random_member" [2] true; RandomPermutation "random_permutation" [2] true;
    Functor "functor" [3] false; Arg "arg" [3] false; Univ "=.." [2] false;
    CopyTerm "copy_term" [2] false; TermVariables "term_variables" [2] false; Tab "tab" [1, 2] false;
    AtomCodes "atom_codes" [2] false; AtomChars "atom_chars" [2] false; CharCode "char_code" [2] false;
    AtomLength "atom_length" [2] false; AtomConcat "atom_concat" [3] false; SubAtom "sub_atom" [5] false;
    AtomNumber "atom_number" [2] false; NumberCodes "number_codes" [2] false;
    NumberChars "number_chars" [2] false; AtomString "atom_string" [2] false;
    AtomToTerm "atom_to_term" [3] false; TermToAtom "term_to_atom" [2] false;
    TermString "term_string" [2] false;
    UpcaseAtom "upcase_atom" [2] false; DowncaseAtom "downcase_atom" [2] false;
    StringConcat "string_concat" [3] false; StringChars "string_chars" [2] false;
    StringCodes "string_codes" [2] false; StringToAtom "string_to_atom" [2] false;
    StringLength "string_length" [2] false; SubString "sub_string" [5] false;
    SplitString "split_string" [4] false; NumberString "number_string" [2] false;
    StringLower "string_lower" [2] false; StringUpper "string_upper" [2] false;
    StringCode "string_code" [3] false; TextConcat "text_concat" [3] false;
    AtomicListConcat "atomic_list_concat" [2, 3] false;
    Write "write" [1, 2] false; Print "print" [1, 2] false; Writeln "writeln" [1, 2] false;
    Writeq "writeq" [1, 2] false; WriteCanonical "write_canonical" [1, 2] false;
    WriteTerm "write_term" [2, 3] false;
    Nl "nl" [0, 1] false; Format "format" [1, 2, 3] false; PrintMessage "print_message" [2] false;
    GetTime "get_time" [1] false;
    Length "length" [2] true; Delete "delete" [3] true; Memberchk "memberchk" [2] true; Reverse "reverse" [2] true;
    Msort "msort" [2] true; Sort "sort" [2] false; Sort4 "sort" [4] false; Keysort "keysort" [2] false;
    Predsort "predsort" [3] true;
    Nth0 "nth0" [3] true; Nth1 "nth1" [3] true; SumList "sum_list" [2] true; SumList2 "sumlist" [2] true;
    MaxList "max_list" [2] true; MinList "min_list" [2] true; MaxMember "max_member" [2] true;
    MinMember "min_member" [2] true; Numlist "numlist" [3] true; ListToSet "list_to_set" [2] true;
    Flatten "flatten" [2] true; PairsKeysValues "pairs_keys_values" [3] true;
    PairsKeys "pairs_keys" [2] true; PairsValues "pairs_values" [2] true;
    OrdSubtract "ord_subtract" [3] true; OrdUnion "ord_union" [3] true; OrdUnion2 "ord_union" [2] true;
    OrdIntersection "ord_intersection" [3] true; OrdMemberchk "ord_memberchk" [2] true;
    OrdInsert "ord_insert" [3] true; OrdAddElement "ord_add_element" [3] true;
    OrdDelElement "ord_del_element" [3] true; OrdSubset "ord_subset" [2] true;
    ListToOrdSet "list_to_ord_set" [2] true; OrdEmpty "ord_empty" [1] true;
    RandomSelect "random_select" [3] true; Randseq "randseq" [3] true; Randset "randset" [3] true;
    CharType "char_type" [2] false; CodeType "code_type" [2] false;
    TextToString "text_to_string" [2] false;
    SumEval "$sum_eval" [2] false; MaxEval "$max_eval" [3] false; BagofPrep "$bagof_prep" [4] false;
    BagofGroups "$bagof_groups" [2] false; Protected "$protected" [] false;
}

/// True when programs may redefine this built-in (SWI library predicates).
pub(crate) fn is_library(b: B) -> bool {
    TABLE.iter().any(|(x, _, _, lib)| *x == b && *lib)
}

/// The library: built-ins plus the prelude clauses, compiled once.
pub(crate) fn library() -> &'static Knowledge {
    static LIB: OnceLock<Knowledge> = OnceLock::new();
    LIB.get_or_init(|| {
        let mut k = Knowledge::blank();
        for (b, name, arities, _) in TABLE {
            for a in arities.iter() {
                k.table
                    .insert((Sym::intern(name), *a), PredRef::Builtin(*b));
            }
        }
        // Protected predicates called at run time (`call(assert(X))`, a `goal prolog` query)
        // raise a permission error instead of failing as unknown predicates do.
        for name in crate::kr::knowledge::protected_names() {
            for a in 0..=4 {
                k.table
                    .entry((Sym::intern(name), a))
                    .or_insert(PredRef::Builtin(B::Protected));
            }
        }
        // So are file and operating-system predicates: an agent never reads or writes files
        // (knowledge may still define predicates of these names; they then shadow these).
        for (name, arities) in crate::kr::knowledge::FILE_IO {
            for a in arities.iter() {
                k.table
                    .entry((Sym::intern(name), *a))
                    .or_insert(PredRef::Builtin(B::Protected));
            }
        }
        for clause in super::prelude::clauses() {
            k.add(&clause);
        }
        // Convert to library references first, so that body goals resolve to them.
        let mut k = k.into_library();
        k.finish();
        k
    })
}

// ---- errors ----

/// `error(instantiation_error, Name/Arity)`.
pub(crate) fn inst(name: &str, arity: usize) -> KrError {
    KrError::iso(
        Term::atom("instantiation_error"),
        Some((Sym::intern(name), arity)),
    )
}

/// `error(type_error(Type, Culprit), Name/Arity)`.
pub(crate) fn type_error(s: &Solver, ty: &str, culprit: Cell, name: &str, arity: usize) -> KrError {
    let t = s.m.st.to_term(culprit, &mut VarNames::new(&[]));
    KrError::iso(
        Term::compound("type_error", vec![Term::atom(ty), t]),
        Some((Sym::intern(name), arity)),
    )
}

/// `error(domain_error(Domain, Culprit), Name/Arity)`.
pub(crate) fn domain_error(
    s: &Solver,
    d: &str,
    culprit: Cell,
    name: &str,
    arity: usize,
) -> KrError {
    let t = s.m.st.to_term(culprit, &mut VarNames::new(&[]));
    KrError::iso(
        Term::compound("domain_error", vec![Term::atom(d), t]),
        Some((Sym::intern(name), arity)),
    )
}

/// An integer argument (instantiation or type error otherwise).
pub(crate) fn int_arg(s: &Solver, p: u32, i: u32, name: &str, arity: usize) -> KrResult<i64> {
    match s.ad(p, i) {
        Cell::Int(n) => Ok(n),
        Cell::Ref(_) => Err(inst(name, arity)),
        other => Err(type_error(s, "integer", other, name, arity)),
    }
}

fn bool_flow(b: bool) -> Flow {
    if b {
        Flow::True
    } else {
        Flow::Fail
    }
}

/// Builds a goal `name(args...)` for [`Flow::Call`].
pub(crate) fn goal(s: &mut Solver, name: &str, args: &[Cell]) -> Cell {
    s.m.st.new_struct(Sym::intern(name), args)
}

/// Runs a deterministic built-in.
pub(crate) fn det(s: &mut Solver, b: B, g: Cell, p: u32) -> KrResult<Flow> {
    let arity = s.m.st.functor(g).map_or(0, |f| f.1);
    Ok(match b {
        B::Otherwise => Flow::True,
        B::False => Flow::Fail,
        B::OrBar => {
            let (l, r) = (s.a(p, 0), s.a(p, 1));
            Flow::Call(s.m.st.new_struct(wk::SEMICOLON, &[l, r]))
        }
        B::NotWord => {
            let a = s.a(p, 0);
            Flow::Call(s.m.st.new_struct(wk::NAF, &[a]))
        }
        B::Once => {
            let a = s.a(p, 0);
            let t = Cell::Atom(wk::TRUE);
            Flow::Call(s.m.st.new_struct(wk::ARROW, &[a, t]))
        }
        B::Ignore => {
            let a = s.a(p, 0);
            let t = Cell::Atom(wk::TRUE);
            let ite = s.m.st.new_struct(wk::ARROW, &[a, t]);
            Flow::Call(s.m.st.new_struct(wk::SEMICOLON, &[ite, t]))
        }
        B::Forall => {
            let (c, a) = (s.a(p, 0), s.a(p, 1));
            let na = s.m.st.new_struct(wk::NAF, &[a]);
            let conj = s.m.st.new_struct(wk::COMMA, &[c, na]);
            Flow::Call(s.m.st.new_struct(wk::NAF, &[conj]))
        }
        B::Caret => Flow::Call(s.a(p, 1)),
        B::Unify => {
            let (x, y) = (s.a(p, 0), s.a(p, 1));
            bool_flow(s.unify(x, y))
        }
        B::UnifyOc => {
            let (x, y) = (s.a(p, 0), s.a(p, 1));
            let old = s.m.st.occurs_check;
            s.m.st.occurs_check = true;
            let ok = s.unify(x, y);
            s.m.st.occurs_check = old;
            bool_flow(ok)
        }
        B::NotUnify => {
            let (x, y) = (s.a(p, 0), s.a(p, 1));
            let mark = s.m.st.trail.len();
            let ok = s.unify(x, y);
            s.m.st.undo(mark);
            bool_flow(!ok)
        }
        B::Eq | B::Neq | B::Lt | B::Le | B::Gt | B::Ge => {
            let o = s.m.st.compare(s.a(p, 0), s.a(p, 1));
            bool_flow(match b {
                B::Eq => o == Ordering::Equal,
                B::Neq => o != Ordering::Equal,
                B::Lt => o == Ordering::Less,
                B::Le => o != Ordering::Greater,
                B::Gt => o == Ordering::Greater,
                _ => o != Ordering::Less,
            })
        }
        B::Variant => bool_flow(s.m.st.variant(s.a(p, 0), s.a(p, 1))),
        B::NotVariant => bool_flow(!s.m.st.variant(s.a(p, 0), s.a(p, 1))),
        B::Compare => {
            let o = s.m.st.compare(s.a(p, 1), s.a(p, 2));
            let name = match o {
                Ordering::Less => "<",
                Ordering::Equal => "=",
                Ordering::Greater => ">",
            };
            match s.ad(p, 0) {
                Cell::Ref(_) | Cell::Atom(_) => {}
                other => return Err(type_error(s, "atom", other, "compare", 3)),
            }
            let x = s.a(p, 0);
            bool_flow(s.unify(x, Cell::Atom(Sym::intern(name))))
        }
        B::Var => bool_flow(matches!(s.ad(p, 0), Cell::Ref(_))),
        B::Nonvar => bool_flow(!matches!(s.ad(p, 0), Cell::Ref(_))),
        B::Atom => bool_flow(matches!(s.ad(p, 0), Cell::Atom(_))),
        B::Number => bool_flow(matches!(
            s.ad(p, 0),
            Cell::Int(_) | Cell::Flt(_) | Cell::Big(_)
        )),
        B::Integer => bool_flow(matches!(s.ad(p, 0), Cell::Int(_) | Cell::Big(_))),
        B::Float => bool_flow(matches!(s.ad(p, 0), Cell::Flt(_))),
        B::Atomic => bool_flow(!matches!(s.ad(p, 0), Cell::Ref(_) | Cell::Ptr(_))),
        B::Compound => bool_flow(matches!(s.ad(p, 0), Cell::Ptr(_))),
        B::Callable => bool_flow(matches!(s.ad(p, 0), Cell::Ptr(_) | Cell::Atom(_))),
        B::String => bool_flow(matches!(s.ad(p, 0), Cell::Str(_))),
        B::IsDict => Flow::Fail,
        B::IsList => {
            let (_, end) = s.m.st.list_items(s.a(p, 0));
            bool_flow(matches!(end, Cell::Atom(n) if n == wk::NIL))
        }
        B::Ground => bool_flow(s.m.st.is_ground(s.a(p, 0))),
        B::Functor => functor(s, p)?,
        B::Arg => arg(s, p)?,
        B::Univ => univ(s, p)?,
        B::CopyTerm => {
            let c = s.m.st.copy(s.a(p, 0));
            let y = s.a(p, 1);
            bool_flow(s.unify(c, y))
        }
        B::TermVariables => {
            let mut vars = Vec::new();
            s.m.st.term_vars(s.a(p, 0), &mut vars);
            let cells: Vec<Cell> = vars.into_iter().map(Cell::Ref).collect();
            let l = s.m.st.new_list(&cells, Cell::Atom(wk::NIL));
            let y = s.a(p, 1);
            bool_flow(s.unify(l, y))
        }
        B::BagofPrep => bagof_prep(s, p),
        B::BagofGroups => bagof_groups(s, p)?,
        _ => {
            if let Some(f) = arith::det(s, b, p)? {
                return Ok(f);
            }
            if let Some(f) = text::det(s, b, p, arity)? {
                return Ok(f);
            }
            if let Some(f) = lists::det(s, b, p)? {
                return Ok(f);
            }
            if let Some(f) = output::det(s, b, p, arity)? {
                return Ok(f);
            }
            if let Some(f) = super::library::det(s, b, p)? {
                return Ok(f);
            }
            Flow::Fail
        }
    })
}

fn functor(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let t = s.ad(p, 0);
    match t {
        Cell::Ref(_) => {
            let name = s.ad(p, 1);
            let n = int_arg(s, p, 2, "functor", 3)?;
            if n < 0 {
                return Err(domain_error(
                    s,
                    "not_less_than_zero",
                    Cell::Int(n),
                    "functor",
                    3,
                ));
            }
            if n == 0 {
                return Ok(match name {
                    Cell::Ref(_) => return Err(inst("functor", 3)),
                    Cell::Ptr(_) => return Err(type_error(s, "atomic", name, "functor", 3)),
                    c => bool_flow(s.unify(t, c)),
                });
            }
            let Cell::Atom(f) = name else {
                return Err(match name {
                    Cell::Ref(_) => inst("functor", 3),
                    Cell::Ptr(_) => type_error(s, "atomic", name, "functor", 3),
                    _ => type_error(s, "atom", name, "functor", 3),
                });
            };
            if n > 1_000_000 {
                return Err(KrError::iso(
                    Term::compound("resource_error", vec![Term::atom("memory")]),
                    Some((Sym::intern("functor"), 3)),
                ));
            }
            let args: Vec<Cell> = (0..n).map(|_| s.m.st.new_var()).collect();
            let c = s.m.st.new_struct(f, &args);
            Ok(bool_flow(s.unify(t, c)))
        }
        Cell::Ptr(q) => {
            let Some((f, n)) = s.m.st.heap[q as usize].fun() else {
                return Ok(Flow::Fail);
            };
            let (x, y) = (s.a(p, 1), s.a(p, 2));
            Ok(bool_flow(
                s.unify(x, Cell::Atom(f)) && s.unify(y, Cell::Int(n as i64)),
            ))
        }
        c => {
            let (x, y) = (s.a(p, 1), s.a(p, 2));
            Ok(bool_flow(s.unify(x, c) && s.unify(y, Cell::Int(0))))
        }
    }
}

fn arg(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let t = s.ad(p, 1);
    let Cell::Ptr(q) = t else {
        return Err(match t {
            Cell::Ref(_) => inst("arg", 3),
            _ => type_error(s, "compound", t, "arg", 3),
        });
    };
    let n = s.m.st.heap[q as usize].fun().map_or(0, |f| f.1) as i64;
    match s.ad(p, 0) {
        Cell::Int(i) => {
            if i < 1 || i > n {
                return Ok(Flow::Fail);
            }
            let (a, y) = (s.a(q, (i - 1) as u32), s.a(p, 2));
            Ok(bool_flow(s.unify(a, y)))
        }
        Cell::Ref(_) => {
            // Enumerate: arg(N, T, A) :- between(1, Arity, N), arg(N, T, A).
            let v = s.a(p, 0);
            let bt = goal(s, "between", &[Cell::Int(1), Cell::Int(n), v]);
            let args = [s.a(p, 0), s.a(p, 1), s.a(p, 2)];
            let ag = goal(s, "arg", &args);
            Ok(Flow::Call(s.m.st.new_struct(wk::COMMA, &[bt, ag])))
        }
        other => Err(type_error(s, "integer", other, "arg", 3)),
    }
}

fn univ(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let t = s.ad(p, 0);
    match t {
        Cell::Ptr(q) => {
            let Some((f, n)) = s.m.st.heap[q as usize].fun() else {
                return Ok(Flow::Fail);
            };
            let mut items = vec![Cell::Atom(f)];
            items.extend((0..n).map(|i| s.a(q, i)));
            let l = s.m.st.new_list(&items, Cell::Atom(wk::NIL));
            let y = s.a(p, 1);
            Ok(bool_flow(s.unify(l, y)))
        }
        Cell::Ref(_) => {
            let (items, end) = s.m.st.list_items(s.a(p, 1));
            if !matches!(end, Cell::Atom(n) if n == wk::NIL) {
                return Err(match end {
                    Cell::Ref(_) => inst("=..", 2),
                    _ => type_error(s, "list", s.a(p, 1), "=..", 2),
                });
            }
            let Some(&head) = items.first() else {
                return Err(domain_error(
                    s,
                    "non_empty_list",
                    Cell::Atom(wk::NIL),
                    "=..",
                    2,
                ));
            };
            let head = s.m.st.deref(head);
            let c = match head {
                Cell::Ref(_) => return Err(inst("=..", 2)),
                Cell::Atom(f) => s.m.st.new_struct(f, &items[1..]),
                c if items.len() == 1 && !matches!(c, Cell::Ptr(_)) => c,
                c => return Err(type_error(s, "atom", c, "=..", 2)),
            };
            Ok(bool_flow(s.unify(t, c)))
        }
        c => {
            let l = s.m.st.new_list(&[c], Cell::Atom(wk::NIL));
            let y = s.a(p, 1);
            Ok(bool_flow(s.unify(l, y)))
        }
    }
}

/// `'$bagof_prep'(Template, Goal, Witness, InnerGoal)`: strips `V^` from the goal and collects
/// the free variables (not in the template, not `^`-bound) into `Witness` (`'$w'(...)`).
fn bagof_prep(s: &mut Solver, p: u32) -> Flow {
    let mut bound = Vec::new();
    s.m.st.term_vars(s.a(p, 0), &mut bound);
    let mut g = s.ad(p, 1);
    while let Cell::Ptr(q) = g {
        if s.m.st.heap[q as usize].fun() == Some((wk::CARET, 2)) {
            s.m.st.term_vars(s.a(q, 0), &mut bound);
            g = s.ad(q, 1);
        } else {
            break;
        }
    }
    let mut all = Vec::new();
    s.m.st.term_vars(g, &mut all);
    let free: Vec<Cell> = all
        .into_iter()
        .filter(|v| !bound.contains(v))
        .map(Cell::Ref)
        .collect();
    let w = s.m.st.new_struct(Sym::intern("$w"), &free);
    let (x, y) = (s.a(p, 2), s.a(p, 3));
    bool_flow(s.unify(x, w) && s.unify(y, g))
}

/// `'$bagof_groups'(Pairs, Groups)`: key-sorted `W-T` pairs to a list of `W-Items` groups of
/// variant witnesses, in order.
fn bagof_groups(s: &mut Solver, p: u32) -> KrResult<Flow> {
    let (items, _) = s.m.st.list_items(s.a(p, 0));
    let mut pairs = Vec::new();
    for it in items {
        if let Cell::Ptr(q) = s.m.st.deref(it) {
            pairs.push((s.a(q, 0), s.a(q, 1)));
        }
    }
    pairs.sort_by(|a, b| s.m.st.compare(a.0, b.0));
    let mut groups: Vec<(Cell, Vec<Cell>)> = Vec::new();
    for (w, t) in pairs {
        let member = s.m.st.new_struct(wk::MINUS, &[w, t]);
        match groups.iter_mut().find(|(k, _)| s.m.st.variant(*k, w)) {
            Some((_, v)) => v.push(member),
            None => groups.push((w, vec![member])),
        }
    }
    let mut out = Vec::new();
    for (w, members) in groups {
        let l = s.m.st.new_list(&members, Cell::Atom(wk::NIL));
        out.push(s.m.st.new_struct(wk::MINUS, &[w, l]));
    }
    let l = s.m.st.new_list(&out, Cell::Atom(wk::NIL));
    let y = s.a(p, 1);
    Ok(bool_flow(s.unify(l, y)))
}
