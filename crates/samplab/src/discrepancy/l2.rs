//! L2 discrepancies in closed form (Warnock 1972; Hickernell 1998): the pair sums are
//! formed with compensated (Neumaier) summation in a fixed order, in parallel over fixed
//! chunks, so the value does not depend on the thread count.
//!
//! Every function here returns the **squared** discrepancy; callers take the square root
//! where the convention is the root (see [`super::Metric`]).

use super::{Limits, MetricEntry};
use crate::error::Result;
use crate::points::PointSet;
use crate::registry::About;
use crate::spec::Params;
use rayon::prelude::*;

/// Neumaier's compensated sum.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sum {
    sum: f64,
    err: f64,
}

impl Sum {
    /// Add `x`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.err += (self.sum - t) + x;
        } else {
            self.err += (x - t) + self.sum;
        }
        self.sum = t;
    }
    /// Add another compensated sum.
    pub fn merge(&mut self, other: Sum) {
        self.add(other.sum);
        self.add(other.err);
    }
    /// The sum.
    pub fn value(&self) -> f64 {
        self.sum + self.err
    }
}

const CHUNK: usize = 64;

/// (1/N) sum_i prod_k f(x_ik) and (1/N^2) sum_i sum_j prod_k g(x_ik, x_jk), g symmetric:
/// every closed form here is a product over coordinates.
fn sums(points: &[f64], dims: usize, f: impl Fn(f64) -> f64 + Sync, g: impl Fn(f64, f64) -> f64 + Sync) -> (f64, f64) {
    let n = points.len() / dims;
    let columns: Vec<Vec<f64>> = (0..dims).map(|k| points.iter().skip(k).step_by(dims).copied().collect()).collect();
    let parts: Vec<(Sum, Sum)> = (0..n)
        .into_par_iter()
        .step_by(CHUNK)
        .map(|start| {
            let (mut single, mut pair) = (Sum::default(), Sum::default());
            for i in start..(start + CHUNK).min(n) {
                let p = &points[i * dims..(i + 1) * dims];
                single.add(p.iter().map(|&x| f(x)).product());
                pair.add(p.iter().map(|&x| g(x, x)).product());
                pair.add(2.0 * row_sum(p, &columns, i + 1, &g));
            }
            (single, pair)
        })
        .collect();
    let (mut single, mut pair) = (Sum::default(), Sum::default());
    for (s, p) in parts {
        single.merge(s);
        pair.merge(p);
    }
    (single.value() / n as f64, pair.value() / (n * n) as f64)
}

/// Independent Kahan-compensated accumulators: enough of them that the compiler can keep
/// several vector registers busy, merged with Neumaier's sum.
const LANES: usize = 16;

struct Lanes {
    sum: [f64; LANES],
    comp: [f64; LANES],
}

impl Lanes {
    fn new() -> Lanes {
        Lanes { sum: [0.0; LANES], comp: [0.0; LANES] }
    }

    #[inline(always)]
    fn add(&mut self, values: [f64; LANES]) {
        for ((sum, comp), v) in self.sum.iter_mut().zip(&mut self.comp).zip(values) {
            let y = v - *comp;
            let t = *sum + y;
            *comp = (t - *sum) - y;
            *sum = t;
        }
    }

    fn total(&self) -> Sum {
        let mut s = Sum::default();
        for (&sum, &comp) in self.sum.iter().zip(&self.comp) {
            s.add(sum);
            s.add(-comp);
        }
        s
    }
}

/// sum over the points j >= `from` of prod_k g(p_k, columns_k[j]), the coordinates stored
/// by column so that consecutive j vectorize. With AVX-512 or AVX2 where the processor has
/// them (chosen at run time): the same operations in the same order, so the same value,
/// only wider.
fn row_sum(p: &[f64], columns: &[Vec<f64>], from: usize, g: &impl Fn(f64, f64) -> f64) -> f64 {
    crate::simd::wide(
        #[inline(always)]
        || row_sum_any(p, columns, from, g),
    )
}

#[inline(always)]
fn row_sum_any(p: &[f64], columns: &[Vec<f64>], from: usize, g: &impl Fn(f64, f64) -> f64) -> f64 {
    let n = columns[0].len();
    let mut lanes = Lanes::new();
    let mut j = from;
    while j + LANES <= n {
        let mut v = [1.0; LANES];
        for (&a, column) in p.iter().zip(columns) {
            for (x, &b) in v.iter_mut().zip(&column[j..j + LANES]) {
                *x *= g(a, b);
            }
        }
        lanes.add(v);
        j += LANES;
    }
    let mut total = lanes.total();
    for j in j..n {
        total.add(p.iter().zip(columns).map(|(&a, column)| g(a, column[j])).product());
    }
    total.value()
}

/// Squared L2-star discrepancy (Warnock's formula):
/// 3^-d - 2^(1-d)/N sum_i prod_k (1 - x_ik^2) + 1/N^2 sum_ij prod_k (1 - max(x_ik, x_jk)).
pub fn l2_star_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(points, dims, |x| 1.0 - x * x, |x, y| 1.0 - x.max(y));
    3f64.powi(-(dims as i32)) - 2f64.powi(1 - dims as i32) * a + b
}

/// Squared L2-extreme (unanchored) discrepancy, the mean over all boxes [u, v]:
/// 12^-d - 2/N sum_i prod_k x_ik (1 - x_ik) / 2 + 1/N^2 sum_ij prod_k (min - x_ik x_jk).
pub fn l2_extreme_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(points, dims, |x| x * (1.0 - x) / 2.0, |x, y| x.min(y) - x * y);
    12f64.powi(-(dims as i32)) - 2.0 * a + b
}

/// Squared centered L2 discrepancy (Hickernell 1998, eq. 5.1c).
pub fn centered_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |x| {
            let t = (x - 0.5).abs();
            1.0 + 0.5 * t - 0.5 * t * t
        },
        |x, y| 1.0 + 0.5 * (x - 0.5).abs() + 0.5 * (y - 0.5).abs() - 0.5 * (x - y).abs(),
    );
    (13.0f64 / 12.0).powi(dims as i32) - 2.0 * a + b
}

/// Squared wrap-around L2 discrepancy (Hickernell 1998, eq. 5.1d); invariant under
/// toroidal shifts of the set.
pub fn wraparound_sq(points: &[f64], dims: usize) -> f64 {
    let (_, b) = sums(
        points,
        dims,
        |_| 0.0,
        |x, y| {
            let t = (x - y).abs();
            1.5 - t * (1.0 - t)
        },
    );
    -(4.0f64 / 3.0).powi(dims as i32) + b
}

/// Squared mixture L2 discrepancy (Zhou, Fang & Ning 2013, the "MD" of scipy).
pub fn mixture_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |x| {
            let t = (x - 0.5).abs();
            5.0 / 3.0 - 0.25 * t - 0.25 * t * t
        },
        |x, y| {
            let d = (x - y).abs();
            15.0 / 8.0 - 0.25 * (x - 0.5).abs() - 0.25 * (y - 0.5).abs() - 0.75 * d + 0.5 * d * d
        },
    );
    (19.0f64 / 12.0).powi(dims as i32) - 2.0 * a + b
}

/// Squared L2-star discrepancy in 2D in O(n log n) (Heinrich 1996's idea: the pair sum
/// of Warnock's formula splits by which point is larger in x, and the inner sums over y
/// are prefix sums kept in a Fenwick tree over y ranks).
pub fn l2_star_sq_2d(points: &[f64]) -> f64 {
    let n = points.len() / 2;
    let mut pts: Vec<(f64, f64)> = points.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    pts.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    // the rank of each point's y among the distinct y values, in x order
    let mut by_y: Vec<u32> = (0..n as u32).collect();
    by_y.sort_unstable_by(|&a, &b| pts[a as usize].1.total_cmp(&pts[b as usize].1));
    let mut rank = vec![0usize; n];
    let mut distinct = 0;
    for (k, &i) in by_y.iter().enumerate() {
        if k > 0 && pts[i as usize].1 != pts[by_y[k - 1] as usize].1 {
            distinct += 1;
        }
        rank[i as usize] = distinct;
    }
    let ys = distinct + 1;
    // per y rank: the count of earlier points and the sum of their (1 - y)
    let mut tree = Fenwick::new(ys);
    let mut total_tail = 0.0;
    let (mut single, mut pair) = (Sum::default(), Sum::default());
    for (&(x, y), &r) in pts.iter().zip(&rank) {
        single.add((1.0 - x * x) * (1.0 - y * y));
        // earlier points j have x_j <= x: (1 - x)(1 - max(y, y_j))
        let [le, tail_le] = tree.prefix(r + 1);
        let inner = le * (1.0 - y) + (total_tail - tail_le);
        pair.add(2.0 * (1.0 - x) * inner + (1.0 - x) * (1.0 - y));
        tree.add(r, [1.0, 1.0 - y]);
        total_tail += 1.0 - y;
    }
    let (a, b) = (single.value() / n as f64, pair.value() / (n * n) as f64);
    1.0 / 9.0 - 0.5 * a + b
}

/// A Fenwick (binary indexed) tree of pairs of f64 sums.
struct Fenwick {
    tree: Vec<[f64; 2]>,
}

impl Fenwick {
    fn new(n: usize) -> Self {
        Fenwick { tree: vec![[0.0; 2]; n + 1] }
    }
    fn add(&mut self, i: usize, v: [f64; 2]) {
        let mut i = i + 1;
        while i < self.tree.len() {
            self.tree[i][0] += v[0];
            self.tree[i][1] += v[1];
            i += i & i.wrapping_neg();
        }
    }
    /// Sums of entries 0..i.
    fn prefix(&self, i: usize) -> [f64; 2] {
        let (mut i, mut s) = (i, [0.0; 2]);
        while i > 0 {
            s[0] += self.tree[i][0];
            s[1] += self.tree[i][1];
            i -= i & i.wrapping_neg();
        }
        s
    }
}

/// An L2 metric: the root of its squared closed form (clamped at zero: the closed forms
/// cancel heavily).
const fn l2_entry(about: About, compute: fn(&Params, &PointSet, Limits) -> Result<f64>) -> MetricEntry {
    MetricEntry { l2: true, ..MetricEntry::new(about, compute) }
}

fn root(sq: f64) -> Result<f64> {
    Ok(sq.max(0.0).sqrt())
}

/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[
    l2_entry(
        About::new("l2-star", "root mean square over anchored boxes (Shirley's S), Warnock's formula")
            .aliases(&["rms", "s", "warnock"])
            .cite(&["shirley1991"]),
        |_, p, _| root(if p.dims() == 2 { l2_star_sq_2d(p.as_slice()) } else { l2_star_sq(p.as_slice(), p.dims()) }),
    ),
    l2_entry(
        About::new("l2-extreme", "root mean square over all boxes").aliases(&["l2-unanchored"]).cite(&["shirley1991"]),
        |_, p, _| root(l2_extreme_sq(p.as_slice(), p.dims())),
    ),
    l2_entry(About::new("centered", "centered L2 discrepancy (Hickernell)").aliases(&["cd"]), |_, p, _| {
        root(centered_sq(p.as_slice(), p.dims()))
    }),
    MetricEntry {
        shift_invariant: true,
        ..l2_entry(
            About::new("wraparound", "wrap-around L2 discrepancy (Hickernell); toroidal-shift invariant")
                .aliases(&["wd", "wrap-around"]),
            |_, p, _| root(wraparound_sq(p.as_slice(), p.dims())),
        )
    },
    l2_entry(About::new("mixture", "mixture L2 discrepancy").aliases(&["md"]), |_, p, _| {
        root(mixture_sq(p.as_slice(), p.dims()))
    }),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_instruction_set_gives_the_same_bits() {
        let mut rng = crate::Seed(11).rng();
        for dims in [1, 2, 3, 5] {
            let columns: Vec<Vec<f64>> =
                (0..dims).map(|_| (0..203).map(|_| crate::seed::uniform(&mut rng)).collect()).collect();
            let g = |x: f64, y: f64| 1.5 - (x - y).abs() * (1.0 - (x - y).abs());
            for (i, from) in [0, 1, 17, 190].into_iter().enumerate() {
                let p: Vec<f64> = columns.iter().map(|c| c[i]).collect();
                let any = row_sum_any(&p, &columns, from, &g);
                // the plain sum, to a tolerance: the lanes reorder it
                let plain: f64 =
                    (from..203).map(|j| columns.iter().zip(&p).map(|(c, &a)| g(a, c[j])).product::<f64>()).sum();
                assert!((any - plain).abs() <= 1e-12 * plain.abs(), "{any} vs {plain}");
                let runs = crate::simd::on_each_instruction_set(
                    #[inline(always)]
                    || row_sum_any(&p, &columns, from, &g).to_bits(),
                );
                assert!(runs.iter().all(|&r| r == any.to_bits()));
            }
        }
    }
}
