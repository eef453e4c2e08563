//! Numerics shared across samplab: the last double below one, the normal distribution
//! function, and Gauss–Legendre quadrature ([`quadrature`]).

pub mod quadrature;

/// The largest f64 below one: where a rounding could land a coordinate on 1.0, it is
/// clamped here, so that every coordinate stays in [0, 1).
pub const BELOW_ONE: f64 = 1.0 - f64::EPSILON / 2.0;

/// The standard normal distribution function Phi(x) = erfc(-x / sqrt 2) / 2.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}
