//! The process's allocator: the system's, with two guarantees for a command-line tool.
//!
//! - An allocation the system refuses ends the command with one line and exit code 2
//!   (after its temporary outputs are removed), instead of Rust's abort (exit 134): the
//!   library checks its large buffers against the memory available before any work
//!   ([`samplab::memory`]), and this catches whatever such a check does not foresee.
//! - `--max-memory` holds for every large allocation: the bytes held in blocks of at
//!   least [`COUNTED`] are counted, and one that would take the count over the limit is
//!   refused the same way.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};

/// Blocks from this size are counted against `--max-memory` (smaller ones are not: every
/// process has a few megabytes of them, and counting them would cost every allocation).
const COUNTED: usize = 1 << 16;

/// The limit set by `--max-memory`; 0 when none.
static LIMIT: AtomicU64 = AtomicU64::new(0);

/// Bytes held now in counted blocks.
static HELD: AtomicUsize = AtomicUsize::new(0);

/// Count counted blocks against `bytes` (`--max-memory`) from now on.
pub(crate) fn set_limit(bytes: Option<u64>) {
    LIMIT.store(bytes.unwrap_or(0), Ordering::Relaxed);
}

pub(crate) struct Checked;

/// Set by the first refusal: a thread refused after it waits for the first one's exit.
static REFUSED: AtomicBool = AtomicBool::new(false);

/// One line, no allocation (this runs inside the allocator), then the exit.
#[cold]
fn refuse(size: usize, why: &str) -> ! {
    use std::io::Write as _;
    if REFUSED.swap(true, Ordering::Relaxed) {
        loop {
            std::thread::park();
        }
    }
    let (value, unit) = match size {
        s if s >= 1 << 30 => (s as f64 / f64::from(1u32 << 30), "GiB"),
        s if s >= 1 << 20 => (s as f64 / f64::from(1u32 << 20), "MiB"),
        s => (s as f64 / 1024.0, "KiB"),
    };
    let _ = writeln!(
        std::io::stderr(),
        "samplab: error: out of memory: {why} {value:.1} {unit}; lower the sizes asked for, or set another limit with --max-memory"
    );
    samplab::io::abandon(2)
}

impl Checked {
    /// Count `size` more bytes, refusing them over the limit.
    fn take(size: usize) {
        if size < COUNTED {
            return;
        }
        let held = HELD.fetch_add(size, Ordering::Relaxed) + size;
        let limit = LIMIT.load(Ordering::Relaxed);
        if limit != 0 && held as u64 > limit {
            HELD.fetch_sub(size, Ordering::Relaxed);
            refuse(size, "over the --max-memory limit with a block of");
        }
    }

    fn give(size: usize) {
        if size >= COUNTED {
            HELD.fetch_sub(size, Ordering::Relaxed);
        }
    }

    fn got(ptr: *mut u8, size: usize) -> *mut u8 {
        if ptr.is_null() {
            Checked::give(size);
            refuse(size, "the system refused a block of");
        }
        huge_pages(ptr, size);
        ptr
    }
}

/// Blocks from this size ask for transparent huge pages.
const HUGE: usize = 4 << 20;

/// Ask the kernel to back the whole 2 MiB pages inside a block of at least [`HUGE`] bytes
/// with huge pages (where it allows them on request, as most Linux systems do): a 16 MiB
/// grid then costs 8 page faults instead of 4096, and freeing it one TLB invalidation per
/// 2 MiB on the other cores instead of one per 4 KiB (measured: on two threads, the faults
/// and invalidations of the spectra's buffers took more system time than the transforms).
/// Memory contents and results are unchanged; a refusal is harmless and ignored.
fn huge_pages(ptr: *mut u8, size: usize) {
    #[cfg(target_os = "linux")]
    if size >= HUGE {
        const PAGE: usize = 2 << 20;
        let start = (ptr as usize).next_multiple_of(PAGE);
        let end = (ptr as usize + size) / PAGE * PAGE;
        if end > start {
            // SAFETY: advice on whole pages inside a block this process holds; it changes
            // no contents, and its failure is ignored.
            unsafe { libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE) };
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (ptr, size);
}

// SAFETY: every call goes to the system allocator with the caller's layout; the wrapper
// only counts sizes and never returns a null pointer (it exits instead).
unsafe impl GlobalAlloc for Checked {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        Checked::take(layout.size());
        // SAFETY: the caller's layout, as GlobalAlloc::alloc requires.
        Checked::got(unsafe { System.alloc(layout) }, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        Checked::take(layout.size());
        // SAFETY: as alloc.
        Checked::got(unsafe { System.alloc_zeroed(layout) }, layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        Checked::give(layout.size());
        // SAFETY: ptr came from this allocator with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        Checked::take(new_size);
        // SAFETY: as GlobalAlloc::realloc requires, passed through.
        let out = unsafe { System.realloc(ptr, layout, new_size) };
        let out = Checked::got(out, new_size);
        Checked::give(layout.size());
        out
    }
}
