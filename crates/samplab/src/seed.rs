//! Seeds, sub-seed derivation by hashing, and the one portable RNG.
//!
//! Realization `k` of a batch uses `seed.derive(k)`, never `seed + k`: sub-seeds are
//! hashed, so batches split across threads give bit-identical results, and neighbouring
//! seeds give unrelated streams.

use rand::distr::Distribution;
use rand_core::Rng as _;
use rand_distr::StandardNormal;

/// The one random number generator of samplab: PCG64 (XSL-RR 128/64, O'Neill 2014),
/// from the `rand_pcg` crate. Its output for a seed never changes with a crate upgrade.
pub type Rng = rand_pcg::Pcg64;

/// The seed of every random choice samplab makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
pub struct Seed(pub u64);

impl Seed {
    /// The CLI's default seed, printed in every output header.
    pub const DEFAULT: Seed = Seed(0x5A3D_1AB0);

    /// A sub-seed for `key`, by hashing (seed, key).
    pub fn derive(self, key: u64) -> Seed {
        Seed(mix64(mix64(self.0 ^ 0x9E37_79B9_7F4A_7C15).wrapping_add(key)))
    }

    /// A sub-seed for a named purpose (e.g. "offset", "permutation x").
    pub fn derive_str(self, label: &str) -> Seed {
        let mut h = 0xCBF2_9CE4_8422_2325u64; // FNV-1a over the label, then mixed
        for b in label.bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01B3);
        }
        self.derive(mix64(h))
    }

    /// The RNG this seed starts.
    pub fn rng(self) -> Rng {
        let hi = mix64(self.0);
        let lo = mix64(hi ^ self.0);
        Rng::new((u128::from(hi) << 64) | u128::from(lo), 0xA02B_DBF7_BB3C_0A7A_C28F_A16A_64AB_F96D)
    }

    /// 32 hashed bits for stateless per-index randomness (scrambling seeds).
    pub fn bits32(self) -> u32 {
        (mix64(self.0) >> 32) as u32
    }
}

/// A 64-bit finalizing hash (the SplitMix64 mixer, Steele, Lea & Flood 2014).
pub fn mix64(mut x: u64) -> u64 {
    x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^ (x >> 31)
}

/// A uniform draw in [0, 1) with 53 random bits.
#[inline]
pub fn uniform(rng: &mut Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A uniform integer in [0, bound), without modulo bias (Lemire 2019, "Fast random integer
/// generation in an interval", Algorithm 5): the division that sets the rejection threshold
/// is done only when the low word falls below `bound`, which the threshold never exceeds.
#[inline]
pub fn below(rng: &mut Rng, bound: u64) -> u64 {
    debug_assert!(bound > 0);
    let mut m = u128::from(rng.next_u64()) * u128::from(bound);
    if (m as u64) < bound {
        let threshold = bound.wrapping_neg() % bound;
        while (m as u64) < threshold {
            m = u128::from(rng.next_u64()) * u128::from(bound);
        }
    }
    (m >> 64) as u64
}

/// A standard normal draw (Ziggurat, rand_distr).
#[inline]
pub fn normal(rng: &mut Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// A uniformly random permutation of 0..n (Fisher–Yates).
pub fn permutation(rng: &mut Rng, n: usize) -> Vec<u32> {
    let mut p: Vec<u32> = (0..n as u32).collect();
    shuffle(rng, &mut p);
    p
}

/// Shuffle `items` in place by the same draws as [`permutation`] (Fisher–Yates).
pub fn shuffle<T>(rng: &mut Rng, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        let j = below(rng, i as u64 + 1) as usize;
        items.swap(i, j);
    }
}

/// Wrap a real number into [0, 1) (toroidal boundary).
#[inline(always)]
pub fn wrap01(x: f64) -> f64 {
    let y = x - x.floor();
    // x.floor() can round so that y == 1.0 for tiny negative x
    if y >= 1.0 { 0.0 } else { y }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derive_is_a_hash_not_an_offset() {
        let s = Seed(7);
        assert_ne!(s.derive(1), Seed(8));
        assert_ne!(s.derive(1), s.derive(2));
        assert_eq!(s.derive(3), Seed(7).derive(3));
        assert_ne!(s.derive_str("x"), s.derive_str("y"));
    }

    #[test]
    fn uniform_in_unit_interval_and_seeded() {
        let mut a = Seed(1).rng();
        let mut b = Seed(1).rng();
        for _ in 0..1000 {
            let x = uniform(&mut a);
            assert!((0.0..1.0).contains(&x));
            assert_eq!(x.to_bits(), uniform(&mut b).to_bits());
        }
    }

    #[test]
    fn below_is_unbiased_enough() {
        let mut rng = Seed(3).rng();
        let mut counts = [0u32; 3];
        for _ in 0..30_000 {
            counts[below(&mut rng, 3) as usize] += 1;
        }
        // each count ~ Binomial(30000, 1/3): sd ~ 82; 5 sd bound
        assert!(counts.iter().all(|&c| (c as i64 - 10_000).abs() < 410), "{counts:?}");
    }

    #[test]
    fn permutation_is_a_permutation() {
        let mut p = permutation(&mut Seed(5).rng(), 100);
        p.sort();
        assert_eq!(p, (0..100).collect::<Vec<u32>>());
    }

    #[test]
    fn wrap01_edges() {
        assert_eq!(wrap01(1.0), 0.0);
        assert_eq!(wrap01(-1e-300), 0.0);
        assert_eq!(wrap01(1.25), 0.25);
        assert_eq!(wrap01(-0.25), 0.75);
    }
}
