//! A rule's source text on one line, as `goal why` shows it (kept in the compiled rule).

use crate::syntax::ast;

/// The source text of a rule on one line; a nested block's rules are elided (`{ ... }`).
pub(crate) fn rule_text(source: &str, r: &ast::Rule) -> String {
    let end = match &r.body {
        ast::RuleBody::Block(rules) => rules.first().map(|f| f.span.start),
        ast::RuleBody::Combo(_) => None,
    };
    match end.and_then(|e| source.get(r.span.start..e)) {
        Some(head) => format!("{} ... }}", one_line(head)),
        None => one_line(source.get(r.span.clone()).unwrap_or("")),
    }
}

/// `text` on one line: comments (`% ...`, `/* ... */`) left out, each run of white space one
/// space; quoted text is kept as written.
pub(crate) fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    let mut quote: Option<char> = None;
    let mut space = false;
    while let Some(c) = chars.next() {
        if let Some(q) = quote {
            out.push(c);
            if c == '\\' {
                if let Some(n) = chars.next() {
                    out.push(n);
                }
            } else if c == q {
                quote = None;
            }
            continue;
        }
        match c {
            '%' => {
                for n in chars.by_ref() {
                    if n == '\n' {
                        break;
                    }
                }
                space = true;
                continue;
            }
            '/' if chars.peek() == Some(&'*') => {
                chars.next();
                let mut prev = ' ';
                for n in chars.by_ref() {
                    if prev == '*' && n == '/' {
                        break;
                    }
                    prev = n;
                }
                space = true;
                continue;
            }
            c if c.is_whitespace() => {
                space = true;
                continue;
            }
            _ => {}
        }
        if space && !out.is_empty() {
            out.push(' ');
        }
        space = false;
        if matches!(c, '\'' | '"' | '`') {
            quote = Some(c);
        }
        out.push(c);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::one_line;

    #[test]
    fn one_line_drops_comments_and_keeps_quotes() {
        let text = "if bel(a), % why\n   bel('x  % y') /* c */ then\n\tinsert(\"b  c\").";
        assert_eq!(
            one_line(text),
            "if bel(a), bel('x  % y') then insert(\"b  c\")."
        );
    }
}
