//! The `.mas2g` lexer: keywords, identifiers, numbers, strings and punctuation, with `%` and
//! `/* */` comments skipped; produces `(start, Tok, end)` triples for the lalrpop parser.

use crate::diag::Diagnostic;
use logos::Logos;

/// Deepest bracket nesting accepted before parsing (keeps the AST shallow enough to drop and
/// print without deep recursion).
pub const MAX_NESTING: usize = 200;

/// A `.mas2g` token.
#[derive(Logos, Clone, Debug, PartialEq)]
#[logos(skip r"[ \t\r\n\f]+")]
#[logos(skip r"%[^\n]*")]
pub enum Tok<'s> {
    #[token("environment")]
    Environment,
    #[token("env")]
    Env,
    #[token("init")]
    Init,
    #[token("agentfiles")]
    AgentFiles,
    #[token("name")]
    Name,
    #[token("language")]
    Language,
    #[token("launchpolicy")]
    LaunchPolicy,
    #[token("launch")]
    Launch,
    #[token("when")]
    When,
    #[token("entity")]
    Entity,
    #[token("do")]
    Do,
    #[token("type")]
    Type,
    #[token("max")]
    Max,
    #[token("@env")]
    AtEnv,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("=")]
    Eq,
    #[token(".")]
    Dot,
    #[token(",")]
    Comma,
    #[token(":")]
    Colon,
    #[token("*")]
    Star,
    #[token("+")]
    Plus,
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*")]
    Ident(&'s str),
    #[regex(r"-?[0-9]+", |lex| lex.slice().parse::<i64>().ok())]
    Int(i64),
    #[regex(r"-?[0-9]+\.[0-9]+([eE][+-]?[0-9]+)?", |lex| lex.slice().parse::<f64>().ok())]
    Float(f64),
    #[regex(r#""([^"\\]|\\.)*""#, |lex| unescape(lex.slice()))]
    #[regex(r#"'([^'\\]|\\.)*'"#, |lex| unescape(lex.slice()))]
    Str(String),
    #[token("/*", block_comment)]
    BlockComment,
}

/// Skips to the end of a block comment; `false` (an error) when it is not terminated.
fn block_comment<'s>(lex: &mut logos::Lexer<'s, Tok<'s>>) -> bool {
    match lex.remainder().find("*/") {
        Some(i) => {
            lex.bump(i + 2);
            true
        }
        None => {
            lex.bump(lex.remainder().len());
            false
        }
    }
}

/// The text of a quoted string without its quotes. Only an escaped quote (`\"`, `\'`) is an
/// escape: other backslashes are kept, since `.mas2g` strings are mostly Windows paths
/// (`"environments\BW4T2\BW4TClient.jar"`).
pub fn unescape(quoted: &str) -> String {
    let inner = &quoted[1..quoted.len() - 1];
    let mut out = String::with_capacity(inner.len());
    let mut chars = inner.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, chars.peek()) {
            ('\\', Some(&q)) if q == '"' || q == '\'' => {
                out.push(q);
                chars.next();
            }
            _ => out.push(c),
        }
    }
    out
}

/// A `(start, token, end)` triple as lalrpop expects it.
pub type Spanned<'s> = (usize, Tok<'s>, usize);

/// Lexes `source` completely: the tokens (comments removed) or the first lexical error.
pub fn lex<'s>(source: &'s str, file: &str) -> Result<Vec<Spanned<'s>>, Diagnostic> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut lexer = Tok::lexer(source);
    while let Some(item) = lexer.next() {
        let span = lexer.span();
        match item {
            Ok(Tok::BlockComment) => continue,
            Ok(tok) => {
                match tok {
                    Tok::LBrace | Tok::LBracket | Tok::LParen => {
                        depth += 1;
                        if depth > MAX_NESTING {
                            return Err(Diagnostic::error(
                                "E0201",
                                format!("brackets nested more than {MAX_NESTING} deep"),
                                file,
                                span,
                            )
                            .with_hint("flatten the nested lists or function terms"));
                        }
                    }
                    Tok::RBrace | Tok::RBracket | Tok::RParen => depth = depth.saturating_sub(1),
                    _ => {}
                }
                out.push((span.start, tok, span.end));
            }
            Err(()) => return Err(lex_error(source, file, span)),
        }
    }
    Ok(out)
}

fn lex_error(source: &str, file: &str, span: std::ops::Range<usize>) -> Diagnostic {
    let text = source.get(span.clone()).unwrap_or("");
    let (message, hint) = if text.starts_with("/*") {
        ("unterminated block comment", "close the comment with `*/`")
    } else if text.starts_with('"') || text.starts_with('\'') {
        (
            "unterminated string",
            "close the string with a matching quote",
        )
    } else if text
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || c == '-')
    {
        ("number out of range", "use a smaller number")
    } else {
        (
            "unexpected character",
            "remove it or put it inside a string",
        )
    };
    let end = span.start + text.chars().next().map_or(0, char::len_utf8);
    let span = if text.starts_with("/*") || text.starts_with('"') || text.starts_with('\'') {
        span.start..span.start + 1
    } else if message == "number out of range" {
        span
    } else {
        span.start..end
    };
    Diagnostic::error("E0200", format!("{message} in .mas2g file"), file, span).with_hint(hint)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok<'_>> {
        lex(s, "t.mas2g")
            .unwrap()
            .into_iter()
            .map(|(_, t, _)| t)
            .collect()
    }

    #[test]
    fn lexes_keywords_strings_numbers_and_skips_comments() {
        let t = toks("env = \"a\" + 'b' % c\n /* x */ 3 -2 1.5 @env foo");
        assert_eq!(
            t,
            vec![
                Tok::Env,
                Tok::Eq,
                Tok::Str("a".into()),
                Tok::Plus,
                Tok::Str("b".into()),
                Tok::Int(3),
                Tok::Int(-2),
                Tok::Float(1.5),
                Tok::AtEnv,
                Tok::Ident("foo")
            ]
        );
    }

    #[test]
    fn comment_at_end_of_file_without_newline() {
        assert_eq!(toks("launch % end"), vec![Tok::Launch]);
    }

    #[test]
    fn unterminated_things_are_errors() {
        assert!(lex("\"abc", "f")
            .unwrap_err()
            .message
            .contains("unterminated string"));
        assert!(lex("/* abc", "f")
            .unwrap_err()
            .message
            .contains("block comment"));
        assert!(lex("99999999999999999999999", "f").is_err());
        assert!(lex("é", "f").is_err());
        let deep = "[".repeat(MAX_NESTING + 1);
        assert_eq!(lex(&deep, "f").unwrap_err().code, "E0201");
    }
}
