//! Tokens of Prolog text, produced by a `logos` lexer plus a small pass that finds end tokens,
//! functional notation (`name(` with no space) and numbers anonymous variables apart.

use crate::diag::Span;
use crate::term::Sym;
use logos::Logos;

/// Longest integer literal read (reading digits into a big integer takes quadratic time).
const MAX_DIGITS: usize = 10_000;

/// Raw tokens straight from logos.
#[derive(Logos, Debug, Clone, PartialEq)]
#[logos(skip r"[ \t\r\n\x0C]+")]
enum Raw {
    #[regex(r"%[^\n]*", logos::skip)]
    #[token("/*", block_comment)]
    Comment,
    // The first letter only: `name_rest` takes the others. A Unicode-class repetition in the
    // pattern would make logos recurse once per character (a stack overflow on long names).
    #[regex(r"\p{Lowercase}", name_rest)]
    Name,
    #[regex(r"[\p{Uppercase}\p{Lt}_]", name_rest)]
    Var,
    #[regex(r"[0-9][0-9_]*")]
    Int,
    #[regex(r"0x[0-9a-fA-F]+")]
    Hex,
    #[regex(r"0o[0-7]+")]
    Octal,
    #[regex(r"0b[01]+")]
    Binary,
    #[token("0'", char_code)]
    CharCode,
    #[regex(r"[0-9]+\.[0-9]+([eE][+-]?[0-9]+)?")]
    #[regex(r"[0-9]+[eE][+-]?[0-9]+")]
    Float,
    #[token("'", |lex| quoted(lex, '\''))]
    Quoted,
    #[token("\"", |lex| quoted(lex, '"'))]
    Str,
    #[token("`", |lex| quoted(lex, '`'))]
    BackQuoted,
    #[regex(r"[+\-*/\\^<>=~:.?@#&$]+")]
    Graphic,
    #[token("(")]
    Open,
    #[token(")")]
    Close,
    #[token("[")]
    LBracket,
    #[token("]")]
    RBracket,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token(",")]
    Comma,
    #[token("|")]
    Bar,
    #[token("!")]
    Cut,
    #[token(";")]
    Semicolon,
}

/// Consumes the rest of a name or variable: letters, digits and `_`.
fn name_rest(lex: &mut logos::Lexer<Raw>) {
    let rest = lex.remainder();
    let end = rest
        .char_indices()
        .find(|&(_, c)| !(c.is_alphabetic() || c.is_numeric() || c == '_'))
        .map_or(rest.len(), |(i, _)| i);
    lex.bump(end);
}

/// Consumes a block comment; fails when it is not closed.
fn block_comment(lex: &mut logos::Lexer<Raw>) -> logos::FilterResult<(), ()> {
    match lex.remainder().find("*/") {
        Some(end) => {
            lex.bump(end + 2);
            logos::FilterResult::Skip
        }
        None => {
            lex.bump(lex.remainder().len());
            logos::FilterResult::Error(())
        }
    }
}

/// Consumes a quoted item up to its closing quote (doubled quotes and escapes stay inside).
fn quoted(lex: &mut logos::Lexer<Raw>, quote: char) -> bool {
    let rest = lex.remainder();
    let mut chars = rest.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c == '\\' {
            chars.next();
        } else if c == quote {
            if matches!(chars.peek(), Some((_, q)) if *q == quote) {
                chars.next();
            } else {
                lex.bump(i + 1);
                return true;
            }
        } else if c == '\n' && quote != '`' {
            // A newline inside a quoted item is almost always a missing quote.
            break;
        }
    }
    lex.bump(rest.find('\n').unwrap_or(rest.len()));
    false
}

/// Consumes the character of a `0'c` character code.
fn char_code(lex: &mut logos::Lexer<Raw>) -> bool {
    let rest = lex.remainder();
    let mut chars = rest.chars();
    match chars.next() {
        Some('\\') => match escape_len(&rest[1..]) {
            Some(n) => {
                lex.bump(1 + n);
                true
            }
            None => false,
        },
        Some('\'') if rest[1..].starts_with('\'') => {
            lex.bump(2);
            true
        }
        Some(c) => {
            lex.bump(c.len_utf8());
            true
        }
        None => false,
    }
}

/// Length in bytes of the escape sequence body after a backslash.
fn escape_len(s: &str) -> Option<usize> {
    let c = s.chars().next()?;
    if c == 'x' {
        let end = s[1..].find('\\')?;
        return Some(end + 2);
    }
    if c.is_digit(8) {
        let end = s.find('\\')?;
        return Some(end + 1);
    }
    Some(c.len_utf8())
}

/// A token of Prolog text as the grammar sees it.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// An atom or operator name (letters, graphic characters, quoted, `!`, `;`).
    Name(Sym),
    /// A name immediately followed by `(`: functional notation.
    Functor(Sym),
    Var(Sym),
    Int(i64),
    /// An integer literal beyond 64 bits.
    BigInt(num_bigint::BigInt),
    Float(f64),
    Str(String),
    /// A back-quoted string (read as a list of character codes).
    BackQuoted(String),
    Open,
    Close,
    LBracket,
    RBracket,
    LBrace,
    RBrace,
    Comma,
    Bar,
    /// The end token: `.` followed by whitespace, `%` or the end of the text.
    End,
}

/// A lexical error with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct LexError {
    pub message: String,
    pub hint: Option<String>,
    pub span: Span,
}

/// Deepest bracket nesting accepted: deeper terms are almost certainly generated garbage, and
/// every later pass over the term would need that much stack.
pub const MAX_NESTING: usize = 1000;

/// Splits Prolog text into tokens with file-absolute spans; `anonymous` numbers `_` variables.
pub fn tokenize(
    text: &str,
    offset: usize,
    anonymous: &mut u32,
) -> Result<Vec<(usize, Tok, usize)>, LexError> {
    tokenize_with(text, offset, anonymous, None)
}

/// Like [`tokenize`]; with `spaced`, also reads `name (args)` (blanks between a plain name and
/// `(`) as functional notation, as GOAL's own Prolog reader did, and records the span from the
/// name to the `(` of each such place. Standard Prolog reads it as an error (or, for a prefix
/// operator, as the operator applied to a bracketed term), so operator names are never joined.
pub fn tokenize_with(
    text: &str,
    offset: usize,
    anonymous: &mut u32,
    mut spaced: Option<&mut Vec<Span>>,
) -> Result<Vec<(usize, Tok, usize)>, LexError> {
    let mut out: Vec<(usize, Tok, usize)> = Vec::new();
    let mut lex = Raw::lexer(text);
    let mut depth = 0usize;
    while let Some(raw) = lex.next() {
        let span = lex.span();
        let slice = lex.slice();
        let (start, end) = (span.start + offset, span.end + offset);
        let err = |message: String, hint: Option<&str>| LexError {
            message,
            hint: hint.map(str::to_string),
            span: start..end,
        };
        let raw = match raw {
            Ok(r) => r,
            Err(()) => {
                return Err(if slice.starts_with("/*") {
                    LexError {
                        message: "unterminated block comment".into(),
                        hint: Some("close the comment with `*/`".into()),
                        span: start..start + 2,
                    }
                } else if slice.starts_with('\'')
                    || slice.starts_with('"')
                    || slice.starts_with('`')
                {
                    LexError {
                        message: "unterminated quoted text".into(),
                        hint: Some(format!(
                            "close it with a matching {} on the same line",
                            &slice[..1]
                        )),
                        span: start..start + 1,
                    }
                } else if slice.starts_with("0'") {
                    err(
                        "incomplete character code".into(),
                        Some("write a character after 0', e.g. 0'a"),
                    )
                } else {
                    err(
                        format!(
                            "unexpected character `{}`",
                            slice.chars().next().unwrap_or(' ')
                        ),
                        None,
                    )
                });
            }
        };
        let tok = match raw {
            Raw::Comment => continue,
            Raw::Name => Tok::Name(Sym::intern(slice)),
            Raw::Var if slice == "_" => {
                *anonymous += 1;
                Tok::Var(Sym::intern(&format!("_G{anonymous}")))
            }
            Raw::Var => Tok::Var(Sym::intern(slice)),
            Raw::Int | Raw::Hex | Raw::Octal | Raw::Binary if slice.len() > MAX_DIGITS => {
                return Err(err(
                    format!("integer of {} digits is too large", slice.len()),
                    Some("integers may have at most 10000 digits"),
                ))
            }
            Raw::Int => match slice.replace('_', "").parse::<i64>() {
                Ok(i) => Tok::Int(i),
                Err(_) => Tok::BigInt(slice.replace('_', "").parse().unwrap_or_default()),
            },
            Raw::Hex | Raw::Octal | Raw::Binary => {
                let radix = match raw {
                    Raw::Hex => 16,
                    Raw::Octal => 8,
                    _ => 2,
                };
                match i64::from_str_radix(&slice[2..], radix) {
                    Ok(i) => Tok::Int(i),
                    Err(_) => Tok::BigInt(
                        num_bigint::BigInt::parse_bytes(&slice.as_bytes()[2..], radix)
                            .unwrap_or_default(),
                    ),
                }
            }
            Raw::CharCode => match unescape(&slice[2..], '\'') {
                Ok(s) if s.chars().count() == 1 => {
                    Tok::Int(s.chars().next().map_or(0, |c| c as i64))
                }
                _ => {
                    return Err(err(
                        "invalid character code".into(),
                        Some("write 0' followed by one character"),
                    ))
                }
            },
            Raw::Float => match slice.parse::<f64>() {
                Ok(f) if f.is_finite() => Tok::Float(f),
                _ => return Err(err(format!("float `{slice}` is out of range"), None)),
            },
            Raw::Quoted | Raw::Str | Raw::BackQuoted => {
                let q = slice.chars().next().unwrap_or('\'');
                let body = &slice[1..slice.len() - 1];
                let text = unescape(body, q).map_err(|m| {
                    err(m, Some("see the escape sequences \\n \\t \\\\ \\' \\xHH\\"))
                })?;
                match raw {
                    Raw::Quoted => Tok::Name(Sym::intern(&text)),
                    Raw::Str => Tok::Str(text),
                    _ => Tok::BackQuoted(text),
                }
            }
            Raw::Graphic => {
                if let Some(pos) = slice.find("/*") {
                    // `/*` starts a comment even right after graphic characters.
                    if pos > 0 {
                        out.push((start, Tok::Name(Sym::intern(&slice[..pos])), start + pos));
                    }
                    let comment_start = span.start + pos;
                    match text[comment_start + 2..].find("*/") {
                        Some(e) => {
                            let resume = comment_start + 2 + e + 2;
                            lex = Raw::lexer(text);
                            lex.bump(resume);
                            continue;
                        }
                        None => {
                            return Err(LexError {
                                message: "unterminated block comment".into(),
                                hint: Some("close the comment with `*/`".into()),
                                span: offset + comment_start..offset + comment_start + 2,
                            })
                        }
                    }
                }
                let next = text[span.end..].chars().next();
                if slice == "." && next.is_none_or(|c| c.is_whitespace() || c == '%') {
                    Tok::End
                } else {
                    Tok::Name(Sym::intern(slice))
                }
            }
            Raw::Open => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(err(
                        format!("term nested more than {MAX_NESTING} levels deep"),
                        Some("split the term into smaller parts"),
                    ));
                }
                let glued = out
                    .last()
                    .is_some_and(|(_, t, e)| *e == start && matches!(t, Tok::Name(_)));
                let joined = !glued
                    && spaced.is_some()
                    && out.last().is_some_and(|(l, t, e)| {
                        joinable_name(t, &text[l - offset..*e - offset])
                            && text[*e - offset..span.start]
                                .bytes()
                                .all(|b| b.is_ascii_whitespace())
                    });
                if joined {
                    if let (Some(list), Some((l, _, _))) = (spaced.as_deref_mut(), out.last()) {
                        list.push(*l..end);
                    }
                }
                if glued || joined {
                    if let Some((_, t, _)) = out.last_mut() {
                        if let Tok::Name(s) = t {
                            *t = Tok::Functor(*s);
                        }
                    }
                }
                Tok::Open
            }
            Raw::LBracket | Raw::LBrace => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Err(err(
                        format!("term nested more than {MAX_NESTING} levels deep"),
                        Some("split the term into smaller parts"),
                    ));
                }
                if raw == Raw::LBracket {
                    Tok::LBracket
                } else {
                    Tok::LBrace
                }
            }
            Raw::Close | Raw::RBracket | Raw::RBrace => {
                depth = depth.saturating_sub(1);
                match raw {
                    Raw::Close => Tok::Close,
                    Raw::RBracket => Tok::RBracket,
                    _ => Tok::RBrace,
                }
            }
            Raw::Comma => Tok::Comma,
            Raw::Bar => Tok::Bar,
            Raw::Cut => Tok::Name(Sym::intern("!")),
            Raw::Semicolon => Tok::Name(Sym::intern(";")),
        };
        out.push((start, tok, end));
    }
    Ok(out)
}

/// A plain lower-case name that is no operator: standard Prolog has no reading of `name (`.
fn joinable_name(tok: &Tok, slice: &str) -> bool {
    matches!(tok, Tok::Name(_))
        && slice.starts_with(|c: char| c.is_ascii_lowercase())
        && !crate::term::ops::is_operator(slice)
}

/// Resolves escape sequences and doubled quotes in the body of a quoted item.
pub fn unescape(body: &str, quote: char) -> Result<String, String> {
    let mut out = String::with_capacity(body.len());
    let mut chars = body.chars().peekable();
    while let Some(c) = chars.next() {
        if c == quote {
            // A doubled quote stands for one quote character.
            chars.next();
            out.push(quote);
            continue;
        }
        if c != '\\' {
            out.push(c);
            continue;
        }
        let e = chars
            .next()
            .ok_or("a backslash at the end of quoted text")?;
        match e {
            'n' => out.push('\n'),
            't' => out.push('\t'),
            'r' => out.push('\r'),
            'a' => out.push('\x07'),
            'b' => out.push('\x08'),
            'f' => out.push('\x0C'),
            'v' => out.push('\x0B'),
            'e' => out.push('\x1B'),
            's' => out.push(' '),
            '0'..='7' | 'x' => {
                let radix = if e == 'x' { 16 } else { 8 };
                let mut digits = String::new();
                if e != 'x' {
                    digits.push(e);
                }
                loop {
                    match chars.next() {
                        Some('\\') => break,
                        Some(d) if d.is_digit(radix) => digits.push(d),
                        _ => {
                            return Err(
                                "a numeric escape must end with a backslash, as in \\x41\\".into()
                            )
                        }
                    }
                }
                let code = u32::from_str_radix(&digits, radix)
                    .map_err(|_| "invalid numeric escape".to_string())?;
                out.push(char::from_u32(code).ok_or("numeric escape is not a valid character")?);
            }
            '\n' => {}
            '\\' | '\'' | '"' | '`' => out.push(e),
            other => return Err(format!("unknown escape sequence `\\{other}`")),
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(text: &str) -> Vec<Tok> {
        let mut n = 0;
        tokenize(text, 0, &mut n)
            .unwrap()
            .into_iter()
            .map(|(_, t, _)| t)
            .collect()
    }

    #[test]
    fn end_tokens_and_dots() {
        assert_eq!(toks("a. b.").iter().filter(|t| **t == Tok::End).count(), 2);
        assert_eq!(
            toks("X =.. Y").iter().filter(|t| **t == Tok::End).count(),
            0
        );
        assert_eq!(toks("X is 3.14.").last(), Some(&Tok::End));
        assert_eq!(toks("a.%c").last(), Some(&Tok::End));
    }

    #[test]
    fn functional_notation_needs_no_space() {
        assert_eq!(toks("f(a)")[0], Tok::Functor(Sym::intern("f")));
        assert_eq!(toks("f (a)")[0], Tok::Name(Sym::intern("f")));
        assert_eq!(toks("-(1)")[0], Tok::Functor(Sym::intern("-")));
    }

    #[test]
    fn quotes_codes_and_comments() {
        assert_eq!(toks("'('"), vec![Tok::Name(Sym::intern("("))]);
        assert_eq!(toks("'it''s'"), vec![Tok::Name(Sym::intern("it's"))]);
        assert_eq!(
            toks("0'a 0'' 0'\\n"),
            vec![Tok::Int(97), Tok::Int(39), Tok::Int(10)]
        );
        assert_eq!(
            toks("a /* ) */ b % )\n"),
            vec![Tok::Name(Sym::intern("a")), Tok::Name(Sym::intern("b"))]
        );
        assert_eq!(
            toks("=/*x*/a"),
            vec![Tok::Name(Sym::intern("=")), Tok::Name(Sym::intern("a"))]
        );
        assert_eq!(toks("\"a\\\"b\""), vec![Tok::Str("a\"b".into())]);
    }

    #[test]
    fn anonymous_variables_are_numbered_apart() {
        assert_eq!(
            toks("_ _"),
            vec![Tok::Var(Sym::intern("_G1")), Tok::Var(Sym::intern("_G2"))]
        );
    }

    #[test]
    fn errors_are_values() {
        let mut n = 0;
        assert!(tokenize("'abc", 0, &mut n).is_err());
        assert!(tokenize("/* abc", 0, &mut n).is_err());
        // logos recurses per character of a token in debug builds: a roomy stack for this one.
        let long = std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn(|| tokenize(&"9".repeat(10_001), 0, &mut 0).is_err())
            .map(|h| h.join().unwrap_or(false));
        assert_eq!(long.ok(), Some(true));
        let big = tokenize("99999999999999999999", 0, &mut n).map(|t| t.len());
        assert_eq!(big.ok(), Some(1));
        assert!(tokenize(&"(".repeat(5000), 0, &mut n).is_err());
        assert!(tokenize("0'", 0, &mut n).is_err());
    }
}
