//! ZSobol (Ahmed & Wonka 2020, as pbrt-v4's `ZSobolSampler` implements it): one Sobol'
//! sequence over the whole screen, pixels visited in Morton order, with a random
//! permutation of every base-4 digit of the Morton index that depends on the digits above
//! it, so that neighbouring pixels get well-spread, different parts of the sequence: the
//! error is spread over the screen as blue noise. `curve=hilbert` visits the pixels along a
//! Hilbert curve instead ([`crate::construct::curve::hilbert2`]): every aligned block of
//! pixels is still one run of the index, and consecutive pixels are neighbours.

use super::RANDOMIZE;
use crate::construct::pbrt::{Scramble, Sobol2, frame_seed, hash_words, mix_bits, morton2};
use super::{Family, Film, POWER_OF_TWO_SPP, Pairs, PixelEntry, Mapping, MappingKind};
use crate::construct::curve::hilbert2;
use crate::error::Result;
use crate::registry::About;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The order pixels are visited in.
const CURVE: ParamSpec = ParamSpec {
    name: "curve",
    kind: Kind::Choice(&["morton", "hilbert"]),
    default: Default::Word("morton"),
    doc: "the screen order of the pixels: Morton's (pbrt-v4's, Ahmed & Wonka 2020) or a Hilbert curve's",
};

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "zsobol",
        "ZSobol: screen-space blue-noise error from Morton-ordered Sobol' with per-level random digit \
         permutations (pbrt-v4's ZSobolSampler, bit for bit)",
    )
    .aliases(&["zsobolsampler"])
    .params(&[RANDOMIZE, CURVE])
    .terse()
    .cite(&["ahmed2020", "pharr2023", "burley2020", "hilbert1891"]),
    spp: POWER_OF_TWO_SPP,
    dims_note: "pairs of 2D Sobol'",
    max_dims: super::MAX_DIMS,
    mapping: Mapping {
        kind: MappingKind::ScreenOrder,
        family: "sobol",
        how: "sample i of pixel p is Sobol' point P(morton(p) * spp + i) (or hilbert(p)), P \
              permuting each base-4 digit by a hash of the digits above it and of the dimension pair; \
              dimensions 2k, 2k+1 are Sobol' dimensions 0, 1 scrambled by Hash(2k + 2, seed) \
              (frame 0 uses the seed's low 32 bits as pbrt's seed)",
    },
    build,
}];

/// The 24 permutations of four digits, in pbrt-v4's order (which its hashes index).
const PERMUTATIONS: [[u8; 4]; 24] = [
    [0, 1, 2, 3],
    [0, 1, 3, 2],
    [0, 2, 1, 3],
    [0, 2, 3, 1],
    [0, 3, 2, 1],
    [0, 3, 1, 2],
    [1, 0, 2, 3],
    [1, 0, 3, 2],
    [1, 2, 0, 3],
    [1, 2, 3, 0],
    [1, 3, 2, 0],
    [1, 3, 0, 2],
    [2, 1, 0, 3],
    [2, 1, 3, 0],
    [2, 0, 1, 3],
    [2, 0, 3, 1],
    [2, 3, 0, 1],
    [2, 3, 1, 0],
    [3, 1, 2, 0],
    [3, 1, 0, 2],
    [3, 2, 1, 0],
    [3, 2, 0, 1],
    [3, 0, 2, 1],
    [3, 0, 1, 2],
];

/// Each permutation in one byte: digit d goes to bits 2d, 2d + 1.

#[derive(Debug)]
pub(crate) struct ZSobol {
    seed: u64,
    scramble: Scramble,
    /// The Hilbert curve's order (the film's side, a power of two, is 2^order); None: Morton's.
    hilbert: Option<u32>,
    log2_spp: u32,
    base4_digits: u32,
    sobol: Sobol2,
    /// Frame 0's scramble hash of every pair of the film's dimensions.
    hashes: Vec<u64>,
}

fn build(p: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let log2_spp = film.spp.ilog2();
    let side = film.width.max(film.height).next_power_of_two();
    Ok(Family::from(ZSobol {
        seed: seed.0,
        scramble: Scramble::from_word(p.word("randomize")),
        hilbert: (p.word("curve") == "hilbert").then(|| side.ilog2()),
        log2_spp,
        base4_digits: side.ilog2() + log2_spp.div_ceil(2),
        sobol: Sobol2::default(),
        hashes: (0..film.dims.div_ceil(2)).map(|k| hash_words(&[2 * k + 2, frame_seed(seed.0, 0)])).collect(),
    }))
}

impl ZSobol {
    /// The permuted sequence indices of the sample whose Morton index is `morton`, for the
    /// dimension pairs starting at each of `dims` (pbrt's `GetSampleIndex`; several at once,
    /// so that their independent hashes overlap).
    #[inline(always)]
    fn sequence_indices<const N: usize>(&self, morton: u64, dims: [u32; N]) -> [u64; N] {
        let odd = self.log2_spp & 1;
        // pbrt multiplies in 32 bits (`0x55555555u * dimension`)
        let salts = dims.map(|d| u64::from(0x5555_5555u32.wrapping_mul(d)));
        // the base-4 digits from the lowest up, so that every shift is by a constant: each
        // permuted digit enters at the top of `acc`, which moves down two bits per digit
        let digits = self.base4_digits - odd;
        let mut rest = morton >> odd;
        let mut acc = [0u64; N];
        for _ in 0..digits {
            let digit = (rest & 3) as usize;
            rest >>= 2;
            for k in 0..N {
                let p = ((mix_bits(rest ^ salts[k]) >> 24) % 24) as usize;
                acc[k] = (acc[k] >> 2) | u64::from(PERMUTATIONS[p][digit]) << 62;
            }
        }
        let mut index = acc.map(|a| a.checked_shr(64 - 2 * digits).unwrap_or(0) << odd);
        if odd == 1 {
            for k in 0..N {
                index[k] |= (morton & 1) ^ (mix_bits((morton >> 1) ^ salts[k]) & 1);
            }
        }
        index
    }

    #[inline(always)]
    fn hash(&self, frame: u32, seed: u32, dim: u32) -> u64 {
        match self.hashes.get((dim / 2) as usize) {
            Some(&h) if frame == 0 => h,
            _ => hash_words(&[dim + 2, seed]),
        }
    }
}

impl Pairs for ZSobol {
    /// The sample's Morton (or Hilbert) index and pbrt's seed for the frame.
    type Key = (u64, u32);

    #[inline(always)]
    fn key(&self, pixel: [u32; 2], frame: u32, index: u32) -> (u64, u32) {
        let order = match self.hilbert {
            None => morton2(pixel[0], pixel[1]),
            Some(order) => hilbert2(order, pixel[0], pixel[1]),
        };
        ((order << self.log2_spp) | u64::from(index), frame_seed(self.seed, frame))
    }

    #[inline(always)]
    fn pair(&self, (morton, seed): (u64, u32), _: [u32; 2], frame: u32, _: u32, dim: u32) -> [f64; 2] {
        let [i] = self.sequence_indices(morton, [dim]);
        self.sobol.pair(self.scramble, i, self.hash(frame, seed, dim))
    }

    #[inline(always)]
    fn two_pairs(&self, (morton, seed): (u64, u32), _: [u32; 2], frame: u32, _: u32, dim: u32) -> [f64; 4] {
        let [i, j] = self.sequence_indices(morton, [dim, dim + 2]);
        let [a, b] = self.sobol.pair(self.scramble, i, self.hash(frame, seed, dim));
        let [c, d] = self.sobol.pair(self.scramble, j, self.hash(frame, seed, dim + 2));
        [a, b, c, d]
    }
}

