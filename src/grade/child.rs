//! Running one child process under limits: wall time (the child's own limit plus a grace
//! period, then a kill), memory (an address-space rlimit on Unix, besides the child's own
//! `--max-memory`), and bounded capture of its standard error.

use std::io::Read;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Bytes of standard error kept from the start and from the end of the child's output.
const KEEP: usize = 4096;
/// How often a running child is looked at.
const POLL: Duration = Duration::from_millis(20);

/// The limits of one child process.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChildLimits {
    /// Wall time after which the child is killed (its own limit plus a grace period).
    pub kill_after: Duration,
    /// Address-space limit in bytes (Unix), `None` for none.
    pub address_space: Option<u64>,
}

/// How a child process ended.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ChildEnd {
    /// The exit code, if it exited.
    pub code: Option<i32>,
    /// The signal that ended it, if one did (Unix).
    pub signal: Option<i32>,
    /// True when it outlived `kill_after` and was killed.
    pub killed: bool,
    /// The start and end of its standard error (what was cut is marked).
    pub stderr: String,
    /// Wall time it ran.
    pub wall: Duration,
}

/// Bytes of standard output kept by [`run_capturing`].
const KEEP_OUT: usize = 1 << 20;

/// Runs `cmd` (standard output discarded) under `limits`; `Err` when it cannot be started.
pub fn run(cmd: Command, limits: &ChildLimits) -> Result<ChildEnd, String> {
    run_with(cmd, limits, false).map(|(end, _)| end)
}

/// Runs `cmd` under `limits` and also returns the first MiB of its standard output.
pub fn run_capturing(cmd: Command, limits: &ChildLimits) -> Result<(ChildEnd, String), String> {
    run_with(cmd, limits, true)
}

fn run_with(
    mut cmd: Command,
    limits: &ChildLimits,
    capture: bool,
) -> Result<(ChildEnd, String), String> {
    let out = if capture {
        Stdio::piped()
    } else {
        Stdio::null()
    };
    cmd.stdin(Stdio::null()).stdout(out).stderr(Stdio::piped());
    limit_memory(&mut cmd, limits.address_space);
    let start = Instant::now();
    let mut child = cmd
        .spawn()
        .map_err(|e| format!("cannot start {}: {e}", cmd.get_program().to_string_lossy()))?;
    let err_reader = child
        .stderr
        .take()
        .map(|err| std::thread::spawn(move || head_and_tail(err, KEEP)));
    let out_reader = child
        .stdout
        .take()
        .map(|out| std::thread::spawn(move || head_and_tail(out, KEEP_OUT)));
    let mut killed = false;
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Ok(s),
            Ok(None) if start.elapsed() >= limits.kill_after => {
                killed = true;
                let _ = child.kill();
                break child.wait();
            }
            Ok(None) => std::thread::sleep(POLL),
            Err(e) => break Err(e),
        }
    }
    .map_err(|e| format!("waiting for a child process: {e}"))?;
    let wall = start.elapsed();
    let joined = |h: Option<std::thread::JoinHandle<String>>| {
        h.and_then(|h| h.join().ok()).unwrap_or_default()
    };
    let end = ChildEnd {
        code: status.code(),
        signal: signal_of(&status),
        killed,
        stderr: joined(err_reader),
        wall,
    };
    Ok((end, joined(out_reader)))
}

#[cfg(unix)]
fn signal_of(s: &std::process::ExitStatus) -> Option<i32> {
    std::os::unix::process::ExitStatusExt::signal(s)
}

#[cfg(not(unix))]
fn signal_of(_: &std::process::ExitStatus) -> Option<i32> {
    None
}

/// Sets the child's address-space rlimit, so that a run whose allocations outpace the
/// runtime's own memory check fails to allocate instead of taking the machine's memory.
#[cfg(target_os = "linux")]
fn limit_memory(cmd: &mut Command, bytes: Option<u64>) {
    use std::os::unix::process::CommandExt;
    let Some(bytes) = bytes else { return };
    let lim = libc::rlimit {
        rlim_cur: bytes as libc::rlim_t,
        rlim_max: bytes as libc::rlim_t,
    };
    // SAFETY: the closure runs in the forked child before exec and only calls setrlimit,
    // which is async-signal-safe; it touches no memory shared with the parent.
    unsafe {
        cmd.pre_exec(move || {
            if libc::setrlimit(libc::RLIMIT_AS, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
}

#[cfg(not(target_os = "linux"))]
fn limit_memory(_cmd: &mut Command, _bytes: Option<u64>) {}

/// The first and last `keep` bytes of `r` (read to its end, never held whole).
fn head_and_tail(mut r: impl Read, keep: usize) -> String {
    let mut head = Vec::new();
    let mut tail: std::collections::VecDeque<u8> = std::collections::VecDeque::new();
    let mut cut = false;
    let mut buf = [0u8; 8192];
    while let Ok(n) = r.read(&mut buf) {
        if n == 0 {
            break;
        }
        for &b in &buf[..n] {
            if head.len() < keep {
                head.push(b);
            } else {
                tail.push_back(b);
                if tail.len() > keep {
                    tail.pop_front();
                    cut = true;
                }
            }
        }
    }
    let mut text = String::from_utf8_lossy(&head).into_owned();
    if cut {
        text.push_str("\n[... cut ...]\n");
    }
    text.push_str(&String::from_utf8_lossy(
        &tail.into_iter().collect::<Vec<u8>>(),
    ));
    text
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    #[test]
    fn a_hanging_child_is_killed_after_its_time() {
        let mut cmd = Command::new("sleep");
        cmd.arg("30");
        let limits = ChildLimits {
            kill_after: Duration::from_millis(200),
            address_space: None,
        };
        let end = run(cmd, &limits).unwrap();
        assert!(end.killed);
        assert_eq!(end.code, None);
        assert_eq!(end.signal, Some(9));
    }

    #[test]
    fn exit_code_and_stderr_are_kept() {
        let mut cmd = Command::new("sh");
        cmd.args(["-c", "echo oops >&2; exit 4"]);
        let limits = ChildLimits {
            kill_after: Duration::from_secs(30),
            address_space: Some(1 << 30),
        };
        let end = run(cmd, &limits).unwrap();
        assert_eq!((end.code, end.killed), (Some(4), false));
        assert_eq!(end.stderr.trim(), "oops");
    }

    #[test]
    fn a_flood_on_stderr_is_cut_not_kept() {
        let text = vec![b'x'; 100_000];
        let kept = head_and_tail(&text[..], KEEP);
        assert!(kept.len() < 3 * KEEP, "{}", kept.len());
        assert!(kept.contains("[... cut ...]"));
    }
}
