//! The trace lines of a run as they are written, shared by the run (one writer) and any number
//! of page clients (readers that wait for new lines).
//!
//! Memory stays bounded however long the run: the feed holds only its newest lines, up to a
//! byte budget; older lines go to a [`Spill`] file on disk and are read back, a chunk at a
//! time, when a client that joined late (or reloads the page) asks for them. A replay's feed is
//! its trace file, indexed, with nothing held in memory.

use super::spill::Spill;
use std::collections::VecDeque;
use std::io::Write;
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::time::Duration;

/// The bytes of trace lines a live feed holds in memory before spilling the oldest to disk.
pub const DEFAULT_BUDGET: usize = 8 << 20;
/// What one held line costs besides its text (its `Arc` and its slot), counted in the budget.
const LINE_OVERHEAD: usize = 32;
/// About how many bytes one read from disk returns (a client streams the rest in more reads).
const READ_CHUNK: usize = 1 << 20;

struct Lines {
    /// The newest lines, in memory; `tail[0]` is line number `first`.
    tail: VecDeque<Arc<str>>,
    first: usize,
    /// Bytes `tail` holds (text plus [`LINE_OVERHEAD`] per line).
    tail_bytes: usize,
    /// Lines `0..first`, on disk.
    spill: Option<Spill>,
    /// Bytes of every line so far, each with its newline (the size of the whole trace).
    total_bytes: u64,
    budget: usize,
    closed: bool,
    /// Spilling failed (said once on stderr): lines are kept in memory from then on.
    spill_failed: bool,
}

/// Append-only trace lines; `closed` once the run (or the replayed file) is complete.
pub struct Feed {
    state: Mutex<Lines>,
    grown: Condvar,
}

impl Default for Feed {
    fn default() -> Feed {
        Feed::new()
    }
}

impl Feed {
    /// An empty, open feed holding at most [`DEFAULT_BUDGET`] bytes of lines in memory.
    pub fn new() -> Feed {
        Feed::with_budget(DEFAULT_BUDGET)
    }

    /// An empty, open feed holding at most about `budget` bytes of lines in memory (always at
    /// least the newest line).
    pub fn with_budget(budget: usize) -> Feed {
        Feed {
            state: Mutex::new(Lines {
                tail: VecDeque::new(),
                first: 0,
                tail_bytes: 0,
                spill: None,
                total_bytes: 0,
                budget,
                closed: false,
                spill_failed: false,
            }),
            grown: Condvar::new(),
        }
    }

    /// A closed feed holding `lines` in memory.
    pub fn complete(lines: Vec<String>) -> Feed {
        let feed = Feed::with_budget(usize::MAX);
        for l in lines {
            feed.push(&l);
        }
        feed.close();
        feed
    }

    /// A closed feed reading its `total_bytes` of lines from `spill` (a replayed trace file).
    pub fn on_disk(spill: Spill, total_bytes: u64) -> Feed {
        let feed = Feed::with_budget(0);
        {
            let mut s = feed.lock();
            s.first = spill.len();
            s.spill = Some(spill);
            s.total_bytes = total_bytes;
            s.closed = true;
        }
        feed
    }

    // A panicking client thread must not stop the run: a poisoned lock is still usable, since
    // every change under it leaves the lines consistent.
    fn lock(&self) -> MutexGuard<'_, Lines> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Appends one line (without its newline).
    pub fn push(&self, line: &str) {
        {
            let mut s = self.lock();
            s.total_bytes += line.len() as u64 + 1;
            s.tail_bytes += line.len() + LINE_OVERHEAD;
            s.tail.push_back(Arc::from(line));
            s.spill_over();
        }
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
        (s.first + s.tail.len(), s.closed)
    }

    /// True when no line was written yet.
    pub fn is_empty(&self) -> bool {
        self.len().0 == 0
    }

    /// The number of lines so far and their bytes, each with its newline.
    pub fn size(&self) -> (usize, u64) {
        let s = self.lock();
        (s.first + s.tail.len(), s.total_bytes)
    }

    /// Bytes of memory the feed holds: the lines kept in memory and the index of those on disk.
    pub fn held_bytes(&self) -> usize {
        let s = self.lock();
        s.tail_bytes + s.spill.as_ref().map_or(0, Spill::held_bytes)
    }

    /// The lines from index `from` on (all that are in memory, or a chunk of those on disk),
    /// waiting up to `wait` for some when there are none yet; also whether the feed is closed
    /// (no more will come after the last line).
    pub fn read_from(&self, from: usize, wait: Duration) -> Result<(Vec<Arc<str>>, bool), String> {
        let mut s = self.lock();
        if s.first + s.tail.len() <= from && !s.closed {
            s = match self.grown.wait_timeout(s, wait) {
                Ok((g, _)) => g,
                Err(e) => e.into_inner().0,
            };
        }
        let closed = s.closed;
        if from < s.first {
            let upto = s.first;
            let spill = s.spill.as_mut().ok_or("the trace's early lines are gone")?;
            let lines = spill
                .read(from, upto, READ_CHUNK)
                .map_err(|e| format!("cannot read the trace's line {} back: {e}", from + 1))?;
            return Ok((lines, closed));
        }
        // A client may ask from past the end (a stale or made-up `from`): nothing yet.
        let skip = (from - s.first).min(s.tail.len());
        let lines = s.tail.range(skip..).cloned().collect();
        Ok((lines, closed))
    }
}

impl Lines {
    /// Moves the oldest lines to disk while the lines in memory are over the budget.
    fn spill_over(&mut self) {
        while self.tail_bytes > self.budget && self.tail.len() > 1 && !self.spill_failed {
            if self.spill.is_none() {
                match Spill::scratch() {
                    Ok(s) => self.spill = Some(s),
                    Err(e) => return self.cannot_spill(&e),
                }
            }
            let (Some(spill), Some(line)) = (self.spill.as_mut(), self.tail.front()) else {
                return;
            };
            if let Err(e) = spill.append(line) {
                return self.cannot_spill(&e);
            }
            self.tail_bytes -= line.len() + LINE_OVERHEAD;
            self.tail.pop_front();
            self.first += 1;
        }
    }

    fn cannot_spill(&mut self, e: &std::io::Error) {
        self.spill_failed = true;
        eprintln!(
            "warning: the view cannot keep the run's older trace lines on disk ({e}); it \
             keeps them in memory instead, which grows with the run"
        );
    }
}

/// Lines `from..upto` of a feed as bytes, each with its newline, read a chunk at a time (so a
/// late client's copy of a long trace is never all in memory).
pub struct FeedReader {
    feed: Arc<Feed>,
    next: usize,
    upto: usize,
    chunk: Vec<u8>,
    pos: usize,
}

impl FeedReader {
    /// A reader of `feed`'s lines `from..upto`.
    pub fn new(feed: Arc<Feed>, from: usize, upto: usize) -> FeedReader {
        FeedReader {
            feed,
            next: from,
            upto,
            chunk: Vec::new(),
            pos: 0,
        }
    }
}

impl std::io::Read for FeedReader {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        if self.pos == self.chunk.len() && self.next < self.upto {
            let (lines, _) = self
                .feed
                .read_from(self.next, Duration::ZERO)
                .map_err(std::io::Error::other)?;
            self.chunk.clear();
            self.pos = 0;
            for l in lines.iter().take(self.upto - self.next) {
                self.chunk.extend_from_slice(l.as_bytes());
                self.chunk.push(b'\n');
                self.next += 1;
            }
        }
        let n = buf.len().min(self.chunk.len() - self.pos);
        buf[..n].copy_from_slice(&self.chunk[self.pos..self.pos + n]);
        self.pos += n;
        Ok(n)
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
