//! The integer and float functions Blender Cycles' sampling patterns are built from
//! (Cycles' `util/hash.h`, `kernel/sample/util.h`, `kernel/sample/sobol_burley.h` and
//! `scene/tabulated_sobol.cpp`, Apache-2.0), written here from their definitions so that
//! [`crate::pixel`]'s `cycles.*` families give Cycles' values bit for bit (the fixture
//! `tests/fixtures/cycles_patterns.txt`, printed by Cycles'
//! own source). Floats are single precision and every operation is Cycles' own, in its
//! order, so the values are the same singles.

// Cycles' `reversed_bit_owen` and `nested_uniform_scramble` are samplab's Owen scramble
// (Burley 2020's hash with Vegdahl's constants), in the reversed domain and not
use crate::construct::scramble::kensler_permute;
pub use crate::construct::scramble::{
    owen_scramble_reversed as reversed_bit_owen, owen_scramble_u32 as nested_uniform_scramble,
};
use crate::construct::sobol::{ByteTables, byte_tables, owen_digits, reversed_digits};

/// [0, 2^32) to [0, 1) in single precision, as Cycles maps it (`uint_to_float_excl`: over
/// 2^32 + 512, so that the largest value stays below 1).
#[inline(always)]
pub fn to_unit(n: u32) -> f32 {
    n as f32 * (1.0f32 / 4_294_967_808.0f32)
}

/// Hash Prospector's 32-bit mixer with Cycles' output offset (`hash_hp_uint`).
#[inline(always)]
pub fn hash_hp(mut i: u32) -> u32 {
    i ^= i >> 16;
    i = i.wrapping_mul(0x21f0_aaad);
    i ^= i >> 15;
    i = i.wrapping_mul(0xd35a_2d97);
    i ^= i >> 15;
    i ^ 0xe6fe_3beb
}

/// [`hash_hp`] of `i` under a seed (`hash_hp_seeded_uint`).
#[inline(always)]
pub fn hash_hp_seeded(i: u32, seed: u32) -> u32 {
    hash_hp(i ^ seed ^ (seed << 19))
}

/// Cycles' modified Wang hash (`hash_wang_seeded_uint`).
#[inline(always)]
pub fn hash_wang_seeded(i: u32, seed: u32) -> u32 {
    let mut i = (i ^ 61) ^ seed;
    i = i.wrapping_add(i << 3);
    i ^= i >> 4;
    i.wrapping_mul(0x27d4_eb2d)
}

/// The index shuffle of Helmer (`hash_shuffle_uint`): a permutation of 0 .. length by
/// Kensler's hash with cycle walking.
#[inline(always)]
pub fn hash_shuffle(i: u32, length: u32, seed: u32) -> u32 {
    let mask = ((1u64 << (32 - (length - 1).leading_zeros())) - 1) as u32;
    kensler_permute(i % length, length, mask, seed)
}

/// The 2D hash of Jarzynski & Olano's survey that Cycles keys its white-noise pixels by
/// (`hash_iqnt2d`).
#[inline(always)]
pub fn hash_iqnt2d(x: u32, y: u32) -> u32 {
    const K: u32 = 1_103_515_245;
    let qx = K.wrapping_mul((x >> 1) ^ y);
    let qy = K.wrapping_mul((y >> 1) ^ x);
    K.wrapping_mul(qx ^ (qy >> 3))
}

/// Bob Jenkins' lookup3 `final` mix over (a, b, c), as Cycles' `hash_uint*` end.
#[inline(always)]
fn lookup3_final(mut a: u32, mut b: u32, mut c: u32) -> u32 {
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(14));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(11));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(25));
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(16));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(4));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(14));
    c ^= b;
    c.wrapping_sub(b.rotate_left(24))
}

/// lookup3 of one word (`hash_uint`).
pub fn hash_uint(kx: u32) -> u32 {
    let init = 0xdead_beefu32.wrapping_add((1 << 2) + 13);
    lookup3_final(init.wrapping_add(kx), init, init)
}

/// lookup3 of two words (`hash_uint2`).
pub fn hash_uint2(kx: u32, ky: u32) -> u32 {
    let init = 0xdead_beefu32.wrapping_add((2 << 2) + 13);
    lookup3_final(init.wrapping_add(kx), init.wrapping_add(ky), init)
}

/// The base-4 variant of Cycles' `reversed_bit_owen` (which is
/// [`owen_scramble_reversed`](crate::construct::scramble::owen_scramble_reversed), Burley
/// 2020's hash with Vegdahl's constants): permutes base-4 digits as wholes
/// (`reversed_bit_owen_base4`).
#[inline(always)]
pub fn reversed_bit_owen_base4(mut n: u32, seed: u32) -> u32 {
    n ^= n.wrapping_mul(0x3d20_adea);
    n ^= (n >> 1) & (n << 1) & 0x5555_5555;
    n = n.wrapping_add(seed);
    n = n.wrapping_mul((seed >> 16) | 1);
    n ^= (n >> 1) & (n << 1) & 0x5555_5555;
    n ^= n.wrapping_mul(0x0552_6c56);
    n ^ n.wrapping_mul(0x53a2_2864)
}

/// Its base-4 variant (`nested_uniform_scramble_base4`).
#[inline(always)]
pub fn nested_uniform_scramble_base4(i: u32, seed: u32) -> u32 {
    reversed_bit_owen_base4(i.reverse_bits(), seed).reverse_bits()
}

/// The Morton code of (x, y), x's bits above y's in each pair, 16 bits of each
/// (`morton2d`).
pub fn morton2d(x: u32, y: u32) -> u32 {
    fn expand(mut v: u32) -> u32 {
        v &= 0xffff;
        v = (v ^ (v << 8)) & 0x00ff_00ff;
        v = (v ^ (v << 4)) & 0x0f0f_0f0f;
        v = (v ^ (v << 2)) & 0x3333_3333;
        (v ^ (v << 1)) & 0x5555_5555
    }
    (expand(x) << 1) | expand(y)
}

/// The adaptive sampler's two classes of samples (`sample_is_class_A`, after Christensen et
/// al. 2018, section 10.2.1): class A when the count of odd-position bits of the sample
/// index is odd.
pub fn sample_is_class_a(sample: u32) -> bool {
    (sample & 0xaaaa_aaaa).count_ones() & 1 == 1
}

/// The per-draw seeds of a 2D draw (`sobol_burley_sample_2D`): the index shuffle's, then
/// each dimension's scramble's.
const SOBOL_2D_SEEDS: [u32; 3] = [0xf8ad_e99a, 0xe0aa_af76, 0x9496_4d4e];

/// Cycles' Sobol-Burley sampler: Sobol' dimensions 0-1 (Joe & Kuo's, which Cycles'
/// `sobol_burley_table` holds bit-reversed), read through samplab's byte tables.
#[derive(Debug, Clone)]
pub(crate) struct SobolBurley {
    tables: [ByteTables; 2],
}

impl SobolBurley {
    pub(crate) fn new() -> SobolBurley {
        SobolBurley { tables: std::array::from_fn(byte_tables) }
    }

    /// Owen-scrambled Sobol' dimension `dimension` (0-1) at a bit-reversed index
    /// (`sobol_burley`), as a single.
    #[inline(always)]
    pub(crate) fn value(&self, rev_index: u32, dimension: usize, seed: u32) -> f32 {
        to_unit(owen_digits(reversed_digits(&self.tables[dimension], rev_index.reverse_bits()), seed))
    }

    /// A 2D draw of shuffled Owen-scrambled Sobol' (`sobol_burley_sample_2D`): sample
    /// `index` of the sequence `seed`, for the dimension set `set`, the shuffled index
    /// masked to `mask` (reversed: the sample count's bits). Cycles' 3D and 4D draws derive
    /// their dimensions' seeds by XOR with constants whose lowest bits are fixed, and the
    /// lowest bit of a seed alone flips a value's first digit: with 4D draws (this family's
    /// first version, 2026-12-07, 128 x 128 pixels at 4 spp) dimensions 2 and 3 were always
    /// in the same half and 1 and 3 always in opposite halves. Its 2D draws are not tied.
    #[inline(always)]
    pub(crate) fn sample_2d(&self, index: u32, set: u32, seed: u32, mask: u32) -> [f32; 2] {
        let seed = seed ^ hash_hp(set);
        let shuffled = reversed_bit_owen(index.reverse_bits(), seed ^ SOBOL_2D_SEEDS[0]) & mask;
        std::array::from_fn(|d| self.value(shuffled, d, seed ^ SOBOL_2D_SEEDS[d + 1]))
    }
}

/// The 4D patterns of Cycles' tabulated Sobol' (`tabulated_sobol_generate_4D`): `size`
/// points, each new one in the stratum its predecessor leaves empty, with a jitter from
/// hashes seeded by `pattern` (an Owen-scrambled Sobol' set drawn by stratification).
pub fn tabulated_sobol(size: usize, pattern: u32) -> Vec<[f32; 4]> {
    let mut points = vec![[0.0f32; 4]; size];
    let mut rng = hash_hp_seeded(pattern, 0x4460_5a73);
    let mut next = || {
        let v = to_unit(hash_hp(rng));
        rng = rng.wrapping_add(1);
        v
    };
    if size == 0 {
        return points;
    }
    for v in &mut points[0] {
        *v = next();
    }
    let mut n = 1;
    let mut log_n = 0;
    while n < size {
        let strata = (n * 2) as f32;
        for i in 0..n.min(size - n) {
            let mut point = [0.0f32; 4];
            for (d, v) in point.iter_mut().enumerate() {
                let occupied = (points[i ^ TABULATED_XORS[d][log_n] as usize][d] * strata) as u32;
                *v = ((occupied ^ 1) as f32 + next()) / strata;
            }
            points[n + i] = point;
        }
        n *= 2;
        log_n += 1;
    }
    points
}

/// The strata visiting orders of [`tabulated_sobol`] per dimension and level (Cycles'
/// `xors` table: they make the stratification an Owen-scrambled Sobol' set's).
const TABULATED_XORS: [[u32; 32]; 4] = [
    [0; 32],
    [
        0x00000000, 0x00000001, 0x00000001, 0x00000007, 0x00000001, 0x00000013, 0x00000015, 0x0000007f, 0x00000001,
        0x00000103, 0x00000105, 0x0000070f, 0x00000111, 0x00001333, 0x00001555, 0x00007fff, 0x00000001, 0x00010003,
        0x00010005, 0x0007000f, 0x00010011, 0x00130033, 0x00150055, 0x007f00ff, 0x00010101, 0x01030303, 0x01050505,
        0x070f0f0f, 0x01111111, 0x13333333, 0x15555555, 0x7fffffff,
    ],
    [
        0x00000000, 0x00000001, 0x00000003, 0x00000001, 0x00000005, 0x0000001f, 0x0000002b, 0x0000003d, 0x00000011,
        0x00000133, 0x00000377, 0x00000199, 0x00000445, 0x00001ccf, 0x00002ddb, 0x0000366d, 0x00000101, 0x00010303,
        0x00030707, 0x00010909, 0x00051515, 0x001f3f3f, 0x002b6b6b, 0x003dbdbd, 0x00101011, 0x01303033, 0x03707077,
        0x01909099, 0x04515145, 0x1cf3f3cf, 0x2db6b6db, 0x36dbdb6d,
    ],
    [
        0x00000000, 0x00000001, 0x00000000, 0x00000003, 0x0000000d, 0x0000000c, 0x00000005, 0x0000004f, 0x00000014,
        0x000000e7, 0x00000329, 0x0000039c, 0x00000011, 0x00001033, 0x00000044, 0x000030bb, 0x0000d1cd, 0x0000c2ec,
        0x00005415, 0x0004fc3f, 0x00015054, 0x000e5c97, 0x0032e5b9, 0x0039725c, 0x00000101, 0x01000303, 0x00000404,
        0x03000b0b, 0x0d001d1d, 0x0c002c2c, 0x05004545, 0x4f00cfcf,
    ],
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hashes_are_permutations_where_cycles_says_so() {
        // hash_shuffle permutes 0 .. length for any length and seed
        for (length, seed) in [(256, 7u32), (100, 0xdead_beef), (1, 3)] {
            let mut seen = vec![false; length as usize];
            for i in 0..length {
                let j = hash_shuffle(i, length, seed) as usize;
                assert!(!std::mem::replace(&mut seen[j], true));
            }
        }
        // the nested scrambles permute: every 8-bit prefix maps to a distinct one
        for scramble in [nested_uniform_scramble, nested_uniform_scramble_base4] {
            let mut images: Vec<u32> = (0..256u32).map(|i| scramble(i << 24, 0x1234_5678) >> 24).collect();
            images.sort_unstable();
            assert!(images.iter().enumerate().all(|(i, &v)| v == i as u32));
        }
    }

    #[test]
    fn the_byte_tables_are_cycles_bit_loop_over_the_direction_numbers() {
        // Cycles' loop: each set bit of the reversed index, from the top, selects a
        // bit-reversed direction number
        let sobol = SobolBurley::new();
        for d in 0..2 {
            let directions = crate::construct::sobol::direction_numbers(d);
            for rev in [1u32, 0x8000_0000, 0xdead_beef, 0x0123_4567, u32::MAX] {
                let want =
                    (0..32).filter(|p| rev >> (31 - p) & 1 == 1).fold(0, |x, p| x ^ directions[p].reverse_bits());
                let seed = 0x9e37_79b9;
                assert_eq!(sobol.value(rev, d, seed), to_unit(reversed_bit_owen(want, seed).reverse_bits()));
            }
        }
    }

    #[test]
    fn a_tabulated_pattern_is_stratified_in_each_dimension() {
        let points = tabulated_sobol(256, 3);
        for d in 0..4 {
            let mut seen = [false; 256];
            for p in &points {
                assert!(!std::mem::replace(&mut seen[(p[d] * 256.0) as usize], true), "dimension {d}");
            }
        }
    }

    #[test]
    fn class_a_is_half_of_every_aligned_group_of_four() {
        for base in (0..64).step_by(4) {
            assert_eq!((base..base + 4).filter(|&s| sample_is_class_a(s)).count(), 2);
        }
    }
}
