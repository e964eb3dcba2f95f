//! The human-readable summary table printed at the end of a run (to standard error).

use super::stats::RunSummary;
use std::fmt::Write;

/// The summary: result, ticks, deliveries, messages, then one row per agent.
pub fn table(s: &RunSummary) -> String {
    let mut o = String::new();
    let result = if s.completed {
        "completed".to_string()
    } else if s.map.is_none() {
        // No environment: there is no task to complete, only a reason to stop.
        s.end.describe().to_string()
    } else {
        format!("not completed ({})", s.end.describe())
    };
    let _ = writeln!(o, "result      {result}");
    if let Some(m) = &s.map {
        let _ = writeln!(o, "map         {m}  (seed {})", s.seed);
    }
    let _ = writeln!(o, "ticks       {}", s.ticks);
    if s.map.is_some() {
        let _ = writeln!(
            o,
            "deliveries  {} right, {} wrong",
            s.deliveries.right, s.deliveries.wrong
        );
    }
    let _ = writeln!(o, "messages    {}", s.messages);
    let w = s
        .agents
        .keys()
        .map(|n| n.chars().count())
        .max()
        .unwrap_or(5)
        .max(5);
    let _ = writeln!(
        o,
        "{:<w$}  {:>8}  {:>8}  {:>10}  status",
        "agent", "cycles", "actions", "idle ticks"
    );
    for (name, a) in &s.agents {
        let status = match (&a.error, a.stopped) {
            (Some(e), _) => format!("error: {e}"),
            (None, true) => "stopped".to_string(),
            (None, false) => "running".to_string(),
        };
        let _ = writeln!(
            o,
            "{name:<w$}  {:>8}  {:>8}  {:>10}  {status}",
            a.cycles, a.actions, a.idle_ticks
        );
    }
    for (name, a) in s.agents.iter().filter(|(_, a)| a.messages_dropped > 0) {
        let _ = writeln!(
            o,
            "{name}: {} messages dropped (mailbox full, --max-mailbox)",
            a.messages_dropped
        );
    }
    o
}
