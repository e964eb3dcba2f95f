//! The Prolog (`.pl`) files of modular projects: `:- dynamic` directives, which GOAL's fixed
//! operator table cannot read, are blanked out or dropped; other directives are warned about.

use crate::diag::{Diagnostic, Span};
use crate::syntax::prolog::Located;
use crate::term::Term;

/// Drops `:- dynamic` directives (they only declare belief predicates) and warns about others.
pub fn kr_clauses(clauses: Vec<Located>, file: &str, diags: &mut Vec<Diagnostic>) -> Vec<Located> {
    let mut out = Vec::new();
    for c in clauses {
        match c.term.functor() {
            Some((f, 1)) if f.name() == ":-" => {
                let dynamic =
                    matches!(c.term.args()[0].functor(), Some((d, 1)) if d.name() == "dynamic");
                if !dynamic {
                    diags.push(
                        Diagnostic::warning(
                            "W0605",
                            "directive ignored: only `:- dynamic ...` is understood",
                            file,
                            c.spans.span.clone(),
                        )
                        .with_hint("remove the directive"),
                    );
                }
            }
            Some((f, 2))
                if f.name() == "/"
                    && matches!(c.term.args()[0], Term::Atom(_))
                    && matches!(c.term.args()[1], Term::Int(_)) =>
            {
                // `:- dynamic a/1.` followed by `b/2.`: a dot where a comma was meant. The
                // line is a fact of '/'/2 (as in SWI-Prolog); say what it probably meant.
                diags.push(
                    Diagnostic::warning(
                        "W0609",
                        format!("`{}` looks like a declaration cut off by `.`", c.term),
                        file,
                        c.spans.span.clone(),
                    )
                    .with_hint("end the line before with `,` to declare it, or remove it"),
                );
                out.push(c)
            }
            _ => out.push(c),
        }
    }
    out
}

/// `:- dynamic p/1, q/2.` directives blanked out (same length, so spans stay right): GOAL's fixed
/// operator table has no `dynamic` operator, and the directives only declare belief predicates.
pub fn blank_dynamic(text: &str) -> String {
    let mut out = text.as_bytes().to_vec();
    for s in dynamic_spans(text) {
        for x in &mut out[s] {
            if *x != b'\n' {
                *x = b' ';
            }
        }
    }
    // Only ASCII bytes outside quotes were replaced by spaces: still UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| text.to_string())
}

/// The predicates `:- dynamic` directives of `text` declare, as name and arity, and those of
/// `p/1.` lines (a declaration cut off by `.`, which GOAL counts as declared too).
pub fn declared(text: &str, clauses: &[Located]) -> Vec<(String, usize)> {
    let mut out = Vec::new();
    for s in dynamic_spans(text) {
        let body = text[s].trim_start_matches(|c: char| c == ':' || c == '-' || c.is_whitespace());
        let body = body.strip_prefix("dynamic").unwrap_or(body);
        for part in body.split(',') {
            let p = part.trim_matches(|c: char| "()[]. \t\r\n".contains(c));
            if let Some((n, a)) = p.rsplit_once('/') {
                if let Ok(a) = a.trim().parse::<usize>() {
                    out.push((n.trim().trim_matches('\'').to_string(), a));
                }
            }
        }
    }
    for c in clauses {
        if let (Some((f, 2)), [Term::Atom(n), Term::Int(a)]) = (c.term.functor(), c.term.args()) {
            if f.name() == "/" && *a >= 0 {
                out.push((n.name().to_string(), *a as usize));
            }
        }
    }
    out
}

/// The byte spans of the `:- dynamic ... .` directives of `text`.
fn dynamic_spans(text: &str) -> Vec<Span> {
    let b = text.as_bytes();
    let mut walk = crate::syntax::lexer::kr::Significant::new(text, 0, text.len());
    let mut blanks: Vec<Span> = Vec::new();
    let (mut clause_start, mut depth, mut directive) = (true, 0i64, None);
    while let Some(Ok((p, c))) = walk.next_byte() {
        if clause_start && !c.is_ascii_whitespace() {
            clause_start = false;
            let rest = text[p..].strip_prefix(":-").map(str::trim_start);
            if rest.is_some_and(|r| {
                r.strip_prefix("dynamic")
                    .is_some_and(|x| x.starts_with(|ch: char| ch.is_whitespace()))
            }) {
                directive = Some(p);
            }
        }
        match c {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            b'.' if depth <= 0
                && b.get(p + 1)
                    .is_none_or(|n| n.is_ascii_whitespace() || *n == b'%') =>
            {
                if let Some(s) = directive.take() {
                    blanks.push(s..p + 1);
                }
                clause_start = true;
                depth = 0;
            }
            _ => {}
        }
    }
    blanks
}
