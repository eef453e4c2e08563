//! Progressive multi-jittered (0,2) sequences per pixel (Christensen, Kensler & Kilpatrick
//! 2018, made by Helmer, Christensen & Kensler 2021's stochastic construction), padded by
//! pairs of dimensions from a pool of independent sequences, as pbrt-v4's `PMJ02BNSampler`
//! pads; `pmj02.bn` adds a blue-noise shift per pixel.

use super::dither::{MASK, Shifts};
use super::{Family, Film, Pairs, PixelEntry, Keys, rekey, unit};
use crate::error::Result;
use crate::registry::About;
use crate::sampler::randomize::scramble::{owen_scramble_reversed, permute};
use crate::sampler::stratified::pmj::pmj02_digits;
use crate::seed::Seed;
use crate::spec::Params;

/// Sequences in the pool.
const POOL: usize = 16;

/// The largest spp: the pool holds [`POOL`] sequences of at most this many points.
const MOST: u64 = 1 << 16;

pub(crate) static ENTRIES: &[PixelEntry] = &[
    PixelEntry {
        about: About::new(
            "pmj02",
            "pmj02 per pixel: each pair of dimensions one of 16 pmj02 sequences, its samples permuted \
             and digitally shifted by a hash of (seed, pixel, frame, pair)",
        )
        .aliases(&["pixel.pmj02"])
        .cite(&["christensen2018", "helmer2021", "pharr2023"]),
        spp: super::Counts::AtMost { most: MOST, why: "the pool holds 16 sequences of at most 2^16 points" },
        dims: "any (pairs of 2D pmj02)",
        max_dims: super::MAX_DIMS,
        mapping: "dimension padding: dimensions 2k, 2k+1 take sequence h mod 16 of the pool, sample \
                  pi(i) of its first spp (pi a nested uniform scramble of the index for a power-of-two spp, \
                  so that every prefix of 2^j samples is a net; a hashed permutation otherwise), XOR-ed \
                  with hashed digits (a digital shift, which keeps every (0,m,2)-net a net), h a hash of \
                  (seed, pixel, frame, k)",
        build: build_plain,
    },
    PixelEntry {
        about: About::new(
            "pmj02.bn",
            "pmj02 with blue-noise pixel shifts: pair k of every pixel is pool sequence k mod 16, its \
             samples permuted per pixel and toroidally shifted by a void-and-cluster mask",
        )
        .aliases(&["pmj02bn"])
        .params(&[MASK])
        .cite(&["christensen2018", "helmer2021", "georgiev2016", "ulichney1993", "pharr2023"]),
        spp: super::Counts::AtMost { most: MOST, why: "the pool holds 16 sequences of at most 2^16 points" },
        dims: "any (pairs of 2D pmj02)",
        max_dims: super::MAX_DIMS,
        mapping: "screen-space mask: as pbrt-v4's PMJ02BNSampler, the pair's sequence is shared by all \
                  pixels, its samples permuted per pixel, then shifted modulo 1 by the pixel's \
                  blue-noise value (the mask shifted by a hash of frame and pair)",
        build: build_bn,
    },
];

#[derive(Debug)]
pub(crate) struct Pmj {
    keys: Keys,
    spp: u32,
    /// The pool's sequences one after the other, `spp` points each; for a power-of-two
    /// spp each sequence is stored in bit-reversed order of its index (see [`Pmj::pair`]).
    pool: Vec<[u32; 2]>,
    /// The blue-noise shifts (`pmj02.bn`); none for `pmj02`, which shifts digits by hashes.
    shifts: Option<Shifts>,
}

fn pool(film: Film, seed: Seed) -> Vec<[u32; 2]> {
    let base = seed.derive_str("pmj02 pool");
    let spp = film.spp as usize;
    (0..POOL)
        .flat_map(|k| {
            let points = pmj02_digits(spp, base.derive(k as u64));
            if spp.is_power_of_two() {
                let bits = spp.ilog2();
                // position v holds sample reverse(v) (on log2 spp bits): the draws then read
                // the scrambled index in the reversed domain, where it is computed
                (0..spp).map(|v| points[v.reverse_bits().checked_shr(usize::BITS - bits).unwrap_or(0)]).collect()
            } else {
                points
            }
        })
        .collect()
}

fn build_plain(_: &Params, film: Film, seed: Seed) -> Result<Family> {
    Ok(Family::from(Pmj { keys: Keys::new(seed, 0), spp: film.spp, pool: pool(film, seed), shifts: None }))
}

fn build_bn(p: &Params, film: Film, seed: Seed) -> Result<Family> {
    let shifts = Some(Shifts::new(p.int("mask") as usize, seed, film.dims.div_ceil(2))?);
    Ok(Family::from(Pmj { keys: Keys::new(seed, 0), spp: film.spp, pool: pool(film, seed), shifts }))
}

/// [`permute`] as a call: its cycle-walking loop, inlined into the power-of-two path's
/// draws, slowed them.
#[inline(never)]
fn permute_out_of_line(i: u32, len: u32, key: u32) -> u32 {
    permute(i, len, key)
}

impl Pairs for Pmj {
    /// The pixel's key, and the sample index's 16 bits reversed (shared by the pairs).
    type Key = (u64, u32);

    #[inline(always)]
    fn key(&self, pixel: [u32; 2], frame: u32, index: u32) -> (u64, u32) {
        (self.keys.pixel(pixel, frame), (index & (self.spp - 1)).reverse_bits() >> 16)
    }

    #[inline(always)]
    fn pair(&self, (key, reversed): (u64, u32), pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 2] {
        let pair = dim / 2;
        let key = rekey(key, u64::from(pair));
        let i = if self.spp.is_power_of_two() {
            // a nested uniform scramble of the index (Burley 2020, section 4): every aligned
            // block of the sequence stays a block, so each prefix of 2^k of the pixel's
            // samples is still a (0,k,2)-net, and two pairs' orders are independent (an XOR
            // of the index, used before, tied sample j of one pair to sample j ^ c of
            // another, and pairs drawn from alike sequences were correlated). It is
            // `shuffle(index, key) & (spp - 1)` computed in the reversed domain: the
            // scramble's bits 16 - log2 spp .. 16 read as a position of the reversed pool
            let bits = self.spp.trailing_zeros();
            (owen_scramble_reversed(reversed, key as u32) >> (16 - bits)) & (self.spp - 1)
        } else {
            permute_out_of_line(index % self.spp, self.spp, key as u32)
        } as usize;
        let spp = self.spp as usize;
        let [x, y] = match &self.shifts {
            None => {
                let [x, y] = self.pool[(key >> 40) as usize % POOL * spp + i];
                let bits = rekey(key, 1);
                [x ^ bits as u32, y ^ (bits >> 32) as u32]
            }
            Some(shifts) => {
                let [x, y] = self.pool[pair as usize % POOL * spp + i];
                let [sx, sy] = shifts.shift(pixel, frame, pair);
                [x.wrapping_add(sx), y.wrapping_add(sy)]
            }
        };
        [unit(x), unit(y)]
    }
}

