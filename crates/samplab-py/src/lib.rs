//! `samplab._samplab`: the native half of the Python package, thin over the library (no
//! second implementation of anything). The pure-Python half (`python/samplab`) adds the
//! docstrings users read, argument checks that are Python's business (array shapes and
//! dtypes), and the scipy.stats.qmc engine.
//!
//! Every call that does real work releases the GIL; every samplab error becomes a
//! `samplab.Error` (a `ValueError`) carrying the CLI's one-line message. Long calls can be
//! stopped with Ctrl-C (`interruptible`).
//!
//! The crate has no Rust tests (pytest tests it through Python), so its test build is empty:
//! `cargo test --workspace --lib` builds every library's test harness, `test = false` or
//! not, and this one cost 15 s of the tests' build for nothing.
#![cfg(not(test))]

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::sync::{Mutex, PoisonError};
use std::time::Duration;

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArray3, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use rayon::prelude::*;
use samplab::discrepancy::{Limits, Metric};
use samplab::progress::Progress;
use samplab::registry::{Entry, Registry};
use samplab::spec::{Default, Kind};
use samplab::{PointSet, Seed};
use samplab_render::study::Study;

mod integrand;
mod sampler;

// named in the package it is raised from, so that it pickles (Dask sends it between processes)
create_exception!(samplab, Error, PyValueError, "Every samplab error: its message names what is wrong and where.");

/// An error as `samplab.Error`, or as the subclass of it (defined in the package) that also
/// derives from the matching built-in for the library's unknown names (`LookupError`),
/// memory refusals (`MemoryError`), file failures (`OSError`) and work limits, with the
/// failure's fields as attributes.
pub(crate) fn err<E: std::fmt::Display + 'static>(e: E) -> PyErr {
    let any = &e as &dyn std::any::Any;
    let library = any.downcast_ref::<samplab::Error>().or_else(|| match any.downcast_ref::<samplab_render::Error>() {
        Some(samplab_render::Error::Samplab(e)) => Some(e),
        _ => match any.downcast_ref::<samplab_report::Error>() {
            Some(samplab_report::Error::Samplab(e)) => Some(e),
            _ => None,
        },
    });
    let (file, message) = match any.downcast_ref::<samplab_render::Error>() {
        Some(samplab_render::Error::Image { path, .. }) => (Some(path.clone()), e.to_string()),
        Some(e @ samplab_render::Error::PathOutsideScene { .. }) => {
            (None, format!("{e}; allow it with allow_paths_outside_scene=True"))
        }
        _ => (None, library.map_or_else(|| e.to_string(), in_keywords)),
    };
    typed(library.map(samplab::Error::innermost), file, &message).unwrap_or_else(|| Error::new_err(message))
}

/// A library error's message, with the hints that name Python's keywords.
fn in_keywords(e: &samplab::Error) -> String {
    match e {
        samplab::Error::WorkLimit { .. } => format!("{e}; raise it with max_work"),
        samplab::Error::InSet { set, error } => format!("set {set}: {}", in_keywords(error)),
        samplab::Error::ForeignEntry { folder, entry } => {
            format!(
                "{folder}: holds '{entry}', which samplab did not write; name a new folder, or pass force=True to replace it"
            )
        }
        e => e.to_string(),
    }
}

/// The typed exception for a library failure, when it has one.
fn typed(library: Option<&samplab::Error>, file: Option<String>, message: &str) -> Option<PyErr> {
    use samplab::Error as E;
    Python::attach(|py| -> PyResult<Option<PyErr>> {
        let make = |class: &str| py.import("samplab")?.getattr(class)?.call1((message,));
        let instance = match (library, file.as_ref()) {
            (Some(E::UnknownName { kind, name, suggestions }), _) => {
                let e = make("UnknownNameError")?;
                e.setattr("kind", *kind)?;
                e.setattr("name", name)?;
                e.setattr("suggestions", suggestions.clone())?;
                e
            }
            (Some(E::Memory { need, available, .. }), _) => {
                let e = make("MemoryLimitError")?;
                e.setattr("need", *need)?;
                e.setattr("available", *available)?;
                e
            }
            (Some(E::WorkLimit { work, limit, .. }), _) => {
                let e = make("WorkLimitError")?;
                e.setattr("work", *work)?;
                e.setattr("limit", *limit)?;
                e
            }
            (Some(E::Io { path, .. }), _) | (None, Some(path)) => {
                let e = make("FileError")?;
                e.setattr("path", path)?;
                e
            }
            _ => return Ok(None),
        };
        Ok(Some(PyErr::from_value(instance)))
    })
    .ok()
    .flatten()
}

/// Jobs of fewer values than this run on the calling thread ([`interruptible`]): they
/// finish in well under a millisecond, less than the hand-off to the pool would cost.
const SMALL: usize = 1 << 16;

/// How long [`interruptible`] waits awake for the work's result before sleeping.
const AWAKE: Duration = Duration::from_micros(200);

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
fn interruptible_raising<R: Send, E: std::fmt::Display + Send + 'static>(
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

/// The seed the CLI uses when none is given.
#[pyfunction]
fn default_seed() -> u64 {
    Seed::DEFAULT.0
}

/// One registry's entries as dictionaries: name, aliases, summary, parameters (name, kind,
/// default, range, doc), references, and the kind-specific details `samplab list` prints.
fn entries<'py, E: Entry>(py: Python<'py>, registry: &Registry<E>) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for e in registry.iter() {
        let a = e.about();
        let d = PyDict::new(py);
        d.set_item("name", a.name)?;
        d.set_item("aliases", a.aliases.to_vec())?;
        d.set_item("summary", a.summary)?;
        d.set_item("references", a.references.to_vec())?;
        d.set_item("details", e.details())?;
        let params = PyList::empty(py);
        for p in a.params {
            let q = PyDict::new(py);
            q.set_item("name", p.name)?;
            q.set_item("doc", p.doc)?;
            q.set_item("range", p.range_text())?;
            q.set_item("kind", p.kind.name())?;
            match p.kind {
                Kind::Real { min, max } | Kind::Reals { min, max } => {
                    q.set_item("min", min)?;
                    q.set_item("max", max)?;
                }
                Kind::Int { min, max } => {
                    q.set_item("min", min)?;
                    q.set_item("max", max)?;
                }
                Kind::Choice(c) => q.set_item("choices", c.to_vec())?,
                _ => {}
            }
            match p.default {
                Default::Number(x) => q.set_item("default", x)?,
                Default::Int(x) => q.set_item("default", x)?,
                _ => q.set_item("default", p.default_text())?,
            }
            params.append(q)?;
        }
        d.set_item("params", params)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The entries of one registry: samplers, metrics, warps, integrands, formats or scenes.
#[pyfunction]
fn registry<'py>(py: Python<'py>, kind: &str) -> PyResult<Bound<'py, PyList>> {
    match kind {
        "samplers" => entries(py, &samplab::sampler::SAMPLERS),
        "metrics" => entries(py, &samplab::discrepancy::METRICS),
        "warps" => entries(py, &samplab::warp::WARPS),
        "integrands" => entries(py, &samplab::integrand::INTEGRANDS),
        "formats" => entries(py, &samplab::io::FORMATS),
        "scenes" => entries(py, &samplab_render::scenes::SCENES),
        "pixels" => entries(py, &samplab::pixel::PIXEL_SAMPLERS),
        _ => Err(err(format!(
            "unknown registry '{kind}' (samplers, metrics, warps, integrands, formats, scenes, pixels)"
        ))),
    }
}

/// A flat vector as an array of `shape`.
pub(crate) fn shaped<'py>(py: Python<'py>, data: Vec<f64>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
}

/// Every value of `frames` frames of a film (width, height, spp, dims) from the pixel
/// sampler `spec` (with `per_pixel`, the point-set sequence `spec` served per pixel, even
/// where a pixel sampler has its name), as an array (frames, height, width, spp, dims): the
/// bytes of `samplab pixels`.
#[pyfunction]
#[pyo3(signature = (spec, film, frames, seed, per_pixel=false))]
fn pixels<'py>(
    py: Python<'py>,
    spec: &str,
    film: (u32, u32, u32, u32),
    frames: u32,
    seed: u64,
    per_pixel: bool,
) -> PyResult<Bound<'py, PyAny>> {
    if frames == 0 {
        return Err(err("frames = 0: at least one frame"));
    }
    let (width, height, spp, dims) = film;
    let film = samplab::pixel::Film { width, height, spp, dims };
    let data = interruptible(py, usize::MAX, |stop| {
        let stop = Progress::until(stop);
        let pixels = if per_pixel {
            samplab::pixel::per_pixel(spec, film, Seed(seed))?
        } else {
            samplab::pixel::prepare_with(spec, film, Seed(seed), &stop)?
        };
        pixels.fill_with(frames, &stop)
    })?;
    shaped(py, data, &[frames, height, width, spp, dims].map(|k| k as usize))
}

/// The CUDA source of `samplab.gpu`'s kernels, one text that NVRTC compiles (CuPy's
/// RawModule): the header-only samplers' tables and header, then the kernels of
/// `crates/samplab-c/examples/cuda/fill.cu`, each file in the place of its `#include`.
#[pyfunction]
fn cuda_source() -> String {
    const TABLES: &str = include_str!("../../samplab-c/include/samplab/tables.hpp");
    const SAMPLERS: &str = include_str!("../../samplab-c/include/samplab/samplers.hpp");
    const KERNELS: &str = include_str!("../../samplab-c/examples/cuda/fill.cu");
    KERNELS.replace("#include <samplab/samplers.hpp>", &SAMPLERS.replace("#include \"tables.hpp\"", TABLES))
}

/// The seed of pixel (x, y) in `frame` under `seed`, under which a point-set sequence
/// served per pixel draws its points.
#[pyfunction]
fn pixel_seed(seed: u64, x: u32, y: u32, frame: u32) -> u64 {
    samplab::pixel::pixel_seed(Seed(seed), [x, y], frame).0
}

/// A tileable blue-noise mask by void-and-cluster, (size, size, channels): the bytes of
/// `samplab mask -o FILE.npy`.
#[pyfunction]
fn blue_noise_mask<'py>(py: Python<'py>, size: usize, channels: usize, seed: u64) -> PyResult<Bound<'py, PyAny>> {
    let mask = py.detach(|| samplab::pixel::mask::Mask::void_and_cluster(size, channels, Seed(seed))).map_err(err)?;
    shaped(py, mask.values().to_vec(), &[size, size, channels])
}

/// Point sets from a C-contiguous float64 array of shape (sets, n, d), every coordinate
/// finite (the Python side makes the array contiguous).
fn point_sets(points: &PyReadonlyArray3<f64>) -> PyResult<Vec<PointSet>> {
    let shape = points.shape();
    let (sets, n, d) = (shape[0], shape[1], shape[2]);
    let data = points.as_slice().map_err(|_| err("points: the array must be C-contiguous"))?;
    if d == 0 {
        return Err(err("points: d must be at least 1"));
    }
    if let Some(i) = data.iter().position(|x| !x.is_finite()) {
        return Err(err(format!(
            "set {} point {} coordinate {} is {} (not finite)",
            i / (n * d),
            i / d % n,
            i % d,
            data[i]
        )));
    }
    (0..sets).map(|k| PointSet::new(d, data[k * n * d..(k + 1) * n * d].to_vec()).map_err(err)).collect()
}

/// The format `name` (a registry name or extension), or the one `path`'s extension implies.
fn format_of(path: &str, name: Option<&str>) -> PyResult<samplab::io::Format> {
    match name {
        Some(n) => samplab::io::Format::from_name(n).map_err(err),
        None => Ok(samplab::io::Format::from_path(std::path::Path::new(path))),
    }
}

/// `data` written to `path` atomically (a temporary file renamed over it: the old file or the
/// new one, never part of one), as every samplab output is.
#[pyfunction]
fn write_file(path: &str, data: &[u8]) -> PyResult<()> {
    samplab::io::write_atomic(std::path::Path::new(path), data).map_err(err)
}

/// Write a (sets, n, d) stack to `path` in `format` (text, csv, npy, json; by default
/// from the extension), atomically, as `samplab generate -o` writes files.
#[pyfunction]
#[pyo3(signature = (path, points, format=None, header=None))]
fn save(path: &str, points: PyReadonlyArray3<f64>, format: Option<&str>, header: Option<Vec<String>>) -> PyResult<()> {
    let sets = point_sets(&points)?;
    let bytes = samplab::io::encode(&sets, format_of(path, format)?, &header.unwrap_or_default()).map_err(err)?;
    samplab::io::write_atomic(std::path::Path::new(path), &bytes).map_err(err)
}

/// Read every set of a point file (text, csv, npy, json; by default from the extension)
/// as a list of (n, d) arrays; malformed or non-finite data is an error naming the line.
#[pyfunction]
#[pyo3(signature = (path, format=None))]
fn load<'py>(py: Python<'py>, path: &str, format: Option<&str>) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let sets = samplab::io::read(std::path::Path::new(path), Some(format_of(path, format)?)).map_err(err)?;
    sets.into_iter()
        .map(|s| {
            let (n, d) = (s.len(), s.dims());
            shaped(py, s.into_vec(), &[n, d])
        })
        .collect()
}

/// Warp an (n, d) array of points (rejection warps drop points).
#[pyfunction]
fn warp<'py>(py: Python<'py>, name: &str, points: PyReadonlyArray2<f64>) -> PyResult<Bound<'py, PyAny>> {
    let w = samplab::warp::lookup(name).map_err(err)?;
    let (n, d) = (points.shape()[0], points.shape()[1]);
    let data = points.as_slice().map_err(|_| err("points: the array must be C-contiguous"))?.to_vec();
    let set = PointSet::new(d, data).map_err(err)?;
    debug_assert_eq!(set.len(), n);
    let out = py.detach(|| samplab::warp::apply(w, &set)).map_err(err)?;
    let (m, e) = (out.len(), out.dims());
    shaped(py, out.into_vec(), &[m, e])
}

/// The discrepancy `metric` of each set of a (sets, n, d) array.
#[pyfunction]
#[pyo3(signature = (metric, points, max_work=None))]
fn discrepancy(
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
fn conform(
    py: Python<'_>,
    points: PyReadonlyArray3<f64>,
    spec: &str,
    seed: Option<u64>,
    res: Option<(u32, u32)>,
    frame: u32,
    single: bool,
    ulps: u64,
    frames: u32,
) -> PyResult<String> {
    use samplab::conform::{Claim, Layout, Precision};
    let sets = point_sets(&points)?;
    let last = frame.checked_add(frames).ok_or_else(|| err(format!("frames {frame} + {frames} past 2^32")))?;
    let layout = res.map_or(Layout::Sets, |(w, h)| Layout::frames(w, h, frame..last));
    let precision = if single { Precision::Single } else { Precision::Found };
    let claim = Claim { spec, layout, seed: seed.map(Seed), precision, ulps };
    let checks =
        interruptible(py, points.len(), |stop| samplab::conform::conform(&sets, &claim, &Progress::until(stop)))?;
    serde_json::to_string(&checks).map_err(err)
}

/// The t of each projection of a sampler's nets at b^1 .. b^m points, as
/// `samplab t-values --json` prints it.
#[pyfunction]
#[pyo3(signature = (spec, dims, m, projection, base, seed, max_work=None))]
#[allow(clippy::too_many_arguments)] // the CLI's options, one for one
fn t_values(
    py: Python<'_>,
    spec: &str,
    dims: usize,
    m: usize,
    projection: &str,
    base: Option<u32>,
    seed: u64,
    max_work: Option<f64>,
) -> PyResult<String> {
    if m == 0 {
        return Err(err("m = 0: the nets start at m = 1"));
    }
    let sampler = samplab::sampler::build(spec).map_err(err)?;
    let limits = Limits::new(max_work).map_err(err)?;
    interruptible(py, usize::MAX, |stop| {
        let limits = limits.stopped_by(Progress::until(stop));
        samplab::discrepancy::tvalue::projection_table(&sampler, dims, m, projection, base, Seed(seed), &limits)
            .map(|table| table.json(sampler.spec(), Seed(seed)))
    })
}

/// A metric's canonical spec and flags ([`Metric::flags`]) as JSON.
#[pyfunction]
fn metric_flags(metric: &str) -> PyResult<String> {
    serde_json::to_string(&Metric::parse(metric).map_err(err)?.flags()).map_err(err)
}

/// Periodogram, amplitude of the expected spectrum and variance of the spectrum of a
/// (sets, n, d) stack, each an R^d array (index R/2 = DC), with their radial averages and
/// anisotropies (`samplab spectrum`'s numbers).
#[pyfunction]
#[pyo3(signature = (points, res, direct=false, tolerance=1e-9))]
fn spectrum<'py>(
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
fn statistics_dict<'py>(py: Python<'py>, st: &samplab::spectrum::Statistics) -> PyResult<Bound<'py, PyDict>> {
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

/// Every study kind's parameters, as JSON ([`samplab_render::study::KINDS`]).
#[pyfunction]
fn study_kinds() -> PyResult<String> {
    serde_json::to_string(samplab_render::study::KINDS).map_err(err)
}

/// A study's chunk list: the constructor's arguments (JSON, `{"kind": ..., arguments}`,
/// read by [`samplab_render::study::read`]) checked before any work and cut into chunks;
/// returns the description as the CLI writes it, the chunks, and whether chunk 0's result
/// feeds the others ([`samplab_render::study::Study`]).
#[pyfunction]
fn study_plan(arguments: &str) -> PyResult<(String, Vec<Vec<u64>>, bool)> {
    let (study, chunks) =
        samplab_render::study::read(arguments).and_then(|(s, per_chunk)| s.plan(per_chunk)).map_err(err)?;
    Ok((study.to_json(), chunks, study.first_feeds_the_rest()))
}

/// A study's checkpoint folder: finished chunks kept and read back, each checked
/// ([`samplab::study::Checkpoint`]).
#[pyclass(module = "samplab._samplab", frozen)]
struct Checkpoint(samplab::study::Checkpoint);

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
fn study_chunk<'py>(
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
        ) => Some(integrand::Given::from_python(f, *seed, *d, Some(*exact))?.0),
        (Some(_), _) => return Err(err("a function was given to a study that declares no integrand function")),
    };
    let data = interruptible(py, usize::MAX, |stop| {
        study.compute(&chunk, first.as_deref(), given.as_ref().map(integrand::Given::integrand), &Progress::until(stop))
    });
    if let Some(e) = given.as_ref().and_then(integrand::Given::failure) {
        return Err(e);
    }
    Ok(PyBytes::new(py, &data?))
}

/// Every chunk's bytes, in chunk order, merged: (JSON, CSV, the spectrum statistics as
/// `spectrum` returns them or None).
#[pyfunction]
fn study_merge<'py>(
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
fn integrate(
    py: Python<'_>,
    samplers: Vec<String>,
    integrand: &str,
    ns: Vec<usize>,
    sets: usize,
    instances: usize,
    seed: u64,
) -> PyResult<String> {
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
    Ok(interruptible(py, usize::MAX, |stop| d.run(&Progress::until(stop)))?.json)
}

/// An integration study of a callable of `dims` dimensions with integral `exact` (every
/// instance the same function), as [`integrate`] returns it.
#[pyfunction]
fn integrate_given(
    py: Python<'_>,
    samplers: Vec<String>,
    f: Bound<'_, PyAny>,
    ns: Vec<usize>,
    sets: usize,
    seed: u64,
    given: (usize, f64),
) -> PyResult<String> {
    let (dims, exact) = given;
    let (given, name) = integrand::Given::from_python(&f, seed, dims, Some(exact))?;
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
    Ok(merged?.json)
}

/// A prediction study, as `samplab predict --json` prints it: {"rows", "ranking", ...};
/// every registered sampler of the integrands' dimension when `samplers` is empty. Each
/// integrand is a spec, a 2D array or a callable of `dims` dimensions (its integral in
/// `exact`, in order, needed to measure).
#[pyfunction]
#[allow(clippy::too_many_arguments)] // the keywords of samplab.predict, checked there
fn predict(
    py: Python<'_>,
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
) -> PyResult<String> {
    let mut exact = exact.into_iter();
    let mut given = Vec::new();
    for value in &integrands {
        if value.is_callable() && !(1..=2).contains(&dims) {
            return Err(err(format!("d = {dims}: a callable integrand is 1D or 2D here")));
        }
        let known = if value.is_callable() { exact.next() } else { None };
        given.push(integrand::Given::from_python(value, seed, dims, known)?);
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
    serde_json::to_string(&outcome?).map_err(err)
}

/// The integral of `integrand` (a family spec, instance 0 for the seed, or a callable of
/// `dims` dimensions with integral `exact` when known) to a tolerance:
/// [`samplab::cubature::cubature`] with `settings` (JSON, any of its fields), as the JSON
/// `samplab cubature --json` prints.
#[pyfunction]
fn cubature(
    py: Python<'_>,
    integrand: Bound<'_, PyAny>,
    dims: usize,
    exact: Option<f64>,
    settings: &str,
) -> PyResult<String> {
    let settings: samplab::cubature::Settings =
        serde_json::from_str(settings).map_err(|e| err(format!("cubature settings: {e}")))?;
    let (given, name) = integrand::Given::from_python(&integrand, settings.seed.0, dims, exact)?;
    let f = given.integrand();
    let flags: Vec<&AtomicBool> = given.stop().into_iter().collect();
    let outcome = interruptible_raising(py, usize::MAX, &flags, |stop| {
        samplab::cubature::cubature(f, &settings, &Progress::until(stop))
    });
    if let Some(e) = given.failure() {
        return Err(e);
    }
    Ok(outcome?.to_json(&name, given.has_exact().then(|| f.exact())).to_string())
}

/// The integral of the callable `f` of `dims` dimensions for reference:
/// [`samplab::cubature::reference`].
#[pyfunction]
fn reference(py: Python<'_>, f: Bound<'_, PyAny>, dims: usize) -> PyResult<f64> {
    let (given, _) = integrand::Given::from_python(&f, Seed::DEFAULT.0, dims, None)?;
    let flags: Vec<&AtomicBool> = given.stop().into_iter().collect();
    let value = interruptible_raising(py, usize::MAX, &flags, |stop| {
        samplab::cubature::reference(given.integrand(), &Progress::until(stop))
    });
    if let Some(e) = given.failure() {
        return Err(e);
    }
    value
}

/// Instance `instance` of the integrand family `spec` for `seed`: its values at the rows of
/// an (n, d) array, and its exact integral.
#[pyfunction]
fn integrand_eval<'py>(
    py: Python<'py>,
    spec: &str,
    instance: u64,
    seed: u64,
    points: PyReadonlyArray2<f64>,
) -> PyResult<(Bound<'py, PyAny>, f64)> {
    let f = samplab::integrand::Family::parse(spec).and_then(|fam| fam.instance(Seed(seed), instance)).map_err(err)?;
    let d = points.shape()[1];
    if d != f.dims() {
        return Err(err(format!("{spec}: takes {}D points, got {d}D", f.dims())));
    }
    let data = points.as_slice().map_err(|_| err("points: the array must be C-contiguous"))?;
    let values: Vec<f64> = py.detach(|| data.chunks_exact(d).map(|x| f.eval(x)).collect());
    let n = values.len();
    Ok((shaped(py, values, &[n])?, f.exact()))
}

/// Render settings from Python keywords, over the defaults of [`Settings`] (the CLI's).
fn settings(given: Option<&Bound<'_, PyDict>>) -> PyResult<samplab_render::Settings> {
    let mut s = samplab_render::Settings::default();
    let Some(given) = given else { return Ok(s) };
    for (key, value) in given.iter() {
        let key: String = key.extract()?;
        let bad = |e: PyErr| err(format!("{key}: {e}"));
        match key.as_str() {
            "sampler" => s.sampler = value.extract().map_err(bad)?,
            "n" => s.n = value.extract().map_err(bad)?,
            "spp" => s.spp = value.extract().map_err(bad)?,
            "mode" => s.mode = value.extract().map_err(bad)?,
            "max_depth" => s.max_depth = Some(value.extract().map_err(bad)?),
            "pixel" => s.pixel = Some(value.extract().map_err(bad)?),
            "area_sampler" => s.area_sampler = value.extract().map_err(bad)?,
            "pixel_sampler" => s.pixel_sampler = Some(value.extract().map_err(bad)?),
            "lens_sampler" => s.lens_sampler = value.extract().map_err(bad)?,
            "time_sampler" => s.time_sampler = value.extract().map_err(bad)?,
            "gloss_sampler" => s.gloss_sampler = value.extract().map_err(bad)?,
            "pattern" => s.pattern = value.extract().map_err(bad)?,
            "disk_map" => s.disk_map = value.extract().map_err(bad)?,
            "range" => s.range = value.extract().map_err(bad)?,
            "interleave" => s.interleave = value.extract().map_err(bad)?,
            "res" => s.res = value.extract().map_err(bad)?,
            "seed" => s.seed = value.extract().map_err(bad)?,
            _ => {
                return Err(err(format!(
                    "unknown render setting '{key}' (sampler, n, spp, mode, max_depth, pixel, area_sampler, pixel_sampler, \
                     lens_sampler, time_sampler, gloss_sampler, pattern, disk_map, range, interleave, res, seed)"
                )));
            }
        }
    }
    Ok(s)
}

/// An image as a dictionary: rgb (h, w, 3) and visibility (h, w) float32 arrays.
fn image_dict<'py>(py: Python<'py>, image: samplab_render::Image) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let (w, h) = (image.width, image.height);
    out.set_item("rgb", PyArray1::from_vec(py, image.rgb).reshape([h, w, 3])?)?;
    match image.visibility {
        Some(v) => out.set_item("visibility", PyArray1::from_vec(py, v).reshape([h, w])?)?,
        None => out.set_item("visibility", py.None())?,
    }
    Ok(out)
}

/// Render `scene` (a built-in name or a Mitsuba XML file, lit by `light` if given) with the
/// settings given (the CLI's defaults otherwise); `reference_samples` renders the reference
/// `samplab render` would (converged, Owen-scrambled Sobol') instead.
#[pyfunction]
#[pyo3(signature = (scene, light=None, settings=None, reference_samples=None, allow_paths_outside_scene=false))]
fn render<'py>(
    py: Python<'py>,
    scene: &str,
    light: Option<&str>,
    settings: Option<&Bound<'py, PyDict>>,
    reference_samples: Option<usize>,
    allow_paths_outside_scene: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let s = self::settings(settings)?;
    let paths = if allow_paths_outside_scene {
        samplab_render::mitsuba::Paths::Anywhere
    } else {
        samplab_render::mitsuba::Paths::InsideScene
    };
    let scene = samplab_render::settings::load_scene(scene, light, paths).map_err(err)?;
    let mut options = s.options(&scene).map_err(err)?;
    if let Some(samples) = reference_samples {
        options = options.reference(&scene, samples).map_err(err)?;
    }
    let rendered =
        interruptible(py, usize::MAX, |stop| samplab_render::render(&scene, &options, &Progress::until(stop)))?;
    let out = image_dict(py, rendered.image)?;
    out.set_item("camera_rays", rendered.camera_rays)?;
    out.set_item("shadow_rays", rendered.shadow_rays)?;
    Ok(out)
}

/// An image from float32 arrays rgb (h, w, 3) and, optionally, visibility (h, w).
fn image_of(
    rgb: &PyReadonlyArray3<f32>,
    visibility: Option<&PyReadonlyArray2<f32>>,
) -> PyResult<samplab_render::Image> {
    let shape = rgb.shape();
    if shape[2] != 3 {
        return Err(err(format!("rgb: expected shape (h, w, 3), got {shape:?}")));
    }
    let (h, w) = (shape[0], shape[1]);
    let contiguous = |_| err("the array must be C-contiguous");
    let visibility = match visibility {
        Some(v) if v.shape() != [h, w] => {
            return Err(err(format!("visibility: expected shape ({h}, {w}), got {:?}", v.shape())));
        }
        Some(v) => Some(v.as_slice().map_err(contiguous)?.to_vec()),
        None => None,
    };
    Ok(samplab_render::Image { width: w, height: h, rgb: rgb.as_slice().map_err(contiguous)?.to_vec(), visibility })
}

/// Error metrics of an image against a reference (luminance, Rec. 709), as `samplab render
/// --json` reports them; `penumbra` restricts them to the reference's 0 < V < 1.
#[pyfunction]
#[pyo3(signature = (rgb, reference_rgb, reference_visibility=None, penumbra=false))]
fn image_errors(
    rgb: PyReadonlyArray3<f32>,
    reference_rgb: PyReadonlyArray3<f32>,
    reference_visibility: Option<PyReadonlyArray2<f32>>,
    penumbra: bool,
) -> PyResult<String> {
    let image = image_of(&rgb, None)?;
    let reference = image_of(&reference_rgb, reference_visibility.as_ref())?;
    serde_json::to_string(&image.errors(&reference, penumbra).map_err(err)?).map_err(err)
}

/// The screen measures of error images (frames, height, width) (`samplab image-metrics
/// --json`'s objects, one per frame), with the flicker over the frames when there are two or
/// more, or with `spp` (one count per image) their convergence.
#[pyfunction]
#[pyo3(signature = (errors, sigmas, spp=None))]
fn image_metrics(
    py: Python<'_>,
    errors: PyReadonlyArray3<f64>,
    sigmas: Vec<f64>,
    spp: Option<Vec<f64>>,
) -> PyResult<String> {
    let [frames, h, w] = [0, 1, 2].map(|k| errors.shape()[k]);
    if w == 0 || h == 0 {
        return Err(err(format!("an empty image, {w}x{h} pixels")));
    }
    let values = errors.as_slice().map_err(|_| err("the array must be C-contiguous"))?;
    let planes = values
        .chunks(w * h.max(1))
        .take(frames)
        .map(|f| samplab::screen::Plane::new(w, h, f.to_vec()))
        .collect::<samplab::Result<Vec<_>>>()
        .map_err(err)?;
    if planes.is_empty() {
        return Err(err("no image: the array has 0 frames"));
    }
    let result = py
        .detach(|| {
            let m = planes.iter().map(|p| p.metrics(&sigmas)).collect::<samplab::Result<Vec<_>>>()?;
            Ok::<_, samplab::Error>(match &spp {
                Some(spp) => serde_json::json!({
                    "frames": m, "convergence": samplab::screen::convergence(&planes, spp, &sigmas)?,
                }),
                None if planes.len() > 1 => {
                    serde_json::json!({ "frames": m, "flicker": samplab::screen::flicker(&planes)? })
                }
                None => serde_json::json!({ "frames": m }),
            })
        })
        .map_err(err)?;
    serde_json::to_string(&result).map_err(err)
}

/// Read an OpenEXR image (as `samplab render` writes them).
#[pyfunction]
fn read_exr<'py>(py: Python<'py>, path: &str) -> PyResult<Bound<'py, PyDict>> {
    image_dict(py, samplab_render::Image::read_exr(std::path::Path::new(path)).map_err(err)?)
}

/// Run the reproduction into `out` (replaced when complete, if samplab made it or `force`);
/// returns the claims as JSON. `progress(paper, experiment, done, total)` is called as each
/// experiment starts, advances (at most once per percent) and finishes; an exception it
/// raises stops the run and is raised here.
#[pyfunction]
#[pyo3(signature = (out, full=false, only=None, seed=None, force=false, progress=None))]
#[allow(clippy::too_many_arguments)] // the keywords of samplab.reproduce
fn reproduce(
    py: Python<'_>,
    out: &str,
    full: bool,
    only: Option<Vec<String>>,
    seed: Option<u64>,
    force: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
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
    serde_json::to_string(&list).map_err(err)
}

/// What a Python progress callback has been told of one running experiment.
#[derive(Default)]
struct Watched {
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

/// The native module.
#[pymodule]
fn _samplab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C interface is fetched now: fetched at the first array returned, it runs
    // Python code, where a Ctrl-C pending from the call raised inside numpy's crate (a
    // PanicException in place of KeyboardInterrupt)
    PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add("Error", m.py().get_type::<Error>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(default_seed, m)?)?;
    m.add_function(wrap_pyfunction!(registry, m)?)?;
    m.add_class::<sampler::Sampler>()?;
    m.add_function(wrap_pyfunction!(pixels, m)?)?;
    m.add_function(wrap_pyfunction!(pixel_seed, m)?)?;
    m.add_function(wrap_pyfunction!(cuda_source, m)?)?;
    m.add_function(wrap_pyfunction!(blue_noise_mask, m)?)?;
    m.add_function(wrap_pyfunction!(image_metrics, m)?)?;
    m.add_function(wrap_pyfunction!(warp, m)?)?;
    m.add_function(wrap_pyfunction!(save, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(discrepancy, m)?)?;
    m.add_function(wrap_pyfunction!(metric_flags, m)?)?;
    m.add_function(wrap_pyfunction!(t_values, m)?)?;
    m.add_function(wrap_pyfunction!(conform, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(integrate, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_class::<Checkpoint>()?;
    m.add_function(wrap_pyfunction!(cubature, m)?)?;
    m.add_function(wrap_pyfunction!(integrate_given, m)?)?;
    m.add_function(wrap_pyfunction!(write_file, m)?)?;
    m.add_function(wrap_pyfunction!(reference, m)?)?;
    m.add_function(wrap_pyfunction!(study_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(study_plan, m)?)?;
    m.add_function(wrap_pyfunction!(study_chunk, m)?)?;
    m.add_function(wrap_pyfunction!(study_merge, m)?)?;
    m.add_function(wrap_pyfunction!(integrand_eval, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(image_errors, m)?)?;
    m.add_function(wrap_pyfunction!(read_exr, m)?)?;
    Ok(())
}
