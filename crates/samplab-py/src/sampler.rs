//! A sampler built once from its spec (`samplab.Sampler`'s native half): its sets, its
//! sequence's points and what it makes, from one object that Python holds for as long as
//! it likes (the library's samplers own their state, so nothing here borrows).

use pyo3::prelude::*;
use samplab::Seed;
use samplab::progress::Progress;

use crate::errors::err;
use crate::interrupt::interruptible;
use crate::points::shaped;

/// One sampler, built from `spec` (the registry's checks run once, here).
#[pyclass(module = "samplab._samplab", frozen)]
pub struct Sampler {
    /// The spec as given (the registry reads it again for `randomized`).
    given: String,
    sampler: samplab::Sampler,
}

#[pymethods]
impl Sampler {
    #[new]
    fn new(spec: &str) -> PyResult<Self> {
        Ok(Sampler { given: spec.to_string(), sampler: samplab::sampler::build(spec).map_err(err)? })
    }

    /// Pickled as its spec as given (Dask's workers, `copy.deepcopy`): unpickled, it is
    /// built again from the same words.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, pyo3::types::PyType>, (String,)) {
        (slf.get_type(), (slf.get().given.clone(),))
    }

    /// The canonical spec (name and every parameter).
    #[getter]
    fn spec(&self) -> String {
        self.sampler.spec().to_string()
    }

    /// The dimensions it makes, (fewest, most).
    fn dims(&self) -> (usize, usize) {
        let range = self.sampler.dims();
        (*range.start(), *range.end())
    }

    /// Whether it makes `d` dimensions (the library's error, naming those it makes, if not).
    fn check_dims(&self, d: usize) -> PyResult<()> {
        self.sampler.check_dims(d).map_err(err)
    }

    /// Whether its points depend on the seed.
    fn randomized(&self) -> PyResult<bool> {
        samplab::sampler::randomized(&self.given).map_err(err)
    }

    /// Whether it is a progressive sequence (random access, extensible).
    fn is_sequence(&self) -> bool {
        // a sequence makes any count, so one point in its fewest dimensions plans
        let plan = self.sampler.plan(1, *self.sampler.dims().start());
        plan.is_ok_and(|p| p.access(Seed(0)).is_some())
    }

    /// `sets` realizations of `n` points in `d` dimensions as a (sets, n, d) array, starting
    /// at realization `first`; set k is seeded `seed.derive(k)`, as `samplab generate` does,
    /// so the bytes are the CLI's.
    #[pyo3(signature = (n, d, seed, sets, first=0))]
    fn generate<'py>(
        &self,
        py: Python<'py>,
        n: usize,
        d: usize,
        seed: u64,
        sets: usize,
        first: u64,
    ) -> PyResult<Bound<'py, PyAny>> {
        if sets == 0 {
            return Err(err("sets must be at least 1"));
        }
        let end = first.checked_add(sets as u64).ok_or_else(|| err("first + sets passes 2^64 - 1"))?;
        let plan = self.sampler.plan(n, d).map_err(err)?;
        // a sequence's or a stream's points cost about the same each; a construction's cost
        // is not its size (Lloyd's 10^5 iterations on 1024 points ran for minutes unstoppable)
        let cheap = plan.access(Seed(seed)).is_some() || plan.stream(Seed(seed)).is_some();
        let size = if cheap { sets.saturating_mul(n * d) } else { usize::MAX };
        let data = interruptible(py, size, |stop| plan.stack(Seed(seed), first..end, &Progress::until(stop)))?;
        shaped(py, data, &[sets, n, d])
    }

    /// Points `start .. start + n` of the sequence in `d` dimensions, randomized as set 0 of
    /// `generate` with the same seed (so `start = 0` gives the same points).
    fn points<'py>(&self, py: Python<'py>, start: u64, n: usize, d: usize, seed: u64) -> PyResult<Bound<'py, PyAny>> {
        let sampler = &self.sampler;
        let whole = || err(format!("{}: makes whole sets, not a sequence: it cannot be extended", sampler.spec()));
        // a sequence makes any count: a plan of one point fails only on the dimension
        let plan = match sampler.plan(1, d) {
            Ok(plan) => plan,
            Err(e @ samplab::Error::InvalidDims { .. }) => return Err(err(e)),
            Err(_) => return Err(whole()),
        };
        // planned for the points asked for where the sequence has them, so that its tables
        // (a cache: Owen-scrambled Halton's) fit the count
        let end = start.checked_add(n as u64).and_then(|end| usize::try_from(end).ok());
        let plan = end.and_then(|end| sampler.plan(end, d).ok()).unwrap_or(plan);
        let Some(access) = plan.access(Seed(seed).derive(0)) else {
            return Err(whole());
        };
        let data = py
            .detach(|| -> samplab::Result<Vec<f64>> {
                samplab::memory::check(|| format!("{n} points of {d} dimensions"), 8 * n as u128 * d as u128)?;
                let mut data = Vec::with_capacity(n * d);
                for i in 0..n as u64 {
                    let index = start.checked_add(i).ok_or_else(|| samplab::Error::Setting {
                        name: "start",
                        value: start.to_string(),
                        reason: format!("start + {n} points passes the last index 2^64 - 1"),
                    })?;
                    for dim in 0..d {
                        data.push(access.sample(index, dim)?);
                    }
                }
                Ok(data)
            })
            .map_err(err)?;
        shaped(py, data, &[n, d])
    }
}
