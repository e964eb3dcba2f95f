//! Parsing `.goal` agent programs and `.mod2g` module files into the AST.
//!
//! Entry points: [`parse_goal`] and [`parse_mod2g`]. Both return the AST (as far as it could be
//! read) and every syntax error and warning found; they never panic.

mod assemble;
pub mod build;
pub mod errors;
pub mod imports;

use crate::diag::Diagnostic;
use crate::syntax::ast::{AgentProgram, Module};
use crate::syntax::lexer::Lexer;
use build::{Builder, TopItem};
use lalrpop_util::lalrpop_mod;

lalrpop_mod!(
    #[allow(clippy::all, unused, dead_code, missing_docs)]
    grammar,
    "/goal.rs"
);

/// At most this many diagnostics are reported per file (then one saying there were more).
pub const MAX_DIAGNOSTICS: usize = 100;

/// Parses the text of a `.goal` file named `file`.
pub fn parse_goal(file: &str, src: &str) -> (AgentProgram, Vec<Diagnostic>) {
    let mut lexer = Lexer::new(src, file);
    let mut b = Builder::new(src, file);
    lexer.give_up = b.give_up.clone();
    let result = grammar::AgentParser::new().parse(&mut b, &mut lexer);
    b.take_reader_warnings();
    // The builder stops recording syntax errors at the cap; the file then still says so.
    let gave_up = b.give_up.get();
    let mut diags = std::mem::take(&mut b.diagnostics);
    let items = match result {
        Ok(items) => items,
        Err(e) => {
            diags.push(errors::syntax_error(e, src, file));
            Vec::new()
        }
    };
    if lexer.stopped_early {
        // The parser's complaints about the abandoned end of the file are noise.
        diags.retain(|d| d.code != "E0015");
    }
    diags.extend(lexer.diagnostics);
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    if diags.len() > MAX_DIAGNOSTICS || gave_up {
        let at = diags
            .get(MAX_DIAGNOSTICS)
            .or(diags.last())
            .map_or(0..0, |d| d.span.clone());
        diags.truncate(MAX_DIAGNOSTICS);
        diags.push(
            Diagnostic::error(
                "E0033",
                format!("too many problems: only the first {MAX_DIAGNOSTICS} are reported"),
                file,
                at,
            )
            .with_hint("fix these and check again"),
        );
    }
    let mut program = AgentProgram {
        file: file.to_string(),
        modules: Vec::new(),
        imports: Vec::new(),
        span: 0..src.len(),
    };
    for item in items {
        match item {
            TopItem::Module(m) => program.modules.push(m),
            TopItem::Import(i) => program.imports.push(i),
            TopItem::Error => {}
        }
    }
    (program, diags)
}

/// Parses the text of a `.mod2g` file: exactly one module.
pub fn parse_mod2g(file: &str, src: &str) -> (Option<Module>, Vec<Diagnostic>) {
    let (program, mut diags) = parse_goal(file, src);
    for i in &program.imports {
        diags.push(Diagnostic::error(
            "E0032",
            "a module file cannot import other module files",
            file,
            i.span.clone(),
        ));
    }
    let mut modules = program.modules.into_iter();
    let first = modules.next();
    for extra in modules {
        diags.push(
            Diagnostic::error(
                "E0032",
                "a `.mod2g` file holds exactly one module",
                file,
                extra.head_span.clone(),
            )
            .with_hint("put each module in its own `.mod2g` file"),
        );
    }
    if first.is_none() && !diags.iter().any(Diagnostic::is_error) {
        diags.push(Diagnostic::error(
            "E0032",
            "the module file holds no module",
            file,
            0..0,
        ));
    }
    (first, diags)
}
