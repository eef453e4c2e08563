//! The Sobol' sequence (Sobol' 1967) with Joe–Kuo direction numbers (Joe & Kuo 2008,
//! new-joe-kuo-6.21201, first 1024 dimensions, baked in by `build.rs`), 32-bit
//! resolution, at most 2^32 points; randomized by [`Randomization`].

use std::ops::RangeInclusive;

use super::registry::{SamplerEntry, randomized_entries};
use super::scramble::{Randomization, hash_unit, owen_scramble_reversed};
use super::{Access, Fill, Sampler, Sequence};
use crate::error::{Error, Result};
use crate::registry::About;
use crate::seed::{Seed, wrap01};
use crate::simd::wide;

include!(concat!(env!("OUT_DIR"), "/sobol_directions.rs"));

/// How many dimensions the baked-in table holds.
pub const SOBOL_MAX_DIMS: usize = SOBOL_DIRECTIONS.len();

const TO_UNIT: f64 = 1.0 / 4_294_967_296.0;

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

/// The unscrambled 32-bit digits of coordinate `dim` of Sobol' point `index` in natural
/// (not Gray-code) order.
#[inline]
pub fn sobol_u32(index: u32, dim: usize) -> u32 {
    let v = &SOBOL_DIRECTIONS[dim];
    let mut x = 0;
    let mut i = index;
    let mut k = 0;
    while i != 0 {
        if i & 1 == 1 {
            x ^= v[k];
        }
        i >>= 1;
        k += 1;
    }
    x
}

/// The 32 direction numbers of dimension `dim` (column k of its generating matrix, row 0
/// the most significant bit).
///
/// # Panics
/// When `dim` is not below [`SOBOL_MAX_DIMS`].
pub fn direction_numbers(dim: usize) -> [u32; 32] {
    SOBOL_DIRECTIONS[dim]
}

/// Per-dimension randomization state derived from the seed.
#[derive(Debug, Clone, Copy)]
struct DimKey {
    bits: u32,
    shift: f64,
}

impl DimKey {
    fn new(seed: Seed, dim: usize) -> Self {
        let s = seed.derive(dim as u64);
        DimKey { bits: s.bits32(), shift: hash_unit(dim as u64, s.0) }
    }
}

impl Sobol {
    /// Randomize the raw digits `x` (given bit-reversed as `rev` for Owen) of one coordinate.
    #[inline]
    fn finish(&self, x: u32, key: DimKey) -> f64 {
        match self.randomization {
            Randomization::None => f64::from(x) * TO_UNIT,
            Randomization::Xor => f64::from(x ^ key.bits) * TO_UNIT,
            Randomization::Owen => {
                f64::from(owen_scramble_reversed(x.reverse_bits(), key.bits).reverse_bits()) * TO_UNIT
            }
            Randomization::Shift => wrap01(f64::from(x) * TO_UNIT + key.shift),
        }
    }
}

/// The direction numbers bit-reversed, for Owen scrambling's reversed domain (computed once,
/// so that many small fills, as a renderer's per-pixel patterns, pay nothing per call).
static REVERSED_DIRECTIONS: std::sync::LazyLock<Vec<[u32; 32]>> =
    std::sync::LazyLock::new(|| SOBOL_DIRECTIONS.iter().map(|v| v.map(u32::reverse_bits)).collect());

/// Walk the first `out.len() / dims` points in Gray-code order (Antonov & Saleev 1979), as
/// Joe & Kuo's and scipy's generators do: point i+1 is point i XOR v_c with c =
/// trailing_zeros(i+1). `reversed` keeps the state bit-reversed. `finish` maps a state
/// word of dimension d to the coordinate.
#[inline(always)]
fn gray_walk(out: &mut [f64], dims: usize, reversed: bool, finish: impl Fn(u32, usize) -> f64) {
    let directions: &[[u32; 32]] = if reversed { &REVERSED_DIRECTIONS[..dims] } else { &SOBOL_DIRECTIONS[..dims] };
    match dims {
        // fixed sizes let the compiler interleave the coordinates' work
        1 => walk_fixed::<1>(out, directions, &finish),
        2 => walk_fixed::<2>(out, directions, &finish),
        3 => walk_fixed::<3>(out, directions, &finish),
        _ => {
            let mut state = vec![0u32; dims];
            for (i, p) in out.chunks_exact_mut(dims).enumerate() {
                for (d, x) in p.iter_mut().enumerate() {
                    *x = finish(state[d], d);
                }
                let c = (i as u64 + 1).trailing_zeros().min(31) as usize;
                for (s, v) in state.iter_mut().zip(directions) {
                    *s ^= v[c];
                }
            }
        }
    }
}

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

impl Sampler for Sobol {
    fn spec(&self) -> String {
        match self.randomization {
            Randomization::None => "sobol".into(),
            r => format!("sobol.{}", r.suffix()),
        }
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=SOBOL_MAX_DIMS
    }
    fn as_sequence(&self) -> Option<&dyn Sequence> {
        Some(self)
    }
}

impl Fill for Sobol {
    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        if n as u64 > 1 << 32 {
            return Err(Error::InvalidCount {
                sampler: self.spec(),
                n,
                dims,
                reason: "32-bit Sobol' points stop at 2^32".into(),
            });
        }
        Ok(())
    }
    fn fill(&self, _n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        // keys on the stack for the usual few dimensions: small fills stay allocation-free
        let mut few = [DimKey { bits: 0, shift: 0.0 }; 4];
        let many: Vec<DimKey>;
        let keys: &[DimKey] = if dims <= few.len() {
            for (d, k) in few.iter_mut().enumerate().take(dims) {
                *k = DimKey::new(seed, d);
            }
            &few[..dims]
        } else {
            many = (0..dims).map(|d| DimKey::new(seed, d)).collect();
            &many
        };
        // compiled wide: a block's coordinates are computed in vector lanes
        wide(
            #[inline(always)]
            || match self.randomization {
                // Owen works in the bit-reversed domain: keep the state reversed, so each
                // coordinate costs one hash and one reversal
                Randomization::Owen => gray_walk(
                    out,
                    dims,
                    true,
                    #[inline(always)]
                    |x, d| f64::from(owen_scramble_reversed(x, keys[d].bits).reverse_bits()) * TO_UNIT,
                ),
                Randomization::None => gray_walk(
                    out,
                    dims,
                    false,
                    #[inline(always)]
                    |x, _| f64::from(x) * TO_UNIT,
                ),
                Randomization::Xor => gray_walk(
                    out,
                    dims,
                    false,
                    #[inline(always)]
                    |x, d| f64::from(x ^ keys[d].bits) * TO_UNIT,
                ),
                Randomization::Shift => gray_walk(
                    out,
                    dims,
                    false,
                    #[inline(always)]
                    |x, d| wrap01(f64::from(x) * TO_UNIT + keys[d].shift),
                ),
            },
        );
        Ok(())
    }
}

impl Sequence for Sobol {
    fn access(&self, dims: usize, seed: Seed) -> Result<Box<dyn Access + '_>> {
        (self as &dyn Sampler).plan(1, dims)?;
        Ok(Box::new(SobolAccess { sobol: self, keys: (0..dims).map(|d| DimKey::new(seed, d)).collect() }))
    }
}

/// Random access to a randomized Sobol' sequence: the per-dimension keys, drawn once.
#[derive(Debug)]
struct SobolAccess<'a> {
    sobol: &'a Sobol,
    keys: Vec<DimKey>,
}

impl Access for SobolAccess<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        let index = u32::try_from(index).map_err(|_| Error::Setting {
            name: "index",
            value: index.to_string(),
            reason: "32-bit Sobol' points stop at index 2^32 - 1".into(),
        })?;
        Ok(self.sobol.finish(sobol_u32(index ^ (index >> 1), dim), self.keys[dim]))
    }
}

/// The samplers this file registers: Sobol' and its three randomizations.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_entries!((
    Sobol,
    "sobol",
    "Sobol' sequence, Joe-Kuo directions",
    "n <= 2^32 (nets at powers of two)",
    "1..=1024",
    ["sobol1967", "joe2008"]
));
