//! The trace lines of a run as they are written, shared by the run (one writer) and any number
//! of page clients (readers that wait for new lines).

use std::io::Write;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

#[derive(Default)]
struct Lines {
    lines: Vec<Arc<str>>,
    closed: bool,
}

/// Append-only trace lines; `closed` once the run (or the replayed file) is complete.
#[derive(Default)]
pub struct Feed {
    state: Mutex<Lines>,
    grown: Condvar,
}

impl Feed {
    /// An empty, open feed.
    pub fn new() -> Feed {
        Feed::default()
    }

    /// A closed feed holding `lines` (a replay).
    pub fn complete(lines: Vec<String>) -> Feed {
        let feed = Feed::new();
        {
            let mut s = feed.lock();
            s.lines = lines.into_iter().map(Arc::from).collect();
            s.closed = true;
        }
        feed
    }

    // A panicking client thread must not stop the run: a poisoned lock is still usable, since
    // every change under it is a single push or flag.
    fn lock(&self) -> MutexGuard<'_, Lines> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Appends one line (without its newline).
    pub fn push(&self, line: &str) {
        self.lock().lines.push(Arc::from(line));
        self.grown.notify_all();
    }

    /// No more lines will come.
    pub fn close(&self) {
        self.lock().closed = true;
        self.grown.notify_all();
    }

    /// The number of lines so far and whether the feed is closed.
    pub fn len(&self) -> (usize, bool) {
        let s = self.lock();
        (s.lines.len(), s.closed)
    }

    /// True when no line was written yet.
    pub fn is_empty(&self) -> bool {
        self.len().0 == 0
    }

    /// The lines from index `from` on, waiting up to `wait` for some when there are none yet;
    /// also whether the feed is closed (no more will come after these).
    pub fn read_from(&self, from: usize, wait: Duration) -> (Vec<Arc<str>>, bool) {
        let mut s = self.lock();
        if s.lines.len() <= from && !s.closed {
            s = match self.grown.wait_timeout(s, wait) {
                Ok((g, _)) => g,
                Err(e) => e.into_inner().0,
            };
        }
        let lines = s.lines.get(from..).map(<[_]>::to_vec).unwrap_or_default();
        (lines, s.closed)
    }
}

/// Writes into a [`Feed`]: each complete line written becomes one feed line.
pub struct FeedWriter {
    feed: Arc<Feed>,
    partial: Vec<u8>,
}

impl FeedWriter {
    /// A writer appending to `feed`.
    pub fn new(feed: Arc<Feed>) -> FeedWriter {
        FeedWriter {
            feed,
            partial: Vec::new(),
        }
    }
}

impl Write for FeedWriter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        for chunk in buf.split_inclusive(|b| *b == b'\n') {
            match chunk.strip_suffix(b"\n") {
                Some(rest) => {
                    self.partial.extend_from_slice(rest);
                    self.feed.push(&String::from_utf8_lossy(&self.partial));
                    self.partial.clear();
                }
                None => self.partial.extend_from_slice(chunk),
            }
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Writes everything to both sinks (the trace file and the feed); the file's errors count.
pub struct Tee<A: Write, B: Write> {
    pub first: A,
    pub second: B,
}

impl<A: Write, B: Write> Write for Tee<A, B> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.second.write_all(buf)?;
        self.first.write_all(buf)?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.second.flush()?;
        self.first.flush()
    }
}
