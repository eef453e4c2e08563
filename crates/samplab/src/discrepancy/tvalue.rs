//! The t-value of a point set as a (t, m, s)-net in base b (Niederreiter 1992, definition
//! 4.1), counted on its points by brute force, so that it holds for any set (scrambled or
//! not, a saved file, a pixel's samples): n = b^m points form a (t, m, s)-net when every
//! elementary interval of volume b^(t-m), the product of [a_j b^-d_j, (a_j + 1) b^-d_j)
//! over the axes with d_1 + ... + d_s = m - t, holds exactly b^t of them. The value is the
//! least such t; with `projection=pairs`, the largest over the set's 2D projections (the
//! quality of the worst pair, which the 2023-2025 papers argue with).

use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::points::PointSet;
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
    kind: Kind::Choice(&["all", "pairs"]),
    default: Default::Word("all"),
    doc: "the whole set, or the largest t over its 2D projections",
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
        // the next composition of k into s parts
        let Some(j) = (0..s - 1).rev().find(|&j| split[j + 1..].iter().sum::<usize>() > 0) else { return true };
        let rest: usize = split[j + 1..].iter().sum();
        split[j] += 1;
        split[j + 1..].iter_mut().for_each(|x| *x = 0);
        split[s - 1] = rest - 1;
    }
}

/// The least t of the axes `axes` as a (t, m, s)-net in base b.
fn t_of(points: &PointSet, axes: &[usize], b: usize, m: usize, cells: &mut Vec<u32>) -> usize {
    // strength k (every interval of volume b^-k balanced) holds for every k below a strength
    // that holds: the finest strength is m - t
    let strength = (1..=m).take_while(|&k| stratified(points, axes, b, k, cells)).last().unwrap_or(0);
    m - strength
}

/// C(n, k) as a float (the number of compositions, for the work estimate).
fn choose(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

fn t_value(p: &Params, points: &PointSet, limits: Limits) -> Result<f64> {
    let b = p.int("base") as usize;
    let n = points.len();
    let m = (0..=64).find(|&m| b.checked_pow(m as u32) == Some(n)).ok_or_else(|| {
        Error::Invalid(format!("t-value: {n} points are not a power of the base {b}"))
    })?;
    let s = points.dims();
    let projections: Vec<Vec<usize>> = match p.word("projection") {
        "pairs" if s < 2 => return Err(Error::Invalid("t-value: pairs of a 1D set".into())),
        "pairs" => (0..s).flat_map(|i| (i + 1..s).map(move |j| vec![i, j])).collect(),
        _ => vec![(0..s).collect()],
    };
    // each strength k counts the points once per composition of k into the axes
    let width = projections[0].len();
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

/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry::new(
    About::new("t-value", "the least t of a (t,m,s)-net in base b, by brute force over elementary intervals")
        .params(&[BASE, PROJECTION])
        .cite(&["niederreiter1992"]),
    t_value,
)];
