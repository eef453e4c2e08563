//! Star discrepancy D*: the supremum over boxes [0, q) anchored at the origin of
//! |#points in box / N - volume| (Shirley 1991 section 3.1, "D"; Zaremba's definition).
//!
//! The supremum is attained in the limit of a critical box: every upper corner
//! coordinate is a point's coordinate or 1, and the box is either open (points on its
//! upper faces excluded: the volume exceeds the count) or closed (included: the count
//! exceeds the volume). Ties and coordinates equal to 1 are handled by that rule.

use std::sync::atomic::{AtomicU64, Ordering};

use rayon::prelude::*;

use super::kinetic::KineticTree;
use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::registry::About;
use crate::spec::Params;

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
    c.par_sort_unstable_by(f64::total_cmp);
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

/// Points (x, the rank of y among the critical y values) sorted by x, and those values.
type Order = (Vec<(f64, usize)>, Vec<f64>);

/// The points' [`Order`], looking at the stop flag between its stages: two sorts and two
/// linear passes, each at most a few hundred milliseconds for 4 x 10^6 points. The y ranks
/// come from the sort by y itself (a binary search per point among the critical values was
/// a stage of seconds, with a cache miss per step).
fn sweep_order(points: &[f64], progress: Progress) -> Result<Order> {
    let mut by_y: Vec<(f64, usize)> = points.par_chunks_exact(2).enumerate().map(|(i, p)| (p[1], i)).collect();
    by_y.par_sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    progress.check()?;
    // the critical y values (equal ones once, then 1.0 where absent: every y is in [0, 1])
    // and each point's rank among them
    let mut ys: Vec<f64> = Vec::new();
    let mut rank = vec![0; by_y.len()];
    for &(y, i) in &by_y {
        if ys.last() != Some(&y) {
            ys.push(y);
        }
        rank[i] = ys.len() - 1;
    }
    if ys.last() != Some(&1.0) {
        ys.push(1.0);
    }
    drop(by_y);
    progress.check()?;
    let mut order: Vec<(f64, usize)> = points.par_chunks_exact(2).zip(rank).map(|(p, k)| (p[0], k)).collect();
    progress.check()?;
    // equal x are inserted together before the next look at the boxes: their order is free
    order.par_sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    progress.check()?;
    Ok((order, ys))
}

/// What a 2D sweep over x does at each event.
trait Sweeper {
    /// A point whose y has critical rank `k` enters (x = the current a).
    fn insert(&mut self, k: usize);
    /// Open boxes [0,a) x [0,b): the points with x < a are in.
    fn open(&mut self, a: f64);
    /// Closed boxes [0,a] x [0,b]: the points with x <= a are in.
    fn closed(&mut self, a: f64);
    /// Whether to go on to the next distinct x.
    fn go_on(&mut self) -> bool {
        true
    }
}

/// Visit every distinct x in increasing order (and finally 1), while the sweeper goes on.
fn sweep(order: &[(f64, usize)], s: &mut impl Sweeper) {
    let mut i = 0;
    while i < order.len() {
        if !s.go_on() {
            return;
        }
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
    // (never stopped: the silent progress)
    let (order, ys) = sweep_order(points, Progress::SILENT).unwrap_or_default();
    let m = ys.len();
    let mut s = ArraySweep { ys: &ys, n: order.len() as f64, below: vec![0; m], upto: vec![0; m], worst: 0.0 };
    sweep(&order, &mut s);
    s.worst
}

/// The local discrepancies of one kind of boxes (open or closed) as lines in a, in a
/// kinetic segment tree.
struct KineticSweep<'a> {
    m: usize,
    open: bool,
    tree: KineticTree,
    max: f64,
    /// Checked every [`SWEEP_CHECK`] distinct x (10^6 points take seconds).
    progress: Progress<'a>,
    steps: usize,
    stopped: bool,
}

/// Distinct x values a 2D sweep passes between two looks at its stop flag.
const SWEEP_CHECK: usize = 1 << 12;

impl<'a> KineticSweep<'a> {
    /// The largest local discrepancy of the open or the closed boxes: lines of `slopes` (the
    /// negated ones for closed boxes) rising by `step` per point counted.
    ///
    /// # Errors
    /// [`Error::Interrupted`] once `progress` says stop.
    fn run(order: &[(f64, usize)], slopes: &[f64], step: f64, open: bool, progress: Progress<'a>) -> Result<f64> {
        let tree = if open {
            KineticTree::new(slopes, -step, 0.0)
        } else {
            KineticTree::new(&slopes.iter().map(|s| -s).collect::<Vec<_>>(), step, 0.0)
        };
        progress.check()?;
        let mut s =
            KineticSweep { m: slopes.len(), open, tree, max: f64::NEG_INFINITY, progress, steps: 0, stopped: false };
        sweep(order, &mut s);
        if s.stopped { Err(Error::Interrupted) } else { Ok(s.max) }
    }
}

impl Sweeper for KineticSweep<'_> {
    fn insert(&mut self, k: usize) {
        self.tree.add(k + usize::from(self.open), self.m, 1);
    }
    fn open(&mut self, a: f64) {
        if self.open {
            self.max = self.max.max(self.tree.max_at(a));
        }
    }
    fn closed(&mut self, a: f64) {
        if !self.open {
            self.max = self.max.max(self.tree.max_at(a));
        }
    }
    fn go_on(&mut self) -> bool {
        self.steps += 1;
        if self.steps.is_multiple_of(SWEEP_CHECK) {
            self.stopped = self.progress.check().is_err();
        }
        !self.stopped
    }
}

/// The largest open and closed local discrepancies, max over boxes of w vol - open/N and
/// closed/N - w vol, for `points` (row-major, `dims` coordinates) counted against a
/// total of `total` points. The building block of the exact d-D star discrepancy.
///
/// # Errors
/// [`Error::Interrupted`] once `progress` says stop.
fn weighted(points: &[f64], dims: usize, w: f64, total: f64, progress: Progress) -> Result<(f64, f64)> {
    Ok(match dims {
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
            // the setup of 10^6 points takes a second: a look at the stop flag per stage
            progress.check()?;
            let (order, ys) = sweep_order(points, progress)?;
            let slopes: Vec<f64> = ys.iter().map(|b| w * b).collect();
            // the two kinds of boxes share nothing but the order: one sweep each, side by side
            let (open, closed) = rayon::join(
                || KineticSweep::run(&order, &slopes, 1.0 / total, true, progress),
                || KineticSweep::run(&order, &slopes, 1.0 / total, false, progress),
            );
            (open?, closed?)
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
                progress.check()?;
                let c = rows[i][dims - 1];
                open = open.max(weighted(&inside, dims - 1, w * c, total, progress)?.0);
                while i < rows.len() && rows[i][dims - 1] == c {
                    inside.extend_from_slice(&rows[i][..dims - 1]);
                    i += 1;
                }
                closed = closed.max(weighted(&inside, dims - 1, w * c, total, progress)?.1);
            }
            if rows.last().is_none_or(|r| r[dims - 1] < 1.0) {
                open = open.max(weighted(&inside, dims - 1, w, total, progress)?.0);
            }
            (open, closed)
        }
    })
}

/// Exact 2D star discrepancy in O(n log^2 n): sweep x; keep the local discrepancies
/// a*b_j - c_j/N (open boxes) and c_j/N - a*b_j (closed boxes) of every critical y value
/// b_j as lines in a, in two kinetic segment trees: a new point adds one to the counts of
/// a suffix of the b_j, and a only increases.
///
/// # Errors
/// [`Error::Interrupted`] once `progress` says stop (checked every 4096
/// distinct x).
pub fn star_2d(points: &[f64], progress: Progress) -> Result<f64> {
    star_exact(points, 2, progress)
}

/// Exact star discrepancy in d dimensions in O(n^(d-1) log^2 n) (d >= 2): sweep the last
/// coordinate, solving the (d-1)-D problem with the volume weighted by it over the points
/// passed, down to the 2D kinetic sweep. What `star_2d` runs; for d >= 3 [`star_dem`] is
/// faster, and this stays as its independent cross-check.
///
/// # Errors
/// [`Error::Interrupted`] once `progress` says stop.
pub fn star_exact(points: &[f64], dims: usize, progress: Progress) -> Result<f64> {
    let (open, closed) = weighted(points, dims, 1.0, (points.len() / dims) as f64, progress)?;
    Ok(open.max(closed).max(0.0))
}

/// One side of the d-D star discrepancy on the integer grid of critical corners, solved by
/// the decomposition of Dobkin, Eppstein & Mitchell (1996, section 5). Corner `c` (an
/// index into each axis's critical values) has volume prod_k axes_k[c_k] and counts the
/// points whose key `a` satisfies a <= c on every axis.
///
/// The grid is cut into slabs one axis after the other. Within a cell lo <= c <= hi a point
/// is *inside* (a <= lo: it counts at every corner), *out* (a_k > hi_k on some axis: at
/// none) or *partial*. The cuts make every partial point vary on one axis only (the key of
/// each point already partial is a slab boundary), with at most `slab` new partial points
/// per slab. The count is then separable, inside + sum_k #{partial on axis k, a_k <= c_k},
/// and the best corner of a cell follows from a product knapsack over the axes: for each
/// total count, the largest (open boxes) or smallest (closed) volume.
struct Dem<'a> {
    axes: &'a [Vec<f64>],
    /// Row-major keys, `dims` per point.
    keys: &'a [u32],
    dims: usize,
    n: f64,
    /// +1: maximise volume - count / n (open boxes); -1: count / n - volume (closed).
    sign: f64,
    /// The best found by this worker, and by every worker of both kinds of boxes (read when
    /// a worker starts, raised when it ends: a higher best prunes more).
    best: f64,
    shared: &'a AtomicU64,
    /// Checked before each slab task: once it says stop, the tasks left are skipped.
    progress: Progress<'a>,
    slab: usize,
    lo: Vec<u32>,
    hi: Vec<u32>,
    /// Per level j (axes 0..j cut): the points inside on the cut axes, and the partial ones.
    levels: Vec<(Vec<u32>, Vec<u32>)>,
    /// Knapsack scratch: per axis the partial keys, and the volumes per count.
    lists: Vec<Vec<u32>>,
    table: Vec<f64>,
    next: Vec<f64>,
    /// Sorting scratch: (key << 32 | point), which sorts faster than points by a looked-up key.
    packed: Vec<u64>,
}

/// One slab lo..=hi of an axis: the first `inside` points of the level (sorted by the
/// axis) stay inside, the first `kept` partial ones stay partial, and the points
/// inside[inside..new] become partial on this axis.
#[derive(Clone, Copy)]
struct Slab {
    lo: u32,
    hi: u32,
    inside: usize,
    kept: usize,
    new: usize,
}

impl<'a> Dem<'a> {
    /// A worker for one kind of boxes (`sign`), its points' `keys`, with empty scratch.
    fn new(axes: &'a [Vec<f64>], keys: &'a [u32], sign: f64, shared: &'a AtomicU64, progress: Progress<'a>) -> Dem<'a> {
        let dims = axes.len();
        let n = keys.len() / dims;
        Dem {
            axes,
            keys,
            dims,
            n: n as f64,
            sign,
            best: f64::from_bits(shared.load(Ordering::Relaxed)),
            shared,
            progress,
            slab: ((n as f64).sqrt().ceil() as usize).max(1),
            lo: vec![0; dims],
            hi: vec![0; dims],
            levels: vec![(Vec::new(), Vec::new()); dims + 1],
            lists: vec![Vec::new(); dims],
            table: Vec::new(),
            next: Vec::new(),
            packed: Vec::new(),
        }
    }

    /// Solve one slab of axis j of `self`'s on `own`, a worker of the same kind with scratch
    /// of its own (reused from slab to slab: fresh scratch for each of the second axis's
    /// thousands of slabs cost 3-5% on one thread), from `self`'s cut so far and the best
    /// known now; make its best known.
    fn visit_on(&self, own: &mut Dem<'a>, j: usize, slab: Slab, inside: &[u32], partial: &[u32]) -> f64 {
        if self.progress.check().is_err() {
            return own.best;
        }
        own.lo.copy_from_slice(&self.lo);
        own.hi.copy_from_slice(&self.hi);
        own.best = own.best.max(self.best).max(f64::from_bits(self.shared.load(Ordering::Relaxed)));
        own.visit(j, slab, inside, partial);
        self.shared.fetch_max(own.best.to_bits(), Ordering::Relaxed);
        own.best
    }

    /// A worker of the same kind, with empty scratch.
    fn worker(&self) -> Dem<'a> {
        Dem::new(self.axes, self.keys, self.sign, self.shared, self.progress)
    }

    fn key(&self, p: u32, axis: usize) -> u32 {
        self.keys[p as usize * self.dims + axis]
    }

    fn volume(&self, corner: &[u32]) -> f64 {
        corner.iter().zip(self.axes).map(|(&i, a)| a[i as usize]).product()
    }

    /// Sort points by their key on axis j.
    fn sort_by_axis(&mut self, points: &mut [u32], j: usize) {
        let mut packed = std::mem::take(&mut self.packed);
        packed.clear();
        packed.extend(points.iter().map(|&p| (u64::from(self.key(p, j)) << 32) | u64::from(p)));
        packed.sort_unstable();
        for (p, &v) in points.iter_mut().zip(&packed) {
            *p = v as u32;
        }
        self.packed = packed;
    }

    /// Sort the points of level j by axis j and cut the axis into slabs.
    fn slabs(&mut self, j: usize, inside: &mut [u32], partial: &mut [u32]) -> Vec<Slab> {
        self.sort_by_axis(inside, j);
        self.sort_by_axis(partial, j);
        let last = self.axes[j].len() as u32 - 1;
        let mut slabs = Vec::new();
        let (mut p, mut q, mut r, mut lo) = (0, 0, 0, 0);
        loop {
            while p < inside.len() && self.key(inside[p], j) <= lo {
                p += 1;
            }
            while q < partial.len() && self.key(partial[q], j) <= lo {
                q += 1;
            }
            // end before the next partial point's key and before the slab-th new one
            let mut hi = last;
            if let Some(&f) = partial.get(q) {
                hi = hi.min(self.key(f, j) - 1);
            }
            if let Some(&s) = inside.get(p + self.slab) {
                hi = hi.min(self.key(s, j) - 1);
            }
            r = r.max(p);
            while r < inside.len() && self.key(inside[r], j) <= hi {
                r += 1;
            }
            slabs.push(Slab { lo, hi, inside: p, kept: q, new: r });
            if hi == last {
                return slabs;
            }
            lo = hi + 1;
        }
    }

    /// Solve the cells of every slab of axis j (level j's points are taken and restored);
    /// the second axis's slabs in parallel, on workers with scratch of their own, so that the first
    /// axis's slabs, about sqrt(n) tasks of unequal work, are not the only ones to share.
    fn cut(&mut self, j: usize) {
        let (mut inside, mut partial) = std::mem::take(&mut self.levels[j]);
        let slabs = self.slabs(j, &mut inside, &mut partial);
        if j == 1 {
            let this = &*self;
            let best = slabs
                .into_par_iter()
                .map_init(|| this.worker(), |own, slab| this.visit_on(own, j, slab, &inside, &partial))
                .reduce(|| 0.0, f64::max);
            self.best = self.best.max(best);
        } else {
            for slab in slabs {
                self.visit(j, slab, &inside, &partial);
            }
        }
        self.levels[j] = (inside, partial);
    }

    /// Solve the cells of one slab of axis j, unless its bound cannot beat the best.
    fn visit(&mut self, j: usize, slab: Slab, inside: &[u32], partial: &[u32]) {
        (self.lo[j], self.hi[j]) = (slab.lo, slab.hi);
        let (kept, new) = (&partial[..slab.kept], &inside[slab.inside..slab.new]);
        if !self.promising(j, slab.inside, kept.len() + new.len()) {
            return;
        }
        if j + 1 == self.dims {
            self.cell(slab.inside, kept, new);
            return;
        }
        let (mut inside2, mut partial2) = std::mem::take(&mut self.levels[j + 1]);
        inside2.clear();
        inside2.extend_from_slice(&inside[..slab.inside]);
        partial2.clear();
        partial2.extend_from_slice(kept);
        partial2.extend_from_slice(new);
        self.levels[j + 1] = (inside2, partial2);
        self.cut(j + 1);
    }

    /// Whether a cell with axes 0..=j cut (the others spanning their whole range), with
    /// `inside` points below lo on the cut axes and `partial` others, may beat the best.
    fn promising(&self, j: usize, inside: usize, partial: usize) -> bool {
        let bound = if self.sign > 0.0 {
            // the largest volume, counting nobody
            (0..=j).map(|k| self.axes[k][self.hi[k] as usize]).product::<f64>()
        } else {
            let least: f64 =
                (0..self.dims).map(|k| self.axes[k][if k <= j { self.lo[k] as usize } else { 0 }]).product();
            (inside + partial) as f64 / self.n - least
        };
        bound > self.best
    }

    /// The coordinate on axis k of the corner that takes exactly t of the axis's (sorted)
    /// partial points: the largest such (open boxes: just below the next key) or the
    /// smallest (closed: at the t-th key).
    fn corner(&self, k: usize, t: usize) -> f64 {
        let list = &self.lists[k];
        let c = if self.sign > 0.0 {
            list.get(t).map_or(self.hi[k], |&a| a - 1)
        } else if t == 0 {
            self.lo[k]
        } else {
            list[t - 1]
        };
        self.axes[k][c as usize]
    }

    /// Whether a bound on a fully cut cell from one axis at a time cannot beat the best:
    /// the other axes at hi (open; none of their partial points) or at lo (closed; all of
    /// them), the best this axis alone reaches; the cell is pruned when any axis's is
    /// no better than the best.
    fn axis_prunes(&self, inside: usize, partial: usize) -> bool {
        let open = self.sign > 0.0;
        let at = |i: usize| self.axes[i][if open { self.hi[i] } else { self.lo[i] } as usize];
        (0..self.dims).any(|k| {
            let others: f64 = (0..self.dims).filter(|&i| i != k).map(at).product();
            let m = self.lists[k].len();
            let fixed = if open { inside } else { inside + partial - m };
            (0..=m).all(|t| self.sign * (others * self.corner(k, t) - (fixed + t) as f64 / self.n) <= self.best)
        })
    }

    /// The best corner of a fully cut cell: `inside` points count everywhere, `earlier`
    /// are partial on some axis before the last, `last` on the last axis (sorted by it).
    fn cell(&mut self, inside: usize, earlier: &[u32], last: &[u32]) {
        let d = self.dims;
        for list in &mut self.lists {
            list.clear();
        }
        for &p in earlier {
            let axis = (0..d).find(|&k| self.key(p, k) > self.lo[k]).expect("a partial point varies on one axis");
            let key = self.key(p, axis);
            self.lists[axis].push(key);
        }
        for list in &mut self.lists[..d - 1] {
            list.sort_unstable();
        }
        let keys = self.keys;
        self.lists[d - 1].extend(last.iter().map(|&p| keys[p as usize * d + d - 1]));
        let partial = earlier.len() + last.len();
        let count = |c: usize| (inside + c) as f64 / self.n;
        // the corners lo (inside points only) and hi (every partial point too) are exact
        let (v_lo, v_hi) = (self.volume(&self.lo), self.volume(&self.hi));
        self.best = self.best.max(self.sign * (v_lo - count(0))).max(self.sign * (v_hi - count(partial)));
        if partial == 0 || self.axis_prunes(inside, partial) {
            return;
        }
        // knapsack: table[t] = the best volume over the axes so far taking t partial points
        let open = self.sign > 0.0;
        self.table.clear();
        self.table.push(1.0);
        for k in 0..d {
            let m = self.lists[k].len();
            let mut next = std::mem::take(&mut self.next);
            next.clear();
            next.resize(self.table.len() + m, if open { 0.0 } else { f64::INFINITY });
            for t in 0..=m {
                let v = self.corner(k, t);
                let slots = next[t..t + self.table.len()].iter_mut().zip(&self.table);
                // plain comparisons (no NaN here) compile to one max / min instruction
                if open {
                    slots.for_each(|(slot, &prev)| *slot = if prev * v > *slot { prev * v } else { *slot });
                } else {
                    slots.for_each(|(slot, &prev)| *slot = if prev * v < *slot { prev * v } else { *slot });
                }
            }
            self.next = std::mem::replace(&mut self.table, next);
        }
        for (t, &v) in self.table.iter().enumerate() {
            self.best = self.best.max(self.sign * (v - count(t)));
        }
    }
}

/// The number of steps `star_dem` is bounded by, n^(1 + d/2): what `Limits` is compared with.
pub fn star_dem_work(n: usize, dims: usize) -> f64 {
    (n as f64).powf(1.0 + dims as f64 / 2.0)
}

/// Exact star discrepancy in d dimensions (d >= 2) by the decomposition of Dobkin,
/// Eppstein & Mitchell (1996, section 5): O(n^(d/2)) cells of O(d^2 n) knapsack work
/// each, O(n^(1 + d/2)) in all for fixed d, and far less where a cell's bound cannot beat
/// the best box found so far. The slabs of the first axis are solved in parallel; the
/// result does not depend on their order (every value compared is an exact local
/// discrepancy, computed the same way wherever it is met). The slabs of both kinds of boxes
/// (open, then closed) are handed out from one list, and each slab's slabs of the second
/// axis are tasks too: a schedule of their one-thread times bounds 16 threads at 15x for
/// d = 5, 400 points, where the first axis's slabs alone bounded it at 7.2x
/// (docs/performance.md, 2026-12-01).
///
/// # Errors
/// [`crate::Error::Interrupted`] once `progress` says stop (checked before each slab task).
///
/// # Panics
/// When a coordinate is NaN (every value must rank among the critical values; callers
/// check the unit cube first, as [`super::compute`] does).
pub fn star_dem(points: &[f64], dims: usize, progress: Progress) -> Result<f64> {
    let n = points.len() / dims;
    let axes: Vec<Vec<f64>> = (0..dims).map(|d| critical(points.iter().skip(d).step_by(dims).copied())).collect();
    let rank = |k: usize, x: f64| axes[k].binary_search_by(|c| c.total_cmp(&x)).expect("a critical value") as u32;
    // the best so far, shared between threads: non-negative floats order as their bits
    let best = AtomicU64::new(0.0f64.to_bits());
    // open boxes [0, q): a point counts when its rank is below the corner's (key rank + 1);
    // closed boxes [0, q]: when at or below it (key rank)
    let kinds: Vec<(Vec<u32>, f64)> = [(1u32, 1.0), (0, -1.0)]
        .into_iter()
        .map(|(shift, sign)| (points.iter().enumerate().map(|(i, &x)| rank(i % dims, x) + shift).collect(), sign))
        .collect();
    // each kind's slabs of the first axis, with every point inside none of them yet
    let roots: Vec<(Dem, Vec<u32>, Vec<Slab>)> = kinds
        .iter()
        .map(|(keys, sign)| {
            let mut dem = Dem::new(&axes, keys, *sign, &best, progress);
            let mut all: Vec<u32> = (0..n as u32).collect();
            let slabs = dem.slabs(0, &mut all, &mut []);
            (dem, all, slabs)
        })
        .collect();
    let tasks: Vec<(usize, Slab)> =
        roots.iter().enumerate().flat_map(|(k, (_, _, slabs))| slabs.iter().map(move |&s| (k, s))).collect();
    // handed out in order (the open boxes' first): the closed boxes' slabs start as the open
    // ones run out, with the best those found to prune by, and fill their tail
    tasks.into_iter().par_bridge().for_each(|(k, slab)| {
        let (dem, all, _) = &roots[k];
        dem.visit_on(&mut dem.worker(), 0, slab, all, &[]);
    });
    progress.check()?;
    Ok(f64::from_bits(best.into_inner()))
}

/// The metric this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry {
    // the 2D sweep's order and its two kinetic trees: 170 bytes a point measured
    bytes_per_point: 192,
    ..MetricEntry::new(
        About::new("star", "sup over boxes anchored at the origin (Shirley's D)")
            .aliases(&["d", "star-discrepancy"])
            .cite(&["shirley1991"]),
        star,
    )
}];

/// The exact star discrepancy: closed form in 1D, the sweep in 2D, Dobkin-Eppstein-Mitchell
/// beyond (refused over the work limit).
fn star(_: &Params, points: &PointSet, limits: Limits) -> Result<f64> {
    let (x, d) = (points.as_slice(), points.dims());
    Ok(match d {
        1 => star_1d(x),
        2 => star_2d(x, limits.progress)?,
        _ if d > DEM_DIMS => {
            return Err(Error::Dimension {
                what: "the exact star discrepancy".into(),
                takes: format!("1 to {DEM_DIMS} dimensions (its work, n^(1 + d/2), is beyond reach past them for any n > 1)"),
                got: d,
            });
        }
        _ => {
            limits.allow("the exact star discrepancy", points, star_dem_work(points.len(), d))?;
            star_dem(x, d, limits.progress)?
        }
    })
}

/// The most dimensions [`star_dem`] is run in: its recursion takes one frame (a few hundred
/// bytes) per axis, on a worker thread's stack of 2 MiB; 2^(1 + d/2) steps for two points
/// pass the default work limit (2e10) from d = 68.
const DEM_DIMS: usize = 1000;
