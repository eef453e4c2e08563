//! Samplers: every strategy of the four papers plus the modern low-discrepancy ones.
//!
//! Planned, then filled (as RustFFT's planner): [`Sampler::plan`] checks a count and a
//! dimension once and returns a [`Plan`], which fills buffers from seeds:
//! - [`Plan::fill`] / [`Plan::generate`]: a batch of `n` points in `d` dimensions for a seed;
//! - [`Plan::generate_sets`] (or [`Plan::stack`], in one buffer): `m` independent
//!   realizations in parallel, realization `k` seeded with `seed.derive(k)`, identical
//!   whatever the thread count;
//! - [`Plan::access`]: random access to coordinate `dim` of point `index` (for the
//!   progressive sequences: Halton, Sobol', nets, the lattice sequence), from the same
//!   prepared tables; it equals the batch bit for bit.
//!
//! The [`Plan`] owns everything prepared before a seed is known ([`Construction::prepare`]:
//! generating vectors, matrices, digit tables): no sampler keeps a process-wide cache.
//!
//! ```
//! use samplab::{Seed, progress::Progress, sampler};
//! let s = sampler::build("sobol.owen")?;
//! let plan = s.plan(1024, 3)?;
//! let sets = plan.generate_sets(Seed(7), 4, &Progress::SILENT)?;
//! assert_eq!(sets[1], plan.generate(Seed(7).derive(1))?);
//! let access = plan.access(Seed(7)).expect("Sobol' has random access");
//! assert_eq!(access.sample(5, 2)?, plan.generate(Seed(7))?.point(5)[2]);
//! # Ok::<(), samplab::Error>(())
//! ```
//!
//! Build samplers by spec through [`build`]; [`SAMPLERS`] (and `samplab list samplers`) is the
//! table with every name, alias, parameter and reference.
//!
//! The map of the folder, one family per folder, each opening with what it holds and the
//! papers it follows:
//! - [`random`]: independent uniform points; [`file`](mod@file): a saved set, replayed;
//! - [`stratified`]: grids and their jitters, N-rooks and Latin hypercubes, multi-jittered;
//! - [`blue_noise`]: Poisson disks, elimination, relaxation and optimization;
//! - [`qmc`]: Sobol', Halton and Hammersley, digital nets, Kronecker sequences, lattices;
//! - [`randomize`]: the scrambles of the digital constructions, declared once per family
//!   (the scrambles themselves are [`crate::construct::scramble`], shared with the pixel
//!   samplers), and the stages written after any spec (`+shift`, `+micro-jitter`);
//! - [`registry`]: the entries' shape (their typed counts are [`crate::construct::Counts`])
//!   and [`build`].
//!
//! The mathematics under the families (generating matrices, digit tables, scrambles, CBC
//! searches) is in [`crate::construct`], which the pixel samplers read as well.
//!
//! One trait, [`Construction`], describes every construction, built-in or written outside
//! samplab (its documentation has one); a [`Sampler`] is a construction with its spec,
//! named by its registry entry or by [`Sampler::new`].

use std::fmt::Debug;
use std::ops::RangeInclusive;
use std::sync::Arc;

use rayon::prelude::*;

use crate::construct::{Counts, MAX_POINTS};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::seed::Seed;

pub mod blue_noise;
pub mod file;
pub mod qmc;
pub mod random;
pub mod randomize;
pub mod registry;
pub mod stratified;

/// Every sampler, in listing order: random and a saved set, then the families' files in
/// their folders' order.
pub static SAMPLERS: crate::registry::Registry<SamplerEntry> = crate::registry::Registry::new(
    "sampler",
    "SAMPLERS  (spec: name[:key=value,...] or name[:value,...] in the order listed; \
     after any spec, stages: +shift, +micro-jitter[:fraction=F])",
    &[&[random::ENTRIES, file::ENTRIES], stratified::FILES, blue_noise::FILES, qmc::FILES, randomize::FILES],
);

pub use registry::{SamplerEntry, build, inputs, randomized};

/// The count and dimension a plan was checked for, and the spec of the sampler it is
/// for. Only [`Sampler::plan`] makes one, so [`Construction::prepare`], which takes it, is
/// reached only after every check passed: the shape is the token that keeps the checks, for
/// constructions written outside samplab too. A construction's errors name its sampler
/// where they are made ([`Shape::invalid_count`], [`Shape::infeasible`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Shape {
    n: usize,
    dims: usize,
    sampler: Arc<str>,
}

impl Shape {
    /// Points per set.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Dimensions.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// The spec of the sampler being planned.
    pub fn sampler(&self) -> &str {
        &self.sampler
    }

    /// The error for a count the construction cannot make, `reason` in words (the nearest
    /// counts that work, where known).
    pub fn invalid_count(&self, reason: impl Into<String>) -> Error {
        Error::InvalidCount { sampler: self.sampler.to_string(), n: self.n, dims: self.dims, reason: reason.into() }
    }

    /// The error for a construction that fails for this shape (or, in a fill, for a seed).
    pub fn infeasible(&self, reason: impl Into<String>) -> Error {
        Error::Infeasible { what: self.sampler.to_string(), reason: reason.into() }
    }
}

/// A construction: a sampling strategy without its name, an immutable value whose
/// randomness comes from the seed. A [`Sampler`] is a construction with its spec; every
/// built-in one is named by its registry entry ([`build`]), and one written outside
/// samplab by [`Sampler::new`].
///
/// Make points by planning first ([`Sampler::plan`]: every check, then
/// [`Construction::prepare`], once), then filling from seeds, as often as needed.
///
/// The trait is open: a construction written outside samplab implements `dims` and
/// `prepare` (and `check_count` when not every count works), and is then planned, measured
/// and integrated like a built-in one:
///
/// ```
/// use std::ops::RangeInclusive;
/// use samplab::discrepancy::{self, Limits, Metric};
/// use samplab::sampler::{self, Construction, Prepared, Sampler, Shape};
/// use samplab::spectrum::{self, Method};
/// use samplab::{Result, Seed, progress::Progress};
///
/// /// A 2D Korobov lattice with a fixed multiplier a, its points centred in their columns:
/// /// point i at ((i + 1/2) / n, frac(a (i + 1/2) / n)).
/// #[derive(Debug)]
/// struct Centred {
///     a: u64,
/// }
///
/// impl Construction for Centred {
///     fn dims(&self) -> RangeInclusive<usize> {
///         2..=2
///     }
///     fn check_count(&self, shape: &Shape) -> Result<()> {
///         match shape.n() {
///             1 => Err(shape.invalid_count("a lattice needs 2 points or more")),
///             _ => Ok(()),
///         }
///     }
///     fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
///         let (n, a) = (shape.n() as f64, self.a as f64);
///         Ok(sampler::from_fill(move |_seed, out| {
///             for (i, p) in out.chunks_exact_mut(2).enumerate() {
///                 let x = (i as f64 + 0.5) / n;
///                 p[0] = x;
///                 p[1] = (a * x).fract();
///             }
///             Ok(())
///         }))
///     }
/// }
///
/// let mine = Sampler::new("centred:a=13", Centred { a: 13 });
/// assert!(mine.plan(64, 3).is_err()); // the dimension check holds for it too
/// assert!(mine.plan(1, 2).unwrap_err().to_string().starts_with("centred:a=13")); // and names it
/// let plan = mine.plan(64, 2)?;
/// let points = plan.generate(Seed(1))?;
/// let star = discrepancy::compute(&Metric::parse("star")?, &points, Limits::default())?;
/// assert!(star > 0.0 && star < 0.2, "{star}");
/// let sets = plan.generate_sets(Seed(1), 2, &Progress::SILENT)?;
/// let st = spectrum::statistics(&sets, 16, Method::Direct)?;
/// assert!((st.periodogram[8 * 16 + 8] - 1.0).abs() < 1e-12); // the DC of a set is 1
/// # Ok::<(), samplab::Error>(())
/// ```
pub trait Construction: Send + Sync + Debug {
    /// The dimensions this construction supports.
    fn dims(&self) -> RangeInclusive<usize>;

    /// Whether exactly `shape.n()` points can be made in `shape.dims()` dimensions (the
    /// dimension is already checked); a count the construction cannot make is an error
    /// naming the nearest counts that work (never rounded): [`Shape::invalid_count`].
    ///
    /// # Errors
    /// [`Error::InvalidCount`] for a count the construction cannot make.
    fn check_count(&self, _shape: &Shape) -> Result<()> {
        Ok(())
    }

    /// Everything a set of `shape` needs before any seed is known (generating vectors,
    /// matrices, digit tables), built once; the [`Plan`] owns it, and every fill, stream
    /// and random access reads it. Called only by [`Sampler::plan`], after the checks.
    ///
    /// # Errors
    /// Tables that cannot be built (a construction that fails for this count:
    /// [`Shape::infeasible`]).
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>>;

    /// The closed form of the variance of the spectrum of `n` points in `dims` dimensions,
    /// where one is known (Gaussian and box jitter: Subr & Kautz 2013 eqs. 9 and 11 in their
    /// exact form).
    fn spectrum_theory(&self, _n: usize, _dims: usize) -> Option<crate::construct::spectrum_theory::VarianceTheory> {
        None
    }
}

/// A sampler: a [`Construction`] with its spec (name and parameters, for messages and
/// headers, and in every error its construction makes). [`build`] makes the built-in ones
/// from a spec; [`Sampler::new`] names one written outside samplab.
#[derive(Debug)]
pub struct Sampler {
    spec: Arc<str>,
    /// The registry entry's counts, checked before the construction's own rule (none for a
    /// construction outside samplab, or a stage: it makes the counts of the sampler before it).
    counts: Option<Counts>,
    construction: Box<dyn Construction>,
}

impl Sampler {
    /// The construction `construction` under the spec `spec`.
    pub fn new(spec: impl Into<String>, construction: impl Construction + 'static) -> Sampler {
        Sampler { spec: spec.into().into(), counts: None, construction: Box::new(construction) }
    }

    /// A registered construction: its entry's `counts` checked first.
    pub(crate) fn registered(spec: String, counts: Option<Counts>, construction: Box<dyn Construction>) -> Sampler {
        Sampler { spec: spec.into(), counts, construction }
    }

    /// The canonical spec (name and parameters).
    pub fn spec(&self) -> &str {
        &self.spec
    }

    /// The dimensions this sampler supports.
    pub fn dims(&self) -> RangeInclusive<usize> {
        self.construction.dims()
    }

    /// As [`Construction::spectrum_theory`].
    pub fn spectrum_theory(&self, n: usize, dims: usize) -> Option<crate::construct::spectrum_theory::VarianceTheory> {
        self.construction.spectrum_theory(n, dims)
    }

    /// The shape of `n` points in `dims` dimensions of this sampler, unchecked: for
    /// [`Sampler::plan`] and the stages, which check it.
    pub(crate) fn shape(&self, n: usize, dims: usize) -> Shape {
        Shape { n, dims, sampler: self.spec.clone() }
    }

    /// The count checks of `shape` (its entry's rule, then the construction's), the errors
    /// named by `shape`'s sampler (a stage checks the sampler before it under its own name).
    pub(crate) fn check_count(&self, shape: &Shape) -> Result<()> {
        if let Some(reason) = self.counts.and_then(|c| c.check(shape.n, shape.dims).err()) {
            return Err(shape.invalid_count(reason));
        }
        self.construction.check_count(shape)
    }

    /// Prepare `shape`'s count and dimension, the errors named by this sampler (for a stage
    /// that checked them).
    pub(crate) fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        self.construction.prepare(&self.shape(shape.n, shape.dims))
    }

    /// Check that the sampler makes `dims` dimensions: the first of `plan`'s checks, for a
    /// front end that holds a sampler for one dimension before any count.
    ///
    /// # Errors
    /// [`Error::InvalidDims`] naming the dimensions it makes.
    pub fn check_dims(&self, dims: usize) -> Result<()> {
        let range = self.dims();
        if range.contains(&dims) {
            return Ok(());
        }
        Err(Error::InvalidDims {
            sampler: self.spec().to_string(),
            dims,
            supported: format!("{}..={}", range.start(), range.end()),
        })
    }

    /// Check that `n` points in `dims` dimensions can be made, and prepare to make them
    /// ([`Construction::prepare`]: every table built here, once).
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
    pub fn plan(&self, n: usize, dims: usize) -> Result<Plan> {
        self.check_dims(dims)?;
        if n == 0 || n > MAX_POINTS || n.checked_mul(dims).is_none() {
            return Err(Error::InvalidCount {
                sampler: self.spec().to_string(),
                n,
                dims,
                reason: format!("n must be in 1..={MAX_POINTS}"),
            });
        }
        let shape = self.shape(n, dims);
        self.check_count(&shape)?;
        let prepared = self.construction.prepare(&shape)?;
        Ok(Plan { shape, prepared })
    }

    /// `n` points in [0,1)^dims for `seed`: `plan`, then [`Plan::generate`].
    ///
    /// # Errors
    /// As `plan` and [`Plan::fill`].
    pub fn generate(&self, n: usize, dims: usize, seed: Seed) -> Result<PointSet> {
        self.plan(n, dims)?.generate(seed)
    }
}

/// A sampler prepared for one [`Shape`] ([`Construction::prepare`]): it fills sets from seeds,
/// and, for the progressive sequences, gives random access and streams.
pub trait Prepared: Send + Sync {
    /// Write the set for `seed` into `out` (length `n * dims`, row-major), advancing
    /// `progress` by [`Prepared::units`] in all (an optimizer once per iteration, stopping
    /// between iterations when `progress` says so).
    ///
    /// # Errors
    /// A construction that fails for this seed ([`Error::Infeasible`]), or a stop.
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()>;

    /// The units of progress one set reports: an optimizer's iterations, 1 otherwise.
    fn units(&self) -> u64 {
        1
    }

    /// Random access to coordinate `dim` of point `index` for `seed` (the progressive
    /// sequences: Halton, Sobol', nets, the lattice sequence), equal bit for bit to the
    /// batch; `None` for the other samplers.
    fn access(&self, _seed: Seed) -> Option<Box<dyn Access + '_>> {
        None
    }

    /// Coordinate `dim` of point `index` for `seed`, equal to what [`Prepared::access`]
    /// gives, one value at a time: a point set served per pixel ([`crate::pixel`]) asks
    /// each value under the pixel's own seed. The default prepares the seed's whole access;
    /// a sequence whose keys are cheap per coordinate (Sobol') overrides it.
    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        self.access(seed).map(|access| access.sample(index, dim))
    }

    /// The set for `seed` made chunk by chunk, for a sampler without random access that can
    /// (random); the sequences stream through [`Prepared::access`].
    fn stream(&self, _seed: Seed) -> Option<Box<dyn Stream + '_>> {
        None
    }

    /// A digital net's generating matrices, whose t its randomizations keep (a digital
    /// shift, a linear matrix scramble, Owen's): `None` for the other samplers.
    fn generating_matrices(&self) -> Option<&qmc::net::Matrices> {
        None
    }
}

/// The prepared state of a sampler that needs no tables: `fill(seed, out)` writes one set
/// (`out` holds n x dims coordinates, row-major); one unit of progress per set.
pub fn from_fill(fill: impl Fn(Seed, &mut [f64]) -> Result<()> + Send + Sync + 'static) -> Box<dyn Prepared> {
    Box::new(FromFill(fill))
}

/// The prepared state of an optimizer without tables: `units` units of progress per set,
/// which `fill(seed, out, progress)` reports itself (once per iteration).
pub fn from_fill_reporting(
    units: u64,
    fill: impl Fn(Seed, &mut [f64], &Progress) -> Result<()> + Send + Sync + 'static,
) -> Box<dyn Prepared> {
    Box::new(FromFillReporting { units, fill })
}

struct FromFill<F>(F);

impl<F: Fn(Seed, &mut [f64]) -> Result<()> + Send + Sync> Prepared for FromFill<F> {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        (self.0)(seed, out)?;
        progress.advance(1)
    }
}

struct FromFillReporting<F> {
    units: u64,
    fill: F,
}

impl<F: Fn(Seed, &mut [f64], &Progress) -> Result<()> + Send + Sync> Prepared for FromFillReporting<F> {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        (self.fill)(seed, out, progress)
    }
    fn units(&self) -> u64 {
        self.units
    }
}

/// A sampler checked for one count and dimension, with its prepared tables: fill it from as
/// many seeds as needed.
pub struct Plan {
    shape: Shape,
    prepared: Box<dyn Prepared>,
}

impl Debug for Plan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Plan({}, n = {}, d = {})", self.shape.sampler, self.shape.n, self.shape.dims)
    }
}

impl Plan {
    /// Points per set.
    pub fn n(&self) -> usize {
        self.shape.n
    }

    /// Dimensions.
    pub fn dims(&self) -> usize {
        self.shape.dims
    }

    /// The sampler's canonical spec.
    pub fn spec(&self) -> &str {
        self.shape.sampler()
    }

    /// Write the `n` points for `seed` into `out` (length `n * dims`, row-major), reading
    /// the tables built by `plan`.
    ///
    /// # Errors
    /// Only the stochastic constructions that can fail for a seed: Poisson-disk samplers
    /// whose dart throwing (or radius search) could not place `n` points
    /// ([`Error::Infeasible`]). Every other sampler's fill cannot fail once planned.
    ///
    /// # Panics
    /// When `out.len() != n * dims`.
    pub fn fill(&self, seed: Seed, out: &mut [f64]) -> Result<()> {
        self.fill_reporting(seed, out, &Progress::SILENT)
    }

    /// [`Plan::fill`], advancing `progress` by [`Plan::units`].
    fn fill_reporting(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        assert_eq!(out.len(), self.shape.n * self.shape.dims, "the buffer must hold n x dims coordinates");
        self.prepared.fill(seed, out, progress)
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
        let mut data = crate::memory::zeroed(|| self.describe(1), self.shape.n * self.shape.dims)?;
        self.fill_reporting(seed, &mut data, progress)?;
        Ok(PointSet::from_raw(self.shape.dims, data))
    }

    /// The units of progress one set reports ([`Plan::generate_sets`], [`Plan::stack`]): an
    /// optimizer's iterations, 1 for the other samplers.
    pub fn units(&self) -> u64 {
        self.prepared.units()
    }

    /// `m` realizations in parallel; realization k uses `seed.derive(k)`, so the sets are
    /// the same whatever the thread count. `progress` advances by [`Plan::units`] per set
    /// (an optimizer: one per iteration) and can stop the work.
    ///
    /// # Errors
    /// [`Error::Memory`] before any work when the sets do not fit, a stop
    /// ([`Error::Interrupted`]), or as [`Plan::fill`] (the first failing realization's).
    pub fn generate_sets(&self, seed: Seed, m: usize, progress: &Progress) -> Result<Vec<PointSet>> {
        crate::memory::check(|| self.describe(m), 8 * m as u128 * (self.shape.n * self.shape.dims) as u128)?;
        (0..m as u64)
            .into_par_iter()
            .map(|k| {
                progress.check()?;
                self.generate_reporting(seed.derive(k), progress)
            })
            .collect()
    }

    /// Random access to the points for `seed` (the progressive sequences; `None` for the
    /// others): coordinate `dim` of point `index`, equal bit for bit to [`Plan::generate`]
    /// for the indices below n, and on past n as far as the sequence goes.
    pub fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        self.prepared.access(seed)
    }

    /// The generating matrices of a digital net (the families of `net`: their t, from
    /// [`crate::discrepancy::tvalue::of_matrices`], is the points' under every randomization
    /// but a Cranley-Patterson shift); `None` for the other samplers.
    pub fn generating_matrices(&self) -> Option<&qmc::net::Matrices> {
        self.prepared.generating_matrices()
    }

    /// Coordinate `dim` of point `index` for `seed`, as [`Plan::access`] gives it, without
    /// keeping the access (`None` for the samplers without random access).
    pub fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        self.prepared.sample_at(seed, index, dim)
    }

    /// The set for `seed` made chunk by chunk, equal to [`Plan::generate`]`(seed)`, for the
    /// samplers that can (the sequences, random); `None` for the others.
    pub fn stream(&self, seed: Seed) -> Option<Box<dyn Stream + '_>> {
        match self.prepared.access(seed) {
            Some(access) => Some(Box::new(Indexed { access, dims: self.shape.dims, index: 0 })),
            None => self.prepared.stream(seed),
        }
    }

    /// `m sets of n dD points` (`n dD points` for one set), for messages.
    fn describe(&self, m: usize) -> String {
        match m {
            1 => format!("{} {}D points", self.shape.n, self.shape.dims),
            m => format!("{m} sets of {} {}D points", self.shape.n, self.shape.dims),
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
        let (size, m) = (
            self.shape.n * self.shape.dims,
            usize::try_from(sets.end.saturating_sub(sets.start)).unwrap_or(usize::MAX),
        );
        let mut out = crate::memory::zeroed(|| self.describe(m), m.saturating_mul(size))?;
        out.par_chunks_mut(size).enumerate().try_for_each(|(j, set)| {
            progress.check()?;
            self.fill_reporting(seed.derive(sets.start + j as u64), set, progress)
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

/// Random access to a progressive sequence for one seed ([`Plan::access`]).
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
/// As [`Sampler::plan`] and [`Plan::fill`].
pub fn generate_sets(sampler: &Sampler, n: usize, dims: usize, seed: Seed, m: usize) -> Result<Vec<PointSet>> {
    sampler.plan(n, dims)?.generate_sets(seed, m, &Progress::SILENT)
}

#[cfg(test)]
mod tests {
    use super::*;

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
