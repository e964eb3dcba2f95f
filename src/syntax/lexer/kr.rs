//! Scanning raw KR (Prolog) text without tokenising it: find the bracket that closes a KR span,
//! skipping quoted atoms, strings, back-quoted strings, `0'c` character codes and comments, so that
//! `bel(X = '(')` works (GOAL's own lexer broke on it).

/// Why a KR span could not be scanned.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ScanError {
    /// A quote opened at `start` is never closed (`quote` is the quote character).
    UnterminatedQuote { start: usize, quote: char },
    /// A `/*` at `start` has no `*/`.
    UnterminatedComment { start: usize },
    /// The opening bracket at `start` has no matching closing bracket.
    Unclosed { start: usize },
}

impl ScanError {
    /// The diagnostic a lexer gives for this error in `src` (a file named `file`).
    pub fn diagnostic(self, src: &str, file: &str) -> crate::diag::Diagnostic {
        use crate::diag::Diagnostic;
        match self {
            ScanError::UnterminatedQuote { start, quote } => Diagnostic::error(
                "E0011",
                format!("unterminated quoted item: the {quote} here is never closed"),
                file,
                start..start + 1,
            )
            .with_hint(format!("add the closing {quote}")),
            ScanError::UnterminatedComment { start } => Diagnostic::error(
                "E0012",
                "unterminated block comment: `/*` without `*/`",
                file,
                start..start + 2,
            )
            .with_hint("close the comment with `*/`"),
            ScanError::Unclosed { start } => {
                let c = &src[start..start + 1];
                let close = if c == "(" { ")" } else { "}" };
                Diagnostic::error(
                    "E0013",
                    format!("unclosed `{c}`: no matching `{close}` before the end of the file"),
                    file,
                    start..start + 1,
                )
                .with_hint(format!("add the missing `{close}`"))
            }
        }
    }
}

/// The position after the whitespace and comments from `pos` (up to `end`) of `src`.
pub fn skip_trivia(src: &str, mut pos: usize, end: usize) -> Result<usize, ScanError> {
    let b = &src.as_bytes()[..end];
    loop {
        while pos < end && b[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if pos < end && b[pos] == b'%' {
            while pos < end && b[pos] != b'\n' {
                pos += 1;
            }
        } else if src[pos..end].starts_with("/*") {
            match src[pos + 2..end].find("*/") {
                Some(i) => pos += 2 + i + 2,
                None => return Err(ScanError::UnterminatedComment { start: pos }),
            }
        } else {
            return Ok(pos);
        }
    }
}

/// Walks KR text byte by byte, yielding only the bytes outside quotes and comments.
pub struct Significant<'a> {
    src: &'a [u8],
    pos: usize,
    end: usize,
}

impl<'a> Significant<'a> {
    /// Walks `src[start..end]`.
    pub fn new(src: &'a str, start: usize, end: usize) -> Significant<'a> {
        Significant {
            src: src.as_bytes(),
            pos: start,
            end: end.min(src.len()),
        }
    }

    fn at(&self, i: usize) -> Option<u8> {
        if i < self.end {
            Some(self.src[i])
        } else {
            None
        }
    }

    /// Skips a quoted item starting at `self.pos` (the opening quote `q`).
    fn skip_quoted(&mut self, q: u8) -> Result<(), ScanError> {
        let start = self.pos;
        let mut i = self.pos + 1;
        loop {
            match self.at(i) {
                None => {
                    return Err(ScanError::UnterminatedQuote {
                        start,
                        quote: q as char,
                    })
                }
                Some(b'\\') => i += 2,
                Some(c) if c == q => {
                    if self.at(i + 1) == Some(q) {
                        i += 2; // doubled quote inside the quoted item
                    } else {
                        self.pos = i + 1;
                        return Ok(());
                    }
                }
                Some(_) => i += 1,
            }
        }
    }

    /// The next significant byte and its position, or an error for an unterminated quote/comment.
    pub fn next_byte(&mut self) -> Option<Result<(usize, u8), ScanError>> {
        loop {
            let c = self.at(self.pos)?;
            match c {
                b'\'' | b'"' | b'`' => {
                    if let Err(e) = self.skip_quoted(c) {
                        self.pos = self.end;
                        return Some(Err(e));
                    }
                }
                b'%' => {
                    while let Some(c) = self.at(self.pos) {
                        if c == b'\n' {
                            break;
                        }
                        self.pos += 1;
                    }
                }
                b'/' if self.at(self.pos + 1) == Some(b'*') => {
                    let start = self.pos;
                    let mut i = self.pos + 2;
                    loop {
                        match self.at(i) {
                            None => {
                                self.pos = self.end;
                                return Some(Err(ScanError::UnterminatedComment { start }));
                            }
                            Some(b'*') if self.at(i + 1) == Some(b'/') => {
                                self.pos = i + 2;
                                break;
                            }
                            Some(_) => i += 1,
                        }
                    }
                }
                b'0' if self.at(self.pos + 1) == Some(b'\'') && !self.prev_is_alnum() => {
                    // 0'c character code: 0'a, 0'\n, 0''' (quote) or 0'' (also a quote in SWI)
                    let start = self.pos;
                    let mut i = self.pos + 2;
                    match self.at(i) {
                        Some(b'\\') => i += 2,
                        Some(b'\'') if self.at(i + 1) == Some(b'\'') => i += 2,
                        Some(_) => {
                            i += 1;
                            while self.at(i).is_some_and(|b| (b & 0xC0) == 0x80) {
                                i += 1;
                            }
                        }
                        None => {}
                    }
                    self.pos = i.min(self.end);
                    return Some(Ok((start, b'0')));
                }
                _ => {
                    let p = self.pos;
                    self.pos += 1;
                    return Some(Ok((p, c)));
                }
            }
        }
    }

    fn prev_is_alnum(&self) -> bool {
        self.pos > 0 && {
            let b = self.src[self.pos - 1];
            b.is_ascii_alphanumeric() || b == b'_'
        }
    }
}

/// Given the position of an opening `open` bracket in `src`, the position of the matching
/// `close` bracket (only brackets of that kind are counted, as in GOAL).
pub fn matching_close(src: &str, open_pos: usize, open: u8, close: u8) -> Result<usize, ScanError> {
    let mut walk = Significant::new(src, open_pos, src.len());
    let mut depth = 0usize;
    while let Some(item) = walk.next_byte() {
        let (pos, c) = item?;
        if c == open {
            depth += 1;
        } else if c == close {
            depth -= 1;
            if depth == 0 {
                return Ok(pos);
            }
        }
    }
    Err(ScanError::Unclosed { start: open_pos })
}

/// Positions of the commas at bracket depth 0 in `src[start..end]` (outside quotes and comments).
pub fn top_level_commas(src: &str, start: usize, end: usize) -> Vec<usize> {
    let mut walk = Significant::new(src, start, end);
    let mut depth = 0i64;
    let mut out = Vec::new();
    while let Some(Ok((pos, c))) = walk.next_byte() {
        match c {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' | b'}' => depth -= 1,
            b',' if depth == 0 => out.push(pos),
            _ => {}
        }
    }
    out
}

/// `#import "file".` lines inside KR text `src[start..end]` (the legacy form inside `knowledge`):
/// for each, the span of the whole directive and the span of the path (inside the quotes).
pub fn legacy_imports(src: &str, start: usize, end: usize) -> Vec<(usize, usize, usize, usize)> {
    let bytes = src.as_bytes();
    let mut walk = Significant::new(src, start, end);
    let mut out = Vec::new();
    while let Some(Ok((pos, c))) = walk.next_byte() {
        if c != b'#' || !src[pos..end].starts_with("#import") {
            continue;
        }
        let mut i = pos + "#import".len();
        while i < end && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if i >= end || (bytes[i] != b'"' && bytes[i] != b'\'') {
            continue;
        }
        let q = bytes[i];
        let Some(rel) = src[i + 1..end].find(q as char) else {
            continue;
        };
        let path_end = i + 1 + rel;
        let mut j = path_end + 1;
        while j < end && bytes[j].is_ascii_whitespace() {
            j += 1;
        }
        if j < end && bytes[j] == b'.' {
            out.push((pos, j + 1, i + 1, path_end));
            walk = Significant::new(src, j + 1, end);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(s: &str) -> Result<usize, ScanError> {
        let open = s.as_bytes()[0];
        let close = if open == b'(' { b')' } else { b'}' };
        matching_close(s, 0, open, close)
    }

    #[test]
    fn quotes_and_comments_do_not_count() {
        assert_eq!(close("(X = '(')"), Ok(8));
        assert_eq!(close("{ a(\"}\"). }"), Ok(10));
        assert_eq!(close("(0')) x"), Ok(4));
        assert_eq!(close("(a % ) \n )"), Ok(9));
        assert_eq!(close("(a /* ) */ )"), Ok(11));
        assert_eq!(close("(`)`)"), Ok(4));
        assert_eq!(close("('it''s')"), Ok(8));
        assert_eq!(
            close("(a0')"),
            Err(ScanError::UnterminatedQuote {
                start: 3,
                quote: '\''
            })
        );
    }

    #[test]
    fn unterminated_things_are_errors() {
        assert_eq!(close("(a"), Err(ScanError::Unclosed { start: 0 }));
        assert_eq!(
            close("(a /* x"),
            Err(ScanError::UnterminatedComment { start: 3 })
        );
        assert_eq!(
            close("(\"abc"),
            Err(ScanError::UnterminatedQuote {
                start: 1,
                quote: '"'
            })
        );
    }

    #[test]
    fn commas_and_imports() {
        let s = "bob, f(a,b), 'x,y'";
        assert_eq!(top_level_commas(s, 0, s.len()), vec![3, 11]);
        let k = "a. #import \"x.pl\". b.";
        assert_eq!(legacy_imports(k, 0, k.len()), vec![(3, 18, 12, 16)]);
    }
}
