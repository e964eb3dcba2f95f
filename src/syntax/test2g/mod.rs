//! 2014 `.test2g` test files (`masTest`, see the README's "Testing agents"): token stream, parser, AST and
//! checks. Conditions and actions are the `.goal` AST's literals and actions.
//!
//! Entry points: [`parse`] (text to [`MasTest`] plus syntax diagnostics) and [`check_files`]
//! (the MAS file exists and launches the tested agents).

pub mod ast;
mod calls;
pub mod check;
pub mod ctx;
pub mod dump;
pub mod lexer;

pub use ast::MasTest;
pub use check::check_files;

use crate::diag::Diagnostic;
use lalrpop_util::{lalrpop_mod, ParseError};

lalrpop_mod!(
    #[allow(clippy::all, unused, dead_code, missing_docs)]
    grammar,
    "/test2g.rs"
);

/// Parses `.test2g` text read from `file`: the test (if the text could be read far enough) and
/// every syntax error found.
pub fn parse(source: &str, file: &str) -> (Option<MasTest>, Vec<Diagnostic>) {
    // A modular GOAL (A) test file (no `masTest`) is lowered to the same AST.
    if !crate::syntax::modular::test2g::is_classic(source) {
        return crate::syntax::modular::test2g::parse(source, file);
    }
    let (tokens, mut diags) = lexer::tokens(source, file);
    let lexing_failed = diags.iter().any(Diagnostic::is_error);
    let mut ctx = ctx::Ctx::new(source, file);
    let result =
        grammar::MasTestParser::new().parse(&mut ctx, tokens.into_iter().map(Ok::<_, Diagnostic>));
    let recovered = std::mem::take(&mut ctx.recovered);
    diags.append(&mut ctx.diags);
    diags.append(&mut ctx.reader.warnings);
    for e in recovered {
        diags.push(syntax_error(e.error, source, file));
    }
    match result {
        Ok(t) => (Some(t), diags),
        Err(e) => {
            // After a lexical error the token stream stops early; the parser's complaint about
            // the end of the file would only repeat it.
            if !(lexing_failed && matches!(e, ParseError::UnrecognizedEof { .. })) {
                diags.push(syntax_error(e, source, file));
            }
            (None, diags)
        }
    }
}

fn syntax_error<T>(e: ParseError<usize, T, Diagnostic>, source: &str, file: &str) -> Diagnostic {
    let mut d = crate::syntax::mas2g::syntax_error(e, source, file);
    if d.code == "E0202" {
        d.code = "E0304".to_string();
        if d.hint.is_none() {
            d.hint = Some(
                "a test file is `masTest { mas = \"x.mas2g\". [timeout = N.] agent { test { ... } } }`"
                    .to_string(),
            );
        }
    }
    d
}
