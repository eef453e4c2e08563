//! Owen-scrambled Sobol' per pixel: the true high-dimensional sequence shuffled per pixel
//! (Burley 2020) and pbrt-v4's padded 2D Sobol' (Pharr, Jakob & Humphreys 2023).

use super::RANDOMIZE;
use crate::construct::pbrt::{Scramble, Sobol2, frame_seed, hash_words, permutation_element};
use super::{one_by_one, Family, Film, Keys, Pairs, PixelEntry, PixelSampler, Mapping, MappingKind};
use crate::construct::{counts::ANY, unit};
use crate::error::Result;
use crate::registry::About;
use crate::construct::sobol::{ReversedLow, SOBOL_MAX_DIMS, owen_digits};
use crate::construct::scramble::owen_scramble_reversed;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

pub(crate) static ENTRIES: &[PixelEntry] = &[
    PixelEntry {
        about: About::new(
            "sobol",
            "Owen-scrambled Sobol' per pixel: dimension d is Sobol' dimension d (Joe-Kuo), the index \
             shuffled and every dimension Owen-scrambled by hashes of (seed, pixel, frame)",
        )
        .aliases(&["pixel.sobol", "burley"])
        .cite(&["burley2020", "joe2008", "sobol1967"]),
        spp: super::Counts::Any("each pixel's first 2^m samples a (t,m,s)-net"),
        dims_note: "the Joe-Kuo table",
        max_dims: SOBOL_MAX_DIMS as u32,
        mapping: Mapping {
            kind: MappingKind::PerPixel,
            family: "sobol",
            how: "the index's low 16 digits are nested-uniform scrambled by the \
                  pixel's hash (Burley 2020, section 4), which maps samples 0..2^m to an aligned block \
                  of 2^m Sobol' points, itself a net; each dimension then Owen-scrambled by its own \
                  hash of (pixel, dimension)",
        },
        build: build_sobol,
    },
    PixelEntry {
        about: About::new(
            "sobol.padded",
            "pbrt-v4's PaddedSobolSampler: each pair of dimensions a 2D Sobol' pattern with its own \
             index permutation and scramble per pixel",
        )
        .aliases(&["paddedsobol"])
        .params(&[RANDOMIZE])
        .terse()
        .cite(&["pharr2023", "burley2020", "kensler2013"]),
        spp: ANY,
        dims_note: "pairs of 2D Sobol'",
        max_dims: super::MAX_DIMS,
        mapping: Mapping {
            kind: MappingKind::Padded,
            family: "sobol",
            how: "dimensions 2k, 2k+1 are Sobol' dimensions 0, 1 at a per-pixel \
                  permutation of the sample index, scrambled by Hash(pixel, 2k, seed), as pbrt-v4 \
                  (bit for bit; frame 0 uses the seed's low 32 bits as pbrt's seed)",
        },
        build: build_padded,
    },
];

#[derive(Debug)]
pub(crate) struct Burley {
    keys: Keys,
    tables: Vec<ReversedLow>,
}

fn build_sobol(_: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    Ok(Family::from(Burley { keys: Keys::new(seed, film.dims), tables: (0..film.dims as usize).map(ReversedLow::new).collect() }))
}

impl Burley {
    #[inline(always)]
    fn value(&self, key: u32, (high, low): (u32, u32), dim: u32) -> f64 {
        unit(owen_digits(self.tables[dim as usize].digits(high, low), self.keys.dim(key, dim)))
    }

    /// The pixel's key, and sample `index`'s place in the pixel's shuffled sequence: its
    /// low 16 digits nested-uniform scrambled by the key (so samples 0..2^m, m <= 16, map
    /// to an aligned block of 2^m points, a net), the digits above kept; the place as
    /// (high digits, low 16 digits bit-reversed), the form [`ReversedLow`] reads.
    #[inline(always)]
    fn shuffled(&self, pixel: [u32; 2], frame: u32, index: u32) -> (u32, (u32, u32)) {
        let key = self.keys.pixel(pixel, frame);
        let low = owen_scramble_reversed(index.reverse_bits() >> 16, (key >> 32) as u32) & 0xFFFF;
        (key as u32, (index & !0xFFFF, low))
    }
}

impl PixelSampler for Burley {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        let (key, i) = self.shuffled(pixel, frame, index);
        self.value(key, i, dim)
    }

    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        let (key, i) = self.shuffled(pixel, frame, index);
        let d = dim as usize;
        match (self.tables.get(d..d + 4), self.keys.dims.get(d..d + 4)) {
            (Some(t), Some(h)) => {
                let v = |k: usize| unit(owen_digits(t[k].digits(i.0, i.1), Keys::combine(key, h[k])));
                [v(0), v(1), v(2), v(3)]
            }
            // past the last dimension: only a caller's out-of-range key comes here
            _ => one_by_one(self, pixel, frame, index, dim),
        }
    }
}

#[derive(Debug)]
pub(crate) struct Padded {
    seed: u64,
    spp: u32,
    scramble: Scramble,
    sobol: Sobol2,
}

fn build_padded(p: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let scramble = Scramble::from_word(p.word("randomize"));
    Ok(Family::from(Padded { seed: seed.0, spp: film.spp, scramble, sobol: Sobol2::default() }))
}

impl Pairs for Padded {
    /// pbrt's seed for the frame.
    type Key = u32;

    #[inline(always)]
    fn key(&self, _: [u32; 2], frame: u32, _: u32) -> u32 {
        frame_seed(self.seed, frame)
    }

    #[inline(always)]
    fn pair(&self, seed: u32, pixel: [u32; 2], _: u32, index: u32, dim: u32) -> [f64; 2] {
        let hash = hash_words(&[pixel[0], pixel[1], dim, seed]);
        let i = permutation_element(index, self.spp, hash as u32);
        self.sobol.pair(self.scramble, i.into(), hash)
    }
}

