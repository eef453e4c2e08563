//! Integrands from Python: a family spec, a 2D array of values (a [`Grid`]), or a vectorized
//! callable, evaluated in batches with the GIL taken for each batch; and what is computed
//! of one integrand alone: its values, its reference integral, adaptive cubature.

use crate::errors::err;
use crate::interrupt::interruptible_raising;
use crate::points::shaped;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use samplab::Seed;
use samplab::integrand::{Family, Grid, Integrand};
use samplab::progress::Progress;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// A Python function f(x) of an (n, d) array returning n values, with its integral when
/// known. The first exception it raises (or a wrong shape, or a value that is not finite)
/// is kept and re-raised by [`Callable::failure`]; later batches are not evaluated, nor
/// are they once its stop flag is raised (a signal: the caller raises the signal's own
/// exception).
pub struct Callable {
    f: Py<PyAny>,
    dims: usize,
    exact: Option<f64>,
    failed: Mutex<Option<PyErr>>,
    stop: AtomicBool,
}

impl Callable {
    /// The error kept from the evaluations, if any.
    pub fn failure(&self) -> Option<PyErr> {
        self.failed.lock().map_or(None, |mut e| e.take())
    }

    fn batch(&self, py: Python<'_>, points: &[f64]) -> PyResult<Vec<f64>> {
        let n = points.len() / self.dims;
        let x = PyArray1::from_slice(py, points).reshape([n, self.dims])?;
        let result = self.f.call1(py, (x,))?;
        let numpy = py.import("numpy")?;
        let flat = numpy.call_method1("asarray", (result, "float64"))?.call_method0("ravel")?;
        let values: Vec<f64> = flat.extract()?;
        if values.len() != n {
            return Err(err(format!(
                "the integrand returned {} values for {n} points; it must return one per row",
                values.len()
            )));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            let at = &points[i * self.dims..(i + 1) * self.dims];
            return Err(err(format!("the integrand returned {} at {at:?}", values[i])));
        }
        Ok(values)
    }
}

impl Integrand for Callable {
    fn dims(&self) -> usize {
        self.dims
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let mut out = [0.0];
        self.eval_many(x, &mut out);
        out[0]
    }
    fn exact(&self) -> f64 {
        self.exact.unwrap_or(f64::NAN)
    }
    fn eval_many(&self, points: &[f64], out: &mut [f64]) {
        let failed = self.stop.load(Ordering::Relaxed) || self.failed.lock().map_or(true, |e| e.is_some());
        let values = if failed { Err(None) } else { Python::attach(|py| self.batch(py, points)).map_err(Some) };
        match values {
            Ok(v) => out.copy_from_slice(&v),
            Err(e) => {
                out.fill(f64::NAN);
                if let (Some(e), Ok(mut kept)) = (e, self.failed.lock()) {
                    kept.get_or_insert(e);
                }
            }
        }
    }
}

/// One integrand as given from Python, with its name.
pub enum Given {
    /// A family's instance 0 for the seed.
    Family(Box<dyn Integrand>),
    /// Values on a grid.
    Grid(Grid),
    /// A callable.
    Callable(Callable),
}

impl Given {
    /// `value`: a spec string, a 2D float array (rows from y = 0) or a callable of `dims`
    /// dimensions with integral `exact` when known.
    pub fn from_python(
        value: &Bound<'_, PyAny>,
        seed: u64,
        dims: usize,
        exact: Option<f64>,
    ) -> PyResult<(Given, String)> {
        if let Ok(spec) = value.extract::<String>() {
            let family = Family::parse(&spec).map_err(err)?;
            return Ok((Given::Family(family.instance(Seed(seed), 0).map_err(err)?), family.spec()));
        }
        if let Ok(array) = value.extract::<PyReadonlyArray2<f64>>() {
            let (h, w) = (array.shape()[0], array.shape()[1]);
            let values = array.as_array().iter().copied().collect();
            return Ok((Given::Grid(Grid::new(w, h, values).map_err(err)?), format!("array {w}x{h}")));
        }
        if value.is_callable() {
            if dims == 0 {
                return Err(err("d = 0: a callable integrand needs at least one dimension".to_string()));
            }
            if let Some(e) = exact.filter(|e| !e.is_finite()) {
                return Err(err(format!("exact = {e}: the integral must be a finite number")));
            }
            let name =
                value.getattr("__name__").and_then(|n| n.extract::<String>()).unwrap_or_else(|_| "callable".into());
            let f = Callable {
                f: value.clone().unbind(),
                dims,
                exact,
                failed: Mutex::new(None),
                stop: AtomicBool::new(false),
            };
            return Ok((Given::Callable(f), name));
        }
        Err(err(format!(
            "integrand: expected a spec string, a 2D float array or a callable, not {}",
            value.get_type().name()?
        )))
    }

    /// The integrand.
    pub fn integrand(&self) -> &dyn Integrand {
        match self {
            Given::Family(f) => f.as_ref(),
            Given::Grid(g) => g,
            Given::Callable(c) => c,
        }
    }

    /// The error a callable kept, if any.
    pub fn failure(&self) -> Option<PyErr> {
        match self {
            Given::Callable(c) => c.failure(),
            _ => None,
        }
    }

    /// A callable's stop flag (raised, its remaining batches are skipped).
    pub fn stop(&self) -> Option<&AtomicBool> {
        match self {
            Given::Callable(c) => Some(&c.stop),
            _ => None,
        }
    }

    /// Whether the integral is known (a callable's only when given).
    pub fn has_exact(&self) -> bool {
        !matches!(self, Given::Callable(Callable { exact: None, .. }))
    }
}

/// The integral of `integrand` (a family spec, instance 0 for the seed, or a callable of
/// `dims` dimensions with integral `exact` when known) to a tolerance:
/// [`samplab::cubature::cubature`] with `settings` (JSON, any of its fields), as the JSON
/// `samplab cubature --json` prints.
#[pyfunction]
pub(crate) fn cubature<'py>(
    py: Python<'py>,
    integrand: Bound<'_, PyAny>,
    dims: usize,
    exact: Option<f64>,
    settings: Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let settings: samplab::cubature::Settings =
        serde_json::from_value(crate::convert::json_of("cubature settings", &settings)?)
            .map_err(|e| err(format!("cubature settings: {e}")))?;
    let (given, name) = Given::from_python(&integrand, settings.seed.0, dims, exact)?;
    let f = given.integrand();
    let flags: Vec<&AtomicBool> = given.stop().into_iter().collect();
    let outcome = interruptible_raising(py, usize::MAX, &flags, |stop| {
        samplab::cubature::cubature(f, &settings, &Progress::until(stop))
    });
    if let Some(e) = given.failure() {
        return Err(e);
    }
    crate::convert::py_of(py, &outcome?.to_json(&name, given.has_exact().then(|| f.exact())))
}

/// The integral of the callable `f` of `dims` dimensions for reference:
/// [`samplab::cubature::reference`].
#[pyfunction]
pub(crate) fn reference(py: Python<'_>, f: Bound<'_, PyAny>, dims: usize) -> PyResult<f64> {
    let (given, _) = Given::from_python(&f, Seed::DEFAULT.0, dims, None)?;
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
pub(crate) fn integrand_eval<'py>(
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
