//! The Sobol' sequence (Sobol' 1967) with Joe–Kuo direction numbers (Joe & Kuo 2008,
//! new-joe-kuo-6.21201, first 1024 dimensions, baked in by `build.rs`), 32-bit
//! resolution, at most 2^32 points; randomized by [`Randomization`]. The scrambled and
//! digitally shifted points are the centres of their 2^-32 cells ([`cell_centre`]), never 0.

use std::ops::RangeInclusive;

use crate::sampler::randomize::{randomized_families, shift};
use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::construct::scramble::{Randomization, owen_scramble_reversed};
use crate::construct::sobol::{SOBOL_REVERSED, SOBOL_DIRECTIONS, SOBOL_MAX_DIMS, sobol_u32};
use crate::construct::{cell_centre, unit};
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;
use crate::simd::wide;

/// Sobol' points in Gray-code order: coordinate j of point i is the XOR of the direction
/// numbers v_{j,k} for the set bits k of gray(i) = i ^ (i >> 1), read as a 32-bit binary
/// fraction (the order of Joe & Kuo's and scipy's generators; every prefix of 2^m points
/// is the same set as in natural order). The first 2^m points of
/// every pair of the first two dimensions form a (0,m,2)-net.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sobol {
    randomization: Randomization,
}

impl Sobol {
    /// A Sobol' sampler with the given randomization.
    pub fn new(randomization: Randomization) -> Self {
        Sobol { randomization }
    }
}

/// Per-dimension randomization state derived from the seed.
#[derive(Debug, Clone, Copy)]
struct DimKey {
    bits: u32,
}

impl DimKey {
    fn new(seed: Seed, dim: usize) -> Self {
        DimKey { bits: seed.derive(dim as u64).bits32() }
    }
}

impl Sobol {
    /// Randomize the raw digits `x` (given bit-reversed as `rev` for Owen) of one coordinate.
    #[inline]
    fn finish(&self, x: u32, key: DimKey) -> f64 {
        match self.randomization {
            Randomization::None => unit(x),
            Randomization::Xor => cell_centre(x ^ key.bits),
            Randomization::Owen => cell_centre(owen_scramble_reversed(x.reverse_bits(), key.bits).reverse_bits()),
            Randomization::Lms | Randomization::Shift => unreachable!("{}", UNDECLARED),
        }
    }
}

/// Walk the first `out.len() / dims` points in Gray-code order (Antonov & Saleev 1979), as
/// Joe & Kuo's and scipy's generators do: point i+1 is point i XOR v_c with c =
/// trailing_zeros(i+1). Only dimensions `first..first + count` of each point are written.
/// `reversed` keeps the state bit-reversed. `finish` maps a state word of dimension
/// `first + j` to the coordinate, given j.
#[inline(always)]
fn gray_walk(out: &mut [f64], dims: usize, first: usize, count: usize, reversed: bool, finish: impl Fn(u32, usize) -> f64) {
    let table: &[[u32; 32]] = if reversed { &SOBOL_REVERSED } else { &SOBOL_DIRECTIONS };
    let directions = &table[first..first + count];
    match (dims, count) {
        // fixed sizes let the compiler interleave the coordinates' work
        (1, 1) => walk_fixed::<1>(out, directions, &finish),
        (2, 2) => walk_fixed::<2>(out, directions, &finish),
        (3, 3) => walk_fixed::<3>(out, directions, &finish),
        _ => {
            let mut state = [0u32; CHUNK];
            for (i, p) in out.chunks_exact_mut(dims).enumerate() {
                for (j, x) in p[first..first + count].iter_mut().enumerate() {
                    *x = finish(state[j], j);
                }
                let c = (i as u64 + 1).trailing_zeros().min(31) as usize;
                for (s, v) in state.iter_mut().zip(directions) {
                    *s ^= v[c];
                }
            }
        }
    }
}

/// Dimensions walked at once beyond three: their state and keys live on the stack, so a
/// fill allocates nothing whatever its dimension.
const CHUNK: usize = 64;

/// Points walked per block: state(8j + k) = state(8j) ^ state(k) for k < 8, because
/// gray(8j + k) = gray(8j) ^ gray(k) and the digits are linear in the Gray code.
const BLOCK: usize = 8;

/// The walk for a fixed number of dimensions, a block of points at a time: each block's
/// coordinates are one loop over its lanes (the finishing hash and reversal vectorize), and
/// the state steps once per block.
#[inline(always)]
fn walk_fixed<const D: usize>(out: &mut [f64], directions: &[[u32; 32]], finish: &impl Fn(u32, usize) -> f64) {
    let v: [[u32; 32]; D] = std::array::from_fn(|d| directions[d]);
    let mut low = [[0u32; BLOCK]; D];
    for (low, v) in low.iter_mut().zip(&v) {
        for k in 1..BLOCK {
            low[k] = low[k - 1] ^ v[k.trailing_zeros() as usize];
        }
    }
    let mut state = [0u32; D];
    let first = out.len() / D / BLOCK * BLOCK;
    let mut blocks = out.chunks_exact_mut(BLOCK * D);
    for (j, block) in (&mut blocks).enumerate() {
        let mut x = [[0.0; BLOCK]; D];
        for d in 0..D {
            for k in 0..BLOCK {
                x[d][k] = finish(state[d] ^ low[d][k], d);
            }
        }
        for (k, p) in block.chunks_exact_mut(D).enumerate() {
            for d in 0..D {
                p[d] = x[d][k];
            }
        }
        // on from point 8j + 7 to point 8j + 8
        let c = ((j as u64 + 1) * BLOCK as u64).trailing_zeros().min(31) as usize;
        for d in 0..D {
            state[d] ^= low[d][BLOCK - 1] ^ v[d][c];
        }
    }
    for (i, p) in blocks.into_remainder().chunks_exact_mut(D).enumerate() {
        for d in 0..D {
            p[d] = finish(state[d], d);
        }
        let c = (first as u64 + i as u64 + 1).trailing_zeros().min(31) as usize;
        for d in 0..D {
            state[d] ^= v[d][c];
        }
    }
}

impl Construction for Sobol {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=SOBOL_MAX_DIMS
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        // the tables are the baked-in direction numbers: nothing to build
        Ok(Box::new(Planned { sobol: *self, dims: shape.dims() }))
    }
}

/// Sobol' points of a dimension.
#[derive(Debug)]
struct Planned {
    sobol: Sobol,
    dims: usize,
}

impl Planned {
    /// Dimensions `first..first + count` of every point, with `keys` the keys of those
    /// dimensions.
    #[inline(always)]
    fn walk(&self, out: &mut [f64], first: usize, keys: &[DimKey]) {
        let (dims, count) = (self.dims, keys.len());
        // compiled wide: a block's coordinates are computed in vector lanes
        wide(
            #[inline(always)]
            || match self.sobol.randomization {
                // Owen works in the bit-reversed domain: keep the state reversed, so each
                // coordinate costs one hash and one reversal
                Randomization::Owen => gray_walk(
                    out,
                    dims,
                    first,
                    count,
                    true,
                    #[inline(always)]
                    |x, j| cell_centre(owen_scramble_reversed(x, keys[j].bits).reverse_bits()),
                ),
                Randomization::None => gray_walk(
                    out,
                    dims,
                    first,
                    count,
                    false,
                    #[inline(always)]
                    |x, _| unit(x),
                ),
                Randomization::Xor => gray_walk(
                    out,
                    dims,
                    first,
                    count,
                    false,
                    #[inline(always)]
                    |x, j| cell_centre(x ^ keys[j].bits),
                ),
                Randomization::Lms | Randomization::Shift => unreachable!("{}", UNDECLARED),
            },
        );
    }
}

impl Prepared for Planned {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        // the keys of up to CHUNK dimensions at a time, on the stack
        let mut keys = [DimKey { bits: 0 }; CHUNK];
        let count = if self.dims <= 3 { self.dims } else { CHUNK };
        for first in (0..self.dims).step_by(count) {
            let keys = &mut keys[..count.min(self.dims - first)];
            for (j, k) in keys.iter_mut().enumerate() {
                *k = DimKey::new(seed, first + j);
            }
            self.walk(out, first, keys);
        }
        progress.advance(1)
    }

    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(SobolAccess { sobol: self.sobol, keys: (0..self.dims).map(|d| DimKey::new(seed, d)).collect() }))
    }

    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        Some(self.sobol.at(index, dim, DimKey::new(seed, dim)))
    }
}

/// Random access to a randomized Sobol' sequence: the per-dimension keys, drawn once.
#[derive(Debug)]
struct SobolAccess {
    sobol: Sobol,
    keys: Vec<DimKey>,
}

impl Access for SobolAccess {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        self.sobol.at(index, dim, self.keys[dim])
    }
}

impl Sobol {
    /// Coordinate `dim` of point `index` (in Gray-code order) under the dimension's key.
    fn at(&self, index: u64, dim: usize, key: DimKey) -> Result<f64> {
        let index = u32::try_from(index).map_err(|_| Error::Setting {
            name: "index",
            value: index.to_string(),
            reason: "32-bit Sobol' points stop at index 2^32 - 1".into(),
        })?;
        Ok(self.finish(sobol_u32(index ^ (index >> 1), dim), key))
    }
}

/// What a Sobol' construction never holds: no linear matrix scrambling is declared, and
/// `sobol.shift` is the plain sequence under the `+shift` stage's code ([`build`]).
const UNDECLARED: &str = "Sobol' declares no linear matrix scrambling, and its shift is the +shift stage's";

/// The construction of each entry.
fn build(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(shift::applied(randomization, |r| Box::new(Sobol::new(r))))
}

/// The samplers this file registers: Sobol' and its three randomizations.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!({
    family: "sobol",
    summary: "Sobol' sequence, Joe-Kuo directions",
    aliases: [],
    params: &[],
    counts: Counts::AtMost { most: 1 << 32, why: "32-bit Sobol' points stop at 2^32" },
    dims: "1..=1024",
    cite: ["sobol1967", "joe2008"],
    build: build,
    randomizations: [xor, owen, shift],
});
