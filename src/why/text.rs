//! A [`WhyReport`] as readable text: one block per module run in the cycle, each rule with its
//! location, text and outcome; the literals of a failed condition marked one by one.

use super::{Outcome, RuleWhy, WhyReport};
use std::fmt::Write;

/// The report as text for a terminal.
pub fn render(r: &WhyReport) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} at tick {} (its cycle {}, {}), ended in module {}",
        r.agent, r.ran_at, r.cycle, r.file, r.module
    );
    if let Some(n) = &r.note {
        let _ = writeln!(out, "note: {n}");
    }
    if let Some(s) = &r.stopped {
        let _ = writeln!(out, "the agent stopped in this cycle: {s}");
    }
    let mut section = None;
    for rule in &r.rules {
        let key = (
            rule.phase.as_str(),
            rule.depth,
            rule.module.as_str(),
            rule.block_of.as_deref(),
        );
        if section != Some(key) {
            section = Some(key);
            let what = match &rule.block_of {
                Some(owner) => format!("nested block of rule {owner}"),
                None => format!("module {}", rule.module),
            };
            let _ = writeln!(out, "\n{}{what} ({} phase)", indent(rule.depth), rule.phase);
        }
        render_rule(&mut out, rule);
    }
    out
}

fn indent(depth: usize) -> String {
    "  ".repeat(depth.saturating_sub(1).min(20))
}

fn render_rule(out: &mut String, r: &RuleWhy) {
    let pad = indent(r.depth);
    let what = match r.outcome {
        Outcome::Fired => "FIRED",
        Outcome::Failed => "failed",
        Outcome::PreconditionFailed => "ACTION NOT RUN",
        Outcome::NotEvaluated => "not evaluated",
        Outcome::Error => "ERROR",
    };
    let _ = writeln!(out, "{pad}  {}:{}  {}  {what}", r.file, r.line, r.rule);
    let _ = writeln!(out, "{pad}    {}", r.text);
    let with = |b: &str| {
        if b.is_empty() {
            String::new()
        } else {
            format!(" with {b}")
        }
    };
    match r.outcome {
        Outcome::Fired => {
            if r.fired_with.len() > 1 {
                let _ = writeln!(
                    out,
                    "{pad}    fired {} times: {}",
                    r.fired_with.len(),
                    r.fired_with.join(" | ")
                );
            } else {
                let _ = writeln!(out, "{pad}    fired{}", with(&r.bindings));
            }
        }
        Outcome::Failed => {
            for l in &r.literals {
                let mark = match l.status {
                    "held" => "   held         ",
                    "failed" => "-> FAILED       ",
                    _ => "   not reached  ",
                };
                let _ = writeln!(out, "{pad}    {mark}{}", l.text);
            }
            if let Some(c) = &r.failed_conjunct {
                let b = r.conjunct_bindings.as_deref().unwrap_or("");
                let _ = writeln!(out, "{pad}       its first failing part: {c}{}", with(b));
            }
            if r.answers > 1 {
                let _ = writeln!(
                    out,
                    "{pad}    (tried for {} bindings of the literals before it, e.g.{})",
                    r.answers,
                    with(&r.bindings)
                );
            } else if !r.bindings.is_empty() {
                let _ = writeln!(out, "{pad}    (tried{})", with(&r.bindings));
            }
        }
        Outcome::PreconditionFailed => {
            let action = r.failed_action.as_deref().unwrap_or("an action");
            let _ = writeln!(
                out,
                "{pad}    the condition held{}, but {action} did not run: {}",
                with(&r.bindings),
                r.reason.as_deref().unwrap_or("")
            );
            if let Some(p) = &r.failed_precondition {
                let _ = writeln!(out, "{pad}    -> failed precondition literal: {p}");
            }
        }
        Outcome::NotEvaluated | Outcome::Error => {}
    }
    if r.outcome != Outcome::PreconditionFailed {
        if let Some(reason) = &r.reason {
            let _ = writeln!(out, "{pad}    ({reason})");
        }
    }
}
