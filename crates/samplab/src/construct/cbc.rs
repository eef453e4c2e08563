//! Component-by-component construction of rank-1 lattice generating vectors, fast
//! (Nuyens & Cools 2006): O(s n log n) for n prime or a power of 2, where the naive search
//! costs O(s n^2).
//!
//! The criterion is the squared worst-case error of the weighted Korobov space with
//! smoothness alpha = 2 and product weights gamma_j (Sloan & Joe 1994, eq. 5.9 for gamma = 1):
//!
//!   e^2(z) = -1 + (1/n) sum_i prod_j (1 + gamma_j omega({i z_j / n})),  omega(x) = 2 pi^2 B_2(x),
//!
//! with gamma_j = gamma_1 j^-decay (j from 1). z_1 = 1; component s is the candidate minimizing
//! sum_i q_i omega({i z / n}), q_i the product over the components already chosen. Since
//! omega(x) = omega(1 - x), z and n - z are equivalent, and the candidates are the units
//! mod n up to sign. Ordered as powers of a generator of that group (a primitive root for
//! prime n, 5 for n = 2^m), the sum is a cyclic correlation, computed by FFT (Nuyens &
//! Cools 2006, sections 3 and 5); for n = 2^m the indices i = 2^l u (u odd) split into
//! levels, each a correlation of length 2^(m-l-2).
//!
//! Embedded rules (Cools, Kuo & Nuyens 2006): for n = 2^m the first 2^k points in
//! radical-inverse order are the lattice of 2^k points with the same z (mod 2^k), and the
//! levels l >= m - k give its error for every k at once. The embedded construction takes
//! the candidate whose largest ratio e_k^2(z) / min_z' e_k^2(z') over k = 1..m is smallest:
//! no prefix is far from the best lattice of its own size.

use std::sync::Arc;

use rayon::prelude::*;

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

use crate::error::{Error, Result};

/// omega(x) = 2 pi^2 B_2(x), B_2(x) = x^2 - x + 1/6.
#[inline]
pub fn omega(x: f64) -> f64 {
    2.0 * std::f64::consts::PI * std::f64::consts::PI * (x * x - x + 1.0 / 6.0)
}

/// Product weights gamma_j = first j^-decay (j from 1): `first` scales every coordinate
/// alike (Lattice Builder's `product:w` is first = w, decay = 0), `decay` orders them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Weights {
    /// gamma_1.
    pub first: f64,
    /// The exponent of j's decay.
    pub decay: f64,
}

impl Weights {
    /// gamma_j = j^-decay.
    pub fn decaying(decay: f64) -> Weights {
        Weights { first: 1.0, decay }
    }

    /// The weight of component j (from 0): first (j + 1)^-decay.
    pub fn gamma(self, j: usize) -> f64 {
        self.first * ((j + 1) as f64).powf(-self.decay)
    }
}

/// The squared worst-case error e^2(z) of the lattice (module docs), by its definition:
/// O(n s).
pub fn worst_case_error(z: &[u64], n: usize, weights: Weights) -> f64 {
    let sum: f64 = (0..n as u128)
        .map(|i| {
            z.iter()
                .enumerate()
                .map(|(j, &zj)| 1.0 + weights.gamma(j) * omega((i * u128::from(zj) % n as u128) as f64 / n as f64))
                .product::<f64>()
        })
        .sum();
    sum / n as f64 - 1.0
}

/// The largest n the fast construction takes (its work arrays hold n doubles).
pub const MAX_N: usize = 1 << 24;

/// Whether the fast construction takes n: a prime or a power of 2, up to [`MAX_N`].
pub fn supports(n: usize) -> bool {
    n <= MAX_N && (n.is_power_of_two() || is_prime(n))
}

fn is_prime(n: usize) -> bool {
    n >= 2 && (2..).take_while(|k| k * k <= n).all(|k| !n.is_multiple_of(k))
}

/// One level of the search: indices `index[t]` of q (two per group element for n = 2^m,
/// one for a prime), and omega at the group's powers, `w[t] = omega(g^t mod n' / n')`.
struct Level {
    /// Pairs of q indices whose weights add (a unit and its negative), per group power.
    index: Vec<[usize; 2]>,
    /// omega at the group's powers.
    w: Vec<f64>,
    /// The FFT of w, for the correlation.
    w_hat: Vec<Complex<f64>>,
    fft: Arc<dyn rustfft::Fft<f64>>,
    ifft: Arc<dyn rustfft::Fft<f64>>,
    /// log2 of this level's n' for n = 2^m (points 2^l u), unused for primes.
    level: u32,
}

impl Level {
    fn new(index: Vec<[usize; 2]>, w: Vec<f64>, planner: &mut FftPlanner<f64>, level: u32) -> Level {
        let len = w.len();
        let (fft, ifft) = (planner.plan_fft_forward(len), planner.plan_fft_inverse(len));
        let mut w_hat: Vec<Complex<f64>> = w.iter().map(|&x| Complex::new(x, 0.0)).collect();
        fft.process(&mut w_hat);
        Level { index, w, w_hat, fft, ifft, level }
    }

    /// c[k] = sum_t a[t] w[(t + k) mod len] with a[t] = the q weights of group power t.
    fn correlate(&self, q: &[f64]) -> Vec<f64> {
        let len = self.w.len();
        let mut a: Vec<Complex<f64>> = self.index.iter().map(|&[i, j]| Complex::new(q[i] + q[j], 0.0)).collect();
        if len <= 16 {
            return (0..len).map(|k| (0..len).map(|t| a[t].re * self.w[(t + k) % len]).sum()).collect();
        }
        self.fft.process(&mut a);
        for (x, w) in a.iter_mut().zip(&self.w_hat) {
            *x = x.conj() * w;
        }
        self.ifft.process(&mut a);
        a.iter().map(|x| x.re / len as f64).collect()
    }
}

/// The candidates (units mod n up to sign, as powers of a generator) and the levels whose
/// correlations give every candidate's sum.
struct Search {
    n: usize,
    candidates: Vec<u64>,
    levels: Vec<Level>,
    /// Indices i whose omega({i z / n}) is the same for every candidate, by level (i = 0,
    /// and the levels with n' <= 4 for n = 2^m).
    constant: Vec<(u32, usize, f64)>,
}

fn pow_mod(mut base: u64, mut exp: u64, n: u64) -> u64 {
    let mut r = 1u64 % n;
    base %= n;
    while exp > 0 {
        if exp & 1 == 1 {
            r = (u128::from(r) * u128::from(base) % u128::from(n)) as u64;
        }
        base = (u128::from(base) * u128::from(base) % u128::from(n)) as u64;
        exp >>= 1;
    }
    r
}

/// The smallest primitive root mod a prime p.
fn primitive_root(p: u64) -> u64 {
    let mut factors = Vec::new();
    let mut rest = p - 1;
    let mut f = 2;
    while f * f <= rest {
        if rest.is_multiple_of(f) {
            factors.push(f);
            while rest.is_multiple_of(f) {
                rest /= f;
            }
        }
        f += 1;
    }
    if rest > 1 {
        factors.push(rest);
    }
    (2..p).find(|&g| factors.iter().all(|&f| pow_mod(g, (p - 1) / f, p) != 1)).unwrap_or(1)
}

impl Search {
    fn new(n: usize) -> Search {
        let mut planner = FftPlanner::new();
        let mut constant = vec![(0, 0, omega(0.0))];
        if n.is_power_of_two() {
            let m = n.trailing_zeros();
            let candidates =
                if n >= 8 { (0..n / 4).map(|k| pow_mod(5, k as u64, n as u64)).collect() } else { vec![1] };
            let mut levels = Vec::new();
            // from the smallest level up, the order `sums` builds its rows in
            for l in (0..m).rev() {
                let small = n >> l; // n' = 2^(m - l); points i = 2^l u, u odd
                if small <= 4 {
                    for u in (1..small).step_by(2) {
                        constant.push((m - l, u << l, omega(u as f64 / small as f64)));
                    }
                    continue;
                }
                let len = small / 4;
                let powers: Vec<usize> = (0..len).map(|t| pow_mod(5, t as u64, small as u64) as usize).collect();
                let index = powers.iter().map(|&u| [u << l, (small - u) << l]).collect();
                let w = powers.iter().map(|&u| omega(u as f64 / small as f64)).collect();
                levels.push(Level::new(index, w, &mut planner, m - l));
            }
            Search { n, candidates, levels, constant }
        } else {
            let g = primitive_root(n as u64);
            let len = n - 1;
            let powers: Vec<usize> = (0..len).map(|t| pow_mod(g, t as u64, n as u64) as usize).collect();
            // one q index per power: pair it with index 0, whose q joins the constant instead
            let index = powers.iter().map(|&u| [u, n]).collect();
            let w = powers.iter().map(|&u| omega(u as f64 / n as f64)).collect();
            let levels = if len > 0 { vec![Level::new(index, w, &mut planner, 0)] } else { Vec::new() };
            Search { n, candidates: powers.iter().map(|&u| u as u64).collect(), levels, constant }
        }
    }

    /// For every candidate, sum_i q_i omega({i z / n}) over the indices i of each
    /// embedded size 2^k (k = 0..=m) for n = 2^m, or over all i for a prime: `sums[k]`,
    /// the last row the whole lattice's. Row k depends on z mod 2^k only, so it holds
    /// 2^(k-2) values (candidate c's at c mod its length), built from row k - 1 tiled,
    /// plus level k's correlation: O(n) over all rows.
    fn sums(&self, q: &[f64]) -> Vec<Vec<f64>> {
        let constant = |size: u32| self.constant.iter().filter(|c| c.0 == size).map(|&(_, i, w)| q[i] * w).sum::<f64>();
        if !self.n.is_power_of_two() {
            let mut row = self.levels.first().map_or_else(|| vec![0.0], |l| l.correlate(q));
            let c = constant(0);
            row.iter_mut().for_each(|s| *s += c);
            return vec![row];
        }
        let m = self.n.trailing_zeros();
        // the levels' correlations are independent: computed side by side, added in order
        let correlations: Vec<(u32, Vec<f64>)> = self.levels.par_iter().map(|l| (l.level, l.correlate(q))).collect();
        let mut levels = correlations.into_iter().peekable();
        let mut rows: Vec<Vec<f64>> = Vec::with_capacity(m as usize + 1);
        for k in 0..=m {
            let len = ((1usize << k) / 4).max(1);
            let previous = rows.last();
            let mut row: Vec<f64> = (0..len).map(|c| previous.map_or(0.0, |p| p[c % p.len()])).collect();
            let c = constant(k);
            row.iter_mut().for_each(|s| *s += c);
            if let Some((_, correlation)) = levels.next_if(|l| l.0 == k) {
                for (s, x) in row.iter_mut().zip(correlation) {
                    *s += x;
                }
            }
            rows.push(row);
        }
        rows
    }
}

/// A generating vector of `dims` components for n points by fast CBC (module docs), with
/// product weights; `embedded` (n = 2^m) chooses for every prefix of 2^k points.
///
/// # Errors
/// n not a prime or a power of 2 up to [`MAX_N`], or `embedded` for n not a power of 2.
pub fn construct(n: usize, dims: usize, weights: Weights, embedded: bool) -> Result<Vec<u64>> {
    if !supports(n) || (embedded && !n.is_power_of_two()) {
        let reason = if embedded {
            "an embedded fast CBC lattice takes a power of 2 up to 2^24"
        } else {
            "fast CBC takes a prime or a power of 2 up to 2^24"
        };
        return Err(Error::Setting { name: "n", value: n.to_string(), reason: reason.into() });
    }
    if n == 1 {
        return Ok(vec![0; dims]);
    }
    let search = Search::new(n);
    // q has a spare slot at index n holding 0: the prime case's partner index
    let mut q = vec![1.0; n + 1];
    q[n] = 0.0;
    let mut z = Vec::with_capacity(dims);
    for j in 0..dims {
        let zj = if j == 0 {
            1
        } else {
            let sums = search.sums(&q);
            let gamma = weights.gamma(j);
            let full = sums.len() - 1;
            let pick = if embedded {
                // e_k^2 = -1 + 2^-k (sum of q over the prefix + gamma * sums[k]); the sum of q
                // over each prefix is the same for every candidate
                let qsum: Vec<f64> = (0..=full).map(|k| (0..n).step_by(n >> k).map(|i| q[i]).sum()).collect();
                // row k holds 2^(k-2) values (at least one), candidate c's at c mod its length:
                // e_k^2 and its ratio to the best are computed once per value (every value
                // is some candidate's, so a row's minimum is the candidates'; minima and
                // maxima are exact in any order)
                let ratios: Vec<Vec<f64>> = (1..=full)
                    .map(|k| {
                        let error: Vec<f64> =
                            sums[k].iter().map(|&s| (qsum[k] + gamma * s) / (1u64 << k) as f64 - 1.0).collect();
                        let best = error.iter().copied().fold(f64::INFINITY, f64::min);
                        error.into_iter().map(|e| e / best).collect()
                    })
                    .collect();
                let worst: Vec<f64> = (0..search.candidates.len())
                    .into_par_iter()
                    .map(|c| ratios.iter().map(|row| row[c & (row.len() - 1)]).fold(0.0, f64::max))
                    .collect();
                argmin(worst.into_iter())
            } else {
                argmin(sums[full].iter().copied())
            };
            search.candidates[pick]
        };
        let gamma = weights.gamma(j);
        // n <= 2^24: i z < 2^48 fits a u64; a power of 2 reduces by a mask, not a division
        let reduce = |x: u64| if n.is_power_of_two() { x & (n as u64 - 1) } else { x % n as u64 };
        q[..n].par_iter_mut().enumerate().with_min_len(1 << 12).for_each(|(i, qi)| {
            *qi *= 1.0 + gamma * omega(reduce(i as u64 * zj) as f64 / n as f64);
        });
        z.push(zj);
    }
    Ok(z)
}

/// The index of the smallest value, the first on ties.
fn argmin(values: impl Iterator<Item = f64>) -> usize {
    values.enumerate().fold((0, f64::INFINITY), |best, (i, v)| if v < best.1 { (i, v) } else { best }).0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitive_roots_generate_the_group() {
        for p in [3u64, 5, 7, 11, 101, 65537] {
            let g = primitive_root(p);
            let mut seen = std::collections::HashSet::new();
            let mut x = 1;
            for _ in 0..p - 1 {
                seen.insert(x);
                x = x * g % p;
            }
            assert_eq!(seen.len() as u64, p - 1, "p = {p}, g = {g}");
        }
    }
}
