//! The t-value of a point set as a (t, m, s)-net in base b (Niederreiter 1992, definition
//! 4.1), counted on its points by brute force, so that it holds for any set (scrambled or
//! not, a saved file, a pixel's samples): n = b^m points form a (t, m, s)-net when every
//! elementary interval of volume b^(t-m), the product of [a_j b^-d_j, (a_j + 1) b^-d_j)
//! over the axes with d_1 + ... + d_s = m - t, holds exactly b^t of them. The value is the
//! least such t; with `projection=pairs`, the largest over the set's 2D projections (the
//! quality of the worst pair, which the 2023-2025 papers argue with), with
//! `projection=consecutive` over its pairs (j, j + 1) and with `projection=quadruples` over
//! its consecutive quadruples. A digital net's t also follows from its generating matrices,
//! by ranks ([`of_matrices`]), without making its points.

use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::sampler::qmc::net::Matrices;
use crate::registry::About;
use crate::spec::{Default, Kind, ParamSpec, Params};

const BASE: ParamSpec = ParamSpec {
    name: "base",
    kind: Kind::Int { min: 2, max: 64 },
    default: Default::Int(2),
    doc: "the base b: the set must have b^m points",
};

const PROJECTION: ParamSpec = ParamSpec {
    name: "projection",
    kind: Kind::Choice(&["all", "pairs", "consecutive", "quadruples"]),
    default: Default::Word("all"),
    doc: "the whole set, or the largest t over its 2D projections (pairs), over its pairs of consecutive dimensions \
          (j, j + 1), or over its consecutive quadruples (j .. j + 3)",
};

/// A coordinate this close below a cell's edge counts in the cell above: the points of an
/// unscrambled net in an odd base are rounded rationals (1/3 is stored below 1/3).
const EDGE: f64 = 1e-12;

/// Whether the axes `axes` of `points` (b^m of them) have `b^(m-k)` points in every
/// elementary interval of volume b^-k: every split of k digits among the axes.
fn stratified(points: &PointSet, axes: &[usize], b: usize, k: usize, cells: &mut Vec<u32>) -> bool {
    let s = axes.len();
    let mut split = vec![0usize; s];
    split[s - 1] = k;
    let per = points.len() / b.pow(k as u32);
    loop {
        cells.clear();
        cells.resize(b.pow(k as u32), 0);
        for p in points.iter() {
            let cell = axes.iter().zip(&split).fold(0usize, |acc, (&a, &kj)| {
                let side = b.pow(kj as u32);
                acc * side + ((p[a] * side as f64 + EDGE) as usize).min(side - 1)
            });
            cells[cell] += 1;
        }
        if cells.iter().any(|&c| c as usize != per) {
            return false;
        }
        if !next_composition(&mut split) {
            return true;
        }
    }
}

/// The next composition of `split`'s sum into its parts (starting from all in the last
/// part), or `false` after the last.
fn next_composition(split: &mut [usize]) -> bool {
    let s = split.len();
    let Some(j) = (0..s - 1).rev().find(|&j| split[j + 1..].iter().sum::<usize>() > 0) else { return false };
    let rest: usize = split[j + 1..].iter().sum();
    split[j] += 1;
    split[j + 1..].iter_mut().for_each(|x| *x = 0);
    split[s - 1] = rest - 1;
    true
}

/// The least t of the axes `axes` as a (t, m, s)-net in base b.
fn t_of(points: &PointSet, axes: &[usize], b: usize, m: usize, cells: &mut Vec<u32>) -> usize {
    // strength k (every interval of volume b^-k balanced) holds for every k below a strength
    // that holds: the finest strength is m - t
    let strength = (1..=m).take_while(|&k| stratified(points, axes, b, k, cells)).last().unwrap_or(0);
    m - strength
}

/// The least t of `points` (b^m of them) as a (t, m, s)-net in base b over all their axes,
/// counted interval by interval.
pub fn counted(points: &PointSet, b: usize, m: usize) -> usize {
    let axes: Vec<usize> = (0..points.dims()).collect();
    t_of(points, &axes, b, m, &mut Vec::new())
}

/// C(n, k) as a float (the number of compositions, for the work estimate).
fn choose(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The refusal of the t-value's parameter `param`.
fn param(param: &str, reason: String) -> Error {
    Error::Param { owner: "t-value".into(), param: param.into(), reason }
}

/// The axes of each projection of `kind` (`all`, `pairs`, `consecutive` or `quadruples`,
/// the words of the `t-value` metric's `projection`) of an `s`-dimensional set.
///
/// # Errors
/// A kind that names none of them, or projections wider than the set.
pub fn projections(kind: &str, s: usize) -> Result<Vec<Vec<usize>>> {
    let width = match kind {
        "all" => s,
        "quadruples" => 4,
        "pairs" | "consecutive" => 2,
        _ => return Err(param("projection", format!("'{kind}': expected all, pairs, consecutive or quadruples"))),
    };
    if width > s || s == 0 {
        return Err(Error::Dimension { what: format!("the t-value of {kind}"), takes: format!("sets of {width} or more dimensions"), got: s });
    }
    Ok(match kind {
        "pairs" => (0..s).flat_map(|i| (i + 1..s).map(move |j| vec![i, j])).collect(),
        "all" => vec![(0..s).collect()],
        // consecutive pairs or quadruples
        _ => (0..=s - width).map(|j| (j..j + width).collect()).collect(),
    })
}

/// The t of each projection of a sampler's nets, at every count b^m, m = 1..=most: from
/// the generating matrices where the sampler has them (the digital nets: their t holds
/// under every scramble they take), else counted on the points of the seed's set.
#[derive(Debug, Clone, PartialEq)]
pub struct ProjectionTable {
    /// The base b.
    pub base: u32,
    /// Whether the values come from the generating matrices (else from the points).
    pub from_matrices: bool,
    /// Each projection's axes.
    pub axes: Vec<Vec<usize>>,
    /// `t[j][m - 1]`: projection j's t at b^m points.
    pub t: Vec<Vec<usize>>,
}

impl ProjectionTable {
    /// Where the values come from, in words, for `spec` (and `seed`, counted on points).
    pub fn source(&self, spec: &str, seed: crate::Seed) -> String {
        if self.from_matrices {
            format!("{spec}: t from the generating matrices (ranks over GF({}))", self.base)
        } else {
            format!("{spec} (seed {}): t counted on the points in base {}", seed.0, self.base)
        }
    }

    /// The table as JSON (`samplab t-values --json`, Python's `t_values`): the source, the
    /// base, whether from the matrices, and each projection's axes and t at m = 1, 2, ...
    pub fn json(&self, spec: &str, seed: crate::Seed) -> String {
        let projections: Vec<serde_json::Value> =
            self.axes.iter().zip(&self.t).map(|(a, row)| serde_json::json!({ "axes": a, "t": row })).collect();
        let value = serde_json::json!({
            "source": self.source(spec, seed),
            "base": self.base,
            "from_matrices": self.from_matrices,
            "projections": projections,
        });
        format!("{value:#}\n")
    }
}

/// The [`ProjectionTable`] of `sampler` in `dims` dimensions, for `kind` (as
/// [`projections`]), at b^m points for m = 1..=`most`; `base` is the matrices' for a
/// digital net, the one given (2 when none) otherwise, where set 0 of `seed` is counted
/// (the set `samplab generate --seed` writes). The progress of `limits` advances by one
/// per m.
///
/// # Errors
/// The sampler's own (a count it cannot make), a base that disagrees with the matrices',
/// a projection wider than the set, more work than `limits` allow, or a stop.
pub fn projection_table(
    sampler: &crate::Sampler,
    dims: usize,
    most: usize,
    kind: &str,
    base: Option<u32>,
    seed: crate::Seed,
    limits: &Limits,
) -> Result<ProjectionTable> {
    let axes = projections(kind, dims)?;
    // the matrices decide the base; a set without them is counted in the base given
    let probe = sampler.plan(1, dims).ok();
    let probed = probe.as_ref().and_then(crate::sampler::Plan::generating_matrices);
    let from_matrices = probed.is_some();
    let b = match (probed.map(Matrices::base), base) {
        (Some(m), Some(given)) if m != given => {
            return Err(param("base", format!("{given} for matrices in base {m}")));
        }
        (Some(m), _) => m,
        (None, given) => given.unwrap_or(2),
    };
    if !(2..=64).contains(&b) || (b as f64).powi(most as i32) > 2f64.powi(32) {
        return Err(param("base", format!("{b}^{most} points (base 2 to 64, at most 2^32 points)")));
    }
    if !from_matrices {
        // every count's box count, refused before any set is made
        let width = axes[0].len();
        let work: f64 = (1..=most)
            .map(|m| axes.len() as f64 * (1..=m).map(|k| choose(k + width - 1, width - 1)).sum::<f64>() * f64::from(b).powi(m as i32))
            .sum();
        limits.allow_points("the t-value", (b as usize).pow(most as u32), dims, work)?;
    }
    let mut t = vec![Vec::with_capacity(most); axes.len()];
    let mut cells = Vec::new();
    for m in 1..=most {
        let plan = sampler.plan((b as usize).pow(m as u32), dims)?;
        match plan.generating_matrices() {
            Some(matrices) => {
                for (row, a) in t.iter_mut().zip(&axes) {
                    row.push(of_matrices(matrices, a, m, limits)?);
                }
            }
            None => {
                // set 0 of the seed, as `samplab generate --seed` writes it
                let points = plan.generate(seed.derive(0))?;
                for (row, a) in t.iter_mut().zip(&axes) {
                    limits.progress.check()?;
                    row.push(t_of(&points, a, b as usize, m, &mut cells));
                }
            }
        }
        limits.progress.advance(1)?;
    }
    Ok(ProjectionTable { base: b, from_matrices, axes, t })
}

fn t_value(p: &Params, points: &PointSet, limits: Limits) -> Result<f64> {
    let b = p.int("base") as usize;
    let n = points.len();
    let m = (0..=64)
        .find(|&m| b.checked_pow(m as u32) == Some(n))
        .ok_or_else(|| param("base", format!("{n} points are not a power of the base {b}")))?;
    let projections = projections(p.word("projection"), points.dims())?;
    let width = projections[0].len();
    // each strength k counts the points once per composition of k into the axes
    let work: f64 = projections.len() as f64 * (1..=m).map(|k| choose(k + width - 1, width - 1)).sum::<f64>() * n as f64;
    limits.allow("the t-value", points, work)?;
    let mut cells = Vec::new();
    let mut worst = 0;
    for axes in &projections {
        limits.progress.check()?;
        worst = worst.max(t_of(points, axes, b, m, &mut cells));
    }
    Ok(worst as f64)
}

/// Whether `rows` (digits in base b, each as long) are linearly independent over GF(b), by
/// elimination; base 2 as bit words.
fn independent(rows: &[Vec<u8>], b: u32) -> bool {
    if b == 2 && rows.first().is_none_or(|r| r.len() <= 64) {
        // a basis indexed by its leading bit: a row reduced to zero depends on the others
        let mut basis = [0u64; 64];
        for r in rows {
            let mut x = r.iter().fold(0u64, |w, &d| w << 1 | u64::from(d));
            while x != 0 {
                let lead = 63 - x.leading_zeros() as usize;
                if basis[lead] == 0 {
                    basis[lead] = x;
                    break;
                }
                x ^= basis[lead];
            }
            if x == 0 {
                return false;
            }
        }
        return true;
    }
    let mut rows: Vec<Vec<u32>> = rows.iter().map(|r| r.iter().map(|&d| u32::from(d)).collect()).collect();
    let (n, width) = (rows.len(), rows.first().map_or(0, Vec::len));
    let mut rank = 0;
    for col in 0..width {
        let Some(p) = (rank..n).find(|&i| rows[i][col] != 0) else { continue };
        rows.swap(rank, p);
        // the pivot scaled to 1 (b is prime: x^(b-2) is x's inverse)
        let inverse = (0..b - 2).fold(1, |acc, _| acc * rows[rank][col] % b);
        rows[rank].iter_mut().for_each(|x| *x = *x * inverse % b);
        let pivot = rows[rank].clone();
        for (i, r) in rows.iter_mut().enumerate() {
            let f = r[col];
            if i != rank && f != 0 {
                r.iter_mut().zip(&pivot).for_each(|(x, &y)| *x = (*x + (b - f) * y) % b);
            }
        }
        rank += 1;
    }
    rank == n
}

/// The least t of the first b^m points of a digital net on the axes `axes`, from its
/// generating matrices: the least t such that, for every split d_1 + ... + d_s = m - t of
/// digits among the axes, the first d_j rows of axis j's matrix (its first m columns) are
/// linearly independent over GF(b) (Niederreiter 1992, theorem 4.28). It is the t the
/// points of the net have (the [`t-value`](self) metric counts it on them), and that of
/// every digital scramble of them (a digital shift, a linear matrix scramble, Owen's).
///
/// # Errors
/// More columns than the matrices have, an axis past their dimensions, no axis, more work
/// than `limits` allow (the compositions of m digits among the axes, each an elimination),
/// or a stop.
pub fn of_matrices(matrices: &Matrices, axes: &[usize], m: usize, limits: &Limits) -> Result<usize> {
    let what = || "the t-value of generating matrices".to_string();
    if m > matrices.cols() {
        return Err(Error::Mismatch { what: what(), expected: format!("{m} columns"), got: matrices.cols().to_string() });
    }
    if let Some(&a) = axes.iter().find(|&&a| a >= matrices.dims()) {
        return Err(Error::Dimension { what: format!("axis {a}"), takes: format!("matrices of more than {a} dimensions"), got: matrices.dims() });
    }
    let s = axes.len();
    if s == 0 {
        return Err(Error::TooFew { what: what(), least: 1, of: "axis", got: 0 });
    }
    let work = choose(m + s - 1, s - 1) * (m * m) as f64;
    if work > limits.max_work {
        return Err(Error::WorkLimit { what: format!("the t-value of {s} axes at {m} columns"), work, limit: limits.max_work });
    }
    let row = |a: usize, r: usize| -> Vec<u8> {
        (0..m).map(|k| if r < matrices.rows() { matrices.digit(a, r, k) as u8 } else { 0 }).collect()
    };
    let b = matrices.base();
    // the first t whose strength m - t holds (every weaker one then holds too)
    for t in 0..m {
        limits.progress.check()?;
        let mut split = vec![0usize; s];
        split[s - 1] = m - t;
        let holds = loop {
            let rows: Vec<Vec<u8>> = axes.iter().zip(&split).flat_map(|(&a, &d)| (0..d).map(move |r| (a, r))).map(|(a, r)| row(a, r)).collect();
            if !independent(&rows, b) {
                break false;
            }
            if !next_composition(&mut split) {
                break true;
            }
        };
        if holds {
            return Ok(t);
        }
    }
    Ok(m)
}

/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry::new(
    About::new("t-value", "the least t of a (t,m,s)-net in base b, by brute force over elementary intervals")
        .params(&[BASE, PROJECTION])
        .cite(&["niederreiter1992"]),
    t_value,
)];
