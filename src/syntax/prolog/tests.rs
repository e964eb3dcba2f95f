use super::*;
use crate::term::{Style, Sym};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn read(text: &str) -> Term {
    match Reader::new("t").term(text, 0) {
        Ok(t) => t.term,
        Err(d) => panic!("{}", d.render(text)),
    }
}

fn shown(text: &str) -> String {
    read(text).to_text(Style::CANONICAL)
}

#[test]
fn operators_follow_the_fixed_table() {
    assert_eq!(shown("a :- b, c ; d -> e"), ":-(a,;(','(b,c),->(d,e)))");
    assert_eq!(shown("X is 1 + 2 * 3 - 4"), "is(X,-(+(1,*(2,3)),4))");
    assert_eq!(shown("2 ** 3"), "**(2,3)");
    assert_eq!(shown("3 ^ 4 ^ 5"), "^(3,^(4,5))");
    assert!(Reader::new("t").term("2 ** 3 ^ 4", 0).is_err());
    assert_eq!(shown("\\+ a, b"), "','(\\+(a),b)");
    assert_eq!(shown("- a + b"), "+(-(a),b)");
    assert_eq!(shown("a = b"), "=(a,b)");
    assert_eq!(shown("X =.. [f|T]"), "=..(X,[f|T])");
    assert_eq!(shown("a | b"), ";(a,b)");
    assert_eq!(shown(":- a"), ":-(a)");
    assert_eq!(shown("X mod 2 =:= 0"), "=:=(mod(X,2),0)");
}

#[test]
fn negative_numbers_and_minus() {
    assert_eq!(read("-1"), Term::Int(-1));
    assert_eq!(read("- 1"), Term::compound("-", vec![Term::Int(1)]));
    assert_eq!(read("-(1)"), Term::compound("-", vec![Term::Int(1)]));
    assert_eq!(shown("a - 1"), "-(a,1)");
    assert_eq!(shown("a-1"), "-(a,1)");
    assert_eq!(shown("a - -1"), "-(a,-1)");
    assert_eq!(read("-2.5"), Term::from(-2.5));
    assert_eq!(shown("Y-(Z*2)"), "-(Y,*(Z,2))");
    assert_eq!(shown("X =(a)"), "=(X,a)");
}

#[test]
fn functional_notation_lists_and_curly() {
    assert_eq!(shown("f(a, (b, c))"), "f(a,','(b,c))");
    assert_eq!(shown("[a, b | T]"), "[a,b|T]");
    assert_eq!(shown("[]"), "[]");
    assert_eq!(shown("{a, b}"), "'{}'(','(a,b))");
    assert_eq!(read("{a, b}").to_string(), "{a,b}");
    assert_eq!(shown("'hello world'(X)"), "'hello world'(X)");
    assert_eq!(shown("=(X, Y)"), "=(X,Y)");
    assert_eq!(shown("f(-)"), "f(-)");
    assert_eq!(shown("[-]"), "[-]");
    assert_eq!(read("\"abc\""), Term::string("abc"));
    assert_eq!(read("`ab`"), Term::list(vec![Term::Int(97), Term::Int(98)]));
    assert_eq!(read("0'a"), Term::Int(97));
    assert_eq!(read("0x1F"), Term::Int(31));
}

#[test]
fn quoted_brackets_do_not_confuse_the_reader() {
    assert_eq!(shown("X = '('"), "=(X,'(')");
    assert_eq!(shown("X = \")\""), "=(X,\")\")");
}

#[test]
fn anonymous_variables_are_distinct() {
    let t = read("f(_, _, X, X)");
    let vars = t.vars();
    assert_eq!(vars.len(), 3);
    assert_eq!(vars[2], Sym::intern("X"));
}

#[test]
fn spans_point_at_sub_terms() {
    let text = "on(X, table)";
    let t = Reader::new("t").term(text, 10).unwrap();
    assert_eq!(t.spans.span, 10..22);
    assert_eq!(t.spans.args[0].span, 13..14);
    assert_eq!(t.spans.args[1].span, 16..21);
}

#[test]
fn clauses_recover_after_errors() {
    let text = "a. b :- . c(X) :- d(X).\ne(.\nf.";
    let (clauses, errors) = Reader::new("t").clauses(text, 0);
    let heads: Vec<String> = clauses.iter().map(|c| c.term.to_string()).collect();
    assert_eq!(heads, ["a", "c(X):-d(X)", "f"]);
    assert_eq!(errors.len(), 2, "{errors:?}");
    let (clauses, errors) = Reader::new("t").clauses("a. b", 0);
    assert_eq!(clauses.len(), 1);
    assert!(errors[0].message.contains("missing `.`"));
}

#[test]
fn clause_errors_are_capped() {
    let text = "a :- . ".repeat(10_000);
    let (_, errors) = Reader::new("t").clauses(&text, 0);
    assert_eq!(errors.len(), MAX_CLAUSE_ERRORS + 1);
    assert!(errors.last().unwrap().message.contains("too many"));
}

#[test]
fn term_lists_are_arguments() {
    let ts = Reader::new("t").term_list("X, f(Y), [a]", 0).unwrap();
    assert_eq!(ts.len(), 3);
}

#[test]
fn errors_are_diagnostics_with_spans() {
    for bad in [
        "f(",
        "a b",
        "[a|]",
        "f(a,)",
        "'unterminated",
        "/* open",
        "a :- :- b",
        ")",
        "",
        "a.",
    ] {
        match Reader::new("t").term(bad, 0) {
            Ok(t) => panic!("{bad:?} parsed as {}", t.term),
            Err(d) => assert!(
                d.span.start <= bad.len() && d.span.end <= bad.len(),
                "{bad:?}: {d:?}"
            ),
        }
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_crash() {
    let deep = format!("{}a{}", "f(".repeat(100_000), ")".repeat(100_000));
    assert!(Reader::new("t").term(&deep, 0).is_err());
    let minus = format!("{}a", "- ".repeat(100_000));
    assert!(Reader::new("t").term(&minus, 0).is_err());
    let long = format!("[{}]", vec!["a"; 200_000].join(","));
    let t = Reader::new("t").term(&long, 0).unwrap();
    assert_eq!(t.term.list_items().map(|v| v.len()), Some(200_000));
}

/// Generates a random term over atoms, numbers, variables, operators, lists and strings.
fn gen_term(rng: &mut ChaCha8Rng, depth: u32) -> Term {
    const ATOMS: &[&str] = &[
        "a",
        "foo",
        "[]",
        "RoomA1",
        "it's",
        "+",
        "-",
        "is",
        "mod",
        ",",
        "|",
        "{}",
        "!",
        ";",
        "\\+",
        "hello world",
        "é",
        "",
        ">",
        "\\",
        "-->",
        "ü",
        "straße",
        "Über",
        "---",
        ".",
        "/*",
        "=..",
        "a.b",
        "_x",
    ];
    const FUNCTORS: &[&str] = &[
        "f", "g", "-", "+", "*", "^", "**", ",", ";", "->", ":-", "=", "\\+", "is", "mod", "{}",
        "\\", "=..", "'q'", "|", ".",
    ];
    let leaf = depth == 0 || rng.gen_bool(0.3);
    if leaf {
        return match rng.gen_range(0..7) {
            0 => Term::atom(ATOMS[rng.gen_range(0..ATOMS.len())]),
            1 => Term::Int(rng.gen_range(-1000..1000)),
            2 => Term::from(rng.gen_range(-100.0..100.0f64)),
            3 => Term::var(["X", "Y", "_Z", "Abc"][rng.gen_range(0..4)]),
            4 => Term::string(["", "s", "a\"b", "line\nbreak"][rng.gen_range(0..4)]),
            5 => [
                Term::Int(i64::MIN + 1),
                Term::integer(num_bigint::BigInt::from(i64::MAX) * 1000),
                Term::integer(-num_bigint::BigInt::from(i64::MAX) * 7),
            ][rng.gen_range(0..3)]
            .clone(),
            _ => Term::from([0.5, 1e15, 2.5e-7, 1e300, -0.0][rng.gen_range(0..5)]),
        };
    }
    match rng.gen_range(0..3) {
        0 => {
            let n = rng.gen_range(0..4);
            let items: Vec<Term> = (0..n).map(|_| gen_term(rng, depth - 1)).collect();
            if rng.gen_bool(0.3) {
                Term::list_with_tail(items, Term::var("T"))
            } else {
                Term::list(items)
            }
        }
        _ => {
            let name = FUNCTORS[rng.gen_range(0..FUNCTORS.len())];
            let arity = rng.gen_range(1..4);
            Term::compound(name, (0..arity).map(|_| gen_term(rng, depth - 1)).collect())
        }
    }
}

#[test]
fn printing_then_reading_gives_the_same_term() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for i in 0..20_000 {
        let t = gen_term(&mut rng, 4);
        for style in [Style::WRITEQ, Style::CANONICAL] {
            let text = t.to_text(style);
            match Reader::new("t").term(&text, 0) {
                Ok(back) => assert_eq!(back.term, t, "case {i}: {text}"),
                Err(d) => panic!("case {i}: {text}\n{}", d.render(&text)),
            }
        }
    }
}

#[test]
fn goal_reader_joins_a_name_and_a_spaced_bracket_with_a_warning() {
    let mut r = Reader::goal("f");
    let t = r.term("p(room (X), not (q))", 0).expect("read");
    assert_eq!(t.term.to_string(), "p(room(X),not(q))");
    let spans: Vec<_> = r
        .warnings
        .iter()
        .map(|d| (d.code.as_str(), d.span.clone()))
        .collect();
    assert_eq!(spans, [(SPACED_FUNCTOR, 2..8), (SPACED_FUNCTOR, 12..17)]);
    // Names that are operators, graphic names and names inside quotes are not joined.
    let mut r = Reader::goal("f");
    assert_eq!(
        r.term("X is (1)", 0).expect("read").term.to_string(),
        "X is 1"
    );
    assert!(r.term("'a b' (c)", 0).is_err());
    assert!(r.warnings.is_empty());
}

#[test]
fn goal_reader_ignores_text_after_a_term_with_a_warning() {
    let mut r = Reader::goal("f");
    let t = r.term("a, not(b)) ) c", 0).expect("read");
    assert_eq!(t.term.to_string(), "a,not(b)");
    assert_eq!(r.warnings.len(), 1);
    assert_eq!(
        (r.warnings[0].code.as_str(), r.warnings[0].span.clone()),
        (TRAILING_TEXT, 9..14)
    );
    // A missing operator stays an error; so do clause lists and the standard reader.
    assert!(Reader::goal("f").term("a b", 0).is_err());
    assert!(Reader::new("f").term("a)", 0).is_err());
    let (_, errors) = Reader::goal("f").clauses("a). b.", 0);
    assert_eq!(errors.len(), 1);
}
