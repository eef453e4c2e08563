//! The integer functions pbrt-v4's samplers are built from (Pharr, Jakob & Humphreys 2023,
//! `util/hash.h`, `util/math.h`, `util/lowdiscrepancy.h`), written here from their
//! definitions so that `zsobol` and `sobol.padded` give pbrt's values bit for bit (the
//! fixture `tests/fixtures/pbrt_pixel_samplers.txt`, the values pbrt's own headers print).

use super::scramble::owen_scramble_u32;
use super::unit;
use crate::construct::sobol::{ByteTables, byte_tables, owen_digits, reversed_digits};

/// MurmurHash64A (Appleby) with seed 0 over little-endian 32-bit words, as pbrt's
/// `Hash(args...)` hashes the bytes of its (int) arguments.
#[inline]
pub fn hash_words(words: &[u32]) -> u64 {
    const M: u64 = 0xc6a4_a793_5bd1_e995;
    let len = 4 * words.len() as u64;
    let mut h = len.wrapping_mul(M);
    let mix = |mut k: u64| {
        k = k.wrapping_mul(M);
        k ^= k >> 47;
        k.wrapping_mul(M)
    };
    let mut pairs = words.chunks_exact(2);
    for pair in &mut pairs {
        h ^= mix(u64::from(pair[0]) | (u64::from(pair[1]) << 32));
        h = h.wrapping_mul(M);
    }
    if let [last] = pairs.remainder() {
        h ^= u64::from(*last);
        h = h.wrapping_mul(M);
    }
    h ^= h >> 47;
    h = h.wrapping_mul(M);
    h ^ (h >> 47)
}

/// pbrt's `MixBits`: a 64-bit finalizer in the style of Stafford's mixers, with pbrt's
/// constants.
#[inline(always)]
pub fn mix_bits(mut v: u64) -> u64 {
    v ^= v >> 31;
    v = v.wrapping_mul(0x7fb5_d329_728e_a185);
    v ^= v >> 27;
    v = v.wrapping_mul(0x81da_def4_bc2d_d44d);
    v ^ (v >> 33)
}

/// pbrt's `PermutationElement(i, l, p)`: element i of a permutation of 0..l keyed by p
/// (Kensler 2013's hash permutation with cycle walking, then pbrt's final rotation by p).
#[inline]
pub fn permutation_element(i: u32, l: u32, p: u32) -> u32 {
    let w = u32::MAX >> (l.max(2) - 1).leading_zeros();
    super::scramble::kensler_permute(i, l, w, p).wrapping_add(p) % l
}

/// Morton code of (x, y): x in the even bits, y in the odd ones.
#[inline]
pub fn morton2(x: u32, y: u32) -> u64 {
    let spread = |v: u32| {
        let mut v = u64::from(v);
        v = (v | (v << 16)) & 0x0000_ffff_0000_ffff;
        v = (v | (v << 8)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333_3333_3333;
        (v | (v << 1)) & 0x5555_5555_5555_5555
    };
    (spread(y) << 1) | spread(x)
}

/// pbrt's `RandomizeStrategy` for its Sobol' samplers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Scramble {
    /// The deterministic sequence.
    None,
    /// XOR with the hash (pbrt's `PermuteDigits`: a random digital shift).
    Xor,
    /// The Laine–Karras style hash of Burley 2020 with Vegdahl's constants (`FastOwen`).
    FastOwen,
    /// Owen scrambling bit by bit, one `MixBits` per digit (`Owen`).
    Owen,
}

impl Scramble {
    /// From the word of the pixel samplers' `randomize` parameter (pbrt's names).
    pub(crate) fn from_word(word: &str) -> Scramble {
        match word {
            "none" => Scramble::None,
            "xor" => Scramble::Xor,
            "owen" => Scramble::Owen,
            _ => Scramble::FastOwen,
        }
    }

    /// Scramble the 32 fixed-point digits `v` with `seed`.
    #[inline]
    pub fn apply(self, v: u32, seed: u32) -> u32 {
        match self {
            Scramble::None => v,
            Scramble::Xor => v ^ seed,
            Scramble::FastOwen => owen_scramble_u32(v, seed),
            Scramble::Owen => owen_bit_by_bit(v, seed),
        }
    }
}

/// pbrt's `OwenScrambler`: digit b flipped by bit b of `MixBits` of the digits above it
/// XOR the seed, one hash per digit.
#[inline(always)]
pub fn owen_bit_by_bit(v: u32, seed: u32) -> u32 {
    let mut v = v ^ ((seed & 1) << 31);
    for b in 1..32 {
        let above = v & (u32::MAX << (32 - b));
        v ^= (((mix_bits(u64::from(above ^ seed)) as u32) >> b) & 1) << (31 - b);
    }
    v
}

/// The first two dimensions of Sobol' (van der Corput and its partner), whose 32-bit
/// generator columns are all pbrt's 2D Sobol' samplers use (columns past 32 vanish at
/// 32-bit precision, so only the index's low 32 bits count), as byte tables.
#[derive(Debug, Clone)]
pub struct Sobol2 {
    tables: [ByteTables; 2],
}

impl std::default::Default for Sobol2 {
    fn default() -> Sobol2 {
        Sobol2 { tables: [byte_tables(0), byte_tables(1)] }
    }
}

impl Sobol2 {
    /// Point `index` scrambled by `scramble`, dimension 0 with the low word of `hash` and
    /// dimension 1 with its high word (as pbrt's 2D Sobol' samplers split their hashes).
    #[inline(always)]
    pub fn pair(&self, scramble: Scramble, index: u64, hash: u64) -> [f64; 2] {
        let seeds = [hash as u32, (hash >> 32) as u32];
        std::array::from_fn(|d| {
            let reversed = reversed_digits(&self.tables[d], index as u32);
            unit(match scramble {
                // the fast scramble works on reversed digits: one reversal in all
                Scramble::FastOwen => owen_digits(reversed, seeds[d]),
                other => other.apply(reversed.reverse_bits(), seeds[d]),
            })
        })
    }
}

/// The seed pbrt's samplers get for `frame`: frame 0 takes the low 32 bits of samplab's
/// seed as pbrt's own seed (so `--seed 7` is pbrt's `seed 7`); a later frame hashes it
/// with the frame number.
#[inline]
pub fn frame_seed(seed: u64, frame: u32) -> u32 {
    if frame == 0 { seed as u32 } else { hash_words(&[seed as u32, frame]) as u32 }
}

/// How many base-`base` digits pbrt's Halton sampler randomizes (its single-precision loops
/// in `DigitPermutation` and `OwenScrambledRadicalInverse`): until (base - 1) b^-n no longer
/// changes 1 - (base - 1) b^-n in `f32` (`with_top` false: until b^-n no longer changes
/// 1 - b^-n).
pub fn halton_digit_count(base: u32, with_top: bool) -> u32 {
    let (inv, top) = (1.0 / base as f32, if with_top { (base - 1) as f32 } else { 1.0 });
    let (mut n, mut inv_m) = (0, 1.0f32);
    while 1.0 - top * inv_m < 1.0 {
        n += 1;
        inv_m *= inv;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;

    /// MurmurHash64A from its published definition, byte by byte (the reference the word
    /// version must match).
    fn murmur_bytes(key: &[u8]) -> u64 {
        const M: u64 = 0xc6a4_a793_5bd1_e995;
        let mut h = (key.len() as u64).wrapping_mul(M);
        let mut blocks = key.chunks_exact(8);
        for b in &mut blocks {
            let mut k = u64::from_le_bytes(b.try_into().unwrap());
            k = k.wrapping_mul(M);
            k ^= k >> 47;
            k = k.wrapping_mul(M);
            h ^= k;
            h = h.wrapping_mul(M);
        }
        let tail = blocks.remainder();
        if !tail.is_empty() {
            for (i, &b) in tail.iter().enumerate() {
                h ^= u64::from(b) << (8 * i);
            }
            h = h.wrapping_mul(M);
        }
        h ^= h >> 47;
        h = h.wrapping_mul(M);
        h ^ (h >> 47)
    }

    #[test]
    fn word_hash_equals_the_byte_definition() {
        for words in [&[][..], &[1], &[1, 2], &[3, 4, 5], &[0xFFFF_FFFF, 7, 9, 11]] {
            let bytes: Vec<u8> = words.iter().flat_map(|w: &u32| w.to_le_bytes()).collect();
            assert_eq!(hash_words(words), murmur_bytes(&bytes), "{words:?}");
        }
    }

    #[test]
    fn permutation_element_is_a_permutation() {
        for l in [1u32, 2, 3, 7, 16, 33] {
            for p in [0u32, 1, 0xDEAD_BEEF] {
                let mut seen: Vec<u32> = (0..l).map(|i| permutation_element(i, l, p)).collect();
                seen.sort_unstable();
                assert_eq!(seen, (0..l).collect::<Vec<_>>(), "l={l} p={p}");
            }
        }
    }

    #[test]
    fn owen_scrambles_are_bijections_that_keep_prefixes_together() {
        // nested scrambling: values sharing their first k digits still share them after
        for s in [Scramble::FastOwen, Scramble::Owen, Scramble::Xor] {
            let a = s.apply(0b1011 << 28, 99);
            let b = s.apply((0b1011 << 28) | 12345, 99);
            assert_eq!(a >> 28, b >> 28, "{s:?}");
            let mut v: Vec<u32> = (0..256u32).map(|i| s.apply(i << 24, 5) >> 24).collect();
            v.sort_unstable();
            assert_eq!(v, (0..256).collect::<Vec<_>>(), "{s:?}");
        }
    }

    #[test]
    fn morton_interleaves() {
        assert_eq!(morton2(0b11, 0), 0b0101);
        assert_eq!(morton2(0, 0b11), 0b1010);
        assert_eq!(morton2(u32::MAX, u32::MAX), u64::MAX);
    }
}
