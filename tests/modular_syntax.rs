//! Every construct of the modular GOAL (A) and MARBEL (B) grammars parses: one fixture per
//! group of constructs under `tests/fixtures/modular/`, its AST snapshotted; and the syntax
//! errors of modular files are reported with file, position and a hint.

use goal::syntax::ast::{dump, AgentProgram, Module, ModuleKind, ModuleOptions};
use goal::syntax::modular::{ast::dump_uses, mas, parse_act2g, parse_mod2g};
use std::path::PathBuf;

fn fixture(path: &str) -> (String, String) {
    let full = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/modular")
        .join(path);
    let text = std::fs::read_to_string(&full).expect("fixture");
    (path.to_string(), text)
}

/// The AST of a fixture as text; asserts it parsed without diagnostics.
fn ast(path: &str) -> String {
    let (file, text) = fixture(path);
    let marbel = path.starts_with("b/");
    let (out, diags) = if path.ends_with(".test2g") {
        let (t, d) = goal::syntax::test2g::parse(&text, &file);
        (
            goal::syntax::test2g::dump::mas_test(&t.expect("parsed"), &text),
            d,
        )
    } else if path.ends_with(".mas2g") {
        let (m, d) = mas::parse(&text, &file);
        (m.dump(), d)
    } else if path.ends_with(".act2g") {
        let (a, d) = parse_act2g(&file, &text, 0, text.len());
        let a = a.expect("parsed");
        let module = Module {
            kind: ModuleKind::Event,
            options: ModuleOptions::default(),
            knowledge: vec![],
            beliefs: vec![],
            goals: vec![],
            program: None,
            action_specs: a.specs,
            imports: vec![],
            sections: vec![],
            head_span: 0..0,
            span: 0..0,
        };
        let p = AgentProgram {
            file: file.clone(),
            modules: vec![module],
            imports: vec![],
            span: 0..0,
        };
        (
            format!("{}{}", dump_uses(&a.uses), dump::agent_program(&p, &text)),
            d,
        )
    } else {
        let (m, d) = parse_mod2g(&file, &text, 0, text.len(), marbel);
        let m = m.expect("parsed");
        (
            format!("{}{}", dump_uses(&m.uses), dump::module(&m.module, &text)),
            d,
        )
    };
    let errors: Vec<String> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.render(&text))
        .collect();
    assert!(errors.is_empty(), "{path}:\n{}", errors.join("\n"));
    let warnings: Vec<String> = diags
        .iter()
        .map(|d| format!("{}: {}\n", d.code, d.message))
        .collect();
    format!("{out}{}", warnings.concat())
}

macro_rules! construct {
    ($name:ident, $path:expr) => {
        #[test]
        fn $name() {
            insta::assert_snapshot!(ast($path));
        }
    };
}

construct!(a_use_clauses, "a/use_clauses.mod2g");
construct!(a_learn_clauses_and_options, "a/learn_options.mod2g");
construct!(a_macros, "a/macros.mod2g");
construct!(a_module_parameters, "a/module_params.mod2g");
construct!(a_rules_and_nested_blocks, "a/rules.mod2g");
construct!(a_literals_and_selectors, "a/literals.mod2g");
construct!(a_actions, "a/actions.mod2g");
construct!(a_action_specifications, "a/specs.act2g");
construct!(a_mas, "a/team.mas2g");
construct!(a_tests, "a/tests.test2g");
construct!(b_mas, "b/team.mas2g");
construct!(b_plain_literal_conditions, "b/conditions.mod2g");
construct!(a_timers_sleep_and_channels, "a/timing.mod2g");
construct!(a_joined_strings_and_unicode_names, "a/unicode.mod2g");
construct!(a_mas_joined_strings_and_unicode_names, "a/unicode.mas2g");
construct!(a_shutdown_role, "a/shutdown.mas2g");

/// The first diagnostic of a parse, rendered.
fn first_error(path: &str, text: &str, marbel: bool) -> String {
    let diags = if path.ends_with(".mas2g") {
        mas::parse(text, path).1
    } else if path.ends_with(".act2g") {
        parse_act2g(path, text, 0, text.len()).1
    } else {
        parse_mod2g(path, text, 0, text.len(), marbel).1
    };
    diags
        .iter()
        .find(|d| d.is_error())
        .map(|d| d.render(text))
        .unwrap_or_else(|| "no error".into())
}

#[test]
fn errors_name_the_place_and_what_to_do() {
    let cases = [
        ("missing_dot.mod2g", "module m {\n\tif bel(a) then print(a)\n\tif bel(b) then print(b).\n}\n", false),
        ("sendonce.mod2g", "module m { if true then allother.sendonce(p). }\n", false),
        ("send_this.mod2g", "module m { if true then send(p). }\n", false),
        ("bad_order.mod2g", "order = sideways.\nmodule m { if true then print(a). }\n", false),
        ("timer_args.mod2g", "module m { if true then starttimer(t, 1). }\n", false),
        ("no_then.mod2g", "module m { if in(P), room(P) goTo(P). }\n", true),
        ("post_not.act2g", "define a with pre { true } post- { not(b) } post+ { c }\n", false),
        ("post_minus_alone.act2g", "define a with pre { true } post- { b }\n", false),
        ("mixed.mas2g", "use \"bw4t.jar\" as environment.\ndefine r { use m for decisions. }\nlaunchpolicy { when * launch r. }\n", false),
        ("bad_role.mas2g", "define r as agent { use m as boss module. }\nlaunchpolicy { }\n", false),
        ("bad_constraint.mas2g", "define r as agent { use m as main. }\nlaunchpolicy { when * launch r with colour = red. }\n", false),
    ];
    let out: Vec<String> = cases
        .iter()
        .map(|(p, t, b)| format!("--- {p}\n{}", first_error(p, t, *b)))
        .collect();
    insta::assert_snapshot!(out.join("\n"));
}

#[test]
fn for_aliases_warn_with_the_canonical_word() {
    let text = "define r { use m for decision. use u for events. }\nlaunchpolicy { }\n";
    let (m, diags) = mas::parse(text, "a.mas2g");
    let warnings: Vec<&str> = diags.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        warnings,
        [
            "`for decision` is read as `for decisions`",
            "`for events` is read as `for updates`"
        ]
    );
    assert_eq!(m.generation, goal::syntax::modular::ast::Generation::Marbel);
}

#[test]
fn generation_is_told_by_the_mas_form() {
    use goal::syntax::modular::{ast::Generation::*, detect::mas_generation};
    assert_eq!(mas_generation("environment { env = \"bw4t\". }"), Classic);
    assert_eq!(mas_generation("% x\nagentfiles { \"a.goal\". }"), Classic);
    assert_eq!(
        mas_generation("launchpolicy { when [type=bot]@env do launch a:a. }"),
        Classic
    );
    assert_eq!(mas_generation("use \"x.jar\" as environment."), Modular);
    assert_eq!(
        mas_generation("/* c */ define a { use m for decisions. }"),
        Modular
    );
    assert_eq!(mas_generation("launchpolicy { when * launch a. }"), Modular);
}
