//! A small client of the Chrome DevTools protocol for tests that click on a page in a real
//! headless chromium: the browser is started with `--remote-debugging-pipe` (the protocol's
//! JSON messages, each ended by a NUL byte, on file descriptors 3 and 4), so no port and no
//! WebSocket library are needed. Clicks are real mouse events dispatched at an element's
//! position (`Input.dispatchMouseEvent`), hit-tested by the browser like a person's.
#![allow(dead_code)]

use serde_json::{json, Value};
use std::fs::File;
use std::io::{BufRead, BufReader, Write};
use std::os::fd::{FromRawFd, RawFd};
use std::os::unix::process::CommandExt;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

/// How long one protocol call may take.
const CALL_LIMIT: Duration = Duration::from_secs(60);

/// A headless chromium driven over the DevTools protocol.
pub struct Browser {
    child: Child,
    to: File,
    from: mpsc::Receiver<Value>,
    next: u64,
}

/// One tab of the browser.
pub struct Tab<'b> {
    browser: &'b mut Browser,
    session: String,
}

fn pipe() -> (RawFd, RawFd) {
    let mut fds = [0; 2];
    // SAFETY: `fds` has room for the two descriptors pipe(2) writes.
    let r = unsafe { libc::pipe(fds.as_mut_ptr()) };
    assert_eq!(r, 0, "pipe(2) failed");
    (fds[0], fds[1])
}

impl Browser {
    /// Starts `browser` headless with its profile in `profile`.
    pub fn launch(browser: &Path, profile: &Path) -> Browser {
        let (child_reads, we_write) = pipe();
        let (we_read, child_writes) = pipe();
        let mut cmd = Command::new(browser);
        // Tests using this module also have `view_support` (the server side of the page).
        cmd.args(super::view_support::HEADLESS)
            .arg("--remote-debugging-pipe")
            .arg(format!("--user-data-dir={}", profile.display()))
            .arg("about:blank")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null());
        // SAFETY: only async-signal-safe calls (dup2, close) between fork and exec.
        unsafe {
            cmd.pre_exec(move || {
                if libc::dup2(child_reads, 3) < 0 || libc::dup2(child_writes, 4) < 0 {
                    return Err(std::io::Error::last_os_error());
                }
                for fd in [child_reads, child_writes, we_read, we_write] {
                    if fd > 4 {
                        libc::close(fd);
                    }
                }
                Ok(())
            });
        }
        let child = cmd.spawn().expect("chromium starts");
        // SAFETY: the descriptors are ours alone from here on.
        let (to, from) = unsafe {
            libc::close(child_reads);
            libc::close(child_writes);
            (File::from_raw_fd(we_write), File::from_raw_fd(we_read))
        };
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let mut r = BufReader::new(from);
            let mut buf = Vec::new();
            loop {
                buf.clear();
                match r.read_until(0, &mut buf) {
                    Ok(0) | Err(_) => break,
                    Ok(_) => {
                        if buf.last() == Some(&0) {
                            buf.pop();
                        }
                        if let Ok(v) = serde_json::from_slice::<Value>(&buf) {
                            if tx.send(v).is_err() {
                                break;
                            }
                        }
                    }
                }
            }
        });
        Browser {
            child,
            to,
            from: rx,
            next: 1,
        }
    }

    /// Calls `method` (in `session`, or on the browser) and waits for its result.
    fn call(&mut self, session: Option<&str>, method: &str, params: Value) -> Value {
        let id = self.next;
        self.next += 1;
        let mut msg = json!({"id": id, "method": method, "params": params});
        if let Some(s) = session {
            msg["sessionId"] = json!(s);
        }
        let mut bytes = msg.to_string().into_bytes();
        bytes.push(0);
        self.to.write_all(&bytes).expect("write to chromium");
        let end = Instant::now() + CALL_LIMIT;
        loop {
            let left = end.saturating_duration_since(Instant::now());
            let v = self
                .from
                .recv_timeout(left)
                .unwrap_or_else(|_| panic!("chromium did not answer {method}"));
            if v["id"] == json!(id) {
                if let Some(e) = v.get("error") {
                    panic!("{method} failed: {e}");
                }
                return v["result"].clone();
            }
        }
    }

    /// Opens `url` in a new tab.
    pub fn open(&mut self, url: &str) -> Tab<'_> {
        let target = self.call(None, "Target.createTarget", json!({"url": "about:blank"}));
        let id = target["targetId"]
            .as_str()
            .expect("a target id")
            .to_string();
        let attached = self.call(
            None,
            "Target.attachToTarget",
            json!({"targetId": id, "flatten": true}),
        );
        let session = attached["sessionId"]
            .as_str()
            .expect("a session")
            .to_string();
        let mut tab = Tab {
            browser: self,
            session,
        };
        tab.call("Page.enable", json!({}));
        tab.call("Page.navigate", json!({"url": url}));
        tab
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Tab<'_> {
    fn call(&mut self, method: &str, params: Value) -> Value {
        let s = self.session.clone();
        self.browser.call(Some(&s), method, params)
    }

    /// The value of the JavaScript expression `js` in the page (promises awaited).
    pub fn eval(&mut self, js: &str) -> Value {
        let r = self.call(
            "Runtime.evaluate",
            json!({"expression": js, "returnByValue": true, "awaitPromise": true}),
        );
        if let Some(e) = r.get("exceptionDetails") {
            panic!("{js} threw: {e}");
        }
        r["result"]["value"].clone()
    }

    /// True when `js` is true in the page now; false while it throws (e.g. before the page
    /// has loaded).
    pub fn holds(&mut self, js: &str) -> bool {
        self.eval(&format!(
            "(() => {{ try {{ return !!({js}); }} catch (e) {{ return false; }} }})()"
        )) == json!(true)
    }

    /// Waits until `js` is true in the page (panics with `what` after `limit`).
    pub fn wait_for(&mut self, js: &str, what: &str, limit: Duration) {
        let end = Instant::now() + limit;
        loop {
            if self.holds(js) {
                return;
            }
            if Instant::now() > end {
                panic!("waited {limit:?} for {what} ({js})");
            }
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// A point of the element `selector` (the first match) where a click hits that element
    /// itself, not something drawn over it, after scrolling it into view.
    pub fn point_of(&mut self, selector: &str) -> Option<(f64, f64)> {
        let sel = serde_json::to_string(selector).unwrap();
        let js = format!(
            "(() => {{ const e = document.querySelector({sel}); if (!e) return null;
              e.scrollIntoView({{block: 'center', inline: 'center'}});
              const r = e.getBoundingClientRect();
              for (let i = 1; i < 8; i++) for (let j = 1; j < 8; j++) {{
                const x = r.left + r.width * i / 8, y = r.top + r.height * j / 8;
                const hit = document.elementFromPoint(x, y);
                if (hit === e || e.contains(hit)) return [x, y];
              }}
              return null; }})()"
        );
        let v = self.eval(&js);
        Some((v[0].as_f64()?, v[1].as_f64()?))
    }

    /// Clicks the element `selector` with the (virtual) mouse, as a person would.
    pub fn click(&mut self, selector: &str) {
        assert!(self.try_click(selector), "nothing to click at {selector}");
    }

    /// Clicks the element `selector` if it can be clicked now (false: it is missing, or
    /// something is drawn over all of it).
    pub fn try_click(&mut self, selector: &str) -> bool {
        let Some((x, y)) = self.point_of(selector) else {
            return false;
        };
        for kind in ["mouseMoved", "mousePressed", "mouseReleased"] {
            self.call(
                "Input.dispatchMouseEvent",
                json!({"type": kind, "x": x, "y": y, "button": "left", "clickCount": 1}),
            );
        }
        true
    }

    /// Chooses `value` in the `<select>` `selector` (a real choice: the change event fires).
    pub fn choose(&mut self, selector: &str, value: &str) {
        let (sel, val) = (
            serde_json::to_string(selector).unwrap(),
            serde_json::to_string(value).unwrap(),
        );
        let done = self.eval(&format!(
            "(() => {{ const e = document.querySelector({sel}); if (!e) return false;
               e.value = {val}; if (e.value !== {val}) return false;
               e.dispatchEvent(new Event('change', {{bubbles: true}})); return true; }})()"
        ));
        assert_eq!(done, json!(true), "cannot choose {value} in {selector}");
    }

    /// Saves a screenshot of the tab to `png`.
    pub fn screenshot(&mut self, png: &Path) {
        let r = self.call("Page.captureScreenshot", json!({"format": "png"}));
        let data = r["data"].as_str().expect("screenshot data");
        std::fs::write(png, decode_base64(data)).expect("write the screenshot");
    }
}

/// Standard base64 (what the protocol sends screenshots in).
fn decode_base64(text: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => Some(c - b'A'),
        b'a'..=b'z' => Some(c - b'a' + 26),
        b'0'..=b'9' => Some(c - b'0' + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    };
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for c in text.bytes().filter_map(val) {
        acc = (acc << 6) | u32::from(c);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
        }
    }
    out
}
