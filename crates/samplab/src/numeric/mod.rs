//! Numerics shared across samplab: the last double below one, the normal distribution
//! function and its inverse, Student's t quantiles, and Gauss–Legendre quadrature
//! ([`quadrature`]).

pub mod quadrature;

/// The largest f64 below one: where a rounding could land a coordinate on 1.0, it is
/// clamped here, so that every coordinate stays in [0, 1).
pub const BELOW_ONE: f64 = 1.0 - f64::EPSILON / 2.0;

/// The standard normal distribution function Phi(x) = erfc(-x / sqrt 2) / 2.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The standard normal quantile Phi^-1(p) for p in (0, 1): Abramowitz & Stegun 26.2.23's
/// rational start (error below 4.5e-4), then Halley steps on Phi (from `erfc`, accurate in
/// the tails) to full precision. 0 and 1 give -inf and inf.
pub fn normal_quantile(p: f64) -> f64 {
    if p <= 0.0 || p >= 1.0 {
        return if p <= 0.0 { f64::NEG_INFINITY } else { f64::INFINITY };
    }
    // the lower tail; the upper by symmetry
    let q = p.min(1.0 - p);
    let t = (-2.0 * q.ln()).sqrt();
    let mut x = -(t - (2.515_517 + 0.802_853 * t + 0.010_328 * t * t)
        / (1.0 + 1.432_788 * t + 0.189_269 * t * t + 0.001_308 * t * t * t));
    for _ in 0..3 {
        let e = normal_cdf(x) - q;
        let u = e * (2.0 * std::f64::consts::PI).sqrt() * (x * x / 2.0).exp();
        x -= u / (1.0 + x * u / 2.0);
    }
    if p > 0.5 { -x } else { x }
}
