//! Star discrepancy D*: the supremum over boxes [0, q) anchored at the origin of
//! |#points in box / N - volume| (Shirley 1991 section 3.1, "D"; Zaremba's definition).
//!
//! The supremum is attained in the limit of a critical box: every upper corner
//! coordinate is a point's coordinate or 1, and the box is either open (points on its
//! upper faces excluded: the volume exceeds the count) or closed (included: the count
//! exceeds the volume). Ties and coordinates equal to 1 are handled by that rule.

use super::kinetic::KineticTree;

/// 1D closed form: with x sorted, max_i max(i/N - x_(i), x_(i) - (i-1)/N). O(n log n).
pub fn star_1d(x: &[f64]) -> f64 {
    let mut v = x.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len() as f64;
    let mut worst = 1.0 - v.iter().filter(|&&t| t < 1.0).count() as f64 / n; // [0, 1)
    let mut i = 0;
    while i < v.len() {
        let mut j = i;
        while j < v.len() && v[j] == v[i] {
            j += 1;
        }
        // open [0, x): i points below; closed [0, x]: j points
        worst = worst.max(v[i] - i as f64 / n).max(j as f64 / n - v[i]);
        i = j;
    }
    worst
}

/// Sorted distinct values of `v` with 1.0 appended when absent: the critical coordinates.
pub(crate) fn critical(v: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut c: Vec<f64> = v.collect();
    c.push(1.0);
    c.sort_by(f64::total_cmp);
    c.dedup();
    c
}

/// Brute force over every critical box in d dimensions: O(n^(d+1)). The reference for
/// every faster algorithm; `points` is row-major with `dims` coordinates.
pub fn star_naive(points: &[f64], dims: usize) -> f64 {
    let n = points.len() / dims;
    let axes: Vec<Vec<f64>> = (0..dims).map(|d| critical(points.iter().skip(d).step_by(dims).copied())).collect();
    let mut idx = vec![0usize; dims];
    let mut worst: f64 = 0.0;
    loop {
        let q: Vec<f64> = idx.iter().zip(&axes).map(|(&i, a)| a[i]).collect();
        let vol: f64 = q.iter().product();
        let (mut open, mut closed) = (0usize, 0usize);
        for p in points.chunks_exact(dims) {
            open += usize::from(p.iter().zip(&q).all(|(x, b)| x < b));
            closed += usize::from(p.iter().zip(&q).all(|(x, b)| x <= b));
        }
        worst = worst.max(vol - open as f64 / n as f64).max(closed as f64 / n as f64 - vol);
        let mut d = 0;
        loop {
            if d == dims {
                return worst;
            }
            idx[d] += 1;
            if idx[d] < axes[d].len() {
                break;
            }
            idx[d] = 0;
            d += 1;
        }
    }
}

/// Points sorted by x, with the rank of each y among the critical y values.
fn sweep_order(points: &[f64]) -> (Vec<(f64, usize)>, Vec<f64>) {
    let ys = critical(points.iter().skip(1).step_by(2).copied());
    let mut order: Vec<(f64, usize)> = points
        .chunks_exact(2)
        .map(|p| (p[0], ys.binary_search_by(|c| c.total_cmp(&p[1])).expect("y is a critical value")))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    (order, ys)
}

/// What a 2D sweep over x does at each event.
trait Sweeper {
    /// A point whose y has critical rank `k` enters (x = the current a).
    fn insert(&mut self, k: usize);
    /// Open boxes [0,a) x [0,b): the points with x < a are in.
    fn open(&mut self, a: f64);
    /// Closed boxes [0,a] x [0,b]: the points with x <= a are in.
    fn closed(&mut self, a: f64);
}

/// Visit every distinct x in increasing order (and finally 1).
fn sweep(order: &[(f64, usize)], s: &mut impl Sweeper) {
    let mut i = 0;
    while i < order.len() {
        let a = order[i].0;
        s.open(a);
        while i < order.len() && order[i].0 == a {
            s.insert(order[i].1);
            i += 1;
        }
        s.closed(a);
    }
    if order.last().is_none_or(|l| l.0 < 1.0) {
        s.open(1.0);
    }
}

/// Per critical y value b_j: the counts of inserted points with y < b_j and y <= b_j.
struct ArraySweep<'a> {
    ys: &'a [f64],
    n: f64,
    below: Vec<u32>,
    upto: Vec<u32>,
    worst: f64,
}

impl Sweeper for ArraySweep<'_> {
    fn insert(&mut self, k: usize) {
        self.below[k + 1..].iter_mut().for_each(|c| *c += 1);
        self.upto[k..].iter_mut().for_each(|c| *c += 1);
    }
    fn open(&mut self, a: f64) {
        let w = self.below.iter().zip(self.ys).map(|(&c, &b)| a * b - c as f64 / self.n).fold(f64::MIN, f64::max);
        self.worst = self.worst.max(w);
    }
    fn closed(&mut self, a: f64) {
        let w = self.upto.iter().zip(self.ys).map(|(&c, &b)| c as f64 / self.n - a * b).fold(f64::MIN, f64::max);
        self.worst = self.worst.max(w);
    }
}

/// Exact 2D star discrepancy by an O(n^2) sweep: the public cross-check for [`star_2d`].
pub fn star_2d_sweep(points: &[f64]) -> f64 {
    let (order, ys) = sweep_order(points);
    let m = ys.len();
    let mut s = ArraySweep { ys: &ys, n: order.len() as f64, below: vec![0; m], upto: vec![0; m], worst: 0.0 };
    sweep(&order, &mut s);
    s.worst
}

/// The local discrepancies as lines in a, in two kinetic segment trees.
struct KineticSweep {
    m: usize,
    open: KineticTree,
    closed: KineticTree,
    open_max: f64,
    closed_max: f64,
}

impl Sweeper for KineticSweep {
    fn insert(&mut self, k: usize) {
        self.open.add(k + 1, self.m, 1);
        self.closed.add(k, self.m, 1);
    }
    fn open(&mut self, a: f64) {
        self.open_max = self.open_max.max(self.open.max_at(a));
    }
    fn closed(&mut self, a: f64) {
        self.closed_max = self.closed_max.max(self.closed.max_at(a));
    }
}

/// The largest open and closed local discrepancies, max over boxes of w vol - open/N and
/// closed/N - w vol, for `points` (row-major, `dims` coordinates) counted against a
/// total of `total` points. The building block of the exact d-D star discrepancy.
fn weighted(points: &[f64], dims: usize, w: f64, total: f64) -> (f64, f64) {
    match dims {
        1 => {
            let mut v = points.to_vec();
            v.sort_by(f64::total_cmp);
            let (mut open, mut closed) =
                (w * 1.0 - v.iter().filter(|&&t| t < 1.0).count() as f64 / total, f64::NEG_INFINITY);
            let mut i = 0;
            while i < v.len() {
                let mut j = i;
                while j < v.len() && v[j] == v[i] {
                    j += 1;
                }
                open = open.max(w * v[i] - i as f64 / total);
                closed = closed.max(j as f64 / total - w * v[i]);
                i = j;
            }
            (open, closed)
        }
        2 => {
            let (order, ys) = sweep_order(points);
            let slopes: Vec<f64> = ys.iter().map(|b| w * b).collect();
            let neg: Vec<f64> = slopes.iter().map(|s| -s).collect();
            let mut s = KineticSweep {
                m: ys.len(),
                open: KineticTree::new(&slopes, -1.0 / total, 0.0),
                closed: KineticTree::new(&neg, 1.0 / total, 0.0),
                open_max: f64::NEG_INFINITY,
                closed_max: f64::NEG_INFINITY,
            };
            sweep(&order, &mut s);
            (s.open_max, s.closed_max)
        }
        _ => {
            // sweep the last coordinate c; the boxes below it are a (d-1)-D problem with
            // weight w c over the points already passed
            let mut rows: Vec<&[f64]> = points.chunks_exact(dims).collect();
            rows.sort_by(|a, b| a[dims - 1].total_cmp(&b[dims - 1]));
            let mut inside: Vec<f64> = Vec::with_capacity(points.len());
            let (mut open, mut closed) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
            let mut i = 0;
            while i < rows.len() {
                let c = rows[i][dims - 1];
                open = open.max(weighted(&inside, dims - 1, w * c, total).0);
                while i < rows.len() && rows[i][dims - 1] == c {
                    inside.extend_from_slice(&rows[i][..dims - 1]);
                    i += 1;
                }
                closed = closed.max(weighted(&inside, dims - 1, w * c, total).1);
            }
            if rows.last().is_none_or(|r| r[dims - 1] < 1.0) {
                open = open.max(weighted(&inside, dims - 1, w, total).0);
            }
            (open, closed)
        }
    }
}

/// Exact 2D star discrepancy in O(n log^2 n): sweep x; keep the local discrepancies
/// a*b_j - c_j/N (open boxes) and c_j/N - a*b_j (closed boxes) of every critical y value
/// b_j as lines in a, in two kinetic segment trees: a new point adds one to the counts of
/// a suffix of the b_j, and a only increases.
pub fn star_2d(points: &[f64]) -> f64 {
    star_exact(points, 2)
}

/// Exact star discrepancy in d dimensions in O(n^(d-1) log^2 n) (d >= 2): sweep the last
/// coordinate, solving the (d-1)-D problem with the volume weighted by it over the points
/// passed, down to the 2D kinetic sweep.
pub fn star_exact(points: &[f64], dims: usize) -> f64 {
    let (open, closed) = weighted(points, dims, 1.0, (points.len() / dims) as f64);
    open.max(closed).max(0.0)
}
