//! Radical inverses in prime bases (van der Corput 1935, Halton 1960): the first primes,
//! and the digit tables that sum an index's base-b digits (identity or randomly permuted
//! per position, Matousek 1998) into a coordinate.

use super::scramble::Divisor;
use crate::numeric::BELOW_ONE;
use crate::seed::{Seed, shuffle};

/// How many primes [`PRIMES`] holds.
pub const PRIME_COUNT: usize = 1024;

/// The first [`PRIME_COUNT`] primes (by trial division, at compile time).
pub static PRIMES: [u32; PRIME_COUNT] = first_primes();

const fn first_primes() -> [u32; PRIME_COUNT] {
    let mut primes = [0u32; PRIME_COUNT];
    let (mut found, mut c) = (0, 2u32);
    while found < PRIME_COUNT {
        let mut k = 0;
        while k < found && primes[k] * primes[k] <= c && c % primes[k] != 0 {
            k += 1;
        }
        if k == found || primes[k] * primes[k] > c {
            primes[found] = c;
            found += 1;
        }
        c += 1;
    }
    primes
}

/// The unscrambled radical inverse of `index` in `base` (van der Corput for base 2).
pub fn radical_inverse(index: u64, base: u32) -> f64 {
    DigitTable::new(base, None).value(index)
}

/// The digit weights of one coordinate, b^-(j+1) for positions j < P, and (random digit
/// scrambling) the permuted digits' terms `scaled[j*b + a] = pi_j(a) b^-(j+1)` with
/// `tail[m]`, the contribution of positions m..P when those digits are zero. The identity's
/// terms a b^-(j+1) are computed as they are needed (the same products, so the same bits):
/// a plan holds only the weights, a few dozen numbers per base.
#[derive(Debug, Clone)]
pub(crate) struct DigitTable {
    /// The base b.
    pub(crate) base: u32,
    /// The base, prepared for division by multiplication (random access's digits).
    by_base: Divisor,
    weights: Vec<f64>,
    permuted: Option<Permuted>,
}

/// The terms of randomly permuted digits ([`DigitTable`]).
#[derive(Debug, Clone)]
struct Permuted {
    scaled: Vec<f64>,
    tail: Vec<f64>,
}

fn positions(base: u32) -> usize {
    (53.0 / f64::from(base).log2()).ceil() as usize + 1
}

impl DigitTable {
    /// Identity digits (`perms = None`) or one random permutation per position.
    pub(crate) fn new(base: u32, perm_seed: Option<Seed>) -> Self {
        let (b, p) = (base as usize, positions(base));
        let mut weights = Vec::with_capacity(p);
        let mut weight = 1.0 / f64::from(base);
        for _ in 0..p {
            weights.push(weight);
            weight /= f64::from(base);
        }
        let permuted = perm_seed.map(|seed| {
            let mut rng = seed.rng();
            let mut perm: Vec<u32> = (0..base).collect();
            let mut scaled = Vec::with_capacity(p * b);
            for &weight in &weights {
                shuffle(&mut rng, &mut perm);
                scaled.extend(perm.iter().map(|&a| f64::from(a) * weight));
            }
            let mut tail = vec![0.0; p + 1];
            for m in (0..p).rev() {
                tail[m] = tail[m + 1] + scaled[m * b];
            }
            Permuted { scaled, tail }
        });
        DigitTable { base, by_base: Divisor::new(u64::from(base)), weights, permuted }
    }

    /// The term of digit `a` at position `j`.
    #[inline]
    pub(crate) fn term(&self, j: usize, a: u32) -> f64 {
        match &self.permuted {
            Some(t) => t.scaled[j * self.base as usize + a as usize],
            None => f64::from(a) * self.weights[j],
        }
    }

    /// The contribution of positions m..P when their digits are zero.
    #[inline]
    pub(crate) fn tail(&self, m: usize) -> f64 {
        self.permuted.as_ref().map_or(0.0, |t| t.tail[m])
    }

    pub(crate) fn value(&self, mut index: u64) -> f64 {
        let mut digits = [0u32; 64];
        let mut m = 0;
        while index != 0 {
            let (q, r) = self.by_base.divide(index);
            digits[m] = r as u32;
            index = q;
            m += 1;
        }
        // from the last digit up (as the odometer sums), each table's loop on its own
        let v = match &self.permuted {
            None => (0..m).rev().fold(0.0, |v, j| v + f64::from(digits[j]) * self.weights[j]),
            Some(t) => {
                let b = self.base as usize;
                (0..m).rev().fold(t.tail[m], |v, j| v + t.scaled[j * b + digits[j] as usize])
            }
        };
        v.min(BELOW_ONE)
    }
}
