//! Measures of point sets: discrepancies, t-values, conformance and spectra.

use crate::errors::err;
use crate::interrupt::interruptible;
use crate::points::{point_sets, shaped};
use numpy::{PyArray1, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use samplab::Seed;
use samplab::discrepancy::{Limits, Metric};
use samplab::progress::Progress;

/// The discrepancy `metric` of each set of a (sets, n, d) array.
#[pyfunction]
#[pyo3(signature = (metric, points, max_work=None))]
pub(crate) fn discrepancy(
    py: Python<'_>,
    metric: &str,
    points: PyReadonlyArray3<f64>,
    max_work: Option<f64>,
) -> PyResult<Vec<f64>> {
    let m = Metric::parse(metric).map_err(err)?;
    let limits = Limits::new(max_work).map_err(err)?;
    let sets = point_sets(&points)?;
    // the exact metrics and the L2 family's pair sums grow faster than the values
    let n = points.shape()[1];
    interruptible(py, points.len().saturating_mul(n), |stop| {
        let progress = Progress::until(stop);
        sets.par_iter()
            .enumerate()
            .map(|(k, s)| {
                progress.check()?;
                samplab::discrepancy::compute(&m, s, limits.stopped_by(progress)).map_err(|e| e.in_set(k))
            })
            .collect::<samplab::Result<Vec<f64>>>()
    })
}

/// The checks of `samplab conform` on `points` as samplab's `spec`, as `--json` prints them:
/// the sets are realizations, or with `res` the pixels of a film row by row at each of
/// `frames` frames from `frame`.
#[pyfunction]
#[pyo3(signature = (points, spec, seed=None, res=None, frame=0, single=false, ulps=0, frames=1))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one for one
pub(crate) fn conform<'py>(
    py: Python<'py>,
    points: PyReadonlyArray3<f64>,
    spec: &str,
    seed: Option<u64>,
    res: Option<(u32, u32)>,
    frame: u32,
    single: bool,
    ulps: u64,
    frames: u32,
) -> PyResult<Bound<'py, PyAny>> {
    use samplab::conform::{Claim, Layout, Precision};
    let sets = point_sets(&points)?;
    let last = frame.checked_add(frames).ok_or_else(|| err(format!("frames {frame} + {frames} past 2^32")))?;
    let layout = res.map_or(Layout::Sets, |(w, h)| Layout::frames(w, h, frame..last));
    let precision = if single { Precision::Single } else { Precision::Found };
    let claim = Claim { spec, layout, seed: seed.map(Seed), precision, ulps };
    let checks =
        interruptible(py, points.len(), |stop| samplab::conform::conform(&sets, &claim, &Progress::until(stop)))?;
    crate::convert::py_from(py, &checks)
}

/// The t of each projection of a sampler's nets at b^1 .. b^m points, as
/// `samplab t-values --json` prints it.
#[pyfunction]
#[pyo3(signature = (spec, dims, m, projection, base, seed, max_work=None))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one for one
pub(crate) fn t_values<'py>(
    py: Python<'py>,
    spec: &str,
    dims: usize,
    m: usize,
    projection: &str,
    base: Option<u32>,
    seed: u64,
    max_work: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    if m == 0 {
        return Err(err("m = 0: the nets start at m = 1"));
    }
    let sampler = samplab::sampler::build(spec).map_err(err)?;
    let limits = Limits::new(max_work).map_err(err)?;
    let text = interruptible(py, usize::MAX, |stop| {
        let limits = limits.stopped_by(Progress::until(stop));
        samplab::discrepancy::tvalue::projection_table(&sampler, dims, m, projection, base, Seed(seed), &limits)
            .map(|table| table.json(sampler.spec(), Seed(seed)))
    })?;
    crate::convert::py_from_text(py, &text)
}

/// A metric's canonical spec and flags ([`Metric::flags`]) as JSON.
#[pyfunction]
pub(crate) fn metric_flags<'py>(py: Python<'py>, metric: &str) -> PyResult<Bound<'py, PyAny>> {
    crate::convert::py_from(py, &Metric::parse(metric).map_err(err)?.flags())
}

/// Periodogram, amplitude of the expected spectrum and variance of the spectrum of a
/// (sets, n, d) stack, each an R^d array (index R/2 = DC), with their radial averages and
/// anisotropies (`samplab spectrum`'s numbers).
#[pyfunction]
#[pyo3(signature = (points, res, direct=false, tolerance=1e-9))]
pub(crate) fn spectrum<'py>(
    py: Python<'py>,
    points: PyReadonlyArray3<f64>,
    res: usize,
    direct: bool,
    tolerance: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let sets = point_sets(&points)?;
    let method = samplab::spectrum::Method::of(direct, tolerance);
    let st = interruptible(py, usize::MAX, |stop| {
        samplab::spectrum::statistics_with_progress(&sets, res, method, &Progress::until(stop))
    })?;
    statistics_dict(py, &st)
}

/// The spectrum statistics as `spectrum` returns them.
pub(crate) fn statistics_dict<'py>(
    py: Python<'py>,
    st: &samplab::spectrum::Statistics,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let shape: Vec<usize> = vec![st.res; st.dims];
    for (name, values) in [("periodogram", &st.periodogram), ("expected", &st.expected), ("variance", &st.variance)] {
        out.set_item(name, shaped(py, values.clone(), &shape)?)?;
        let (radial, anisotropy) = samplab::spectrum::radial(values, st.res, st.dims);
        out.set_item(format!("{name}_radial"), PyArray1::from_vec(py, radial))?;
        out.set_item(format!("{name}_anisotropy_db"), PyArray1::from_vec(py, anisotropy))?;
    }
    Ok(out)
}
