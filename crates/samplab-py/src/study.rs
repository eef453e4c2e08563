//! Studies: integration and prediction, and the chunked studies any executor runs.

use crate::errors::err;
use crate::interrupt::{interruptible, interruptible_raising};
use crate::measure::statistics_dict;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use samplab::Seed;
use samplab::progress::Progress;
use samplab_render::study::Study;
use std::sync::atomic::AtomicBool;

/// Every study kind's parameters, as JSON ([`samplab_render::study::KINDS`]).
#[pyfunction]
pub(crate) fn study_kinds(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    crate::convert::py_from(py, &samplab_render::study::KINDS)
}

/// A study's chunk list: the constructor's arguments (JSON, `{"kind": ..., arguments}`,
/// read by [`samplab_render::study::read`]) checked before any work and cut into chunks;
/// returns the description as the CLI writes it, the chunks, and whether chunk 0's result
/// feeds the others ([`samplab_render::study::Study`]).
#[pyfunction]
pub(crate) fn study_plan(arguments: &str) -> PyResult<(String, Vec<Vec<u64>>, bool)> {
    let (study, chunks) =
        samplab_render::study::read(arguments).and_then(|(s, per_chunk)| s.plan(per_chunk)).map_err(err)?;
    Ok((study.to_json(), chunks, study.first_feeds_the_rest()))
}

/// A study's checkpoint folder: finished chunks kept and read back, each checked
/// ([`samplab::study::Checkpoint`]).
#[pyclass(module = "samplab._samplab", frozen)]
pub(crate) struct Checkpoint(samplab::study::Checkpoint);

#[pymethods]
impl Checkpoint {
    #[new]
    fn new(folder: std::path::PathBuf, fingerprint: &str, manifest: &str) -> PyResult<Self> {
        samplab::study::Checkpoint::open(&folder, fingerprint, manifest).map(Checkpoint).map_err(err)
    }

    /// Keeps chunk `chunk`'s bytes.
    fn save(&self, chunk: usize, data: &[u8]) -> PyResult<()> {
        self.0.save(chunk, data).map_err(err)
    }

    /// The kept chunks among the first `chunks`: (chunk, bytes) pairs.
    fn load<'py>(&self, py: Python<'py>, chunks: usize) -> PyResult<Vec<(usize, Bound<'py, PyBytes>)>> {
        let found = self.0.load(chunks).map_err(err)?;
        Ok(found.into_iter().map(|(i, data)| (i, PyBytes::new(py, &data))).collect())
    }
}

/// One chunk of a study, as bytes (what a worker returns and a checkpoint keeps); `first`
/// is chunk 0's bytes where they feed the others; `function` the integrand of an
/// integration study that declares one (`d` and `exact`).
#[pyfunction]
#[pyo3(signature = (description, chunk, first=None, function=None))]
pub(crate) fn study_chunk<'py>(
    py: Python<'py>,
    description: &str,
    chunk: Vec<u64>,
    first: Option<Vec<u8>>,
    function: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyBytes>> {
    let study = Study::from_json(description).map_err(err)?;
    let given = match (&function, &study) {
        (None, _) => None,
        (
            Some(f),
            Study::Library(samplab::study::Description::Integrate { d: Some(d), exact: Some(exact), seed, .. }),
        ) => Some(crate::integrand::Given::from_python(f, *seed, *d, Some(*exact))?.0),
        (Some(_), _) => return Err(err("a function was given to a study that declares no integrand function")),
    };
    let data = interruptible(py, usize::MAX, |stop| {
        study.compute(
            &chunk,
            first.as_deref(),
            given.as_ref().map(crate::integrand::Given::integrand),
            &Progress::until(stop),
        )
    });
    if let Some(e) = given.as_ref().and_then(crate::integrand::Given::failure) {
        return Err(e);
    }
    Ok(PyBytes::new(py, &data?))
}

/// Every chunk's bytes, in chunk order, merged: (JSON, CSV, the spectrum statistics as
/// `spectrum` returns them or None).
#[pyfunction]
pub(crate) fn study_merge<'py>(
    py: Python<'py>,
    description: &str,
    parts: Vec<Vec<u8>>,
) -> PyResult<(String, String, Option<Bound<'py, PyDict>>)> {
    let study = Study::from_json(description).map_err(err)?;
    let merged = py.detach(|| study.merge(&parts)).map_err(err)?;
    let statistics = merged.statistics.as_ref().map(|st| statistics_dict(py, st)).transpose()?;
    Ok((merged.json, merged.csv, statistics))
}

/// An integration study, as `samplab integrate --json` prints it: {"rows": [...], "fits": [...]}.
#[pyfunction]
pub(crate) fn integrate<'py>(
    py: Python<'py>,
    samplers: Vec<String>,
    integrand: &str,
    ns: Vec<usize>,
    sets: usize,
    instances: usize,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let d = samplab::study::Description::Integrate {
        samplers,
        integrand: integrand.into(),
        n: ns,
        sets,
        instances,
        seed,
        d: None,
        exact: None,
    };
    let merged = interruptible(py, usize::MAX, |stop| d.run(&Progress::until(stop)))?;
    crate::convert::py_from_text(py, &merged.json)
}

/// An integration study of a callable of `dims` dimensions with integral `exact` (every
/// instance the same function), as [`integrate`] returns it.
#[pyfunction]
pub(crate) fn integrate_given<'py>(
    py: Python<'py>,
    samplers: Vec<String>,
    f: Bound<'_, PyAny>,
    ns: Vec<usize>,
    sets: usize,
    seed: u64,
    given: (usize, f64),
) -> PyResult<Bound<'py, PyAny>> {
    let (dims, exact) = given;
    let (given, name) = crate::integrand::Given::from_python(&f, seed, dims, Some(exact))?;
    let study = samplab::study::Description::Integrate {
        samplers,
        integrand: name,
        n: ns,
        sets,
        instances: 1,
        seed,
        d: Some(dims),
        exact: Some(exact),
    };
    let merged = interruptible_raising(py, usize::MAX, &given.stop().into_iter().collect::<Vec<_>>(), |stop| {
        study.run_with(Some(given.integrand()), &Progress::until(stop))
    });
    if let Some(e) = given.failure() {
        return Err(e);
    }
    crate::convert::py_from_text(py, &merged?.json)
}

/// A prediction study, as `samplab predict --json` prints it: {"rows", "ranking", ...};
/// every registered sampler of the integrands' dimension when `samplers` is empty. Each
/// integrand is a spec, a 2D array or a callable of `dims` dimensions (its integral in
/// `exact`, in order, needed to measure).
#[pyfunction]
#[allow(clippy::too_many_arguments)] // the keywords of samplab.predict, checked there
pub(crate) fn predict<'py>(
    py: Python<'py>,
    samplers: Vec<String>,
    integrands: Vec<Bound<'_, PyAny>>,
    ns: Vec<usize>,
    res: usize,
    sets: usize,
    measure: Option<(usize, bool)>,
    seed: u64,
    dims: usize,
    exact: Vec<f64>,
    cache: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let mut exact = exact.into_iter();
    let mut given = Vec::new();
    for value in &integrands {
        if value.is_callable() && !(1..=2).contains(&dims) {
            return Err(err(format!("d = {dims}: a callable integrand is 1D or 2D here")));
        }
        let known = if value.is_callable() { exact.next() } else { None };
        given.push(crate::integrand::Given::from_python(value, seed, dims, known)?);
    }
    if measure.is_some()
        && let Some((_, name)) = given.iter().find(|(g, _)| !g.has_exact())
    {
        return Err(err(format!("{name}: measuring needs the callable's integral: pass exact=")));
    }
    let borrowed: Vec<(&dyn samplab::integrand::Integrand, String)> =
        given.iter().map(|(g, name)| (g.integrand(), name.clone())).collect();
    let dims = borrowed.first().map_or(2, |(f, _)| f.dims());
    let samplers = if samplers.is_empty() {
        samplab::predict::every_sampler(dims)
    } else {
        samplers.iter().map(|s| samplab::sampler::build(s)).collect::<Result<_, _>>().map_err(err)?
    };
    let cache = if cache { samplab::predict::Cache::user() } else { None };
    let study = samplab::predict::Study {
        samplers: &samplers,
        integrands: &borrowed,
        ns: &ns,
        res,
        sets,
        measure,
        seed: Seed(seed),
        cache: cache.as_ref(),
    };
    let flags: Vec<&AtomicBool> = given.iter().filter_map(|(g, _)| g.stop()).collect();
    let outcome = interruptible_raising(py, usize::MAX, &flags, |stop| study.run(&Progress::until(stop)));
    if let Some(e) = given.iter().find_map(|(g, _)| g.failure()) {
        return Err(e);
    }
    crate::convert::py_from(py, &outcome?)
}
