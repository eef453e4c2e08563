//! Capacity-constrained Voronoi tessellation (Balzer, Schlömer & Deussen 2009): n sites
//! and `capacity` x n uniform random points on the torus, each site owning exactly
//! `capacity` of them (a random assignment to start). An iteration visits every pair of
//! neighbouring sites (closer than 2 mean spacings) and swaps their points while a swap
//! lowers the energy sum |x - s(x)|^2: the point of site i that gains most by moving to j
//! against the point of j that gains most by moving to i, while the two gains sum above
//! zero; then every site moves to the centroid of its points. It stops when an iteration
//! swaps nothing, or after `iterations`. Each site keeps its capacity throughout, so the
//! cells have equal areas (to the points' resolution) while Lloyd's drift to hexagons is
//! resisted. Pairs that share no site swap in parallel, with the sites of one pair after
//! another ([`State::iterate`]).

use std::ops::RangeInclusive;

use crate::sampler::random::Random;
use crate::construct::counts::ANY;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Seed, wrap01};
use crate::spatial::{Grid, distance2, torus_gap};
use crate::spec::{Default, Kind, ParamSpec};
use rayon::prelude::*;
use std::collections::BinaryHeap;
use std::mem::take;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::sync::{Mutex, PoisonError};

/// Capacity-constrained Voronoi tessellation.
#[derive(Debug, Clone, Copy)]
pub struct Ccvt {
    capacity: usize,
    iterations: usize,
}

/// The state of the optimization: sites, points and which site owns each point.
pub struct State {
    dims: usize,
    /// Site coordinates.
    pub sites: Vec<f64>,
    points: Vec<f64>,
    /// The points of each site.
    members: Vec<Vec<Member>>,
    /// The points' buffer of the iteration before, which the next regrouping fills (a
    /// fresh one was zeroed on one thread, freed on one, and its pages faulted in anew).
    spare: Vec<f64>,
}

/// A point of a site: its index and, during the swaps, its squared distance to the site
/// (the sites stay put while their points swap, so each distance is computed once per
/// iteration, and again only for a point that moves: the distance to its new site, which
/// its gain already computed).
#[derive(Clone, Copy)]
struct Member {
    k: u32,
    own: f64,
}

impl State {
    /// `n` random sites and `capacity` random points each, assigned at random.
    ///
    /// # Errors
    /// None in practice (the random sampler's own checks).
    ///
    /// # Panics
    /// As [`State::from_points`].
    pub fn new(n: usize, dims: usize, capacity: usize, seed: Seed) -> Result<State> {
        let mut sites = vec![0.0; n * dims];
        Random::draw(seed, &mut sites);
        let mut points = vec![0.0; n * capacity * dims];
        Random::draw(seed.derive(1), &mut points);
        // the points are independent of the sites: owning them in blocks is a random assignment
        Ok(State::from_points(dims, sites, points))
    }

    /// The sites (`dims` coordinates each, in [0, 1)) and points given, site s owning points
    /// s c, ..., (s + 1) c - 1 for c points per site (the points' count over the sites'
    /// count, rounded down; the rest belong to no site).
    ///
    /// # Panics
    /// `dims` outside 1..=4 (the sampler's dimensions).
    #[must_use]
    pub fn from_points(dims: usize, sites: Vec<f64>, points: Vec<f64>) -> State {
        assert!((1..=4).contains(&dims), "CCVT in {dims} dimensions: 1 to 4 are made");
        let n = sites.len() / dims;
        let capacity = (points.len() / dims).checked_div(n).unwrap_or(0);
        let members =
            (0..n).into_par_iter().map(|s| (s * capacity..(s + 1) * capacity).map(|k| Member { k: k as u32, own: 0.0 }).collect()).collect();
        State { dims, sites, points, members, spare: Vec::new() }
    }

    fn site(&self, s: usize) -> &[f64] {
        &self.sites[s * self.dims..(s + 1) * self.dims]
    }

    fn point(&self, k: u32) -> &[f64] {
        &self.points[k as usize * self.dims..(k as usize + 1) * self.dims]
    }

    /// The energy sum over points of the squared distance to their site.
    pub fn energy(&self) -> f64 {
        self.members.iter().enumerate().map(|(s, m)| m.iter().map(|p| distance2(self.point(p.k), self.site(s), true)).sum::<f64>()).sum()
    }

    /// How many points each site owns.
    pub fn counts(&self) -> Vec<usize> {
        self.members.iter().map(Vec::len).collect()
    }

    /// One iteration: swaps over every pair of neighbouring sites, then the sites to their
    /// centroids. Returns how many swaps it made.
    ///
    /// The pairs go in increasing order (i, j), each seeing its two sites' points as the
    /// pairs before it left them. Site i's pairs (i, j) are one task of a dataflow (the
    /// crate's `dataflow` module), which runs as soon as the latest earlier task of each of
    /// its sites is done: tasks that run together share no site, and each site meets its
    /// pairs in the same order, with the same points, as one pair after another. (A task
    /// per site keeps its points in the core's cache, where a task per pair did not; and
    /// levels of tasks with a barrier after each, 49 per iteration at 4096 sites, were
    /// about 5% slower on two threads than this dataflow: medians 1.17 s against 1.11 s,
    /// six runs each, 2026-11-28.)
    pub fn iterate(&mut self) -> usize {
        self.regroup();
        let members = take(&mut self.members);
        let members: Vec<Mutex<Vec<Member>>> = members
            .into_par_iter()
            .enumerate()
            .map(|(s, mut list)| {
                for p in &mut list {
                    p.own = distance2(self.point(p.k), self.site(s), true);
                }
                Mutex::new(list)
            })
            .collect();
        let n = members.len();
        let reach = 2.0 * (n as f64).powf(-1.0 / self.dims as f64);
        let grid = Grid::covering(&self.sites, self.dims, reach.min(0.5));
        // each site i's pairs (i, j), j increasing, as one task (its grid position's
        // neighbours; a small torus grid can meet one cell twice)
        let mut tasks: Vec<(usize, Vec<usize>)> = (0..grid.len())
            .into_par_iter()
            .filter_map(|q| {
                let i = grid.ids[q] as usize;
                let mut js = Vec::new();
                grid.near(q, 1, true, |cell| {
                    for r in cell {
                        let j = grid.ids[r] as usize;
                        if i < j && distance2(self.site(i), self.site(j), true) < reach * reach {
                            js.push(j);
                        }
                    }
                });
                js.sort_unstable();
                js.dedup();
                (!js.is_empty()).then_some((i, js))
            })
            .collect();
        tasks.par_sort_unstable_by_key(|&(i, _)| i);
        // each task waits for the latest earlier task of each of its sites
        let sites = |t: usize| std::iter::once(tasks[t].0).chain(tasks[t].1.iter().copied());
        let graph = crate::dataflow::Graph::new(n, tasks.len(), sites, sites);
        let swaps = AtomicUsize::new(0);
        let state = &*self;
        graph.run(|t| {
            // the points of each site, locked by the one task that holds the site
            let lock = |s: usize| members[s].lock().unwrap_or_else(PoisonError::into_inner);
            let (i, js) = &tasks[t];
            let mut mi = lock(*i);
            let swap = match state.dims {
                1 => State::swap::<1>,
                2 => State::swap::<2>,
                3 => State::swap::<3>,
                _ => State::swap::<4>, // from_points admits 1..=4
            };
            let mut scratch = [Vec::new(), Vec::new()];
            let count: usize = js.iter().map(|&j| swap(state, (*i, &mut mi), (j, &mut lock(j)), &mut scratch)).sum();
            swaps.fetch_add(count, Relaxed);
        });
        self.members = members.into_iter().map(|m| m.into_inner().unwrap_or_else(PoisonError::into_inner)).collect();
        let swaps = swaps.into_inner();
        let dims = self.dims;
        let moved: Vec<f64> = self
            .members
            .par_iter()
            .enumerate()
            .flat_map_iter(|(s, members)| {
                let mut mean = vec![0.0; dims];
                for p in members {
                    for ((m, &x), &c) in mean.iter_mut().zip(self.point(p.k)).zip(self.site(s)) {
                        *m += torus_gap(x, c);
                    }
                }
                let count = members.len() as f64;
                mean.into_iter().zip(self.site(s)).map(move |(m, &c)| wrap01(c + m / count))
            })
            .collect();
        self.sites = moved;
        swaps
    }

    /// Store each site's points together, in site order (the swaps scatter them; a site's
    /// points are then read from one stretch of memory), the sites in parallel.
    fn regroup(&mut self) {
        let d = self.dims;
        let mut points = take(&mut self.spare);
        let len = self.members.iter().map(Vec::len).sum::<usize>() * d;
        points.truncate(len);
        // the first time, its pages zeroed and faulted in by every thread
        points.par_extend(rayon::iter::repeat_n(0.0, len - points.len()));
        // each site's stretch of the new points, and the index of its first point
        let mut stretches = Vec::with_capacity(self.members.len());
        let (mut rest, mut first) = (points.as_mut_slice(), 0u32);
        for members in &self.members {
            let (mine, after) = rest.split_at_mut(members.len() * d);
            stretches.push((mine, first));
            (rest, first) = (after, first + members.len() as u32);
        }
        let old = &self.points;
        self.members.par_iter_mut().zip(stretches).for_each(|(members, (stretch, first))| {
            for ((p, to), k) in members.iter_mut().zip(stretch.chunks_exact_mut(d)).zip(first..) {
                to.copy_from_slice(&old[p.k as usize * d..(p.k as usize + 1) * d]);
                p.k = k;
            }
        });
        self.spare = std::mem::replace(&mut self.points, points);
    }

    /// Swap points between sites i and j (their points `mi` and `mj`) while the swap lowers
    /// the energy; D is the dimension (so that the distances unroll), `scratch` the two
    /// sides' lists of moves, reused from pair to pair.
    fn swap<const D: usize>(
        &self,
        (i, mi): (usize, &mut [Member]),
        (j, mj): (usize, &mut [Member]),
        scratch: &mut [Vec<Move>; 2],
    ) -> usize {
        // each point of a (its points `ma`) moving to b: its cached distance to a less its
        // distance to b; returns the best gain
        let moves = |list: &mut Vec<Move>, ma: &[Member], b: usize| -> f64 {
            let site: &[f64; D] = self.site(b).try_into().expect("D coordinates");
            list.clear();
            list.extend(ma.iter().enumerate().map(|(slot, p)| {
                let point: &[f64; D] = self.point(p.k).try_into().expect("D coordinates");
                let to = distance2(point, site, true);
                Move { gain: p.own - to, k: p.k, slot: slot as u32, to }
            }));
            list.iter().fold(f64::NEG_INFINITY, |m, x| m.max(x.gain))
        };
        let [from_i, from_j] = scratch;
        let (best_i, best_j) = (moves(from_i, mi, j), moves(from_j, mj, i));
        if best_i + best_j <= 0.0 {
            return 0;
        }
        // only a point whose gain beats the other side's best loss can take part; largest
        // gain first (ties: the lower point index), taken from a heap as they are needed
        from_i.retain(|x| x.gain + best_j > 0.0);
        from_j.retain(|x| x.gain + best_i > 0.0);
        let (mut hi, mut hj) = (BinaryHeap::from(take(from_i)), BinaryHeap::from(take(from_j)));
        let mut count = 0;
        while let (Some(a), Some(b)) = (hi.peek(), hj.peek()) {
            if a.gain + b.gain <= 0.0 {
                break;
            }
            mi[a.slot as usize] = Member { k: b.k, own: b.to };
            mj[b.slot as usize] = Member { k: a.k, own: a.to };
            hi.pop();
            hj.pop();
            count += 1;
        }
        (*from_i, *from_j) = (hi.into_vec(), hj.into_vec());
        count
    }
}

/// A point of one site moving to another: what it gains (its squared distance to the one
/// less that to the other), its index, its slot in the first site's list and its squared
/// distance to the other. Ordered by gain, then by the lower index first: no two points of
/// a site compare equal.
#[derive(Clone, Copy)]
struct Move {
    gain: f64,
    k: u32,
    slot: u32,
    to: f64,
}

impl Ord for Move {
    fn cmp(&self, other: &Move) -> std::cmp::Ordering {
        self.gain.total_cmp(&other.gain).then(other.k.cmp(&self.k))
    }
}

impl PartialOrd for Move {
    fn partial_cmp(&self, other: &Move) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for Move {
    fn eq(&self, other: &Move) -> bool {
        self.cmp(other).is_eq()
    }
}

impl Eq for Move {}

impl Construction for Ccvt {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let n = shape.n();
        if n.saturating_mul(self.capacity) > 1 << 28 {
            return Err(shape.invalid_count(format!("{n} sites x capacity {} points exceed 2^28", self.capacity)));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(self.units(), move |seed, out, progress| {
            me.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
        }))
    }
}

impl Ccvt {


    fn units(&self) -> u64 {
        self.iterations as u64
    }
    fn fill_reporting(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let mut state = State::new(n, dims, self.capacity, seed)?;
        for it in 0..self.iterations {
            if state.iterate() == 0 {
                // converged: the remaining iterations are done
                progress.advance((self.iterations - it) as u64)?;
                break;
            }
            progress.advance(1)?;
        }
        out.copy_from_slice(&state.sites);
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("ccvt", "capacity-constrained Voronoi tessellation: equal-capacity point swaps, on the torus")
        .aliases(&["capacity-constrained"])
        .params(&[
            ParamSpec {
                name: "capacity",
                kind: Kind::Int { min: 1, max: 1 << 16 },
                default: Default::Int(64),
                doc: "points per site (the cells' area resolution)",
            },
            ParamSpec {
                name: "iterations",
                kind: Kind::Int { min: 0, max: 100_000 },
                default: Default::Int(50),
                doc: "most swap-and-centre rounds (fewer when a round swaps nothing)",
            },
        ])
        .cite(&["balzer2009"]),
    counts: ANY,
    randomized: true,
    dims: "1..=4",
    build: |p| Ok(Box::new(Ccvt { capacity: p.int("capacity") as usize, iterations: p.int("iterations") as usize })),
}];
