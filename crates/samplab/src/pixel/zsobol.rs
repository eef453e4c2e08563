//! ZSobol (Ahmed & Wonka 2020, as pbrt-v4's `ZSobolSampler` implements it): one Sobol'
//! sequence over the whole screen, pixels visited in Morton order, with a random
//! permutation of every base-4 digit of the Morton index that depends on the digits above
//! it, so that neighbouring pixels get well-spread, different parts of the sequence: the
//! error is spread over the screen as blue noise.

use super::pbrt::{RANDOMIZE, Scramble, Sobol2, frame_seed, hash_words, mix_bits, morton2};
use super::{Film, POWER_OF_TWO_SPP, Pairs, PixelEntry, PixelSampler, unit};
use crate::error::Result;
use crate::registry::About;
use crate::seed::Seed;
use crate::spec::Params;

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "zsobol",
        "ZSobol: screen-space blue-noise error from Morton-ordered Sobol' with per-level random digit \
         permutations (pbrt-v4's ZSobolSampler, bit for bit)",
    )
    .aliases(&["zsobolsampler"])
    .params(&[RANDOMIZE])
    .terse()
    .cite(&["ahmed2020", "pharr2023", "burley2020"]),
    spp: POWER_OF_TWO_SPP,
    dims: "any (pairs of 2D Sobol')",
    max_dims: super::MAX_DIMS,
    mapping: "screen-space ordering: sample i of pixel p is Sobol' point P(morton(p) * spp + i), P \
              permuting each base-4 digit by a hash of the digits above it and of the dimension pair; \
              dimensions 2k, 2k+1 are Sobol' dimensions 0, 1 scrambled by Hash(2k + 2, seed) \
              (frame 0 uses the seed's low 32 bits as pbrt's seed)",
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

#[derive(Debug)]
struct ZSobol {
    seed: u64,
    scramble: Scramble,
    log2_spp: u32,
    base4_digits: u32,
    sobol: Sobol2,
}

fn build(p: &Params, film: Film, seed: Seed) -> Result<Box<dyn PixelSampler>> {
    let log2_spp = film.spp.ilog2();
    let side = film.width.max(film.height).next_power_of_two();
    Ok(Box::new(ZSobol {
        seed: seed.0,
        scramble: Scramble::from_word(p.word("randomize")),
        log2_spp,
        base4_digits: side.ilog2() + log2_spp.div_ceil(2),
        sobol: Sobol2::default(),
    }))
}

impl ZSobol {
    /// The permuted sequence index of the sample whose Morton index is `morton`, for the
    /// dimension pair starting at `dim` (pbrt's `GetSampleIndex`).
    #[inline]
    fn sequence_index(&self, morton: u64, dim: u32) -> u64 {
        let odd = self.log2_spp & 1;
        // pbrt multiplies in 32 bits (`0x55555555u * dimension`)
        let salt = u64::from(0x5555_5555u32.wrapping_mul(dim));
        let mut index = 0;
        for i in (odd..self.base4_digits).rev() {
            let shift = 2 * i - odd;
            let digit = (morton >> shift) & 3;
            let higher = morton >> (shift + 2);
            let p = ((mix_bits(higher ^ salt) >> 24) % 24) as usize;
            index |= u64::from(PERMUTATIONS[p][digit as usize]) << shift;
        }
        if odd == 1 {
            index |= (morton & 1) ^ (mix_bits((morton >> 1) ^ salt) & 1);
        }
        index
    }

}

impl Pairs for ZSobol {
    #[inline(always)]
    fn pair(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 2] {
        let morton = (morton2(pixel[0], pixel[1]) << self.log2_spp) | u64::from(index);
        let i = self.sequence_index(morton, dim);
        let bits = hash_words(&[dim + 2, frame_seed(self.seed, frame)]);
        [
            unit(self.scramble.apply(self.sobol.digits(i, 0), bits as u32)),
            unit(self.scramble.apply(self.sobol.digits(i, 1), (bits >> 32) as u32)),
        ]
    }
}

