//! Randomizations of digital sequences, as their own axis (none, random digit scrambling,
//! Owen scrambling, Cranley–Patterson shift), and the hash-based permutations they use.

/// How a low-discrepancy construction is randomized.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
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
    /// Linear matrix scrambling (Matousek 1998), then a digital shift: each generating
    /// matrix C_j replaced by L_j C_j, L_j lower triangular with a non-zero diagonal (the
    /// digital nets, which have matrices).
    Lms,
    /// Cranley–Patterson rotation (Cranley & Patterson 1976): one uniform offset per
    /// dimension, added modulo 1. Keeps the set a toroidal translate of the original; it
    /// does not preserve elementary-interval stratification. No construction applies it
    /// itself: every family's `.shift` is its plain construction under the `+shift`
    /// stage's code (64-bit fixed point).
    Shift,
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

/// Element i of a permutation of 0 .. l keyed by p: Kensler's (2013) hash of i within
/// the bits of `mask` (the least all-ones word covering l - 1, as the caller rounds it),
/// walked until it falls below l. pbrt-v4's `PermutationElement` and Cycles'
/// `hash_shuffle_uint` are this walk with their own masks and ends.
#[inline(always)]
pub fn kensler_permute(mut i: u32, l: u32, mask: u32, p: u32) -> u32 {
    loop {
        i ^= p;
        i = i.wrapping_mul(0xe170_893d);
        i ^= p >> 16;
        i ^= (i & mask) >> 4;
        i ^= p >> 8;
        i = i.wrapping_mul(0x0929_eb3f);
        i ^= p >> 23;
        i ^= (i & mask) >> 1;
        i = i.wrapping_mul(1 | p >> 27);
        i = i.wrapping_mul(0x6935_fa69);
        i ^= (i & mask) >> 11;
        i = i.wrapping_mul(0x74dc_b303);
        i ^= (i & mask) >> 2;
        i = i.wrapping_mul(0x9e50_1cc3);
        i ^= (i & mask) >> 2;
        i = i.wrapping_mul(0xc860_a3df);
        i &= mask;
        i ^= i >> 5;
        if i < l {
            return i;
        }
    }
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

/// Owen's nested uniform scrambling in base b (Owen 1995) of digit strings that end: the
/// string y_0 y_1 ... y_(m-1) 0 0 ... (most significant first, y_(m-1) != 0) is given as the
/// integer Y = sum y_j b^j (for a radical inverse, the index itself), and [`OwenDigits::value`]
/// is its scrambled value in [0, 1).
///
/// The node of the digit tree at depth j with prefix p = Y mod b^j permutes digit j by a
/// random affine map pi(a) = (alpha a + t) mod b, alpha uniform in 1..b-1 and t uniform,
/// independent across nodes (b prime). The affine maps are sharply 2-transitive: each digit
/// goes to a uniform digit and any two distinct digits to a uniform pair of distinct digits,
/// the distributions Owen's variance of scrambled nets is computed from (Owen 1997); the
/// nesting is Owen's (1995), the affine digit maps Matousek's (1998). (Kensler's hash
/// permutation, used here before, is far from pair-uniform for small lengths: for b = 5,
/// digit pairs one apart came three times as often as pairs two apart.)
///
/// Every node (j, p) lies on p's own path below its last non-zero digit (j >= m(p)), so its
/// t and alpha are taken as digit j - m(p) of two 64-bit hashes of p, U(p) in base b and
/// V(p) in base b - 1: one pair of hashes per prefix, computed when the prefix changes (at a
/// non-zero digit), and the endless zeros after a string's end scramble to U(Y) b^-m(Y) at
/// once. A value is (D + U(Y) 2^-64) b^-m, D the integer of the m scrambled digits; the
/// first J digits' D is tabulated for every prefix below b^J (b^J at most the table bound
/// given, and 2^16; built level by level, one step per entry): the table is a cache of the
/// same arithmetic, so every path gives the same bits.
#[derive(Debug, Clone)]
pub(crate) struct OwenDigits {
    base: u64,
    by_base: Divisor,
    by_low: Divisor,
    key: u64,
    /// b^k and (b-1)^k mod 2^64 (shifting a 64-bit fraction by k digits).
    pow: [[u64; 65]; 2],
    /// b^-m as f64.
    inv: [f64; 65],
    /// J and b^J.
    low_digits: usize,
    low: u64,
    /// For each L < b^J: D of its J digits (the first J digits of every longer string),
    /// shifted left by 8, and m(L) in the low byte.
    table: Vec<u64>,
    /// For each L < b^J: its own scrambled value.
    small: Vec<f64>,
    /// b^M, M the most digits whose D fits 64 bits (u64::MAX when every string's does).
    narrow: u64,
}

/// The state of a scramble after some digits: depth, prefix p, m(p), b^depth, U(p), and D
/// so far (exact: in 64 bits while Y < b^M, b^M <= 2^64, else in 128).
#[derive(Clone, Copy)]
struct Walk<D> {
    depth: usize,
    prefix: u64,
    ends: usize,
    power: u64,
    u: u64,
    d: D,
}

/// A divisor below 2^32 prepared for division by multiplication (Lemire, Kaser & Kurz
/// 2019): for x < 2^32, x / d = floor(ceil(2^64 / d) x / 2^64); a hardware division costs
/// several times the latency, and the digit loop's quotients depend on each other.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Divisor {
    d: u64,
    magic: u64,
}

impl Divisor {
    pub(crate) fn new(d: u64) -> Divisor {
        Divisor { d, magic: if d.is_power_of_two() { 0 } else { u64::MAX / d + 1 } }
    }

    /// (x / d, x mod d).
    #[inline(always)]
    pub(crate) fn divide(self, x: u64) -> (u64, u64) {
        if self.magic == 0 {
            (x >> self.d.trailing_zeros(), x & (self.d - 1))
        } else if x >> 32 == 0 {
            let q = ((u128::from(self.magic) * u128::from(x)) >> 64) as u64;
            (q, x - q * self.d)
        } else {
            (x / self.d, x % self.d)
        }
    }
}

/// The leading base-`base` digit of the 64-bit fraction `x`.
#[inline(always)]
fn leading(x: u64, base: u64) -> u64 {
    ((u128::from(x) * u128::from(base)) >> 64) as u64
}

impl OwenDigits {
    /// The scramble of prime base `base` (below 2^32) keyed by `key`, with prefix tables of
    /// at most `bound` entries.
    pub(crate) fn new(base: u32, key: u64, bound: u64) -> OwenDigits {
        let b = u64::from(base);
        let mut pow = [[1u64; 65]; 2];
        let mut inv = [1.0f64; 65];
        for k in 1..65 {
            pow[0][k] = pow[0][k - 1].wrapping_mul(b);
            pow[1][k] = pow[1][k - 1].wrapping_mul(b - 1);
            inv[k] = inv[k - 1] / b as f64;
        }
        let bound = bound.clamp(1, 1 << 16);
        let (mut low_digits, mut low) = (0, 1u64);
        while low * b <= bound {
            low *= b;
            low_digits += 1;
        }
        let digits = (1..=64).take_while(|&m| u128::from(b).pow(m) <= 1 << 64).last().expect("b < 2^32");
        let narrow = b.checked_pow(digits).unwrap_or(u64::MAX);
        let mut o = OwenDigits {
            base: b,
            by_base: Divisor::new(b),
            by_low: Divisor::new(low),
            key,
            pow,
            inv,
            low_digits,
            low,
            table: Vec::new(),
            small: Vec::new(),
            narrow,
        };
        // level by level: the walk of L' = L + a b^j is one step from the walk of L, and L's
        // own value is read off where its last digit was placed
        let mut small = vec![0.0; low as usize];
        small[0] = o.end(&o.root());
        let mut walks = vec![o.root()];
        for _ in 0..low_digits {
            let size = walks.len();
            let mut next = Vec::with_capacity(size * b as usize);
            for a in 0..b {
                for w in &walks {
                    let mut w = *w;
                    o.step(&mut w, a);
                    if a != 0 {
                        small[next.len()] = o.end(&w);
                    }
                    next.push(w);
                }
            }
            walks = next;
        }
        o.table = walks.iter().map(|w| (w.d << 8) | w.ends as u64).collect(); // D < b^J <= 2^16
        o.small = small;
        o
    }

    /// U(p): 64 uniform bits per prefix.
    #[inline(always)]
    fn hash(&self, prefix: u64) -> u64 {
        crate::seed::mix64(self.key ^ prefix.wrapping_mul(0x9e37_79b9_7f4a_7c15))
    }

    fn root(&self) -> Walk<u64> {
        Walk { depth: 0, prefix: 0, ends: 0, power: 1, u: self.hash(0), d: 0 }
    }

    /// Scramble digit `a` at the walk's node and move below it.
    #[inline(always)]
    fn step<D: Accumulate>(&self, w: &mut Walk<D>, a: u64) {
        let b = self.base;
        let k = w.depth - w.ends;
        let t = leading(w.u.wrapping_mul(self.pow[0][k]), b);
        let digit = if a == 0 {
            t
        } else {
            let r = if b == 2 {
                a
            } else {
                let v = crate::seed::mix64(w.u ^ 0xd6e8_feb8_6659_fd93);
                self.by_base.divide((1 + leading(v.wrapping_mul(self.pow[1][k]), b - 1)) * a).1
            };
            w.prefix += a * w.power;
            w.ends = w.depth + 1;
            w.u = self.hash(w.prefix);
            if r + t >= b { r + t - b } else { r + t }
        };
        w.d = w.d.push(b, digit);
        w.power = w.power.wrapping_mul(b);
        w.depth += 1;
    }

    /// The scrambled value of the string whose integer is `y`.
    #[inline]
    pub(crate) fn value(&self, y: u64) -> f64 {
        if y < self.low {
            return self.small[y as usize];
        }
        let (rest, l) = self.by_low.divide(y);
        let entry = self.table[l as usize];
        let w = Walk {
            depth: self.low_digits,
            prefix: l,
            ends: (entry & 0xff) as usize,
            power: self.low,
            u: self.hash(l),
            d: entry >> 8,
        };
        if y < self.narrow {
            self.finish(w, rest)
        } else {
            let Walk { depth, prefix, ends, power, u, d } = w;
            self.finish(Walk { depth, prefix, ends, power, u, d: u128::from(d) }, rest)
        }
    }

    /// The value from the walk `w` over a string's digits so far, `rest` = the digits still
    /// to come (Y / b^depth): at the end the prefix is Y and `w.u` = U(Y) gives the tail.
    #[inline(always)]
    fn finish<D: Accumulate>(&self, mut w: Walk<D>, mut rest: u64) -> f64 {
        while rest != 0 {
            let (q, a) = self.by_base.divide(rest);
            self.step(&mut w, a);
            rest = q;
        }
        self.end(&w)
    }

    /// The value of a walk at its string's end (its prefix is Y, its depth m(Y)).
    #[inline(always)]
    fn end<D: Accumulate>(&self, w: &Walk<D>) -> f64 {
        ((w.d.to_f64() + (w.u >> 11) as f64 * (1.0 / (1u64 << 53) as f64)) * self.inv[w.depth])
            .min(crate::numeric::BELOW_ONE)
    }
}

/// The integer D of scrambled digits, in 64 or 128 bits (the same value, correctly rounded
/// to f64 either way).
trait Accumulate: Copy {
    /// D b + digit.
    fn push(self, b: u64, digit: u64) -> Self;
    /// D, correctly rounded.
    fn to_f64(self) -> f64;
}

impl Accumulate for u64 {
    #[inline(always)]
    fn push(self, b: u64, digit: u64) -> u64 {
        self * b + digit
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
}

impl Accumulate for u128 {
    #[inline(always)]
    fn push(self, b: u64, digit: u64) -> u128 {
        self * u128::from(b) + u128::from(digit)
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
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
