//! Reading a recorded trace for `goal view`: every line must be a JSON object and the first a
//! `goal-trace` header of the version this program writes; anything else is a plain error
//! naming the file and line.

use crate::mas::trace::{FORMAT, VERSION};
use serde_json::Value;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// The largest trace `goal view` reads (the page holds all of it in memory too).
pub const MAX_TRACE_BYTES: u64 = 1 << 30;

/// The lines of the trace at `path`, checked.
pub fn load(path: &Path) -> Result<Vec<String>, String> {
    let shown = path.display();
    let file = std::fs::File::open(path).map_err(|e| format!("cannot open {shown}: {e}"))?;
    let size = file.metadata().map(|m| m.len()).unwrap_or(0);
    if size > MAX_TRACE_BYTES {
        return Err(format!(
            "{shown} is {} MiB, more than the {} MiB goal view reads; record a shorter run \
             (--max-ticks)",
            size >> 20,
            MAX_TRACE_BYTES >> 20
        ));
    }
    read(
        BufReader::new(file.take(MAX_TRACE_BYTES)),
        &shown.to_string(),
    )
}

/// The checked lines of a trace read from `input` (`name` is used in messages).
pub fn read(input: impl BufRead, name: &str) -> Result<Vec<String>, String> {
    let mut lines = Vec::new();
    for (i, line) in input.lines().enumerate() {
        let n = i + 1;
        let line = line.map_err(|e| format!("{name}:{n}: cannot read the line: {e}"))?;
        if line.trim().is_empty() {
            continue;
        }
        let v: Value = serde_json::from_str(&line).map_err(|e| {
            format!("{name}:{n}: not a trace record (a JSON object per line expected): {e}")
        })?;
        if !v.is_object() || v.get("type").and_then(Value::as_str).is_none() {
            return Err(format!(
                "{name}:{n}: not a trace record: a JSON object with a \"type\" field expected"
            ));
        }
        if lines.is_empty() {
            header(&v, name)?;
        }
        lines.push(line);
    }
    if lines.is_empty() {
        return Err(format!(
            "{name} is empty: a trace starts with a header line (write one with goal run --trace FILE)"
        ));
    }
    Ok(lines)
}

/// Checks the first record: a header of this program's format and version.
fn header(v: &Value, name: &str) -> Result<(), String> {
    let kind = v.get("type").and_then(Value::as_str);
    let format = v.get("format").and_then(Value::as_str);
    if kind != Some("header") || format != Some(FORMAT) {
        return Err(format!(
            "{name}:1: not a goal trace: the first line must be a \"{FORMAT}\" header (write one \
             with goal run --trace FILE)"
        ));
    }
    match v.get("version").and_then(Value::as_u64) {
        Some(x) if x == u64::from(VERSION) => Ok(()),
        Some(x) => Err(format!(
            "{name}:1: trace format version {x}, but this goal reads version {VERSION}; record \
             the run again with this goal (goal run --trace FILE)"
        )),
        None => Err(format!("{name}:1: the header has no version number")),
    }
}
