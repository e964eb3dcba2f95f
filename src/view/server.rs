//! The view's HTTP server: the embedded page, the trace lines (all at once and as a stream of
//! server-sent events), the live run's controls and the why endpoint. Each request gets its
//! own thread, so a slow or vanished client never holds up the run or other clients.

use super::control::{Command, Control};
use super::feed::{Feed, FeedReader};
use super::{page, WhyProvider};
use serde_json::{json, Value};
use std::io::Write;
use std::net::{SocketAddr, TcpListener, ToSocketAddrs};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;
use tiny_http::{Header, Method, Request, Response, Server};

/// The address `--view` serves on without one: this machine only, any free port.
pub const DEFAULT_ADDR: &str = "127.0.0.1:0";
/// Requests handled at once; more get "503 busy" (each open page holds one stream).
const MAX_CLIENTS: usize = 256;
/// How long a stream waits for new lines before sending a keep-alive comment (which also
/// notices a closed tab).
const STREAM_WAIT: Duration = Duration::from_millis(500);

/// What the server shows.
pub struct Site {
    /// The trace lines (live or replayed).
    pub feed: Arc<Feed>,
    /// The live run's controls; `None` for a replay.
    pub control: Option<Arc<Control>>,
    /// Answers why-questions; `None`: the page says they are unavailable.
    pub why: Option<Arc<dyn WhyProvider>>,
    /// Shown as the page's title (the system file).
    pub title: String,
}

/// A running view server; dropping it stops the server.
pub struct ViewServer {
    url: String,
    server: Arc<Server>,
    thread: Option<JoinHandle<()>>,
}

impl ViewServer {
    /// The page's address, e.g. `http://127.0.0.1:40123/`.
    pub fn url(&self) -> &str {
        &self.url
    }
}

impl Drop for ViewServer {
    fn drop(&mut self) {
        self.server.unblock();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// Reads `ADDR:PORT`, or a bare `PORT` (on 127.0.0.1).
pub fn parse_addr(text: &str) -> Result<SocketAddr, String> {
    let text = text.trim();
    let full = if text.parse::<u16>().is_ok() {
        format!("127.0.0.1:{text}")
    } else {
        text.to_string()
    };
    full.to_socket_addrs()
        .ok()
        .and_then(|mut a| a.next())
        .ok_or_else(|| {
            format!("`{text}` is not an address to serve on: write ADDR:PORT, e.g. 127.0.0.1:8080")
        })
}

/// Binds `addr`; when its port is taken, says so (in `notes`) and takes a free port instead.
fn bind(addr: SocketAddr, notes: &mut Vec<String>) -> Result<TcpListener, String> {
    match TcpListener::bind(addr) {
        Ok(l) => Ok(l),
        Err(e) if e.kind() == std::io::ErrorKind::AddrInUse && addr.port() != 0 => {
            notes.push(format!(
                "address {addr} is already in use (another program, or another goal view); \
                 serving on a free port instead"
            ));
            let any = SocketAddr::new(addr.ip(), 0);
            TcpListener::bind(any).map_err(|e| format!("cannot serve the view on {any}: {e}"))
        }
        Err(e) => Err(format!("cannot serve the view on {addr}: {e}")),
    }
}

/// Starts serving `site` on `addr`; warnings (e.g. the port was taken) go to `notes`.
pub fn serve(addr: &str, site: Site, notes: &mut Vec<String>) -> Result<ViewServer, String> {
    let addr = parse_addr(addr)?;
    let listener = bind(addr, notes)?;
    let local = listener
        .local_addr()
        .map_err(|e| format!("cannot serve the view on {addr}: {e}"))?;
    let server = Server::from_listener(listener, None)
        .map_err(|e| format!("cannot serve the view on {addr}: {e}"))?;
    let server = Arc::new(server);
    let site = Arc::new(site);
    let accept = server.clone();
    let thread = std::thread::Builder::new()
        .name("view-server".into())
        .spawn(move || accept_loop(&accept, &site))
        .map_err(|e| format!("cannot start the view server: {e}"))?;
    let host = match local.ip() {
        ip if ip.is_unspecified() => "127.0.0.1".to_string(),
        std::net::IpAddr::V6(ip) => format!("[{ip}]"),
        ip => ip.to_string(),
    };
    Ok(ViewServer {
        url: format!("http://{host}:{}/", local.port()),
        server,
        thread: Some(thread),
    })
}

fn accept_loop(server: &Server, site: &Arc<Site>) {
    let active = Arc::new(AtomicUsize::new(0));
    for request in server.incoming_requests() {
        if active.fetch_add(1, Ordering::SeqCst) >= MAX_CLIENTS {
            active.fetch_sub(1, Ordering::SeqCst);
            let _ = request.respond(error(503, "too many clients at once; try again"));
            continue;
        }
        let site = site.clone();
        let done = active.clone();
        let spawned = std::thread::Builder::new()
            .name("view-client".into())
            .spawn(move || {
                handle(request, &site);
                done.fetch_sub(1, Ordering::SeqCst);
            });
        if spawned.is_err() {
            active.fetch_sub(1, Ordering::SeqCst);
        }
    }
}

fn header(name: &str, value: &str) -> Header {
    // Names and values here are fixed ASCII text, which `from_bytes` always accepts.
    Header::from_bytes(name.as_bytes(), value.as_bytes()).unwrap_or_else(|_| {
        Header::from_bytes(&b"X-Invalid"[..], &b"1"[..]).expect("a constant header is valid")
    })
}

fn json_response(status: u16, v: &Value) -> Response<std::io::Cursor<Vec<u8>>> {
    Response::from_data(v.to_string().into_bytes())
        .with_status_code(status)
        .with_header(header("Content-Type", "application/json; charset=utf-8"))
        .with_header(header("Cache-Control", "no-store"))
}

fn error(status: u16, message: &str) -> Response<std::io::Cursor<Vec<u8>>> {
    json_response(status, &json!({ "error": message }))
}

/// Splits a request URL into its path and decoded `key=value` query pairs.
fn split_url(url: &str) -> (&str, Vec<(String, String)>) {
    let (path, query) = url.split_once('?').unwrap_or((url, ""));
    let pairs = query
        .split('&')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let (k, v) = p.split_once('=').unwrap_or((p, ""));
            (decode(k), decode(v))
        })
        .collect();
    (path, pairs)
}

/// Percent-decoding of a query component (`+` is a space).
fn decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        match b[i] {
            b'%' if i + 2 < b.len() => match (hex(b[i + 1]), hex(b[i + 2])) {
                (Some(h), Some(l)) => {
                    out.push((h * 16 + l) as u8);
                    i += 3;
                    continue;
                }
                _ => out.push(b'%'),
            },
            b'+' => out.push(b' '),
            c => out.push(c),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

fn param<'q>(query: &'q [(String, String)], key: &str) -> Option<&'q str> {
    query
        .iter()
        .find(|(k, _)| k == key)
        .map(|(_, v)| v.as_str())
}

fn handle(mut request: Request, site: &Site) {
    let url = request.url().to_string();
    let (path, query) = split_url(&url);
    if path == "/api/play" || path.starts_with("/api/play/") {
        let (status, body) = super::play::handle(&mut request, site, path, param(&query, "token"));
        let _ = request.respond(json_response(status, &body));
        return;
    }
    let get = *request.method() == Method::Get || *request.method() == Method::Head;
    let response = match (get, path) {
        (true, "/api/stream") => return stream(request, site, &query),
        (true, "/api/trace") => return trace(request, site),
        (true, "/api/info") => json_response(200, &info(site)),
        (true, "/api/why") => why(site, &query),
        (false, "/api/control") => control(site, &query, &url),
        (true, p) => match page::asset(p) {
            Some((body, kind)) => Response::from_data(body.as_bytes().to_vec())
                .with_header(header("Content-Type", kind))
                .with_header(header("Cache-Control", "no-store")),
            None => error(404, &format!("no such page: {p}")),
        },
        (false, p) => error(405, &format!("{p} accepts GET only")),
    };
    // A client that left before its answer is nobody's problem.
    let _ = request.respond(response);
}

fn info(site: &Site) -> Value {
    let (lines, complete) = site.feed.len();
    json!({
        "mode": if site.control.is_some() { "live" } else { "replay" },
        "title": site.title,
        "why": site.why.is_some(),
        "lines": lines,
        "complete": complete,
        "feed_bytes": site.feed.held_bytes(),
        "control": site.control.as_ref().map(|c| c.to_json()),
    })
}

/// Every trace line so far, as JSON lines; `X-Trace-Lines` says how many (a live page then
/// streams from there). The body is read from the feed as it is sent.
fn trace(request: Request, site: &Site) {
    let (lines, bytes) = site.feed.size();
    let complete = site.feed.len().1;
    let body = FeedReader::new(site.feed.clone(), 0, lines);
    let headers = vec![
        header("Content-Type", "application/x-ndjson; charset=utf-8"),
        header("Cache-Control", "no-store"),
        header("X-Trace-Lines", &lines.to_string()),
        header("X-Trace-Complete", &complete.to_string()),
    ];
    let length = usize::try_from(bytes).ok();
    let _ = request.respond(Response::new(200.into(), headers, body, length, None));
}

/// Server-sent events: one `data:` event per trace line from `from` on, as the run writes
/// them, then an `end` event when the trace is complete. A closed tab ends the stream at the
/// next write; the run never waits for a client.
fn stream(request: Request, site: &Site, query: &[(String, String)]) {
    let mut from: usize = param(query, "from")
        .and_then(|f| f.parse().ok())
        .unwrap_or(0);
    let mut out = request.into_writer();
    let head = "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream; charset=utf-8\r\n\
                Cache-Control: no-store\r\nConnection: close\r\n\r\n";
    if out.write_all(head.as_bytes()).is_err() {
        return;
    }
    loop {
        let (lines, closed) = match site.feed.read_from(from, STREAM_WAIT) {
            Ok(r) => r,
            Err(e) => {
                // The page then says its connection to the run is lost.
                eprintln!("warning: the view stopped streaming to a page: {e}");
                return;
            }
        };
        let mut chunk = String::new();
        for l in &lines {
            chunk.push_str("data: ");
            chunk.push_str(l);
            chunk.push_str("\n\n");
        }
        from += lines.len();
        let finished = closed && lines.is_empty();
        if finished {
            chunk.push_str("event: end\ndata: {}\n\n");
        } else if lines.is_empty() {
            chunk.push_str(": waiting\n\n");
        }
        if out.write_all(chunk.as_bytes()).is_err() || out.flush().is_err() || finished {
            return;
        }
    }
}

fn control(
    site: &Site,
    query: &[(String, String)],
    url: &str,
) -> Response<std::io::Cursor<Vec<u8>>> {
    let Some(c) = &site.control else {
        return error(
            409,
            "this is a replay: the page controls it, not the server",
        );
    };
    let text = url.split_once('?').map_or("", |(_, q)| q);
    let text = match query.first() {
        Some((k, v)) if !v.is_empty() => format!("{k}={v}"),
        Some((k, _)) => k.clone(),
        None => text.to_string(),
    };
    match Command::parse(&text) {
        Ok(cmd) => {
            c.apply(cmd);
            json_response(200, &c.to_json())
        }
        Err(e) => error(400, &e),
    }
}

fn why(site: &Site, query: &[(String, String)]) -> Response<std::io::Cursor<Vec<u8>>> {
    let Some(provider) = &site.why else {
        return error(
            501,
            "the why answer is unavailable for this run (this view has no way to rerun it)",
        );
    };
    let Some(agent) = param(query, "agent").filter(|a| !a.is_empty()) else {
        return error(400, "name the agent: /api/why?agent=NAME&tick=N");
    };
    let Some(tick) = param(query, "tick").and_then(|t| t.parse::<u64>().ok()) else {
        return error(
            400,
            "give the tick as a whole number: /api/why?agent=NAME&tick=N",
        );
    };
    match provider.why(agent, tick) {
        Ok(v) => json_response(200, &v),
        Err(e) => error(422, &e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_are_decoded() {
        let (p, q) = split_url("/api/why?agent=Bot%201&tick=12&x");
        assert_eq!(p, "/api/why");
        assert_eq!(param(&q, "agent"), Some("Bot 1"));
        assert_eq!(param(&q, "tick"), Some("12"));
        assert_eq!(param(&q, "x"), Some(""));
        assert_eq!(decode("100%"), "100%");
        assert_eq!(decode("%4"), "%4");
    }

    #[test]
    fn addresses() {
        assert_eq!(parse_addr("8080").unwrap().port(), 8080);
        assert_eq!(parse_addr("127.0.0.1:0").unwrap().port(), 0);
        assert!(parse_addr("no such host:x").is_err());
    }
}
