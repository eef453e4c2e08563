//! A lower bound on the star discrepancy in high dimension by threshold accepting (Winker
//! & Fang 1997; refined by Gnewuch, Wahlstrom & Winzen 2012): a randomized local search
//! over the critical boxes (corners on the grid of point coordinates and 1), accepting
//! moves that lose less than a threshold that decreases to zero, with a neighbourhood that
//! shrinks as it goes. Every evaluated box gives a true local discrepancy, so the best one
//! found is a lower bound on D*; it is exact only if the search happens to find the worst
//! box. Deterministic for a seed.

use super::star::critical;
use super::{Limits, MetricEntry};
use crate::error::Result;
use crate::points::PointSet;
use crate::registry::About;
use crate::seed::{Seed, below, uniform};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The local discrepancy of the critical box with corner indices `idx` (open and closed).
fn local(points: &[f64], dims: usize, axes: &[Vec<f64>], idx: &[usize]) -> f64 {
    let n = (points.len() / dims) as f64;
    let q: Vec<f64> = idx.iter().zip(axes).map(|(&i, a)| a[i]).collect();
    let vol: f64 = q.iter().product();
    let (mut open, mut closed) = (0usize, 0usize);
    for p in points.chunks_exact(dims) {
        open += usize::from(p.iter().zip(&q).all(|(x, b)| x < b));
        closed += usize::from(p.iter().zip(&q).all(|(x, b)| x <= b));
    }
    (vol - open as f64 / n).max(closed as f64 / n - vol)
}

/// Independent searches the iterations are split into.
const RESTARTS: usize = 8;

/// The best local discrepancy found in `iterations` steps of threshold accepting (split
/// into independent restarts): a lower bound on the star discrepancy. O(iterations n d).
pub fn star_lower_bound(points: &[f64], dims: usize, iterations: usize, seed: Seed) -> f64 {
    let axes: Vec<Vec<f64>> = (0..dims).map(|d| critical(points.iter().skip(d).step_by(dims).copied())).collect();
    let per = iterations.div_ceil(RESTARTS);
    (0..RESTARTS as u64).map(|r| search(points, dims, &axes, per, seed.derive(r))).fold(0.0, f64::max)
}

/// One threshold-accepting search.
fn search(points: &[f64], dims: usize, axes: &[Vec<f64>], iterations: usize, seed: Seed) -> f64 {
    let mut rng = seed.rng();
    // start from the box through a random point (closed) or the full box
    let mut idx: Vec<usize> =
        axes.iter().map(|a| a.len() - 1 - below(&mut rng, a.len() as u64 / 2 + 1) as usize).collect();
    let mut current = local(points, dims, axes, &idx);
    let mut best = current;
    // the first threshold: the typical loss of a random move
    let mut losses = Vec::new();
    let mut trial = idx.clone();
    for _ in 0..32 {
        for (t, a) in trial.iter_mut().zip(axes) {
            *t = below(&mut rng, a.len() as u64) as usize;
        }
        losses.push((current - local(points, dims, axes, &trial)).abs());
    }
    losses.sort_by(f64::total_cmp);
    let t0 = losses[losses.len() / 2];
    let mut next = idx.clone();
    for i in 0..iterations {
        let progress = i as f64 / iterations as f64;
        let threshold = t0 * (1.0 - progress);
        // move a few coordinates by up to a shrinking span of critical values
        for (d, a) in axes.iter().enumerate() {
            next[d] = idx[d];
            if uniform(&mut rng) < (2.0 / dims as f64).min(1.0) {
                let span = ((a.len() as f64 / 4.0) * (1.0 - progress)).ceil().max(1.0) as i64;
                let step = below(&mut rng, 2 * span as u64 + 1) as i64 - span;
                next[d] = (idx[d] as i64 + step).clamp(0, a.len() as i64 - 1) as usize;
            }
        }
        let value = local(points, dims, axes, &next);
        if value >= current - threshold {
            idx.copy_from_slice(&next);
            current = value;
            best = best.max(value);
        }
    }
    best
}

/// The metric this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry {
    lower_bound: true,
    ..MetricEntry::new(
        About::new("star-bound", "LOWER BOUND on the star discrepancy by threshold accepting (high d and n)")
            .aliases(&["star-ta", "threshold-accepting"])
            .params(&[
                ParamSpec {
                    name: "iterations",
                    kind: Kind::Int { min: 1, max: 1_000_000_000 },
                    default: Default::Int(20000),
                    doc: "search steps (cost: iterations x n x d)",
                },
                ParamSpec {
                    name: "seed",
                    kind: Kind::Int { min: 0, max: u64::MAX },
                    default: Default::Int(0),
                    doc: "seed of the search",
                },
            ]),
        bound,
    )
}];

fn bound(params: &Params, points: &PointSet, _: Limits) -> Result<f64> {
    let iterations = params.int("iterations") as usize;
    Ok(star_lower_bound(points.as_slice(), points.dims(), iterations, Seed(params.int("seed"))))
}
