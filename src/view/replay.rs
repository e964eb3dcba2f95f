//! Reading a recorded trace for `goal view`: every line must be a JSON object and the first a
//! `goal-trace` header of the version this program writes; anything else is a plain error
//! naming the file and line. The checked file is then served from disk.

use super::feed::Feed;
use super::spill::{record_text, Spill};
use crate::mas::trace::{FORMAT, VERSION};
use serde_json::Value;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

/// The largest trace `goal view` reads (the page holds all of it in memory).
pub const MAX_TRACE_BYTES: u64 = 1 << 30;

/// The trace at `path`, checked, as a closed feed that reads its lines from the file when a
/// page asks for them (nothing of it is held in memory but a small index).
pub fn load(path: &Path) -> Result<Feed, String> {
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
    let mut spill = Spill::existing(path).map_err(|e| format!("cannot open {shown}: {e}"))?;
    let bytes = check(
        BufReader::new(file.take(MAX_TRACE_BYTES)),
        &shown.to_string(),
        |offset, _| spill.note(offset),
    )?;
    Ok(Feed::on_disk(spill, bytes))
}

/// Checks every line of a trace read from `input`, handing each record line to `line` with
/// its byte offset; the bytes of the record lines, each with a newline.
fn check(
    mut input: impl BufRead,
    name: &str,
    mut line: impl FnMut(u64, &str),
) -> Result<u64, String> {
    let (mut offset, mut bytes, mut records) = (0u64, 0u64, 0usize);
    let mut raw = Vec::new();
    for n in 1.. {
        raw.clear();
        let read = input
            .read_until(b'\n', &mut raw)
            .map_err(|e| format!("{name}:{n}: cannot read the line: {e}"))?;
        if read == 0 {
            break;
        }
        let at = offset;
        offset += read as u64;
        let text = std::str::from_utf8(&raw)
            .map_err(|e| format!("{name}:{n}: cannot read the line: not UTF-8 text ({e})"))?;
        let text = record_text(text);
        if text.trim().is_empty() {
            continue;
        }
        let v: Value = serde_json::from_str(text).map_err(|e| {
            format!("{name}:{n}: not a trace record (a JSON object per line expected): {e}")
        })?;
        if !v.is_object() || v.get("type").and_then(Value::as_str).is_none() {
            return Err(format!(
                "{name}:{n}: not a trace record: a JSON object with a \"type\" field expected"
            ));
        }
        if records == 0 {
            header(&v, name)?;
        }
        records += 1;
        bytes += text.len() as u64 + 1;
        line(at, text);
    }
    if records == 0 {
        return Err(format!(
            "{name} is empty: a trace starts with a header line (write one with goal run --trace FILE)"
        ));
    }
    Ok(bytes)
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
