//! Weighted sample elimination (Yuksel 2015): from `ratio` x n uniform candidates, remove
//! the point of largest weight until n remain. A point's weight is the sum over its
//! neighbours closer than d_max = 2 r_max (r_max the packing radius of the target count,
//! [`crate::spatial::packing_radius`]) of (1 - d^/d_max)^8, d^ = max(d, 2 r_min) with
//! Yuksel's weight limiting r_min = r_max (1 - (n / m)^1.5) 0.65 for m candidates; removing
//! a point lowers its neighbours' weights, kept in an indexed max-heap (ties: the lower
//! candidate index goes first). Progressive order as Yuksel's: the n survivors are
//! eliminated again to n/2 (with the radius of n/2 points), those to n/4, ... to one
//! point; the points are output in the reverse order of their elimination, so every
//! prefix of n / 2^k points is a stage's survivors, a blue-noise set of its own.

use std::ops::RangeInclusive;

use super::poisson::edge_is_torus;
use crate::sampler::registry::{ANY, EDGE, SamplerEntry};
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::registry::About;
use crate::sampler::random::Random;
use crate::seed::Seed;
use crate::spatial::{Grid, distance2, packing_radius};
use crate::spec::{Default, Kind, ParamSpec};
use rayon::prelude::*;

/// Sample elimination with `ratio` x n candidates.
#[derive(Debug, Clone, Copy)]
pub struct Elimination {
    ratio: f64,
    torus: bool,
}

/// The start of the optimizers that need a set whose long wavelengths are already settled
/// (`kdm`, `step`, `single-peak`): elimination from 5n candidates on the torus.
pub(crate) const SETTLED: Elimination = Elimination { ratio: 5.0, torus: true };

/// The weight exponent alpha and the weight-limiting constants beta and gamma (Yuksel 2015).
const ALPHA: i32 = 8;
const BETA: f64 = 0.65;
const GAMMA: f64 = 1.5;

/// The weight of a pair at distance d, in units of 2^-40 (exact sums and differences: the
/// weights a point's lost neighbours leave do not depend on the order they went in).
pub fn pair_weight(d: f64, r_min: f64, d_max: f64) -> u64 {
    ((1.0 - d.max(2.0 * r_min) / d_max).powi(ALPHA) * (1u64 << 40) as f64).round() as u64
}

/// Points per unit of parallel work in the weights' first sums.
const CHUNK: usize = 1024;

/// One chunk's neighbour lists: each point's end in the pairs, and the (position, weight)
/// pairs.
type Lists = (Vec<u32>, Vec<(u32, u64)>);

/// Eliminate `points` (m of them, `dims` coordinates) down to `target`: the survivors'
/// indices in increasing order and the eliminated ones in elimination order.
///
/// # Errors
/// Dimensions outside 1..=8 (no packing radius).
pub fn eliminate(points: &[f64], dims: usize, target: usize, torus: bool) -> Result<(Vec<usize>, Vec<usize>)> {
    let m = points.len() / dims;
    if target >= m {
        return Ok(((0..m).collect(), Vec::new()));
    }
    let r_max = packing_radius(target.max(1), dims)?;
    let d_max = 2.0 * r_max;
    let r_min = r_max * (1.0 - (target as f64 / m as f64).powf(GAMMA)) * BETA;
    let weight = |d2: f64| pair_weight(d2.sqrt(), r_min, d_max);
    // positions in the grid's cell order, ids[q] the candidate at position q
    let grid = Grid::covering(points, dims, d_max);
    // every point's neighbours closer than d_max with their weights, by chunk (fixed order)
    let lists: Vec<Lists> = (0..m.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let (mut ends, mut pairs) = (Vec::new(), Vec::new());
            for q in c * CHUNK..((c + 1) * CHUNK).min(m) {
                let p = grid.point(q);
                grid.near(q, 1, torus, |cell| {
                    for r in cell.filter(|&r| r != q) {
                        let d2 = distance2(p, grid.point(r), torus);
                        if d2 < d_max * d_max {
                            pairs.push((r as u32, weight(d2)));
                        }
                    }
                });
                ends.push(pairs.len() as u32);
            }
            (ends, pairs)
        })
        .collect();
    // position q's neighbours, read in its chunk's lists (not gathered into one list: that
    // copy was a sixth of a run, on one thread)
    let near = |q: usize| -> &[(u32, u64)] {
        let (ends, pairs) = &lists[q / CHUNK];
        let k = q % CHUNK;
        &pairs[if k == 0 { 0 } else { ends[k - 1] as usize }..ends[k] as usize]
    };
    let weights = (0..m).into_par_iter().map(|q| near(q).iter().map(|&(_, w)| w).sum()).collect();
    let mut heap = Heap::new(weights, &grid.ids);
    let mut alive = vec![true; m];
    let mut gone = Vec::with_capacity(m - target);
    while gone.len() < m - target {
        let q = heap.pop();
        alive[q] = false;
        gone.push(grid.ids[q] as usize);
        for &(r, w) in near(q) {
            if alive[r as usize] {
                heap.lower(r as usize, w);
            }
        }
    }
    let mut kept: Vec<usize> = (0..m).filter(|&q| alive[q]).map(|q| grid.ids[q] as usize).collect();
    kept.sort_unstable();
    Ok((kept, gone))
}

/// A max-heap of grid positions by weight (ties: the lower candidate index first) whose
/// weights can be lowered in place.
struct Heap<'a> {
    weight: Vec<u64>,
    /// The candidate index of each position, for ties.
    ids: &'a [u32],
    heap: Vec<u32>,
    /// Each position's place in `heap`.
    at: Vec<u32>,
}

impl<'a> Heap<'a> {
    fn new(weight: Vec<u64>, ids: &'a [u32]) -> Heap<'a> {
        let m = weight.len();
        let mut h = Heap { weight, ids, heap: (0..m as u32).collect(), at: (0..m as u32).collect() };
        for k in (0..m / 2).rev() {
            h.down(k);
        }
        h
    }

    /// Whether position a goes before position b.
    #[inline]
    fn before(&self, a: u32, b: u32) -> bool {
        let (wa, wb) = (self.weight[a as usize], self.weight[b as usize]);
        wa > wb || (wa == wb && self.ids[a as usize] < self.ids[b as usize])
    }

    /// Sift the entry at place k down to where it belongs.
    fn down(&mut self, mut k: usize) {
        let item = self.heap[k];
        loop {
            let a = 2 * k + 1;
            if a >= self.heap.len() {
                break;
            }
            let child = if a + 1 < self.heap.len() && self.before(self.heap[a + 1], self.heap[a]) { a + 1 } else { a };
            if !self.before(self.heap[child], item) {
                break;
            }
            self.heap[k] = self.heap[child];
            self.at[self.heap[k] as usize] = k as u32;
            k = child;
        }
        self.heap[k] = item;
        self.at[item as usize] = k as u32;
    }

    /// Remove and return the first position.
    fn pop(&mut self) -> usize {
        let first = self.heap[0] as usize;
        let last = self.heap.pop().unwrap_or_default();
        if !self.heap.is_empty() {
            self.heap[0] = last;
            self.down(0);
        }
        first
    }

    /// Lower position q's weight by `by`.
    fn lower(&mut self, q: usize, by: u64) {
        self.weight[q] -= by;
        self.down(self.at[q] as usize);
    }
}

/// The candidates' progressive order of elimination: m = `points.len() / dims` candidates
/// to n, then halving to one point (module docs); the n kept indices, first kept first.
///
/// # Errors
/// As [`eliminate`].
pub fn progressive(points: &[f64], dims: usize, n: usize, torus: bool) -> Result<Vec<usize>> {
    let (mut alive, _) = eliminate(points, dims, n, torus)?;
    let mut later = Vec::with_capacity(n);
    while alive.len() > 1 {
        let target = alive.len() / 2;
        let subset: Vec<f64> = alive.iter().flat_map(|&i| points[i * dims..(i + 1) * dims].iter().copied()).collect();
        let (kept, gone) = eliminate(&subset, dims, target, torus)?;
        later.extend(gone.iter().map(|&k| alive[k]));
        alive = kept.iter().map(|&k| alive[k]).collect();
    }
    later.extend(alive);
    later.reverse();
    Ok(later)
}

impl Construction for Elimination {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        if n as f64 * self.ratio > u32::MAX as f64 {
            return Err(Error::InvalidCount {
                sampler: String::new(),
                n,
                dims,
                reason: format!("{} candidates exceed 2^32", (n as f64 * self.ratio).ceil()),
            });
        }
        Ok(())
    }

    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        Ok(crate::sampler::from_fill(move |seed, out| self.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Elimination {


    pub(crate) fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        if n == 0 {
            return Ok(());
        }
        let m = ((n as f64 * self.ratio).ceil() as usize).max(n);
        // the candidates, their neighbour lists, the heap and the halvings' copies: the peak
        // was 0.30 GB for 5 * 10^5 candidates in 2D (measured, 2026-11-26), 600 bytes each
        crate::memory::check(|| format!("elimination from {m} candidates"), m as u128 * (640 + 8 * dims as u128))?;
        let mut candidates = vec![0.0; m * dims];
        Random::draw(seed, &mut candidates);
        for (p, i) in out.chunks_exact_mut(dims).zip(progressive(&candidates, dims, n, self.torus)?) {
            p.copy_from_slice(&candidates[i * dims..(i + 1) * dims]);
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("elimination", "weighted sample elimination of uniform candidates to n, progressive")
        .aliases(&["sample-elimination", "yuksel"])
        .params(&[
            ParamSpec {
                name: "ratio",
                kind: Kind::Real { min: 1.0, max: 64.0 },
                default: Default::Number(5.0),
                doc: "candidates per output point",
            },
            EDGE,
        ])
        .cite(&["yuksel2015"]),
    counts: ANY,
    randomized: true,
    dims: "1..=4",
    build: |p| Ok(Box::new(Elimination { ratio: p.real("ratio"), torus: edge_is_torus(p.word("edge")) })),
}];
