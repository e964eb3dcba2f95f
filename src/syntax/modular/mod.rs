//! Modular GOAL (A, 2016+) and MARBEL (B, the VU course language): `.mod2g` module files,
//! `.act2g` action specifications and the `.mas2g` forms that assemble agents from them.
//!
//! Every file is parsed into the 2014 AST ([`crate::syntax::ast`]); `assemble` builds one
//! [`crate::syntax::ast::AgentProgram`] per agent definition, so the validator, the compiler
//! and the interpreter have a single path for all generations. See `docs/modular-goal.md`.

pub mod assemble;
pub mod ast;
pub mod build;
pub mod check;
pub mod detect;
pub mod lexer;
pub mod lower;
pub mod mas;
pub mod pl;
pub mod sources;
pub mod test2g;
pub mod token;

use crate::diag::Diagnostic;
use ast::{ActFile, ModFile};
use build::MBuilder;
use lalrpop_util::lalrpop_mod;
use lexer::ModLexer;

lalrpop_mod!(
    #[allow(clippy::all, unused, dead_code, missing_docs)]
    grammar,
    "/mod2g.rs"
);

/// Parses the `.mod2g` text at `src[start..end]` (spans are positions in `src`); `marbel` reads
/// conditions as plain Prolog literals (B).
pub fn parse_mod2g(
    file: &str,
    src: &str,
    start: usize,
    end: usize,
    marbel: bool,
) -> (Option<ModFile>, Vec<Diagnostic>) {
    let text = &src[..end];
    let mut lexer = ModLexer::new(text, start, end, file, marbel);
    let mut b = MBuilder::new(text, file);
    let result = grammar::ModFileParser::new().parse(&mut b, &mut lexer);
    let mut diags = std::mem::take(&mut b.inner.diagnostics);
    let parsed = match result {
        Ok((uses, module)) => Some(ModFile {
            file: file.to_string(),
            uses,
            module,
        }),
        Err(e) => {
            diags.push(build::syntax_error(e, text, file));
            None
        }
    };
    if lexer.stopped_early {
        // The parser's complaints about the abandoned end of the file are noise.
        diags.retain(|d| d.code != "E0015");
    }
    diags.extend(lexer.diagnostics);
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    (parsed, diags)
}

/// Parses the `.act2g` text at `src[start..end]`.
pub fn parse_act2g(
    file: &str,
    src: &str,
    start: usize,
    end: usize,
) -> (Option<ActFile>, Vec<Diagnostic>) {
    let text = &src[..end];
    let mut lexer = ModLexer::new(text, start, end, file, false);
    let mut b = MBuilder::new(text, file);
    let result = grammar::ActFileParser::new().parse(&mut b, &mut lexer);
    let mut diags = std::mem::take(&mut b.inner.diagnostics);
    let parsed = match result {
        Ok((uses, specs)) => Some(ActFile {
            file: file.to_string(),
            uses,
            specs,
        }),
        Err(e) => {
            diags.push(build::syntax_error(e, text, file));
            None
        }
    };
    if lexer.stopped_early {
        // The parser's complaints about the abandoned end of the file are noise.
        diags.retain(|d| d.code != "E0015");
    }
    diags.extend(lexer.diagnostics);
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    (parsed, diags)
}
