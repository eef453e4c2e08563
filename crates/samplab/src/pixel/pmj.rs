//! Progressive multi-jittered (0,2) sequences per pixel (Christensen, Kensler & Kilpatrick
//! 2018, made by Helmer, Christensen & Kensler 2021's stochastic construction) from a pool
//! of independent sequences: `pmj02` pads by blocks of four dimensions (two pairs read at
//! one scrambled index, as OpenQMC's `PmjSampler` reads its 4D table), `pmj02.bn` by pairs
//! with a blue-noise shift per pixel, as pbrt-v4's `PMJ02BNSampler` pads.

use super::dither::{MASK, Shifts};
use super::{Family, Film, Pairs, PixelEntry, Keys, rekey, Mapping, MappingKind};
use crate::construct::unit;
use crate::error::Result;
use crate::registry::About;
use crate::construct::scramble::{owen_scramble_reversed, owen_scramble_u32, permute};
use crate::construct::pmj02::pmj02_digits;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

/// Entries in the pool (two sequences each).
const POOL: usize = 16;

/// The largest spp: the pool holds 2 [`POOL`] sequences of at most this many points.
const MOST: u64 = 1 << 16;

pub(crate) static ENTRIES: &[PixelEntry] = &[
    PixelEntry {
        about: About::new(
            "pmj02",
            "pmj02 per pixel: each block of four dimensions two of 32 pmj02 sequences, their samples \
             permuted and digitally shifted by a hash of (seed, pixel, frame, block)",
        )
        .aliases(&["pixel.pmj02"])
        .cite(&["christensen2018", "helmer2021", "pharr2023"]),
        spp: super::Counts::AtMost { most: MOST, why: "the pool holds 32 sequences of at most 2^16 points" },
        dims_note: "blocks of two 2D pmj02",
        max_dims: super::MAX_DIMS,
        mapping: Mapping {
            kind: MappingKind::Padded,
            family: "pmj02",
            how: "blocks of four: dimensions 4k .. 4k+3 take the pool entry named by \
                  the top 4 bits of h (two independent pmj02 sequences, the second read through a fixed \
                  nested scramble of its index, which decorrelates the pairs and keeps its prefixes nets), \
                  sample pi(i) of its first spp for both pairs (pi a nested uniform scramble of the index for \
                  a power-of-two spp, so that every prefix of 2^j samples is a net; a hashed permutation \
                  otherwise), each value XOR-ed with hashed digits (a digital shift, which keeps every \
                  (0,m,2)-net a net), h a 64-bit hash of (seed, pixel, frame, k)",
        },
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
        dims_note: "pairs of 2D pmj02",
        max_dims: super::MAX_DIMS,
        mapping: Mapping {
            kind: MappingKind::Mask,
            family: "pmj02",
            how: "as pbrt-v4's PMJ02BNSampler, the pair's sequence is shared by all \
                  pixels, its samples permuted per pixel, then shifted modulo 1 by the pixel's \
                  blue-noise value (the mask shifted by a hash of frame and pair)",
        },
        build: build_bn,
    },
];

#[derive(Debug)]
pub(crate) struct Pmj {
    keys: Keys,
    spp: u32,
    /// [`POOL`] entries one after the other, `spp` points each: entry `e`'s point `j` holds
    /// x and y of point `j` of pmj02 sequence `e` and of point sigma(j) of sequence
    /// `POOL + e` (see [`pool`]); for a power-of-two spp stored in bit-reversed order of the
    /// index (see [`Pmj::index`]). `pmj02.bn` reads the first sequences only.
    pool: Vec<[u32; 4]>,
    /// The blue-noise shifts (`pmj02.bn`); none for `pmj02`, which shifts digits by hashes.
    shifts: Option<Shifts>,
}

fn pool(film: Film, seed: Seed) -> Vec<[u32; 4]> {
    let base = seed.derive_str("pmj02 pool");
    let spp = film.spp as usize;
    let pow2 = spp.is_power_of_two();
    let bits = spp.ilog2();
    // position v holds sample reverse(v) (on log2 spp bits) for a power-of-two spp: the
    // draws then read the scrambled index in the reversed domain, where it is computed
    let at = |v: usize| if pow2 { v.reverse_bits().checked_shr(usize::BITS - bits).unwrap_or(0) } else { v };
    (0..POOL as u64)
        .flat_map(|e| {
            let [a, b] = [e, POOL as u64 + e].map(|k| pmj02_digits(spp, base.derive(k)));
            // the second sequence is read through a fixed permutation of the entry's own: the
            // pool's sequences share the low bits of their index structure (which half of x
            // sample j falls in follows j's last bit alike), and read at one index their
            // pairs were correlated. A nested uniform scramble of the index (its top bits the
            // top levels) maps every aligned block of 2^k samples to one, so each prefix of
            // the pixel's samples stays a net
            let key = base.derive(2 * POOL as u64 + e).0 as u32;
            let sigma = move |j: usize| {
                if pow2 {
                    (owen_scramble_u32((j as u32).checked_shl(32 - bits).unwrap_or(0), key)
                        .checked_shr(32 - bits)
                        .unwrap_or(0)) as usize
                } else {
                    permute(j as u32, spp as u32, key) as usize
                }
            };
            (0..spp).map(move |v| {
                let j = at(v);
                let k = sigma(j);
                [a[j][0], a[j][1], b[k][0], b[k][1]]
            })
        })
        .collect()
}

fn build_plain(_: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    Ok(Family::from(Pmj { keys: Keys::new(seed, 0), spp: film.spp, pool: pool(film, seed), shifts: None }))
}

fn build_bn(p: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let shifts = Some(Shifts::new(p.int("mask") as usize, seed, film.dims.div_ceil(2))?);
    Ok(Family::from(Pmj { keys: Keys::new(seed, 0), spp: film.spp, pool: pool(film, seed), shifts }))
}

/// [`permute`] as a call: its cycle-walking loop, inlined into the power-of-two path's
/// draws, slowed them.
#[inline(never)]
fn permute_out_of_line(i: u32, len: u32, key: u32) -> u32 {
    permute(i, len, key)
}

/// Odd multipliers whose products' high words give the digital shifts of a block's four
/// dimensions from its hash.
const SHIFTS: [u64; 4] = [0x9E37_79B9_7F4A_7C15, 0xC2B2_AE3D_27D4_EB4F, 0x1656_67B1_9E37_79F9, 0xD6E8_FEB8_6659_FD93];

impl Pmj {
    /// [`super::Pixels::header_tables`]: the pool, then the mask where there is one.
    pub(super) fn header_tables(&self) -> Vec<u32> {
        let mut t: Vec<u32> = self.pool.iter().flatten().copied().collect();
        if let Some(shifts) = &self.shifts {
            t.extend(shifts.fixed_mask());
        }
        t
    }

    /// The position in an entry of the pixel's sample whose index is `index` (`reversed`
    /// its 16 bits reversed), scrambled by `key`.
    #[inline(always)]
    fn index(&self, reversed: u32, index: u32, key: u32) -> usize {
        if self.spp.is_power_of_two() {
            // a nested uniform scramble of the index (Burley 2020, section 4): every aligned
            // block of the sequence stays a block, so each prefix of 2^k of the pixel's
            // samples is still a (0,k,2)-net, and two blocks' orders are independent (an XOR
            // of the index, used before, tied sample j of one pair to sample j ^ c of
            // another, and pairs drawn from alike sequences were correlated). It is
            // `shuffle(index, key) & (spp - 1)` computed in the reversed domain: the
            // scramble's bits 16 - log2 spp .. 16 read as a position of the reversed pool
            let bits = self.spp.trailing_zeros();
            ((owen_scramble_reversed(reversed, key) >> (16 - bits)) & (self.spp - 1)) as usize
        } else {
            permute_out_of_line(index % self.spp, self.spp, key) as usize
        }
    }

    /// `pmj02`'s block of dimensions 4b .. 4b + 3: its hash picks the pool entry, scrambles
    /// the index (one scramble for the block's two pairs, as OpenQMC's 4D tables are read)
    /// and gives each dimension's digital shift, which keeps every (0,m,2)-net a net.
    #[inline(always)]
    fn block(&self, (key, reversed): (u64, u32), index: u32, block: u32) -> [u32; 4] {
        let h = rekey(key, u64::from(block));
        let entry = (h >> 60) as usize;
        let point = self.pool[entry * self.spp as usize + self.index(reversed, index, h as u32)];
        let shift = |d: usize| ((u128::from(h) * u128::from(SHIFTS[d])) >> 64) as u32;
        [point[0] ^ shift(0), point[1] ^ shift(1), point[2] ^ shift(2), point[3] ^ shift(3)]
    }
}

impl Pairs for Pmj {
    /// The pixel's key, and the sample index's 16 bits reversed (shared by the pairs).
    type Key = (u64, u32);

    #[inline(always)]
    fn key(&self, pixel: [u32; 2], frame: u32, index: u32) -> (u64, u32) {
        (self.keys.pixel(pixel, frame), (index & (self.spp - 1)).reverse_bits() >> 16)
    }

    #[inline(always)]
    fn pair(&self, key: (u64, u32), pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 2] {
        let pair = dim / 2;
        let [x, y] = match &self.shifts {
            None => {
                let v = self.block(key, index, pair / 2);
                let half = (pair % 2 * 2) as usize;
                [v[half], v[half + 1]]
            }
            Some(shifts) => {
                // the first sequence of entry pair mod 16
                let i = self.index(key.1, index, rekey(key.0, u64::from(pair)) as u32);
                let [x, y, ..] = self.pool[(pair as usize % POOL) * self.spp as usize + i];
                let [sx, sy] = shifts.shift(pixel, frame, pair);
                [x.wrapping_add(sx), y.wrapping_add(sy)]
            }
        };
        [unit(x), unit(y)]
    }

    #[inline(always)]
    fn two_pairs(&self, key: (u64, u32), pixel: [u32; 2], frame: u32, index: u32, first: u32) -> [f64; 4] {
        if self.shifts.is_none() && first.is_multiple_of(4) {
            return self.block(key, index, first / 4).map(unit);
        }
        let [a, b] = self.pair(key, pixel, frame, index, first);
        let [c, d] = self.pair(key, pixel, frame, index, first + 2);
        [a, b, c, d]
    }
}
