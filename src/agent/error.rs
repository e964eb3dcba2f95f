//! Runtime errors: they stop the agent with a message naming file, line, rule and binding.

use std::fmt;

/// A fatal runtime error of one agent.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RuntimeError {
    /// Program file name.
    pub file: String,
    /// 1-based line of the rule or action (0 when unknown).
    pub line: usize,
    /// The rule (as `module:line`) in which it happened, if any.
    pub rule: Option<String>,
    /// What went wrong.
    pub message: String,
    /// The offending binding (printed substitution), if any.
    pub binding: Option<String>,
}

impl fmt::Display for RuntimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.message)?;
        if let Some(r) = &self.rule {
            write!(f, " (in rule {r})")?;
        }
        if let Some(b) = &self.binding {
            if !b.is_empty() {
                write!(f, " with {b}")?;
            }
        }
        Ok(())
    }
}

impl std::error::Error for RuntimeError {}

/// Where an error is raised: the message plus (optionally) the offending binding; the
/// interpreter adds file, line and rule.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fault {
    /// What went wrong.
    pub message: String,
    /// Printed substitution at the time.
    pub binding: Option<String>,
}

impl Fault {
    /// A fault with a message only.
    pub fn new(message: impl Into<String>) -> Fault {
        Fault {
            message: message.into(),
            binding: None,
        }
    }
}
