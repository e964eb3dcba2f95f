//! Process memory figures from `/proc/self/status` (Linux; `None` elsewhere).

/// A `Vm*` field of `/proc/self/status` in KiB.
fn status_kib(field: &str) -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    text.lines().find_map(|l| {
        let rest = l.strip_prefix(field)?.strip_prefix(':')?;
        rest.trim().strip_suffix("kB")?.trim().parse().ok()
    })
}

/// Peak resident set size (VmHWM) in KiB.
pub fn peak_kib() -> Option<u64> {
    status_kib("VmHWM")
}

/// Current resident set size (VmRSS) in KiB.
pub fn current_kib() -> Option<u64> {
    status_kib("VmRSS")
}
