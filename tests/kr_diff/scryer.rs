//! scryer-prolog 0.10 as the reference engine: load clauses given as `Term`s, run a query given as
//! a `Term`, and read the answers back as `Term`s in a canonical printed form.
//!
//! Shared by `tests/kr_diff.rs` and `benches/kr.rs` (through `#[path]`).

#![allow(dead_code)]

use goal::term::{well_known as wk, Sym, Term};
use scryer_prolog::{LeafAnswer, Machine, MachineBuilder, Term as STerm};

/// Predicates GOAL's native engine has that scryer 0.10 lacks (or has under another name), in SWI's
/// meaning. Loaded into every scryer machine so queries can use the same built-ins on both sides.
/// GOAL semantics that differ on purpose are mapped here too: `not/1` exists (it is `\+`), and the
/// `unknown` flag is `fail` because undefined predicates fail in GOAL instead of raising
/// `existence_error`.
pub const PRELUDE: &str = r#"
:- use_module(library(lists)).
:- use_module(library(between)).
:- use_module(library(iso_ext)).
:- use_module(library(pairs)).
:- use_module(library(ordsets)).
:- use_module(library(error)).
:- set_prolog_flag(unknown, fail).

not(G) :- \+ call(G).

'$goal_run'(T, G, R) :- catch(findall(T, G, L), E, true), ( var(E) -> R = ok(L) ; R = err(E) ).
ignore(G) :- ( call(G) -> true ; true ).

atom_number(A, N) :- var(A), !, number(N), number_chars(N, Cs), atom_chars(A, Cs).
atom_number(A, N) :- atom_chars(A, Cs), catch(number_chars(N0, Cs), _, fail), N = N0.

'$goal_is'(X, E) :- '$goal_eval'(E, V), X = V.
'$goal_cmp'(Op, A, B) :- '$goal_eval'(A, VA), '$goal_eval'(B, VB), G =.. [Op, VA, VB], call(G).
'$goal_eval'(E, V) :- var(E), !, V is E.
'$goal_eval'(A / B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB =\= 0, VA mod VB =:= 0 -> V is VA // VB ; V is VA / VB ).
'$goal_eval'(A ** B, V) :- !, '$goal_eval'(A, VA), '$goal_eval'(B, VB),
    ( integer(VA), integer(VB), VB >= 0 -> V is VA ^ VB ; V is VA ** VB ).
'$goal_eval'(E, V) :- compound(E), E \= [_|_], !, E =.. [F|Args], '$goal_eval_args'(Args, Vs),
    E2 =.. [F|Vs], V is E2.
'$goal_eval'(E, V) :- V is E.
'$goal_eval_args'([], []).
'$goal_eval_args'([A|As], [V|Vs]) :- '$goal_eval'(A, V), '$goal_eval_args'(As, Vs).

'$goal_softcut'(C, T, E) :- ( \+ call(C) -> call(E) ; call(C), call(T) ).

last([X], X) :- !.
last([_|T], X) :- last(T, X).

msort(L, S) :- '$goal_keys'(L, K), keysort(K, KS), pairs_values(KS, S).
'$goal_keys'([], []).
'$goal_keys'([X|Xs], [X-X|Ks]) :- '$goal_keys'(Xs, Ks).

sort(0, O, L, S) :- !, '$goal_sort_whole'(O, L, S).
sort(K, O, L, S) :- '$goal_key_pairs'(L, K, P), '$goal_sort_pairs'(O, P, SP), pairs_values(SP, S).
'$goal_sort_whole'(@<, L, S) :- sort(L, S).
'$goal_sort_whole'(@=<, L, S) :- msort(L, S).
'$goal_sort_whole'(@>, L, S) :- sort(L, S0), reverse(S0, S).
'$goal_sort_whole'(@>=, L, S) :- msort(L, S0), reverse(S0, S).
'$goal_key_pairs'([], _, []).
'$goal_key_pairs'([X|Xs], K, [Y-X|Ps]) :- arg(K, X, Y), '$goal_key_pairs'(Xs, K, Ps).
'$goal_sort_pairs'(@=<, P, S) :- keysort(P, S).
'$goal_sort_pairs'(@<, P, S) :- keysort(P, S0), '$goal_dedup_keys'(S0, S).
'$goal_sort_pairs'(@>=, P, S) :- '$goal_rev_keysort'(P, S).
'$goal_sort_pairs'(@>, P, S) :- '$goal_rev_keysort'(P, S0), '$goal_dedup_keys'(S0, S).
'$goal_rev_keysort'(P, S) :- reverse(P, R), keysort(R, S0), reverse(S0, S).
'$goal_dedup_keys'([], []).
'$goal_dedup_keys'([P], [P]) :- !.
'$goal_dedup_keys'([K1-V1, K2-V2|T], S) :- K1 == K2, !, '$goal_dedup_keys'([K1-V1|T], S).
'$goal_dedup_keys'([P|T], [P|S]) :- '$goal_dedup_keys'(T, S).

delete([], _, []).
delete([E|T], X, R) :- E \= X, !, R = [E|R1], delete(T, X, R1).
delete([_|T], X, R) :- delete(T, X, R).

subtract([], _, []).
subtract([E|T], D, R) :- memberchk(E, D), !, subtract(T, D, R).
subtract([H|T], D, [H|R]) :- subtract(T, D, R).

union([], L, L).
union([H|T], L, R) :- memberchk(H, L), !, union(T, L, R).
union([H|T], L, [H|R]) :- union(T, L, R).

intersection([], _, []).
intersection([X|T], L, I) :- memberchk(X, L), !, I = [X|R], intersection(T, L, R).
intersection([_|T], L, R) :- intersection(T, L, R).

exclude(_, [], []).
exclude(P, [X|Xs], R) :- ( call(P, X) -> R = R1 ; R = [X|R1] ), exclude(P, Xs, R1).
include(_, [], []).
include(P, [X|Xs], R) :- ( call(P, X) -> R = [X|R1] ; R = R1 ), include(P, Xs, R1).
partition(_, [], [], []).
partition(P, [H|T], I, E) :- ( call(P, H) -> I = [H|I1], E = E1 ; I = I1, E = [H|E1] ), partition(P, T, I1, E1).

sumlist(L, S) :- sum_list(L, S).
max_list(L, M) :- list_max(L, M).
min_list(L, M) :- list_min(L, M).

nextto(X, Y, [X,Y|_]).
nextto(X, Y, [_|Zs]) :- nextto(X, Y, Zs).

selectchk(E, L, R) :- select(E, L, R), !.

plus(X, Y, Z) :- integer(X), integer(Y), !, Z is X + Y.
plus(X, Y, Z) :- integer(X), integer(Z), !, Y is Z - X.
plus(X, Y, Z) :- integer(Y), integer(Z), !, X is Z - Y.

aggregate_all(count, G, C) :- !, findall(x, G, L), length(L, C).
aggregate_all(count(T), G, C) :- !, findall(T, G, L), length(L, C).
aggregate_all(sum(E), G, S) :- !, findall(E, G, L), '$goal_sum'(L, 0, S).
aggregate_all(max(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_max'(T, H, M).
aggregate_all(min(E), G, M) :- !, findall(E, G, L), L = [H|T], '$goal_min'(T, H, M).
aggregate_all(bag(E), G, L) :- !, findall(E, G, L).
aggregate_all(set(E), G, S) :- !, findall(E, G, L), sort(L, S).
'$goal_sum'([], S, S).
'$goal_sum'([X|Xs], A, S) :- A1 is A + X, '$goal_sum'(Xs, A1, S).
'$goal_max'([], M, M).
'$goal_max'([X|Xs], A, M) :- ( X > A -> A1 = X ; A1 = A ), '$goal_max'(Xs, A1, M).
'$goal_min'([], M, M).
'$goal_min'([X|Xs], A, M) :- ( X < A -> A1 = X ; A1 = A ), '$goal_min'(Xs, A1, M).
"#;

/// The outcome of one query, in a canonical form both engines can be compared on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The answers in order: each is the query's template instantiated, printed with `writeq`
    /// after renaming its variables `_A`, `_B`, ... by first appearance.
    Answers(Vec<String>),
    /// The query raised this error term (printed the same way).
    Error(String),
}

/// A scryer machine with the prelude loaded.
pub struct Scryer {
    machine: Machine,
    modules: usize,
}

impl Scryer {
    /// A fresh machine (about 80 ms) with `PRELUDE` loaded.
    pub fn new() -> Scryer {
        let mut machine = MachineBuilder::default().build();
        machine.load_module_string("goal_prelude", PRELUDE.to_string());
        Scryer {
            machine,
            modules: 0,
        }
    }

    /// Loads clauses (printed from `Term`s, so the text is always well formed).
    pub fn load(&mut self, clauses: &[Term]) {
        // scryer keeps only the last group of a discontiguous predicate: group the clauses by
        // predicate (in order of first appearance, keeping their relative order).
        let key = |c: &Term| {
            let head = match c {
                Term::Compound(k) if k.name.name() == ":-" && k.args.len() == 2 => &k.args[0],
                other => other,
            };
            head.functor().map(|(n, a)| (n.name().to_string(), a))
        };
        let mut groups: Vec<(Option<(String, usize)>, Vec<&Term>)> = Vec::new();
        for c in clauses {
            let k = key(c);
            match groups.iter_mut().find(|(g, _)| *g == k) {
                Some((_, v)) => v.push(c),
                None => groups.push((k, vec![c])),
            }
        }
        let mut text = String::new();
        for c in groups.iter().flat_map(|(_, v)| v.iter()) {
            text.push_str(&clause_text(c));
        }
        self.modules += 1;
        let name = format!("goal_kb_{}", self.modules);
        self.machine.load_module_string(&name, text);
    }

    /// Loads trusted program text (directives such as `:- dynamic(bel/1).`).
    pub fn load_text(&mut self, text: &str) {
        self.modules += 1;
        let name = format!("goal_kb_{}", self.modules);
        self.machine.load_module_string(&name, text.to_string());
    }

    /// Runs `goal` and returns its answers as instances of `template`, collected inside scryer
    /// with `findall/3` (so bindings between query variables survive), or the error it raised.
    pub fn query(&mut self, template: &Term, goal: &Term) -> Outcome {
        // The goal runs inside the prelude's `'$goal_run'/3`, under `catch/3` (an error that
        // escapes to scryer 0.10's library interface is not cleared and comes back as the answer
        // of the next queries) and not as query text (scryer compiles control constructs in a
        // query on every run: 1.5 ms instead of 0.1 ms).
        let out = Term::var("GoalDiffOut__");
        let q = Term::compound(
            Sym::intern("$goal_run"),
            vec![template.clone(), goal.clone(), out],
        );
        let answers = match self.solutions(&q) {
            Err(e) => return Outcome::Error(canonical(&e)),
            Ok(answers) => answers,
        };
        for a in answers {
            if let LeafAnswer::LeafAnswer { bindings, .. } = a {
                let Some(result) = bindings.get("GoalDiffOut__").map(from_scryer) else {
                    continue;
                };
                let inner = result.args().first().cloned().unwrap_or(Term::nil());
                if result.is_functor(Sym::intern("err"), 1) {
                    return Outcome::Error(canonical(&inner));
                }
                return match inner.list_items() {
                    Some(items) => Outcome::Answers(items.iter().map(canonical).collect()),
                    None => Outcome::Error(format!("unexpected scryer result {result}")),
                };
            }
        }
        Outcome::Answers(vec![])
    }

    /// Runs a query and returns every leaf answer, or the error term it raised.
    pub fn solutions(&mut self, goal: &Term) -> Result<Vec<LeafAnswer>, Term> {
        let text = format!("{}.", fix_softcut_pairs(&to_scryer(goal)));
        // `run_query` panics on text it cannot parse; report that as an error instead.
        let machine = &mut self.machine;
        let run = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            machine.run_query(text.clone()).collect::<Vec<_>>()
        }));
        let answers = match run {
            Ok(a) => a,
            Err(_) => {
                return Err(Term::compound(
                    Sym::intern("scryer_cannot_parse"),
                    vec![Term::atom(&text)],
                ))
            }
        };
        let mut out = Vec::new();
        for a in answers {
            match a {
                Ok(LeafAnswer::False) => break,
                Ok(LeafAnswer::Exception(e)) => return Err(from_scryer(&e)),
                Ok(a) => out.push(a),
                Err(e) => return Err(from_scryer(&e)),
            }
        }
        Ok(out)
    }

    /// Runs query text (only for trusted, well-formed text).
    pub fn solutions_text(&mut self, text: &str) -> Vec<Result<LeafAnswer, STerm>> {
        self.machine.run_query(text.to_string()).collect()
    }

    /// True when `goal` has at least one answer (runs it to completion).
    pub fn succeeds(&mut self, goal: &Term) -> bool {
        matches!(self.solutions(goal), Ok(v) if !v.is_empty())
    }
}

impl Default for Scryer {
    fn default() -> Self {
        Scryer::new()
    }
}

/// A clause as Prolog text ending in `.` and a newline.
pub fn clause_text(clause: &Term) -> String {
    format!("{} .\n", fix_softcut_pairs(&to_scryer(clause)))
}

/// Rewrites what scryer 0.10 cannot read or reads differently on purpose:
/// - it has no `*->` operator, so `(C *-> T ; E)` becomes `'$goal_softcut'(C, T, E)` (same
///   answers for goals without side effects) and `C *-> T` becomes `(C, T)`;
/// - GOAL evaluates like SWI-Prolog, where `/` of two integers is an integer when exact and
///   `**` of two integers is an integer, while scryer gives floats: `is/2` and the arithmetic
///   comparisons go through the prelude's `'$goal_eval'/2`, which applies SWI's meaning;
/// - scryer 0.10 lets a cut in the condition of if-then-else cut the else branch too
///   (`((true, !, fail) -> true ; X = c)` fails; ISO: `X = c`): conditions run under `call/1`,
///   which ISO makes equivalent (the condition is opaque to cut).
pub fn to_scryer(t: &Term) -> Term {
    let Term::Compound(c) = t else {
        return t.clone();
    };
    let args: Vec<Term> = c.args.iter().map(to_scryer).collect();
    match (c.name.name(), args.as_slice()) {
        (";", [cond, e]) => match cond {
            Term::Compound(ct) if ct.name.name() == "$goal_softcut_pair" => Term::compound(
                Sym::intern("$goal_softcut"),
                vec![ct.args[0].clone(), ct.args[1].clone(), e.clone()],
            ),
            _ => Term::compound(c.name, args),
        },
        ("is", [x, e]) => Term::compound(Sym::intern("$goal_is"), vec![x.clone(), e.clone()]),
        ("<" | ">" | "=<" | ">=" | "=:=" | "=\\=", [l, r]) => Term::compound(
            Sym::intern("$goal_cmp"),
            vec![Term::Atom(c.name), l.clone(), r.clone()],
        ),
        ("->", [cond, then]) => Term::compound(
            c.name,
            vec![
                Term::compound(Sym::intern("call"), vec![cond.clone()]),
                then.clone(),
            ],
        ),
        ("*->", [cond, then]) => Term::compound(
            Sym::intern("$goal_softcut_pair"),
            vec![cond.clone(), then.clone()],
        ),
        _ => Term::compound(c.name, args),
    }
}

/// A `C *-> T` left outside a disjunction means `(C, T)`.
fn fix_softcut_pairs(t: &Term) -> Term {
    let Term::Compound(c) = t else {
        return t.clone();
    };
    let args: Vec<Term> = c.args.iter().map(fix_softcut_pairs).collect();
    if c.name.name() == "$goal_softcut_pair" {
        Term::compound(Sym::intern(","), args)
    } else {
        Term::compound(c.name, args)
    }
}

/// Converts a scryer answer term to the crate's `Term` (strings are lists of one-char atoms
/// because scryer's `double_quotes` flag is `chars`; big numbers become `'$big'(Text)`).
pub fn from_scryer(t: &STerm) -> Term {
    match t {
        STerm::Integer(i) => match i64::try_from(i.clone()) {
            Ok(n) => Term::Int(n),
            Err(_) => Term::compound(Sym::intern("$big"), vec![Term::atom(&i.to_string())]),
        },
        STerm::Rational(r) => {
            Term::compound(Sym::intern("$rational"), vec![Term::atom(&r.to_string())])
        }
        STerm::Float(f) => Term::Float(goal::term::Float(*f)),
        STerm::Atom(a) => Term::atom(a),
        STerm::String(s) => Term::list(
            s.chars()
                .map(|c| Term::atom(&c.to_string()))
                .collect::<Vec<_>>(),
        ),
        STerm::List(items) => Term::list(items.iter().map(from_scryer).collect::<Vec<_>>()),
        STerm::Compound(name, args) => {
            Term::compound(Sym::intern(name), args.iter().map(from_scryer).collect())
        }
        STerm::Var(v) => Term::var(&format!("_S{v}")),
        _ => Term::atom("$unknown_scryer_term"),
    }
}

/// `writeq` text of `t` after renaming its variables `_A`, `_B`, ... in order of first appearance,
/// so answers that differ only in variable names compare equal.
pub fn canonical(t: &Term) -> String {
    let vars = t.vars();
    rename(t, &vars).to_string()
}

fn rename(t: &Term, vars: &[Sym]) -> Term {
    match t {
        Term::Var(v) => {
            let i = vars.iter().position(|x| x == v).unwrap_or(0);
            Term::var(&format!("_{}", letter_name(i)))
        }
        Term::Compound(c) => {
            Term::compound(c.name, c.args.iter().map(|a| rename(a, vars)).collect())
        }
        other => other.clone(),
    }
}

fn letter_name(mut i: usize) -> String {
    let mut out = Vec::new();
    loop {
        out.push((b'A' + (i % 26) as u8) as char);
        i /= 26;
        if i == 0 {
            break;
        }
    }
    out.into_iter().rev().collect()
}

/// The template `ans(V1, ..., Vn)` of the named variables of `goal` in order of first appearance
/// (variables starting with `_` are left out, as the `goal prolog` command does).
pub fn template(goal: &Term) -> Term {
    let vars: Vec<Term> = goal
        .vars()
        .into_iter()
        .filter(|v| !v.name().starts_with('_'))
        .map(Term::Var)
        .collect();
    if vars.is_empty() {
        Term::atom("ans")
    } else {
        Term::compound(Sym::intern("ans"), vars)
    }
}

/// True when `t` is the empty list (kept for callers that inspect converted answers).
pub fn is_nil(t: &Term) -> bool {
    matches!(t, Term::Atom(s) if *s == wk::NIL)
}
