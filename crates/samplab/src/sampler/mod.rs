//! Samplers: every strategy of the four papers plus the modern low-discrepancy ones.
//!
//! Planned, then filled (as RustFFT's planner): `plan` (on `dyn Sampler`) checks a count and a
//! dimension once and returns a [`Plan`], which fills buffers from seeds:
//! - [`Plan::fill`] / [`Plan::generate`]: a batch of `n` points in `d` dimensions for a seed;
//! - [`Plan::generate_sets`] (or [`Plan::stack`], in one buffer): `m` independent
//!   realizations in parallel, realization `k` seeded with `seed.derive(k)`, identical
//!   whatever the thread count;
//! - [`Sequence::access`]: random access to coordinate `dim` of point `index` (for the
//!   progressive sequences: Halton, Sobol'), tables built once; it equals the batch bit for
//!   bit.
//!
//! ```
//! use samplab::{Seed, progress::Progress, sampler};
//! let s = sampler::build("sobol.owen")?;
//! let plan = s.plan(1024, 3)?;
//! let sets = plan.generate_sets(Seed(7), 4, &Progress::SILENT)?;
//! assert_eq!(sets[1], plan.generate(Seed(7).derive(1))?);
//! let access = s.as_sequence().expect("Sobol' has random access").access(3, Seed(7))?;
//! assert_eq!(access.sample(5, 2)?, plan.generate(Seed(7))?.point(5)[2]);
//! # Ok::<(), samplab::Error>(())
//! ```
//!
//! Build samplers by spec through [`build`]; [`SAMPLERS`] (and `samplab list samplers`) is the
//! table with every name, alias, parameter and reference.

use std::fmt::Debug;
use std::ops::RangeInclusive;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::seed::Seed;

pub mod cbc;
pub mod registry;
pub mod scramble;

crate::registry::registry_files! {
    /// Every sampler, in listing order, gathered from the files that declare them.
    pub static SAMPLERS: Registry<SamplerEntry> =
        ("sampler", "SAMPLERS  (spec: name[:key=value,...] or name[:value,...] in the order listed; \
                     +micro-jitter[:fraction=F] after any spec micro-jitters its points)")
        from [random, grid, nrooks, poisson, elimination, lloyd, ccvt, sot, gbn, heck, pmj, force_matrix, sobol, radical, net, kronecker, lattice, micro_jitter];
}

pub use registry::{SamplerEntry, build};
pub use scramble::Randomization;

/// The largest point count samplab will allocate for one set (2^32 points).
pub const MAX_POINTS: usize = 1 << 32;

mod sealed {
    use crate::error::Result;
    use crate::progress::Progress;
    use crate::seed::Seed;

    /// What every sampler implements inside samplab: its count rule and its filling. Reached
    /// from outside only through a checked [`super::Plan`] (the trait is not nameable
    /// outside the crate, so the unchecked entry points are not public).
    pub trait Fill {
        /// Whether exactly `n` points can be made in `dims` dimensions (the dimension is
        /// already checked); a count the method cannot make is an error naming the nearest
        /// counts that work (never rounded).
        fn check_count(&self, _n: usize, _dims: usize) -> Result<()> {
            Ok(())
        }

        /// Write `n` points of `dims` coordinates into `out` (length `n * dims`), row-major.
        /// Called only by a [`super::Plan`], after every check passed. Every sampler
        /// implements this or [`Fill::fill_reporting`] (the optimizers), each defined by the
        /// other.
        fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
            self.fill_reporting(n, dims, seed, out, &Progress::SILENT)
        }

        /// The units of progress one set reports: an optimizer's iterations, 1 otherwise.
        fn units(&self) -> u64 {
            1
        }

        /// [`Fill::fill`], advancing `progress` by [`Fill::units`] in all: the optimizers
        /// once per iteration, stopping between iterations when `progress` says so.
        fn fill_reporting(
            &self,
            n: usize,
            dims: usize,
            seed: Seed,
            out: &mut [f64],
            progress: &Progress,
        ) -> Result<()> {
            self.fill(n, dims, seed, out)?;
            progress.advance(self.units())
        }
    }
}

pub(crate) use sealed::Fill;

/// A sampling strategy: an immutable value; randomness comes from the seed. Make points by
/// planning first (`plan` on `dyn Sampler`: every check, once), then filling from
/// seeds, as often as needed.
pub trait Sampler: Fill + Send + Sync + Debug {
    /// The canonical spec (name and parameters), for messages and headers.
    fn spec(&self) -> String;

    /// The dimensions this method supports.
    fn dims(&self) -> RangeInclusive<usize>;

    /// Random access to the points, for the progressive sequences (Sobol', Halton).
    fn as_sequence(&self) -> Option<&dyn Sequence> {
        None
    }

    /// The points of one set made chunk by chunk (for sets larger than memory), where the
    /// method can: the same numbers [`Plan::fill`] writes for `seed`. The progressive
    /// sequences stream through their random access ([`Plan::stream`]); others say here.
    fn stream(&self, _dims: usize, _seed: Seed) -> Option<Box<dyn Stream>> {
        None
    }

    /// The closed form of the variance of the spectrum of `n` points in `dims` dimensions,
    /// where one is known (Gaussian and box jitter: Subr & Kautz 2013 eqs. 9 and 11 in their
    /// exact form).
    fn spectrum_theory(&self, _n: usize, _dims: usize) -> Option<crate::spectrum::theory::VarianceTheory> {
        None
    }
}

impl<'s> dyn Sampler + 's {
    /// Check that `n` points in `dims` dimensions can be made, and prepare to make them.
    ///
    /// # Errors
    /// An unsupported dimension ([`Error::InvalidDims`]), a count the method cannot make
    /// ([`Error::InvalidCount`], naming the nearest counts that work), or (Poisson disks) a
    /// radius that cannot fit `n` points ([`Error::Infeasible`]).
    ///
    /// ```
    /// use samplab::{Seed, sampler};
    /// let jitter = sampler::build("jitter").unwrap();
    /// assert!(jitter.plan(15, 2).unwrap_err().to_string().contains("9 and 16"));
    /// let plan = jitter.plan(16, 2).unwrap();
    /// let mut buffer = vec![0.0; 32];
    /// for k in 0..3 {
    ///     plan.fill(Seed(7).derive(k), &mut buffer).unwrap();
    /// }
    /// ```
    pub fn plan(&self, n: usize, dims: usize) -> Result<Plan<'_>> {
        let range = self.dims();
        if !range.contains(&dims) {
            return Err(Error::InvalidDims {
                sampler: self.spec(),
                dims,
                supported: format!("{}..={}", range.start(), range.end()),
            });
        }
        if n == 0 || n > MAX_POINTS || n.checked_mul(dims).is_none() {
            return Err(Error::InvalidCount {
                sampler: self.spec(),
                n,
                dims,
                reason: format!("n must be in 1..={MAX_POINTS}"),
            });
        }
        self.check_count(n, dims)?;
        Ok(Plan { sampler: self, n, dims })
    }

    /// `n` points in [0,1)^dims for `seed`: `plan`, then [`Plan::generate`].
    ///
    /// # Errors
    /// As `plan` and [`Plan::fill`].
    pub fn generate(&self, n: usize, dims: usize, seed: Seed) -> Result<PointSet> {
        self.plan(n, dims)?.generate(seed)
    }
}

/// A sampler checked for one count and dimension: fill it from as many seeds as needed.
#[derive(Debug, Clone, Copy)]
pub struct Plan<'s> {
    sampler: &'s dyn Sampler,
    n: usize,
    dims: usize,
}

impl<'s> Plan<'s> {
    /// Points per set.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Dimensions.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// The sampler's canonical spec.
    pub fn spec(&self) -> String {
        self.sampler.spec()
    }

    /// Write the `n` points for `seed` into `out` (length `n * dims`, row-major), without
    /// allocating for the grids, the sequences, random, N-rooks and the multi-jittered
    /// patterns.
    ///
    /// # Errors
    /// Only the stochastic constructions that can fail for a seed: Poisson-disk samplers
    /// whose dart throwing (or radius search) could not place `n` points
    /// ([`Error::Infeasible`]). Every other sampler's fill cannot fail once planned.
    ///
    /// # Panics
    /// When `out.len() != n * dims`.
    pub fn fill(&self, seed: Seed, out: &mut [f64]) -> Result<()> {
        assert_eq!(out.len(), self.n * self.dims, "the buffer must hold n x dims coordinates");
        self.sampler.fill(self.n, self.dims, seed, out)
    }

    /// The `n` points for `seed`.
    ///
    /// # Errors
    /// [`Error::Memory`] before any work when the set does not fit, or as [`Plan::fill`].
    pub fn generate(&self, seed: Seed) -> Result<PointSet> {
        self.generate_reporting(seed, &Progress::SILENT)
    }

    /// [`Plan::generate`], advancing `progress` by [`Plan::units`].
    fn generate_reporting(&self, seed: Seed, progress: &Progress) -> Result<PointSet> {
        let mut data = crate::memory::zeroed(|| self.describe(1), self.n * self.dims)?;
        self.sampler.fill_reporting(self.n, self.dims, seed, &mut data, progress)?;
        Ok(PointSet::from_raw(self.dims, data))
    }

    /// The units of progress one set reports ([`Plan::generate_sets`], [`Plan::stack`]): an
    /// optimizer's iterations, 1 for the other samplers.
    pub fn units(&self) -> u64 {
        self.sampler.units()
    }

    /// `m` realizations in parallel; realization k uses `seed.derive(k)`, so the sets are
    /// the same whatever the thread count. `progress` advances by [`Plan::units`] per set
    /// (an optimizer: one per iteration) and can stop the work.
    ///
    /// # Errors
    /// [`Error::Memory`] before any work when the sets do not fit, a stop
    /// ([`Error::Interrupted`]), or as [`Plan::fill`] (the first failing realization's).
    pub fn generate_sets(&self, seed: Seed, m: usize, progress: &Progress) -> Result<Vec<PointSet>> {
        crate::memory::check(|| self.describe(m), 8 * m as u128 * (self.n * self.dims) as u128)?;
        (0..m as u64)
            .into_par_iter()
            .map(|k| {
                progress.check()?;
                self.generate_reporting(seed.derive(k), progress)
            })
            .collect()
    }

    /// The set for `seed` made chunk by chunk, equal to [`Plan::generate`]`(seed)`, for the
    /// samplers that can (the sequences, random); `None` for the others.
    ///
    /// # Errors
    /// A sequence's tables that cannot be built.
    pub fn stream(&self, seed: Seed) -> Result<Option<Box<dyn Stream + 's>>> {
        match self.sampler.as_sequence() {
            Some(sequence) => {
                let access = sequence.access(self.dims, seed)?;
                Ok(Some(Box::new(Indexed { access, dims: self.dims, index: 0 })))
            }
            None => Ok(self.sampler.stream(self.dims, seed)),
        }
    }

    /// `m sets of n dD points` (`n dD points` for one set), for messages.
    fn describe(&self, m: usize) -> String {
        match m {
            1 => format!("{} {}D points", self.n, self.dims),
            m => format!("{m} sets of {} {}D points", self.n, self.dims),
        }
    }

    /// Realizations `sets` (set k seeded by `seed.derive(k)`, as in [`Plan::generate_sets`])
    /// in one buffer, set `sets.start + j` at `[j n dims, (j + 1) n dims)` (an array of shape
    /// (sets, n, dims), no copies), filled in parallel; `progress` advances by [`Plan::units`]
    /// per set and can stop the work.
    ///
    /// # Errors
    /// [`Error::Memory`] before any work when the buffer does not fit, a stop
    /// ([`Error::Interrupted`]), or as [`Plan::fill`].
    pub fn stack(&self, seed: Seed, sets: std::ops::Range<u64>, progress: &Progress) -> Result<Vec<f64>> {
        let (size, m) =
            (self.n * self.dims, usize::try_from(sets.end.saturating_sub(sets.start)).unwrap_or(usize::MAX));
        let mut out = crate::memory::zeroed(|| self.describe(m), m.saturating_mul(size))?;
        out.par_chunks_mut(size).enumerate().try_for_each(|(j, set)| {
            progress.check()?;
            self.sampler.fill_reporting(self.n, self.dims, seed.derive(sets.start + j as u64), set, progress)
        })?;
        Ok(out)
    }
}

/// One set's points made in order, chunk by chunk ([`Plan::stream`]).
pub trait Stream: Send {
    /// Fill `out` with the next `out.len() / dims` points, row-major.
    ///
    /// # Errors
    /// An index beyond the sequence.
    fn next(&mut self, out: &mut [f64]) -> Result<()>;
}

/// A sequence streamed through its random access.
struct Indexed<'a> {
    access: Box<dyn Access + 'a>,
    dims: usize,
    index: u64,
}

impl Stream for Indexed<'_> {
    fn next(&mut self, out: &mut [f64]) -> Result<()> {
        for p in out.chunks_exact_mut(self.dims) {
            for (d, x) in p.iter_mut().enumerate() {
                *x = self.access.sample(self.index, d)?;
            }
            self.index += 1;
        }
        Ok(())
    }
}

/// Random access to a progressive sequence (Sobol', Halton): coordinate `dim` of point
/// `index`, equal bit for bit to the batch.
pub trait Sequence: Sampler {
    /// Random access for `dims` dimensions and `seed`, with its tables built once.
    ///
    /// # Errors
    /// An unsupported dimension.
    fn access(&self, dims: usize, seed: Seed) -> Result<Box<dyn Access + '_>>;
}

/// A prepared random access to a sequence ([`Sequence::access`]).
pub trait Access: Send + Sync + Debug {
    /// Coordinate `dim` of point `index`, in [0, 1).
    ///
    /// # Errors
    /// An index beyond the sequence (32-bit Sobol' points stop at 2^32 - 1).
    ///
    /// # Panics
    /// When `dim` is not below the dimensions the access was prepared for.
    fn sample(&self, index: u64, dim: usize) -> Result<f64>;
}

/// `m` realizations of `n` points each, in parallel; realization k uses `seed.derive(k)`.
///
/// # Errors
/// As `plan` (on `dyn Sampler`) and [`Plan::fill`].
pub fn generate_sets(sampler: &dyn Sampler, n: usize, dims: usize, seed: Seed, m: usize) -> Result<Vec<PointSet>> {
    sampler.plan(n, dims)?.generate_sets(seed, m, &Progress::SILENT)
}

/// Ok when `n` is one of `counts` (increasing), else the error naming the rule and the
/// nearest counts below and above n.
pub(crate) fn check_listed(
    sampler: String,
    n: usize,
    dims: usize,
    rule: &str,
    counts: impl Iterator<Item = usize> + Clone,
) -> Result<()> {
    if counts.clone().take_while(|&c| c <= n).any(|c| c == n) {
        return Ok(());
    }
    let below = counts.clone().take_while(|&c| c < n).last();
    let above = counts.take_while(|&c| c <= MAX_POINTS).find(|&c| c > n);
    let near = match (below, above) {
        (Some(b), Some(a)) => format!("try {b} and {a}"),
        (Some(c), None) | (None, Some(c)) => format!("try {c}"),
        (None, None) => "no count fits".into(),
    };
    Err(Error::InvalidCount { sampler, n, dims, reason: format!("{rule}: {near}") })
}

/// The integer k with k^d == n, if there is one; otherwise the two nearest valid counts.
pub(crate) fn exact_root(n: usize, dims: usize) -> std::result::Result<usize, (usize, usize)> {
    let guess = (n as f64).powf(1.0 / dims as f64).round() as usize;
    let pow = |k: usize| k.checked_pow(dims as u32).unwrap_or(usize::MAX);
    for k in guess.saturating_sub(1)..=guess + 1 {
        if pow(k) == n {
            return Ok(k);
        }
    }
    let mut k = guess.max(1);
    while pow(k) > n && k > 1 {
        k -= 1;
    }
    while pow(k + 1) <= n {
        k += 1;
    }
    Err((pow(k), pow(k + 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_root_names_neighbours() {
        assert_eq!(exact_root(16, 2), Ok(4));
        assert_eq!(exact_root(15, 2), Err((9, 16)));
        assert_eq!(exact_root(27, 3), Ok(3));
        assert_eq!(exact_root(28, 3), Err((27, 64)));
        assert_eq!(exact_root(7, 1), Ok(7));
        assert_eq!(exact_root(2, 2), Err((1, 4)));
    }

    #[test]
    fn optimizers_report_each_iteration_and_stop_between_them() {
        use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
        // every optimizer reports its iterations (ccvt the rest at once when it converges);
        // the others one unit per set
        for (spec, units) in [
            ("lloyd:iterations=7", 7),
            ("ccvt:iterations=7", 7),
            ("sot:iterations=7", 7),
            ("gbn:iterations=7", 7),
            ("kdm:iterations=7", 7),
            ("step:iterations=7", 7),
            ("lloyd:iterations=7+micro-jitter", 7),
            ("jitter", 1),
        ] {
            let sampler = build(spec).unwrap();
            let plan = sampler.plan(64, 2).unwrap();
            assert_eq!(plan.units(), units, "{spec}");
            let done = AtomicU64::new(0);
            let report = |k| {
                done.fetch_add(k, Ordering::Relaxed);
            };
            let sets = plan.generate_sets(Seed(1), 3, &Progress::new(&report)).unwrap();
            assert_eq!(done.load(Ordering::Relaxed), 3 * units, "{spec}");
            // the same sets as without a report
            assert_eq!(sets[1], plan.generate(Seed(1).derive(1)).unwrap(), "{spec}");
        }
        // a stop raised during the iterations of one set ends the work there
        let plan = build("gbn:iterations=1000").unwrap();
        let plan = plan.plan(256, 2).unwrap();
        let (done, stop) = (AtomicU64::new(0), AtomicBool::new(false));
        let report = |k| {
            if done.fetch_add(k, Ordering::Relaxed) + k >= 5 {
                stop.store(true, Ordering::Relaxed);
            }
        };
        let progress = Progress::new(&report).stopped_by(&stop);
        assert_eq!(plan.generate_sets(Seed(1), 1, &progress).unwrap_err(), Error::Interrupted);
        assert_eq!(done.load(Ordering::Relaxed), 5);
    }
}
