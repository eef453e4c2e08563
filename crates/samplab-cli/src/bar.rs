//! Progress bars on stderr, and a clean stop on Ctrl-C, SIGTERM or SIGHUP.
//!
//! A signal raises [`STOP`]; long work checks it (through [`Bar::progress`])
//! and stops, the command exits 130 saying so, and nothing is written: every output is
//! written whole and renamed into place at the end. A command that has not stopped [`GRACE`]
//! after the signal (a blocking open of a FIFO, a loop between checks) is ended then, after
//! its temporary outputs are removed ([`samplab::io::abandon`]).

use std::sync::atomic::{AtomicBool, Ordering};

use indicatif::{ProgressBar, ProgressStyle};
use samplab::progress::Progress;
use samplab::sampler::Plan;

/// Raised by the first signal.
pub(crate) static STOP: AtomicBool = AtomicBool::new(false);

/// The exit code of a command stopped by a signal (128 + SIGINT, as shells report it).
pub(crate) const STOPPED: u8 = 130;

/// How long after a signal the work may take to stop by itself.
const GRACE: std::time::Duration = std::time::Duration::from_millis(700);

/// Route Ctrl-C, SIGTERM and SIGHUP to [`STOP`].
pub(crate) fn install() {
    // when no handler can be installed, the signals keep their default action (exit)
    let _ = ctrlc::set_handler(|| {
        if !STOP.swap(true, Ordering::Relaxed) {
            // ctrlc's own thread: the first signal waits here, a second one finds it busy
            std::thread::sleep(GRACE);
        }
        crate::say!("samplab: interrupted: nothing was written");
        samplab::io::abandon(i32::from(STOPPED))
    });
}

/// A progress bar with a time estimate on stderr (hidden when stderr is not a terminal,
/// and for a single item), cleared when dropped.
pub(crate) struct Bar {
    bar: ProgressBar,
    report: Box<dyn Fn(u64) + Send + Sync>,
}

impl Bar {
    /// A bar over `len` items called `unit`.
    pub(crate) fn new(len: u64, unit: &str) -> Bar {
        let bar = if len < 2 { ProgressBar::hidden() } else { ProgressBar::new(len) };
        if let Ok(style) = ProgressStyle::with_template(&format!(
            "{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {unit} (eta {{eta}})"
        )) {
            bar.set_style(style);
        }
        let counter = bar.clone();
        Bar { bar, report: Box::new(move |k| counter.inc(k)) }
    }

    /// A bar over the making of `m` sets by `plan`: sets, or an optimizer's iterations
    /// (shown for a single set too).
    pub(crate) fn sets(plan: &Plan, m: usize) -> Bar {
        match plan.units() {
            1 => Bar::new(m as u64, "sets"),
            units => Bar::new(m as u64 * units, "iterations"),
        }
    }

    /// What the library's long calls take: this bar, stopped by a signal.
    pub(crate) fn progress(&self) -> Progress<'_> {
        Progress::new(&*self.report).stopped_by(&STOP)
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// A bar per experiment of `samplab reproduce`, one under the other (the report's
/// [`samplab_report::Event`]s drawn on stderr).
pub(crate) struct Experiments {
    bars: indicatif::MultiProgress,
    /// The bars of the experiments running, by their place in the run.
    running: std::sync::Mutex<std::collections::HashMap<usize, ProgressBar>>,
}

impl Experiments {
    pub(crate) fn new() -> Experiments {
        Experiments { bars: indicatif::MultiProgress::new(), running: Default::default() }
    }

    /// Draw `event`.
    pub(crate) fn show(&self, task: usize, event: samplab_report::Event<'_>) {
        use samplab_report::Event;
        let mut running = self.running.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        match event {
            Event::Started { paper, experiment } => {
                let bar = self.bars.add(ProgressBar::new(1));
                if let Ok(style) = ProgressStyle::with_template("{prefix:40} [{bar:30}] {pos}/{len} {elapsed}") {
                    bar.set_style(style);
                }
                bar.set_prefix(format!("{paper} {experiment}"));
                running.insert(task, bar);
            }
            Event::Length(units) => running.get(&task).iter().for_each(|b| b.set_length(units)),
            Event::Advanced(units) => running.get(&task).iter().for_each(|b| b.inc(units)),
            Event::Finished(_) => running.remove(&task).iter().for_each(ProgressBar::finish),
            _ => {}
        }
    }
}
