//! Trace lines kept on disk instead of in memory: a file of lines (the live feed's own
//! anonymous scratch file, or a replayed trace file) with a sparse index, so that reading from
//! any line costs one seek and at most one index stride of skipped lines. The index is thinned
//! (every other mark dropped, the stride doubled) when it grows, so its memory is bounded too.

use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom, Write};
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// The most index marks kept (8 bytes each); more halve the index.
const MAX_MARKS: usize = 4096;

/// Lines on disk, read back by index.
pub struct Spill {
    file: File,
    /// Bytes in the file (where the next line goes).
    end: u64,
    /// Lines stored.
    lines: usize,
    /// `marks[k]`: the byte offset of line `k * stride`.
    marks: Vec<u64>,
    stride: usize,
}

impl Spill {
    /// An empty spill in a scratch file that disappears with it (removed from the directory at
    /// once, so nothing is left behind even when the program is killed).
    pub fn scratch() -> std::io::Result<Spill> {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let path =
            std::env::temp_dir().join(format!("goal-view-feed-{}-{n}.jsonl", std::process::id()));
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create_new(true)
            .open(&path)?;
        // Unix keeps an unlinked file while it is open; elsewhere it stays until the end.
        let _ = std::fs::remove_file(&path);
        Ok(Spill::over(file))
    }

    fn over(file: File) -> Spill {
        Spill {
            file,
            end: 0,
            lines: 0,
            marks: Vec::new(),
            stride: 1,
        }
    }

    /// The spill over an existing file of lines (a replayed trace), to be indexed with
    /// [`Spill::note`] line by line.
    pub fn existing(path: &Path) -> std::io::Result<Spill> {
        let mut s = Spill::over(File::open(path)?);
        s.end = s.file.metadata()?.len();
        Ok(s)
    }

    /// Counts one more line starting at byte `offset`, marking it when it starts a stride.
    pub fn note(&mut self, offset: u64) {
        if self.lines.is_multiple_of(self.stride) {
            self.marks.push(offset);
            if self.marks.len() > MAX_MARKS {
                let mut k = 0;
                self.marks.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
                self.stride *= 2;
            }
        }
        self.lines += 1;
    }

    /// Appends one line (a newline is added).
    pub fn append(&mut self, line: &str) -> std::io::Result<()> {
        self.file.seek(SeekFrom::Start(self.end))?;
        self.file.write_all(line.as_bytes())?;
        self.file.write_all(b"\n")?;
        let at = self.end;
        self.end += line.len() as u64 + 1;
        self.note(at);
        Ok(())
    }

    /// The number of lines stored.
    pub fn len(&self) -> usize {
        self.lines
    }

    /// True when no line is stored.
    pub fn is_empty(&self) -> bool {
        self.lines == 0
    }

    /// Bytes of memory the spill holds (its index).
    pub fn held_bytes(&self) -> usize {
        self.marks.capacity() * std::mem::size_of::<u64>()
    }

    /// Lines `from..upto` (`upto` at most [`Spill::len`]), stopping early after about
    /// `max_bytes` bytes (at least one line is read).
    pub fn read(
        &mut self,
        from: usize,
        upto: usize,
        max_bytes: usize,
    ) -> std::io::Result<Vec<Arc<str>>> {
        let upto = upto.min(self.lines);
        if from >= upto {
            return Ok(Vec::new());
        }
        let k = from / self.stride;
        let mut skip = from - k * self.stride;
        self.file.seek(SeekFrom::Start(self.marks[k]))?;
        let mut input = BufReader::new((&mut self.file).take(self.end - self.marks[k]));
        let (mut out, mut bytes, mut line) = (Vec::new(), 0, String::new());
        while from + out.len() < upto && (out.is_empty() || bytes < max_bytes) {
            line.clear();
            if input.read_line(&mut line)? == 0 {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    "the trace file is shorter than when it was read",
                ));
            }
            let text = record_text(&line);
            if text.trim().is_empty() {
                continue; // a replayed trace may have blank lines; they are not records
            }
            if skip > 0 {
                skip -= 1;
                continue;
            }
            bytes += text.len();
            out.push(Arc::from(text));
        }
        Ok(out)
    }
}

/// A line read with its line ending, without it (`\n` or `\r\n`).
pub fn record_text(line: &str) -> &str {
    let line = line.strip_suffix('\n').unwrap_or(line);
    line.strip_suffix('\r').unwrap_or(line)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_come_back_from_anywhere_and_the_index_stays_small() {
        let mut s = Spill::scratch().unwrap();
        let n = 3 * MAX_MARKS + 17;
        for i in 0..n {
            s.append(&format!("line {i}")).unwrap();
        }
        assert_eq!(s.len(), n);
        assert!(s.held_bytes() <= 2 * MAX_MARKS * 8, "{}", s.held_bytes());
        for from in [0, 1, 4095, 4096, 9999, n - 1] {
            let got = s.read(from, n, 1 << 20).unwrap();
            assert_eq!(got.len(), n - from);
            assert_eq!(&*got[0], format!("line {from}"));
        }
        let some = s.read(10, n, 30).unwrap();
        assert!(!some.is_empty() && some.len() < 10, "{}", some.len());
        assert_eq!(&*some[0], "line 10");
        assert!(s.read(n, n + 5, 100).unwrap().is_empty());
    }
}
