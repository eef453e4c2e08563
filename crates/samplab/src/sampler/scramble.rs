//! Randomizations of digital sequences, as their own axis (none, random digit scrambling,
//! Owen scrambling, Cranley–Patterson shift), and the hash-based permutations they use.

/// How a low-discrepancy construction is randomized.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Randomization {
    /// The deterministic construction.
    None,
    /// Random digit scrambling (Matousek 1998): one random permutation of the digits per
    /// digit position and dimension; in base 2 this is an XOR with random bits (a digital
    /// shift). Preserves (t,m,s)-net properties.
    Xor,
    /// Owen's nested uniform scrambling (Owen 1995), hash-based (Burley 2020): the
    /// permutation of each digit depends on all the digits before it. Preserves
    /// (t,m,s)-net properties.
    Owen,
    /// Cranley–Patterson rotation (Cranley & Patterson 1976): one uniform offset per
    /// dimension, added modulo 1. Keeps the set a toroidal translate of the original; it
    /// does not preserve elementary-interval stratification.
    Shift,
}

impl Randomization {
    /// The variant suffix used in sampler names ("", "xor", "owen", "shift").
    pub fn suffix(self) -> &'static str {
        match self {
            Randomization::None => "",
            Randomization::Xor => "xor",
            Randomization::Owen => "owen",
            Randomization::Shift => "shift",
        }
    }
}

/// A nested uniform scramble of a 32-bit fixed-point value, whose bits are read most
/// significant first (Burley 2020, section 3). Each output bit is the input bit XOR a
/// hash of the bits above it.
#[inline]
pub fn owen_scramble_u32(x: u32, seed: u32) -> u32 {
    owen_scramble_reversed(x.reverse_bits(), seed).reverse_bits()
}

/// The same scramble applied in the bit-reversed domain (bit 0 is the most significant
/// digit), where it is a Laine–Karras style hash: every operation lets bit k depend only
/// on bits below k. Constants from Vegdahl 2021.
#[inline(always)]
pub fn owen_scramble_reversed(mut x: u32, seed: u32) -> u32 {
    x ^= x.wrapping_mul(0x3d20_adea);
    x = x.wrapping_add(seed);
    x = x.wrapping_mul((seed >> 16) | 1);
    x ^= x.wrapping_mul(0x0552_6c56);
    x ^= x.wrapping_mul(0x53a2_2864);
    x
}

/// A 32-bit hash of two words (for per-node permutation seeds).
#[inline]
pub fn hash2(a: u32, b: u32) -> u32 {
    (crate::seed::mix64((u64::from(a) << 32) | u64::from(b)) >> 32) as u32
}

/// Element `i` of a pseudo-random permutation of 0..len keyed by `key` (Kensler 2013,
/// section 3, "permute"): a keyed bijection on the smallest power-of-two range holding
/// len, iterated until it lands below len (cycle walking), which makes it a bijection on
/// 0..len. Requires i < len.
#[inline]
pub fn permute(mut i: u32, len: u32, key: u32) -> u32 {
    debug_assert!(i < len);
    if len <= 1 {
        return 0;
    }
    let mask = u32::MAX >> (len - 1).leading_zeros();
    loop {
        // each step is a bijection on 0..=mask
        i ^= key;
        i = i.wrapping_mul(0xe170_893d) & mask;
        i ^= key >> 16;
        i ^= (i & mask) >> 4;
        i ^= key >> 8;
        i = i.wrapping_mul(0x0929_eb3f) & mask;
        i ^= key >> 23;
        i ^= (i & mask) >> 1;
        i = i.wrapping_mul(1 | key >> 27) & mask;
        i = i.wrapping_mul(0x6935_fa69) & mask;
        i ^= (i & mask) >> 11;
        i = i.wrapping_mul(0x74dc_b303) & mask;
        i ^= (i & mask) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3) & mask;
        i ^= (i & mask) >> 2;
        i = i.wrapping_mul(0xc860_a3df) & mask;
        i ^= (i & mask) >> 5;
        if i < len {
            return i;
        }
    }
}

/// A uniform f64 in [0,1) from hashing (index, key), 53 bits.
#[inline]
pub fn hash_unit(index: u64, key: u64) -> f64 {
    let h = crate::seed::mix64(index ^ crate::seed::mix64(key));
    (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_bijection_for_many_lengths_and_keys() {
        for len in [1u32, 2, 3, 5, 7, 16, 17, 100, 1000] {
            for key in [0u32, 1, 0xdead_beef, 12345] {
                let mut seen = vec![false; len as usize];
                for i in 0..len {
                    let j = permute(i, len, key) as usize;
                    assert!(!seen[j], "len {len} key {key}: {j} twice");
                    seen[j] = true;
                }
            }
        }
    }

    #[test]
    fn owen_scramble_is_nested() {
        // Two inputs that share their top k bits give outputs that share their top k bits,
        // and the bit below differs in the output exactly when it differs in the input.
        let seed = 0x1234_5678;
        for (a, b) in [(0x8000_0000u32, 0xC000_0000u32), (0x1234_0000, 0x1235_0000), (5, 4)] {
            let k = (a ^ b).leading_zeros();
            let (sa, sb) = (owen_scramble_u32(a, seed), owen_scramble_u32(b, seed));
            assert_eq!((sa ^ sb).leading_zeros(), k, "{a:x} {b:x}");
        }
    }

    #[test]
    fn owen_scramble_permutes_every_level() {
        // On 8-bit prefixes, the scramble is a bijection.
        let mut seen = [false; 256];
        for v in 0u32..256 {
            let s = owen_scramble_u32(v << 24, 99) >> 24;
            assert!(!seen[s as usize]);
            seen[s as usize] = true;
        }
    }
}
