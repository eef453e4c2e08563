//! The expected spectrum and spectrum variance of jittered sampling (Subr & Kautz 2013
//! section 3 and appendices A-B). For independent jitter with characteristic function
//! phi(w) applied to base points X_i: <S'(w)> = phi(w) <S(w)> exactly, and for fixed X_i
//! V(S'(w)) = (1 - |phi(w)|^2) / N. Their second-order expansions are the paper's eqs.
//! 8-11; both forms are given so figures can show where the approximation holds.

use std::f64::consts::PI;

/// A sampler's closed-form spectrum variance, where one is known ([`crate::Sampler::spectrum_theory`]).
pub struct VarianceTheory {
    /// What the curve is, with its parameter in the units of x.
    pub label: String,
    variance: Box<dyn Fn(f64) -> f64 + Send + Sync>,
}

impl std::fmt::Debug for VarianceTheory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VarianceTheory").field("label", &self.label).finish_non_exhaustive()
    }
}

impl VarianceTheory {
    /// A curve called `label`.
    pub fn new(label: String, variance: impl Fn(f64) -> f64 + Send + Sync + 'static) -> Self {
        VarianceTheory { label, variance: Box::new(variance) }
    }

    /// The predicted variance of the spectrum at radial frequency `w`.
    pub fn at(&self, w: f64) -> f64 {
        (self.variance)(w)
    }
}

/// Gaussian jitter of standard deviation `sigma` (in the units of x): phi = exp(-2 pi^2 sigma^2 w^2).
pub fn gaussian_ratio(w: f64, sigma: f64) -> f64 {
    (-2.0 * PI * PI * sigma * sigma * w * w).exp()
}

/// Eq. 8's factor, to second order: 1 - (2 pi w sigma)^2 / 2.
pub fn gaussian_ratio_eq8(w: f64, sigma: f64) -> f64 {
    1.0 - (2.0 * PI * w * sigma).powi(2) / 2.0
}

/// Exact variance of the spectrum of N fixed points under Gaussian jitter.
pub fn gaussian_variance(w: f64, sigma: f64, n: usize) -> f64 {
    (1.0 - gaussian_ratio(w, sigma).powi(2)) / n as f64
}

/// Eq. 9 as printed: (2 pi w sigma)^2 / N (1 + 2 (pi w sigma)^2). The exact variance
/// expands as (2 pi w sigma)^2 / N (1 - 2 (pi w sigma)^2 + ...): the leading term agrees,
/// the printed second-order term has the opposite sign.
pub fn gaussian_variance_eq9(w: f64, sigma: f64, n: usize) -> f64 {
    (2.0 * PI * w * sigma).powi(2) / n as f64 * (1.0 + 2.0 * (PI * w * sigma).powi(2))
}

/// Box jitter of half-width `delta`: phi = sin(2 pi w delta) / (2 pi w delta).
pub fn box_ratio(w: f64, delta: f64) -> f64 {
    let t = 2.0 * PI * w * delta;
    if t.abs() < 1e-12 { 1.0 } else { t.sin() / t }
}

/// Eq. 10's factor: 1 - (2 pi w delta)^2 / 6.
pub fn box_ratio_eq10(w: f64, delta: f64) -> f64 {
    1.0 - (2.0 * PI * w * delta).powi(2) / 6.0
}

/// Exact variance of the spectrum of N fixed points under box jitter.
pub fn box_variance(w: f64, delta: f64, n: usize) -> f64 {
    (1.0 - box_ratio(w, delta).powi(2)) / n as f64
}

/// Eq. 11 as printed: (2 pi w delta)^2 / N (1/3 + 4/45 (pi w delta)^2). The exact
/// variance expands as (2 pi w delta)^2 / N (1/3 - 8/45 (pi w delta)^2 + ...): the leading
/// term agrees.
pub fn box_variance_eq11(w: f64, delta: f64, n: usize) -> f64 {
    (2.0 * PI * w * delta).powi(2) / n as f64 * (1.0 / 3.0 + 4.0 / 45.0 * (PI * w * delta).powi(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn second_order_forms_agree_at_low_frequency() {
        // leading terms agree; the remainder of exp(-x) ~ 1 - x is about x^2 / 2
        for (w, s) in [(1.0, 0.001), (3.0, 0.002)] {
            let x = 2.0 * PI * PI * s * s * w * w;
            assert!((gaussian_ratio(w, s) - gaussian_ratio_eq8(w, s)).abs() <= x * x);
            // eq. 9 / exact = (1 + x) / (1 - x) to second order: equal leading terms
            assert!((gaussian_variance(w, s, 10) / gaussian_variance_eq9(w, s, 10) - 1.0).abs() <= 3.0 * x);
            let lead = (2.0 * PI * w * s).powi(2) / 10.0;
            assert!((gaussian_variance(w, s, 10) - lead * (1.0 - x)).abs() <= 2.0 * lead * x * x);
            assert!((box_ratio(w, s) - box_ratio_eq10(w, s)).abs() <= (2.0 * PI * w * s).powi(4) / 100.0);
            let y = (PI * w * s).powi(2);
            assert!((box_variance(w, s, 10) / box_variance_eq11(w, s, 10) - 1.0).abs() <= 2.0 * y);
            let lead = (2.0 * PI * w * s).powi(2) / 10.0;
            assert!((box_variance(w, s, 10) - lead * (1.0 / 3.0 - 8.0 / 45.0 * y)).abs() <= lead * y * y);
        }
    }
}
