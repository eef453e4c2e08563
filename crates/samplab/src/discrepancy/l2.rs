//! L2 discrepancies in closed form (Warnock 1972; Hickernell 1998): the pair sums are
//! formed with compensated (Neumaier) summation in a fixed order, in parallel over fixed
//! chunks, so the value does not depend on the thread count.
//!
//! Every function here returns the **squared** discrepancy; callers take the square root
//! where the convention is the root (see [`super::Metric`]).

use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::numeric::{Sum, order_key};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::registry::About;
use crate::spec::Params;
use rayon::prelude::*;

const CHUNK: usize = 64;

/// (1/N) sum_i prod_k f(x_ik) and (1/N^2) sum_i sum_j prod_k g(x_ik, x_jk), g symmetric:
/// every closed form here is a product over coordinates.
fn sums(
    points: &[f64],
    dims: usize,
    f: impl Fn(f64) -> f64 + Sync,
    g: impl Fn(f64, f64) -> f64 + Sync,
    progress: Progress,
) -> Result<(f64, f64)> {
    let n = points.len() / dims;
    let columns: Vec<Vec<f64>> = (0..dims).map(|k| points.iter().skip(k).step_by(dims).copied().collect()).collect();
    let parts: Vec<(Sum, Sum)> = (0..n)
        .into_par_iter()
        .step_by(CHUNK)
        .map(|start| {
            progress.check()?;
            let (mut single, mut pair) = (Sum::default(), Sum::default());
            for i in start..(start + CHUNK).min(n) {
                let p = &points[i * dims..(i + 1) * dims];
                single.add(p.iter().map(|&x| f(x)).product());
                pair.add(p.iter().map(|&x| g(x, x)).product());
                pair.add(2.0 * row_sum(p, &columns, i + 1, &g));
            }
            Ok((single, pair))
        })
        .collect::<Result<_>>()?;
    let (mut single, mut pair) = (Sum::default(), Sum::default());
    for (s, p) in parts {
        single.merge(s);
        pair.merge(p);
    }
    Ok((single.value() / n as f64, pair.value() / (n * n) as f64))
}

/// Independent compensated accumulators: enough of them (16 for a row of pairs) that the
/// compiler can keep several vector registers busy, merged with Neumaier's sum. Each adds
/// by Knuth's TwoSum, its rounding error gathered apart (Ogita, Rump & Oishi 2005's Sum2):
/// no branch, and only the one addition on the running sum's dependency chain.
const LANES: usize = 16;

#[derive(Clone, Copy)]
struct Lanes<const N: usize> {
    sum: [f64; N],
    err: [f64; N],
}

impl<const N: usize> Lanes<N> {
    fn new() -> Lanes<N> {
        Lanes { sum: [0.0; N], err: [0.0; N] }
    }

    /// Each accumulator's compensated value.
    #[inline(always)]
    fn values(&self) -> [f64; N] {
        array(|k| self.sum[k] + self.err[k])
    }

    #[inline(always)]
    fn add(&mut self, values: [f64; N]) {
        for ((sum, err), v) in self.sum.iter_mut().zip(&mut self.err).zip(values) {
            let t = *sum + v;
            let w = t - *sum;
            *err += (*sum - (t - w)) + (v - w);
            *sum = t;
        }
    }

    /// This total less a running sum, part by part (the difference of the leading parts is
    /// exact or rounded at its own scale, not the total's).
    #[inline(always)]
    fn less(&self, running: &Lanes<N>) -> [f64; N] {
        array(|k| (self.sum[k] - running.sum[k]) + (self.err[k] - running.err[k]))
    }

    fn total(&self) -> Sum {
        let mut s = Sum::default();
        for (&sum, &err) in self.sum.iter().zip(&self.err) {
            s.add(sum);
            s.add(err);
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
    let mut lanes = Lanes::<LANES>::new();
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

/// (1/N) sum_i prod_k f and (1/N^2) sum_ij prod_k g of points with `dims` coordinates,
/// stoppable ([`sums`]).
type PairSums = fn(&[f64], usize, Progress) -> Result<(f64, f64)>;

/// One L2 discrepancy's closed form: D^2 = sign base^d - (2/N) sum_i prod_k f(x_ik) +
/// (1/N^2) sum_ij prod_k g(x_ik, x_jk), the kernel g symmetric and, for u >= v, a sum of a
/// few separable terms sum_r a_r(u) b_r(v), which is what lets the 2D pair sum be swept in
/// O(n log n) ([`pair_sum_2d`]).
#[derive(Clone, Copy)]
pub struct Form {
    base: f64,
    sign: f64,
    f: fn(f64) -> f64,
    g: fn(f64, f64) -> f64,
    /// [`sums`] with f and g inlined (monomorphized: a call through `f` and `g` per pair
    /// would not vectorize).
    quadratic: PairSums,
    /// [`pair_sum_2d`] with g and its split inlined.
    sweep: fn(&[f64]) -> f64,
}

/// A [`Form`] from its parts: `split` gives, for u >= v, g(u, v) = sum_r a_r(u) b_r(v) as
/// `u -> (a(u), b(u))`.
macro_rules! form {
    (base: $base:expr, sign: $sign:expr, f: $f:expr, g: $g:expr, split: $split:expr $(,)?) => {
        Form {
            base: $base,
            sign: $sign,
            f: $f,
            g: $g,
            quadratic: |p, d, progress| sums(p, d, $f, $g, progress),
            sweep: |p| pair_sum_2d(p, $g, $split),
        }
    };
}

/// Warnock's formula for the L2-star discrepancy: 3^-d - 2^(1-d)/N sum_i prod_k (1 - x_ik^2)
/// + 1/N^2 sum_ij prod_k (1 - max(x_ik, x_jk)).
pub const STAR: Form = form! {
    base: 1.0 / 3.0,
    sign: 1.0,
    f: |x| (1.0 - x * x) / 2.0,
    g: |x, y| 1.0 - x.max(y),
    split: |u| ([1.0 - u], [1.0]),
};

/// The L2-extreme (unanchored) discrepancy, the mean over all boxes [u, v]: 12^-d - 2/N
/// sum_i prod_k x_ik (1 - x_ik) / 2 + 1/N^2 sum_ij prod_k (min - x_ik x_jk).
pub const EXTREME: Form = form! {
    base: 1.0 / 12.0,
    sign: 1.0,
    f: |x| x * (1.0 - x) / 2.0,
    g: |x, y| x.min(y) - x * y,
    split: |u| ([1.0 - u], [u]),
};

/// The centered L2 discrepancy (Hickernell 1998, eq. 5.1c).
pub const CENTERED: Form = form! {
    base: 13.0 / 12.0,
    sign: 1.0,
    f: |x| {
        let t = (x - 0.5).abs();
        1.0 + 0.5 * t - 0.5 * t * t
    },
    g: |x, y| 1.0 + 0.5 * (x - 0.5).abs() + 0.5 * (y - 0.5).abs() - 0.5 * (x - y).abs(),
    // u >= v: (1 + |u - 1/2| / 2 - u / 2) + (|v - 1/2| / 2 + v / 2)
    split: |u| {
        let t = 0.5 * (u - 0.5).abs();
        ([1.0 + t - 0.5 * u, 1.0], [1.0, t + 0.5 * u])
    },
};

/// The wrap-around L2 discrepancy (Hickernell 1998, eq. 5.1d); invariant under toroidal
/// shifts of the set.
pub const WRAPAROUND: Form = form! {
    base: 4.0 / 3.0,
    sign: -1.0,
    f: |_| 0.0,
    g: |x, y| {
        let t = (x - y).abs();
        1.5 - t * (1.0 - t)
    },
    // u >= v, t = u - v: (3/2 - u + u^2) + (v + v^2) - 2 u v
    split: |u| ([1.5 - u + u * u, 1.0, u], [1.0, u + u * u, -2.0 * u]),
};

/// 2 pi^2.
const TWO_PI2: f64 = 2.0 * std::f64::consts::PI * std::f64::consts::PI;

/// Zinterhof's diaphony, squared: sum over nonzero frequencies h of
/// |(1/N) sum_i e^(2 pi i h.x_i)|^2 / prod_k max(1, |h_k|)^2, which, since
/// sum_h e^(2 pi i h t) / max(1, |h|)^2 = 1 + 2 pi^2 B_2({t}), is
/// -1 + (1/N^2) sum_ij prod_k (1 + 2 pi^2 B_2(|x_ik - x_jk|)), B_2(t) = t^2 - t + 1/6
/// (even and 1-periodic, so |t| stands for {t}). Toroidal-shift invariant; for a rank-1
/// lattice it equals the worst-case error P_2 (`sampler::qmc::lattice::p2`).
pub const DIAPHONY: Form = form! {
    base: 1.0,
    sign: -1.0,
    f: |_| 0.0,
    g: |x, y| {
        let t = (x - y).abs();
        1.0 + TWO_PI2 * (t * t - t + 1.0 / 6.0)
    },
    // u >= v, t = u - v: (1 + pi^2/3 - 2 pi^2 u + 2 pi^2 u^2) + 2 pi^2 (v + v^2) - 4 pi^2 u v
    split: |u| {
        ([1.0 + TWO_PI2 / 6.0 - TWO_PI2 * u + TWO_PI2 * u * u, 1.0, u], [1.0, TWO_PI2 * (u + u * u), -2.0 * TWO_PI2 * u])
    },
};

/// The mixture L2 discrepancy (Zhou, Fang & Ning 2013, the "MD" of scipy).
pub const MIXTURE: Form = form! {
    base: 19.0 / 12.0,
    sign: 1.0,
    f: |x| {
        let t = (x - 0.5).abs();
        5.0 / 3.0 - 0.25 * t - 0.25 * t * t
    },
    g: |x, y| {
        let d = (x - y).abs();
        15.0 / 8.0 - 0.25 * (x - 0.5).abs() - 0.25 * (y - 0.5).abs() - 0.75 * d + 0.5 * d * d
    },
    // u >= v, d = u - v: (15/8 - |u - 1/2| / 4 - 3u/4 + u^2/2) + (-|v - 1/2| / 4 + 3v/4 + v^2/2) - u v
    split: |u| {
        let t = 0.25 * (u - 0.5).abs();
        ([15.0 / 8.0 - t - 0.75 * u + 0.5 * u * u, 1.0, u], [1.0, -t + 0.75 * u + 0.5 * u * u, -u])
    },
};

impl Form {
    /// The squared discrepancy of `points` (`dims` coordinates each): the pair sum swept in
    /// O(n log n) in 2D, else formed pair by pair (O(n^2 d); no better bound is known to us
    /// for these in general d, Heinrich 1996's O(n log^d n) for L2-star aside).
    ///
    /// # Errors
    /// [`Error::Interrupted`] once `progress` says stop (checked between chunks of pairs).
    pub fn squared(&self, points: &[f64], dims: usize, progress: Progress) -> Result<f64> {
        if dims == 2 {
            // the single sum is one serial loop: it runs beside the sweep
            let (single, pair) = rayon::join(|| self.single(points, dims), || (self.sweep)(points));
            Ok(self.finish(single, pair, dims, points.len() / dims))
        } else {
            self.squared_quadratic(points, dims, progress)
        }
    }

    /// The same, every pair's kernel formed (the oracle of the sweep).
    ///
    /// # Errors
    /// As [`Form::squared`].
    pub fn squared_quadratic(&self, points: &[f64], dims: usize, progress: Progress) -> Result<f64> {
        let (a, b) = (self.quadratic)(points, dims, progress)?;
        Ok(self.sign * self.base.powi(dims as i32) - 2.0 * a + b)
    }

    /// sum_i prod_k f(x_ik), compensated.
    fn single(&self, points: &[f64], dims: usize) -> f64 {
        let mut s = Sum::default();
        for p in points.chunks_exact(dims) {
            s.add(p.iter().map(|&x| (self.f)(x)).product());
        }
        s.value()
    }

    fn finish(&self, single: f64, pair: f64, dims: usize, n: usize) -> f64 {
        let n = n as f64;
        self.sign * self.base.powi(dims as i32) - 2.0 * single / n + pair / (n * n)
    }

    /// The discrepancy itself (the root of [`Form::squared`], clamped at zero): in up to
    /// [`PLAIN_DIMS`] dimensions from the plain products, beyond from their logarithms
    /// ([`Form::squared_scaled`]), since a product of d factors leaves the double range
    /// (the wrap-around form's 1.5^d passes 10^308 at d = 1750).
    ///
    /// # Errors
    /// A value outside the double range (about 10^-308 to 10^308), which is stated, never
    /// rounded to 0 or infinity; [`Error::Interrupted`] as [`Form::squared`].
    pub fn value(&self, points: &[f64], dims: usize, progress: Progress) -> Result<f64> {
        if dims <= PLAIN_DIMS {
            return Ok(self.squared(points, dims, progress)?.max(0.0).sqrt());
        }
        let (bracket, log_scale) = self.squared_scaled(points, dims, progress)?;
        if bracket <= 0.0 {
            return Ok(0.0);
        }
        // D = exp(M / 2) sqrt(bracket)
        let log = 0.5 * (log_scale + bracket.ln());
        let value = log.exp();
        if value == 0.0 || !value.is_finite() {
            return Err(Error::Infeasible {
                what: format!("the L2 discrepancy in {dims} dimensions"),
                reason: format!(
                    "its value, 10^{:.1}, is outside the double-precision range (10^-308 to 10^308)",
                    log / std::f64::consts::LN_10
                ),
            });
        }
        Ok(value)
    }

    /// The squared discrepancy as (bracket, M) with D^2 = e^M bracket: every product of d
    /// factors is summed as sign e^(sum of log |factor| - M), M the largest such sum (kept
    /// as the sums go, the partial sums rescaled when it grows), so no product over- or
    /// underflows. O(n^2 d) logarithms.
    ///
    /// # Errors
    /// As [`Form::squared`].
    pub fn squared_scaled(&self, points: &[f64], dims: usize, progress: Progress) -> Result<(f64, f64)> {
        let n = points.len() / dims;
        // the logarithms summed compensated: a plain sum of 1000 of them loses 10 bits
        let log_product = |values: &mut dyn Iterator<Item = f64>| {
            let (mut log, mut sign) = (Sum::default(), 1.0);
            for v in values {
                if v == 0.0 {
                    return (f64::NEG_INFINITY, 1.0);
                }
                log.add(v.abs().ln());
                sign *= v.signum();
            }
            (log.value(), sign)
        };
        let rows: Vec<ScaledSum> = (0..n)
            .into_par_iter()
            .map(|i| {
                progress.check()?;
                let p = &points[i * dims..(i + 1) * dims];
                let mut row = ScaledSum::default();
                let (log, sign) = log_product(&mut p.iter().map(|&x| (self.f)(x)));
                row.add(-2.0 * sign / n as f64, log);
                let (log, sign) = log_product(&mut p.iter().map(|&x| (self.g)(x, x)));
                row.add(sign / (n * n) as f64, log);
                for j in i + 1..n {
                    let q = &points[j * dims..(j + 1) * dims];
                    let (log, sign) = log_product(&mut p.iter().zip(q).map(|(&x, &y)| (self.g)(x, y)));
                    row.add(2.0 * sign / (n * n) as f64, log);
                }
                Ok(row)
            })
            .collect::<Result<_>>()?;
        let mut total = ScaledSum::default();
        total.add(self.sign, dims as f64 * self.base.ln());
        for row in rows {
            total.merge(row);
        }
        Ok((total.sum.value(), total.log))
    }
}

/// Up to this many dimensions [`Form::value`] multiplies the factors as they are.
pub const PLAIN_DIMS: usize = 64;

/// A compensated sum of terms c e^l, kept as e^log sum.
struct ScaledSum {
    log: f64,
    sum: Sum,
}

impl Default for ScaledSum {
    fn default() -> Self {
        ScaledSum { log: f64::NEG_INFINITY, sum: Sum::default() }
    }
}

impl ScaledSum {
    /// Add c e^l (nothing for a zero factor, l = -inf).
    fn add(&mut self, c: f64, l: f64) {
        if l == f64::NEG_INFINITY || c == 0.0 {
            return;
        }
        if l > self.log {
            self.rescale(l);
        }
        self.sum.add(c * (l - self.log).exp());
    }

    /// The same sum, kept as e^log sum.
    fn rescale(&mut self, log: f64) {
        let factor = if self.log == f64::NEG_INFINITY { 0.0 } else { (self.log - log).exp() };
        self.sum = self.sum.scaled(factor);
        self.log = log;
    }

    fn merge(&mut self, mut other: ScaledSum) {
        if other.log == f64::NEG_INFINITY {
            return;
        }
        if other.log > self.log {
            self.rescale(other.log);
        } else {
            other.rescale(self.log);
        }
        self.sum.merge(other.sum);
    }
}

/// sum_ij g(x_i, x_j) g(y_i, y_j) over a 2D set in O(n log n) (the structure of Heinrich
/// 1996's L2-star algorithm, for any kernel of finite separable rank): in x order, an
/// earlier point j has x_j <= x_i, so g(x_i, x_j) = sum_r a_r(x_i) b_r(x_j); by y order,
/// g(y_i, y_j) = sum_s a_s(y_i) b_s(y_j) when y_j <= y_i, else sum_s b_s(y_i) a_s(y_j). The
/// sums over earlier j of b_r(x_j) b_s(y_j) (y_j <= y_i) and b_r(x_j) a_s(y_j) (y_j > y_i)
/// are formed by a merge sort on y over the x order (divide and conquer: the pairs split
/// between two halves are met while merging them, `sweep`), with compensated running
/// sums; memory O(n), sequential access. Ties on either axis fall in either case alike (g
/// is continuous).
pub fn pair_sum_2d<const R: usize>(
    points: &[f64],
    g: impl Fn(f64, f64) -> f64 + Sync,
    split: impl Fn(f64) -> ([f64; R], [f64; R]) + Copy + Sync,
) -> f64 {
    pair_sum_2d_in_runs(points, g, split, RUN)
}

/// Outputs per task of a merge (the bits do not depend on it: see [`merge_halves`]).
const RUN: usize = 1 << 14;

/// [`pair_sum_2d`], each merge cut into tasks of about `run` outputs.
fn pair_sum_2d_in_runs<const R: usize>(
    points: &[f64],
    g: impl Fn(f64, f64) -> f64 + Sync,
    split: impl Fn(f64) -> ([f64; R], [f64; R]) + Copy + Sync,
    run: usize,
) -> f64 {
    let pts: Vec<Point> = points.par_chunks_exact(2).map(|p| Point { x: p[0], y: p[1], inner: 0.0 }).collect();
    let n = pts.len();
    let (mut pts, mut spare) = bucket_sort_x(pts);
    // merge levels above the blocks, from one buffer into the other: the whole ends in
    // `pts` after an even number of them
    let levels = (0..).find(|&l| BLOCK << l >= n).unwrap_or(0);
    // RR = R^2 products, W >= 2 RR running sums padded to whole vectors
    match R {
        1 => sweep::<R, 1, 8>(&g, split, &mut pts, &mut spare, levels, run),
        2 => sweep::<R, 4, 8>(&g, split, &mut pts, &mut spare, levels, run),
        3 => sweep::<R, 9, 24>(&g, split, &mut pts, &mut spare, levels, run),
        _ => unreachable!("the closed forms here have kernels of rank 1 to 3"),
    }
    let from = if levels % 2 == 0 { &pts } else { &spare };
    // the terms' compensated sums by fixed chunks of RUN points in parallel, merged in order
    // (a serial pass over 10^6 points took 4-5 ms, after which the other threads idle)
    let parts: Vec<Sum> = from
        .par_chunks(RUN)
        .with_max_len(1)
        .map(|chunk| {
            let mut part = Sum::default();
            chunk.iter().for_each(|p| part.add(2.0 * p.inner + g(p.x, p.x) * g(p.y, p.y)));
            part
        })
        .collect();
    let mut pair = Sum::default();
    parts.into_iter().for_each(|part| pair.merge(part));
    pair.value()
}

/// Nodes of at most this many points are swept on one thread (no task per half).
const SERIAL: usize = 64 * BLOCK;

/// One node of the merge sort on y, depth first: the points of `a` (at most BLOCK 2^level,
/// in x order) sorted by y into `a` after an even level, into `b` after an odd one (each
/// the other's scratch), every point given its pairs with the node's earlier points. A
/// block's pairs are summed directly ([`block_pairs`]); a larger node sweeps its halves,
/// in parallel above [`SERIAL`] points, then merges them ([`merge_halves`]). The earlier
/// half's running sums ([`Marks`]) are made on the thread that sorted it while the later
/// half may still be sorting on others: made after both, as in the merge sort by levels
/// this replaced, they kept one thread alone for 2-3.4 ms at the top merge of 10^6 points
/// (timers, 2026-12-01), and every level ended by waiting for its last merges. The nodes
/// and merges are those of the merge sort by levels (node k of a level the points from k
/// BLOCK 2^level on), and so are the bits.
fn sweep<const R: usize, const RR: usize, const W: usize>(
    g: &(impl Fn(f64, f64) -> f64 + Sync),
    split: impl Fn(f64) -> ([f64; R], [f64; R]) + Copy + Sync,
    a: &mut [Point],
    b: &mut [Point],
    level: u32,
    run: usize,
) {
    if a.is_empty() {
        return;
    }
    if level == 0 {
        // (compiled for the widest vector instructions: the sums are independent lanes,
        // the same bits on every instruction set)
        return crate::simd::wide(
            #[inline(always)]
            || {
                block_pairs(g, a);
                a.sort_unstable_by_key(|p| order_key(p.y));
            },
        );
    }
    let (width, cut, parallel) = (BLOCK << (level - 1), a.len() > run, a.len() > SERIAL);
    let (early, late) = a.split_at_mut(width.min(a.len()));
    let (early_b, late_b) = b.split_at_mut(width.min(b.len()));
    // (the halves' tasks hold a reference: `split` is Sync, not necessarily Send)
    let split_ref = &split;
    let mut earlier_half = move || {
        sweep::<R, RR, W>(g, *split_ref, early, early_b, level - 1, run);
        let sorted = if level % 2 == 1 { &*early } else { &*early_b };
        // marks where the merge may be cut into runs, else the total alone
        Marks::new::<R, RR>(*split_ref, sorted, if cut { MARK } else { usize::MAX })
    };
    let mut later_half = move || sweep::<R, RR, W>(g, *split_ref, late, late_b, level - 1, run);
    let marks = if parallel {
        rayon::join(earlier_half, later_half).0
    } else {
        let marks = earlier_half();
        later_half();
        marks
    };
    let (from, to) = if level % 2 == 1 { (&*a, b) } else { (&*b, a) };
    merge_halves::<R, RR, W>(split, from, to, width, &marks, run);
}

/// Where a merge of `left` earlier and `right` later items is cut into `pieces` runs: at
/// later items j_k = k right / pieces, each with `before(j_k)`, the earlier items the
/// serial merge has output before later item j_k; from (0, 0) to (left, right).
fn cuts(left: usize, right: usize, pieces: usize, before: impl Fn(usize) -> usize) -> Vec<(usize, usize)> {
    (0..=pieces)
        .map(|k| match k {
            0 => (0, 0),
            _ if k == pieces => (left, right),
            _ => (before(k * right / pieces), k * right / pieces),
        })
        .collect()
}

/// Earlier points between running-sum marks of a merge cut into runs.
const MARK: usize = 1024;

/// An earlier half's running sums over its points' terms ([`earlier`]), in its y order:
/// before every `every`-th point, and over all of them.
struct Marks<const W: usize> {
    every: usize,
    before: Vec<Lanes<W>>,
    total: Lanes<W>,
}

impl<const W: usize> Marks<W> {
    fn new<const R: usize, const RR: usize>(
        split: impl Fn(f64) -> ([f64; R], [f64; R]),
        left: &[Point],
        every: usize,
    ) -> Marks<W> {
        crate::simd::wide(
            #[inline(always)]
            || {
                let mut sums = Lanes::<W>::new();
                let mut before = Vec::with_capacity(left.len().div_ceil(every));
                for chunk in left.chunks(every) {
                    before.push(sums);
                    for q in chunk {
                        sums.add(earlier::<R, RR, W>(&split, q, 1.0));
                    }
                }
                Marks { every, before, total: sums }
            },
        )
    }

    /// The running sums over `left[..i]`, on from the last mark at or before i: the same
    /// additions in the same order as from the first point, so the same bits.
    #[inline(always)]
    fn at<const R: usize, const RR: usize>(
        &self,
        split: &impl Fn(f64) -> ([f64; R], [f64; R]),
        left: &[Point],
        i: usize,
    ) -> Lanes<W> {
        let Some(&mark) = self.before.get(i / self.every) else { return self.total };
        let mut sums = mark;
        for q in &left[i / self.every * self.every..i] {
            sums.add(earlier::<R, RR, W>(split, q, 1.0));
        }
        sums
    }
}

/// One run of a merge: the earlier half's points `left` and the later half's `right` that
/// it outputs, and the running sums over the earlier half's points before `left`.
struct Run<'a, const W: usize> {
    left: &'a [Point],
    right: &'a [Point],
    below: Lanes<W>,
    total: Lanes<W>,
}

/// A node's merge: its y-sorted halves `from[..width]` (earlier) and `from[width..]`
/// (later) merged into `to`, every later point given its pairs with the earlier half
/// ([`merge`]). A merge of more than `run` points is cut into runs of about `run` outputs
/// at later points j_k, with the earlier points i_k the serial merge has output before j_k
/// (those with y <= y_(j_k)); a run starts from the earlier half's running sums over its
/// first i_k points, which are the sums the serial merge holds there (its steps that take
/// a later point add zeros, which leave the sums' bits as they are). So every run gives the
/// serial merge's bits, and the runs go in parallel.
fn merge_halves<const R: usize, const RR: usize, const W: usize>(
    split: impl Fn(f64) -> ([f64; R], [f64; R]) + Copy + Sync,
    from: &[Point],
    to: &mut [Point],
    width: usize,
    marks: &Marks<W>,
    run: usize,
) {
    let (left, right) = from.split_at(width.min(from.len()));
    let pieces = from.len().div_ceil(run.max(1)).min(right.len()).max(1);
    let total = marks.total;
    if pieces == 1 {
        // (a plain call: an iterator's fold here would not be compiled wide)
        return crate::simd::wide(
            #[inline(always)]
            || merge::<R, RR, W>(&split, Run { left, right, below: Lanes::new(), total }, to),
        );
    }
    let cuts = cuts(left.len(), right.len(), pieces, |j| left.partition_point(|q| q.y <= right[j].y));
    let outs = crate::memory::split(to, cuts.windows(2).map(|c| c[1].0 - c[0].0 + c[1].1 - c[0].1));
    let tasks: Vec<_> =
        cuts.windows(2).zip(outs).map(|(c, out)| (c[0].0, &left[c[0].0..c[1].0], &right[c[0].1..c[1].1], out)).collect();
    // a task a run: rayon's own split handed a thread a quarter of a merge's runs in one
    // piece, which the other thread could not share (one thread alone for the last 5 ms of
    // the top merge in a profile on two threads)
    tasks.into_par_iter().with_max_len(1).for_each(|(i0, l, r, out)| {
        crate::simd::wide(
            #[inline(always)]
            || {
                let below = marks.at::<R, RR>(&split, left, i0);
                merge::<R, RR, W>(&split, Run { left: l, right: r, below, total }, out)
            },
        )
    });
}

/// Below this many points a comparison sort is faster than the bucket sort's passes.
const BUCKETS_FROM: usize = 4096;

/// Points per bucket of [`bucket_sort_x`], on average.
const PER_BUCKET: usize = 16;

/// Groups of buckets in [`bucket_sort_x`]'s first pass.
const GROUPS: usize = 256;

/// A group of more than 1 / CROWDED of the points (16 times its share) turns
/// [`bucket_sort_x`] into a parallel merge sort.
const CROWDED: usize = GROUPS / 16;

/// The points in x order (`f64::total_cmp`'s), and a spare buffer of the same length: a
/// comparison sort below [`BUCKETS_FROM`] points, else a stable sort, which has one result
/// however it is made. Each point goes to one of about n / [`PER_BUCKET`] buckets by its x
/// between the finite extremes (a function of x that never decreases in the order, NaNs
/// and infinities in the end buckets), in two stable counting passes: by groups of
/// buckets, the points cut into blocks that each write their own places (one pass over the
/// points, in parallel), then each group on its own, in the cache, by bucket, each bucket
/// then sorted stably by x. The least-significant-digit radix sort this replaced made six
/// passes over the points and, on more than one thread, a merge of sorted pieces. Where
/// one group would hold more than 16 times its share of the points, a parallel stable
/// merge sort does the whole instead.
fn bucket_sort_x(mut pts: Vec<Point>) -> (Vec<Point>, Vec<Point>) {
    const BLOCK_POINTS: usize = 1 << 14;
    let n = pts.len();
    // scratch, its first touch shared among the threads
    let mut spare: Vec<Point> = pts.par_iter().copied().collect();
    if n < BUCKETS_FROM {
        pts.sort_unstable_by_key(|p| order_key(p.x));
        return (pts, spare);
    }
    let buckets = (n / PER_BUCKET).next_power_of_two().max(GROUPS);
    let per_group = buckets / GROUPS;
    // the finite extremes, in one pass
    let (lo, hi) = pts
        .par_iter()
        .filter(|p| p.x.is_finite())
        .map(|p| (p.x, p.x))
        .reduce(|| (f64::INFINITY, f64::NEG_INFINITY), |a, b| (a.0.min(b.0), a.1.max(b.1)));
    let scale = if hi > lo { buckets as f64 / (hi - lo) } else { 0.0 };
    let scale = if scale.is_finite() { scale } else { 0.0 };
    // (a float cast saturates, and a NaN casts to 0: the positive NaNs, last in the order,
    // go to the last bucket)
    let bucket = |x: f64| {
        if x.is_nan() && x.is_sign_positive() { buckets - 1 } else { (((x - lo) * scale) as usize).min(buckets - 1) }
    };
    // each block's count of points per group, then its first place in each group
    let mut places: Vec<Vec<usize>> = pts
        .par_chunks(BLOCK_POINTS)
        .map(|block| {
            let mut count = vec![0; GROUPS];
            block.iter().for_each(|p| count[bucket(p.x) / per_group] += 1);
            count
        })
        .collect();
    let mut starts = Vec::with_capacity(GROUPS + 1);
    let mut at = 0;
    for group in 0..GROUPS {
        starts.push(at);
        for block in places.iter_mut() {
            (block[group], at) = (at, at + block[group]);
        }
    }
    starts.push(at);
    // x crowded into a few buckets (a cluster beside a far outlier, say): the groups' own
    // passes would leave one thread sorting most of the points, so a parallel stable sort,
    // which gives the same order
    if starts.windows(2).any(|w| w[1] - w[0] > n / CROWDED) {
        pts.par_sort_by_key(|p| order_key(p.x));
        return (pts, spare);
    }
    let out = crate::memory::Disjoint(spare.as_mut_ptr());
    pts.par_chunks(BLOCK_POINTS).zip(places).for_each(|(block, mut place)| {
        for p in block {
            let group = bucket(p.x) / per_group;
            // SAFETY: the blocks' places are disjoint (counted above) and inside `spare`,
            // which no one else touches during the loop
            unsafe { out.write(place[group], *p) };
            place[group] += 1;
        }
    });
    // each group by bucket, back into `pts`, each bucket then sorted
    let tos = crate::memory::split(&mut pts, starts.windows(2).map(|w| w[1] - w[0]));
    let groups: Vec<_> = starts.windows(2).map(|w| &spare[w[0]..w[1]]).zip(tos).collect();
    groups.into_par_iter().enumerate().with_max_len(1).for_each(|(group, (from, to))| {
        let first = group * per_group;
        let mut start = vec![0usize; per_group + 1];
        from.iter().for_each(|p| start[bucket(p.x) - first + 1] += 1);
        for k in 1..=per_group {
            start[k] += start[k - 1];
        }
        let mut next = start.clone();
        for p in from {
            let k = bucket(p.x) - first;
            to[next[k]] = *p;
            next[k] += 1;
        }
        for k in 0..per_group {
            to[start[k]..start[k + 1]].sort_by_key(|p| order_key(p.x));
        }
    });
    (pts, spare)
}

/// The sweep's leaves: blocks whose pairs are summed directly (fewer, longer merges).
const BLOCK: usize = 64;

/// Each point's sum over the block's earlier points of g(x_i, x_j) g(y_i, y_j), in eight
/// lanes (j mod 8) over the whole block, the later points' terms weighted by zero.
#[inline(always)]
fn block_pairs(g: &impl Fn(f64, f64) -> f64, block: &mut [Point]) {
    let mut xs = [0.0; BLOCK];
    let mut ys = [0.0; BLOCK];
    for (k, p) in block.iter().enumerate() {
        (xs[k], ys[k]) = (p.x, p.y);
    }
    for (i, p) in block.iter_mut().enumerate() {
        let mut lanes = [0.0; 8];
        for (c, (x, y)) in xs.chunks_exact(8).zip(ys.chunks_exact(8)).enumerate() {
            for k in 0..8 {
                let weight = if 8 * c + k < i { 1.0 } else { 0.0 };
                lanes[k] += weight * (g(p.x, x[k]) * g(p.y, y[k]));
            }
        }
        p.inner = lanes.iter().sum();
    }
}

/// A point of the sweep, with its sum over the earlier points met so far (a plain sum: a
/// block's pairs, then one term per merge level; the running sums it is read from are the
/// compensated ones).
#[derive(Clone, Copy)]
struct Point {
    x: f64,
    y: f64,
    inner: f64,
}

/// The R x R products u_r v_s, row-major.
#[inline(always)]
fn outer<const R: usize, const RR: usize>(u: &[f64; R], v: &[f64; R]) -> [f64; RR] {
    array(|k| u[k / R] * v[k % R])
}

/// sum_rs u_r v_s sums_rs.
#[inline(always)]
fn contract<const R: usize, const RR: usize>(u: &[f64; R], v: &[f64; R], sums: &[f64; RR]) -> f64 {
    outer::<R, RR>(u, v).iter().zip(sums).map(|(w, s)| w * s).sum()
}

/// Merge a run's y-sorted earlier points `r.left` and later points `r.right` into `to`,
/// adding to each later point its pairs with the earlier half: those below it in y from the
/// running sums over the earlier points met before it, those above from the half's total
/// less them. One pass without branches on the data: both candidates' terms are formed at
/// every step, the one not taken weighted by zero (which leaves the running sums' bits as
/// they are).
#[inline(always)]
fn merge<const R: usize, const RR: usize, const W: usize>(
    split: &impl Fn(f64) -> ([f64; R], [f64; R]),
    r: Run<W>,
    to: &mut [Point],
) {
    let Run { left, right, mut below, total } = r;
    if right.is_empty() || left.is_empty() {
        for (out, p) in to.iter_mut().zip(left.iter().chain(right)) {
            *out = if left.is_empty() { later::<R, RR, W>(split, p, &below.values(), &total.less(&below)) } else { *p };
        }
        return;
    }
    let (mut i, mut j) = (0, 0);
    for out in to.iter_mut() {
        let (q, p) = (left[i.min(left.len() - 1)], right[j.min(right.len() - 1)]);
        let take_left = (j == right.len()) | ((i < left.len()) & (q.y <= p.y));
        below.add(earlier::<R, RR, W>(split, &q, if take_left { 1.0 } else { 0.0 }));
        *out = if take_left { q } else { later::<R, RR, W>(split, &p, &below.values(), &total.less(&below)) };
        i += usize::from(take_left);
        j += usize::from(!take_left);
    }
}

/// An earlier point's terms times `weight`: b_r(x_j) b_s(y_j), then b_r(x_j) a_s(y_j), then
/// zeros.
#[inline(always)]
fn earlier<const R: usize, const RR: usize, const W: usize>(
    split: &impl Fn(f64) -> ([f64; R], [f64; R]),
    q: &Point,
    weight: f64,
) -> [f64; W] {
    let ((_, bx), (ay, by)) = (split(q.x), split(q.y));
    let (bb, ba): ([f64; RR], [f64; RR]) = (outer(&bx, &by), outer(&bx, &ay));
    array(|k| weight * if k < RR { bb[k] } else if k < 2 * RR { ba[k - RR] } else { 0.0 })
}

/// A later point with its pairs with the earlier points added, from their sums (the terms
/// of [`earlier`]) below it and above it in y: g(y_i, y_j) is sum_s a_s(y_i) b_s(y_j) for
/// those below, sum_s b_s(y_i) a_s(y_j) for those above.
#[inline(always)]
fn later<const R: usize, const RR: usize, const W: usize>(
    split: &impl Fn(f64) -> ([f64; R], [f64; R]),
    p: &Point,
    below: &[f64; W],
    above: &[f64; W],
) -> Point {
    let ((ax, _), (ay, by)) = (split(p.x), split(p.y));
    let (below_b, above_a): ([f64; RR], [f64; RR]) = (array(|k| below[k]), array(|k| above[RR + k]));
    Point { inner: p.inner + contract(&ax, &ay, &below_b) + contract(&ax, &by, &above_a), ..*p }
}

/// The array of f(0), f(1), ... (as `std::array::from_fn`, but always inlined: the hot
/// loops here are compiled wide only where everything they call is).
#[inline(always)]
fn array<const N: usize>(f: impl Fn(usize) -> f64) -> [f64; N] {
    let mut out = [0.0; N];
    for (k, o) in out.iter_mut().enumerate() {
        *o = f(k);
    }
    out
}

/// An L2 metric: the root of its squared closed form (clamped at zero: the closed forms
/// cancel heavily).
const fn l2_entry(about: About, compute: fn(&Params, &PointSet, Limits) -> Result<f64>) -> MetricEntry {
    MetricEntry { l2: true, ..MetricEntry::new(about, compute) }
}


/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[
    l2_entry(
        About::new("l2-star", "root mean square over anchored boxes (Shirley's S), Warnock's formula")
            .aliases(&["rms", "s", "warnock"])
            .cite(&["shirley1991"]),
        |_, p, limits| STAR.value(p.as_slice(), p.dims(), limits.progress),
    ),
    l2_entry(
        About::new("l2-extreme", "root mean square over all boxes").aliases(&["l2-unanchored"]).cite(&["shirley1991"]),
        |_, p, limits| EXTREME.value(p.as_slice(), p.dims(), limits.progress),
    ),
    l2_entry(About::new("centered", "centered L2 discrepancy (Hickernell)").aliases(&["cd"]), |_, p, limits| {
        CENTERED.value(p.as_slice(), p.dims(), limits.progress)
    }),
    MetricEntry {
        shift_invariant: true,
        ..l2_entry(
            About::new("wraparound", "wrap-around L2 discrepancy (Hickernell); toroidal-shift invariant")
                .aliases(&["wd", "wrap-around"]),
            |_, p, limits| WRAPAROUND.value(p.as_slice(), p.dims(), limits.progress),
        )
    },
    l2_entry(About::new("mixture", "mixture L2 discrepancy").aliases(&["md"]), |_, p, limits| {
        MIXTURE.value(p.as_slice(), p.dims(), limits.progress)
    }),
    MetricEntry {
        shift_invariant: true,
        ..l2_entry(
            About::new("diaphony", "Zinterhof's diaphony: the Fourier coefficients' weighted energy")
                .cite(&["zinterhof1976"]),
            |_, p, limits| DIAPHONY.value(p.as_slice(), p.dims(), limits.progress),
        )
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucket_sort_gives_total_cmp_order() {
        let mut rng = crate::Seed(12).rng();
        let special = [0.0, -0.0, 1.0, 0.5, f64::MIN_POSITIVE, 1e-310, 0.25, 0.75, -2.0, 3.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, -f64::NAN];
        for n in [1, 2, 7, 64, 1000, 5000, 20000, 70001] {
            let coords: Vec<f64> = (0..2 * n)
                .map(|k| match k % 5 {
                    0 => special[crate::seed::below(&mut rng, special.len() as u64) as usize],
                    1 => (crate::seed::uniform(&mut rng) * 16.0).floor() / 16.0,
                    _ => crate::seed::uniform(&mut rng),
                })
                .collect();
            let pts: Vec<Point> = coords.chunks_exact(2).map(|p| Point { x: p[0], y: p[1], inner: 0.0 }).collect();
            let mut want: Vec<f64> = coords.iter().step_by(2).copied().collect();
            want.sort_by(f64::total_cmp);
            // above the comparison sort, the stable order (ties keep their y order here)
            let mut stable = pts.clone();
            stable.sort_by(|a, b| a.x.total_cmp(&b.x));
            for threads in [1, 2, 3, 8] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let (sorted, spare) = pool.install(|| bucket_sort_x(pts.clone()));
                assert_eq!(spare.len(), n);
                let got: Vec<u64> = sorted.iter().map(|p| p.x.to_bits()).collect();
                assert_eq!(got, want.iter().map(|x| x.to_bits()).collect::<Vec<_>>(), "n = {n}, {threads} threads");
                if n >= BUCKETS_FROM {
                    let ys = |v: &[Point]| v.iter().map(|p| p.y.to_bits()).collect::<Vec<_>>();
                    assert_eq!(ys(&sorted), ys(&stable), "n = {n}, {threads} threads: not stable");
                }
            }
        }
    }

    #[test]
    fn crowded_x_keeps_the_stable_order() {
        // all but one point within 10^-8 (one bucket of 2^12): the merge sort's path
        let mut rng = crate::Seed(14).rng();
        let n = 50000;
        let mut pts: Vec<Point> = (0..n)
            .map(|k| Point { x: 0.3 + (k % 4000) as f64 * 2e-12, y: crate::seed::uniform(&mut rng), inner: 0.0 })
            .collect();
        pts[n / 2].x = 1.0;
        let mut want = pts.clone();
        want.sort_by(|a, b| a.x.total_cmp(&b.x));
        let bits = |v: &[Point]| v.iter().map(|p| (p.x.to_bits(), p.y.to_bits())).collect::<Vec<_>>();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (sorted, _) = pool.install(|| bucket_sort_x(pts.clone()));
            assert!(bits(&sorted) == bits(&want), "{threads} threads");
        }
    }

    #[test]
    fn merges_cut_into_runs_give_the_serial_bits() {
        // ties on both axes (coordinates on a 1/16 grid) put equal y on both sides of a cut
        let mut rng = crate::Seed(13).rng();
        // (40000 points: the terms' sums in three chunks of RUN)
        for n in [3, 200, 5000, 40000] {
            let points: Vec<f64> = (0..2 * n)
                .map(|k| {
                    let u = crate::seed::uniform(&mut rng);
                    if k % 3 == 0 { (u * 16.0).floor() / 16.0 } else { u }
                })
                .collect();
            let serial = pair_sum_2d_in_runs(&points, |x, y| 1.0 - x.max(y), |u| ([1.0 - u], [1.0]), usize::MAX);
            let exact: f64 = (0..n)
                .into_par_iter()
                .map(|i| {
                    (0..n)
                        .map(|j| (1.0 - points[2 * i].max(points[2 * j])) * (1.0 - points[2 * i + 1].max(points[2 * j + 1])))
                        .sum::<f64>()
                })
                .collect::<Vec<f64>>()
                .iter()
                .sum();
            assert!((serial - exact).abs() <= 1e-9 * exact, "n = {n}: {serial} vs {exact}");
            for run in [1, 5, 64, 1000] {
                for threads in [1, 3] {
                    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                    let cut = pool
                        .install(|| pair_sum_2d_in_runs(&points, |x, y| 1.0 - x.max(y), |u| ([1.0 - u], [1.0]), run));
                    assert_eq!(cut.to_bits(), serial.to_bits(), "n = {n}, runs of {run}, {threads} threads");
                }
            }
        }
    }

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
