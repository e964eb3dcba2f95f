//! The `.goal` lexer: KR content is cut out as single tokens, with brackets inside quotes,
//! strings, character codes and comments not counted.

use goal::syntax::lexer::{tokens, Tok};

/// The tokens of `src` as (kind, text) pairs; panics if the lexer reported a problem.
fn lex(src: &str) -> Vec<(Tok, &str)> {
    let (toks, diags) = tokens(src, "t.goal");
    assert!(
        diags.is_empty(),
        "unexpected diagnostics for {src:?}: {diags:?}"
    );
    toks.iter().map(|&(l, t, r)| (t, &src[l..r])).collect()
}

#[test]
fn quoted_paren_inside_bel_does_not_close_it() {
    let t = lex("if bel(X = '(') then a.");
    assert_eq!(t[1], (Tok::Bel, "bel"));
    assert_eq!(t[2], (Tok::KrParens, "(X = '(')"));
    assert_eq!(t[3], (Tok::Then, "then"));
}

#[test]
fn brace_in_string_inside_knowledge() {
    let src = "knowledge { s(\"}\"). t('}'). u(`}`). }";
    let t = lex(src);
    assert_eq!(t.len(), 2);
    assert_eq!(t[1], (Tok::KrBraces, &src[10..]));
}

#[test]
fn character_code_of_close_paren() {
    let t = lex("if bel(X = 0')) then a.");
    assert_eq!(t[2], (Tok::KrParens, "(X = 0'))"));
    let t = lex("if bel(X = 0''') then a.");
    assert_eq!(t[2], (Tok::KrParens, "(X = 0''')"));
}

#[test]
fn comments_with_brackets_inside_kr_content() {
    let src = "beliefs { a. % ) } ( \n b. /* } ) */ c. }";
    let t = lex(src);
    assert_eq!(
        t,
        vec![(Tok::Beliefs, "beliefs"), (Tok::KrBraces, &src[8..])]
    );
    let t = lex("if bel(p % )\n) then a.");
    assert_eq!(t[2], (Tok::KrParens, "(p % )\n)"));
}

#[test]
fn univ_and_floats_stay_inside_kr_blocks() {
    let src = "knowledge { f(T, L) :- T =.. L. pi(3.14). } beliefs { }";
    let t = lex(src);
    assert_eq!(t[1].0, Tok::KrBraces);
    assert_eq!(t[1].1, "{ f(T, L) :- T =.. L. pi(3.14). }");
    assert_eq!(t[2], (Tok::Beliefs, "beliefs"));
}

#[test]
fn hyphenated_keywords_are_single_tokens() {
    let t = lex("a-goal goal-a exit-module goal exit");
    let kinds: Vec<Tok> = t.iter().map(|p| p.0).collect();
    assert_eq!(
        kinds,
        vec![
            Tok::AGoal,
            Tok::GoalA,
            Tok::ExitModule,
            Tok::Goal,
            Tok::Exit
        ]
    );
}

#[test]
fn not_paren_is_an_ordinary_bracket() {
    let t = lex("not(bel(p))");
    let kinds: Vec<Tok> = t.iter().map(|p| p.0).collect();
    assert_eq!(
        kinds,
        vec![Tok::Not, Tok::LParen, Tok::Bel, Tok::KrParens, Tok::RParen]
    );
    let t = lex("not((bob).bel(p))");
    assert_eq!(t[2], (Tok::SelParens, "(bob)"));
}

#[test]
fn selectors_and_listall_variables() {
    let t = lex("(a, b).send(:p) + bob.send(!q)");
    assert_eq!(t[0], (Tok::SelParens, "(a, b)"));
    assert_eq!(t[3], (Tok::KrParens, "(:p)"));
    assert_eq!(t[5], (Tok::SelName, "bob"));
    assert_eq!(t[6], (Tok::Dot, "."));
    let t = lex("listall L <- bel(p(X)) do a.");
    assert_eq!(t[1], (Tok::ListallVar, "L"));
    assert_eq!(t[2], (Tok::LArrow, "<-"));
    let t = lex("listall bel(p(X)) -> L do a.");
    assert_eq!(t[1], (Tok::Bel, "bel"));
    assert_eq!(t[4], (Tok::Ident, "L"));
}

#[test]
fn goal_level_tokens() {
    let t = lex("#import \"x.mod2g\". #define m bel(p). move(X) @int { } @env <- ->");
    let kinds: Vec<Tok> = t.iter().map(|p| p.0).collect();
    assert_eq!(
        kinds,
        vec![
            Tok::Import,
            Tok::Str,
            Tok::Dot,
            Tok::Define,
            Tok::Ident,
            Tok::Bel,
            Tok::KrParens,
            Tok::Dot,
            Tok::Ident,
            Tok::KrParens,
            Tok::AtInt,
            Tok::LBrace,
            Tok::RBrace,
            Tok::AtEnv,
            Tok::LArrow,
            Tok::RArrow
        ]
    );
}

#[test]
fn percent_comment_at_end_of_file_without_newline() {
    let t = lex("main module { } % the end");
    assert_eq!(t.len(), 4);
}

#[test]
fn unterminated_things_are_diagnostics() {
    for (src, code) in [
        ("if bel(X = 'abc) then a.", "E0011"),
        ("knowledge { s(\"abc). }", "E0011"),
        ("main module { /* never closed", "E0012"),
        ("if bel(p(X) then a.", "E0013"),
        ("knowledge { a. ", "E0013"),
        ("main module { $ }", "E0009"),
        ("'open", "E0011"),
    ] {
        let (_, diags) = tokens(src, "t.goal");
        assert!(
            diags.iter().any(|d| d.code == code),
            "{src:?}: expected {code}, got {diags:?}"
        );
        for d in &diags {
            assert!(d.span.end <= src.len(), "{src:?}: span out of file: {d:?}");
        }
    }
}

#[test]
fn deep_block_nesting_is_a_diagnostic() {
    let src =
        "main module { program { if true then ".to_string() + &"{ if true then ".repeat(10_000);
    let (_, diags) = tokens(&src, "t.goal");
    assert!(diags.iter().any(|d| d.code == "E0016"), "{diags:?}");
}
