//! Weighted sample elimination (Yuksel 2015): from `ratio` x n uniform candidates, remove
//! the point of largest weight until n remain. A point's weight is the sum over its
//! neighbours closer than d_max = 2 r_max (r_max the packing radius of the target count,
//! [`crate::spatial::packing_radius`]) of (1 - d^/d_max)^8, d^ = max(d, 2 r_min) with
//! Yuksel's weight limiting r_min = r_max (1 - (n / m)^1.5) 0.65 for m candidates; removing
//! a point lowers its neighbours' weights (ties: the lower candidate index goes first).
//! samplab removes the points in parallel, each one as soon as its weight is above its
//! live neighbours', with the same points in the same order as Yuksel's one max-heap
//! (`by_local_maxima` says why). Progressive order as Yuksel's: the n survivors are
//! eliminated again to n/2 (with the radius of n/2 points), those to n/4, ... to one
//! point; the points are output in the reverse order of their elimination, so every
//! prefix of n / 2^k points is a stage's survivors, a blue-noise set of its own.
//!
//! `elimination.tiled` (samplab's variant, not Yuksel's) eliminates in parallel: the unit
//! cube is cut into T^d tiles of side 1/T >= d_max (T even, about [`TILE_POINTS`] target
//! points per tile; below two tiles per axis, the one-heap algorithm), coloured by the
//! parities of their coordinates, so two tiles of one colour are a tile apart and share no
//! pair closer than d_max. Each tile keeps a quota of the n survivors (equal shares, capped
//! by its candidates, the remainder to the tiles with most candidates). In R = [`ROUNDS`]
//! rounds the colours take turns (colour r mod 2^d first in round r), every tile of the
//! colour on its own thread bringing its candidates down to its share of the round (its
//! quota plus (R - r) / R of its surplus) with its own heap, its removals lowering the
//! weights of its neighbours in the adjacent tiles (integer weights: the same sums in any
//! order). A tile's turn runs as soon as its adjacent tiles have had their turns of the
//! earlier phases, with no barrier between phases (a barrier idled a thread at the end of
//! each of the 64 phases per halving); adjacent tiles never run together and meet each
//! other's removals phase by phase, so the points are those of one phase after another.
//! The points depend on T, not on the thread count; the elimination order is the
//! phases', tiles by index within one. The rounds keep neighbouring tiles at nearly the
//! same density: with 4 rounds in a fixed colour order, the expected power spectrum of
//! 65536 points (16 tiles per axis) had a peak at frequency 8, the colours' period, 4.7
//! times the low-frequency floor; with 16 rounds and the order turning, 1.7 times
//! (measured 2026-11-28, 8 sets).

use std::ops::RangeInclusive;

use super::poisson::edge_is_torus;
use super::select_in_order;
use crate::memory::split;
use crate::construct::counts::ANY;
use crate::sampler::registry::{EDGE, SamplerEntry};
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::registry::About;
use crate::sampler::random::Random;
use crate::seed::Seed;
use crate::spatial::{Grid, SORTED, buckets, distance2, packing_radius};
use crate::spec::{Default, Kind, ParamSpec};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Mutex, PoisonError};

/// Sample elimination with `ratio` x n candidates.
#[derive(Debug, Clone, Copy)]
pub struct Elimination {
    ratio: f64,
    torus: bool,
    /// In tiles, in parallel (module docs), or by one heap.
    tiled: bool,
}

/// The start of the optimizers that need a set whose long wavelengths are already settled
/// (`kdm`, `step`, `single-peak`): elimination from 5n candidates on the torus.
pub(crate) const SETTLED: Elimination = Elimination { ratio: 5.0, torus: true, tiled: false };

/// Target points per tile of the tiled variant: T = 2 floor((n / TILE_POINTS)^(1/d) / 2).
pub const TILE_POINTS: usize = 256;

/// Rounds of the tiled variant: each tile comes down to its quota in this many steps, so
/// that neighbouring tiles thin out together (module docs).
pub const ROUNDS: usize = 16;

/// The weight exponent alpha and the weight-limiting constants beta and gamma (Yuksel 2015).
const ALPHA: i32 = 8;
const BETA: f64 = 0.65;
const GAMMA: f64 = 1.5;

/// The weight of a pair at distance d, in units of 2^-40 (exact sums and differences: the
/// weights a point's lost neighbours leave do not depend on the order they went in).
pub fn pair_weight(d: f64, r_min: f64, d_max: f64) -> u64 {
    let x = (1.0 - d.max(2.0 * r_min) / d_max).powi(ALPHA) * (1u64 << 40) as f64;
    // x rounded half away from zero, as f64::round (a call into libm, 6% of a tiled run):
    // x is in [0, 2^40], its fraction x - trunc(x) exact
    let whole = x as u64;
    whole + u64::from(x - whole as f64 >= 0.5)
}

/// Points per unit of parallel work in the neighbour lists.
const CHUNK: usize = 1024;

/// Live points sampled for each batch's threshold in the one-heap elimination (by local
/// maxima).
const SAMPLE: usize = 8192;

/// The pairs closer than d_max, their weights computed when needed (lists with the
/// weights were 144 MB at 5 x 10^5 candidates, written and read at the memory's pace).
/// Each position's neighbours are listed for the one-heap elimination, which reads them in
/// every round a point waits for a heavier neighbour, and searched in the grid by the
/// tiled one (1.83x on two threads against 1.62x with lists, measured 2026-11-28).
struct Pairs<'g> {
    grid: &'g Grid,
    torus: bool,
    r_min: f64,
    d_max: f64,
    lists: Option<Lists>,
}

/// Per chunk of positions: each one's end in the neighbours, and the neighbours.
struct Lists(Vec<(Vec<u32>, Vec<u32>)>);

impl Lists {
    /// The positions closer than d_max to position q.
    #[inline]
    fn of(&self, q: usize) -> &[u32] {
        let (ends, near) = &self.0[q / CHUNK];
        let k = q % CHUNK;
        &near[if k == 0 { 0 } else { ends[k - 1] as usize }..ends[k] as usize]
    }
}

impl<'g> Pairs<'g> {
    /// The pairs of the grid's points closer than d_max (`listed` or not), and each point's
    /// weight.
    fn new(grid: &'g Grid, torus: bool, (r_min, d_max): (f64, f64), listed: bool) -> (Pairs<'g>, Vec<u64>) {
        let mut pairs = Pairs { grid, torus, r_min, d_max, lists: None };
        let m = grid.len();
        let (lists, weights): (Vec<_>, Vec<Vec<u64>>) = (0..m.div_ceil(CHUNK))
            .into_par_iter()
            // a task a chunk: rayon's own split left runs of up to a quarter of the chunks
            // that a thread, once done, could not share (one thread alone for the last
            // 50 ms of the lists in a profile of `generate elimination -n 100000`)
            .with_max_len(1)
            .map(|c| {
                let (mut ends, mut near, mut weights) = (Vec::new(), Vec::new(), Vec::new());
                for q in c * CHUNK..((c + 1) * CHUNK).min(m) {
                    let mut sum = 0;
                    pairs.search(q, |r, w| {
                        if listed {
                            near.push(r as u32);
                        }
                        sum += w;
                    });
                    ends.push(near.len() as u32);
                    weights.push(sum);
                }
                ((ends, near), weights)
            })
            .unzip();
        pairs.lists = listed.then_some(Lists(lists));
        (pairs, weights.concat())
    }

    /// The weight of the pair of point p and position r, if closer than d_max.
    #[inline]
    fn weight(&self, p: &[f64], r: usize) -> Option<u64> {
        let d2 = distance2(p, self.grid.point(r), self.torus);
        (d2 < self.d_max * self.d_max).then(|| pair_weight(d2.sqrt(), self.r_min, self.d_max))
    }

    /// `visit(r, weight)` for every position r closer than d_max to position q, found in
    /// the grid.
    #[inline]
    fn search(&self, q: usize, mut visit: impl FnMut(usize, u64)) {
        let p = self.grid.point(q);
        self.grid.near(q, 1, self.torus, |cell| {
            for r in cell.filter(|&r| r != q) {
                if let Some(w) = self.weight(p, r) {
                    visit(r, w);
                }
            }
        });
    }
}

/// Eliminate `points` (m of them, `dims` coordinates) down to `target`: the survivors'
/// indices in increasing order and the eliminated ones in elimination order.
///
/// # Errors
/// Dimensions outside 1..=8 (no packing radius).
pub fn eliminate(points: &[f64], dims: usize, target: usize, torus: bool) -> Result<(Vec<usize>, Vec<usize>)> {
    eliminate_in_tiles(points, dims, target, torus, 0)
}

/// As [`eliminate`], in `tiles` tiles per axis (module docs; made even and at most 1/d_max;
/// under 2, one heap as [`eliminate`]).
///
/// # Errors
/// As [`eliminate`].
pub fn eliminate_in_tiles(
    points: &[f64],
    dims: usize,
    target: usize,
    torus: bool,
    tiles: usize,
) -> Result<(Vec<usize>, Vec<usize>)> {
    let m = points.len() / dims;
    if target >= m {
        return Ok(((0..m).collect(), Vec::new()));
    }
    let r_max = packing_radius(target.max(1), dims)?;
    let d_max = 2.0 * r_max;
    let r_min = r_max * (1.0 - (target as f64 / m as f64).powf(GAMMA)) * BETA;
    // positions in the grid's cell order, ids[q] the candidate at position q
    let grid = Grid::covering(points, dims, d_max);
    // tiles per axis: even, each at least d_max wide
    let tiles = (tiles.min((1.0 / d_max).floor() as usize)) / 2 * 2;
    let (pairs, weights) = Pairs::new(&grid, torus, (r_min, d_max), tiles < 2);
    // listed exactly when under two tiles
    let (mut kept, gone) = match &pairs.lists {
        Some(lists) => by_local_maxima(weights, target, &pairs, lists),
        None => by_tiles(weights, tiles, target, &pairs),
    };
    kept.par_sort_unstable();
    Ok((kept, gone.par_iter().map(|&q| grid.ids[q] as usize).collect()))
}

/// Yuksel's elimination, its removals in parallel with the points and order of one heap:
/// the candidates left, and the positions removed in order.
///
/// A point whose key (weight, then the lower candidate index) is above every live
/// neighbour's is a local maximum. Removing one only lowers its neighbours' weights, so the
/// others stay local maxima, two of them are never neighbours, and the removals commute:
/// every order of removing local maxima removes each point at the same weight (a diamond
/// argument; one heap removes the global maximum, a local one). The keys one heap removes
/// only fall, so its order is the removals' by key, and its first k removals are the k
/// largest keys of any complete run of removals down to a threshold theta at or below the
/// k-th one's. Batch by batch, theta is a key ranked among a sample of [`SAMPLE`] live
/// points, and every local maximum at or above theta goes, in rounds (the largest such key
/// is always a local maximum, so each round removes one or more), until none is left at or
/// above theta; the batches go on until enough are removed, and the ones past the count
/// (theta below the last needed key) are kept. So theta changes only how the work is cut,
/// not the points. A batch removes only part of the points at or above its theta (each
/// removal lowers its neighbours' weights, some below theta: 38-47% in a stage's first
/// batch, 2026-11-30), so theta is ranked at the points left to remove divided by the last
/// batch's share (all of them in the first batch), at most halfway from those to every
/// live point. With the count alone, `generate elimination -n 100000` took 10 batches and
/// 70 rounds in its first stage and 7-8 batches and 27-32 rounds per halving, each a few
/// parallel passes; now 5 and 55, and 3 and 14-20, removing 0.2-2.6% more than needed,
/// in the same time on one and two threads.
///
/// A round is two parallel passes over the points at or above theta, by blocks of
/// [`GRAIN`]: each point's turn, then the waiting points written in order to the next
/// round's list and the local maxima removed, each block at offsets from the blocks' counts.
/// Rayon's `partition_map` and `filter().collect()`, which this replaces, built and joined
/// lists of pieces in every round: with them, 16 threads on the two-core machine took 1.18x
/// and 1.28x the CPU time of 2 threads in two runs; with the blocks, 1.04x and 1.11x (10^5
/// points, medians of 9, 2026-11-30; docs/performance.md, "Sixteen cores").
fn by_local_maxima(weights: Vec<u64>, target: usize, pairs: &Pairs, lists: &Lists) -> (Vec<usize>, Vec<usize>) {
    use std::cmp::Reverse;
    let m = weights.len();
    let ids = &pairs.grid.ids;
    // a live point's word is LIVE plus its weight, a removed point's 0 (one load tells a
    // neighbour's liveness and key: the turns read both for every neighbour)
    let weight: Vec<AtomicU64> = weights
        .into_par_iter()
        .map(|w| {
            debug_assert!(w < LIVE);
            AtomicU64::new(LIVE | w)
        })
        .collect();
    let alive = |q: usize| weight[q].load(Relaxed) & LIVE != 0;
    // larger keys go first; a removed point's is below every live one's
    let key = |q: u32| (weight[q as usize].load(Relaxed), Reverse(ids[q as usize]));
    // key(r) < k, reading r's candidate index only on a tie of weights
    let below = |r: u32, (w, Reverse(id)): (u64, Reverse<u32>)| {
        let v = weight[r as usize].load(Relaxed);
        v < w || (v == w && ids[r as usize] > id)
    };
    let mut live: Vec<u32> = (0..m as u32).into_par_iter().collect();
    // (weight, candidate) when removed, as sorted in one heap's order, and the position
    let mut removed: Vec<((Reverse<u64>, u32), u32)> = Vec::with_capacity(m - target);
    // the points at or above theta, the next round's, and each one's turn in this round
    let (mut active, mut next, mut turns) = (Vec::new(), Vec::new(), Vec::new());
    // the share of its points at or above theta that the last batch removed
    let mut share = 1.0f64;
    while removed.len() < m - target {
        let rest = m - target - removed.len();
        // enough points at or above theta for the rest at the last batch's share, at most
        // halfway from the rest to every live point
        let want = ((rest as f64 / share).ceil() as usize).min((rest + live.len()) / 2).max(rest);
        let mut sample: Vec<_> = live.iter().step_by((live.len() / SAMPLE).max(1)).map(|&q| key(q)).collect();
        let rank = (want * sample.len()).div_ceil(live.len()).min(sample.len());
        let theta = *sample.select_nth_unstable_by(rank - 1, |a, b| b.cmp(a)).1;
        select_in_order(live.len(), GRAIN, |i| Some(live[i]).filter(|&q| key(q) >= theta), &mut active);
        let (first_active, first_removed) = (active.len(), removed.len());
        while !active.is_empty() {
            // each point's turn (weights only fall: one below theta stays below), and per
            // block how many wait and how many go
            turns.resize(active.len(), Turn::Below);
            let counts: Vec<[usize; 2]> = active
                .par_chunks(GRAIN)
                .zip(turns.par_chunks_mut(GRAIN))
                .map(|(block, turns)| {
                    let mut count = [0; 2];
                    for (&q, turn) in block.iter().zip(turns) {
                        let k = key(q);
                        *turn = if k < theta {
                            Turn::Below
                        } else if lists.of(q as usize).iter().all(|&r| below(r, k)) {
                            Turn::Go
                        } else {
                            Turn::Wait
                        };
                        if *turn != Turn::Below {
                            count[(*turn == Turn::Go) as usize] += 1;
                        }
                    }
                    count
                })
                .collect();
            // the waiting ones to the next round and the local maxima out, each block at its
            // offsets; no two local maxima are neighbours, so each one's removal leaves the
            // others' weights (read again here) and turns as they were
            next.clear();
            next.resize(counts.iter().map(|c| c[0]).sum(), 0);
            let done = removed.len();
            removed.resize(done + counts.iter().map(|c| c[1]).sum::<usize>(), ((Reverse(0), 0), 0));
            let waits = split(&mut next, counts.iter().map(|c| c[0]));
            let goes = split(&mut removed[done..], counts.iter().map(|c| c[1]));
            waits.into_par_iter().zip(goes).zip(active.par_chunks(GRAIN).zip(turns.par_chunks(GRAIN))).for_each(
                |((waits, goes), (block, turns))| {
                    let (mut waiting, mut going) = (waits.iter_mut(), goes.iter_mut());
                    for (&q, &turn) in block.iter().zip(turns) {
                        match turn {
                            Turn::Below => {}
                            Turn::Wait => *waiting.next().expect("counted") = q,
                            Turn::Go => {
                                let (w, Reverse(id)) = key(q);
                                *going.next().expect("counted") = ((Reverse(w & !LIVE), id), q);
                                weight[q as usize].store(0, Relaxed);
                                // the live neighbours lose their pair's weight (computed for
                                // them alone: most of a late round's neighbours are gone)
                                let p = pairs.grid.point(q as usize);
                                for &r in lists.of(q as usize) {
                                    if alive(r as usize) {
                                        let w = pairs.weight(p, r as usize).unwrap_or_default();
                                        weight[r as usize].fetch_sub(w, Relaxed);
                                    }
                                }
                            }
                        }
                    }
                },
            );
            std::mem::swap(&mut active, &mut next);
        }
        if first_active > 0 {
            share = ((removed.len() - first_removed) as f64 / first_active as f64).max(0.25);
        }
        select_in_order(live.len(), GRAIN, |i| Some(live[i]).filter(|&q| alive(q as usize)), &mut next);
        std::mem::swap(&mut live, &mut next);
    }
    // every key is unique (the candidate), so an unstable sort gives the one order
    removed.par_sort_unstable();
    let past = removed.split_off(m - target);
    live.par_extend(past.into_par_iter().map(|(_, q)| q));
    (
        live.into_par_iter().map(|q| ids[q as usize] as usize).collect(),
        removed.into_par_iter().map(|(_, q)| q as usize).collect(),
    )
}

/// The bit of a live point's word in [`by_local_maxima`], above every weight: at most 2^40
/// per neighbour, and a point has a few dozen neighbours (2^23 would reach it).
const LIVE: u64 = 1 << 63;

/// Points per block of the parallel passes of [`by_local_maxima`]: a round of fewer runs on
/// one thread. Most of the 367 rounds of `generate elimination -n 100000` (500000
/// candidates, halved down to one point) hold under 16 blocks of 4096 points: counted from
/// the rounds' sizes, blocks of 4096 would let 16 threads do the rounds at most 9.4x faster
/// than one, blocks of 1024 12.8x; one thread's time and 16 threads' CPU on two cores are
/// the same with either (medians of 9, 2026-11-30).
const GRAIN: usize = 1024;

/// A point's turn in a round of [`by_local_maxima`].
#[derive(Clone, Copy, PartialEq)]
enum Turn {
    /// Its key fell below theta: out of the batch.
    Below,
    /// A live neighbour has a larger key.
    Wait,
    /// A local maximum: removed.
    Go,
}

/// Each tile's share of `target` survivors: equal shares capped by its candidates
/// (`counts`), one more to the tiles with room, most candidates first (ties: the lower
/// tile).
fn quotas(counts: &[usize], target: usize) -> Vec<usize> {
    let kept = |level: usize| counts.iter().map(|&c| c.min(level)).sum::<usize>();
    // the largest level whose capped shares fit (kept(0) = 0 <= target <= kept(max))
    let (mut low, mut high) = (0, counts.iter().copied().max().unwrap_or(0));
    while low < high {
        let mid = (low + high).div_ceil(2);
        if kept(mid) <= target { low = mid } else { high = mid - 1 }
    }
    let mut share: Vec<usize> = counts.iter().map(|&c| c.min(low)).collect();
    let mut room: Vec<usize> = (0..counts.len()).filter(|&t| counts[t] > low).collect();
    room.sort_by_key(|&t| (std::cmp::Reverse(counts[t]), t));
    for &t in &room[..target - kept(low)] {
        share[t] += 1;
    }
    share
}

/// The tiled elimination (module docs): the candidates left, and the positions removed in
/// order.
fn by_tiles(weights: Vec<u64>, tiles: usize, target: usize, pairs: &Pairs) -> (Vec<usize>, Vec<usize>) {
    let grid = pairs.grid;
    let (m, dims) = (weights.len(), grid.point(0).len());
    let colour_of = |t: usize| (0..dims).fold((0, t), |(c, rest), axis| (c | (rest % tiles % 2) << axis, rest / tiles)).0;
    // each position's tile; each tile's positions, increasing, and each position's place
    // among its tile's
    let owner: Vec<u32> = (0..m).into_par_iter().map(|q| Grid::cell(tiles, grid.point(q)) as u32).collect();
    let count = tiles.pow(dims as u32);
    // per block of positions, each tile's positions in it
    let blocks = buckets(&owner, count, |t| t as usize);
    let members: Vec<Vec<u32>> =
        (0..count).into_par_iter().map(|t| blocks.iter().flat_map(|lists| lists[t].iter().copied()).collect()).collect();
    // each position's place among its tile's: its tile's positions in earlier blocks, then
    // its place in its block's list
    let before: Vec<Vec<u32>> = blocks
        .iter()
        .scan(vec![0u32; count], |sum, lists| {
            let start = sum.clone();
            sum.iter_mut().zip(lists).for_each(|(s, list)| *s += list.len() as u32);
            Some(start)
        })
        .collect();
    let mut place = vec![0u32; m];
    place.par_chunks_mut(SORTED).zip(owner.par_chunks(SORTED)).zip(before).for_each(|((place, owners), mut next)| {
        for (p, &t) in place.iter_mut().zip(owners) {
            *p = next[t as usize];
            next[t as usize] += 1;
        }
    });
    let quota = quotas(&members.iter().map(Vec::len).collect::<Vec<_>>(), target);
    let ids: Vec<Vec<u32>> = members.par_iter().map(|ms| ms.iter().map(|&q| grid.ids[q as usize]).collect()).collect();
    let colours = 1 << dims;
    let colour: &Vec<usize> = &(0..count).map(colour_of).collect();
    // the turns in the order of the phases, the tiles by index within one: phase
    // (round - 1) C + turn is colour (round + turn) mod C's, C = 2^d colours
    let order: Vec<(usize, usize)> = (1..=ROUNDS)
        .flat_map(|round| (0..colours).map(move |turn| (round, (round + turn) % colours)))
        .flat_map(|(round, hue)| (0..count).filter(move |&t| colour[t] == hue).map(move |t| (t, round)))
        .collect();
    // a turn runs as soon as its tile's and its adjacent tiles' turns before it are done:
    // two adjacent tiles never run together, and each meets the other's removals in the
    // order of the phases, so the points are those of phase after phase
    let near: Vec<Vec<u32>> = (0..count).map(|t| adjacent(t, tiles, dims)).collect();
    let graph = crate::dataflow::Graph::new(
        count,
        order.len(),
        |k| std::iter::once(order[k].0).chain(near[order[k].0].iter().map(|&u| u as usize)),
        |k| [order[k].0],
    );
    let turns = Turns {
        pairs,
        members: &members,
        owner: &owner,
        place: &place,
        quota: &quota,
        // the weight each position has lost to the removals of other tiles, not yet in its
        // heap
        lost: (0..m).into_par_iter().map(|_| AtomicU64::new(0)).collect(),
        state: members
            .par_iter()
            .zip(&ids)
            .map(|(ms, ids)| {
                let own = ms.iter().map(|&q| weights[q as usize]).collect();
                let heap = Heap::new(own, ids, (0..ms.len() as u32).collect());
                Mutex::new(Tile { heap, alive: vec![true; ms.len()], removed: Vec::with_capacity(ROUNDS) })
            })
            .collect(),
    };
    graph.run(|k| turns.turn(order[k].0, order[k].1));
    let state: Vec<Tile> = turns.state.into_iter().map(|s| s.into_inner().unwrap_or_else(PoisonError::into_inner)).collect();
    // the removals in the order of the phases
    let mut gone = Vec::with_capacity(m - target);
    for &(t, round) in &order {
        gone.extend_from_slice(&state[t].removed[round - 1]);
    }
    let kept = state
        .par_iter()
        .zip(&ids)
        .flat_map_iter(|(tile, ids)| ids.iter().zip(&tile.alive).filter(|(_, a)| **a).map(|(&id, _)| id as usize))
        .collect();
    (kept, gone)
}

/// The tiles within one tile of tile t along every axis, around the torus (t excluded).
fn adjacent(t: usize, tiles: usize, dims: usize) -> Vec<u32> {
    let mut near: Vec<u32> = (0..3usize.pow(dims as u32))
        .map(|offsets| {
            let (mut u, mut scale, mut rest, mut o) = (0, 1, t, offsets);
            for _ in 0..dims {
                u += (rest % tiles + tiles + o % 3 - 1) % tiles * scale;
                (scale, rest, o) = (scale * tiles, rest / tiles, o / 3);
            }
            u as u32
        })
        .filter(|&u| u as usize != t)
        .collect();
    near.sort_unstable();
    near.dedup();
    near
}

/// One tile of the tiled elimination: its heap, which of its members are alive (by place),
/// and the positions it removed in each round so far.
struct Tile<'a> {
    heap: Heap<'a>,
    alive: Vec<bool>,
    removed: Vec<Vec<usize>>,
}

/// What the tiled elimination's turns share: each tile's state, and the weight each
/// position has lost to other tiles' removals.
struct Turns<'a> {
    pairs: &'a Pairs<'a>,
    members: &'a [Vec<u32>],
    owner: &'a [u32],
    place: &'a [u32],
    quota: &'a [usize],
    lost: Vec<AtomicU64>,
    state: Vec<Mutex<Tile<'a>>>,
}

impl<'a> Turns<'a> {
    /// Tile t's turn in `round`: down to its share of the round, its quota plus (R - r) / R
    /// of its surplus.
    fn turn(&self, t: usize, round: usize) {
        let mut tile = self.state[t].lock().unwrap_or_else(PoisonError::into_inner);
        let Tile { heap, alive, removed } = &mut *tile;
        let members = &self.members[t];
        let share = self.quota[t] + (members.len() - self.quota[t]) * (ROUNDS - round) / ROUNDS;
        for (k, &q) in members.iter().enumerate() {
            let by = self.lost[q as usize].load(Relaxed);
            if by > 0 && alive[k] {
                self.lost[q as usize].store(0, Relaxed);
                heap.lower(k, by);
            }
        }
        let mut gone = Vec::new();
        while heap.len() > share {
            let k = heap.pop();
            alive[k] = false;
            let q = members[k] as usize;
            gone.push(q);
            self.pairs.search(q, |r, w| {
                if self.owner[r] as usize != t {
                    // an adjacent tile's point, resting meanwhile
                    self.lost[r].fetch_add(w, Relaxed);
                } else if alive[self.place[r] as usize] {
                    heap.lower(self.place[r] as usize, w);
                }
            });
        }
        removed.push(gone);
    }
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
    /// The heap of the positions `entries` (of `weight.len()`).
    fn new(weight: Vec<u64>, ids: &'a [u32], entries: Vec<u32>) -> Heap<'a> {
        let mut at = vec![u32::MAX; weight.len()];
        for (k, &q) in entries.iter().enumerate() {
            at[q as usize] = k as u32;
        }
        let mut h = Heap { weight, ids, heap: entries, at };
        for k in (0..h.heap.len() / 2).rev() {
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

    /// How many positions it holds.
    fn len(&self) -> usize {
        self.heap.len()
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
pub fn progressive(points: &[f64], dims: usize, n: usize, torus: bool, tiled: bool) -> Result<Vec<usize>> {
    // the tiled variant's tiles per axis for a target count (module docs)
    let tiles = |target: usize| {
        if tiled { 2 * ((target as f64 / TILE_POINTS as f64).powf(1.0 / dims as f64) / 2.0).floor() as usize } else { 0 }
    };
    let (mut alive, _) = eliminate_in_tiles(points, dims, n, torus, tiles(n))?;
    let mut later = Vec::with_capacity(n);
    while alive.len() > 1 {
        let target = alive.len() / 2;
        let mut subset = vec![0.0; alive.len() * dims];
        subset.par_chunks_exact_mut(dims).zip(&alive).for_each(|(p, &i)| p.copy_from_slice(&points[i * dims..(i + 1) * dims]));
        let (kept, gone) = eliminate_in_tiles(&subset, dims, target, torus, tiles(target))?;
        later.par_extend(gone.par_iter().map(|&k| alive[k]));
        alive = kept.par_iter().map(|&k| alive[k]).collect();
    }
    later.extend(alive);
    later.reverse();
    Ok(later)
}

impl Construction for Elimination {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let n = shape.n();
        if n as f64 * self.ratio > u32::MAX as f64 {
            return Err(shape.invalid_count(format!("{} candidates exceed 2^32", (n as f64 * self.ratio).ceil())));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Elimination {
    pub(crate) fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        if n == 0 {
            return Ok(());
        }
        let m = ((n as f64 * self.ratio).ceil() as usize).max(n);
        // the candidates, their neighbour lists, the heap and the halvings' copies: the peak
        // for 5 * 10^5 candidates was 80 MB in 2D and 156 MB in 4D (tiled: 54 and 68 MB;
        // measured, 2026-11-28), up to 320 bytes each
        crate::memory::check(|| format!("elimination from {m} candidates"), m as u128 * (320 + 8 * dims as u128))?;
        let mut candidates = vec![0.0; m * dims];
        Random::draw(seed, &mut candidates);
        for (p, i) in out.chunks_exact_mut(dims).zip(progressive(&candidates, dims, n, self.torus, self.tiled)?) {
            p.copy_from_slice(&candidates[i * dims..(i + 1) * dims]);
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("elimination", "weighted sample elimination of uniform candidates to n, progressive")
            .aliases(&["sample-elimination", "yuksel"])
            .params(PARAMS)
            .cite(&["yuksel2015"]),
        counts: ANY,
        randomized: true,
        dims: "1..=4",
        build: |p| build(p, false),
    },
    SamplerEntry {
        about: About::new(
            "elimination.tiled",
            "sample elimination in tiles of about 256 points, eliminated in parallel (samplab's variant: other points than elimination's)",
        )
        .params(PARAMS)
        .cite(&["yuksel2015"]),
        counts: ANY,
        randomized: true,
        dims: "1..=4",
        build: |p| build(p, true),
    },
];

/// Either entry's sampler from its parameters.
fn build(p: &crate::spec::Params, tiled: bool) -> Result<Box<dyn Construction>> {
    Ok(Box::new(Elimination { ratio: p.real("ratio"), torus: edge_is_torus(p.word("edge")), tiled }))
}

/// The parameters of both entries.
const PARAMS: &[ParamSpec] = &[
    ParamSpec {
        name: "ratio",
        kind: Kind::Real { min: 1.0, max: 64.0 },
        default: Default::Number(5.0),
        doc: "candidates per output point",
    },
    EDGE,
];
