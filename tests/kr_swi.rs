//! SWI-Prolog's answers, written down from SWI-Prolog 9 (kept apart from `kr_diff.rs`, which
//! compares with scryer-prolog, whose printing differs): every query runs through the built
//! `goal prolog` binary and must print what SWI prints, in `goal prolog`'s answer format
//! (`writeq` text at priority 699, unbound variables as `_`, one line per answer, `false`, or
//! the error term). Errors are compared on their formal part (the context is `goal`'s own).

use std::path::PathBuf;
use std::process::Command;

/// Helper predicates some queries call.
const HELPERS: &str = "\
cmp3(X, O) :- compare(O, X, 3).
cmp(O, A, B) :- compare(O, A, B).
pos(X) :- X > 0.
";

/// (query, expected output lines joined by `|`; `error:F` for an error with formal part `F`).
const TABLE: &[(&str, &str)] = &[
    // ---- printing: quoting (writeq) ----
    ("X = f('A b', c)", "X = f('A b',c)"),
    ("X = ['A', b, 'c d']", "X = ['A',b,'c d']"),
    (
        "X = [;, '>', '\\\\', -, ü, ---, '-->']",
        "X = [;,>,\\,-,ü,---,-->]",
    ),
    (
        "X = ['Über', 'a.b', '.', [], '{}', !]",
        "X = ['Über','a.b','.',[],{},!]",
    ),
    ("X = 'hello world'", "X = 'hello world'"),
    ("X = 'don''t'", "X = 'don\\'t'"),
    ("X = ''", "X = ''"),
    ("X = \"a string\"", "X = \"a string\""),
    ("X = f(-)", "X = f(-)"),
    // ---- printing: operators ----
    ("compare(O, 2, 1.0)", "O = (>)"),
    ("compare(O, 1, 1)", "O = (=)"),
    ("X = (-)", "X = (-)"),
    ("X = ','", "X = (',')"),
    ("X = -(2^2)", "X = -(2^2)"),
    ("X = -(1)", "X = -(1)"),
    ("X = -(1.5)", "X = -(1.5)"),
    ("X = -(a)", "X = -a"),
    ("X = -(-(1))", "X = - -(1)"),
    ("X = - (-1)", "X = - -1"),
    ("X = (-1)^2", "X = -1^2"),
    ("X = -(a^2)", "X = -a^2"),
    ("X = 1 - -1", "X = 1- -1"),
    ("X = a-(b-c)", "X = a-(b-c)"),
    ("X = (a-b)-c", "X = a-b-c"),
    ("X = 1+2*3", "X = 1+2*3"),
    ("X = (1+2)*3", "X = (1+2)*3"),
    ("X = (a:-b,c;d)", "X = (a:-b,c;d)"),
    ("X = (a->b;c)", "X = (a->b;c)"),
    ("X = (a=b)", "X = (a=b)"),
    ("X = [a=b]", "X = [a=b]"),
    ("X = f((a,b))", "X = f((a,b))"),
    ("X = (\\+a)", "X = (\\+a)"),
    ("X = {a,b}", "X = {a,b}"),
    ("X = [a|b]", "X = [a|b]"),
    ("X = 1.0e15", "X = 1.0e15"),
    ("X is 10.0 ** 20", "X = 1.0e20"),
    ("X = 0'a", "X = 97"),
    // ---- output built-ins ----
    ("print(f('A'))", "f('A')|true"),
    ("write(f('A b', \"s\"))", "f(A b,s)|true"),
    (
        "writeq(f('A b', \"s\", -(1), [a|b]))",
        "f('A b',\"s\",-(1),[a|b])|true",
    ),
    ("format(\"~t~w~t~11|]~n\", [abc])", "    abc    ]|true"),
    ("format(\"~t~w~t~10|]~n\", [abc])", "    abc   ]|true"),
    ("format(\"~a~t~10|~a~n\", [ab, cd])", "ab        cd|true"),
    ("format(\"~t~a~10|~n\", [ab])", "        ab|true"),
    (
        "format(\"~`-t~30|~n\")",
        "------------------------------|true",
    ),
    ("format(\"~e~n\", [1.5])", "1.500000e+00|true"),
    ("format(\"~4f~n\", [2])", "2.0000|true"),
    ("format(\"~2d~n\", [1234])", "12.34|true"),
    ("format(\"~D~n\", [1234567])", "1,234,567|true"),
    (
        "format(\"~s and ~w~n\", [\"abc\", f(x)])",
        "abc and f(x)|true",
    ),
    ("format(\"~q ~a~n\", ['A', 'B'])", "'A' B|true"),
    ("format(\"~p~n\", ['A b'])", "'A b'|true"),
    ("format(atom(A), \"~w-~w\", [a, b])", "A = 'a-b'"),
    ("tab(2), write(x), nl", "  x|true"),
    (
        "write_term(f('A', [1,2,3,4,5]), [quoted(true)])",
        "f('A',[1,2,3,4,5])|true",
    ),
    (
        "write_term(f('A', 1+2), [ignore_ops(true)])",
        "f(A,+(1,2))|true",
    ),
    (
        "write_term([1,2,3,4,5,6,7,8,9,10,11,12], [max_depth(5)])",
        "[1,2,3,4,5|...]|true",
    ),
    (
        "write_term(a(s(s(s(s(0)))), [a,b,c,d,e,f]), [max_depth(3)])",
        "a(s(s(...)),[a,b|...])|true",
    ),
    // ---- arithmetic ----
    ("X is 2 ^ -1", "X = 0.5"),
    ("X is 2 ** -1", "X = 0.5"),
    ("X is 2 ** 3", "X = 8"),
    ("X is 1 ^ -3", "X = 1"),
    ("X is max(1, 1.0)", "X = 1.0"),
    ("X is min(1, 2.0)", "X = 1"),
    ("X is max(2, 1.0)", "X = 2"),
    ("X is 5 / 2", "X = 2.5"),
    ("X is 4 / 2", "X = 2"),
    ("X is -7 // 2", "X = -3"),
    ("X is 7 mod -2", "X = -1"),
    ("X is integer(2.5)", "X = 3"),
    ("X is truncate(3.7)", "X = 3"),
    ("succ(X, 4)", "X = 3"),
    ("succ(3, X)", "X = 4"),
    ("succ(X, 0)", "false"),
    ("plus(1, X, 3)", "X = 2"),
    ("divmod(7, 2, Q, R)", "Q = 3, R = 1"),
    // ---- unbounded integers ----
    ("X is 2^100", "X = 1267650600228229401496703205376"),
    ("X is 2**100", "X = 1267650600228229401496703205376"),
    ("X is 9223372036854775807 + 1", "X = 9223372036854775808"),
    ("X is -9223372036854775808 - 1", "X = -9223372036854775809"),
    ("X is 3037000500 * 3037000500", "X = 9223372037000250000"),
    (
        "Y = 9223372036854775807, X is Y + Y",
        "Y = 9223372036854775807, X = 18446744073709551614",
    ),
    ("X is abs(-9223372036854775808)", "X = 9223372036854775808"),
    ("X is 2^100 - 2^100 + 1", "X = 1"),
    (
        "X is 2^64 // 3, Y is 2^64 mod 7",
        "X = 6148914691236517205, Y = 2",
    ),
    ("X is 1 << 70", "X = 1180591620717411303424"),
    ("X is (2^70) >> 68", "X = 4"),
    ("X is integer(1.0e20)", "X = 100000000000000000000"),
    ("X is 2^70 * 1.0", "X = 1.1805916207174113e21"),
    (
        "X = 123456789012345678901234567890",
        "X = 123456789012345678901234567890",
    ),
    (
        "X = -123456789012345678901234567890",
        "X = -123456789012345678901234567890",
    ),
    (
        "X is 2^100, integer(X)",
        "X = 1267650600228229401496703205376",
    ),
    ("2^100 =:= 2^100 + 0", "true"),
    (
        "X is 2^100, X > 1.0e20, X < 2^101",
        "X = 1267650600228229401496703205376",
    ),
    (
        "compare(O, 100000000000000000000, 99999999999999999999)",
        "O = (>)",
    ),
    (
        "msort([100000000000000000000, 3, -100000000000000000000], L)",
        "L = [-100000000000000000000,3,100000000000000000000]",
    ),
    (
        "atom_number('123456789012345678901234567890', N)",
        "N = 123456789012345678901234567890",
    ),
    (
        "X is 2^70, atom_length(X, L)",
        "X = 1180591620717411303424, L = 22",
    ),
    (
        "format(\"~D~n\", [1180591620717411303424])",
        "1,180,591,620,717,411,303,424|true",
    ),
    // ---- lists ----
    (
        "partition(cmp3, [1,2,3,4,5], L, E, G)",
        "L = [1,2], E = [3], G = [4,5]",
    ),
    (
        "partition(pos, [-1, 2, 0, 3], I, E)",
        "I = [2,3], E = [-1,0]",
    ),
    ("nth0(1, L, x)", "L = [_,x|_]"),
    ("nth1(2, L, x)", "L = [_,x|_]"),
    ("nth0(1, [a,b,c], E, R)", "E = b, R = [a,c]"),
    (
        "nth1(I, [a,b], E, R)",
        "I = 1, E = a, R = [b]|I = 2, E = b, R = [a]",
    ),
    ("nth0(I, [a,b], E)", "I = 0, E = a|I = 1, E = b"),
    ("reverse(X, [1,2])", "X = [2,1]"),
    ("reverse([1,2,3], X)", "X = [3,2,1]"),
    ("length([a,b|c], N)", "error:type_error(list,[a,b|c])"),
    ("length(L, -1)", "error:domain_error(not_less_than_zero,-1)"),
    ("length(L, a)", "error:type_error(integer,a)"),
    ("length(L, 2)", "L = [_,_]"),
    ("delete([a,b,a,c], a, R)", "R = [b,c]"),
    ("delete([f(1),g,f(2)], f(_), R)", "R = [g]"),
    ("last([1,2,3], X)", "X = 3"),
    ("last([], X)", "false"),
    ("sum_list([1, 2.5, 3], S)", "S = 6.5"),
    ("sum_list([], S)", "S = 0"),
    ("sumlist([1, 2], S)", "S = 3"),
    ("max_member(M, [3, 1, b, f(x)])", "M = f(x)"),
    ("min_member(M, [3, 1, b])", "M = 1"),
    ("max_member(M, [])", "false"),
    ("max_member(@=<, M, [1,3,2])", "M = 3"),
    ("min_member(@=<, M, [2,1,3])", "M = 1"),
    ("max_list([1, 5, 3], M)", "M = 5"),
    ("min_list([4, 2, 8], M)", "M = 2"),
    ("max_list([], M)", "false"),
    ("numlist(1, 5, L)", "L = [1,2,3,4,5]"),
    ("numlist(5, 1, L)", "false"),
    ("msort([b, a, b], L)", "L = [a,b,b]"),
    ("predsort(cmp, [c,a,b,a], L)", "L = [a,b,c]"),
    ("sort(0, @>=, [1, 3, 2, 3], L)", "L = [3,3,2,1]"),
    ("keysort([b-1, a-2, b-0], L)", "L = [a-2,b-1,b-0]"),
    ("pairs_keys_values(P, [a, b], [1, 2])", "P = [a-1,b-2]"),
    ("list_to_set([a, b, a, c, b], S)", "S = [a,b,c]"),
    ("list_to_set([1, 1.0, 1], S)", "S = [1,1.0]"),
    ("select(b, [a,b,c], R)", "R = [a,c]"),
    ("selectchk(b, [a,b,c,b], x, R)", "R = [a,x,c,b]"),
    ("subtract([a,b,c], [b], R)", "R = [a,c]"),
    ("exclude(==(a), [a,b,a], R)", "R = [b]"),
    ("include(integer, [a,1,2.0,3], R)", "R = [1,3]"),
    ("foldl(plus, [1,2,3], 0, S)", "S = 6"),
    ("is_set([a,b])", "true"),
    ("is_set([a,b,a])", "false"),
    ("subset([a], [b,a])", "true"),
    ("proper_length([a,b|_], N)", "false"),
    ("proper_length([a,b], N)", "N = 2"),
    ("clumped([a,a,b,a], C)", "C = [a-2,b-1,a-1]"),
    ("subseq([1,2,3], [1,3], R)", "R = [2]"),
    ("between(1, 3, X)", "X = 1|X = 2|X = 3"),
    ("between(3, 1, X)", "false"),
    ("between(1, inf, X), X > 2, !", "X = 3"),
    // ---- all solutions ----
    ("aggregate_all(count, member(_, [a, b]), C)", "C = 2"),
    ("aggregate_all(count, fail, C)", "C = 0"),
    ("aggregate_all(sum(_X), member(_X, [1, 2, 3]), S)", "S = 6"),
    ("aggregate_all(max(_X), member(_X, [1, 3, 2]), M)", "M = 3"),
    ("aggregate_all(max(_X), member(_X, []), M)", "false"),
    (
        "aggregate_all(bag(_X), member(_X, [c, a, c]), B)",
        "B = [c,a,c]",
    ),
    (
        "aggregate_all(set(_X), member(_X, [c, a, c]), B)",
        "B = [a,c]",
    ),
    // ---- atoms and strings ----
    ("upcase_atom('straße', U)", "U = 'STRAßE'"),
    ("upcase_atom(hello, U)", "U = 'HELLO'"),
    ("string_upper(\"abc\", U)", "U = \"ABC\""),
    ("atomic_list_concat([a, b, c], X)", "X = abc"),
    ("atomic_list_concat([a, 1, \"s\"], -, X)", "X = 'a-1-s'"),
    ("atomic_list_concat(L, ',', 'a,b,c')", "L = [a,b,c]"),
    ("string_concat(\"ab\", \"cd\", S)", "S = \"abcd\""),
    ("sub_atom(hello, 1, 3, A, S)", "A = 1, S = ell"),
    ("atom_number('12', N)", "N = 12"),
    ("atom_number(foo, N)", "false"),
    ("term_to_atom(f(x, 'A'), A)", "A = 'f(x,\\'A\\')'"),
    ("term_to_atom(T, 'g(1, b)')", "T = g(1,b)"),
    ("number_codes(N, \"42\")", "N = 42"),
    ("char_code(C, 0'a)", "C = a"),
    (
        "split_string(\"a,b,,c\", \",\", \"\", P)",
        "P = [\"a\",\"b\",\"\",\"c\"]",
    ),
    ("split_string(\"  hi  \", \"\", \" \", P)", "P = [\"hi\"]"),
    ("string_chars(S, [h, i])", "S = \"hi\""),
    ("sub_string(\"hello\", 0, 2, _, S)", "S = \"he\""),
    ("string_length(\"héllo\", N)", "N = 5"),
    ("string_code(1, \"abc\", C)", "C = 97"),
    ("atom_string(A, \"xyz\")", "A = xyz"),
    ("text_to_string(hello, S)", "S = \"hello\""),
    ("char_type(a, alpha)", "true"),
    ("char_type('A', upper(L))", "L = a"),
    ("char_type(x, to_upper(U))", "U = 'X'"),
    ("char_type('7', digit(W))", "W = 7"),
    ("char_type(' ', space)", "true"),
    ("char_type(a, digit(_))", "false"),
    ("code_type(0'a, alpha)", "true"),
    ("code_type(0'A, to_lower(L))", "L = 97"),
    // ---- randomness (seeded; only the deterministic cases have fixed answers) ----
    ("random_between(1, 1, X)", "X = 1"),
    ("random_member(X, [a])", "X = a"),
    ("random_permutation([a], P)", "P = [a]"),
    ("random_select(X, [a], R)", "X = a, R = []"),
    ("randset(3, 3, S)", "S = [1,2,3]"),
    ("random(X), float(X), X >= 0.0, X < 1.0, !", "X = _FLOAT_"),
];

/// The helper predicates in a temporary directory of their own (`tag` keeps tests that run in
/// parallel apart).
fn helpers_file(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-kr-swi-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("helpers.pl");
    std::fs::write(&path, HELPERS).expect("write helpers");
    path
}

/// What `goal prolog FILE -q QUERY` prints, lines joined by `|`.
fn run(file: &PathBuf, query: &str, seed: Option<u64>) -> String {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_goal"));
    cmd.arg("prolog").arg(file).arg("-q").arg(query);
    if let Some(seed) = seed {
        cmd.arg("--seed").arg(seed.to_string());
    }
    let out = cmd.output().expect("run goal prolog");
    let text = String::from_utf8_lossy(&out.stdout);
    text.lines().collect::<Vec<_>>().join("|")
}

/// True when the printed output matches the expected table entry.
fn matches(got: &str, want: &str) -> bool {
    if let Some(formal) = want.strip_prefix("error:") {
        return got.starts_with(&format!("error({formal},"));
    }
    if let Some(prefix) = want.strip_suffix("_FLOAT_") {
        return got
            .strip_prefix(prefix)
            .and_then(|f| f.parse::<f64>().ok())
            .is_some_and(|f| (0.0..1.0).contains(&f));
    }
    got == want
}

#[test]
fn answers_agree_with_swi_prolog() {
    let file = helpers_file("table");
    let mut wrong = Vec::new();
    for (query, want) in TABLE {
        let got = run(&file, query, None);
        if !matches(&got, want) {
            wrong.push(format!("{query}\n    want: {want}\n    got:  {got}"));
        }
    }
    let _ = std::fs::remove_dir_all(file.parent().unwrap_or(&file));
    assert!(
        wrong.is_empty(),
        "{} of {} differ from SWI-Prolog:\n{}",
        wrong.len(),
        TABLE.len(),
        wrong.join("\n")
    );
}

/// Deep facts for the printing tests.
const DEEP: &str = "\
deep(0, z) :- !.
deep(N, f(T)) :- N1 is N - 1, deep(N1, T).
";

fn deep_file() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("goal-kr-swi-deep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("deep.pl");
    std::fs::write(&path, DEEP).expect("write deep.pl");
    path
}

#[test]
fn huge_answers_print_and_huge_culprits_are_cut_off() {
    let file = deep_file();
    let list = run(&file, "numlist(1, 30000, L)", None);
    assert!(list.starts_with("L = [1,2,3,"), "{}", &list[..40]);
    assert!(list.ends_with(",29999,30000]"));
    let deep = run(&file, "deep(100000, T)", None);
    assert_eq!(deep.len(), "T = ".len() + 100_000 * 3 + 1);
    assert!(deep.starts_with("T = f(f(") && deep.contains("f(z)))") && deep.ends_with(")))"));
    // The culprit of this error is nested 50,000 deep: the message shows its first levels.
    let error = run(&file, "deep(50000, T), atom_length(T, N)", None);
    assert_eq!(
        error,
        "error(type_error(atomic,f(f(f(f(f(f(f(f(...))))))))),atom_length/2)"
    );
    let _ = std::fs::remove_dir_all(file.parent().unwrap_or(&file));
}

#[test]
fn goal_prolog_draws_random_numbers_from_its_seed() {
    let file = helpers_file("seed");
    let q = "random_between(1, 1000000000, X), random(Y), random_permutation([a,b,c,d,e,f], P)";
    let a = run(&file, q, Some(1));
    assert_eq!(a, run(&file, q, Some(1)));
    assert_ne!(a, run(&file, q, Some(2)));
    assert_eq!(run(&file, q, None), run(&file, q, Some(0)));
    let _ = std::fs::remove_dir_all(file.parent().unwrap_or(&file));
}

#[test]
fn unbounded_modes_are_errors_not_endless_answers() {
    // SWI enumerates lists without end here; `goal prolog` collects every answer, so these
    // modes are instantiation errors instead.
    let file = helpers_file("modes");
    assert_eq!(
        run(&file, "delete(X, a, R)", None),
        "error(instantiation_error,delete/3)"
    );
    assert_eq!(
        run(&file, "reverse(L, X)", None),
        "error(instantiation_error,reverse/2)"
    );
    let _ = std::fs::remove_dir_all(file.parent().unwrap_or(&file));
}

#[test]
fn undefined_predicates_get_did_you_mean_hints() {
    use goal::syntax::{goal::parse_goal, validate::validate};
    let src = "main module {\n  knowledge { at_room(r1). }\n  program {\n    \
               if bel(lenght([a], N), at_rom(R)) then print(N).\n  }\n}\n";
    let (program, parse) = parse_goal("t.goal", src);
    assert!(parse.iter().all(|d| !d.is_error()), "{parse:?}");
    let hints: Vec<String> = validate(&program, None)
        .into_iter()
        .filter(|d| d.code == "E0121")
        .filter_map(|d| d.hint)
        .collect();
    assert_eq!(hints.len(), 2, "{hints:?}");
    assert!(
        hints[0].starts_with("did you mean `length/2`?"),
        "{hints:?}"
    );
    assert!(
        hints[1].starts_with("did you mean `at_room/1`?"),
        "{hints:?}"
    );
    // Library predicates added for SWI compatibility are known to the validator.
    let ok = "main module {\n  program {\n    \
              if bel(char_type(a, alpha), randseq(2, 5, L)) then print(L).\n  }\n}\n";
    let (program, _) = parse_goal("t.goal", ok);
    let codes: Vec<String> = validate(&program, None)
        .into_iter()
        .map(|d| d.code)
        .collect();
    assert!(!codes.contains(&"E0121".to_string()), "{codes:?}");
}

#[test]
fn goal_prolog_warns_about_undefined_goals_with_did_you_mean() {
    let file = helpers_file("warn");
    let out = Command::new(env!("CARGO_BIN_EXE_goal"))
        .arg("prolog")
        .arg(&file)
        .arg("-q")
        .arg("lenght([a], N) ; \\+ cmpp(a, b, c) ; zzqq")
        .output()
        .expect("run goal prolog");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        stderr.lines().collect::<Vec<_>>(),
        [
            "warning: `lenght/2` is not defined, so it fails (did you mean `length/2`?)",
            "warning: `cmpp/3` is not defined, so it fails (did you mean `cmp/3`?)",
            "warning: `zzqq/0` is not defined, so it fails",
        ]
    );
    // The undefined goals fail; `\+` of one succeeds.
    assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "N = _");
    assert_eq!(
        run(&file, "cmp(O, 1, 2), length([a], N)", None),
        "O = (<), N = 1"
    );
    let _ = std::fs::remove_dir_all(file.parent().unwrap_or(&file));
}
