//! Extreme (unanchored) discrepancy: the supremum over all axis-parallel boxes of
//! |#points in box / N - volume| (Stroud's T in Shirley 1991 section 3.1). As for the
//! star discrepancy the supremum is reached by critical boxes, open or closed, whose
//! faces pass through points or the cube's faces; degenerate closed boxes (zero width,
//! points on them) count, as limits of half-open boxes.

use std::collections::BinaryHeap;
use std::collections::binary_heap::PeekMut;

use rayon::prelude::*;

use super::star::critical;
use super::{Limits, MetricEntry};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
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
/// boxes, a running maximum for closed ones). The left sides run in parallel. The
/// reference [`extreme_2d`] is tested against on sets too large for the brute force.
pub fn extreme_2d_sweep(points: &[f64]) -> f64 {
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
            |slab_ys: &mut Vec<f64>, &c| {
                let mut worst: f64 = 0.0;
                // open slabs (c, a): points with x > c; closed slabs [c, a]: points with x >= c
                let first_open = pts.partition_point(|p| p.0 <= c);
                let first_closed = pts.partition_point(|p| p.0 < c);
                // open boxes: the right side a runs over the x values above c, then 1
                slab_ys.clear();
                let mut i = first_open;
                loop {
                    let a = if i < n { pts[i].0 } else { 1.0 };
                    worst = worst.max(slab(slab_ys.iter().copied(), a - c, inv, true));
                    if i >= n {
                        break;
                    }
                    while i < n && pts[i].0 == a {
                        insert_sorted(slab_ys, pts[i].1);
                        i += 1;
                    }
                    if i >= n && a == 1.0 {
                        break;
                    }
                }
                // closed boxes: the right side a runs over the x values at or above c
                slab_ys.clear();
                let mut i = first_closed;
                while i < n {
                    let a = pts[i].0;
                    while i < n && pts[i].0 == a {
                        insert_sorted(slab_ys, pts[i].1);
                        i += 1;
                    }
                    worst = worst.max(slab(slab_ys.iter().copied(), a - c, inv, false));
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

/// The best box of a slab of width `w` whose points have the sorted y values `ys`:
/// open boxes, max over d < b of w (b - d) - #{d < y < b} / N with d, b among 0, the ys
/// and 1; closed boxes, max over d <= b of #{d <= y <= b} / N - w (b - d) with d, b among
/// the ys. One pass with a running minimum of the lower side's term (the maximum
/// subarray); 0 at least (the empty box).
fn slab(ys: impl Iterator<Item = f64>, w: f64, inv: f64, open: bool) -> f64 {
    let mut ys = ys.peekable();
    let mut best: f64 = 0.0;
    // open: the lower side d = 0 costs nothing; closed: no lower side yet
    let mut min_left = if open { 0.0 } else { f64::INFINITY };
    let mut count = 0usize;
    while let Some(b) = ys.next() {
        let below = count;
        count += 1;
        while ys.next_if_eq(&b).is_some() {
            count += 1;
        }
        if open {
            // value(d, b) = (w b - below(b) / N) - (w d - upto(d) / N)
            best = best.max(w * b - below as f64 * inv - min_left);
            min_left = min_left.min(w * b - count as f64 * inv);
        } else {
            // value(d, b) = (upto(b) / N - w b) - (below(d) / N - w d)
            min_left = min_left.min(below as f64 * inv - w * b);
            best = best.max(count as f64 * inv - w * b - min_left);
        }
    }
    if open {
        best = best.max(w - count as f64 * inv - min_left); // the upper side b = 1
    }
    best
}

/// Exact 2D extreme discrepancy by best-first branch and bound over the pairs (left
/// side c, right side a) of critical boxes. The bound of a block of pairs, c in [c0, c1]
/// and a in [a0, a1], is that of Thiemard's partitions for the star discrepancy (J.
/// Complexity 17, 2001: the outer box's count against the inner box's volume) applied to
/// slabs: the best closed box of the outer slab [c0, a1] at the least width a0 - c1, the
/// best open box of the inner slab (c1, a0) at the greatest width a1 - c0. It is tightened
/// by splitting a box's value into its three parts, [c, c1) + [c1, a0] + (a0, a] (open:
/// (c, c1] + (c1, a0) + [a0, a)), each at most the best box of its own slab: the inner
/// slab's at its exact width, plus the best boxes of the two strips, precomputed once per
/// node of the two halving trees of sides (O(k^2) for a node of k sides, up to 2048).
/// A block of one pair is bounded by its exact value (all three slabs are the pair's), so
/// the search refines the blocks of largest bound (one worker per thread takes the next
/// from a shared heap and puts back its children), until no bound exceeds the best exact
/// value found: the result is the maximum over every pair whatever the order or the
/// thread count. A bound is one pass
/// over a slab's points in y order (read from a bitmap of y ranks), O(n).
///
/// How many blocks are refined depends on the set; the worst case is every pair, O(n^3)
/// as [`extreme_2d_sweep`]. Measured on two cores at n = 10^4 (2026-11-25): random 0.49
/// s, jittered 1.0 s, Owen-scrambled Sobol' 5.2 s, Halton 1.6 s; at n = 4096 the
/// Hammersley set, a (0, 12, 2)-net whose boxes come within a point of the maximum
/// almost everywhere, takes 22 s (4% of the pairs evaluated exactly, two O(n) slab passes
/// each; at n = 2048, 70% of the bounds computed were of larger blocks, two to four passes
/// each). Each worker checks `progress` before each block it takes.
///
/// # Errors
/// [`Error::Interrupted`] once `progress` says stop.
pub fn extreme_2d(points: &[f64], progress: Progress) -> Result<f64> {
    use std::sync::atomic::{AtomicU64, Ordering};
    let sides = Sides::new(points);
    let root = sides.bound(Block { i: 1, j: 1, ub: 0.0 }, &mut vec![0; sides.words]);
    // the blocks to refine, and how many workers hold one they are refining
    let shared = std::sync::Mutex::new((BinaryHeap::from([root]), 0usize));
    // the best exact value found (a non-negative double's bits order as the double)
    let best = AtomicU64::new(0.0f64.to_bits());
    // blocks whose bound, computed in floating point, is within this of the best may
    // still hold a pair worth it: refined rather than dropped
    const SLACK: f64 = 1e-13;
    let worth = |b: &Block| b.ub >= f64::from_bits(best.load(Ordering::Relaxed)) - SLACK;
    let lock = || shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    // each worker takes the block of largest bound, bounds its children and puts back
    // those that may beat the best: no step waits for the slowest of a batch, so every
    // thread stays busy to the end; the result is the largest pair whatever the order
    let worker = || {
        let mut bits = vec![0u64; sides.words];
        loop {
            if progress.check().is_err() {
                return;
            }
            let taken = {
                let mut guard = lock();
                let (heap, busy) = &mut *guard;
                match heap.peek_mut() {
                    Some(top) if worth(&top) => {
                        *busy += 1;
                        Some(PeekMut::pop(top))
                    }
                    // nothing worth refining, and nobody who could put more back: done
                    _ if *busy == 0 => return,
                    _ => None,
                }
            };
            let Some(block) = taken else {
                std::thread::yield_now();
                continue;
            };
            let mut keep = Vec::with_capacity(4);
            for child in sides.split(&block) {
                let b = sides.bound(child, &mut bits);
                if sides.lefts.len(b.i) == 1 && sides.rights.len(b.j) == 1 {
                    best.fetch_max(b.ub.max(0.0).to_bits(), Ordering::Relaxed); // one pair: its exact value
                } else if worth(&b) {
                    keep.push(b);
                }
            }
            let mut guard = lock();
            guard.0.extend(keep);
            guard.1 -= 1;
        }
    };
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads() {
            scope.spawn(|_| worker());
        }
    });
    progress.check()?;
    Ok(f64::from_bits(best.into_inner()))
}

/// Strips up to this many sides get their own best boxes precomputed (O(k^2) each).
const STRIPS: usize = 2048;

/// A block of pairs: the left sides of node `i` of the left tree, the right sides of
/// node `j` of the right tree; with an upper bound of its boxes.
#[derive(Clone, Copy)]
struct Block {
    i: u32,
    j: u32,
    ub: f64,
}

impl PartialEq for Block {
    fn eq(&self, other: &Self) -> bool {
        self.ub.total_cmp(&other.ub).is_eq()
    }
}
impl Eq for Block {}
impl PartialOrd for Block {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Block {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.ub.total_cmp(&other.ub)
    }
}

/// Ranges of sides halved down to single sides, as a segment tree (node 1 is every
/// side, node k's halves are 2k and 2k + 1), with the best closed and open box of each
/// node's strip (see [`Sides::bound`]).
struct Tree {
    lo: Vec<u32>,
    hi: Vec<u32>,
    closed: Vec<f64>,
    open: Vec<f64>,
}

impl Tree {
    fn new(sides: usize) -> Self {
        let mut t = Tree { lo: vec![0; 4 * sides], hi: vec![0; 4 * sides], closed: vec![], open: vec![] };
        let mut stack = vec![(1usize, 0u32, sides as u32)];
        while let Some((k, lo, hi)) = stack.pop() {
            (t.lo[k], t.hi[k]) = (lo, hi);
            if hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                stack.extend([(2 * k, lo, mid), (2 * k + 1, mid, hi)]);
            }
        }
        t
    }

    fn len(&self, k: u32) -> usize {
        (self.hi[k as usize] - self.lo[k as usize]) as usize
    }

    /// The node itself when it is one side, else its halves.
    fn halves(&self, k: u32) -> impl Iterator<Item = u32> {
        let one = self.len(k) == 1;
        if one { k..k + 1 } else { 2 * k..2 * k + 2 }
    }

    /// The strips' best boxes, closed and open, by `strip(lo, hi, open)` for the nodes of up
    /// to STRIPS sides (infinite, so never used, above).
    fn strips(&self, strip: impl Fn(usize, usize, bool) -> f64 + Sync) -> (Vec<f64>, Vec<f64>) {
        // one task per node, the largest first: the few large nodes, O(k^2) each, sit
        // together at the top of the tree and would fall to one thread in index order
        let mut nodes: Vec<usize> = (0..self.lo.len()).filter(|&k| (1..=STRIPS).contains(&self.len(k as u32))).collect();
        nodes.sort_by_key(|&k| std::cmp::Reverse(self.len(k as u32)));
        let best: Vec<(f64, f64)> = nodes
            .par_iter()
            .with_max_len(1)
            .map(|&k| {
                let (a, b) = (self.lo[k] as usize, self.hi[k] as usize);
                (strip(a, b, false), strip(a, b, true))
            })
            .collect();
        let (mut closed, mut open) = (vec![f64::INFINITY; self.lo.len()], vec![f64::INFINITY; self.lo.len()]);
        for (&k, (c, o)) in nodes.iter().zip(best) {
            (closed[k], open[k]) = (c, o);
        }
        (closed, open)
    }
}

/// The critical sides of a 2D set and the slabs between them.
struct Sides {
    inv: f64,
    /// left sides: 0 and the distinct x values; right sides: the distinct x values and 1
    left: Vec<f64>,
    right: Vec<f64>,
    /// per left side, the first point (in x order) with x >= c (closed) and x > c (open)
    from_closed: Vec<u32>,
    from_open: Vec<u32>,
    /// per right side, the end of the points (in x order) with x <= a (closed), x < a (open)
    to_closed: Vec<u32>,
    to_open: Vec<u32>,
    /// per point in x order, its rank in y order; the y values in y order
    yrank: Vec<u32>,
    ys: Vec<f64>,
    words: usize,
    lefts: Tree,
    rights: Tree,
}

impl Sides {
    fn new(points: &[f64]) -> Self {
        let n = points.len() / 2;
        let mut by_x: Vec<usize> = (0..n).collect();
        by_x.sort_by(|&a, &b| points[2 * a].total_cmp(&points[2 * b]));
        let mut by_y: Vec<usize> = (0..n).collect();
        by_y.sort_by(|&a, &b| points[2 * a + 1].total_cmp(&points[2 * b + 1]));
        let mut rank = vec![0u32; n];
        for (r, &p) in by_y.iter().enumerate() {
            rank[p] = r as u32;
        }
        let xs: Vec<f64> = by_x.iter().map(|&p| points[2 * p]).collect();
        let mut left = vec![0.0];
        left.extend(&xs);
        left.dedup();
        let mut right = xs.clone();
        right.push(1.0);
        right.dedup();
        let at = |pred: &dyn Fn(f64) -> bool| xs.partition_point(|&x| pred(x)) as u32;
        let mut sides = Sides {
            inv: 1.0 / n as f64,
            from_closed: left.iter().map(|&c| at(&|x| x < c)).collect(),
            from_open: left.iter().map(|&c| at(&|x| x <= c)).collect(),
            to_closed: right.iter().map(|&a| at(&|x| x <= a)).collect(),
            to_open: right.iter().map(|&a| at(&|x| x < a)).collect(),
            lefts: Tree::new(left.len()),
            rights: Tree::new(right.len()),
            left,
            right,
            yrank: by_x.iter().map(|&p| rank[p]).collect(),
            ys: by_y.iter().map(|&p| points[2 * p + 1]).collect(),
            words: n.div_ceil(64),
        };
        let s = &sides;
        let (lefts, rights) = rayon::join(
            // the strip left of c1 = the node's last left side: [c, c1) closed, (c, c1] open
            || {
                s.lefts.strips(|i0, i1, open| {
                    let (c1, from) = (s.left[i1 - 1], if open { &s.from_open } else { &s.from_closed });
                    s.strip_best((i0..i1 - 1).rev().map(|i| (from[i]..from[i + 1], c1 - s.left[i])), open)
                })
            },
            // the strip right of a0 = the node's first right side: (a0, a] closed, [a0, a) open
            || {
                s.rights.strips(|j0, j1, open| {
                    let (a0, to) = (s.right[j0], if open { &s.to_open } else { &s.to_closed });
                    s.strip_best((j0 + 1..j1).map(|j| (to[j - 1]..to[j], s.right[j] - a0)), open)
                })
            },
        );
        ((sides.lefts.closed, sides.lefts.open), (sides.rights.closed, sides.rights.open)) = (lefts, rights);
        sides
    }

    /// The children of a block that hold a pair with the right side at or above the left.
    fn split<'a>(&'a self, b: &Block) -> impl Iterator<Item = Block> + 'a {
        let js: Vec<u32> = self.rights.halves(b.j).collect();
        self.lefts
            .halves(b.i)
            .flat_map(move |i| js.clone().into_iter().map(move |j| Block { i, j, ub: 0.0 }))
            .filter(|c| self.right[self.rights.hi[c.j as usize] as usize - 1] >= self.left[self.lefts.lo[c.i as usize] as usize])
    }

    /// The block with its upper bound (its exact value when it is one pair).
    fn bound(&self, mut b: Block, bits: &mut [u64]) -> Block {
        let (bi, bj) = (b.i as usize, b.j as usize);
        let (i0, i1, j0, j1) =
            (self.lefts.lo[bi] as usize, self.lefts.hi[bi] as usize, self.rights.lo[bj] as usize, self.rights.hi[bj] as usize);
        let (c1, a0) = (self.left[i1 - 1], self.right[j0]);
        // one pair: the outer slab is the inner one, its best box the pair's exact value
        let pair = i1 - i0 == 1 && j1 - j0 == 1;
        let w_min = (a0 - c1).max(0.0);
        let mut closed = self.slab_best(self.from_closed[i0], self.to_closed[j1 - 1], w_min, false, bits);
        let strips = self.lefts.closed[bi] + self.rights.closed[bj];
        if !pair && a0 >= c1 && strips < closed {
            // [c, a] = [c, c1) + [c1, a0] + (a0, a] and a - c = (c1 - c) + (a0 - c1) + (a - a0):
            // a box's value is the sum of its three parts', each at most its slab's best
            let inner = self.slab_best(self.from_closed[i1 - 1], self.to_closed[j0], a0 - c1, false, bits);
            closed = closed.min(inner + strips);
        }
        let w_max = self.right[j1 - 1] - self.left[i0];
        let mut open =
            if w_max > 0.0 { self.slab_best(self.from_open[i1 - 1], self.to_open[j0], w_max, true, bits) } else { 0.0 };
        let strips = self.lefts.open[bi] + self.rights.open[bj];
        if !pair && a0 > c1 && strips < open {
            // (c, a) = (c, c1] + (c1, a0) + [a0, a), likewise
            let inner = self.slab_best(self.from_open[i1 - 1], self.to_open[j0], a0 - c1, true, bits);
            open = open.min(inner + strips);
        }
        b.ub = closed.max(open);
        b
    }

    /// The best box of a strip grown step by step: each step adds the points of a range
    /// (in x order) and takes the best box at its width.
    fn strip_best(&self, steps: impl Iterator<Item = (std::ops::Range<u32>, f64)>, open: bool) -> f64 {
        let mut ys: Vec<f64> = Vec::new();
        let mut best: f64 = 0.0;
        for (range, w) in steps {
            for p in range {
                insert_sorted(&mut ys, self.ys[self.yrank[p as usize] as usize]);
            }
            best = best.max(slab(ys.iter().copied(), w, self.inv, open));
        }
        best
    }

    /// The best box of the points from..to (in x order) at width `w`.
    fn slab_best(&self, from: u32, to: u32, w: f64, open: bool, bits: &mut [u64]) -> f64 {
        for &r in self.yrank.get(from as usize..to as usize).unwrap_or(&[]) {
            bits[r as usize / 64] |= 1 << (r % 64);
        }
        let ys = &self.ys;
        let iter = bits.iter_mut().enumerate().flat_map(|(k, word)| {
            let mut v = std::mem::take(word);
            std::iter::from_fn(move || {
                (v != 0).then(|| {
                    let bit = v.trailing_zeros() as usize;
                    v &= v - 1;
                    ys[64 * k + bit]
                })
            })
        });
        slab(iter, w, self.inv, open)
    }
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
            // a nominal n^2 log2 n: the branch and bound's work depends on the set (at worst n^3)
            let n = points.len() as f64;
            limits.allow("the exact extreme discrepancy", points, n * n * n.log2().max(1.0))?;
            extreme_2d(x, limits.progress)
        }
        d => Err(Error::Dimension { what: "the exact extreme discrepancy".into(), takes: "1D and 2D points".into(), got: d }),
    }
}
