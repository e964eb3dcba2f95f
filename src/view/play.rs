//! The player endpoints of a live run (`/api/play...`): the robots and one's own requests,
//! taking and leaving a HumanBot, a request for it (queued for the next tick boundary), and
//! the seed's fixed message list the page offers. Bodies are small JSON objects; anything else
//! is a plain 4xx answer and the run goes on.

use super::players::{Players, Refusal};
use super::server::Site;
use serde_json::{json, Value};
use std::io::Read;
use tiny_http::{Method, Request};

/// The largest request body read (a body is one short JSON object).
const MAX_BODY: u64 = 8 * 1024;

/// A JSON answer: status and body.
pub type Answer = (u16, Value);

fn refusal(r: Refusal) -> Answer {
    (r.status, json!({ "error": r.message }))
}

fn bad(message: &str) -> Answer {
    (400, json!({ "error": message }))
}

/// The body of `request` as a JSON object.
fn body(request: &mut Request) -> Result<serde_json::Map<String, Value>, Answer> {
    let mut text = String::new();
    let read = request
        .as_reader()
        .take(MAX_BODY + 1)
        .read_to_string(&mut text);
    if read.is_err() {
        return Err(bad("the body is not UTF-8 text: send a JSON object"));
    }
    if text.len() as u64 > MAX_BODY {
        return Err(bad(&format!(
            "the body is longer than {MAX_BODY} bytes: send one small JSON object"
        )));
    }
    match serde_json::from_str::<Value>(&text) {
        Ok(Value::Object(o)) => Ok(o),
        Ok(_) => Err(bad(
            "the body must be a JSON object, e.g. {\"token\": \"...\", \"request\": \"putDown\"}",
        )),
        Err(e) => Err(bad(&format!("the body is not JSON: {e}"))),
    }
}

fn text<'b>(o: &'b serde_json::Map<String, Value>, key: &str) -> Result<&'b str, Answer> {
    o.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| bad(&format!("the body has no text field \"{key}\"")))
}

/// Answers a request to `path` (under `/api/play`); `token` is the query's.
pub fn handle(request: &mut Request, site: &Site, path: &str, token: Option<&str>) -> Answer {
    let get = matches!(request.method(), Method::Get | Method::Head);
    if (get, path) == (true, "/api/play/messages") {
        return (200, messages());
    }
    let Some(control) = &site.control else {
        return (
            409,
            json!({"error": "this is a replay: nobody can play it (watch it, or start a live run with goal run --view)"}),
        );
    };
    let players = control.players();
    match (get, path) {
        (true, "/api/play") => (200, players.state(token)),
        (false, "/api/play/take") => take(request, players),
        (false, "/api/play/leave") => {
            match body(request).and_then(|o| Ok(text(&o, "token")?.to_string())) {
                Ok(t) => {
                    players.leave(&t);
                    (200, players.state(None))
                }
                Err(a) => a,
            }
        }
        (false, "/api/play/request") => {
            if control.ended() {
                return (
                    409,
                    json!({"error": "the run is over: requests are no longer taken"}),
                );
            }
            submit(request, players)
        }
        (_, p) => {
            let known = [
                "/api/play",
                "/api/play/take",
                "/api/play/leave",
                "/api/play/request",
            ];
            let status = if known.contains(&p) { 405 } else { 404 };
            (
                status,
                json!({"error": format!("no player endpoint {} {p}: use GET /api/play, POST /api/play/take, /api/play/leave or /api/play/request", request.method())}),
            )
        }
    }
}

fn take(request: &mut Request, players: &Players) -> Answer {
    let o = match body(request) {
        Ok(o) => o,
        Err(a) => return a,
    };
    let robot = match text(&o, "robot") {
        Ok(r) => r,
        Err(a) => return a,
    };
    let token = o.get("token").and_then(Value::as_str);
    match players.take(robot, token) {
        Ok(t) => (200, json!({"token": t, "robot": robot})),
        Err(r) => refusal(r),
    }
}

fn submit(request: &mut Request, players: &Players) -> Answer {
    let o = match body(request) {
        Ok(o) => o,
        Err(a) => return a,
    };
    let (token, req) = match (text(&o, "token"), text(&o, "request")) {
        (Ok(t), Ok(r)) => (t, r),
        (Err(a), _) | (_, Err(a)) => return a,
    };
    match players.request(token, req) {
        Ok(id) => (202, json!({"id": id, "request": req})),
        Err(r) => refusal(r),
    }
}

/// The seed's fixed message list (logical form with slots, speech act, English) and the
/// colours, from which the page builds its message chooser.
fn messages() -> Value {
    use crate::bw4t::color::Color;
    // The seed's nine colours (DarkGray is what colour-blind robots see, not a block colour).
    let colors: Vec<&str> = Color::ALL
        .iter()
        .filter(|c| **c != Color::DarkGray)
        .map(|c| c.name())
        .collect();
    json!({
        "messages": crate::bw4t::messages::MESSAGES,
        "colors": colors,
    })
}
