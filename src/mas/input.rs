//! People's requests in a run: what a person asked for an environment entity (a click in the
//! browser view), taken into the run between two ticks through `Environment::input`, written
//! to the trace as an `input` record, and applied again at the same round by a rerun.

use crate::syntax::prolog::Reader;
use crate::term::{Style, Term};
use serde_json::Value;
use std::sync::{Arc, Mutex, MutexGuard};

/// The longest request text taken (a request is one short term; longer text is refused).
pub const MAX_REQUEST_TEXT: usize = 2048;

/// A person's request for an environment entity.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    /// The entity the request is for (e.g. a HumanBot, `Human1`).
    pub entity: String,
    /// The request as a term, e.g. `goTo('RoomA1')`.
    pub request: Term,
}

impl Input {
    /// The request as the trace records it (quoted, so it reads back as the same term).
    pub fn request_text(&self) -> String {
        self.request.to_text(Style::WRITEQ)
    }
}

/// Reads a request's text (as the page sends it and the trace records it) as a term.
pub fn parse_request(text: &str) -> Result<Term, String> {
    let text = text.trim();
    if text.is_empty() {
        return Err("the request is empty: send one term, e.g. goTo('RoomA1')".into());
    }
    if text.len() > MAX_REQUEST_TEXT {
        return Err(format!(
            "the request is {} bytes long; a request is one short term (at most {MAX_REQUEST_TEXT} bytes)",
            text.len()
        ));
    }
    // Variables are allowed: the seed's questions leave the asked thing open (`int(at(_, R))`).
    Reader::new("request")
        .term(text, 0)
        .map(|l| l.term)
        .map_err(|d| format!("the request `{text}` is not a term: {}", d.message))
}

/// The requests taken in a run, each with the round it was taken in: a live run appends to it
/// while reruns (`goal why`) read it, so it is shared; a trace's `input` records fill one too.
#[derive(Clone, Debug, Default)]
pub struct InputLog(Arc<Mutex<Vec<(u64, Input)>>>);

impl InputLog {
    /// An empty log.
    pub fn new() -> InputLog {
        InputLog::default()
    }

    // Every change is one push: a poisoned lock is still consistent.
    fn lock(&self) -> MutexGuard<'_, Vec<(u64, Input)>> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Records `input` as taken in round `round`.
    pub fn push(&self, round: u64, input: Input) {
        self.lock().push((round, input));
    }

    /// The requests taken in round `round`, in the order they were taken.
    pub fn at(&self, round: u64) -> Vec<Input> {
        let log = self.lock();
        // Rounds only grow along the log.
        let from = log.partition_point(|(r, _)| *r < round);
        log[from..]
            .iter()
            .take_while(|(r, _)| *r == round)
            .map(|(_, i)| i.clone())
            .collect()
    }

    /// How many requests the log holds.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// True when no request was taken.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Adds the request of a trace record, if `v` is an `input` record; `Err` when it is one
    /// but cannot be read back.
    pub fn add_record(&self, v: &Value) -> Result<(), String> {
        if v["type"] != "input" {
            return Ok(());
        }
        let (Some(round), Some(entity), Some(text)) = (
            v["round"].as_u64(),
            v["entity"].as_str(),
            v["request"].as_str(),
        ) else {
            return Err("an input record without round, entity or request".into());
        };
        let request = parse_request(text)?;
        self.push(
            round,
            Input {
                entity: entity.to_string(),
                request,
            },
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_read_back_as_the_trace_writes_them() {
        let t = parse_request("goTo('RoomA1')").unwrap();
        let i = Input {
            entity: "Human1".into(),
            request: t.clone(),
        };
        assert_eq!(i.request_text(), "goTo('RoomA1')");
        assert_eq!(parse_request(&i.request_text()).unwrap(), t);
        let ask = parse_request("sendMessage(all, int(at(_, 'RoomA1')))").unwrap();
        assert!(!ask.is_ground(), "a question leaves its subject open");
        assert!(parse_request("goTo(").unwrap_err().contains("not a term"));
        assert!(parse_request("  ").unwrap_err().contains("empty"));
        let long = format!("goTo('{}')", "x".repeat(MAX_REQUEST_TEXT));
        assert!(parse_request(&long).unwrap_err().contains("bytes"));
    }

    #[test]
    fn the_log_gives_each_rounds_requests_in_order() {
        let log = InputLog::new();
        let req = |s: &str| Input {
            entity: "Human1".into(),
            request: parse_request(s).unwrap(),
        };
        log.push(3, req("goTo('RoomA1')"));
        log.push(3, req("putDown"));
        log.push(7, req("pickUp(4)"));
        assert_eq!(log.at(3), vec![req("goTo('RoomA1')"), req("putDown")]);
        assert_eq!(log.at(7), vec![req("pickUp(4)")]);
        assert!(log.at(5).is_empty());
        let rec = serde_json::json!({"type": "input", "round": 9, "tick": 9,
            "entity": "Human2", "request": "goToBlock(3)", "result": "ok"});
        log.add_record(&rec).unwrap();
        assert_eq!(log.at(9)[0].entity, "Human2");
        assert!(log
            .add_record(&serde_json::json!({"type": "input"}))
            .is_err());
        log.add_record(&serde_json::json!({"type": "cycle"}))
            .unwrap();
        assert_eq!(log.len(), 4);
    }
}
