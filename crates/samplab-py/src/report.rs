//! `samplab reproduce` from Python, with progress reported to a callback.

use crate::errors::err;
use crate::interrupt::interruptible;
use pyo3::prelude::*;
use samplab::Seed;
use std::sync::atomic::Ordering;
use std::sync::{Mutex, PoisonError};

/// Run the reproduction into `out` (replaced when complete, if samplab made it or `force`);
/// returns the claims as JSON. `progress(paper, experiment, done, total)` is called as each
/// experiment starts, advances (at most once per percent) and finishes; an exception it
/// raises stops the run and is raised here.
#[pyfunction]
#[pyo3(signature = (out, full=false, only=None, seed=None, force=false, progress=None))]
#[allow(clippy::too_many_arguments)] // the keywords of samplab.reproduce
pub(crate) fn reproduce<'py>(
    py: Python<'py>,
    out: &str,
    full: bool,
    only: Option<Vec<String>>,
    seed: Option<u64>,
    force: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let papers = samplab_report::paper::all();
    let chosen: Vec<&samplab_report::Paper> = match &only {
        None => papers.iter().collect(),
        Some(keys) => {
            for k in keys {
                if !papers.iter().any(|p| p.key == k) {
                    return Err(err(format!("unknown paper '{k}' ({})", samplab_report::paper::keys().join(", "))));
                }
            }
            papers.iter().filter(|p| keys.iter().any(|k| k == p.key)).collect()
        }
    };
    let options = samplab_report::Options {
        scale: if full { samplab_report::Scale::Full } else { samplab_report::Scale::Fast },
        seed: seed.map_or(Seed::DEFAULT, Seed),
        out: out.into(),
        replace: if force { samplab::io::Replace::Force } else { samplab::io::Replace::IfOurs },
    };
    let failed: Mutex<Option<PyErr>> = Mutex::new(None);
    let result = interruptible(py, usize::MAX, |stop| {
        // what each running experiment has told, by its place in the run
        let state = Mutex::new(std::collections::HashMap::<usize, Watched>::new());
        let watch = |task: usize, event: samplab_report::Event<'_>| {
            let Some(callback) = &progress else { return };
            let Some(args) = state.lock().unwrap_or_else(PoisonError::into_inner).entry(task).or_default().hear(event)
            else {
                return;
            };
            Python::attach(|py| {
                if let Err(e) = callback.call1(py, args) {
                    stop.store(true, Ordering::Relaxed);
                    failed.lock().unwrap_or_else(PoisonError::into_inner).get_or_insert(e);
                }
            });
        };
        samplab_report::reproduce(&chosen, &options, stop, &watch)
    });
    if let Some(e) = failed.into_inner().unwrap_or_else(PoisonError::into_inner) {
        return Err(e);
    }
    let claims = result?;
    let list: Vec<serde_json::Value> = claims
        .iter()
        .map(|(paper, c)| serde_json::json!({ "paper": paper, "id": c.id, "verdict": c.verdict() }))
        .collect();
    crate::convert::py_from(py, &list)
}

/// What a Python progress callback has been told of one running experiment.
#[derive(Default)]
pub(crate) struct Watched {
    paper: String,
    experiment: String,
    done: u64,
    total: u64,
    percent: u64,
}

impl Watched {
    /// The callback's arguments (paper, experiment, done, total) for `event`, or None when
    /// it need not be called (an advance within the same percent).
    fn hear(&mut self, event: samplab_report::Event<'_>) -> Option<(String, String, u64, u64)> {
        match event {
            samplab_report::Event::Started { paper, experiment } => {
                *self = Watched { paper: paper.into(), experiment: experiment.into(), ..Watched::default() };
            }
            samplab_report::Event::Length(total) => self.total = total,
            samplab_report::Event::Advanced(units) => {
                self.done += units;
                let percent = (self.done * 100).checked_div(self.total).unwrap_or(0);
                if percent == self.percent {
                    return None;
                }
                self.percent = percent;
            }
            samplab_report::Event::Finished(_) => self.done = self.done.max(self.total),
            _ => return None,
        }
        Some((self.paper.clone(), self.experiment.clone(), self.done, self.total))
    }
}
