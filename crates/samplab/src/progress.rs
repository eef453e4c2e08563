//! Long work: progress reports and interruption.
//!
//! The library's long computations (realizations of a sampler, spectra over sets,
//! integration studies, renders) take a [`Progress`]. They call [`Progress::advance`] as
//! units of work finish, and [`Progress::check`] between and within units, so that a front
//! end can draw a progress bar and stop the work promptly: once its stop flag is raised
//! (by a Ctrl-C handler, a SIGTERM handler, a Python thread), every later check returns
//! [`Error::Interrupted`], the parallel loops stop taking new work, and the call returns
//! that error without a result. Nothing the library writes is left half-written, because
//! every file is written whole and renamed into place ([`crate::io::write_atomic`]).
//!
//! ```
//! use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
//! use samplab::progress::Progress;
//! let (done, stop) = (AtomicU64::new(0), AtomicBool::new(false));
//! let report = |units| { done.fetch_add(units, Ordering::Relaxed); };
//! let progress = Progress::new(&report).stopped_by(&stop);
//! assert!(progress.advance(3).is_ok());
//! stop.store(true, Ordering::Relaxed);
//! assert_eq!(progress.advance(1), Err(samplab::Error::Interrupted));
//! assert_eq!(done.load(Ordering::Relaxed), 4);
//! ```

use std::sync::atomic::{AtomicBool, Ordering};

use crate::{Error, Result};

/// Where long work reports finished units and learns whether to stop.
#[derive(Clone, Copy, Default)]
pub struct Progress<'a> {
    report: Option<&'a (dyn Fn(u64) + Sync)>,
    stop: Option<&'a AtomicBool>,
}

impl std::fmt::Debug for Progress<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Progress").field("reports", &self.report.is_some()).field("stop", &self.stop).finish()
    }
}

impl<'a> Progress<'a> {
    /// No reports, never stops.
    pub const SILENT: Progress<'static> = Progress { report: None, stop: None };

    /// Report finished units to `report` (e.g. a progress bar's `inc`).
    pub fn new(report: &'a (dyn Fn(u64) + Sync)) -> Self {
        Progress { report: Some(report), stop: None }
    }

    /// No reports; the work stops once `stop` is true.
    pub fn until(stop: &'a AtomicBool) -> Self {
        Progress { report: None, stop: Some(stop) }
    }

    /// The same reports; the work stops once `stop` is true.
    #[must_use]
    pub fn stopped_by(self, stop: &'a AtomicBool) -> Self {
        Progress { stop: Some(stop), ..self }
    }

    /// Whether to go on.
    ///
    /// # Errors
    /// [`Error::Interrupted`] once the stop flag is raised.
    #[inline]
    pub fn check(&self) -> Result<()> {
        match self.stop {
            Some(flag) if flag.load(Ordering::Relaxed) => Err(Error::Interrupted),
            _ => Ok(()),
        }
    }

    /// `units` more units are finished; then [`Progress::check`].
    ///
    /// # Errors
    /// As [`Progress::check`].
    pub fn advance(&self, units: u64) -> Result<()> {
        if let Some(report) = self.report {
            report(units);
        }
        self.check()
    }
}
