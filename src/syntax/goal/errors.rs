//! Parser errors as diagnostics naming what was found and what was expected.

use crate::diag::Diagnostic;
use crate::syntax::lexer::Tok;
use lalrpop_util::ParseError;

/// How a grammar's syntax errors name what was found and what to do: the 2014 grammar and the
/// modular grammars share [`syntax_error_in`] and differ only in these.
pub struct ErrorStyle<'a, T> {
    /// The found token, shown from its text `src[l..r]`.
    pub found: &'a dyn Fn(&str, usize, usize, &T) -> String,
    /// A hint for an unexpected token, given the expected token names.
    pub hint: &'a dyn Fn(&T, &[String]) -> Option<String>,
    /// The hint for an unexpected end of file.
    pub eof_hint: &'a dyn Fn(&[String]) -> String,
}

/// Turns a lalrpop error into a diagnostic (`E0014` unexpected token, `E0015` unexpected end).
pub fn syntax_error(e: ParseError<usize, Tok, Diagnostic>, src: &str, file: &str) -> Diagnostic {
    let style = ErrorStyle {
        found: &|src: &str, l, r, tok: &Tok| found(src, l, r, *tok),
        hint: &|tok: &Tok, expected: &[String]| hint(*tok, expected),
        eof_hint: &|_: &[String]| {
            "a module, section or rule is not finished: check for a missing `}` or `.`".into()
        },
    };
    syntax_error_in(e, src, file, &style)
}

/// Turns a lalrpop error of any GOAL grammar into a diagnostic, named in `style`.
pub fn syntax_error_in<T>(
    e: ParseError<usize, T, Diagnostic>,
    src: &str,
    file: &str,
    style: &ErrorStyle<'_, T>,
) -> Diagnostic {
    match e {
        ParseError::User { error } => error,
        ParseError::InvalidToken { location } => {
            Diagnostic::error("E0014", "invalid token", file, location..location + 1)
        }
        ParseError::UnrecognizedEof { location, expected } => Diagnostic::error(
            "E0015",
            format!(
                "unexpected end of file, expected {}",
                expected_list(&expected)
            ),
            file,
            location..location,
        )
        .with_hint((style.eof_hint)(&expected)),
        ParseError::UnrecognizedToken {
            token: (l, tok, r),
            expected,
        } => {
            let d = Diagnostic::error(
                "E0014",
                format!(
                    "unexpected {}, expected {}",
                    (style.found)(src, l, r, &tok),
                    expected_list(&expected)
                ),
                file,
                l..r,
            );
            match (style.hint)(&tok, &expected) {
                Some(h) => d.with_hint(h),
                None => d,
            }
        }
        ParseError::ExtraToken { token: (l, tok, r) } => Diagnostic::error(
            "E0014",
            format!("unexpected {}", (style.found)(src, l, r, &tok)),
            file,
            l..r,
        ),
    }
}

fn found(src: &str, l: usize, r: usize, tok: Tok) -> String {
    let text = src.get(l..r).unwrap_or("?");
    match tok {
        Tok::KrBraces | Tok::KrParens | Tok::SelParens if text.len() > 30 => {
            format!("{} starting `{}`", tok.describe(), short(text))
        }
        _ => format!("`{}`", short(text)),
    }
}

fn short(text: &str) -> String {
    let first = text.lines().next().unwrap_or("");
    if first.chars().count() > 30 || first.len() < text.len() {
        format!("{}...", first.chars().take(30).collect::<String>())
    } else {
        first.to_string()
    }
}

fn hint(tok: Tok, expected: &[String]) -> Option<String> {
    let has = |s: &str| expected.iter().any(|e| e.trim_matches('"') == s);
    if has(".") && has("+") {
        return Some("end the rule with `.` (or join actions with `+`)".into());
    }
    if tok == Tok::LBrace && has("then") {
        return Some(
            "a condition is followed by `then` (for `if`) or `do` (for `forall`/`listall`)".into(),
        );
    }
    if tok == Tok::SelParens {
        return Some("a `( ... )` that is not a selector `( ... ).` is out of place here".into());
    }
    None
}

/// `one of `a`, `b`` from lalrpop's expected-token names.
pub fn expected_list(expected: &[String]) -> String {
    let mut names: Vec<String> = expected
        .iter()
        .map(|e| {
            let e = e.trim_matches('"');
            match e {
                "Ident" => "a name".to_string(),
                "Str" => "a string".to_string(),
                "Int" => "an integer".to_string(),
                "Float" => "a number".to_string(),
                "KrBraces" => "`{ ... }`".to_string(),
                "KrParens" => "`( ... )`".to_string(),
                "SelParens" => "a selector `( ... ).`".to_string(),
                "SelName" => "an agent name".to_string(),
                "ListallVar" => "a variable".to_string(),
                other => format!("`{}`", other.replace("\\\"", "\"")),
            }
        })
        .collect();
    names.dedup();
    match names.len() {
        0 => "something else".to_string(),
        1 => names[0].clone(),
        n if n > 8 => format!("one of {}, ...", names[..8].join(", ")),
        _ => format!("one of {}", names.join(", ")),
    }
}
