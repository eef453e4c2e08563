//! How much work a command does (after a signal, or before a refusal), in CPU seconds of
//! the process (all its threads) and its peak resident memory: what a loaded machine does
//! not stretch, as it stretches wall time.

use std::time::{Duration, Instant};

/// The CPU seconds a command may work after a signal: two threads busy for a second at most
/// (the wall-clock second these tests allowed before).
pub const STOP_CPU: f64 = 2.0;

/// CPU seconds the live process `pid` has used (user and system, from /proc).
pub fn cpu_seconds(pid: u32) -> f64 {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap();
    // after the command's closing parenthesis: field 3 (state) on; utime is 14, stime 15
    let fields: Vec<&str> = stat[stat.rfind(')').unwrap() + 2..].split_whitespace().collect();
    let ticks = fields[11].parse::<f64>().unwrap() + fields[12].parse::<f64>().unwrap();
    // SAFETY: sysconf reads a constant of the system.
    ticks / unsafe { libc::sysconf(libc::_SC_CLK_TCK) } as f64
}

/// Reap the child `pid`: how it ended, the CPU seconds it and the children it waited for used
/// in all, and the peak resident memory of any of them in bytes. Past `limit` it (and its
/// process group, if it leads one) is killed and this panics: a hang, not a slow stop.
pub fn reap(pid: u32, limit: Duration) -> (std::process::ExitStatus, f64, u64) {
    use std::os::unix::process::ExitStatusExt as _;
    let start = Instant::now();
    let pid = pid as libc::pid_t;
    loop {
        let (mut status, mut usage) = (0, unsafe { std::mem::zeroed::<libc::rusage>() });
        // SAFETY: wait4 on this test's own child, writing to locals.
        let got = unsafe { libc::wait4(pid, &raw mut status, libc::WNOHANG, &raw mut usage) };
        assert!(got >= 0, "wait4: {}", std::io::Error::last_os_error());
        if got == pid {
            let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
            let peak = u64::try_from(usage.ru_maxrss).unwrap_or(0) * 1024;
            return (
                std::process::ExitStatus::from_raw(status),
                seconds(usage.ru_utime) + seconds(usage.ru_stime),
                peak,
            );
        }
        if start.elapsed() > limit {
            // SAFETY: kill(2) on this test's own child and the group it may lead.
            unsafe {
                libc::kill(-pid, libc::SIGKILL);
                libc::kill(pid, libc::SIGKILL);
            }
            panic!("still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}
