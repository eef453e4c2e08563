//! Extreme (unanchored) discrepancy: the supremum over all axis-parallel boxes of
//! |#points in box / N - volume| (Stroud's T in Shirley 1991 section 3.1). As for the
//! star discrepancy the supremum is reached by critical boxes, open or closed, whose
//! faces pass through points or the cube's faces; degenerate closed boxes (zero width,
//! points on them) count, as limits of half-open boxes.

use rayon::prelude::*;

use super::star::critical;
use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::registry::About;
use crate::spec::Params;

/// 1D closed form: max_i (i/N - x_(i)) + max_i (x_(i) - (i-1)/N) over sorted x
/// (Niederreiter 1992, Theorem 2.9), ties and the end points included.
pub fn extreme_1d(x: &[f64]) -> f64 {
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len() as f64;
    let (mut plus, mut minus) = (0.0f64, 0.0f64);
    for (i, &t) in v.iter().enumerate() {
        plus = plus.max((i + 1) as f64 / n - t);
        minus = minus.max(t - i as f64 / n);
    }
    // the box [0,1) holds the points below one
    let below_one = v.iter().filter(|&&t| t < 1.0).count() as f64 / n;
    (plus + minus).max(1.0 - below_one)
}

/// Brute force over every critical box in 2D (lower and upper faces through points or
/// the square's sides), with O(1) counts from prefix sums: O(n^4). The reference.
///
/// # Panics
/// When a coordinate is NaN.
pub fn extreme_2d_naive(points: &[f64]) -> f64 {
    let n = points.len() / 2;
    let mut xs = critical(points.iter().step_by(2).copied());
    let mut ys = critical(points.iter().skip(1).step_by(2).copied());
    for v in [&mut xs, &mut ys] {
        if v[0] != 0.0 {
            v.insert(0, 0.0);
        }
    }
    let rank = |v: &[f64], t: f64| v.binary_search_by(|c| c.total_cmp(&t)).unwrap();
    // at[i][j] = #points with x == xs[i] and y == ys[j]; prefix sums give any closed or open count
    let (mx, my) = (xs.len(), ys.len());
    let mut pre = vec![0i64; (mx + 1) * (my + 1)];
    for p in points.chunks_exact(2) {
        pre[(rank(&xs, p[0]) + 1) * (my + 1) + rank(&ys, p[1]) + 1] += 1;
    }
    for i in 1..=mx {
        for j in 1..=my {
            pre[i * (my + 1) + j] +=
                pre[(i - 1) * (my + 1) + j] + pre[i * (my + 1) + j - 1] - pre[(i - 1) * (my + 1) + j - 1];
        }
    }
    // points with x-rank in [i0, i1) and y-rank in [j0, j1)
    let count = |i0: usize, i1: usize, j0: usize, j1: usize| -> i64 {
        if i1 <= i0 || j1 <= j0 {
            return 0;
        }
        pre[i1 * (my + 1) + j1] - pre[i0 * (my + 1) + j1] - pre[i1 * (my + 1) + j0] + pre[i0 * (my + 1) + j0]
    };
    let mut worst: f64 = 0.0;
    for i0 in 0..mx {
        for i1 in i0..mx {
            let w = xs[i1] - xs[i0];
            for j0 in 0..my {
                for j1 in j0..my {
                    let area = w * (ys[j1] - ys[j0]);
                    let open = count(i0 + 1, i1, j0 + 1, j1);
                    let closed = count(i0, i1 + 1, j0, j1 + 1);
                    worst = worst.max(area - open as f64 / n as f64).max(closed as f64 / n as f64 - area);
                }
            }
        }
    }
    worst
}

/// Exact 2D extreme discrepancy in O(n^3): for every left side, sweep the right side
/// through the points in x order, keeping the slab's y values sorted; for each slab the
/// best lower and upper sides come from one linear scan (a running minimum for open
/// boxes, a running maximum for closed ones). The left sides run in parallel.
pub fn extreme_2d(points: &[f64]) -> f64 {
    let n = points.len() / 2;
    let inv = 1.0 / n as f64;
    let mut pts: Vec<(f64, f64)> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut lefts: Vec<f64> = vec![0.0];
    lefts.extend(pts.iter().map(|p| p.0));
    lefts.dedup();
    // the left sides are independent: in parallel, each with its own slab (a maximum, so
    // the same value whatever the thread count)
    lefts
        .par_iter()
        .map_init(
            || Vec::with_capacity(n),
            |slab: &mut Vec<f64>, &c| {
                let mut worst: f64 = 0.0;
                // open slabs (c, a): points with x > c; closed slabs [c, a]: points with x >= c
                let first_open = pts.partition_point(|p| p.0 <= c);
                let first_closed = pts.partition_point(|p| p.0 < c);
                // open boxes: the right side a runs over the x values above c, then 1
                slab.clear();
                let mut i = first_open;
                loop {
                    let a = if i < n { pts[i].0 } else { 1.0 };
                    worst = worst.max(open_slab(slab, a - c, inv));
                    if i >= n {
                        break;
                    }
                    while i < n && pts[i].0 == a {
                        insert_sorted(slab, pts[i].1);
                        i += 1;
                    }
                    if i >= n && a == 1.0 {
                        break;
                    }
                }
                // closed boxes: the right side a runs over the x values at or above c
                slab.clear();
                let mut i = first_closed;
                while i < n {
                    let a = pts[i].0;
                    while i < n && pts[i].0 == a {
                        insert_sorted(slab, pts[i].1);
                        i += 1;
                    }
                    worst = worst.max(closed_slab(slab, a - c, inv));
                }
                worst
            },
        )
        .reduce(|| 0.0, f64::max)
}

fn insert_sorted(v: &mut Vec<f64>, y: f64) {
    let at = v.partition_point(|&t| t < y);
    v.insert(at, y);
}

/// max over d < b of w (b - d) - #{d < y < b} / N, with d, b among 0, the ys and 1.
fn open_slab(ys: &[f64], w: f64, inv: f64) -> f64 {
    // value(d = s_i, b = s_j) = (w s_j - below(s_j)/N) - (w s_i - upto(s_i)/N)
    let mut best: f64 = 0.0;
    let mut min_left = 0.0; // d = 0: w*0 - 0
    let mut i = 0;
    while i <= ys.len() {
        let b = if i < ys.len() { ys[i] } else { 1.0 };
        best = best.max(w * b - i as f64 * inv - min_left);
        if i == ys.len() {
            break;
        }
        let mut j = i;
        while j < ys.len() && ys[j] == b {
            j += 1;
        }
        min_left = f64::min(min_left, w * b - j as f64 * inv);
        i = j;
    }
    best
}

/// max over d <= b of #{d <= y <= b} / N - w (b - d), d and b among the ys.
fn closed_slab(ys: &[f64], w: f64, inv: f64) -> f64 {
    // value = (upto(s_j)/N - w s_j) - (below(s_i)/N - w s_i)
    let mut best: f64 = 0.0;
    let mut min_left = f64::INFINITY;
    let mut i = 0;
    while i < ys.len() {
        let b = ys[i];
        let mut j = i;
        while j < ys.len() && ys[j] == b {
            j += 1;
        }
        min_left = min_left.min(i as f64 * inv - w * b);
        best = best.max(j as f64 * inv - w * b - min_left);
        i = j;
    }
    best
}

/// The metric this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry::new(
    About::new("extreme", "sup over all axis-parallel boxes (Stroud's T)")
        .aliases(&["stroud", "unanchored", "t"])
        .cite(&["shirley1991"]),
    extreme,
)];

/// The exact extreme discrepancy in 1D and 2D (the 2D slab sweep refused over the work
/// limit).
fn extreme(_: &Params, points: &PointSet, limits: Limits) -> Result<f64> {
    let x = points.as_slice();
    match points.dims() {
        1 => Ok(extreme_1d(x)),
        2 => {
            limits.allow("the exact extreme discrepancy", points, (points.len() as f64).powi(3))?;
            Ok(extreme_2d(x))
        }
        d => Err(Error::Invalid(format!("the exact extreme discrepancy is implemented in 1D and 2D, not {d}D"))),
    }
}
