//! The table of diagnostic codes, one line each. Ranges: `E00xx`/`W00xx` lexing and parsing of
//! `.goal`/`.mod2g`/`.pl` files and file access, `E01xx`/`W01xx` the validator, `E02xx`/`W02xx`
//! `.mas2g` files, further ranges added by their owners.

/// `(code, meaning)` for every diagnostic code, sorted by code.
pub const CODES: &[(&str, &str)] = &[
    (
        "E0001",
        "Prolog syntax error in KR content (reported by the Prolog reader)",
    ),
    ("E0010", "unexpected character at GOAL level"),
    (
        "E0011",
        "unterminated quoted atom, string or back-quoted string",
    ),
    ("E0012", "unterminated block comment `/*` without `*/`"),
    ("E0013", "unclosed `(` or `{` around KR content"),
    (
        "E0014",
        "unexpected token: the grammar expected something else here",
    ),
    (
        "E0015",
        "unexpected end of file: a module, section or rule is not finished",
    ),
    ("E0016", "blocks nested too deeply"),
    (
        "E0017",
        "the file cannot be read (missing, a directory, no permission)",
    ),
    ("E0018", "the file is not valid UTF-8"),
    ("E0019", "the file is larger than the 10 MB limit"),
    (
        "E0020",
        "unknown module option value, program option or rule order",
    ),
    ("E0021", "`send`/`sendonce` without a receiver"),
    ("E0022", "`listall` needs a variable"),
    (
        "E0024",
        "unknown file extension (not .goal, .mod2g, .pl, .mas2g or .test2g)",
    ),
    ("E0030", "empty KR content or empty argument list"),
    ("E0031", "`#import` of the wrong kind of file at this place"),
    ("E0032", "a `.mod2g` file must hold exactly one module"),
    ("W0001", "duplicate section: only the first one is used"),
    (
        "W0002",
        "legacy send form (`bob.send(p)` or `send(bob, p)`)",
    ),
    ("W0003", "unknown module option (ignored)"),
    ("W0004", "duplicate module option: the first one is used"),
    ("W0006", "empty nested rule block"),
];

/// The meaning of a code, if it is known.
pub fn describe(code: &str) -> Option<&'static str> {
    CODES.iter().find(|(c, _)| *c == code).map(|(_, d)| *d)
}

#[cfg(test)]
mod tests {
    #[test]
    fn codes_are_sorted_and_unique() {
        let codes: Vec<&str> = super::CODES.iter().map(|(c, _)| *c).collect();
        let mut sorted = codes.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(codes, sorted);
    }
}
