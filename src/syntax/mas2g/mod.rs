//! `.mas2g` files: lexer, parser, AST and checks.
//!
//! Entry points: [`parse`] (text to [`MasFile`] plus syntax diagnostics) and [`check_files`]
//! (agent files exist, launch rules reference known files).

pub mod ast;
mod builder;
pub mod check;
pub mod lexer;
pub mod raw;

pub use ast::MasFile;
pub use check::check_files;

use crate::diag::Diagnostic;
use lalrpop_util::{lalrpop_mod, ParseError};

lalrpop_mod!(
    #[allow(clippy::all, unused, dead_code, missing_docs)]
    grammar,
    "/mas2g.rs"
);

/// Parses `.mas2g` text read from `file`: the AST (as far as it could be read) and every syntax
/// error and warning found.
pub fn parse(source: &str, file: &str) -> (MasFile, Vec<Diagnostic>) {
    let tokens = match lexer::lex(source, file) {
        Ok(t) => t,
        Err(d) => {
            return (
                MasFile {
                    file: file.to_string(),
                    ..MasFile::default()
                },
                vec![d],
            )
        }
    };
    let mut recovered = Vec::new();
    let result = grammar::MasParser::new()
        .parse(&mut recovered, tokens.into_iter().map(Ok::<_, Diagnostic>));
    let mut diags: Vec<Diagnostic> = recovered
        .into_iter()
        .map(|e| syntax_error(e.error, source, file))
        .collect();
    let sections = match result {
        Ok(s) => s,
        Err(e) => {
            diags.push(syntax_error(e, source, file));
            Vec::new()
        }
    };
    let mas = builder::build(sections, file, &mut diags);
    (mas, diags)
}

/// Turns a lalrpop error into a diagnostic naming what was found and what was expected.
pub(crate) fn syntax_error<T>(
    e: ParseError<usize, T, Diagnostic>,
    source: &str,
    file: &str,
) -> Diagnostic {
    match e {
        ParseError::User { error } => error,
        ParseError::InvalidToken { location } => {
            Diagnostic::error("E0202", "invalid token", file, location..location + 1)
        }
        ParseError::UnrecognizedEof { location, expected } => Diagnostic::error(
            "E0202",
            format!(
                "unexpected end of file, expected {}",
                expected_list(&expected)
            ),
            file,
            location..location,
        )
        .with_hint("a section or rule is not finished; check for a missing `}` or `.`"),
        ParseError::UnrecognizedToken {
            token: (l, _, r),
            expected,
        } => {
            let found = source.get(l..r).unwrap_or("?");
            Diagnostic::error(
                "E0202",
                format!(
                    "unexpected `{found}`, expected {}",
                    expected_list(&expected)
                ),
                file,
                l..r,
            )
        }
        ParseError::ExtraToken { token: (l, _, r) } => {
            let found = source.get(l..r).unwrap_or("?");
            Diagnostic::error("E0202", format!("unexpected `{found}`"), file, l..r)
        }
    }
}

/// `one of `a`, `b`` from lalrpop's expected-token names (already quoted for literals).
fn expected_list(expected: &[String]) -> String {
    let names: Vec<String> = expected
        .iter()
        .map(|e| {
            let e = e.trim_matches('"');
            match e {
                "Ident" => "a name".to_string(),
                "Int" => "an integer".to_string(),
                "Float" => "a number".to_string(),
                "Str" => "a string".to_string(),
                "KrParens" => "a `( ... )` argument list".to_string(),
                "SelParens" => "a `( ... )` selector".to_string(),
                "SelName" => "an agent-name selector".to_string(),
                other => format!("`{}`", other.replace("\\\"", "\"")),
            }
        })
        .collect();
    match names.len() {
        0 => "something else".to_string(),
        1 => names[0].clone(),
        _ => format!("one of {}", names.join(", ")),
    }
}
