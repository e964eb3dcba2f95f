//! Instructions retired by the process, from the CPU's hardware counter (Linux `perf_event_open`,
//! user space only, worker threads included). `None` where there is no such counter (most
//! virtual machines, other systems, or `perf_event_paranoid` forbidding it): then count with
//! `valgrind --tool=callgrind` instead (README, benchmark table). Instruction counts vary far
//! less with other load than times do.

/// A running count of the instructions of this thread and the threads it starts afterwards.
pub struct Counter {
    #[cfg(target_os = "linux")]
    fd: std::os::fd::OwnedFd,
}

#[cfg(target_os = "linux")]
mod sys {
    /// The first 64 bytes of the kernel's `perf_event_attr` (PERF_ATTR_SIZE_VER0), which the
    /// kernel accepts as a whole attribute.
    #[repr(C)]
    #[derive(Default)]
    pub struct Attr {
        pub kind: u32,
        pub size: u32,
        pub config: u64,
        pub sample_period: u64,
        pub sample_type: u64,
        pub read_format: u64,
        pub flags: u64,
        pub wakeup_events: u32,
        pub bp_type: u32,
        pub config1: u64,
    }
    pub const TYPE_HARDWARE: u32 = 0;
    pub const COUNT_INSTRUCTIONS: u64 = 1;
    /// Flag bits: start disabled, count threads started later, leave out kernel and hypervisor.
    pub const DISABLED: u64 = 1;
    pub const INHERIT: u64 = 1 << 1;
    pub const EXCLUDE_KERNEL: u64 = 1 << 5;
    pub const EXCLUDE_HV: u64 = 1 << 6;
    /// `PERF_EVENT_IOC_ENABLE`: `_IO('$', 0)`.
    pub const IOC_ENABLE: u64 = 0x2400;
}

impl Counter {
    /// Starts counting; `None` when the system offers no instruction counter.
    #[cfg(target_os = "linux")]
    pub fn start() -> Option<Counter> {
        use std::os::fd::{FromRawFd, OwnedFd};
        let attr = sys::Attr {
            kind: sys::TYPE_HARDWARE,
            size: std::mem::size_of::<sys::Attr>() as u32,
            config: sys::COUNT_INSTRUCTIONS,
            flags: sys::DISABLED | sys::INHERIT | sys::EXCLUDE_KERNEL | sys::EXCLUDE_HV,
            ..sys::Attr::default()
        };
        // SAFETY: `attr` is a valid, initialised attribute of the size it declares; the
        // arguments ask for this process (0) on any CPU (-1), without a group (-1).
        let fd = unsafe {
            libc::syscall(
                libc::SYS_perf_event_open,
                &attr as *const sys::Attr,
                0 as libc::pid_t,
                -1 as libc::c_int,
                -1 as libc::c_int,
                0 as libc::c_ulong,
            )
        };
        let fd = libc::c_int::try_from(fd).ok().filter(|&fd| fd >= 0)?;
        // SAFETY: the kernel just returned `fd` as a new descriptor that nothing else owns.
        let fd = unsafe { OwnedFd::from_raw_fd(fd) };
        // SAFETY: an ioctl without argument on the counter's own descriptor.
        let ok = unsafe {
            libc::ioctl(
                std::os::fd::AsRawFd::as_raw_fd(&fd),
                sys::IOC_ENABLE as _,
                0,
            )
        };
        (ok == 0).then_some(Counter { fd })
    }

    /// Starts counting; `None`: no instruction counter on this system.
    #[cfg(not(target_os = "linux"))]
    pub fn start() -> Option<Counter> {
        None
    }

    /// The instructions counted so far (threads that ended included).
    #[cfg(target_os = "linux")]
    pub fn read(&self) -> Option<u64> {
        use std::io::Read;
        let mut buf = [0u8; 8];
        let mut f = std::fs::File::from(self.fd.try_clone().ok()?);
        f.read_exact(&mut buf).ok()?;
        Some(u64::from_ne_bytes(buf))
    }

    /// The instructions counted so far.
    #[cfg(not(target_os = "linux"))]
    pub fn read(&self) -> Option<u64> {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::Counter;

    #[test]
    fn counts_grow_with_work_where_there_is_a_counter() {
        let Some(c) = Counter::start() else {
            eprintln!("no hardware instruction counter here: skipped");
            return;
        };
        let before = c.read().expect("first reading");
        let mut x = 0u64;
        for i in 0..1_000_000u64 {
            x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(i));
        }
        let after = c.read().expect("second reading");
        assert!(after > before + 1_000_000, "{before} -> {after}");
    }
}
