//! The sampler of Heitz, Belcour, Ostromoukhov, Coeurjolly & Iehl 2019 ("A low-discrepancy
//! sampler that distributes Monte Carlo errors as a blue noise in screen space"): every
//! pixel draws the same Owen-scrambled Sobol' points, under two keys per pixel and pair of
//! dimensions read from a tile that covers the screen:
//! - a scrambling key, XORed into the digits of the pair's coordinates (a digital shift:
//!   each pixel's points stay a net);
//! - a ranking key, XORed into the sample index below the sample count (the pixel's first
//!   2^j samples, j <= m, stay an aligned block of the sequence: a net at every power of two).
//!
//! The keys are optimized by samplab for the film's sample count, against test integrands
//! (256 random Heaviside steps in the pair's square; samplab's choice): the pixels' error
//! vectors e_p on them should look like blue noise, which samplab states as the power of
//! the error image after a Gaussian blur g of 1.5 pixels, sum_p |(g * e)_p|^2 (the
//! perceptual error of Chizhov et al. 2022; g truncated at 4 pixels and the energy written with its
//! exact autocorrelation, so it is a sum of squares). Scrambling keys are first swapped
//! between pixels within the energy's reach when a swap lowers it (64 sweeps), then each
//! pixel may trade its key for the best of a few fresh random ones (four sweeps); last, each pixel's
//! ranking key is the one, of all spp, that lowers the summed energies of its prefixes
//! 1, 2, 4, .. spp/2 (each level's energy divided by its mean error power; two sweeps).
//! The errors are against the steps' exact integrals (the clipped square's area).
//!
//! Preparing costs about 3.7 s for 8 dimensions at 16 spp on a 64 x 64 tile, 19 s at
//! 256 spp (two cores, 2026-11-27); the tile is no larger than the film needs.
//!
//! The base scramble is fixed by the seed (the keys are optimized against it); frames move
//! the tile by a hashed toroidal offset. Dimensions past `optimized` get hashed keys per
//! pixel (white noise).

use rayon::prelude::*;

use crate::construct::sobol::{ByteTables, byte_tables, owen_digits, reversed_digits};
use super::{Family, Film, Keys, PixelEntry, PixelSampler, rekey, Mapping, MappingKind};
use crate::construct::unit;
use crate::error::Result;
use crate::integrand::{HalfPlane, Integrand};
use crate::progress::Progress;
use crate::registry::About;
use crate::construct::Counts;
use crate::construct::sobol::SOBOL_MAX_DIMS;
use crate::seed::{Seed, mix64};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The largest sample count (the paper's tables are for 256).
const MAX_SPP: u32 = 256;

/// Test integrands per pair of dimensions.
const INTEGRANDS: usize = 256;

/// The standard deviation of the Gaussian blur whose output's power the keys minimize, in
/// pixels.
const SIGMA_BLUR: f32 = 1.5;

/// The blur's truncation radius, in pixels (its weight beyond is below 0.012).
const BLUR_RADIUS: i32 = 4;

/// Sweeps of swap proposals (one per pixel each) for the scrambling keys, and how far a
/// swap partner may lie (as far as the energy reaches).
const SWAP_SWEEPS: usize = 64;
const SWAP_RADIUS: u32 = 2 * BLUR_RADIUS as u32;

/// Sweeps over the pixels trading a key for the best of fresh random candidates, and the
/// samples all candidates of one visit may take (16 candidates at 16 spp, 1 at 256).
const REFINE_SWEEPS: usize = 4;
const REFINE_SAMPLES: usize = 256;

/// Sweeps over the pixels for the ranking keys (each tries every key).
const RANK_SWEEPS: usize = 2;

const TILE: ParamSpec = ParamSpec {
    name: "tile",
    kind: Kind::Int { min: 16, max: 256 },
    default: Default::Int(64),
    doc: "side of the tile of optimized keys, in pixels (it repeats over the screen)",
};

const OPTIMIZED: ParamSpec = ParamSpec {
    name: "optimized",
    kind: Kind::Int { min: 0, max: 32 },
    default: Default::Int(8),
    doc: "how many dimensions (from 0, in pairs) get optimized keys; the rest hashed keys (white noise)",
};

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "heitz2019",
        "Heitz et al. 2019: one Owen-scrambled Sobol' sequence, per-pixel scrambling and ranking keys \
         optimized so that the errors of neighbouring pixels differ (blue-noise error in screen space)",
    )
    .aliases(&["heitz", "bluenoise.sobol"])
    .params(&[TILE, OPTIMIZED])
    .cite(&["heitz2019", "chizhov2022", "burley2020"]),
    spp: Counts::Listed {
        rule: "spp a power of two up to 256 (the keys are optimized for it)",
        list: |_, _| Box::new((0..=MAX_SPP.trailing_zeros()).map(|k| 1usize << k)),
    },
    dims_note: "the Joe-Kuo table",
    max_dims: SOBOL_MAX_DIMS as u32,
    mapping: Mapping {
        kind: MappingKind::ScreenOrder,
        family: "sobol",
        how: "keys from a tile: sample i of pixel p, dimension d, is Owen-Sobol' point \
              i XOR rank(p, d/2), its digits XOR scramble(p, d); the keys of the first `optimized` \
              dimensions optimized for the film's spp by samplab (swaps of scrambling keys, trades for fresh ones, then a \
              choice of ranking keys, against Heaviside test integrands), the tile offset per frame",
    },
    build,
}];

/// A counter-based stream of random words.
struct Stream(u64, u64);

impl Stream {
    fn next(&mut self) -> u64 {
        self.1 += 1;
        mix64(self.0 ^ self.1.wrapping_mul(0x9E37_79B9_7F4A_7C15))
    }
    fn below(&mut self, n: u32) -> u32 {
        (((self.next() >> 32) * u64::from(n)) >> 32) as u32
    }
    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The optimized keys of one pair of dimensions over the tile: per tile pixel, the
/// scrambling keys of both coordinates and the ranking key.
#[derive(Debug)]
struct PairKeys {
    scramble: Vec<[u32; 2]>,
    rank: Vec<u32>,
}

#[derive(Debug)]
pub(crate) struct Heitz {
    keys: Keys,
    tables: Vec<ByteTables>,
    /// The base Owen scramble of each dimension.
    owen: Vec<u32>,
    side: u32,
    rank_mask: u32,
    pairs: Vec<PairKeys>,
}

fn build(p: &Params, film: Film, seed: Seed, progress: &Progress<'_>) -> Result<Family> {
    // a tile no larger than the film needs (and at least 16: the energy's reach)
    let side = (p.int("tile") as u32).min(film.width.max(film.height).max(16));
    let optimized = (p.int("optimized") as u32).min(film.dims).div_ceil(2);
    let tables: Vec<ByteTables> = (0..film.dims as usize).map(byte_tables).collect();
    let owen: Vec<u32> = (0..film.dims).map(|d| seed.derive_str("heitz base").derive(u64::from(d)).0 as u32).collect();
    let spp = film.spp;
    let pairs = (0..optimized)
        .into_par_iter()
        .map(|pair| {
            let coordinate = |d: u32, i: u32| {
                let d = (2 * pair + d).min(film.dims - 1) as usize;
                owen_digits(reversed_digits(&tables[d], i), owen[d])
            };
            let points: Vec<[u32; 2]> = (0..spp).map(|i| [coordinate(0, i), coordinate(1, i)]).collect();
            optimize(&points, side, seed.derive_str("heitz keys").derive(u64::from(pair)), progress)
        })
        .collect::<Result<_>>()?;
    Ok(Family::from(Heitz { keys: Keys::new(seed, film.dims), tables, owen, side, rank_mask: spp - 1, pairs }))
}

impl Heitz {
    #[inline(always)]
    fn value(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        let pair = (dim / 2) as usize;
        let (rank, key) = match self.pairs.get(pair) {
            Some(keys) => {
                let offset = self.keys.frame(frame);
                let x = pixel[0].wrapping_add(offset as u32) % self.side;
                let y = pixel[1].wrapping_add((offset >> 32) as u32) % self.side;
                let t = (y * self.side + x) as usize;
                (keys.rank[t], keys.scramble[t][(dim & 1) as usize])
            }
            // hashed keys: one rank for the pair, and a scramble of each dimension hashed
            // on its own (two scrambles drawn from one word are related, and their joint
            // shift then leaves the estimates biased)
            None => {
                let h = self.keys.pixel(pixel, frame);
                ((rekey(h, u64::from(dim | 1) << 32) >> 32) as u32, rekey(h, u64::from(dim)) as u32)
            }
        };
        let i = index ^ (rank & self.rank_mask);
        unit(owen_digits(reversed_digits(&self.tables[dim as usize], i), self.owen[dim as usize]) ^ key)
    }
}

impl PixelSampler for Heitz {
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        self.value(pixel, frame, index, dim)
    }
}

/// The energy's neighbourhood: offsets q - p and weights K(q - p), K the autocorrelation
/// of the Gaussian blur of [`SIGMA_BLUR`] pixels truncated at [`BLUR_RADIUS`] (an exact
/// autocorrelation, so the energy is a sum of squares, never negative), scaled to
/// K(0) = 1, without the centre.
fn neighbourhood() -> Vec<(i32, i32, f32)> {
    let r = BLUR_RADIUS;
    let g = |dx: i32, dy: i32| {
        if dx.abs() > r || dy.abs() > r { 0.0 } else { (-((dx * dx + dy * dy) as f32) / (2.0 * SIGMA_BLUR * SIGMA_BLUR)).exp() }
    };
    let k = |ux: i32, uy: i32| -> f32 {
        (-r..=r).flat_map(|vy| (-r..=r).map(move |vx| (vx, vy))).map(|(vx, vy)| g(vx, vy) * g(vx + ux, vy + uy)).sum()
    };
    let k0 = k(0, 0);
    (-2 * r..=2 * r)
        .flat_map(|dy| (-2 * r..=2 * r).map(move |dx| (dx, dy)))
        .filter(|&d| d != (0, 0))
        .map(|(dx, dy)| (dx, dy, k(dx, dy) / k0))
        .collect()
}

/// Error vectors of the tile's pixels on the test integrands (a row of [`INTEGRANDS`] per
/// pixel), and their blurred field without the centre: `blurred[p] = sum_q K(p - q) e_q`
/// over the neighbourhood, which the energy's changes are read from.
struct Field<'a> {
    side: i32,
    near: &'a [(i32, i32, f32)],
    rows: Vec<f32>,
    blurred: Vec<f32>,
}

impl<'a> Field<'a> {
    fn new(rows: Vec<f32>, side: u32, near: &'a [(i32, i32, f32)]) -> Field<'a> {
        let mut f = Field { side: side as i32, near, blurred: vec![0.0; rows.len()], rows: vec![0.0; rows.len()] };
        for (p, row) in rows.chunks(INTEGRANDS).enumerate() {
            f.set(p, row);
        }
        f
    }
    fn row(&self, p: usize) -> &[f32] {
        &self.rows[p * INTEGRANDS..][..INTEGRANDS]
    }
    fn blurred(&self, p: usize) -> &[f32] {
        &self.blurred[p * INTEGRANDS..][..INTEGRANDS]
    }
    /// The tile pixel at (dx, dy) from `p`, on the torus.
    fn at(&self, p: usize, dx: i32, dy: i32) -> usize {
        let s = self.side;
        let (x, y) = ((p as i32 % s + dx).rem_euclid(s), (p as i32 / s + dy).rem_euclid(s));
        (y * s + x) as usize
    }
    /// Give pixel `p` the error vector `row`, updating its neighbours' blurred field.
    fn set(&mut self, p: usize, row: &[f32]) {
        let delta: Vec<f32> = row.iter().zip(self.row(p)).map(|(a, b)| a - b).collect();
        for &(dx, dy, w) in self.near {
            let q = self.at(p, dx, dy);
            for (b, d) in self.blurred[q * INTEGRANDS..][..INTEGRANDS].iter_mut().zip(&delta) {
                *b += w * d;
            }
        }
        self.rows[p * INTEGRANDS..][..INTEGRANDS].copy_from_slice(row);
    }
    /// The mean squared norm of the error vectors.
    fn power(&self) -> f32 {
        dot(&self.rows, &self.rows) / (self.rows.len() / INTEGRANDS) as f32
    }
}

fn dot(a: &[f32], b: &[f32]) -> f32 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Random Heaviside steps in the unit square: the indicator of the side of a random line
/// (a uniform direction through a uniform point) that the normal points to, n . x + c > 0,
/// kept as columns (n_x, n_y, c) so that a point meets all of them in vector instructions.
struct Steps {
    nx: [f32; INTEGRANDS],
    ny: [f32; INTEGRANDS],
    c: [f32; INTEGRANDS],
    /// Their integrals over the unit square.
    exact: Vec<f32>,
}

impl Steps {
    fn new(stream: &mut Stream) -> Steps {
        let mut s =
            Steps { nx: [0.0; INTEGRANDS], ny: [0.0; INTEGRANDS], c: [0.0; INTEGRANDS], exact: vec![0.0; INTEGRANDS] };
        for t in 0..INTEGRANDS {
            let angle = std::f32::consts::TAU * stream.unit();
            let (cx, cy) = (stream.unit(), stream.unit());
            (s.nx[t], s.ny[t]) = (angle.cos(), angle.sin());
            s.c[t] = -(s.nx[t] * cx + s.ny[t] * cy);
            let step = HalfPlane::new([f64::from(s.nx[t]), f64::from(s.ny[t])], [f64::from(cx), f64::from(cy)]);
            s.exact[t] = step.exact() as f32;
        }
        s
    }
    /// Add the steps' values at `point` (32-bit fixed point) to `out`.
    #[inline]
    fn add(&self, point: [u32; 2], out: &mut [f32]) {
        let (x, y) = (unit(point[0]) as f32, unit(point[1]) as f32);
        for (o, ((nx, ny), c)) in out[..INTEGRANDS].iter_mut().zip(self.nx.iter().zip(&self.ny).zip(&self.c)) {
            *o += if nx * x + ny * y + c > 0.0 { 1.0 } else { 0.0 };
        }
    }
}

/// The optimized keys of one pair: `points` are the pair's base points (the film's spp).
/// Pixels an optimizing sweep visits between two looks at the stop flag.
const CHECK: usize = 64;

/// (Stops within a sweep once `progress` says so.)
fn optimize(points: &[[u32; 2]], side: u32, seed: Seed, progress: &Progress<'_>) -> Result<PairKeys> {
    let mut stream = Stream(seed.0, 0);
    let n = (side * side) as usize;
    let spp = points.len();
    let steps = Steps::new(&mut stream);
    let mut scramble: Vec<[u32; 2]> = (0..n).map(|_| [stream.next() as u32, stream.next() as u32]).collect();
    let mut rank: Vec<u32> = (0..n).map(|_| stream.below(spp as u32)).collect();
    let near = neighbourhood();
    let shifted = |p: [u32; 2], key: [u32; 2]| [p[0] ^ key[0], p[1] ^ key[1]];
    // Each pixel's errors are its estimates less the exact integrals (the tile's mean
    // estimate in place of the integrals let key trades bias the tile)

    // scrambling keys: swaps that lower the energy of the full sample count. Swapping the
    // error vectors a, b of p and q changes sum_p |(g * e)_p|^2 by
    // 2 <b - a, B_p - B_q> - 2 K(p - q) |a - b|^2, B the blurred field without centres.
    let mut rows = vec![0.0f32; n * INTEGRANDS];
    for (p, (row, key)) in rows.chunks_mut(INTEGRANDS).zip(&scramble).enumerate() {
        if p % CHECK == 0 {
            progress.check()?;
        }
        points.iter().for_each(|&p| steps.add(shifted(p, *key), row));
        row.iter_mut().for_each(|v| *v /= spp as f32);
    }
    let mean = &steps.exact;
    for row in rows.chunks_mut(INTEGRANDS) {
        row.iter_mut().zip(mean).for_each(|(v, m)| *v -= m);
    }
    let mut field = Field::new(rows, side, &near);
    for _ in 0..SWAP_SWEEPS {
        for p in 0..n {
            if p % CHECK == 0 {
                progress.check()?;
            }
            let (dx, dy) = (stream.below(2 * SWAP_RADIUS + 1) as i32, stream.below(2 * SWAP_RADIUS + 1) as i32);
            let q = field.at(p, dx - SWAP_RADIUS as i32, dy - SWAP_RADIUS as i32);
            if q == p {
                continue;
            }
            // the kernel's offsets reach as far as a swap partner: K(q - p) by offset
            let w = near[(dy as usize * (2 * SWAP_RADIUS as usize + 1) + dx as usize)
                - usize::from((dy, dx) > (SWAP_RADIUS as i32, SWAP_RADIUS as i32))]
            .2;
            let (a, b, bp, bq) = (field.row(p), field.row(q), field.blurred(p), field.blurred(q));
            let (mut across, mut apart) = (0.0f32, 0.0f32);
            for t in 0..INTEGRANDS {
                let d = b[t] - a[t];
                across += d * (bp[t] - bq[t]);
                apart += d * d;
            }
            if across < w * apart {
                let (a, b) = (a.to_vec(), b.to_vec());
                field.set(p, &b);
                field.set(q, &a);
                scramble.swap(p, q);
            }
        }
    }
    // then each pixel may trade its key for a fresh random one that fits its neighbours
    // better: pixel p's part of the energy with error vector e is |e|^2 + 2 <e, B_p>
    let mut row = vec![0.0f32; INTEGRANDS];
    for _ in 0..REFINE_SWEEPS {
        for (p, current) in scramble.iter_mut().enumerate() {
            if p % CHECK == 0 {
                progress.check()?;
            }
            let cost = |e: &[f32]| dot(e, e) + 2.0 * dot(e, field.blurred(p));
            let mut best = (cost(field.row(p)), None);
            for _ in 0..(REFINE_SAMPLES / spp).max(1) {
                let key = [stream.next() as u32, stream.next() as u32];
                row.fill(0.0);
                points.iter().for_each(|&point| steps.add(shifted(point, key), &mut row));
                row.iter_mut().zip(mean).for_each(|(v, m)| *v = *v / spp as f32 - m);
                let c = cost(&row);
                if c < best.0 {
                    best = (c, Some((key, row.clone())));
                }
            }
            if let (_, Some((key, e))) = best {
                *current = key;
                field.set(p, &e);
            }
        }
    }

    // ranking keys: the prefixes 1, 2, 4, .. spp/2 of each pixel, each level's energy
    // divided by its mean error power
    let levels = spp.trailing_zeros() as usize;
    if levels == 0 {
        return Ok(PairKeys { scramble, rank });
    }
    // each pixel's sums over aligned blocks of 2^j samples, j < levels: block b of level j
    // at tree[(offsets[j] + b) * INTEGRANDS ..]
    let offsets: Vec<usize> = (0..levels).scan(0, |o, j| Some(std::mem::replace(o, *o + (spp >> j)))).collect();
    let tree = |p: usize| -> Vec<f32> {
        let mut tree = vec![0.0f32; 2 * spp * INTEGRANDS];
        for (i, &point) in points.iter().enumerate() {
            steps.add(shifted(point, scramble[p]), &mut tree[i * INTEGRANDS..][..INTEGRANDS]);
        }
        for j in 1..levels {
            for b in 0..spp >> j {
                for t in 0..INTEGRANDS {
                    tree[(offsets[j] + b) * INTEGRANDS + t] = tree[(offsets[j - 1] + 2 * b) * INTEGRANDS + t]
                        + tree[(offsets[j - 1] + 2 * b + 1) * INTEGRANDS + t];
                }
            }
        }
        tree
    };
    // the error vector of prefix 2^j for ranking key r: the block holding r, less the mean
    let prefix = |tree: &[f32], j: usize, r: u32, mean: &[f32]| -> Vec<f32> {
        let block = &tree[(offsets[j] + (r as usize >> j)) * INTEGRANDS..][..INTEGRANDS];
        block.iter().zip(mean).map(|(v, m)| v / (1usize << j) as f32 - m).collect()
    };
    let mut fields: Vec<(Vec<f32>, f32, Field)> = Vec::with_capacity(levels);
    for j in 0..levels {
        let mean = steps.exact.clone();
        let mut rows: Vec<f32> = Vec::with_capacity(n * INTEGRANDS);
        for (p, &r) in rank.iter().enumerate() {
            if p % CHECK == 0 {
                progress.check()?;
            }
            rows.extend(prefix(&tree(p), j, r, &mean));
        }
        let field = Field::new(rows, side, &near);
        let scale = 1.0 / field.power().max(f32::MIN_POSITIVE);
        fields.push((mean, scale, field));
    }
    for _ in 0..RANK_SWEEPS {
        for (p, current) in rank.iter_mut().enumerate() {
            if p % CHECK == 0 {
                progress.check()?;
            }
            // pixel p's part of the energy with error vector e at level j is
            // |e|^2 + 2 <e, B_p>; a key's cost adds its blocks' at every level
            let tree = tree(p);
            let blocks: Vec<Vec<f32>> = fields
                .iter()
                .enumerate()
                .map(|(j, (mean, scale, field))| {
                    let (bp, inv) = (field.blurred(p), 1.0 / (1usize << j) as f32);
                    (0..spp >> j)
                        .map(|b| {
                            let block = &tree[(offsets[j] + b) * INTEGRANDS..][..INTEGRANDS];
                            let mut c = 0.0;
                            for t in 0..INTEGRANDS {
                                let e = block[t] * inv - mean[t];
                                c += e * (e + 2.0 * bp[t]);
                            }
                            scale * c
                        })
                        .collect()
                })
                .collect();
            let cost = |r: u32| -> f32 { blocks.iter().enumerate().map(|(j, b)| b[r as usize >> j]).sum() };
            let best = (0..spp as u32).map(|r| (cost(r), r)).fold((f32::INFINITY, 0), |a, b| if b.0 < a.0 { b } else { a });
            if best.1 != *current {
                *current = best.1;
                for (j, (mean, _, field)) in fields.iter_mut().enumerate() {
                    let e = prefix(&tree, j, best.1, mean);
                    field.set(p, &e);
                }
            }
        }
    }
    Ok(PairKeys { scramble, rank })
}
