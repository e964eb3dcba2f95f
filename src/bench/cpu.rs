//! CPU time of the process (user + system) from `/proc/self/stat` (Linux; `None` elsewhere).
//! Wall time on a shared machine varies 2-5x with other load; CPU time much less.

use std::time::Duration;

/// Clock ticks per second of `/proc/*/stat` times (USER_HZ, 100 on Linux).
const TICKS_PER_SEC: u64 = 100;

/// User plus system CPU time the process used so far (all threads).
pub fn process_time() -> Option<Duration> {
    let text = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may contain spaces: fields are counted
    // after its closing parenthesis; utime and stime are fields 14 and 15.
    let rest = &text[text.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(11);
    let user: u64 = fields.next()?.parse().ok()?;
    let system: u64 = fields.next()?.parse().ok()?;
    Some(Duration::from_millis(
        (user + system) * 1000 / TICKS_PER_SEC,
    ))
}

/// CPU time used since `before` (a [`process_time`] reading); `None` where it cannot be read.
pub fn since(before: Option<Duration>) -> Option<Duration> {
    Some(process_time()?.saturating_sub(before?))
}

#[cfg(test)]
mod tests {
    #[test]
    fn cpu_time_grows_with_work() {
        let Some(before) = super::process_time() else {
            eprintln!("no /proc/self/stat here: skipped");
            return;
        };
        let start = std::time::Instant::now();
        let mut x = 0u64;
        while start.elapsed() < std::time::Duration::from_millis(60) {
            x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(7));
        }
        let after = super::process_time().expect("second reading");
        assert!(after >= before, "{after:?} < {before:?}");
        assert!(after > before, "60 ms of busy work used no CPU time");
    }
}
