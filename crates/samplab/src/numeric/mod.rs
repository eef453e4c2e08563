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
    let mut x = -(t
        - (2.515_517 + 0.802_853 * t + 0.010_328 * t * t)
            / (1.0 + 1.432_788 * t + 0.189_269 * t * t + 0.001_308 * t * t * t));
    // Halley's method is cubic: 4.5e-4, then about 1e-10, then below rounding
    for _ in 0..2 {
        let e = normal_cdf(x) - q;
        let u = e * (2.0 * std::f64::consts::PI).sqrt() * (x * x / 2.0).exp();
        x -= u / (1.0 + x * u / 2.0);
    }
    if p > 0.5 { -x } else { x }
}

/// The regularized incomplete beta function I_x(a, b), by the continued fraction of
/// Numerical Recipes' section 6.4 evaluated with the modified Lentz method (the symmetry
/// I_x(a, b) = 1 - I_(1-x)(b, a) where the fraction converges slowly).
fn incomplete_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 || x >= 1.0 {
        return x.clamp(0.0, 1.0);
    }
    if x > (a + 1.0) / (a + b + 2.0) {
        return 1.0 - incomplete_beta(1.0 - x, b, a);
    }
    let front = (libm::lgamma(a + b) - libm::lgamma(a) - libm::lgamma(b) + a * x.ln() + b * (1.0 - x).ln()).exp() / a;
    let tiny = 1e-300;
    let (mut c, mut d) = (1.0, 1.0 - (a + b) * x / (a + 1.0));
    d = 1.0 / if d.abs() < tiny { tiny } else { d };
    let mut h = d;
    for m in 1..500 {
        let m = f64::from(m);
        // the even and the odd step of the fraction
        for numerator in [
            m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
            -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0)),
        ] {
            d = 1.0 + numerator * d;
            d = 1.0 / if d.abs() < tiny { tiny } else { d };
            c = 1.0 + numerator / c;
            c = if c.abs() < tiny { tiny } else { c };
            h *= d * c;
        }
        if (d * c - 1.0).abs() < 1e-16 {
            break;
        }
    }
    front * h
}

/// Student's t distribution function with `df` degrees of freedom.
pub fn student_t_cdf(t: f64, df: f64) -> f64 {
    let tail = 0.5 * incomplete_beta(df / (df + t * t), df / 2.0, 0.5);
    if t > 0.0 { 1.0 - tail } else { tail }
}

/// Student's t quantile: the t with [`student_t_cdf`]`(t, df) = p`, p in (0, 1), by
/// bisection to the last bit.
pub fn student_t_quantile(p: f64, df: f64) -> f64 {
    if p == 0.5 {
        return 0.0;
    }
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    while student_t_cdf(lo, df) > p {
        lo *= 2.0;
    }
    while student_t_cdf(hi, df) < p {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if student_t_cdf(mid, df) < p { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}
