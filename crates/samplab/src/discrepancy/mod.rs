//! Discrepancy: how far a point set's empirical measure is from the uniform one
//! (Shirley 1991 section 3.1), with every variant the papers use.
//!
//! ## Conventions
//!
//! - Points must lie in the closed unit cube \[0,1\]^d (1.0 is allowed and handled).
//! - Every value is reported **unsquared**. The L2 family is computed squared in closed
//!   form and the root taken after clamping at zero (the closed forms cancel heavily; the
//!   sums are compensated). Beware when comparing: `scipy.stats.qmc.discrepancy` returns
//!   the L2-star value unsquared but the centered (CD), wrap-around (WD) and mixture (MD)
//!   values squared.
//! - Invariant under toroidal shifts of the set: `wraparound` only. `extreme` is
//!   invariant under reflections of the axes (Shirley: "a 90 degree rotation"), `star` is not.
//!
//! | metric | algorithm | cost |
//! |---|---|---|
//! | `star` | 1D closed form; 2D sweep + kinetic segment tree; d >= 3 Dobkin-Eppstein-Mitchell cells + knapsack | n log n; n log^2 n; n^(1+d/2) |
//! | `extreme` | 1D closed form; 2D branch and bound over slabs | n log n; data-dependent (n = 10^4: 0.5-5 s for random to Sobol' sets on two cores), at worst n^3 |
//! | `l2-star`, `l2-extreme`, `centered`, `wraparound`, `mixture`, `diaphony` | closed forms (Warnock, Hickernell, Zinterhof); in 2D a merge-sort sweep | d n^2; 2D n log n |
//! | `projected` | 1D star/extreme of the projections against their exact CDF | n log n |
//! | `star-bound` | threshold accepting: a LOWER BOUND on the star discrepancy | iterations x n d |
//! | `min-distance`, `relative-radius` | grid of cells, rings widened until the smallest distance is confirmed | n expected (d <= 4); n^2 d |
//! | `pcf`, `rdf` | pairs within reach through a grid of cells ([`crate::spatial`]) | pairs within reach x radii |
//! | `nyquist`, `oscillation` | the periodogram at the integer frequencies out to 2 sqrt(n) or 7 sqrt(n) (NUFFT) | n + R^2 log R, R ~ sqrt(n) |

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::registry::{About, Entry, canonical};
use crate::spec::Params;

mod kinetic;

pub use projected::projected_uniform;

/// One registered metric: what it is, its flags, and how to compute it.
#[derive(Debug)]
pub struct MetricEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Whether the value is the root of a squared closed form (an L2 metric).
    pub l2: bool,
    /// Whether the value is invariant under toroidal shifts of the set.
    pub shift_invariant: bool,
    /// Whether the value is only a lower bound on the metric.
    pub lower_bound: bool,
    /// The memory its computation takes beyond the points, in bytes per point (an upper
    /// bound read off the peak resident memory at 2 x 10^6 2D points, 2026-12-05).
    pub bytes_per_point: u32,
    /// The value (unsquared) for resolved parameters, on a non-empty set inside [0,1]^d.
    pub(crate) compute: fn(&Params, &PointSet, Limits) -> Result<f64>,
}

impl MetricEntry {
    /// A metric with no flags set, taking [`WORKING_BYTES`] per point.
    pub(crate) const fn new(about: About, compute: fn(&Params, &PointSet, Limits) -> Result<f64>) -> MetricEntry {
        MetricEntry {
            about,
            l2: false,
            shift_invariant: false,
            lower_bound: false,
            bytes_per_point: WORKING_BYTES,
            compute,
        }
    }
}

/// The memory a metric's computation takes per point unless its entry says otherwise: the
/// L2 family's sorts and sweeps and the spacing metrics' grids measured 40-50 bytes.
const WORKING_BYTES: u32 = 64;

impl Entry for MetricEntry {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        [
            (self.l2, "L2: the root of a closed form"),
            (self.shift_invariant, "invariant under toroidal shifts of the set"),
            (self.lower_bound, "a LOWER BOUND, not the exact value"),
        ]
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, text)| (*text).to_string())
        .collect()
    }
}

crate::registry::registry_files! {
    /// Every metric, in listing order, gathered from the files that declare them.
    pub static METRICS: Registry<MetricEntry> =
        ("metric", "METRICS  (values are never squared)") from [star, extreme, l2, bound, projected, spacing, aliasing, tvalue];
}

/// A discrepancy to compute: a registered metric with its parameters.
///
/// ```
/// use samplab::discrepancy::{Limits, Metric, compute};
/// use samplab::PointSet;
/// let metric = Metric::parse("projected:angle=30,kind=extreme").unwrap();
/// assert_eq!(metric.spec(), "projected:angle=30,kind=extreme");
/// let points = PointSet::new(2, vec![0.25, 0.25, 0.75, 0.75]).unwrap();
/// let d = compute(&Metric::parse("star").unwrap(), &points, Limits::default()).unwrap();
/// assert!((d - 0.4375).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct Metric {
    entry: &'static MetricEntry,
    params: Params,
}

impl Metric {
    /// Parse `star`, `l2-star`, `projected:angle=30,kind=extreme`, ...
    ///
    /// # Errors
    /// An unknown name (with suggestions) or bad parameters.
    pub fn parse(text: &str) -> Result<Metric> {
        let (entry, params) = METRICS.resolve(text)?;
        Ok(Metric { entry, params })
    }

    /// The registry entry (name, flags, references).
    pub fn entry(&self) -> &'static MetricEntry {
        self.entry
    }

    /// The memory its computation on `n` points takes beyond the points themselves.
    pub fn memory(&self, n: usize) -> u128 {
        u128::from(self.entry.bytes_per_point) * n as u128
    }

    /// The canonical spec of this metric, every parameter spelled out.
    pub fn spec(&self) -> String {
        canonical(&self.entry.about, &self.params)
    }

    /// The canonical spec and the entry's flags.
    pub fn flags(&self) -> Flags {
        Flags {
            metric: self.spec(),
            squared: false,
            l2_closed_form: self.entry.l2,
            toroidal_shift_invariant: self.entry.shift_invariant,
            lower_bound: self.entry.lower_bound,
        }
    }
}

/// What a metric's value is: its canonical spec and flags, as `samplab discrepancy --json`
/// and the Python package report them.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Flags {
    /// The canonical spec.
    pub metric: String,
    /// Whether values are squared (never: every value is reported unsquared).
    pub squared: bool,
    /// Whether the value is the root of a squared closed form.
    pub l2_closed_form: bool,
    /// Whether the value is invariant under toroidal shifts of the set.
    pub toroidal_shift_invariant: bool,
    /// Whether the value is only a lower bound.
    pub lower_bound: bool,
}

/// `samplab discrepancy --json`: the source, the sets and their sizes `ns`, and per metric
/// its flags, its values on every set (`values[m][k]`), their mean, sd (n - 1) and maximum.
///
/// # Panics
/// Never: plain fields and numbers always make JSON.
pub fn json(metrics: &[Metric], values: &[Vec<f64>], ns: &[usize], source: &str) -> String {
    let rows: Vec<serde_json::Value> = metrics
        .iter()
        .zip(values)
        .map(|(m, v)| {
            let s = crate::stats::Summary::of(v);
            let mut row = serde_json::to_value(m.flags()).expect("JSON of plain fields");
            let fields = row.as_object_mut().expect("a struct is an object");
            for (key, value) in
                [("values", serde_json::json!(v)), ("mean", s.mean.into()), ("sd", s.sd.into()), ("max", s.max.into())]
            {
                fields.insert(key.into(), value);
            }
            row
        })
        .collect();
    let v = serde_json::json!({ "source": source, "sets": ns.len(), "n": ns, "metrics": rows });
    format!("{}\n", serde_json::to_string_pretty(&v).expect("JSON of plain numbers"))
}

/// Per metric its mean, sd (n - 1) and maximum over the sets, as CSV.
pub fn csv(metrics: &[Metric], values: &[Vec<f64>]) -> String {
    let mut out = crate::io::csv_line(["metric", "mean", "sd", "max"]);
    for (m, v) in metrics.iter().zip(values) {
        let s = crate::stats::Summary::of(v);
        out += &crate::io::csv_line([m.spec(), format!("{:?}", s.mean), format!("{:?}", s.sd), format!("{:?}", s.max)]);
    }
    out
}

/// Limits on the exact algorithms whose cost grows fastest.
#[derive(Debug, Clone, Copy)]
pub struct Limits<'a> {
    /// The largest number of elementary steps an exact algorithm may take, estimated before
    /// the work: n^(1 + d/2) for the d-D star discrepancy (d >= 3), n^2 log2 n for the 2D
    /// extreme (a nominal figure: its branch and bound's work depends on the set).
    pub max_work: f64,
    /// Checked between the tasks of the algorithms that can run long (the exact d-D star
    /// and 2D extreme discrepancies, the pair sums of the L2 family beyond 2D): once it says
    /// stop, they end with [`Error::Interrupted`].
    pub progress: Progress<'a>,
}

impl std::default::Default for Limits<'_> {
    fn default() -> Self {
        Limits { max_work: 2e10, progress: Progress::SILENT }
    }
}

impl<'a> Limits<'a> {
    /// The limits with `max_work` steps at most (the default when none), never stopped.
    ///
    /// # Errors
    /// [`Error::Setting`] `max_work` when it is not a positive number.
    pub fn new(max_work: Option<f64>) -> Result<Limits<'static>> {
        match max_work {
            Some(w) if w.is_nan() || w <= 0.0 => Err(Error::Setting {
                name: "max_work",
                value: w.to_string(),
                reason: "must be a positive number".into(),
            }),
            Some(w) => Ok(Limits { max_work: w, progress: Progress::SILENT }),
            None => Ok(Limits::default()),
        }
    }

    /// The same limits, stopped by `progress`.
    #[must_use]
    pub fn stopped_by<'b>(self, progress: Progress<'b>) -> Limits<'b> {
        Limits { max_work: self.max_work, progress }
    }

    /// Refuse `work` steps of `what` over the limit, before doing any of it.
    ///
    /// # Errors
    /// [`Error::WorkLimit`] when `work` exceeds [`Limits::max_work`].
    pub(crate) fn allow(&self, what: &str, points: &PointSet, work: f64) -> Result<()> {
        self.allow_points(what, points.len(), points.dims(), work)
    }

    /// [`Limits::allow`] for `n` points in `dims` dimensions not made yet.
    ///
    /// # Errors
    /// [`Error::WorkLimit`] when `work` exceeds [`Limits::max_work`].
    pub(crate) fn allow_points(&self, what: &str, n: usize, dims: usize, work: f64) -> Result<()> {
        if work > self.max_work {
            return Err(Error::WorkLimit {
                what: format!("{what} of {n} points in {dims}D"),
                work,
                limit: self.max_work,
            });
        }
        Ok(())
    }
}

/// Check that every coordinate lies in [0, 1].
///
/// # Errors
/// The first coordinate outside, by point and coordinate index.
pub fn check_unit_cube(points: &PointSet) -> Result<()> {
    use rayon::prelude::*;
    // the first coordinate outside, whatever the threads, found by blocks: each block's
    // test is a branch-free pass (a test a coordinate through rayon's `position_first`
    // cost 13 ns, 5% of the CPU time of `discrepancy l2-star centered` of 10^6 points)
    const BLOCK: usize = 1 << 14;
    let outside = |x: &f64| !(0.0..=1.0).contains(x);
    let (dims, xs) = (points.dims(), points.as_slice());
    let block = xs.par_chunks(BLOCK).position_first(|b| b.iter().fold(false, |any, x| any | outside(x)));
    match block.and_then(|b| xs[b * BLOCK..].iter().position(outside).map(|i| b * BLOCK + i)) {
        Some(at) => Err(Error::OutsideUnitCube { point: at / dims, coordinate: at % dims, value: xs[at] }),
        None => Ok(()),
    }
}

/// The discrepancy `metric` of `points` (unsquared).
///
/// # Errors
/// Points outside \[0,1\]^d, an empty set, a metric that needs another dimension, or an
/// exact algorithm whose cost would exceed `limits` ([`Error::WorkLimit`]).
pub fn compute(metric: &Metric, points: &PointSet, limits: Limits) -> Result<f64> {
    check_unit_cube(points)?;
    if points.is_empty() {
        return Err(Error::TooFew { what: "a discrepancy".into(), least: 1, of: "point", got: 0 });
    }
    (metric.entry.compute)(&metric.params, points, limits)
}

/// Generalized discrepancy for a separable density with per-axis CDFs (Shirley 1991
/// section 4): sup over rectangles (anchored at the support's lower corner when
/// `anchored`) of |n/N - E(n)/N|, E(n)/N the density's mass of the rectangle. Computed
/// exactly as the star or extreme discrepancy of the points mapped through the CDFs.
///
/// # Errors
/// As [`compute`]; one CDF per dimension is required.
pub fn generalized(points: &PointSet, cdfs: &[&dyn Fn(f64) -> f64], anchored: bool, limits: Limits) -> Result<f64> {
    if cdfs.len() != points.dims() {
        return Err(Error::Mismatch {
            what: "the CDFs".into(),
            expected: format!("one per dimension of {}D points", points.dims()),
            got: cdfs.len().to_string(),
        });
    }
    let mapped: Vec<f64> = points
        .iter()
        .flat_map(|p| p.iter().zip(cdfs).map(|(x, f)| f(*x).clamp(0.0, 1.0)).collect::<Vec<_>>())
        .collect();
    let mapped = PointSet::new(points.dims(), mapped)?;
    compute(&Metric::parse(if anchored { "star" } else { "extreme" })?, &mapped, limits)
}
