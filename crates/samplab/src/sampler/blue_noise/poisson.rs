//! Poisson-disk sampling: every pair of points at least `radius` apart.
//!
//! - [`DartThrowing`] (Cook 1986; Shirley 1991 section 2): uniform candidates, accepted
//!   when no earlier point lies within the radius; exactly n points; a bounded number of
//!   consecutive misses per try, a few tries, then a clear error. 1D to 4D.
//! - [`Bridson`] (Bridson 2007): grows the set from accepted points, trying k candidates
//!   in the annulus [r, 2r] around an active point; radii are drawn as r*sqrt(3u + 1),
//!   uniform in the annulus's area (not r*(1+u), a bias many implementations carry). It
//!   fills the whole domain in O(n); when that gives more than n points a uniformly random
//!   n of them are kept (the minimum distance still holds). 2D.
//! - [`Maximal`]: Bridson, then gap filling on a quadtree of uncovered cells (in the manner
//!   of Ebeida et al. 2012) until no disk of radius r fits anywhere (to cells of side
//!   r*2^-24), with the radius bisected, for a fixed seed, until the maximal set has
//!   exactly n points. The relative radius of such sets is about 0.77 of the hexagonal
//!   packing radius (random sequential adsorption limit). 2D.
//!
//! Distances are toroidal by default (`edge=torus`); `edge=plain` measures them inside the
//! square, as Shirley 1991 did.

use std::ops::RangeInclusive;
use std::sync::atomic::{AtomicU32, Ordering::Relaxed};

use rand_core::Rng as _;

use super::select_in_order;
use crate::construct::counts::ANY;
use crate::sampler::registry::{EDGE, SamplerEntry};
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::memory::{FAULT_CHUNK, FAULT_IN, filled, refill};
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Rng, Seed, below, shuffle, uniform, wrap01};
use crate::spec::{Default, Kind, ParamSpec};
use rayon::prelude::*;

/// d_max: the largest possible minimum distance of n points in the unit torus, the
/// diameter of the densest known packing's balls ([`crate::spatial::packing_radius`]).
fn packing_distance(n: usize, dims: usize) -> Result<f64> {
    Ok(2.0 * crate::spatial::packing_radius(n, dims)?)
}

/// Relative radius used when none is given: 0.7 of the packing radius for dart throwing,
/// 0.72 for Bridson (which saturates near 0.75 with k = 30).
const AUTO_RELATIVE: f64 = 0.7;

/// A uniform grid over [0,1)^d with cells of side >= r: every neighbour within r of a
/// point lies in the 3^d cells around it.
/// The most dimensions the grid supports.
const MAX_DIMS: usize = 4;

struct NeighbourGrid {
    dims: usize,
    cells: usize,
    torus: bool,
    radius2: f64,
    heads: Vec<u32>, // first point of each cell, u32::MAX when empty
    next: Vec<u32>,  // next point in the same cell
    points: Vec<f64>,
}

impl NeighbourGrid {
    fn new(dims: usize, radius: f64, torus: bool, capacity: usize) -> Self {
        let max_cells = ((1usize << 22) as f64).powf(1.0 / dims as f64) as usize;
        let cells = ((1.0 / radius).floor() as usize).clamp(1, max_cells.max(1));
        NeighbourGrid {
            dims,
            cells,
            torus,
            radius2: radius * radius,
            heads: filled(cells.pow(dims as u32), u32::MAX),
            next: Vec::with_capacity(capacity),
            points: reserved(capacity * dims),
        }
    }

    fn clear(&mut self) {
        if !self.next.is_empty() {
            refill(&mut self.heads, u32::MAX);
        }
        self.next.clear();
        self.points.clear();
    }

    fn cell_of(&self, p: &[f64]) -> [usize; MAX_DIMS] {
        let mut c = [0; MAX_DIMS];
        for (ci, &x) in c.iter_mut().zip(p) {
            *ci = ((x * self.cells as f64) as usize).min(self.cells - 1);
        }
        c
    }

    fn flat(&self, c: &[usize]) -> usize {
        c[..self.dims].iter().fold(0, |acc, &i| acc * self.cells + i)
    }

    fn insert(&mut self, p: &[f64]) {
        let cell = self.flat(&self.cell_of(p));
        self.next.push(self.heads[cell]);
        self.heads[cell] = (self.next.len() - 1) as u32;
        self.points.extend_from_slice(p);
    }

    #[inline]
    fn axis_distance(&self, x: f64, y: f64) -> f64 {
        let d = (x - y).abs();
        if self.torus && d > 0.5 { 1.0 - d } else { d }
    }

    fn distance2(&self, a: &[f64], b: &[f64]) -> f64 {
        a.iter().zip(b).map(|(&x, &y)| self.axis_distance(x, y).powi(2)).sum()
    }

    /// Whether a point of the set lies closer than the radius to `p`.
    fn conflict(&self, p: &[f64]) -> bool {
        let span = if self.cells < 3 { self.cells } else { 3 };
        let centre = self.cell_of(p);
        let mut offset = [0usize; MAX_DIMS];
        let mut cell = [0usize; MAX_DIMS];
        'cells: loop {
            let mut inside = true;
            for d in 0..self.dims {
                let c = if span < 3 { offset[d] } else { centre[d] + self.cells + offset[d] - 1 };
                if !self.torus && span == 3 && (c < self.cells || c >= 2 * self.cells) {
                    inside = false;
                }
                cell[d] = c % self.cells;
            }
            if inside && self.cell_conflict(self.flat(&cell), p) {
                return true;
            }
            for o in offset[..self.dims].iter_mut() {
                *o += 1;
                if *o < span {
                    continue 'cells;
                }
                *o = 0;
            }
            return false;
        }
    }

    #[inline]
    fn cell_conflict(&self, cell: usize, p: &[f64]) -> bool {
        let mut i = self.heads[cell];
        while i != u32::MAX {
            let q = &self.points[i as usize * self.dims..(i as usize + 1) * self.dims];
            if self.distance2(p, q) < self.radius2 {
                return true;
            }
            i = self.next[i as usize];
        }
        false
    }
}

/// The occupancy structure the constructions share.
trait Occupancy {
    fn len(&self) -> usize;
    fn insert(&mut self, p: &[f64]);
    fn conflict(&self, p: &[f64]) -> bool;
    fn points(&self) -> &[f64];
    fn clear(&mut self);
    /// Whether `conflict(p)` would find `q` once `q` is inserted: `q` in a cell that
    /// `conflict` reads for `p`, and within the radius by its arithmetic, bit for bit.
    fn near(&self, p: &[f64], q: &[f64]) -> bool;
    /// The radius: `near(p, q)` only where q lies within it of p along every axis (across
    /// the seam on a torus).
    fn radius(&self) -> f64;
    /// Start loading the memory `conflict(p)` will read (a hint; no effect on results).
    fn prefetch(&self, _p: &[f64]) {}
}

impl Occupancy for NeighbourGrid {
    fn len(&self) -> usize {
        self.next.len()
    }
    fn insert(&mut self, p: &[f64]) {
        NeighbourGrid::insert(self, p);
    }
    fn conflict(&self, p: &[f64]) -> bool {
        NeighbourGrid::conflict(self, p)
    }
    fn points(&self) -> &[f64] {
        &self.points
    }
    fn clear(&mut self) {
        NeighbourGrid::clear(self);
    }
    fn radius(&self) -> f64 {
        self.radius2.sqrt()
    }
    fn near(&self, p: &[f64], q: &[f64]) -> bool {
        // the cells `conflict` reads: all of them under 3 a side, else the 3^d around p's,
        // wrapped on the torus
        let (a, b) = (self.cell_of(p), self.cell_of(q));
        let read = self.cells < 3
            || (0..self.dims).all(|d| {
                let step = (b[d] + self.cells - a[d]) % self.cells;
                if self.torus { step <= 1 || step == self.cells - 1 } else { a[d].abs_diff(b[d]) <= 1 }
            });
        read && self.distance2(p, q) < self.radius2
    }
}

/// The 2D grid of Bridson 2007: cells of side at most r/sqrt(2), so a cell holds at most
/// one point, stored inline (NaN when empty); a query reads the 5 x 5 cells around it,
/// nearest first, so most rejected candidates stop at the first cell.
struct DiskGrid {
    g: usize,
    gf: f64,
    torus: bool,
    radius2: f64,
    slots: Vec<[f64; 2]>,
    points: Vec<f64>,
}

/// Cell offsets of the 5 x 5 neighbourhood, by distance from the centre cell.
const NEAREST_FIRST: [(i8, i8); 25] = [
    (0, 0),
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (-1, 1),
    (1, -1),
    (-1, -1),
    (2, 0),
    (-2, 0),
    (0, 2),
    (0, -2),
    (2, 1),
    (2, -1),
    (-2, 1),
    (-2, -1),
    (1, 2),
    (-1, 2),
    (1, -2),
    (-1, -2),
    (2, 2),
    (-2, 2),
    (2, -2),
    (-2, -2),
];

/// The most cells a one-point-per-cell grid may have (2^28: 4 GiB of slots).
const MAX_GRID_CELLS: f64 = (1u64 << 28) as f64;

impl DiskGrid {
    /// The cells of the grid for `radius`, as a float (it may exceed any usize).
    fn cells(radius: f64) -> f64 {
        (2f64.sqrt() / radius).ceil().powi(2)
    }

    fn new(radius: f64, torus: bool, capacity: usize) -> Self {
        let g = ((2f64.sqrt() / radius).ceil() as usize).max(1);
        DiskGrid {
            g,
            gf: g as f64,
            torus,
            radius2: radius * radius,
            // one more slot, always empty, stands for the cells off a plain square
            slots: filled(g * g + 1, [f64::NAN; 2]),
            points: reserved(2 * capacity),
        }
    }

    #[inline]
    fn cell(&self, x: f64) -> usize {
        ((x * self.gf) as usize).min(self.g - 1)
    }

    #[inline]
    fn axis(&self, a: f64, b: f64) -> f64 {
        let d = (a - b).abs();
        if self.torus { d.min(1.0 - d) } else { d }
    }

    /// Indices of the cells c-2..=c+2 along one axis, wrapped on the torus; usize::MAX
    /// off a plain square.
    #[inline]
    fn around(&self, c: usize) -> [usize; 5] {
        let g = self.g;
        std::array::from_fn(|k| {
            let i = c + g + k - 2; // in [g-2, 2g+1]
            if i < g {
                if self.torus { i } else { usize::MAX }
            } else if i < 2 * g {
                i - g
            } else if self.torus {
                i - 2 * g
            } else {
                usize::MAX
            }
        })
    }

    /// For the cells c-2..=c+2 of [`DiskGrid::around`]: the period to add to a neighbour's
    /// coordinate when the torus wraps it (-1 below the seam, +1 above, 0 otherwise).
    #[inline]
    fn seam_shifts(&self, c: usize) -> [f64; 5] {
        std::array::from_fn(|k| {
            let i = c as i64 + k as i64 - 2;
            if !self.torus || (0..self.g as i64).contains(&i) {
                0.0
            } else if i < 0 {
                -1.0
            } else {
                1.0
            }
        })
    }

    /// The slot of the cell in row r, column c (from [`DiskGrid::around`]); the
    /// always-empty sentinel slot when either is off the square.
    #[inline]
    fn slot(&self, r: usize, c: usize) -> usize {
        if r == usize::MAX || c == usize::MAX { self.g * self.g } else { r * self.g + c }
    }

    /// The cells of the 5 x 5 neighbourhood of `p`'s cell, nearest first.
    #[inline]
    fn neighbourhood(&self, x: f64, y: f64) -> impl Iterator<Item = usize> + '_ {
        let (rows, cols) = (self.around(self.cell(x)), self.around(self.cell(y)));
        NEAREST_FIRST.iter().filter_map(move |&(dx, dy)| {
            let (r, c) = (rows[(dx + 2) as usize], cols[(dy + 2) as usize]);
            (r != usize::MAX && c != usize::MAX).then(|| r * self.g + c)
        })
    }

    /// Whether the square [x0,x0+s) x [y0,y0+s) lies inside one disk of radius r.
    fn covers_square(&self, x0: f64, y0: f64, s: f64) -> bool {
        // on the torus a corner past the seam is the one across it; on a plain square the
        // corners on its right and top edges stay there (wrapped to 0 they were never covered,
        // and the search for a maximal set subdivided the edge cells to its last level)
        let fold = |v: f64| if self.torus { wrap01(v) } else { v };
        let (xs, ys) = ([fold(x0), fold(x0 + s)], [fold(y0), fold(y0 + s)]);
        // every corner is inside when the farthest is: its axis distances are each axis's
        // larger one, and squares and sums round monotonically, so the farthest corner's
        // computed distance is the largest of the four computed ones
        let farthest = |v: [f64; 2], q: f64| self.axis(v[0], q).max(self.axis(v[1], q));
        self.neighbourhood(wrap01(x0 + s / 2.0), wrap01(y0 + s / 2.0)).any(|c| {
            let q = self.slots[c];
            !q[0].is_nan() && farthest(xs, q[0]).powi(2) + farthest(ys, q[1]).powi(2) < self.radius2
        })
    }
}

impl Occupancy for DiskGrid {
    fn len(&self) -> usize {
        self.points.len() / 2
    }
    fn insert(&mut self, p: &[f64]) {
        let c = self.cell(p[0]) * self.g + self.cell(p[1]);
        debug_assert!(self.slots[c][0].is_nan());
        self.slots[c] = [p[0], p[1]];
        self.points.extend_from_slice(p);
    }
    #[inline]
    fn conflict(&self, p: &[f64]) -> bool {
        self.conflict_at(p[0], p[1])
    }
    fn points(&self) -> &[f64] {
        &self.points
    }
    fn clear(&mut self) {
        if !self.points.is_empty() {
            refill(&mut self.slots, [f64::NAN; 2]);
        }
        self.points.clear();
    }
    fn radius(&self) -> f64 {
        self.radius2.sqrt()
    }
    fn near(&self, p: &[f64], q: &[f64]) -> bool {
        // each of the 25 cells `conflict_at` reads that is q's (more than one on a torus
        // of under 5 cells a side), with its shift
        let (x, y) = (p[0], p[1]);
        let (rows, cols) = (self.around(self.cell(x)), self.around(self.cell(y)));
        let (sx, sy) = (self.seam_shifts(self.cell(x)), self.seam_shifts(self.cell(y)));
        let (rq, cq) = (self.cell(q[0]), self.cell(q[1]));
        (0..5).any(|a| rows[a] == rq && (0..5).any(|b| cols[b] == cq && self.within(x, y, [q[0], q[1]], (sx[a], sy[b]))))
    }
    #[inline]
    fn prefetch(&self, p: &[f64]) {
        // the middle three rows of the 5 x 5 neighbourhood, each 80 bytes: its two ends (a
        // test reads the outer two only when the middle ones hold no conflict; loading them
        // for every candidate kept memory busier than waiting for them: 8% slower at 10^6)
        let (rows, c) = (self.around(self.cell(p[0])), self.cell(p[1]));
        let (lo, hi) = (c.saturating_sub(2), (c + 2).min(self.g - 1));
        for r in rows[1..4].iter().copied().filter(|&r| r != usize::MAX) {
            crate::simd::prefetch(&self.slots[r * self.g + lo]);
            crate::simd::prefetch(&self.slots[r * self.g + hi]);
        }
    }
}

impl DiskGrid {
    /// Whether q, moved by `shift` (a period across the torus's seam, or 0), lies closer
    /// than the radius to (x, y).
    #[inline]
    fn within(&self, x: f64, y: f64, q: [f64; 2], (sx, sy): (f64, f64)) -> bool {
        let (dx, dy) = (x - (q[0] + sx), y - (q[1] + sy));
        dx * dx + dy * dy < self.radius2
    }

    /// Whether a point of the set lies closer than the radius to (x, y).
    #[inline]
    fn conflict_at(&self, x: f64, y: f64) -> bool {
        let (cx, cy, g) = (self.cell(x), self.cell(y), self.g);
        let inside = 2..g.saturating_sub(2);
        if inside.contains(&cx) && inside.contains(&cy) {
            // away from the edges (most candidates): the 5 x 5 cells are 5 runs of 5 slots,
            // none across a seam, so no shift and no sentinel; the same arithmetic as
            // `within` with a zero shift. The middle three rows first, without branches
            let row = |a: usize| {
                let start = (cx + a - 2) * g + cy - 2;
                self.slots[start..start + 5].iter().fold(false, |hit, q| {
                    let (dx, dy) = (x - q[0], y - q[1]);
                    hit | (dx * dx + dy * dy < self.radius2)
                })
            };
            return (row(1) | row(2) | row(3)) || (row(0) | row(4));
        }
        let (rows, cols) = (self.around(cx), self.around(cy));
        // a neighbour reached across the torus's seam is moved by one period instead of
        // taking min(d, 1 - d) per cell; all 25 cells, without early exit: no
        // data-dependent branch to mispredict
        let (sx, sy) = (self.seam_shifts(cx), self.seam_shifts(cy));
        // NaN compares false: empty cells never conflict
        let near = |a: usize, b: usize| self.within(x, y, self.slots[self.slot(rows[a], cols[b])], (sx[a], sy[b]));
        // the inner 3 x 3 cells first (most rejected candidates conflict there), then the
        // outer ring; each group without data-dependent branches
        let mut hit = false;
        for a in 1..4 {
            for b in 1..4 {
                hit |= near(a, b);
            }
        }
        if hit {
            return true;
        }
        for a in 0..5 {
            for b in [0, 4] {
                hit |= near(a, b);
            }
        }
        for a in [0, 4] {
            for b in 1..4 {
                hit |= near(a, b);
            }
        }
        hit
    }
}

/// An empty vector with room for `capacity` numbers; from [`FAULT_IN`], its pages are
/// faulted in in parallel, so that the insertions, one after another, do not take the
/// faults.
fn reserved(capacity: usize) -> Vec<f64> {
    if capacity < FAULT_IN {
        return Vec::with_capacity(capacity);
    }
    let mut v = filled(capacity, 0.0);
    v.clear();
    v
}

/// `points` copied into `out` (in parallel from [`FAULT_IN`]: the output's first writes
/// fault its pages in).
fn copy_out(points: &[f64], out: &mut [f64]) {
    if out.len() < FAULT_IN {
        return out.copy_from_slice(points);
    }
    out.par_chunks_mut(FAULT_CHUNK).zip(points.par_chunks(FAULT_CHUNK)).for_each(|(o, p)| o.copy_from_slice(p));
}

/// Whether an `edge` parameter word means toroidal distance.
pub(crate) fn edge_is_torus(word: &str) -> bool {
    word == "torus"
}

/// Keep a uniformly random `n` of the points (partial Fisher–Yates), in random order.
fn keep_random(points: &[f64], dims: usize, n: usize, rng: &mut Rng, out: &mut [f64]) {
    let m = points.len() / dims;
    let mut idx: Vec<u32> = (0..m as u32).collect();
    for i in 0..n {
        let j = i + below(rng, (m - i) as u64) as usize;
        idx.swap(i, j);
        let k = idx[i] as usize;
        out[i * dims..(i + 1) * dims].copy_from_slice(&points[k * dims..(k + 1) * dims]);
    }
}

/// Dart throwing with a minimum distance (Shirley 1991's Poisson disk).
#[derive(Debug, Clone, PartialEq)]
pub struct DartThrowing {
    radius: Option<f64>,
    torus: bool,
    attempts: u64,
}

impl DartThrowing {
    /// `radius` None means 0.7 x [`packing_distance`]; `attempts` is the number of
    /// consecutive rejected candidates after which a try is abandoned (16 tries in all).
    pub(crate) fn new(radius: Option<f64>, torus: bool, attempts: u64) -> Self {
        DartThrowing { radius, torus, attempts }
    }
}

const TRIES: u64 = 16;

/// How far ahead of the candidate it tests dart throwing starts loading the grid cells
/// another candidate will read (on large grids a test would otherwise wait for about ten
/// cache misses).
const AHEAD: usize = 16;

/// How many candidates dart throwing on several threads draws and checks together (for n
/// from BATCH / 2), in [`TASKS`] tasks whatever the thread count.
const BATCH: usize = 1 << 16;

/// The tasks a batch is cut into.
const TASKS: usize = 32;

/// The buffers of a batch (its size: candidates drawn together, [`TASKS`] tasks of at least
/// [`AHEAD`]; the tests also run smaller ones than [`BATCH`]): its candidates, whether each passed the first check, the
/// indices of those that did, the coarse grid of [`DartThrowing::earlier_conflicts`]
/// (each cell's first passing candidate, each one's next in its cell; [`NONE`] ends a
/// list), and whether each passing candidate is kept.
struct Batch {
    size: usize,
    candidates: Vec<[f64; MAX_DIMS]>,
    clear: Vec<bool>,
    passing: Vec<usize>,
    heads: Vec<AtomicU32>,
    links: Vec<u32>,
    kept: Vec<bool>,
}

impl Batch {
    fn new(size: usize) -> Batch {
        assert!(size.is_multiple_of(TASKS) && size / TASKS >= AHEAD, "a batch of {size} candidates");
        Batch {
            size,
            candidates: vec![[0.0; MAX_DIMS]; size],
            clear: vec![false; size],
            passing: Vec::with_capacity(size),
            heads: Vec::new(),
            links: vec![NONE; size],
            kept: Vec::with_capacity(size),
        }
    }

    /// The candidates one task takes.
    fn chunk(&self) -> usize {
        self.size / TASKS
    }
}

/// The end of a list in [`Batch`]'s coarse grid.
const NONE: u32 = u32::MAX;

/// The most cells of [`Batch`]'s coarse grid (16 MiB of heads).
const MAX_COARSE_CELLS: usize = 1 << 22;

impl DartThrowing {
    /// Up to [`TRIES`] tries of dart throwing; the points land in `out` when one succeeds.
    /// Returns the largest count placed. Stops when `progress` says so (checked every
    /// 2^16 candidates or more often: a few milliseconds).
    ///
    /// A try is the serial definition: candidate k (draws k d .. k d + d - 1 of the try's
    /// random stream) is kept when no point kept before it lies within the radius, until
    /// n are kept or more than `attempts` candidates in a row are not. One thread runs it
    /// candidate after candidate; several run it in batches ([`DartThrowing::try_in_batches`]),
    /// with the same points.
    fn throw(
        &self,
        grid: &mut (impl Occupancy + Sync),
        (n, dims): (usize, usize),
        seed: Seed,
        out: &mut [f64],
        progress: &Progress,
    ) -> Result<usize> {
        // batches pay off from several batches a try (about 11 candidates a point at the
        // default radius); below, and on one thread, candidate after candidate
        let mut batch = (rayon::current_num_threads() > 1 && n >= BATCH / 2).then(|| Batch::new(BATCH));
        let mut best = 0;
        for t in 0..TRIES {
            let stream = seed.derive(t).rng();
            grid.clear();
            match &mut batch {
                Some(batch) => self.try_in_batches(grid, (n, dims), &stream, batch, progress)?,
                None => self.try_one_by_one(grid, (n, dims), stream, progress)?,
            }
            if grid.len() == n {
                copy_out(grid.points(), out);
                return Ok(n);
            }
            best = best.max(grid.len());
        }
        Ok(best)
    }

    /// One try, candidate after candidate. The candidates are drawn [`AHEAD`] before they
    /// are tested, in the same order, so that the cells each will read are on their way
    /// from memory; a try ends with up to AHEAD candidates drawn and unused, which changes
    /// nothing.
    fn try_one_by_one(
        &self,
        grid: &mut (impl Occupancy + ?Sized),
        (n, dims): (usize, usize),
        mut rng: Rng,
        progress: &Progress,
    ) -> Result<()> {
        let mut ahead = [[0.0; MAX_DIMS]; AHEAD];
        for c in &mut ahead {
            c[..dims].iter_mut().for_each(|x| *x = uniform(&mut rng));
            grid.prefetch(&c[..dims]);
        }
        let mut misses = 0;
        for k in 0usize.. {
            if grid.len() == n || misses > self.attempts {
                break;
            }
            if k % BATCH == 0 {
                progress.check()?;
            }
            let slot = &mut ahead[k % AHEAD];
            let cand = *slot;
            slot[..dims].iter_mut().for_each(|x| *x = uniform(&mut rng));
            grid.prefetch(&slot[..dims]);
            let cand = &cand[..dims];
            if grid.conflict(cand) {
                misses += 1;
            } else {
                grid.insert(cand);
                misses = 0;
            }
        }
        Ok(())
    }

    /// One try in batches of candidates ([`BATCH`] but in tests). Every candidate of a batch is drawn
    /// (from the stream advanced to it) and checked against the points kept before the
    /// batch, in parallel. A candidate that fails this first check fails against the grid
    /// as it is by its turn too (the points only grow); one that passes conflicts at its
    /// turn exactly when one of the batch's points kept before it is [`Occupancy::near`].
    /// So, also in parallel, each passing candidate lists the earlier passing ones near it
    /// ([`DartThrowing::earlier_conflicts`]); then, in order and with no geometry, a
    /// passing candidate is kept when none on its list was, counting the misses and
    /// stopping as [`DartThrowing::try_one_by_one`] does; the kept ones are inserted in
    /// order. The points are those of `try_one_by_one`; candidates drawn past the end of
    /// the try change nothing.
    ///
    /// The second check was a serial pass over the grid (one conflict test a passing
    /// candidate): 76 of 350 4 ms windows of a two-thread `generate poisson -n 1000000`
    /// had one thread busy, and 16 threads ran it 2.6x faster than one (2026-11-29).
    fn try_in_batches(
        &self,
        grid: &mut (impl Occupancy + Sync + ?Sized),
        (n, dims): (usize, usize),
        stream: &Rng,
        batch: &mut Batch,
        progress: &Progress,
    ) -> Result<()> {
        let (mut misses, mut first) = (0, 0u64);
        loop {
            progress.check()?;
            let shared = &*grid;
            let (size, chunk) = (batch.size, batch.chunk());
            let Batch { candidates, clear, passing, .. } = batch;
            candidates.par_chunks_mut(chunk).zip(clear.par_chunks_mut(chunk)).enumerate().for_each(
                |(c, (cands, clear))| {
                    let mut rng = stream.clone();
                    rng.advance(u128::from(first + (c * chunk) as u64) * dims as u128);
                    for cand in cands.iter_mut() {
                        cand[..dims].iter_mut().for_each(|x| *x = uniform(&mut rng));
                    }
                    cands[..AHEAD].iter().for_each(|c| shared.prefetch(&c[..dims]));
                    for (k, (cand, clear)) in cands.iter().zip(clear.iter_mut()).enumerate() {
                        if let Some(ahead) = cands.get(k + AHEAD) {
                            shared.prefetch(&ahead[..dims]);
                        }
                        *clear = !shared.conflict(&cand[..dims]);
                    }
                },
            );
            // in order, the candidates that passed; each one between them is a miss
            select_in_order(size, chunk, |k| clear[k].then_some(k), passing);
            let conflicts = self.earlier_conflicts(shared, dims, batch);
            let Batch { candidates, passing, kept, .. } = batch;
            kept.clear();
            kept.resize(passing.len(), false);
            let (mut count, mut next, mut listed, mut ended) = (grid.len(), 0, conflicts.iter().peekable(), false);
            for (j, &k) in passing.iter().enumerate() {
                misses += (k - next) as u64;
                if count == n || misses > self.attempts {
                    ended = true;
                    break;
                }
                let mut hit = false;
                while let Some(&(_, i)) = listed.next_if(|&&(later, _)| later as usize == j) {
                    hit |= kept[i as usize];
                }
                if hit {
                    misses += 1;
                } else {
                    kept[j] = true;
                    count += 1;
                    misses = 0;
                }
                next = k + 1;
            }
            for (&k, _) in passing.iter().zip(kept.iter()).filter(|&(_, &kept)| kept) {
                grid.insert(&candidates[k][..dims]);
            }
            if ended {
                return Ok(());
            }
            misses += (size - next) as u64;
            if grid.len() == n || misses > self.attempts {
                return Ok(());
            }
            first += size as u64;
        }
    }

    /// For each candidate of the batch that passed the first check (its place j in
    /// `passing`), the earlier ones (places i < j) [`Occupancy::near`] it: the pairs
    /// (j, i), in increasing j (in no set order for one j), in parallel. The passing
    /// candidates are listed by their cell in a coarse grid whose cells are wider than
    /// twice the radius, so the ones near a candidate lie in its own cell and, along each
    /// axis, the one beyond its cell's nearer edge (wrapped on the torus): 2^d cells. The
    /// lists are built with atomic swaps, so their order varies from run to run, but not
    /// what they hold.
    fn earlier_conflicts(&self, grid: &(impl Occupancy + Sync + ?Sized), dims: usize, batch: &mut Batch) -> Vec<(u32, u32)> {
        let chunk = batch.chunk();
        let Batch { candidates, passing, heads, links, .. } = batch;
        // cells a side, each wider than twice the radius by a margin no rounding can eat
        let most = (MAX_COARSE_CELLS as f64).powf(1.0 / dims as f64) as usize;
        let side = ((0.999 / (2.0 * grid.radius())).floor() as usize).clamp(1, most.max(1));
        if heads.len() != side.pow(dims as u32) {
            *heads = (0..side.pow(dims as u32)).into_par_iter().map(|_| AtomicU32::new(NONE)).collect();
        }
        let cell = |x: f64| ((x * side as f64) as usize).min(side - 1);
        let nearer_half = |x: f64| x * side as f64 - (cell(x) as f64) < 0.5;
        let home = |k: usize| candidates[k][..dims].iter().fold(0, |acc, &x| acc * side + cell(x));
        let heads = &*heads;
        links[..passing.len()].par_iter_mut().zip(&*passing).enumerate().for_each(|(j, (link, &k))| {
            *link = heads[home(k)].swap(j as u32, Relaxed);
        });
        // along one axis, x's cell and the one beyond its nearer edge: wrapped on the
        // torus, none past a plain square's edge, the only other one of 2 a side
        let around = |x: f64| -> ([usize; 2], usize) {
            let c = cell(x);
            let beyond = if nearer_half(x) { c.checked_sub(1) } else { Some(c + 1).filter(|&b| b < side) };
            match beyond {
                _ if side == 1 => ([c, c], 1),
                Some(b) => ([c, b], 2),
                None if self.torus => ([c, if c == 0 { side - 1 } else { 0 }], 2),
                None => ([c, c], 1),
            }
        };
        let (links, candidates) = (&*links, &*candidates);
        let lists: Vec<Vec<(u32, u32)>> = passing
            .par_chunks(chunk)
            .enumerate()
            .map(|(c, places)| {
                let mut pairs = Vec::new();
                for (j, &k) in (c * chunk..).zip(places) {
                    let p = &candidates[k][..dims];
                    // the cells to read, axis by axis: each one so far followed by each of
                    // the axis's cells
                    let (mut cells, mut len) = ([0; 1 << MAX_DIMS], 1);
                    for &x in p {
                        let (axis, count) = around(x);
                        for m in 0..len {
                            let base = cells[m] * side;
                            for (t, &c) in axis[..count].iter().enumerate() {
                                cells[t * len + m] = base + c;
                            }
                        }
                        len *= count;
                    }
                    for &near in &cells[..len] {
                        let mut i = heads[near].load(Relaxed);
                        while i != NONE {
                            if (i as usize) < j && grid.near(p, &candidates[passing[i as usize]][..dims]) {
                                pairs.push((j as u32, i));
                            }
                            i = links[i as usize];
                        }
                    }
                }
                pairs
            })
            .collect();
        passing.par_iter().for_each(|&k| heads[home(k)].store(NONE, Relaxed));
        lists.concat()
    }
}

impl Construction for DartThrowing {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let r = self.radius.unwrap_or(AUTO_RELATIVE * packing_distance(n, dims)?);
        // with plain edges the disks may poke out of the square by r/2
        let room = if self.torus { 1.0 } else { (1.0 + r).powi(dims as i32) };
        let most = (room * (packing_distance(1, dims)? / r).powi(dims as i32)).floor();
        if n as f64 > most {
            return Err(shape.infeasible(format!(
                    "radius {r} cannot fit {n} points in {dims}D: even the densest packing holds at most {most}; use a radius below {:.6}",
                    packing_distance(n, dims)? * room.powf(1.0 / dims as f64)
                )));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = self.clone();
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(1, move |seed, out, progress| {
            me.fill_reporting(&shape, seed, out, progress)
        }))
    }
}

impl DartThrowing {

    fn fill_reporting(&self, shape: &Shape, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let r = self.radius.unwrap_or(AUTO_RELATIVE * packing_distance(n, dims)?);
        // the one-point-per-cell grid has (sqrt 2 / r)^2 cells: for tiny radii the linked
        // grid (capped at 2^22 cells, several points each) stands in
        // on a pool thread: from outside the pool, each batch's parallel step would put the
        // calling thread to sleep and wake it again
        let best = rayon::scope(|_| {
            if dims == 2 && DiskGrid::cells(r) <= MAX_GRID_CELLS {
                self.throw(&mut DiskGrid::new(r, self.torus, n), (n, dims), seed, out, progress)
            } else {
                self.throw(&mut NeighbourGrid::new(dims, r, self.torus, n), (n, dims), seed, out, progress)
            }
        })?;
        if best == n {
            return progress.advance(1);
        }
        Err(shape.infeasible(format!(
                "radius {r} is too large for {n} points: dart throwing placed at most {best} ({TRIES} tries, {} consecutive misses each); use a smaller radius (the packing limit is {:.6}) or more attempts",
                self.attempts,
                packing_distance(n, dims)?
            )))
    }
}

/// An offset uniform in the area of the annulus r <= |d| < 2r: its radius has the CDF
/// (rho^2 - r^2) / (3 r^2), i.e. rho = r sqrt(3u + 1) (not r (1 + u), which crowds the
/// inner edge). Drawn by rejection from the bounding square (acceptance 3 pi / 16), which
/// has exactly that law and needs neither a square root nor trigonometry.
#[inline]
fn annulus_offset(rng: &mut Rng, r: f64) -> (f64, f64) {
    let (inner, outer) = (r * r, 4.0 * r * r);
    // both coordinates from one 64-bit draw: 32 bits each resolve r / 2^30, ample for a candidate
    let scale = 4.0 * r / 4_294_967_296.0;
    loop {
        let bits = rng.next_u64();
        let (a, b) = (scale * (bits >> 32) as f64 - 2.0 * r, scale * (bits & 0xFFFF_FFFF) as f64 - 2.0 * r);
        let q = a * a + b * b;
        if q >= inner && q < outer {
            return (a, b);
        }
    }
}

/// Grow a Bridson set with radius r over the unit square (or torus), stopping when
/// `progress` says so (checked every 1024 steps, under a millisecond of work).
fn bridson(r: f64, torus: bool, k: u32, rng: &mut Rng, grid: &mut DiskGrid, progress: &Progress) -> Result<()> {
    let mut active: Vec<u32> = Vec::new();
    let first = [uniform(rng), uniform(rng)];
    grid.insert(&first);
    active.push(0);
    let mut steps = 0u32;
    while !active.is_empty() {
        steps = steps.wrapping_add(1);
        if steps.is_multiple_of(1024) {
            progress.check()?;
        }
        let a = below(rng, active.len() as u64) as usize;
        let i = active[a] as usize;
        let (px, py) = (grid.points()[2 * i], grid.points()[2 * i + 1]);
        let mut placed = false;
        for _ in 0..k {
            let (dx, dy) = annulus_offset(rng, r);
            let (mut x, mut y) = (px + dx, py + dy);
            if torus {
                // |offset| < 2r < 1: one correction suffices (no floor call)
                x = if x < 0.0 {
                    x + 1.0
                } else if x >= 1.0 {
                    x - 1.0
                } else {
                    x
                };
                y = if y < 0.0 {
                    y + 1.0
                } else if y >= 1.0 {
                    y - 1.0
                } else {
                    y
                };
                if x >= 1.0 || y >= 1.0 {
                    continue; // -tiny + 1.0 rounded to 1.0
                }
            } else if !(0.0..1.0).contains(&x) || !(0.0..1.0).contains(&y) {
                continue;
            }
            if !grid.conflict_at(x, y) {
                grid.insert(&[x, y]);
                active.push((grid.len() - 1) as u32);
                placed = true;
                break;
            }
        }
        if !placed {
            active.swap_remove(a);
        }
    }
    Ok(())
}

/// Bridson's fast Poisson-disk sampling (2D), O(n).
#[derive(Debug, Clone, PartialEq)]
pub struct Bridson {
    radius: Option<f64>,
    torus: bool,
    k: u32,
}

impl Bridson {
    /// `radius` None means 0.72 x [`packing_distance`], shrunk when a fill falls short of
    /// n; `k` candidates per active point.
    pub(crate) fn new(radius: Option<f64>, torus: bool, k: u32) -> Self {
        Bridson { radius, torus, k }
    }
}

impl Construction for Bridson {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        // Bridson fills the whole square before keeping n: its grid must fit
        let r = self.radius.unwrap_or(0.72 * packing_distance(n, dims)?);
        if DiskGrid::cells(r) > MAX_GRID_CELLS {
            return Err(shape.infeasible(format!(
                    "radius {r} would fill the square with about {:.1e} points before keeping {n}; use a radius of at least {:.2e} (or dart throwing, `poisson`)",
                    (packing_distance(1, dims)? / r).powi(2),
                    2f64.sqrt() / MAX_GRID_CELLS.sqrt()
                )));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = self.clone();
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(&shape, seed, out)))
    }
}

impl Bridson {

    fn fill(&self, shape: &Shape, seed: Seed, out: &mut [f64]) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let mut r = self.radius.unwrap_or(0.72 * packing_distance(n, dims)?);
        let mut rng = seed.rng();
        let mut grid = DiskGrid::new(r, self.torus, n + n / 4);
        bridson(r, self.torus, self.k, &mut rng, &mut grid, &Progress::SILENT)?;
        // an automatic radius shrinks until the fill holds n points (small n fluctuate)
        while grid.len() < n && self.radius.is_none() {
            r *= 0.98 * (grid.len() as f64 / n as f64).sqrt();
            grid = DiskGrid::new(r, self.torus, n + n / 4);
            bridson(r, self.torus, self.k, &mut rng, &mut grid, &Progress::SILENT)?;
        }
        if grid.len() < n {
            return Err(shape.infeasible(format!(
                    "radius {r} fills the square with only {} points (Bridson, k = {}), fewer than {n}; use a smaller radius",
                    grid.len(),
                    self.k
                )));
        }
        keep_random(grid.points(), 2, n, &mut rng, out);
        Ok(())
    }
}

/// Maximal Poisson-disk sampling with exactly n points (2D).
#[derive(Debug, Clone, PartialEq)]
pub struct Maximal {
    torus: bool,
}

impl Maximal {
    /// A maximal sampler; the radius follows from n.
    pub fn new(torus: bool) -> Self {
        Maximal { torus }
    }
}

/// Bridson followed by gap filling: a maximal set for radius r, stopping when `progress`
/// says so (in Bridson's growth and between the gap filling's levels).
fn maximal_set(r: f64, torus: bool, seed: Seed, capacity: usize, progress: &Progress) -> Result<DiskGrid> {
    let mut rng = seed.rng();
    let mut grid = DiskGrid::new(r, torus, capacity);
    bridson(r, torus, 30, &mut rng, &mut grid, progress)?;
    // quadtree of cells that no single disk covers
    let base = (2f64.sqrt() / r).ceil() as usize;
    let mut side = 1.0 / base as f64;
    let mut cells: Vec<(f64, f64)> =
        (0..base * base).map(|c| ((c / base) as f64 * side, (c % base) as f64 * side)).collect();
    // the cells no disk of the grid covers (in parallel, in order)
    let uncovered = |cells: Vec<(f64, f64)>, grid: &DiskGrid, side: f64| -> Vec<(f64, f64)> {
        cells.into_par_iter().filter(|&(x, y)| !grid.covers_square(x, y, side)).collect()
    };
    for _depth in 0..24 {
        progress.check()?;
        cells = uncovered(cells, &grid, side);
        if cells.is_empty() {
            break;
        }
        // one dart per uncovered cell, in random order, kept when inside and clear of the
        // points before it: first checked against the points so far in parallel, then, in
        // order, the darts that passed against the darts kept before them
        shuffle(&mut rng, &mut cells);
        let darts: Vec<[f64; 2]> =
            cells.iter().map(|&(x, y)| [x + side * uniform(&mut rng), y + side * uniform(&mut rng)]).collect();
        let clear: Vec<bool> =
            darts.par_iter().map(|p| (torus || (p[0] < 1.0 && p[1] < 1.0)) && !grid.conflict(p)).collect();
        for (p, clear) in darts.iter().zip(clear) {
            if clear && !grid.conflict(p) {
                grid.insert(p);
            }
        }
        cells = uncovered(cells, &grid, side);
        side /= 2.0;
        cells = cells
            .into_par_iter()
            .flat_map_iter(|(x, y)| [(x, y), (x + side, y), (x, y + side), (x + side, y + side)])
            .filter(|&(x, y)| x < 1.0 && y < 1.0)
            .collect();
    }
    Ok(grid)
}

impl Construction for Maximal {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = self.clone();
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(1, move |seed, out, progress| {
            me.fill_reporting(&shape, seed, out, progress)
        }))
    }
}

impl Maximal {
    fn fill_reporting(&self, shape: &Shape, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let rmax = packing_distance(n, dims)?;
        for t in 0..8 {
            let s = seed.derive(t);
            let (mut lo, mut hi) = (0.5 * rmax, rmax);
            for _ in 0..64 {
                let r = 0.5 * (lo + hi);
                let grid = maximal_set(r, self.torus, s, n + n / 4, progress)?;
                match grid.len().cmp(&n) {
                    std::cmp::Ordering::Equal => {
                        copy_out(grid.points(), out);
                        return progress.advance(1);
                    }
                    std::cmp::Ordering::Greater => lo = r,
                    std::cmp::Ordering::Less => hi = r,
                }
                if hi - lo < 1e-14 * rmax {
                    break;
                }
            }
        }
        Err(shape.infeasible(format!("no radius gave a maximal set of exactly {n} points in 8 tries of 64 bisection steps")))
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("poisson", "dart throwing with a minimum distance")
            .aliases(&["poisson-disk", "dart-throwing"])
            .params(&[
                ParamSpec {
                    name: "radius",
                    kind: Kind::Real { min: 1e-9, max: 1.0 },
                    default: Default::Auto("0.7 x the packing radius of n points"),
                    doc: "minimum distance between points",
                },
                EDGE,
                ParamSpec {
                    name: "attempts",
                    kind: Kind::Int { min: 1, max: 1_000_000_000 },
                    default: Default::Int(100_000),
                    doc: "consecutive misses before a try is abandoned (16 tries)",
                },
            ])
            .cite(&["cook1986", "shirley1991"]),
        counts: ANY,
        randomized: true,
        dims: "1..=4",
        build: |p| {
            let torus = edge_is_torus(p.word("edge"));
            Ok(Box::new(DartThrowing::new(p.real_or_auto("radius"), torus, p.int("attempts"))))
        },
    },
    SamplerEntry {
        about: About::new("poisson.fast", "Bridson's O(n) Poisson disk: fill, then keep a random n")
            .aliases(&["bridson"])
            .params(&[
                ParamSpec {
                    name: "radius",
                    kind: Kind::Real { min: 1e-6, max: 1.0 },
                    default: Default::Auto("0.72 x the packing radius of n points"),
                    doc: "minimum distance between points",
                },
                EDGE,
                ParamSpec {
                    name: "k",
                    kind: Kind::Int { min: 1, max: 10_000 },
                    default: Default::Int(30),
                    doc: "candidates tried around each active point",
                },
            ])
            .cite(&["bridson2007"]),
        counts: ANY,
        randomized: true,
        dims: "2",
        build: |p| {
            let torus = edge_is_torus(p.word("edge"));
            Ok(Box::new(Bridson::new(p.real_or_auto("radius"), torus, p.int("k") as u32)))
        },
    },
    SamplerEntry {
        about: About::new(
            "poisson.maximal",
            "maximal Poisson disk: no room for another point; radius found for exactly n",
        )
        .aliases(&["maximal-poisson"])
        .params(&[EDGE])
        .cite(&["ebeida2012", "bridson2007"]),
        counts: ANY,
        randomized: true,
        dims: "2",
        build: |p| Ok(Box::new(Maximal::new(edge_is_torus(p.word("edge"))))),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_is_what_conflict_finds_with_one_point() {
        // pairs within about two radii (across the seams too), on grids of both kinds,
        // large radii included (under 5 cells a side, the torus's 5 x 5 cells wrap twice)
        let mut rng = Seed(9).rng();
        let (mut near, mut far) = (0, 0);
        for (dims, r) in [(2, 0.002), (2, 0.05), (2, 0.3), (2, 0.45), (1, 0.01), (3, 0.08), (4, 0.2), (3, 0.6)] {
            for torus in [true, false] {
                let mut grids: Vec<Box<dyn Occupancy>> = vec![Box::new(NeighbourGrid::new(dims, r, torus, 1))];
                if dims == 2 {
                    grids.push(Box::new(DiskGrid::new(r, torus, 1)));
                }
                for grid in &mut grids {
                    for _ in 0..4000 {
                        let p: Vec<f64> = (0..dims).map(|_| uniform(&mut rng)).collect();
                        let q: Vec<f64> = p.iter().map(|&x| wrap01(x + (uniform(&mut rng) - 0.5) * 4.0 * r)).collect();
                        grid.clear();
                        grid.insert(&q);
                        let found = grid.conflict(&p);
                        assert_eq!(grid.near(&p, &q), found, "{dims}D, r {r}, torus {torus}: p {p:?}, q {q:?}");
                        if found { near += 1 } else { far += 1 }
                    }
                }
            }
        }
        assert!(near > 10_000 && far > 10_000, "{near} near and {far} far pairs");
    }

    #[test]
    fn annulus_offsets_are_uniform_in_area() {
        // Kolmogorov-Smirnov against the radius CDF (rho^2 - r^2) / (3 r^2) and the
        // uniform angle; 1.63/sqrt(n) is the 1% critical value
        let (r, n) = (0.3, 100_000);
        let mut rng = Seed(4).rng();
        let (mut radii, mut angles): (Vec<f64>, Vec<f64>) =
            (0..n).map(|_| annulus_offset(&mut rng, r)).map(|(a, b)| (a.hypot(b), b.atan2(a))).unzip();
        radii.sort_by(f64::total_cmp);
        angles.sort_by(f64::total_cmp);
        let ks = |v: &[f64], cdf: &dyn Fn(f64) -> f64| {
            v.iter()
                .enumerate()
                .map(|(i, &x)| (cdf(x) - i as f64 / n as f64).abs().max((cdf(x) - (i + 1) as f64 / n as f64).abs()))
                .fold(0.0, f64::max)
        };
        let crit = 1.63 / (n as f64).sqrt();
        assert!(ks(&radii, &|x| (x * x - r * r) / (3.0 * r * r)) < crit);
        use std::f64::consts::PI;
        assert!(ks(&angles, &|t| (t + PI) / (2.0 * PI)) < crit);
        // and the naive r (1 + u) would fail the same test
        let naive: Vec<f64> = {
            let mut v: Vec<f64> = (0..n).map(|_| r * (1.0 + uniform(&mut rng))).collect();
            v.sort_by(f64::total_cmp);
            v
        };
        assert!(ks(&naive, &|x| (x * x - r * r) / (3.0 * r * r)) > 10.0 * crit);
    }

    #[test]
    fn maximal_sets_cover_the_plain_square_to_its_edges() {
        // with plain edges, the cells on the right and top edges used to stay uncovered at
        // every level (their far corners were wrapped to 0): a maximal set took minutes and
        // the exactly-n search hung. Now a set is maximal: no point of a fine grid of the
        // square is farther than r from the set (a dart could land there), and it is quick
        for torus in [false, true] {
            let r = 0.09;
            let grid = maximal_set(r, torus, Seed(5), 200, &Progress::SILENT).unwrap();
            let points = grid.points();
            let step = 1.0 / 400.0;
            for i in 0..400 {
                for j in 0..400 {
                    let (x, y) = (i as f64 * step, j as f64 * step);
                    let near = points.chunks_exact(2).any(|p| grid.axis(x, p[0]).powi(2) + grid.axis(y, p[1]).powi(2) < r * r);
                    assert!(near, "torus {torus}: ({x}, {y}) is farther than r from every point");
                }
            }
            // pairwise at least r apart
            for (a, p) in points.chunks_exact(2).enumerate() {
                for q in points.chunks_exact(2).skip(a + 1) {
                    assert!(grid.axis(p[0], q[0]).powi(2) + grid.axis(p[1], q[1]).powi(2) >= r * r);
                }
            }
        }
        // the exactly-n search on a plain square finishes (it hung at n = 64): well within
        // 30 s (0.02 s in a debug build), or the test fails
        let (done, finished) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut out = vec![0.0; 128];
            let shape = crate::sampler::Sampler::new("maximal", Maximal::new(false)).shape(64, 2);
            let made = Maximal::new(false).fill_reporting(&shape, Seed(5), &mut out, &Progress::SILENT);
            done.send(made.map(|()| out)).ok();
        });
        let out = finished.recv_timeout(std::time::Duration::from_secs(30)).expect("the search still runs after 30 s");
        assert!(out.unwrap().iter().all(|x| (0.0..1.0).contains(x)));
    }

    /// One try of dart throwing by its definition, brute force: candidate after candidate
    /// from the try's stream, kept when no kept point lies within r, until n are kept or
    /// more than `attempts` in a row are not.
    fn definition(n: usize, dims: usize, r: f64, torus: bool, attempts: u64, mut rng: Rng) -> Vec<f64> {
        let axis = |a: f64, b: f64| {
            let d = (a - b).abs();
            if torus { d.min(1.0 - d) } else { d }
        };
        let (mut points, mut misses) = (Vec::new(), 0);
        while points.len() < n * dims && misses <= attempts {
            let c: Vec<f64> = (0..dims).map(|_| uniform(&mut rng)).collect();
            if points.chunks_exact(dims).any(|q| c.iter().zip(q).map(|(&a, &b)| axis(a, b).powi(2)).sum::<f64>() < r * r) {
                misses += 1;
            } else {
                points.extend(c);
                misses = 0;
            }
        }
        points
    }

    #[test]
    fn dart_throwing_in_batches_gives_the_points_of_the_definition() {
        // tries that end with n points and tries that end with a run of misses, on the
        // one-point-per-cell grid (2D) and the linked one (1D, 3D), in batches of the
        // production size and in smaller ones, so that a try spans several batches (about
        // 11 candidates a point at the default radius): 4096, a 16th of the production
        // size, made the test 24 s -> 1.1 s (2026-11-30)
        const SMALL: usize = BATCH / 16;
        let pool = rayon::ThreadPoolBuilder::new().num_threads(3).build().unwrap();
        let mut ended_by_misses = 0;
        // (n, dimensions, torus, attempts, radius relative to n's packing distance, seeds,
        // batch size); the last case fills the square with a few hundred points (never
        // 4000) and ends with a run of misses longer than a batch
        for (n, dims, torus, attempts, relative, seeds, size) in [
            (3000, 2, true, 100_000, AUTO_RELATIVE, 1, BATCH),
            (3000, 2, true, 100_000, AUTO_RELATIVE, 1, SMALL),
            (2500, 2, false, 100_000, AUTO_RELATIVE, 1, SMALL),
            (1500, 3, true, 100_000, AUTO_RELATIVE, 1, SMALL),
            (400, 1, false, 100_000, AUTO_RELATIVE, 1, SMALL),
            (3000, 2, true, 30, AUTO_RELATIVE, 12, SMALL),
            // tries that end in runs of misses longer than a batch, while points still fit
            (4000, 2, true, 700, 3.0, 6, TASKS * AHEAD),
            (2000, 3, false, 40, AUTO_RELATIVE, 6, SMALL),
            (4000, 2, true, 3 * SMALL as u64 / 2, 3.0, 1, SMALL),
        ] {
            let r = relative * packing_distance(n, dims).unwrap();
            let darts = DartThrowing::new(Some(r), torus, attempts);
            let mut batch = Batch::new(size);
            for s in 0..seeds {
                let stream = Seed(40 + s).derive(0).rng();
                let expected = definition(n, dims, r, torus, attempts, stream.clone());
                ended_by_misses += usize::from(expected.len() < n * dims);
                // one try each way, on a grid of each kind
                let mut both = |grid: &mut (dyn Occupancy + Send + Sync)| {
                    darts.try_one_by_one(grid, (n, dims), stream.clone(), &Progress::SILENT).unwrap();
                    let one = grid.points().to_vec();
                    grid.clear();
                    pool.install(|| darts.try_in_batches(grid, (n, dims), &stream, &mut batch, &Progress::SILENT))
                        .unwrap();
                    (one, grid.points().to_vec())
                };
                let (one, many) = if dims == 2 {
                    both(&mut DiskGrid::new(r, torus, n))
                } else {
                    both(&mut NeighbourGrid::new(dims, r, torus, n))
                };
                for (got, how) in [(one, "one by one"), (many, "in batches")] {
                    let differ = got.iter().zip(&expected).position(|(a, b)| a != b);
                    assert!(
                        got == expected,
                        "{n} points in {dims}D (torus {torus}, attempts {attempts}), {how}: {} coordinates against the definition's {}, first difference at {differ:?}",
                        got.len(),
                        expected.len()
                    );
                }
            }
        }
        assert!(ended_by_misses >= 10, "only {ended_by_misses} tries ended by a run of misses");
    }
}
