//! Checking command-line values (a clear message naming the accepted range; clap adds the
//! flag) and making agent output safe to show on a terminal.

/// Largest number of seconds accepted for a duration (about 31 years).
const MAX_SECONDS: f64 = 1e9;

/// An integer of at least 1.
pub fn positive(s: &str) -> Result<u64, String> {
    match s.parse::<u64>() {
        Ok(0) => Err("must be at least 1".into()),
        Ok(n) => Ok(n),
        Err(_) => Err("must be a whole number of at least 1".into()),
    }
}

/// A number of worker threads: 1 to 1024.
pub fn workers(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if (1..=1024).contains(&n) => Ok(n),
        _ => Err("must be a whole number from 1 to 1024".into()),
    }
}

/// A number of HumanBots: 0 to 16 (the map's spawn points may allow fewer).
pub fn humans(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n <= 16 => Ok(n),
        _ => Err("must be a whole number from 0 to 16".into()),
    }
}

fn number_in(s: &str, lo: f64, hi: f64, what: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= lo && x <= hi => Ok(x),
        _ => Err(format!("must be {what} from {lo} to {hi}")),
    }
}

/// A duration in seconds: more than 0 (at least a millisecond), at most 1e9.
pub fn seconds(s: &str) -> Result<f64, String> {
    number_in(s, 0.001, MAX_SECONDS, "a number of seconds")
}

/// A probability: 0 to 1.
pub fn probability(s: &str) -> Result<f64, String> {
    number_in(s, 0.0, 1.0, "a probability")
}

/// A rate in ticks per second: 0.001 to 1000000.
pub fn rate(s: &str) -> Result<f64, String> {
    number_in(s, 0.001, 1e6, "a number of ticks per second")
}

/// `line` with control characters written as escapes (`\n`, `\t`, `\e`, `\x00`...), so an
/// agent cannot clear the screen, move the cursor or fake another agent's line.
pub fn escape_controls(line: &str) -> std::borrow::Cow<'_, str> {
    if !line.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(line);
    }
    let mut out = String::with_capacity(line.len() + 8);
    for c in line.chars() {
        match c {
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\x1b' => out.push_str("\\e"),
            c if c.is_control() => out.push_str(&format!("\\x{:02x}", u32::from(c))),
            c => out.push(c),
        }
    }
    std::borrow::Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges() {
        assert!(positive("0").is_err());
        assert_eq!(positive("7"), Ok(7));
        assert!(workers("0").is_err() && workers("1025").is_err());
        for bad in ["0", "nan", "inf", "1e300", "1e-20", "-1"] {
            assert!(seconds(bad).is_err(), "{bad}");
            assert!(rate(bad).is_err(), "{bad}");
        }
        assert_eq!(seconds("2.5"), Ok(2.5));
    }

    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(escape_controls("plain ü"), "plain ü");
        assert_eq!(
            escape_controls("a\x1b[2Jb\0c\nBot2: x"),
            "a\\e[2Jb\\x00c\\nBot2: x"
        );
        // Other control characters (C1 range included) become \x escapes.
        assert_eq!(escape_controls("\u{85}\u{7f}"), "\\x85\\x7f");
    }
}

/// A KR engine name for `--kr`: `native` or `scryer` (refused when the build lacks it).
pub fn kr_engine(s: &str) -> Result<goal::kr::KrKind, String> {
    match goal::kr::KrKind::parse(s)? {
        Some(k) if k.available() => Ok(k),
        Some(k) => Err(format!(
            "this goal was built without the {} engine (cargo feature `{}`)",
            k.name(),
            k.name()
        )),
        None => Ok(goal::kr::KrKind::Native),
    }
}
