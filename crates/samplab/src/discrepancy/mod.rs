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
//! | `extreme` | 1D closed form; 2D slab sweep | n log n; n^3 |
//! | `l2-star` | Warnock's closed form; 2D Fenwick-tree form | d n^2; n log n |
//! | `l2-extreme`, `centered`, `wraparound`, `mixture` | Hickernell's closed forms | d n^2 |
//! | `projected` | 1D star/extreme of the projections against their exact CDF | n log n |
//! | `star-bound` | threshold accepting: a LOWER BOUND on the star discrepancy | iterations x n d |

use crate::error::{Error, Result, closest_names};
use crate::points::PointSet;
use crate::spec::{Default, Kind, ParamSpec, Params, Spec};

pub mod bound;
pub mod extreme;
mod kinetic;
pub mod l2;
pub mod star;

/// A discrepancy to compute.
#[derive(Debug, Clone, PartialEq)]
pub enum Metric {
    /// Star discrepancy D* (anchored boxes, sup norm).
    Star,
    /// Extreme (unanchored, Stroud's) discrepancy (all boxes, sup norm).
    Extreme,
    /// L2-star discrepancy (Shirley's root-mean-square S).
    L2Star,
    /// L2 discrepancy over all boxes.
    L2Extreme,
    /// Centered L2 discrepancy (Hickernell 1998).
    Centered,
    /// Wrap-around L2 discrepancy (Hickernell 1998).
    WrapAround,
    /// Mixture L2 discrepancy (Zhou, Fang & Ning 2013).
    Mixture,
    /// A lower bound on the star discrepancy by threshold accepting (any dimension; for
    /// high d and n where the exact algorithms are out of reach).
    StarBound {
        /// Search steps.
        iterations: usize,
        /// Seed of the search.
        seed: u64,
    },
    /// The 1D discrepancy of the projections onto the direction at `angle` degrees from
    /// the x axis, against the exact distribution of projected uniform points (2D).
    Projected {
        /// Direction, degrees.
        angle: f64,
        /// Half-lines (star) or intervals (extreme).
        extreme: bool,
    },
}

/// One registered metric.
#[derive(Debug)]
pub struct MetricEntry {
    /// Canonical name.
    pub name: &'static str,
    /// Other accepted names.
    pub aliases: &'static [&'static str],
    /// One line: what it measures.
    pub summary: &'static str,
    /// Parameters in positional order.
    pub params: &'static [ParamSpec],
    /// Whether the value is the root of a squared closed form (an L2 metric).
    pub l2: bool,
    /// Whether the value is invariant under toroidal shifts of the set.
    pub shift_invariant: bool,
    /// Whether the value is only a lower bound on the metric.
    pub lower_bound: bool,
    /// Bibliography keys.
    pub references: &'static [&'static str],
}

const PROJECTED_PARAMS: &[ParamSpec] = &[
    ParamSpec {
        name: "angle",
        kind: Kind::Real { min: -360.0, max: 360.0 },
        default: Default::Number(0.0),
        doc: "direction, degrees from the x axis",
    },
    ParamSpec {
        name: "kind",
        kind: Kind::Choice(&["star", "extreme"]),
        default: Default::Word("star"),
        doc: "half-lines or intervals",
    },
];

const STAR_BOUND_PARAMS: &[ParamSpec] = &[
    ParamSpec {
        name: "iterations",
        kind: Kind::Int { min: 1, max: 1_000_000_000 },
        default: Default::Number(20000.0),
        doc: "search steps (cost: iterations x n x d)",
    },
    ParamSpec {
        name: "seed",
        kind: Kind::Int { min: 0, max: u64::MAX },
        default: Default::Number(0.0),
        doc: "seed of the search",
    },
];

/// Every metric, in listing order.
pub static METRICS: &[MetricEntry] = &[
    MetricEntry {
        name: "star",
        aliases: &["d", "star-discrepancy"],
        summary: "sup over boxes anchored at the origin (Shirley's D)",
        params: &[],
        l2: false,
        shift_invariant: false,
        lower_bound: false,
        references: &["shirley1991"],
    },
    MetricEntry {
        name: "extreme",
        aliases: &["stroud", "unanchored", "t"],
        summary: "sup over all axis-parallel boxes (Stroud's T)",
        params: &[],
        l2: false,
        shift_invariant: false,
        lower_bound: false,
        references: &["shirley1991"],
    },
    MetricEntry {
        name: "l2-star",
        aliases: &["rms", "s", "warnock"],
        summary: "root mean square over anchored boxes (Shirley's S), Warnock's formula",
        params: &[],
        l2: true,
        shift_invariant: false,
        lower_bound: false,
        references: &["shirley1991"],
    },
    MetricEntry {
        name: "l2-extreme",
        aliases: &["l2-unanchored"],
        summary: "root mean square over all boxes",
        params: &[],
        l2: true,
        shift_invariant: false,
        lower_bound: false,
        references: &["shirley1991"],
    },
    MetricEntry {
        name: "centered",
        aliases: &["cd"],
        summary: "centered L2 discrepancy (Hickernell)",
        params: &[],
        l2: true,
        shift_invariant: false,
        lower_bound: false,
        references: &[],
    },
    MetricEntry {
        name: "wraparound",
        aliases: &["wd", "wrap-around"],
        summary: "wrap-around L2 discrepancy (Hickernell); toroidal-shift invariant",
        params: &[],
        l2: true,
        shift_invariant: true,
        lower_bound: false,
        references: &[],
    },
    MetricEntry {
        name: "mixture",
        aliases: &["md"],
        summary: "mixture L2 discrepancy",
        params: &[],
        l2: true,
        shift_invariant: false,
        lower_bound: false,
        references: &[],
    },
    MetricEntry {
        name: "star-bound",
        aliases: &["star-ta", "threshold-accepting"],
        summary: "LOWER BOUND on the star discrepancy by threshold accepting (high d and n)",
        params: STAR_BOUND_PARAMS,
        l2: false,
        shift_invariant: false,
        lower_bound: true,
        references: &[],
    },
    MetricEntry {
        name: "projected",
        aliases: &[],
        summary: "1D discrepancy of the projections onto a direction (2D)",
        params: PROJECTED_PARAMS,
        l2: false,
        shift_invariant: false,
        lower_bound: false,
        references: &["shirley1991"],
    },
];

impl Metric {
    /// Parse `star`, `l2-star`, `projected:angle=30,kind=extreme`, ...
    ///
    /// # Errors
    /// An unknown name (with suggestions) or bad parameters.
    pub fn parse(text: &str) -> Result<(Metric, &'static MetricEntry)> {
        let spec = Spec::parse(text)?;
        let want = spec.name.to_ascii_lowercase();
        let entry = METRICS.iter().find(|e| e.name == want || e.aliases.contains(&want.as_str())).ok_or_else(|| {
            Error::UnknownName {
                kind: "metric",
                name: spec.name.clone(),
                suggestions: closest_names(
                    &spec.name,
                    METRICS.iter().flat_map(|e| std::iter::once(e.name).chain(e.aliases.iter().copied())),
                ),
            }
        })?;
        let params = Params::resolve(entry.name, entry.params, &spec.args)?;
        let metric = match entry.name {
            "star" => Metric::Star,
            "extreme" => Metric::Extreme,
            "l2-star" => Metric::L2Star,
            "l2-extreme" => Metric::L2Extreme,
            "centered" => Metric::Centered,
            "wraparound" => Metric::WrapAround,
            "mixture" => Metric::Mixture,
            "star-bound" => Metric::StarBound {
                iterations: params.number("iterations").unwrap_or(20000.0) as usize,
                seed: params.number("seed").unwrap_or(0.0) as u64,
            },
            _ => Metric::Projected {
                angle: params.number("angle").unwrap_or(0.0),
                extreme: params.word("kind") == "extreme",
            },
        };
        Ok((metric, entry))
    }

    /// The canonical spec of this metric.
    pub fn spec(&self) -> String {
        match self {
            Metric::Star => "star".into(),
            Metric::Extreme => "extreme".into(),
            Metric::L2Star => "l2-star".into(),
            Metric::L2Extreme => "l2-extreme".into(),
            Metric::Centered => "centered".into(),
            Metric::WrapAround => "wraparound".into(),
            Metric::Mixture => "mixture".into(),
            Metric::StarBound { iterations, seed } => format!("star-bound:iterations={iterations},seed={seed}"),
            Metric::Projected { angle, extreme } => {
                format!("projected:angle={angle},kind={}", if *extreme { "extreme" } else { "star" })
            }
        }
    }
}

/// Limits on the exact algorithms whose cost grows fastest; `--max-work` raises them.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// The largest number of elementary steps an exact algorithm may take, estimated before
    /// the work: n^(1 + d/2) for the d-D star discrepancy (d >= 3), n^3 for the 2D extreme.
    pub max_work: f64,
}

impl std::default::Default for Limits {
    fn default() -> Self {
        Limits { max_work: 2e10 }
    }
}

/// Check that every coordinate lies in [0, 1].
///
/// # Errors
/// The first coordinate outside, by point and coordinate index.
pub fn check_unit_cube(points: &PointSet) -> Result<()> {
    for (i, p) in points.iter().enumerate() {
        if let Some(k) = p.iter().position(|x| !(0.0..=1.0).contains(x)) {
            return Err(Error::Invalid(format!("point {i} coordinate {k} is {} (outside [0, 1])", p[k])));
        }
    }
    Ok(())
}

/// The discrepancy `metric` of `points` (unsquared).
///
/// # Errors
/// Points outside \[0,1\]^d, an empty set, a metric that needs another dimension, or an
/// exact algorithm whose cost would exceed `limits` (the message names `--max-work`).
pub fn compute(metric: &Metric, points: &PointSet, limits: Limits) -> Result<f64> {
    check_unit_cube(points)?;
    if points.is_empty() {
        return Err(Error::Invalid("the set is empty".into()));
    }
    let (n, d) = (points.len() as f64, points.dims());
    let x = points.as_slice();
    let too_big = |what: &str, work: f64| {
        Err(Error::Invalid(format!(
            "{what} of {} points in {d}D takes about {work:.1e} steps, over the limit {:.1e}; raise it with --max-work (or max_work in Limits)",
            points.len(),
            limits.max_work
        )))
    };
    let root = |sq: f64| sq.max(0.0).sqrt();
    Ok(match metric {
        Metric::Star => match d {
            1 => star::star_1d(x),
            2 => star::star_2d(x),
            _ => {
                let work = star::star_dem_work(points.len(), d);
                if work > limits.max_work {
                    return too_big("the exact star discrepancy", work);
                }
                star::star_dem(x, d)
            }
        },
        Metric::Extreme => match d {
            1 => extreme::extreme_1d(x),
            2 => {
                let work = n.powi(3);
                if work > limits.max_work {
                    return too_big("the exact extreme discrepancy", work);
                }
                extreme::extreme_2d(x)
            }
            _ => {
                return Err(Error::Invalid(format!(
                    "the exact extreme discrepancy is implemented in 1D and 2D, not {d}D"
                )));
            }
        },
        Metric::L2Star if d == 2 => root(l2::l2_star_sq_2d(x)),
        Metric::L2Star => root(l2::l2_star_sq(x, d)),
        Metric::L2Extreme => root(l2::l2_extreme_sq(x, d)),
        Metric::Centered => root(l2::centered_sq(x, d)),
        Metric::WrapAround => root(l2::wraparound_sq(x, d)),
        Metric::Mixture => root(l2::mixture_sq(x, d)),
        Metric::StarBound { iterations, seed } => bound::star_lower_bound(x, d, *iterations, crate::Seed(*seed)),
        Metric::Projected { angle, extreme } => {
            if d != 2 {
                return Err(Error::Invalid(format!("projected discrepancy needs 2D points, got {d}D")));
            }
            let u = projected_uniform(points, *angle);
            if *extreme { extreme::extreme_1d(&u) } else { star::star_1d(&u) }
        }
    })
}

/// The projections t = x cos(angle) + y sin(angle), mapped through the exact CDF of the
/// projection of a uniform point of the square (a trapezoid), so that the generalized 1D
/// discrepancy of t equals the ordinary 1D discrepancy of the mapped values.
pub fn projected_uniform(points: &PointSet, angle_degrees: f64) -> Vec<f64> {
    let (s, c) = angle_degrees.to_radians().sin_cos();
    let (a, b) = (c.abs().max(s.abs()), c.abs().min(s.abs()));
    let offset = c.min(0.0) + s.min(0.0);
    let cdf = |z: f64| -> f64 {
        let z = z - offset;
        if b < 1e-15 {
            return (z / a).clamp(0.0, 1.0);
        }
        if z <= 0.0 {
            0.0
        } else if z <= b {
            z * z / (2.0 * a * b)
        } else if z <= a {
            (2.0 * z - b) / (2.0 * a)
        } else if z < a + b {
            1.0 - (a + b - z).powi(2) / (2.0 * a * b)
        } else {
            1.0
        }
    };
    points.iter().map(|p| cdf(p[0] * c + p[1] * s)).collect()
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
        return Err(Error::Invalid(format!("{} CDFs for {}D points", cdfs.len(), points.dims())));
    }
    let mapped: Vec<f64> = points
        .iter()
        .flat_map(|p| p.iter().zip(cdfs).map(|(x, f)| f(*x).clamp(0.0, 1.0)).collect::<Vec<_>>())
        .collect();
    let mapped = PointSet::new(points.dims(), mapped)?;
    compute(if anchored { &Metric::Star } else { &Metric::Extreme }, &mapped, limits)
}
