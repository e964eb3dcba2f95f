//! Unit tests of the KR engines' built-ins and control constructs (error cases too), written
//! as Prolog text read with the project's reader. Every query runs on the native engine and,
//! when the build has it, on the scryer engine: both must give the same answers, except for the
//! queries of [`DIFFERENCES`], where scryer's answer is the one listed there (the reasoned
//! table of `docs/kr-engines.md`).

use goal::kr::{AgentEngine, Engine, FactBase, Knowledge, KrKind, Limits, NativeEngine, View};
use goal::syntax::prolog::Reader;
use goal::term::Term;
use std::collections::HashMap;

fn read(text: &str) -> Term {
    Reader::new("test")
        .term(text, 0)
        .unwrap_or_else(|d| panic!("{text}: {}", d.message))
        .term
}

fn load(program: &str) -> std::sync::Arc<Knowledge> {
    let (clauses, errors) = Reader::new("test").clauses(program, 0);
    assert!(errors.is_empty(), "{errors:?}");
    let terms: Vec<Term> = clauses.into_iter().map(|c| c.term).collect();
    Knowledge::load(&terms).unwrap_or_else(|e| panic!("{e}"))
}

/// Queries the engines answer differently on purpose: (query, scryer's answers joined by
/// ` | `, why). `docs/kr-engines.md` gives the same table to users.
const DIFFERENCES: &[(&str, &str, &str)] = &[
    (
        r#"X is gcd(12, 18) + msb(8)"#,
        r#"error: error(type_error(evaluable,msb/1),(is)/2)"#,
        SWI_ARITHMETIC,
    ),
    (
        r#"X is min(2, 3) + integer(2.5)"#,
        r#"error: error(type_error(evaluable,integer/1),(is)/2)"#,
        SWI_ARITHMETIC,
    ),
    (
        r#"X is max_tagged_integer"#,
        r#"error: error(type_error(evaluable,max_tagged_integer/0),(is)/2)"#,
        SWI_ARITHMETIC,
    ),
    (
        r#"X is "a" + 0"#,
        r#"error: error(type_error(evaluable,[]/0),(is)/2)"#,
        SWI_ARITHMETIC,
    ),
    (
        r#"X is log(2, 8)"#,
        r#"error: error(type_error(evaluable,log/2),(is)/2)"#,
        SWI_ARITHMETIC,
    ),
    (
        r#"atom_string(A, "xy"), atom_string(ab, S)"#,
        r#""#,
        NO_STRINGS,
    ),
    (r#"term_to_atom(f(X, 'A', "s"), T)"#, r#""#, NO_STRINGS),
    (r#"term_to_atom(T, 'g(1, Y)')"#, r#""#, SWI_LIBRARY),
    (r#"atom_to_term('p(X, Y, X)', T, B)"#, r#""#, SWI_LIBRARY),
    (
        r#"upcase_atom(abC, U), downcase_atom('AbC', D)"#,
        r#""#,
        SWI_LIBRARY,
    ),
    (r#"string_concat("ab", cd, S)"#, r#""#, NO_STRINGS),
    (r#"string_concat(ab, S, "abcd")"#, r#""#, NO_STRINGS),
    (
        r#"atom_concat(1, X, '12')"#,
        r#"error: type_error(atom,1)"#,
        ISO_ATOMS,
    ),
    (
        r#"atom_concat(X, 2, '12')"#,
        r#"error: type_error(atom,2)"#,
        ISO_ATOMS,
    ),
    (
        r#"string_chars(S, [h, i]), string_codes(T, [104]), string_to_atom("q", A)"#,
        r#""#,
        NO_STRINGS,
    ),
    (r#"string_length("hello", N)"#, r#""#, NO_STRINGS),
    (r#"sub_string("hello", 0, 2, _, S)"#, r#""#, NO_STRINGS),
    (r#"split_string("a,b,,c", ",", "", P)"#, r#""#, NO_STRINGS),
    (r#"split_string("  hi  ", "", " ", P)"#, r#""#, NO_STRINGS),
    (r#"number_string(N, " 42 ")"#, r#""#, NO_STRINGS),
    (
        r#"string_lower("AbC", L), string_upper("AbC", U)"#,
        r#""#,
        NO_STRINGS,
    ),
    (r#"atomic_list_concat([a, 1, "s"], X)"#, r#""#, NO_STRINGS),
    (r#"atomic_list_concat([a, b], '-', X)"#, r#""#, SWI_LIBRARY),
    (r#"atomic_list_concat(L, '-', 'a-b-c')"#, r#""#, SWI_LIBRARY),
    (
        r#"msort([b, 1, a, 2.0, f(x), "s", Z], L), L = [V|_], V == Z"#,
        r#"L = [Z,1,2.0,a,b,f(x),[s]], V = Z"#,
        NO_STRINGS,
    ),
    (
        r#"var(X), nonvar(a), atom(a), number(1.5), integer(3), float(1.0), atomic("s"), compound(f(x)), callable(a), is_list([1]), string("s"), ground(f(a))"#,
        r#""#,
        NO_STRINGS,
    ),
    (
        r#"format(string(S), "~q~n", ['A'])"#,
        r#"S = ['\'','A','\'','\n']"#,
        NO_STRINGS,
    ),
    (
        r#"format(atom(A), "~2f ~e", [3.14159, 1.5])"#,
        r#"error: error(format(unsupported_directive),format/3)"#,
        FORMAT,
    ),
    (
        r#"format(atom(A), "~s~~~c", [[104, 105], 33])"#,
        r#"error: error(format(unsupported_directive),format/3)"#,
        FORMAT,
    ),
    (
        r#"format(atom(A), "~p", [x])"#,
        r#"error: error(format(unsupported_directive),format/3)"#,
        FORMAT,
    ),
    (
        r#"format(atom(A), "~w", [])"#,
        r#"error: error(domain_error(non_empty_list,[]),format_//2)"#,
        FORMAT,
    ),
    (
        r#"format(atom(A), "~999999999999|x", []), atom_length(A, N)"#,
        r#"A = x, N = 1"#,
        FORMAT,
    ),
    (
        r#"functor(T, f, 100000000)"#,
        r#"error: error(representation_error(max_arity),functor/3)"#,
        BOUNDED,
    ),
    (
        r#"X is random(0)"#,
        r#"error: error(type_error(evaluable,random/1),(is)/2)"#,
        NO_RANDOM,
    ),
    (r#"flatten([1, [2, [3, 4]], [], 5], X)"#, r#""#, SWI_LIBRARY),
    (
        r#"max_member(X, [a, f(b), 3]), min_member(Y, [a, f(b), 3])"#,
        r#""#,
        SWI_LIBRARY,
    ),
    (
        r#"ord_insert([a, c], b, X), ord_del_element([a, b], a, Y), ord_intersection([a, b], [b, c], Z)"#,
        r#""#,
        SWI_LIBRARY,
    ),
    (
        r#"reverse(L, X)"#,
        r#"error: error(resource_error(inferences(10000000)),'scryer query')"#,
        BOUNDED,
    ),
    (
        r#"wrap(200000, z, _T), format(atom(_A), "~w", [_T]), atom_length(_A, N), sub_atom(_A, 0, 6, _, B)"#,
        r#"error: error(resource_error(inferences(10000000)),'scryer query')"#,
        BOUNDED,
    ),
    (
        r#"X is random(1000), Y is random_float, random_between(1, 6, Z)"#,
        r#"error: error(type_error(evaluable,random/1),(is)/2)"#,
        NO_RANDOM,
    ),
    (
        r#"X = f(X), Y = f(Y), compare(O, X, Y)"#,
        r#"error: error(resource_error(inferences(10000000)),'scryer query')"#,
        BOUNDED,
    ),
];

const NO_STRINGS: &str = "scryer has no string type: text in double quotes is a list of characters, and SWI's string built-ins are not defined (undefined predicates fail)";
const SWI_LIBRARY: &str =
    "an SWI library predicate scryer 0.10 does not have (undefined predicates fail)";
const SWI_ARITHMETIC: &str = "an SWI arithmetic function scryer 0.10 does not have";
const NO_RANDOM: &str =
    "no random numbers on scryer: its generator is not seeded by the run, and runs must replay";
const ISO_ATOMS: &str =
    "scryer's atom_concat/3 takes atoms only (ISO); SWI's takes any atomic text";
const FORMAT: &str = "scryer's format_//2 lacks this directive or column handling";
const BOUNDED: &str = "both engines stop the query with an error; scryer's error is another one";

/// The engines of this build.
fn engines() -> Vec<KrKind> {
    [KrKind::Native, KrKind::Scryer]
        .into_iter()
        .filter(|k| k.available())
        .collect()
}

thread_local! {
    /// One engine per (kind, program) and test thread: scryer machines are slow to start.
    static ENGINES: std::cell::RefCell<HashMap<(KrKind, String), AgentEngine>> =
        std::cell::RefCell::new(HashMap::new());
}

/// The answers of one engine, shown as `X = v, Y = w` lines (`true` when nothing is bound), or
/// `error: ...`.
fn ask_on(kind: KrKind, program: &str, facts: &[&str], q: &Term, limits: Limits) -> Vec<String> {
    let kn = load(program);
    let mut fb = FactBase::new();
    for f in facts {
        fb.insert(read(f));
    }
    let bases = [&fb];
    let view = View::beliefs(&kn, &bases);
    let result = ENGINES.with(|cell| {
        let mut map = cell.borrow_mut();
        let e = map
            .entry((kind, program.to_string()))
            .or_insert_with(|| AgentEngine::new(kind, &kn, 7, limits).expect("engine starts"));
        *e.limits_mut() = limits;
        if kind == KrKind::Native {
            // A fresh native engine per query: its random numbers start from the seed.
            *e = AgentEngine::new(kind, &kn, 7, limits).expect("engine starts");
        }
        e.query(&view, q)
    });
    match result {
        Ok(answers) => answers
            .iter()
            .map(|s| {
                let parts: Vec<String> = q
                    .vars()
                    .into_iter()
                    .filter(|v| !v.name().starts_with('_'))
                    .filter_map(|v| s.get(v).map(|t| format!("{} = {}", v.name(), t)))
                    .collect();
                if parts.is_empty() {
                    "true".into()
                } else {
                    parts.join(", ")
                }
            })
            .collect(),
        Err(e) => vec![format!("error: {}", e.to_term())],
    }
}

/// An answer as the engines are compared: an error's context (its second argument, which
/// ISO leaves to the implementation) is left out.
fn formal(answer: &str) -> String {
    match answer.strip_prefix("error: ") {
        Some(e) => {
            let t = read(e);
            if t.is_functor(goal::term::Sym::intern("error"), 2) {
                format!("error: {}", t.args()[0])
            } else {
                answer.to_string()
            }
        }
        None => answer.to_string(),
    }
}

/// The native engine's answers, after checking that scryer (when built) gives the same or
/// the answer [`DIFFERENCES`] lists for the query.
fn ask_with(program: &str, facts: &[&str], query: &str, limits: Limits) -> Vec<String> {
    let q = read(query);
    let native = ask_on(KrKind::Native, program, facts, &q, limits);
    for kind in engines().into_iter().filter(|k| *k != KrKind::Native) {
        let other = ask_on(kind, program, facts, &q, limits);
        match DIFFERENCES.iter().find(|(d, _, _)| *d == query) {
            Some((_, expected, _)) => assert_eq!(
                other
                    .iter()
                    .map(|a| formal(a))
                    .collect::<Vec<_>>()
                    .join(" | "),
                expected
                    .split(" | ")
                    .filter(|a| !a.is_empty())
                    .map(formal)
                    .collect::<Vec<_>>()
                    .join(" | "),
                "{kind:?}: {query}"
            ),
            None => assert_eq!(
                other.iter().map(|a| formal(a)).collect::<Vec<_>>(),
                native.iter().map(|a| formal(a)).collect::<Vec<_>>(),
                "{kind:?} differs from native on {query}"
            ),
        }
    }
    native
}

fn ask(program: &str, query: &str) -> Vec<String> {
    ask_with(program, &[], query, Limits::default())
}

fn one(query: &str) -> String {
    let a = ask("", query);
    assert!(a.len() <= 1, "{query}: several answers {a:?}");
    a.into_iter().next().unwrap_or_else(|| "false".into())
}

#[test]
fn facts_and_rules() {
    let p = "parent(tom, bob). parent(bob, ann). parent(bob, pat).
             grand(X, Z) :- parent(X, Y), parent(Y, Z).";
    assert_eq!(ask(p, "grand(tom, W)"), ["W = ann", "W = pat"]);
    assert_eq!(ask(p, "parent(X, ann)"), ["X = bob"]);
    assert_eq!(ask(p, "undefined_pred(1)"), Vec::<String>::new());
}

#[test]
fn cut_and_control() {
    let p = "t(1). t(2). t(3).
             first(X) :- t(X), !.
             ite(X, R) :- ( X > 1 -> R = big ; R = small ).
             d(X) :- ( X = a ; X = b ).
             c(X) :- call((t(X), !)).
             c(4).";
    assert_eq!(ask(p, "first(X)"), ["X = 1"]);
    assert_eq!(ask(p, "ite(2, R)"), ["R = big"]);
    assert_eq!(ask(p, "ite(0, R)"), ["R = small"]);
    assert_eq!(ask(p, "d(X)"), ["X = a", "X = b"]);
    assert_eq!(ask(p, "c(X)"), ["X = 1", "X = 4"]);
    assert_eq!(ask(p, "\\+ t(5)"), ["true"]);
    assert_eq!(ask(p, "not(t(1))"), Vec::<String>::new());
    assert_eq!(ask(p, "t(X), X > 1, !"), ["X = 2"]);
    assert_eq!(
        ask(p, "( t(X) *-> true ; X = none )"),
        ["X = 1", "X = 2", "X = 3"]
    );
    assert_eq!(ask(p, "( t(9) *-> X = some ; X = none )"), ["X = none"]);
    assert_eq!(ask(p, "forall(t(X), X > 0)"), ["true"]);
    assert_eq!(ask(p, "once(t(X))"), ["X = 1"]);
    assert_eq!(ask(p, "ignore(t(9))"), ["true"]);
}

#[test]
fn all_solutions() {
    let p = "age(peter, 7). age(ann, 11). age(pat, 8). age(tom, 5). age(mike, 11).
             cls(a, x). cls(b, y). cls(c, x).";
    assert_eq!(ask(p, "findall(N, age(N, 11), L)"), ["L = [ann,mike]"]);
    assert_eq!(ask(p, "findall(N, age(N, 99), L)"), ["L = []"]);
    assert_eq!(
        ask(p, "setof(A-N, age(N, A), L)"),
        ["L = [5-tom,7-peter,8-pat,11-ann,11-mike]"]
    );
    assert_eq!(
        ask(p, "bagof(X, cls(X, C), L)"),
        ["C = x, L = [a,c]", "C = y, L = [b]"]
    );
    assert_eq!(ask(p, "setof(X, C^cls(X, C), L)"), ["L = [a,b,c]"]);
    assert_eq!(ask(p, "bagof(X, cls(X, z), L)"), Vec::<String>::new());
    assert_eq!(ask(p, "aggregate_all(count, age(_, _), C)"), ["C = 5"]);
    assert_eq!(ask(p, "aggregate_all(sum(A), age(_, A), S)"), ["S = 42"]);
    assert_eq!(ask(p, "aggregate_all(max(A), age(_, A), S)"), ["S = 11"]);
    assert_eq!(
        ask(p, "aggregate_all(min(A, N), age(N, A), S)"),
        ["S = min(5,tom)"]
    );
    assert_eq!(
        ask(p, "aggregate_all(bag(N), age(N, 11), S)"),
        ["S = [ann,mike]"]
    );
    assert_eq!(
        ask(p, "aggregate_all(set(A), age(_, A), S)"),
        ["S = [5,7,8,11]"]
    );
    assert_eq!(
        ask(p, "aggregate_all(max(A), age(_, A), 99)"),
        Vec::<String>::new()
    );
    assert_eq!(
        ask(p, "findall(X-Y, (member(X, [1,2]), member(Y, [a,b])), L)"),
        ["L = [1-a,1-b,2-a,2-b]"]
    );
    assert_eq!(
        ask(p, "findall(X, member(X, [1,2]), L, [3])"),
        ["L = [1,2,3]"]
    );
}

#[test]
fn arithmetic() {
    assert_eq!(one("X is 1 + 2 * 3"), "X = 7");
    assert_eq!(one("X is 7 / 2"), "X = 3.5");
    assert_eq!(one("X is 8 / 2"), "X = 4");
    assert_eq!(one("X is -7 // 2"), "X = -3");
    assert_eq!(one("X is -7 mod 2"), "X = 1");
    assert_eq!(one("X is -7 rem 2"), "X = -1");
    assert_eq!(one("X is 2 ** 10"), "X = 1024");
    assert_eq!(one("X is 2 ^ 3"), "X = 8");
    assert_eq!(one("X is 2.0 ** 2"), "X = 4.0");
    assert_eq!(one("X is max(3, 4.0)"), "X = 4.0");
    assert_eq!(one("X is abs(-3) + sign(-2.5)"), "X = 2.0");
    assert_eq!(one("X is sqrt(16)"), "X = 4.0");
    assert_eq!(
        one("X is truncate(3.7) + round(2.5) + ceiling(1.1) + floor(-1.1)"),
        "X = 6"
    );
    assert_eq!(one("X is 5 >> 1 + (1 << 3)"), "X = 10");
    assert_eq!(
        one("X is (5 /\\ 3) + (5 \\/ 3) + (5 xor 3) + \\ 0"),
        "X = 13"
    );
    assert_eq!(one("X is gcd(12, 18) + msb(8)"), "X = 9");
    assert_eq!(one("X is min(2, 3) + integer(2.5)"), "X = 5");
    assert_eq!(
        one("X is float_integer_part(2.5) + float_fractional_part(2.5)"),
        "X = 2.5"
    );
    assert_eq!(one("X is pi - pi + e - e"), "X = 0.0");
    assert_eq!(
        one("X is cot"),
        "error: error(type_error(evaluable,cot/0),_)"
    );
    assert_eq!(
        one("X is foo(1)"),
        "error: error(type_error(evaluable,foo/1),_)"
    );
    assert_eq!(one("X is Y + 1"), "error: error(instantiation_error,_)");
    assert_eq!(
        one("X is 1 / 0"),
        "error: error(evaluation_error(zero_divisor),_)"
    );
    assert_eq!(
        one("X is 9223372036854775807 + 1"),
        "X = 9223372036854775808"
    );
    assert_eq!(
        one("X is 1 mod 2.0"),
        "error: error(type_error(integer,2.0),_)"
    );
    assert_eq!(
        one("1 < 2, 2.0 =:= 2, 3 =\\= 4, 2 >= 2, 1 =< 1.5, 3 > 2"),
        "true"
    );
    assert_eq!(one("1 > 2"), "false");
    assert_eq!(
        one("succ(X, 4), succ(3, Y), plus(2, Z, 5)"),
        "X = 3, Y = 4, Z = 3"
    );
    assert_eq!(one("X is atan2(1, 1) * 4 - pi"), "X = 0.0");
    assert_eq!(one("X is max_tagged_integer"), "X = 1152921504606846975");
    assert_eq!(one("X is 10 - 3 - 2"), "X = 5");
    assert_eq!(one("X is \"a\" + 0"), "X = 97");
    assert_eq!(one("X is log(2, 8)"), "X = 3.0");
    assert_eq!(
        one("X is sqrt(-1)"),
        "error: error(evaluation_error(undefined),_)"
    );
}

#[test]
fn random_is_seeded() {
    let a = one("X is random(1000), Y is random_float, random_between(1, 6, Z)");
    let b = one("X is random(1000), Y is random_float, random_between(1, 6, Z)");
    assert_eq!(a, b);
    assert!(a.starts_with("X = "));
}

#[test]
fn comparison_and_types() {
    assert_eq!(one("compare(O, 1, a)"), "O = <");
    assert_eq!(
        one("msort([b, 1, a, 2.0, f(x), \"s\", Z], L), L = [V|_], V == Z"),
        "L = [Z,1,2.0,a,b,\"s\",f(x)], V = Z"
    );
    assert_eq!(one("a @< b, f(a) @> b, 1 @< a, f(a,b) @> g(a)"), "true");
    assert_eq!(one("X == X, X \\== Y"), "true");
    assert_eq!(one("f(A, B) =@= f(C, D), \\+ f(A, A) =@= f(C, D)"), "true");
    assert_eq!(one("var(X), nonvar(a), atom(a), number(1.5), integer(3), float(1.0), atomic(\"s\"), compound(f(x)), callable(a), is_list([1]), string(\"s\"), ground(f(a))"), "true");
    assert_eq!(one("atom(1)"), "false");
    assert_eq!(one("is_list([a|_])"), "false");
    assert_eq!(one("a \\= b, \\+ a \\= a"), "true");
    assert_eq!(one("unify_with_occurs_check(X, f(X))"), "false");
}

#[test]
fn term_construction() {
    assert_eq!(one("functor(f(a, b), N, A)"), "N = f, A = 2");
    assert_eq!(one("functor(T, g, 2)"), "T = g(_R0,_R1)");
    assert_eq!(one("functor(T, foo, 0)"), "T = foo");
    assert_eq!(one("arg(2, f(a, b), X)"), "X = b");
    assert_eq!(
        ask("", "arg(N, f(a, b), X)"),
        ["N = 1, X = a", "N = 2, X = b"]
    );
    assert_eq!(one("f(a, b) =.. L"), "L = [f,a,b]");
    assert_eq!(one("T =.. [g, 1]"), "T = g(1)");
    assert_eq!(one("T =.. [7]"), "T = 7");
    assert_eq!(one("copy_term(f(X, Y, X), C)"), "C = f(_R0,_R1,_R0)");
    assert_eq!(one("term_variables(f(X, g(Y, X)), L)"), "L = [X,Y]");
    assert_eq!(
        one("functor(T, N, 2)"),
        "error: error(instantiation_error,functor/3)"
    );
    assert_eq!(
        one("arg(x, f(a), _)"),
        "error: error(type_error(integer,x),arg/3)"
    );
    assert_eq!(one("T =.. L"), "error: error(instantiation_error,(=..)/2)");
}

#[test]
fn lists() {
    assert_eq!(ask("", "member(X, [a, b])"), ["X = a", "X = b"]);
    assert_eq!(one("memberchk(b, [a, b, c])"), "true");
    assert_eq!(
        ask("", "append(X, Y, [1, 2])"),
        ["X = [], Y = [1,2]", "X = [1], Y = [2]", "X = [1,2], Y = []"]
    );
    assert_eq!(one("append([[1], [2, 3], []], L)"), "L = [1,2,3]");
    assert_eq!(one("length([a, b], N)"), "N = 2");
    assert_eq!(one("length(L, 2)"), "L = [_R0,_R1]");
    assert_eq!(one("length([a|T], 3)"), "T = [_R0,_R1]");
    assert_eq!(
        ask("", "length([a|T], N), N > 2, !"),
        ["T = [_R0,_R1], N = 3"]
    );
    assert_eq!(
        one("length(L, -1)"),
        "error: error(domain_error(not_less_than_zero,-1),length/2)"
    );
    assert_eq!(
        one("length(a, N)"),
        "error: error(type_error(list,a),length/2)"
    );
    assert_eq!(ask("", "length(L, N), N >= 2, !"), ["L = [_R0,_R1], N = 2"]);
    assert_eq!(
        one("nth0(1, [a, b, c], X), nth1(1, [a, b, c], Y)"),
        "X = b, Y = a"
    );
    assert_eq!(
        ask("", "nth1(I, [a, b], X)"),
        ["I = 1, X = a", "I = 2, X = b"]
    );
    assert_eq!(one("last([1, 2, 3], X)"), "X = 3");
    assert_eq!(one("reverse([1, 2, 3], X)"), "X = [3,2,1]");
    assert_eq!(one("sort([c, a, b, a], X)"), "X = [a,b,c]");
    assert_eq!(one("sort(0, @>=, [1, 3, 2, 3], X)"), "X = [3,3,2,1]");
    assert_eq!(
        one("sort(1, @<, [f(2, a), f(1, b), f(2, c)], X)"),
        "X = [f(1,b),f(2,a)]"
    );
    assert_eq!(one("keysort([b-1, a-2, b-0], X)"), "X = [a-2,b-1,b-0]");
    assert_eq!(ask("", "permutation([1, 2, 3], P)").len(), 6);
    assert_eq!(
        one("flatten([1, [2, [3, 4]], [], 5], X)"),
        "X = [1,2,3,4,5]"
    );
    assert_eq!(
        one("sum_list([1, 2, 3.5], S), sumlist([1, 2], T)"),
        "S = 6.5, T = 3"
    );
    assert_eq!(
        one("max_list([1, 5, 3], X), min_list([4, 2, 8], Y)"),
        "X = 5, Y = 2"
    );
    assert_eq!(
        one("max_member(X, [a, f(b), 3]), min_member(Y, [a, f(b), 3])"),
        "X = f(b), Y = 3"
    );
    assert_eq!(one("numlist(1, 5, L)"), "L = [1,2,3,4,5]");
    assert_eq!(one("subtract([1, 2, 3, 4], [2, 4], X)"), "X = [1,3]");
    assert_eq!(one("union([1, 2], [2, 3], X)"), "X = [1,2,3]");
    assert_eq!(one("intersection([1, 2, 3], [3, 1], X)"), "X = [1,3]");
    assert_eq!(one("delete([a, b, a, c], a, X)"), "X = [b,c]");
    assert_eq!(one("list_to_set([a, b, a, c, b], X)"), "X = [a,b,c]");
    assert_eq!(
        ask("", "nextto(X, Y, [1, 2, 3])"),
        ["X = 1, Y = 2", "X = 2, Y = 3"]
    );
    assert_eq!(
        ask("", "select(X, [a, b], R)"),
        ["X = a, R = [b]", "X = b, R = [a]"]
    );
    assert_eq!(one("selectchk(b, [a, b, b], R)"), "R = [a,b]");
    assert_eq!(one("same_length([1, 2], L)"), "L = [_R0,_R1]");
    assert_eq!(
        one("pairs_keys_values(P, [a, b], [1, 2]), pairs_keys(P, K), pairs_values(P, V)"),
        "P = [a-1,b-2], K = [a,b], V = [1,2]"
    );
    assert_eq!(
        one("ord_subtract([a, b, c], [b], X), ord_union([a, c], [b], Y), ord_memberchk(a, [a, b])"),
        "X = [a,c], Y = [a,b,c]"
    );
    assert_eq!(one("ord_insert([a, c], b, X), ord_del_element([a, b], a, Y), ord_intersection([a, b], [b, c], Z)"), "X = [a,b,c], Y = [b], Z = [b]");
    assert_eq!(
        one("reverse(L, X)"),
        "error: error(instantiation_error,reverse/2)"
    );
}

#[test]
fn higher_order() {
    let p = "double(X, Y) :- Y is 2 * X.
             pos(X) :- X > 0.
             add(X, A0, A) :- A is A0 + X.
             cmp_len(O, A, B) :- atom_length(A, LA), atom_length(B, LB), compare(O, LA-A, LB-B).";
    assert_eq!(ask(p, "maplist(double, [1, 2, 3], L)"), ["L = [2,4,6]"]);
    assert_eq!(ask(p, "maplist(pos, [1, 2])"), ["true"]);
    assert_eq!(ask(p, "include(pos, [-1, 2, 0, 3], L)"), ["L = [2,3]"]);
    assert_eq!(ask(p, "exclude(pos, [-1, 2, 0, 3], L)"), ["L = [-1,0]"]);
    assert_eq!(
        ask(p, "partition(pos, [-1, 2, 0, 3], I, E)"),
        ["I = [2,3], E = [-1,0]"]
    );
    assert_eq!(ask(p, "foldl(add, [1, 2, 3], 0, S)"), ["S = 6"]);
    assert_eq!(
        ask(p, "predsort(cmp_len, [ccc, a, bb], L)"),
        ["L = [a,bb,ccc]"]
    );
    assert_eq!(ask(p, "call(double, 4, X)"), ["X = 8"]);
    assert_eq!(
        ask(p, "G = double(5), call(G, X)"),
        ["G = double(5), X = 10"]
    );
}

#[test]
fn atoms_and_strings() {
    assert_eq!(one("atom_codes(abc, L)"), "L = [97,98,99]");
    assert_eq!(one("atom_codes(A, [104, 105])"), "A = hi");
    assert_eq!(one("atom_chars(abc, L)"), "L = [a,b,c]");
    assert_eq!(one("char_code(C, 65), char_code(a, X)"), "C = 'A', X = 97");
    assert_eq!(one("atom_length(hello, N)"), "N = 5");
    assert_eq!(
        one("atom_length(X, N)"),
        "error: error(instantiation_error,atom_length/2)"
    );
    assert_eq!(one("atom_concat(ab, cd, X)"), "X = abcd");
    assert_eq!(
        ask("", "atom_concat(X, Y, ab)"),
        ["X = '', Y = ab", "X = a, Y = b", "X = ab, Y = ''"]
    );
    assert_eq!(one("atom_concat(X, cd, abcd)"), "X = ab");
    assert!(ask("", "atom_concat(cd, X, abcd)").is_empty());
    // As in SWI-Prolog, a number given as one part is its text.
    assert_eq!(one("atom_concat(1, X, '12')"), "X = '2'");
    assert_eq!(one("atom_concat(X, 2, '12')"), "X = '1'");
    assert_eq!(
        ask("", "sub_atom(abcab, B, 2, A, ab)"),
        ["B = 0, A = 3", "B = 3, A = 0"]
    );
    assert_eq!(one("sub_atom(hello, 1, 3, _, S)"), "S = ell");
    assert_eq!(
        one("atom_number('12', N), atom_number(A, 3.5)"),
        "N = 12, A = '3.5'"
    );
    assert_eq!(one("atom_number(foo, N)"), "false");
    assert_eq!(one("number_codes(N, \"42\")"), "N = 42");
    assert_eq!(
        one("number_codes(N, \"4x\")"),
        "error: error(syntax_error(illegal_number),number_codes/2)"
    );
    assert_eq!(
        one("atom_string(A, \"xy\"), atom_string(ab, S)"),
        "A = xy, S = \"ab\""
    );
    assert_eq!(
        one("term_to_atom(f(X, 'A', \"s\"), T)"),
        "T = 'f(_R0,\\'A\\',\"s\")'"
    );
    assert_eq!(one("term_to_atom(T, 'g(1, Y)')"), "T = g(1,_R0)");
    assert_eq!(
        one("atom_to_term('p(X, Y, X)', T, B)"),
        "T = p(_R0,_R1,_R0), B = ['X'=_R0,'Y'=_R1]"
    );
    assert_eq!(
        one("upcase_atom(abC, U), downcase_atom('AbC', D)"),
        "U = 'ABC', D = abc"
    );
    assert_eq!(one("string_concat(\"ab\", cd, S)"), "S = \"abcd\"");
    assert_eq!(one("string_concat(ab, S, \"abcd\")"), "S = \"cd\"");
    assert_eq!(
        one("string_chars(S, [h, i]), string_codes(T, [104]), string_to_atom(\"q\", A)"),
        "S = \"hi\", T = \"h\", A = q"
    );
    assert_eq!(one("string_length(\"hello\", N)"), "N = 5");
    assert_eq!(one("sub_string(\"hello\", 0, 2, _, S)"), "S = \"he\"");
    assert_eq!(
        one("split_string(\"a,b,,c\", \",\", \"\", P)"),
        "P = [\"a\",\"b\",\"\",\"c\"]"
    );
    assert_eq!(
        one("split_string(\"  hi  \", \"\", \" \", P)"),
        "P = [\"hi\"]"
    );
    assert_eq!(one("number_string(N, \" 42 \")"), "N = 42");
    assert_eq!(
        one("string_lower(\"AbC\", L), string_upper(\"AbC\", U)"),
        "L = \"abc\", U = \"ABC\""
    );
    assert_eq!(one("atomic_list_concat([a, 1, \"s\"], X)"), "X = a1s");
    assert_eq!(one("atomic_list_concat([a, b], '-', X)"), "X = 'a-b'");
    assert_eq!(one("atomic_list_concat(L, '-', 'a-b-c')"), "L = [a,b,c]");
}

#[test]
fn format_and_output() {
    assert_eq!(
        one("format(atom(A), \"~w and ~a\", [f(x), b])"),
        "A = 'f(x) and b'"
    );
    assert_eq!(one("format(string(S), \"~q~n\", ['A'])"), "S = \"'A'\\n\"");
    assert_eq!(
        one("format(atom(A), \"~d ~2d ~D\", [42, 314, 1234567])"),
        "A = '42 3.14 1,234,567'"
    );
    assert_eq!(
        one("format(atom(A), \"~2f ~e\", [3.14159, 1.5])"),
        "A = '3.14 1.500000e+00'"
    );
    assert_eq!(
        one("format(atom(A), \"~s~~~c\", [[104, 105], 33])"),
        "A = 'hi~!'"
    );
    assert_eq!(
        one("format(atom(A), \"~w~t~10|~w\", [ab, cd])"),
        "A = 'ab        cd'"
    );
    assert_eq!(
        one("format(atom(A), \"~t~w~10|\", [ab])"),
        "A = '        ab'"
    );
    assert_eq!(one("format(atom(A), \"~p\", [x])"), "A = x");
    assert_eq!(
        one("format(atom(A), \"~w\", [])"),
        "error: error(format(\"not enough arguments for ~w\"),format/2)"
    );
    assert_eq!(one("format(atom(A), \"~a\", x)"), "A = x");
    let kn = load("");
    let mut e = NativeEngine::new(1);
    let q = read("write(f('A', \"s\")), nl, print('A'), writeln(x), format(\"~w-~w\", [1, 2]), tab(2), writeq('B')");
    assert!(e.holds(&View::beliefs(&kn, &[]), &q).unwrap());
    assert_eq!(e.take_output(), "f(A,s)\n'A'x\n1-2  'B'");
    assert_eq!(e.take_output(), "");
}

#[test]
fn between_and_misc() {
    assert_eq!(ask("", "between(1, 3, X)"), ["X = 1", "X = 2", "X = 3"]);
    assert_eq!(ask("", "between(3, 1, X)"), Vec::<String>::new());
    assert_eq!(one("between(1, inf, X), X > 2, !"), "X = 3");
    assert_eq!(
        one("between(1, a, X)"),
        "error: error(type_error(integer,a),between/3)"
    );
    assert_eq!(one("X = f(Y), Y = 1"), "X = f(1), Y = 1");
    assert_eq!(one("X = Y"), "Y = X");
    assert_eq!(one("call(X)"), "error: error(instantiation_error,_)");
    assert_eq!(one("call(1)"), "error: error(type_error(callable,1),_)");
    assert_eq!(ask("", "X = 1 ; X = 2"), ["X = 1", "X = 2"]);
}

#[test]
fn iso_errors_for_bad_lists() {
    assert_eq!(
        one("atom_chars(X, [ab])"),
        "error: error(type_error(character,ab),atom_chars/2)"
    );
    assert_eq!(
        one("atom_codes(X, [0'a|_])"),
        "error: error(instantiation_error,atom_codes/2)"
    );
    assert_eq!(
        one("atom_codes(X, [f(x)])"),
        "error: error(type_error(integer,f(x)),atom_codes/2)"
    );
    assert_eq!(
        one("findall(X, member(X, [1]), 9)"),
        "error: error(type_error(list,9),findall/3)"
    );
    assert_eq!(
        one("aggregate_all(bag(X), fail, 9)"),
        "error: error(type_error(list,9),findall/3)"
    );
    assert_eq!(
        one("findall(X, member(X, [1, 2]), [A|T])"),
        "A = 1, T = [2]"
    );
}

#[test]
fn printing_deep_terms_does_not_crash() {
    let p = "wrap(0, T, T) :- !. wrap(N, T0, T) :- N1 is N - 1, wrap(N1, f(T0), T).";
    assert_eq!(
        ask(
            p,
            "wrap(200000, z, _T), format(atom(_A), \"~w\", [_T]), atom_length(_A, N), sub_atom(_A, 0, 6, _, B)"
        ),
        ["N = 600001, B = 'f(f(f('"]
    );
    // Long lists are not deep: they print.
    assert_eq!(
        ask(
            p,
            "\\+ \\+ (numlist(1, 20000, L), format(atom(A), \"~w\", [L]), atom_length(A, 108895))"
        ),
        ["true"]
    );
}

#[test]
fn cyclic_terms_give_errors_not_hangs() {
    assert_eq!(
        one("X = f(X)"),
        "error: error(representation_error(cyclic_term),_)"
    );
    assert_eq!(
        one("X = f(X), format(atom(_), \"~w\", [X])"),
        "error: error(representation_error(cyclic_term),_)"
    );
    assert_eq!(one("\\+ \\+ X = f(X)"), "true");
}

#[test]
fn cyclic_terms_in_unification_and_comparison_stop() {
    for q in [
        "X = f(X), Y = f(Y), X = Y",
        "X = f(X), Y = f(Y), X == Y",
        "X = f(X), copy_term(X, Y)",
        "X = f(X), ground(X)",
        "X = f(X, Z), term_variables(X, L)",
        "X = f(X), findall(X, true, L)",
        "X = f(X), Y = f(Y), compare(O, X, Y)",
    ] {
        assert_eq!(
            one(q),
            "error: error(representation_error(cyclic_term),_)",
            "{q}"
        );
    }
}

#[test]
fn hostile_arguments_are_errors_or_bounded() {
    assert_eq!(
        one("sort(-1, @<, [f(a)], X)"),
        "error: error(domain_error(not_less_than_zero,-1),sort/4)"
    );
    assert_eq!(
        one("format(atom(A), \"~999999999999|x\", []), atom_length(A, N)"),
        "A = '".to_string() + &" ".repeat(100_000) + "x', N = 100001"
    );
    assert_eq!(
        one("length(L, 1000000000000)"),
        "error: error(domain_error(list_length,1000000000000),length/2)"
    );
    assert_eq!(
        one("functor(T, f, 100000000)"),
        "error: error(resource_error(memory),functor/3)"
    );
    assert_eq!(one("X is 2 ** 100"), "X = 1267650600228229401496703205376");
    assert_eq!(one("X is 1 << 64"), "X = 18446744073709551616");
    // Integers are unbounded, but not without end: a result past about a million bits is an error.
    assert_eq!(
        one("X is 2 ** 2000000"),
        "error: error(resource_error(big_integer),_)"
    );
    assert_eq!(
        one("X is 1 << 100000000"),
        "error: error(resource_error(big_integer),_)"
    );
    assert_eq!(
        one("X is 3 ^ (2^100)"),
        "error: error(resource_error(big_integer),_)"
    );
    assert_eq!(
        one("X is random(0)"),
        "error: error(evaluation_error(undefined),_)"
    );
    assert_eq!(
        one("atom_length(A, B)"),
        "error: error(instantiation_error,atom_length/2)"
    );
    assert_eq!(one("sub_atom(abc, B, L, A, S), fail"), "false");
}

#[test]
fn the_documented_differences_are_the_tested_ones() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/kr-engines.md"))
        .expect("docs/kr-engines.md");
    for (query, _, why) in DIFFERENCES {
        let cell = format!("`{}`", query.replace('|', "\\|"));
        assert!(doc.contains(&cell), "docs/kr-engines.md lacks {cell}");
        assert!(!why.is_empty());
    }
}
