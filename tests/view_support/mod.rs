//! Helpers of the view's tests: the `goal` binary serving a page, plain HTTP requests, and a
//! real headless browser (Debian's chromium) dumping the rendered DOM or a screenshot.
#![allow(dead_code)]

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

pub fn goal() -> Command {
    Command::new(env!("CARGO_BIN_EXE_goal"))
}

/// Runs `goal run ARGS --trace TRACE` to its end (stderr dropped); its exit code.
pub fn record(args: &[&str], trace: &Path) -> Option<i32> {
    goal()
        .arg("run")
        .args(args)
        .arg("--trace")
        .arg(trace)
        .stderr(Stdio::null())
        .status()
        .unwrap()
        .code()
}

/// `goal run` of the default team with `robots` agent robots and `humans` HumanBots, for at
/// most `max_ticks` ticks (it opens the view: start it with [`Served::start`]).
pub fn team_with_humans(robots: u32, humans: u32, max_ticks: u64) -> Command {
    let mut cmd = goal();
    cmd.args([
        "run",
        "--robots",
        &robots.to_string(),
        "--humans",
        &humans.to_string(),
    ])
    .args(["--max-ticks", &max_ticks.to_string()]);
    cmd
}

/// The records of the trace `path`.
pub fn records(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

/// A scratch directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("goal-view-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A `goal` process serving a page: its URL, and its stderr lines as they come.
pub struct Served {
    pub child: Child,
    pub url: String,
    pub lines: mpsc::Receiver<String>,
    pub seen: Vec<String>,
}

impl Served {
    /// Starts `cmd` (with stderr piped) and waits for the `view: URL` line.
    pub fn start(mut cmd: Command) -> Served {
        let mut child = cmd
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("goal starts");
        let err = child.stderr.take().unwrap();
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            for l in BufReader::new(err).lines().map_while(Result::ok) {
                if tx.send(l).is_err() {
                    break;
                }
            }
        });
        let mut s = Served {
            child,
            url: String::new(),
            lines: rx,
            seen: Vec::new(),
        };
        let line = s.wait_line(|l| l.starts_with("view: http://"), Duration::from_secs(60));
        s.url = line
            .split_whitespace()
            .nth(1)
            .expect("a URL after view:")
            .to_string();
        s
    }

    /// Waits for a stderr line matching `pred` (panics with everything seen after `limit`).
    pub fn wait_line(&mut self, pred: impl Fn(&str) -> bool, limit: Duration) -> String {
        let end = Instant::now() + limit;
        loop {
            let left = end.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(l) => {
                    self.seen.push(l.clone());
                    if pred(&l) {
                        return l;
                    }
                }
                Err(_) => panic!("no such line on stderr; saw:\n{}", self.seen.join("\n")),
            }
        }
    }

    /// The last tick the live run reached (0 before its first round).
    pub fn tick(&self) -> u64 {
        json(&self.url, "/api/info")["control"]["tick"]
            .as_u64()
            .unwrap_or(0)
    }

    /// Waits (up to a minute) until the live run is at tick `n` or past it; the tick reached.
    pub fn wait_for_tick(&self, n: u64) -> u64 {
        let end = Instant::now() + Duration::from_secs(60);
        loop {
            let t = self.tick();
            if t >= n {
                return t;
            }
            assert!(
                Instant::now() < end,
                "the live run stays at tick {t}, not {n}"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// Sends SIGINT and waits for the exit code.
    pub fn interrupt(mut self) -> Option<i32> {
        unsafe {
            libc::kill(self.child.id() as i32, libc::SIGINT);
        }
        let status = self.child.wait().ok()?;
        status.code()
    }
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// One HTTP/1.0 request to `url` + `path`: (status, body).
pub fn http(method: &str, url: &str, path: &str) -> (u16, String) {
    http_with(method, url, path, "")
}

/// One HTTP/1.0 request to `url` + `path` with a JSON `body`: (status, body).
pub fn http_with(method: &str, url: &str, path: &str, body: &str) -> (u16, String) {
    let hostport = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .to_string();
    let mut s = TcpStream::connect(&hostport).expect("connect to the view");
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    write!(
        s,
        "{method} {path} HTTP/1.0\r\nHost: {hostport}\r\nContent-Type: application/json\r\n\
         Content-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut text = String::new();
    let _ = s.read_to_string(&mut text);
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    let body = text
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    (status, body)
}

pub fn json(url: &str, path: &str) -> serde_json::Value {
    let (status, body) = http("GET", url, path);
    assert_eq!(status, 200, "{path}: {body}");
    serde_json::from_str(&body).expect("JSON")
}

/// The headless browser, if there is one (CI installs Debian's chromium).
pub fn browser() -> Option<PathBuf> {
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        for dir in std::env::var("PATH").unwrap_or_default().split(':') {
            let p = Path::new(dir).join(name);
            if p.is_file() {
                return Some(p);
            }
        }
    }
    eprintln!("no headless browser (chromium) installed: skipping the browser checks");
    None
}

/// The flags of every headless chromium the tests start.
pub const HEADLESS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--window-size=1400,900",
];

fn chromium(browser: &Path, profile: &Path) -> Command {
    let mut c = Command::new(browser);
    c.args(HEADLESS)
        .arg(format!("--user-data-dir={}", profile.display()))
        .stdin(Stdio::null())
        .stderr(Stdio::null());
    c
}

/// The DOM after the page at `url` has loaded (the page draws before its load event).
pub fn dump_dom(browser: &Path, profile: &Path, url: &str) -> String {
    let out = chromium(browser, profile)
        .arg("--dump-dom")
        .arg(url)
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(dom.contains("</html>"), "no page from {url}: {dom}");
    dom
}

/// Saves a screenshot of the page at `url` to `png`.
pub fn screenshot(browser: &Path, profile: &Path, url: &str, png: &Path) {
    let _ = std::fs::remove_file(png);
    let status = chromium(browser, profile)
        .arg(format!("--screenshot={}", png.display()))
        .arg(url)
        .status()
        .expect("chromium runs");
    assert!(status.success());
    let bytes = std::fs::read(png).expect("a screenshot");
    assert!(bytes.starts_with(b"\x89PNG"), "not a PNG");
}

/// Every match of `<TAG ...class="CLASS...` opening tags: their attribute text.
pub fn tags<'a>(dom: &'a str, class: &str) -> Vec<&'a str> {
    let needle = format!("class=\"{class}");
    dom.match_indices(&needle)
        .map(|(i, _)| {
            let start = dom[..i].rfind('<').unwrap_or(0);
            let end = dom[i..].find('>').map_or(dom.len(), |e| i + e);
            &dom[start..end]
        })
        .collect()
}

/// The value of attribute `name` in a tag's text.
pub fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let i = tag.find(&key)? + key.len();
    tag[i..].split('"').next()
}

/// The text of the `<li>` items of the list with id `id`.
pub fn list(dom: &str, id: &str) -> Vec<String> {
    let Some(start) = dom.find(&format!("id=\"{id}\"")) else {
        return Vec::new();
    };
    let end = dom[start..].find("</ul>").map_or(dom.len(), |e| start + e);
    dom[start..end]
        .split("<li>")
        .skip(1)
        .map(|s| s.split("</li>").next().unwrap_or("").to_string())
        .collect()
}
