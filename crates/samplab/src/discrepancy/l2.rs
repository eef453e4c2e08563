//! L2 discrepancies in closed form (Warnock 1972; Hickernell 1998): the pair sums are
//! formed with compensated (Neumaier) summation in a fixed order, in parallel over fixed
//! chunks, so the value does not depend on the thread count.
//!
//! Every function here returns the **squared** discrepancy; callers take the square root
//! where the convention is the root (see [`super::Metric`]).

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

/// (1/N) sum_i f(x_i) and (1/N^2) sum_i sum_j g(x_i, x_j), g symmetric.
fn sums(
    points: &[f64],
    dims: usize,
    f: impl Fn(&[f64]) -> f64 + Sync,
    g: impl Fn(&[f64], &[f64]) -> f64 + Sync,
) -> (f64, f64) {
    let n = points.len() / dims;
    let rows: Vec<&[f64]> = points.chunks_exact(dims).collect();
    let parts: Vec<(Sum, Sum)> = (0..n)
        .into_par_iter()
        .step_by(CHUNK)
        .map(|start| {
            let (mut single, mut pair) = (Sum::default(), Sum::default());
            for i in start..(start + CHUNK).min(n) {
                single.add(f(rows[i]));
                pair.add(g(rows[i], rows[i]));
                let mut off = Sum::default();
                for row in &rows[i + 1..] {
                    off.add(g(rows[i], row));
                }
                pair.add(2.0 * off.value());
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

/// Squared L2-star discrepancy (Warnock's formula):
/// 3^-d - 2^(1-d)/N sum_i prod_k (1 - x_ik^2) + 1/N^2 sum_ij prod_k (1 - max(x_ik, x_jk)).
pub fn l2_star_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |p| p.iter().map(|x| 1.0 - x * x).product(),
        |p, q| p.iter().zip(q).map(|(x, y)| 1.0 - x.max(*y)).product(),
    );
    3f64.powi(-(dims as i32)) - 2f64.powi(1 - dims as i32) * a + b
}

/// Squared L2-extreme (unanchored) discrepancy, the mean over all boxes [u, v]:
/// 12^-d - 2/N sum_i prod_k x_ik (1 - x_ik) / 2 + 1/N^2 sum_ij prod_k (min - x_ik x_jk).
pub fn l2_extreme_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |p| p.iter().map(|x| x * (1.0 - x) / 2.0).product(),
        |p, q| p.iter().zip(q).map(|(x, y)| x.min(*y) - x * y).product(),
    );
    12f64.powi(-(dims as i32)) - 2.0 * a + b
}

/// Squared centered L2 discrepancy (Hickernell 1998, eq. 5.1c).
pub fn centered_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |p| p.iter().map(|x| (x - 0.5).abs()).map(|t| 1.0 + 0.5 * t - 0.5 * t * t).product(),
        |p, q| {
            p.iter()
                .zip(q)
                .map(|(x, y)| 1.0 + 0.5 * (x - 0.5).abs() + 0.5 * (y - 0.5).abs() - 0.5 * (x - y).abs())
                .product()
        },
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
        |p, q| {
            p.iter()
                .zip(q)
                .map(|(x, y)| {
                    let t = (x - y).abs();
                    1.5 - t * (1.0 - t)
                })
                .product()
        },
    );
    -(4.0f64 / 3.0).powi(dims as i32) + b
}

/// Squared mixture L2 discrepancy (Zhou, Fang & Ning 2013, the "MD" of scipy).
pub fn mixture_sq(points: &[f64], dims: usize) -> f64 {
    let (a, b) = sums(
        points,
        dims,
        |p| p.iter().map(|x| (x - 0.5).abs()).map(|t| 5.0 / 3.0 - 0.25 * t - 0.25 * t * t).product(),
        |p, q| {
            p.iter()
                .zip(q)
                .map(|(x, y)| {
                    let d = (x - y).abs();
                    15.0 / 8.0 - 0.25 * (x - 0.5).abs() - 0.25 * (y - 0.5).abs() - 0.75 * d + 0.5 * d * d
                })
                .product()
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
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut ys: Vec<f64> = pts.iter().map(|p| p.1).collect();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let mut count = Fenwick::new(ys.len());
    let mut tail = Fenwick::new(ys.len()); // sum of (1 - y) per rank
    let mut total_tail = 0.0;
    let (mut single, mut pair) = (Sum::default(), Sum::default());
    for &(x, y) in &pts {
        single.add((1.0 - x * x) * (1.0 - y * y));
        let r = ys.partition_point(|&t| t < y);
        // earlier points j have x_j <= x: (1 - x)(1 - max(y, y_j))
        let le = count.prefix(r + 1);
        let above = total_tail - tail.prefix(r + 1);
        let inner = le * (1.0 - y) + above;
        pair.add(2.0 * (1.0 - x) * inner + (1.0 - x) * (1.0 - y));
        count.add(r, 1.0);
        tail.add(r, 1.0 - y);
        total_tail += 1.0 - y;
    }
    let (a, b) = (single.value() / n as f64, pair.value() / (n * n) as f64);
    1.0 / 9.0 - 0.5 * a + b
}

/// A Fenwick (binary indexed) tree of f64 sums.
struct Fenwick {
    tree: Vec<f64>,
}

impl Fenwick {
    fn new(n: usize) -> Self {
        Fenwick { tree: vec![0.0; n + 1] }
    }
    fn add(&mut self, i: usize, v: f64) {
        let mut i = i + 1;
        while i < self.tree.len() {
            self.tree[i] += v;
            i += i & i.wrapping_neg();
        }
    }
    /// Sum of entries 0..i.
    fn prefix(&self, i: usize) -> f64 {
        let (mut i, mut s) = (i, 0.0);
        while i > 0 {
            s += self.tree[i];
            i -= i & i.wrapping_neg();
        }
        s
    }
}
