//! Halton mapped to pixels as pbrt-v4's `HaltonSampler` does it (Pharr, Jakob & Humphreys
//! 2023, section 8.6): one Halton sequence over the whole screen, whose first two
//! dimensions (bases 2 and 3), scaled by 2^j x 3^k >= the film (at most 128 x 128, then
//! tiled), put exactly one point in each pixel of every block of 2^j x 3^k consecutive
//! indices; the pixel's samples are the points at that offset plus multiples of 2^j 3^k
//! (the offset found by the Chinese remainder theorem). Every value is computed in
//! single precision as pbrt computes it, so the values equal pbrt's bit for bit.

use crate::construct::pbrt::{frame_seed, halton_digit_count, hash_words, mix_bits, permutation_element};
use super::{four, Family, Film, PixelEntry, PixelSampler, Mapping, MappingKind};
use crate::construct::counts::ANY;
use crate::error::Result;
use crate::registry::About;
use crate::construct::radical::PRIMES;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// pbrt's `PrimeTableSize`: its Halton sampler's dimensions.
const PRIME_TABLE_SIZE: u32 = 1000;

/// pbrt's `MaxHaltonResolution`: the film is covered in tiles of at most this side.
const MAX_RESOLUTION: u32 = 128;

/// pbrt's `OneMinusEpsilon` in single precision.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

const RANDOMIZE: ParamSpec = ParamSpec {
    name: "randomize",
    kind: Kind::Choice(&["none", "permutedigits", "owen"]),
    default: Default::Word("permutedigits"),
    doc: "pbrt-v4's RandomizeStrategy for Halton: none, permutedigits (a random permutation per \
          digit position and base), owen (a permutation per digit keyed by the digits before it)",
};

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "halton",
        "pbrt-v4's HaltonSampler: one Halton sequence over the screen, each pixel the indices whose \
         bases-2 and 3 coordinates fall in it, randomized by digit permutations (bit for bit)",
    )
    .aliases(&["pixel.halton", "haltonsampler"])
    .params(&[RANDOMIZE])
    .terse()
    .cite(&["halton1960", "pharr2023", "owen1995"]),
    spp: ANY,
    dims_note: "pbrt's prime table",
    max_dims: PRIME_TABLE_SIZE,
    mapping: Mapping {
        kind: MappingKind::ScreenOrder,
        family: "halton",
        how: "dimensions 0 and 1 (the film position, never \
              randomized, as pbrt's GetPixel2D) place sample i of pixel p at Halton index o(p) + i 2^j 3^k; \
              dimension d >= 2 is the radical inverse in the d-th prime of that index, its digits \
              permuted by Hash(base, digit, seed) (permutedigits) or by the digits before them \
              (owen; pbrt's Owen ignores the seed: samplab XORs the frame's seed into its hash, \
              which is pbrt's value at seed 0); frame 0 uses the seed's low 32 bits as pbrt's seed",
    },
    build,
}];

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Randomize {
    None,
    PermuteDigits,
    Owen,
}

/// The digit permutations of one base for one seed (pbrt's `DigitPermutation`): entry
/// `j * base + a` is where digit value `a` at position `j` goes.
#[derive(Debug)]
struct Digits {
    base: u32,
    permutations: Vec<u16>,
}

/// The permutation of digit position `j` in `base` for `seed`, applied to `a`.
#[inline]
fn permute(base: u32, j: u32, seed: u32, a: u32) -> u32 {
    permutation_element(a, base, hash_words(&[base, j, seed]) as u32)
}

impl Digits {
    fn new(base: u32, seed: u32) -> Digits {
        let n = halton_digit_count(base, true);
        let permutations = (0..n).flat_map(|j| (0..base).map(move |a| permute(base, j, seed, a) as u16)).collect();
        Digits { base, permutations }
    }
}

/// pbrt's radical inverse loops, digit by digit, `digit(j, a)` the (permuted) digit at
/// position j: `stop` is the number of positions, or none for the unscrambled inverse
/// (which stops when the index runs out of digits).
#[inline]
fn radical_inverse(base: u32, mut a: u64, positions: Option<u32>, mut digit: impl FnMut(u32, u32, u64) -> u32) -> f32 {
    let b = u64::from(base);
    let limit = u64::MAX / b - b;
    let inv = 1.0 / base as f32;
    let (mut inv_m, mut reversed, mut j) = (1.0f32, 0u64, 0u32);
    while positions.map_or(a != 0, |n| j < n) && reversed < limit {
        let next = a / b;
        let value = (a - next * b) as u32;
        reversed = reversed * b + u64::from(digit(j, value, reversed));
        inv_m *= inv;
        j += 1;
        a = next;
    }
    (reversed as f32 * inv_m).min(ONE_MINUS_EPSILON)
}

#[derive(Debug)]
pub(crate) struct Halton {
    randomize: Randomize,
    seed: u64,
    /// Frame 0's permutations of every dimension's base (`permutedigits`).
    digits: Vec<Digits>,
    /// Digit positions per dimension's base (`permutedigits`, `owen`).
    positions: Vec<u32>,
    scales: [u64; 2],
    exponents: [u32; 2],
    inverses: [u64; 2],
}

/// x^-1 mod n (x and n coprime), by the extended Euclidean algorithm.
fn inverse_mod(x: u64, n: u64) -> u64 {
    let (mut r0, mut r1, mut s0, mut s1) = (n as i64, (x % n) as i64, 0i64, 1i64);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (s0, s1) = (s1, s0 - q * s1);
    }
    s0.rem_euclid(n as i64) as u64
}

fn build(p: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let randomize = match p.word("randomize") {
        "none" => Randomize::None,
        "owen" => Randomize::Owen,
        _ => Randomize::PermuteDigits,
    };
    Ok(Family::from(Halton::new(randomize, film, seed)))
}

impl Halton {
    fn new(randomize: Randomize, film: Film, seed: Seed) -> Halton {
    let bases = &PRIMES[..film.dims as usize];
    let digits = match randomize {
        Randomize::PermuteDigits => bases.iter().map(|&b| Digits::new(b, frame_seed(seed.0, 0))).collect(),
        _ => Vec::new(),
    };
    let positions = bases.iter().map(|&b| halton_digit_count(b, randomize != Randomize::Owen)).collect();
    let (mut scales, mut exponents) = ([1u64; 2], [0u32; 2]);
    for (i, side) in [film.width, film.height].into_iter().enumerate() {
        while scales[i] < u64::from(side.min(MAX_RESOLUTION)) {
            scales[i] *= u64::from(PRIMES[i]);
            exponents[i] += 1;
        }
    }
    let inverses = [inverse_mod(scales[1], scales[0]), inverse_mod(scales[0], scales[1])];
    Halton { randomize, seed: seed.0, digits, positions, scales, exponents, inverses }
    }

    /// The Halton index of sample `index` of `pixel`.
    #[inline]
    fn halton_index(&self, pixel: [u32; 2], index: u32) -> u64 {
        let stride = self.scales[0] * self.scales[1];
        let mut offset = 0;
        if stride > 1 {
            for i in 0..2 {
                // the pixel's coordinate, digit-reversed in the base: the index's low digits
                let (b, mut c) = (u64::from(PRIMES[i]), u64::from(pixel[i] % MAX_RESOLUTION));
                let mut reversed = 0;
                for _ in 0..self.exponents[i] {
                    reversed = reversed * b + c % b;
                    c /= b;
                }
                offset += reversed * (stride / self.scales[i]) * self.inverses[i];
            }
            offset %= stride;
        }
        offset + u64::from(index) * stride
    }

    fn value(&self, frame: u32, a: u64, dim: u32) -> f32 {
        let base = PRIMES[dim as usize];
        match dim {
            0 => radical_inverse(base, a >> self.exponents[0], None, |_, v, _| v),
            1 => radical_inverse(base, a / self.scales[1], None, |_, v, _| v),
            _ => {
                let positions = Some(self.positions[dim as usize]);
                let seed = frame_seed(self.seed, frame);
                match self.randomize {
                    Randomize::None => radical_inverse(base, a, None, |_, v, _| v),
                    Randomize::PermuteDigits if frame == 0 => {
                        let t = &self.digits[dim as usize];
                        radical_inverse(base, a, positions, |j, v, _| u32::from(t.permutations[(j * t.base + v) as usize]))
                    }
                    Randomize::PermuteDigits => radical_inverse(base, a, positions, |j, v, _| permute(base, j, seed, v)),
                    Randomize::Owen => {
                        let hash = mix_bits(1 + (u64::from(dim) << 4)) as u32 ^ seed;
                        radical_inverse(base, a, positions, |_, v, reversed| {
                            permutation_element(v, base, mix_bits(u64::from(hash) ^ reversed) as u32)
                        })
                    }
                }
            }
        }
    }
}

impl PixelSampler for Halton {
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        f64::from(self.value(frame, self.halton_index(pixel, index), dim))
    }

    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        let a = self.halton_index(pixel, index);
        four(|k| f64::from(self.value(frame, a, dim + k)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverses_are_inverses() {
        assert_eq!(inverse_mod(27, 128), (1..128).find(|k| 27 * k % 128 == 1).unwrap());
        assert_eq!(inverse_mod(128, 27), (1..27).find(|k| 128 * k % 27 == 1).unwrap());
    }

    #[test]
    fn every_pixel_of_a_tile_gets_its_own_first_two_coordinates() {
        let film = Film { width: 20, height: 10, spp: 3, dims: 2 };
        let h = Halton::new(Randomize::None, film, Seed(0));
        let halton = crate::construct::radical::radical_inverse;
        for y in 0..10 {
            for x in 0..20 {
                for i in 0..3 {
                    let a = h.halton_index([x, y], i);
                    // 2^5 = 32 >= 20 columns, 3^3 = 27 >= 10 rows: the Halton point lies in
                    // the pixel's cell of the 32 x 27 grid, and dimensions 0 and 1 are its
                    // position inside the cell
                    let (u, v) = (halton(a, 2) * 32.0, halton(a, 3) * 27.0);
                    assert_eq!((u as u32, v as u32), (x, y), "pixel ({x}, {y}) sample {i}");
                    assert!((h.sample([x, y], 0, i, 0) - u.fract()).abs() < 1e-6);
                    assert!((h.sample([x, y], 0, i, 1) - v.fract()).abs() < 1e-6);
                }
            }
        }
    }
}
