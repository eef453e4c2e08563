//! The deterministic stopping rules of Hickernell & Jimenez Rugama (2016, "Reliable adaptive
//! cubature using digital sequences", digital nets) and Jimenez Rugama & Hickernell (2016,
//! "Adaptive multidimensional integration based on rank-1 lattices", lattices).
//!
//! One randomized sequence in natural order, n = 2^m points. The discrete transform of the
//! values in the index domain gives coefficients c_k (Walsh for a net, Fourier for a
//! lattice in its natural order), scaled so that c_0 is the sample mean. A map kappa orders
//! them by wavenumber level, and within each level by size: for l from the top level down,
//! entry k of level l trades places with entry k + 2^l (and so every block of 2^(l+1)) when
//! the latter's coefficient is the larger. With r = 4 and S = the sum of |c| over the map's
//! entries [2^(m-r-1), 2^(m-r)), the error is at most fudge(m) S for every integrand in the
//! papers' cone (coefficients that do not grow from level to level faster than the cone
//! allows), with fudge(m) = 5 2^-m, QMCPy's default. Outside the cone (a spike the first
//! points miss) the bound is wrong; docs/guide/integrate.md shows such a case.
//!
//! On doubling, the points already evaluated are kept; the map keeps its lower levels and
//! re-sorts the top r levels, as the papers' algorithms do.

use rayon::prelude::*;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

use crate::error::{Error, Result};
use crate::integrand::Integrand;
use crate::progress::Progress;
use crate::sampler::Sampler;
use crate::seed::Seed;

/// Points evaluated together.
const CHUNK: usize = 1 << 16;

/// The lag r between the levels summed and the sample size.
const LAG: u32 = 4;

/// The cone's inflation factor 5 2^-m.
fn fudge(m: u32) -> f64 {
    5.0 * 0.5f64.powi(m as i32)
}

/// Which transform the sequence calls for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Transform {
    /// A digital net in base 2: the Walsh-Hadamard transform.
    Walsh,
    /// A rank-1 lattice in radical-inverse order (periodized by the sampler's baker's
    /// transform, `tent=yes`): the Fourier transform of the values in lattice order.
    Fourier,
}

/// |c_k| for the values `y` of the first 2^m points, c_0 the mean.
fn magnitudes(y: &[f64], transform: Transform, planner: &mut FftPlanner<f64>) -> Vec<f64> {
    let n = y.len();
    match transform {
        Transform::Walsh => {
            let mut c = y.to_vec();
            let mut h = 1;
            while h < n {
                for block in c.chunks_exact_mut(2 * h) {
                    let (lo, hi) = block.split_at_mut(h);
                    for (a, b) in lo.iter_mut().zip(hi) {
                        (*a, *b) = (*a + *b, *a - *b);
                    }
                }
                h *= 2;
            }
            c.iter().map(|v| v.abs() / n as f64).collect()
        }
        Transform::Fourier => {
            // point i of the radical-inverse order is lattice point bitrev(i)
            let bits = n.trailing_zeros();
            let mut c = vec![Complex::new(0.0, 0.0); n];
            for (i, &v) in y.iter().enumerate() {
                let j = if bits == 0 { 0 } else { i.reverse_bits() >> (usize::BITS - bits) };
                c[j] = Complex::new(v, 0.0);
            }
            planner.plan_fft_forward(n).process(&mut c);
            // the decimation-in-time order: index k of the first half pairs with k + n/2
            c.iter().map(|v| v.norm() / n as f64).collect()
        }
    }
}

/// Re-sort levels `top` down to `bottom + 1` of the map over `c`.
fn sort_levels(map: &mut [usize], c: &[f64], top: u32, bottom: u32) {
    let n = map.len();
    for l in (bottom + 1..=top).rev() {
        let half = 1usize << l;
        for k in 1..half {
            if c[map[half + k]] > c[map[k]] {
                for base in (0..n).step_by(2 * half) {
                    map.swap(base + k, base + half + k);
                }
            }
        }
    }
}

/// One run of the rule on one randomization of a sequence: its estimate and bound at each
/// n, until `done(estimate, bound)` or n would pass `max_n`.
pub(super) struct Run<'a> {
    pub(super) f: &'a dyn Integrand,
    pub(super) transform: Transform,
    pub(super) min_n: usize,
    pub(super) max_n: usize,
}

/// The steps taken: (n, estimate, bound) each, and whether the last met `done`.
pub(super) type Steps = (Vec<(usize, f64, f64)>, bool);

impl Run<'_> {
    pub(super) fn run(
        &self,
        sampler: &Sampler,
        seed: Seed,
        done: impl Fn(f64, f64) -> bool,
        progress: &Progress,
    ) -> Result<Steps> {
        let d = self.f.dims();
        let mut planner = FftPlanner::new();
        let mut y: Vec<f64> = Vec::new();
        let mut map: Vec<usize> = Vec::new();
        let mut steps = Vec::new();
        let mut n = self.min_n;
        loop {
            let m = n.trailing_zeros();
            crate::memory::check(|| format!("cubature of {n} {d}D points"), bytes(n, d))?;
            let points = sampler.plan(n, d)?.generate(seed)?;
            let points = points.as_slice();
            let old = y.len();
            y.resize(n, 0.0);
            // in chunks over the threads (each value depends on its point alone, so the bits
            // do not depend on the thread count); a Python function is called once a chunk
            y[old..]
                .par_chunks_mut(CHUNK)
                .zip(points[old * d..].par_chunks(CHUNK * d))
                .for_each(|(out, x)| self.f.eval_many(x, out));
            if let Some(i) = y[old..].iter().position(|v| !v.is_finite()) {
                return Err(non_finite(&points[(old + i) * d..(old + i + 1) * d], y[old + i]));
            }
            let c = magnitudes(&y, self.transform, &mut planner);
            if map.is_empty() {
                map = (0..n).collect();
                sort_levels(&mut map, &c, m - 1, 0);
            } else {
                let half = map.len();
                map.extend_from_within(..);
                map[half..].iter_mut().for_each(|k| *k += half);
                sort_levels(&mut map, &c, m - 1, m - LAG - 1);
            }
            let lo = 1usize << (m - LAG - 1);
            let bound = fudge(m) * map[lo..2 * lo].iter().map(|&k| c[k]).sum::<f64>();
            let estimate = crate::stats::Summary::of(&y).mean;
            steps.push((n, estimate, bound));
            progress.advance(1)?;
            if done(estimate, bound) || n * 2 > self.max_n {
                return Ok((steps, done(estimate, bound)));
            }
            n *= 2;
        }
    }
}

/// The memory a step of `n` points takes: the points, the values, the coefficients
/// (complex for a lattice) and the map.
pub(super) fn bytes(n: usize, d: usize) -> u128 {
    n as u128 * (d as u128 + 4) * 8
}

/// The refusal of an integrand's non-finite value.
pub(super) fn non_finite(x: &[f64], value: f64) -> Error {
    let at: Vec<String> = x.iter().map(|v| format!("{v}")).collect();
    Error::NotFinite { what: format!("the integrand at x = ({})", at.join(", ")), value }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Walsh transform against its definition: c_k = mean of y_i (-1)^popcount(i & k).
    #[test]
    fn walsh_by_definition() {
        let y: Vec<f64> = (0..16).map(|i| ((i * 7 + 3) % 11) as f64 - 4.5).collect();
        let c = magnitudes(&y, Transform::Walsh, &mut FftPlanner::new());
        for (k, ck) in c.iter().enumerate() {
            let direct: f64 =
                y.iter().enumerate().map(|(i, v)| if (i & k).count_ones() % 2 == 0 { *v } else { -*v }).sum::<f64>()
                    / 16.0;
            assert!((ck - direct.abs()).abs() < 1e-14, "k {k}: {ck} vs {direct}");
        }
    }

    /// The Fourier magnitudes against the DFT of the values in lattice order.
    #[test]
    fn fourier_by_definition() {
        let n = 8;
        let y: Vec<f64> = (0..n).map(|i| ((i * 5 + 1) % 7) as f64).collect();
        let c = magnitudes(&y, Transform::Fourier, &mut FftPlanner::new());
        let bitrev = |i: usize| ((i & 1) << 2) | (i & 2) | ((i & 4) >> 2);
        for (k, ck) in c.iter().enumerate() {
            let (mut re, mut im) = (0.0, 0.0);
            for (i, v) in y.iter().enumerate() {
                let t = -2.0 * std::f64::consts::PI * (bitrev(i) * k) as f64 / n as f64;
                re += v * t.cos();
                im += v * t.sin();
            }
            let direct = re.hypot(im) / n as f64;
            assert!((ck - direct).abs() < 1e-13, "k {k}: {ck} vs {direct}");
        }
    }

    /// The map sorts each level's pairs: after it, no later entry of a pair is the larger.
    #[test]
    fn sorted_pairs() {
        let c: Vec<f64> = (0..32).map(|k| ((k * 13 + 5) % 17) as f64).collect();
        let mut map: Vec<usize> = (0..32).collect();
        sort_levels(&mut map, &c, 4, 0);
        let mut seen = map.clone();
        seen.sort_unstable();
        assert_eq!(seen, (0..32).collect::<Vec<_>>(), "a permutation");
        // the top level is sorted last, so its pairs hold
        for k in 1..16 {
            assert!(c[map[k]] >= c[map[16 + k]], "k {k}");
        }
    }
}
