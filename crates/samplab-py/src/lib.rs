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

mod convert;
mod errors;
mod integrand;
mod interrupt;
mod measure;
mod points;
mod render;
mod report;
mod sampler;
mod study;

use numpy::PyArray1;
use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _samplab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C interface is fetched now: fetched at the first array returned, it runs
    // Python code, where a Ctrl-C pending from the call raised inside numpy's crate (a
    // PanicException in place of KeyboardInterrupt)
    PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add("Error", m.py().get_type::<errors::Error>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(points::default_seed, m)?)?;
    m.add_function(wrap_pyfunction!(points::registry, m)?)?;
    m.add_class::<sampler::Sampler>()?;
    m.add_function(wrap_pyfunction!(points::pixels, m)?)?;
    m.add_function(wrap_pyfunction!(points::pixel_seed, m)?)?;
    m.add_function(wrap_pyfunction!(points::cuda_source, m)?)?;
    m.add_function(wrap_pyfunction!(points::blue_noise_mask, m)?)?;
    m.add_function(wrap_pyfunction!(render::image_metrics, m)?)?;
    m.add_function(wrap_pyfunction!(points::warp, m)?)?;
    m.add_function(wrap_pyfunction!(points::save, m)?)?;
    m.add_function(wrap_pyfunction!(points::load, m)?)?;
    m.add_function(wrap_pyfunction!(measure::discrepancy, m)?)?;
    m.add_function(wrap_pyfunction!(measure::metric_flags, m)?)?;
    m.add_function(wrap_pyfunction!(measure::t_values, m)?)?;
    m.add_function(wrap_pyfunction!(measure::conform, m)?)?;
    m.add_function(wrap_pyfunction!(measure::spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(study::integrate, m)?)?;
    m.add_function(wrap_pyfunction!(study::predict, m)?)?;
    m.add_class::<study::Checkpoint>()?;
    m.add_function(wrap_pyfunction!(integrand::cubature, m)?)?;
    m.add_function(wrap_pyfunction!(study::integrate_given, m)?)?;
    m.add_function(wrap_pyfunction!(points::write_file, m)?)?;
    m.add_function(wrap_pyfunction!(integrand::reference, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_kinds, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_plan, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_chunk, m)?)?;
    m.add_function(wrap_pyfunction!(study::study_merge, m)?)?;
    m.add_function(wrap_pyfunction!(integrand::integrand_eval, m)?)?;
    m.add_function(wrap_pyfunction!(report::reproduce, m)?)?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::render_settings, m)?)?;
    m.add_function(wrap_pyfunction!(render::image_errors, m)?)?;
    m.add_function(wrap_pyfunction!(render::read_exr, m)?)?;
    Ok(())
}
