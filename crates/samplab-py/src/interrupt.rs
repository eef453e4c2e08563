//! Work run with the GIL released and stoppable by Ctrl-C.

use crate::errors::err;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

/// Jobs of fewer values than this run on the calling thread ([`interruptible`]): they
/// finish in well under a millisecond, less than the hand-off to the pool would cost.
pub(crate) const SMALL: usize = 1 << 16;

/// How long [`interruptible`] waits awake for the work's result before sleeping.
pub(crate) const AWAKE: Duration = Duration::from_micros(200);

/// Run `work` (of about `size` values) with the GIL released, stoppable by Ctrl-C. The work
/// runs on a thread of rayon's pool, given a stop flag that the library's long loops check
/// ([`samplab::progress`]); this thread waits for it and, every 50 ms, takes the GIL to let
/// Python run its signal handlers. When one raises (`KeyboardInterrupt` on Ctrl-C), the
/// flag is raised, the work stops at its next check, and the handler's exception is raised
/// in place of a result: nothing is returned or written.
///
/// Called from a thread of the pool (a Python callable that samplab evaluates, calling
/// samplab in turn), the work runs on that thread: waiting there for a task queued behind
/// it would never end, and the outer call already watches for signals.
pub(crate) fn interruptible<R: Send, E: std::fmt::Display + Send + 'static>(
    py: Python<'_>,
    size: usize,
    work: impl FnOnce(&AtomicBool) -> Result<R, E> + Send,
) -> PyResult<R> {
    interruptible_raising(py, size, &[], work)
}

/// [`interruptible`], also raising each flag of `also` on a signal: the stop flags of the
/// Python callables the work evaluates, so that their remaining batches are skipped.
pub(crate) fn interruptible_raising<R: Send, E: std::fmt::Display + Send + 'static>(
    py: Python<'_>,
    size: usize,
    also: &[&AtomicBool],
    work: impl FnOnce(&AtomicBool) -> Result<R, E> + Send,
) -> PyResult<R> {
    let stop = AtomicBool::new(false);
    if size < SMALL || rayon::current_thread_index().is_some() {
        return py.detach(|| work(&stop)).map_err(err);
    }
    py.detach(|| {
        rayon::in_place_scope(|scope| {
            let (tx, rx) = std::sync::mpsc::channel();
            let stop = &stop;
            // on a thread of rayon's pool: each parallel call in the work starts on that
            // thread's own queue, not handed to the pool and back (as the CLI's commands)
            scope.spawn(move |_| drop(tx.send(work(stop))));
            // a short job's result is awaited awake, not asleep: a generate of 16 jittered
            // points took 24 us with this thread asleep, 5.3 us awake, 2.4 us run on it
            let awake = std::time::Instant::now();
            let wait = || {
                while awake.elapsed() < AWAKE {
                    match rx.try_recv() {
                        Err(std::sync::mpsc::TryRecvError::Empty) => std::hint::spin_loop(),
                        Ok(result) => return Ok(result),
                        Err(std::sync::mpsc::TryRecvError::Disconnected) => return Err(RecvTimeoutError::Disconnected),
                    }
                }
                rx.recv_timeout(Duration::from_millis(50))
            };
            let mut raised = None;
            loop {
                match wait() {
                    Ok(result) => return raised.map_or_else(|| result.map_err(err), Err),
                    Err(RecvTimeoutError::Timeout) => {
                        if raised.is_none()
                            && let Err(e) = Python::attach(|py| py.check_signals())
                        {
                            stop.store(true, Ordering::Relaxed);
                            also.iter().for_each(|flag| flag.store(true, Ordering::Relaxed));
                            raised = Some(e);
                        }
                    }
                    // the work panicked: the scope re-raises its panic when it ends (pyo3
                    // turns it into a PanicException)
                    Err(RecvTimeoutError::Disconnected) => return Err(err("the computation failed")),
                }
            }
        })
    })
}
