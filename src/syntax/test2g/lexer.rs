//! The `.test2g` token stream: the `.goal` lexer's tokens, with the test keywords picked
//! out of the names, and the brackets of `do(...)` and `reactTo(...)` opened up so the
//! conditions inside them are tokenised (the `.goal` lexer would keep them as raw KR text).

use crate::diag::Diagnostic;
use crate::syntax::lexer::{Lexer, Tok};

/// Deepest nesting of `do(...)` / `reactTo(...)` brackets that are opened up.
const MAX_DEPTH: usize = 50;

/// A `.test2g` token: a `.goal` token or a test keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum T2 {
    G(Tok),
    MasTest,
    Mas,
    Timeout,
    Evaluate,
    Assert,
    AtEnd,
    AtStart,
    Eventually,
    Until,
    While,
    Watch,
    ReactTo,
    In,
}

fn keyword(name: &str) -> Option<T2> {
    Some(match name {
        "masTest" => T2::MasTest,
        "mas" => T2::Mas,
        "timeout" => T2::Timeout,
        "evaluate" => T2::Evaluate,
        "assert" => T2::Assert,
        "atend" => T2::AtEnd,
        "atstart" => T2::AtStart,
        "eventually" => T2::Eventually,
        "until" => T2::Until,
        "while" => T2::While,
        "watch" => T2::Watch,
        "reactTo" => T2::ReactTo,
        "in" => T2::In,
        _ => return None,
    })
}

/// A `(start, token, end)` triple with file-absolute positions.
pub type Triple = (usize, T2, usize);

/// Tokenises the whole `.test2g` text; lexical problems come back as diagnostics.
pub fn tokens(src: &str, file: &str) -> (Vec<Triple>, Vec<Diagnostic>) {
    let mut out = Vec::new();
    let mut diags = Vec::new();
    lex_range(src, 0, src.len(), file, 0, &mut out, &mut diags);
    (out, diags)
}

/// Tokenises `src[start..end]`, appending to `out`.
fn lex_range(
    src: &str,
    start: usize,
    end: usize,
    file: &str,
    depth: usize,
    out: &mut Vec<Triple>,
    diags: &mut Vec<Diagnostic>,
) {
    let Some(text) = src.get(start..end) else {
        return;
    };
    let mut lexer = Lexer::new(text, file);
    let toks: Vec<(usize, Tok, usize)> = lexer.by_ref().filter_map(Result::ok).collect();
    for mut d in lexer.diagnostics {
        d.span = d.span.start + start..d.span.end + start;
        diags.push(d);
    }
    let mut prev: Option<T2> = None;
    for (l, tok, r) in toks {
        let (l, r) = (l + start, r + start);
        let t = match (tok, prev) {
            (Tok::Ident, _) => keyword(&src[l..r]).unwrap_or(T2::G(tok)),
            // The `.goal` lexer takes test keywords for names, whose `(` opens arguments; after
            // a test keyword (`eventually (bob).bel(p)`) a bracket is a selector.
            (Tok::KrParens, Some(p)) if !matches!(p, T2::G(_)) => T2::G(Tok::SelParens),
            _ => T2::G(tok),
        };
        let bracketed = matches!(tok, Tok::SelParens | Tok::KrParens);
        let opens = match prev {
            Some(T2::ReactTo) => bracketed,
            // `do (bob).send(x)` keeps its selector; `do(action)` in a condition is opened up.
            Some(T2::G(Tok::Do)) => {
                let after = src[r..].trim_start_matches([' ', '\t', '\r', '\n']);
                let selector = after.starts_with('.')
                    && after[1..]
                        .chars()
                        .next()
                        .is_some_and(|c| c.is_ascii_alphabetic());
                bracketed && !selector
            }
            _ => false,
        };
        if opens {
            if depth >= MAX_DEPTH {
                diags.push(Diagnostic::error(
                    "E0301",
                    format!("`do(...)`/`reactTo(...)` nested more than {MAX_DEPTH} deep"),
                    file,
                    l..l + 1,
                ));
                return;
            }
            out.push((l, T2::G(Tok::LParen), l + 1));
            lex_range(src, l + 1, r - 1, file, depth + 1, out, diags);
            out.push((r - 1, T2::G(Tok::RParen), r));
        } else {
            out.push((l, t, r));
        }
        prev = Some(t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<T2> {
        let (t, d) = tokens(src, "t.test2g");
        assert!(d.is_empty(), "{d:?}");
        t.into_iter().map(|(_, t, _)| t).collect()
    }

    #[test]
    fn keywords_and_opened_brackets() {
        assert_eq!(
            kinds("masTest { mas = \"a.mas2g\". }"),
            vec![
                T2::MasTest,
                T2::G(Tok::LBrace),
                T2::Mas,
                T2::G(Tok::Eq),
                T2::G(Tok::Str),
                T2::G(Tok::Dot),
                T2::G(Tok::RBrace)
            ]
        );
        assert_eq!(
            kinds("always do(move(a))"),
            vec![
                T2::G(Tok::Always),
                T2::G(Tok::Do),
                T2::G(Tok::LParen),
                T2::G(Tok::Ident),
                T2::G(Tok::KrParens),
                T2::G(Tok::RParen)
            ]
        );
        let t = kinds("reactTo(bel(p), do(a))");
        assert_eq!(t[0], T2::ReactTo);
        assert_eq!(t[1], T2::G(Tok::LParen));
        assert_eq!(t[2], T2::G(Tok::Bel));
        assert_eq!(t[6], T2::G(Tok::LParen));
        assert_eq!(t.len(), 10);
        let t = kinds("do (bob).send(hi).");
        assert_eq!(t[1], T2::G(Tok::SelParens));
    }
}
