//! Memory: a large allocation is estimated and compared with what the process can have
//! before any work, and refused in one line ([`Error::Memory`]) when it does not fit,
//! instead of aborting the process halfway.
//!
//! What the process can have is the smallest of: the memory the kernel reports available
//! (`MemAvailable` in `/proc/meminfo`), the room left under the cgroup's limit
//! (`/sys/fs/cgroup/memory.max`), and the room left under the address-space limit
//! (`ulimit -v`, from `/proc/self/limits` and `/proc/self/status`). A front end can set its
//! own limit instead ([`set_limit`], the CLI's `--max-memory`). Where none of these can be
//! read (not Linux), only the allocator's own refusal is caught.

use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;

use crate::{Error, Result};

/// A buffer written from parallel tasks at entries no two of them share (a spectrum's
/// columns, a sort's scattered outputs), where the entries of one task are not one
/// contiguous slice.
#[derive(Clone, Copy)]
pub(crate) struct Disjoint<T>(pub(crate) *mut T);

impl<T> Disjoint<T> {
    /// Write entry k.
    ///
    /// # Safety
    /// k is inside the buffer, and no other task writes or reads entry k meanwhile.
    pub(crate) unsafe fn write(&self, k: usize, v: T) {
        // SAFETY: as the caller guarantees.
        unsafe { self.0.add(k).write(v) }
    }
}

// SAFETY: the tasks that share it write disjoint entries.
unsafe impl<T: Send> Send for Disjoint<T> {}
// SAFETY: as Send: no entry is written by two tasks, none read while they run.
unsafe impl<T: Send> Sync for Disjoint<T> {}

/// `items` cut into consecutive parts of the given lengths (each a parallel task's own
/// output, say).
pub(crate) fn split<T>(mut items: &mut [T], lengths: impl IntoIterator<Item = usize>) -> Vec<&mut [T]> {
    lengths
        .into_iter()
        .map(|len| {
            let (part, rest) = std::mem::take(&mut items).split_at_mut(len);
            items = rest;
            part
        })
        .collect()
}

/// Buffers of finished work, taken by the next: a fresh large buffer costs a page fault
/// per 4 KiB on its first writes, and with several threads each fault is a TLB shootdown on
/// every core (measured in the spectra: more system time than the transforms).
pub(crate) struct Pool<T>(std::sync::Mutex<Vec<T>>);

impl<T> Default for Pool<T> {
    fn default() -> Self {
        Pool(std::sync::Mutex::new(Vec::new()))
    }
}

impl<T> Pool<T> {
    /// One given back earlier, if any.
    pub(crate) fn take(&self) -> Option<T> {
        self.0.lock().ok().and_then(|mut pool| pool.pop())
    }

    /// Give these back for later takers.
    pub(crate) fn give(&self, items: impl IntoIterator<Item = T>) {
        if let Ok(mut pool) = self.0.lock() {
            pool.extend(items);
        }
    }
}

/// The limit set by [`set_limit`]; 0 when none.
static LIMIT: AtomicU64 = AtomicU64::new(0);

/// Use `bytes` as the memory available instead of what the system reports (`None`: the
/// system's figure again).
pub fn set_limit(bytes: Option<u64>) {
    LIMIT.store(bytes.unwrap_or(0), Ordering::Relaxed);
}

/// The bytes this process can still allocate: the limit set by [`set_limit`], else the
/// smallest of the system's figures (module docs), else `u64::MAX` when none is known.
pub fn available() -> u64 {
    match LIMIT.load(Ordering::Relaxed) {
        0 => system_available().unwrap_or(u64::MAX),
        limit => limit,
    }
}

/// The smallest of the system's figures, when one can be read.
fn system_available() -> Option<u64> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    // a "Name:   1234 kB" line of a /proc file
    let field = |text: &str, name: &str| -> Option<u64> {
        let line = text.lines().find(|l| l.starts_with(name))?;
        line[name.len()..].split_whitespace().next()?.parse::<u64>().ok().map(|kb| kb * 1024)
    };
    let meminfo = read("/proc/meminfo").and_then(|t| field(&t, "MemAvailable:"));
    let cgroup = (|| {
        let max: u64 = read("/sys/fs/cgroup/memory.max")?.trim().parse().ok()?;
        let current: u64 = read("/sys/fs/cgroup/memory.current")?.trim().parse().ok()?;
        Some(max.saturating_sub(current))
    })();
    let address_space = (|| {
        let limits = read("/proc/self/limits")?;
        let line = limits.lines().find(|l| l.starts_with("Max address space"))?;
        let soft: u64 = line["Max address space".len()..].split_whitespace().next()?.parse().ok()?;
        let size = field(&read("/proc/self/status")?, "VmSize:")?;
        Some(soft.saturating_sub(size))
    })();
    [meminfo, cgroup, address_space].into_iter().flatten().min()
}

/// Allocations below this are not compared with the system's figures, which take tens of
/// microseconds to read (more than the work of a small call, made per call from Python):
/// every process has this much. A limit set by [`set_limit`] still holds for them.
const UNCHECKED: u128 = 16 << 20;

/// Refuse `bytes` for `what` when they are more than [`available`].
///
/// # Errors
/// [`Error::Memory`], naming `what`, the bytes needed and the bytes available.
pub fn check(what: impl FnOnce() -> String, bytes: u128) -> Result<()> {
    if bytes < UNCHECKED && LIMIT.load(Ordering::Relaxed) == 0 {
        return Ok(());
    }
    let available = available();
    if bytes > u128::from(available) {
        return Err(Error::Memory { what: what(), need: bytes, available });
    }
    Ok(())
}

/// From how many elements a buffer is written in parallel ([`filled`], [`refill`]): its
/// first writes fault its pages in, which on one thread took about as long as a whole try of
/// dart throwing at 10^6 points; below, one thread is quicker than waking the others.
pub(crate) const FAULT_IN: usize = 1 << 20;

/// The elements one task writes of such a buffer.
pub(crate) const FAULT_CHUNK: usize = 1 << 16;

/// `len` copies of `value` (written in parallel from [`FAULT_IN`]).
pub(crate) fn filled<T: Copy + Send + Sync>(len: usize, value: T) -> Vec<T> {
    if len < FAULT_IN {
        return vec![value; len];
    }
    let mut v = Vec::with_capacity(len);
    #[cfg(target_os = "linux")]
    huge_pages(v.spare_capacity_mut());
    v.par_extend(rayon::iter::repeat_n(value, len));
    v
}

/// Every element set to `value` (in parallel from [`FAULT_IN`]).
pub(crate) fn refill<T: Copy + Send + Sync>(v: &mut [T], value: T) {
    if v.len() < FAULT_IN {
        return v.fill(value);
    }
    v.par_chunks_mut(FAULT_CHUNK).for_each(|c| c.fill(value));
}

/// `len` zeros (default values) for `what`, after [`check`]. Numbers come from the
/// allocator's zeroed pages, so the memory is only touched as it is filled.
///
/// # Errors
/// [`Error::Memory`].
pub fn zeroed<T: Clone + Default>(what: impl FnOnce() -> String, len: usize) -> Result<Vec<T>> {
    check(what, len as u128 * std::mem::size_of::<T>() as u128)?;
    let v = vec![T::default(); len];
    #[cfg(target_os = "linux")]
    huge_pages(&v);
    Ok(v)
}

/// Ask Linux to back a large, still untouched buffer with 2 MB pages (as numpy does for
/// its arrays): filling 256 MB of fresh 4 kB pages costs 65536 page faults, most of the time
/// of writing a large set (Sobol' 2^20 x 32: 70% in the kernel). Advice only: nothing
/// changes but the page size where the system allows it.
#[cfg(target_os = "linux")]
fn huge_pages<T>(v: &[T]) {
    const PAGE: usize = 4096;
    let (start, bytes) = (v.as_ptr() as usize, std::mem::size_of_val(v));
    if bytes < 1 << 22 {
        return;
    }
    let aligned = start.next_multiple_of(PAGE);
    // SAFETY: [aligned, start + bytes) lies inside the vector's allocation; MADV_HUGEPAGE
    // changes how the kernel backs the range, never its contents.
    unsafe {
        libc::madvise(aligned as *mut libc::c_void, start + bytes - aligned, libc::MADV_HUGEPAGE);
    }
}

/// A size in bytes from `4G`, `8GiB`, `512MB`, `100k` or a plain number of bytes: K, M,
/// G, T (with or without `iB`, any case) are powers of 1024; kB, MB, GB, TB powers of 1000.
///
/// # Errors
/// [`Error::Parse`] for anything else, or a size past 2^64 - 1 bytes.
pub fn parse_size(text: &str) -> Result<u64> {
    let bad = || Error::Parse {
        location: format!("'{text}'"),
        reason: "not a size (e.g. 8G, 8GiB, 512MB, 100k or bytes)".into(),
    };
    let t = text.trim();
    let digits = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = (&t[..digits], &t[digits..]);
    let prefix = |c: char| "kmgt".find(c.to_ascii_lowercase()).map(|i| i as i32 + 1);
    let mut chars = unit.chars();
    let scale = match (chars.next(), chars.as_str()) {
        (None, _) | (Some('b' | 'B'), "") => 1.0,
        (Some(p), rest) => {
            let power = prefix(p).ok_or_else(bad)?;
            match rest {
                "" | "i" | "iB" | "ib" | "IB" => 1024f64.powi(power),
                "B" | "b" => 1000f64.powi(power),
                _ => return Err(bad()),
            }
        }
    };
    let x: f64 = number.trim().parse().map_err(|_| bad())?;
    let bytes = (x * scale).round();
    // u64::MAX as f64 is 2^64: the sizes that fit are below it
    if !(1.0..u64::MAX as f64).contains(&bytes) {
        return Err(bad());
    }
    Ok(bytes as u64)
}

/// `bytes` for a person: `64.0 GiB` (exact bytes under 10 KiB).
pub fn human(bytes: u128) -> String {
    const UNITS: [&str; 6] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB"];
    let mut x = bytes as f64;
    let mut unit = 0;
    while x >= 1024.0 && unit + 1 < UNITS.len() {
        x /= 1024.0;
        unit += 1;
    }
    if bytes < 10 << 10 { format!("{bytes} B") } else { format!("{x:.1} {}", UNITS[unit]) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_in_powers_of_1024() {
        assert_eq!(parse_size("4G").unwrap(), 4 << 30);
        assert_eq!(parse_size("1.5k").unwrap(), 1536);
        assert_eq!(parse_size("100").unwrap(), 100);
        assert_eq!(parse_size("8GiB").unwrap(), 8 << 30);
        assert_eq!(parse_size("8gib").unwrap(), 8 << 30);
        assert_eq!(parse_size("512MB").unwrap(), 512_000_000);
        assert_eq!(parse_size("2kB").unwrap(), 2000);
        assert_eq!(parse_size("64B").unwrap(), 64);
        for bad in ["", "G", "-1G", "0", "nanM", "1e30T", "4X", "4GiBs", "4 G B", "GiB"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        assert_eq!(human(68_719_476_736), "64.0 GiB");
        assert_eq!(human(12), "12 B");
    }
}
