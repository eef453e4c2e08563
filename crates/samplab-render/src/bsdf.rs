//! How the reflecting finishes ([`Finish`]) scatter light: sampling a direction, and the
//! value and density of a given one (what the path-traced mode's next-event estimation and
//! multiple importance sampling need).
//!
//! Directions are unit vectors leaving the surface; `n` is the unit normal on the side of
//! `wi`, the direction back toward where the path came from. The values are without the
//! reflectance (albedo), which the caller multiplies in.
//!
//! - Diffuse: f = 1 / pi, sampled by the cosine.
//! - Glossy (Cook et al. 1984's imperfect mirror): the direction spread about the mirror
//!   direction r by the normalized Phong lobe p = (e + 1) / (2 pi) cos^e(wo, r), and
//!   f = p / cos(theta_o), so that a sampled direction weighs exactly the reflectance, as in
//!   the other modes; directions below the surface are lost.
//! - Rough (Mitsuba 3's `roughconductor` with its default perfectly reflecting material):
//!   Walter et al. 2007's microfacet model, f = D(h) G1(wi) G1(wo) / (4 cos_i cos_o) with
//!   h the half vector, D Beckmann (eq. 33) or GGX (eq. 33 of the GGX section), G1 Smith's
//!   (eqs. 27 and 34; Beckmann's exact form through erf, where Mitsuba uses a rational fit
//!   within 0.35%), sampled by D(h) cos(theta_h) (eqs. 28, 35, 36, 38).

use std::f64::consts::PI;

use glam::DVec3;

use crate::scene::{Distribution, Finish};

/// A sampled direction: its weight f cos(theta_o) / pdf (without the reflectance) and its
/// density per solid angle.
#[derive(Debug, Clone, Copy)]
pub struct Sampled {
    /// The direction.
    pub dir: DVec3,
    /// f cos(theta_o) / pdf, without the reflectance.
    pub weight: f64,
    /// Density of `dir` per solid angle.
    pub pdf: f64,
}

/// A direction for `finish` (not a mirror) from `u` in the unit square; None when it falls
/// below the surface.
pub fn sample(finish: Finish, n: DVec3, wi: DVec3, u: [f64; 2]) -> Option<Sampled> {
    let (dir, weight) = match finish {
        Finish::Diffuse => (phong_lobe(n, 1.0, u), 1.0),
        Finish::Glossy { exponent } => (phong_lobe(mirror(wi, n), exponent, u), 1.0),
        Finish::Rough { alpha, distribution } => {
            let tan2 = match distribution {
                Distribution::Beckmann => -alpha * alpha * (1.0 - u[0]).ln(),
                Distribution::Ggx => alpha * alpha * u[0] / (1.0 - u[0]),
            };
            let cos_h = 1.0 / (1.0 + tan2).sqrt();
            let h = about(n, cos_h, u[1]);
            let dot = wi.dot(h);
            let dir = 2.0 * dot * h - wi;
            let (cos_i, cos_o) = (n.dot(wi), n.dot(dir));
            if dot <= 0.0 || cos_o <= 0.0 || cos_i <= 0.0 {
                return None;
            }
            let g = smith(distribution, alpha, wi, h, n) * smith(distribution, alpha, dir, h, n);
            (dir, g * dot / (cos_i * cos_h))
        }
        Finish::Mirror => return None,
    };
    if n.dot(dir) <= 0.0 || weight <= 0.0 {
        return None;
    }
    let (_, pdf) = eval(finish, n, wi, dir);
    Some(Sampled { dir, weight, pdf })
}

/// The value f (without the reflectance) and the sampling density per solid angle of
/// direction `wo` for `finish` (zero for a mirror, which no given direction hits).
pub fn eval(finish: Finish, n: DVec3, wi: DVec3, wo: DVec3) -> (f64, f64) {
    let cos_o = n.dot(wo);
    if cos_o <= 0.0 {
        return (0.0, 0.0);
    }
    match finish {
        Finish::Diffuse => (1.0 / PI, cos_o / PI),
        Finish::Glossy { exponent } => {
            let c = mirror(wi, n).dot(wo);
            if c <= 0.0 {
                return (0.0, 0.0);
            }
            let pdf = (exponent + 1.0) / (2.0 * PI) * c.powf(exponent);
            (pdf / cos_o, pdf)
        }
        Finish::Rough { alpha, distribution } => {
            let cos_i = n.dot(wi);
            let h = (wi + wo).normalize();
            let (cos_h, dot) = (n.dot(h), wo.dot(h));
            if cos_i <= 0.0 || cos_h <= 0.0 || dot <= 0.0 {
                return (0.0, 0.0);
            }
            let d = ndf(distribution, alpha, cos_h);
            let g = smith(distribution, alpha, wi, h, n) * smith(distribution, alpha, wo, h, n);
            (d * g / (4.0 * cos_i * cos_o), d * cos_h / (4.0 * dot))
        }
        Finish::Mirror => (0.0, 0.0),
    }
}

/// The mirror direction of `wi` about `n`.
fn mirror(wi: DVec3, n: DVec3) -> DVec3 {
    (2.0 * wi.dot(n) * n - wi).normalize()
}

/// The microfacet distribution D at a half vector whose cosine with the normal is `cos`.
fn ndf(distribution: Distribution, alpha: f64, cos: f64) -> f64 {
    let c2 = cos * cos;
    let (a2, tan2) = (alpha * alpha, (1.0 - c2) / c2);
    match distribution {
        Distribution::Beckmann => (-tan2 / a2).exp() / (PI * a2 * c2 * c2),
        Distribution::Ggx => a2 / (PI * c2 * c2 * (a2 + tan2) * (a2 + tan2)),
    }
}

/// Smith's masking G1 of direction `v` for microfacet normal `h` (zero where `v` sees the
/// back of the facet).
fn smith(distribution: Distribution, alpha: f64, v: DVec3, h: DVec3, n: DVec3) -> f64 {
    let cos = n.dot(v);
    if v.dot(h) * cos <= 0.0 {
        return 0.0;
    }
    let tan2 = ((1.0 - cos * cos) / (cos * cos)).max(0.0);
    if tan2 == 0.0 {
        return 1.0;
    }
    match distribution {
        Distribution::Beckmann => {
            let a = 1.0 / (alpha * tan2.sqrt());
            let lambda = 0.5 * (libm::erf(a) - 1.0) + (-a * a).exp() / (2.0 * a * PI.sqrt());
            1.0 / (1.0 + lambda)
        }
        Distribution::Ggx => 2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt()),
    }
}

/// The unit vector at cosine `cos` from the unit `axis`, at azimuth 2 pi `u`.
fn about(axis: DVec3, cos: f64, u: f64) -> DVec3 {
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (a, b) = axis.any_orthonormal_pair();
    let (s, c) = (2.0 * PI * u).sin_cos();
    (a * c + b * s) * sin + axis * cos
}

/// A direction about the unit `axis` from the normalized Phong lobe (n + 1) / (2 pi)
/// cos^n(alpha) by inversion: cos(alpha) = u0^(1 / (n + 1)), azimuth 2 pi u1 (n = 1: the
/// cosine-weighted hemisphere).
pub(crate) fn phong_lobe(axis: DVec3, exponent: f64, u: [f64; 2]) -> DVec3 {
    about(axis, u[0].powf(1.0 / (exponent + 1.0)), u[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The midpoint rule over the unit square, k x k points.
    fn grid(k: usize) -> impl Iterator<Item = [f64; 2]> {
        (0..k * k).map(move |i| [((i % k) as f64 + 0.5) / k as f64, ((i / k) as f64 + 0.5) / k as f64])
    }

    #[test]
    fn the_phong_lobe_has_the_mean_cosine_of_its_density() {
        // for density (n + 1) / (2 pi) cos^n about the axis, E[cos] = (n + 1) / (n + 2)
        let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
        for exponent in [0.0, 1.0, 4.0, 10.0] {
            let k = 400;
            let mut sum = 0.0;
            for u in grid(k) {
                let d = phong_lobe(axis, exponent, u);
                assert!((d.length() - 1.0).abs() < 1e-12);
                sum += d.dot(axis);
            }
            let mean = sum / (k * k) as f64;
            let exact = (exponent + 1.0) / (exponent + 2.0);
            // the midpoint rule errs by about 4e-5 on u^(1/(n+1)); a wrong exponent by 1e-3
            assert!((mean - exact).abs() < 1e-4, "n = {exponent}: {mean} vs {exact}");
        }
    }

    /// The integral over the hemisphere about `n` of `f(direction)`, by the midpoint rule in
    /// (t, phi) with k^2 cells, cos theta = 1 - t^2 (dw = 2 t dt d phi: cells fine near the
    /// normal, where the narrow lobes are).
    fn hemisphere(n: DVec3, k: usize, f: impl Fn(DVec3) -> f64) -> f64 {
        grid(k).map(|u| 2.0 * u[0] * f(about(n, 1.0 - u[0] * u[0], u[1]))).sum::<f64>() * 2.0 * PI / (k * k) as f64
    }

    #[test]
    fn microfacet_distributions_are_normalized_and_sampling_agrees_with_eval() {
        let n = DVec3::new(0.2, 0.9, -0.1).normalize();
        let (a, b) = n.any_orthonormal_pair();
        for distribution in [Distribution::Beckmann, Distribution::Ggx] {
            for alpha in [0.15, 0.5] {
                // the projected microfacet area is the macro surface's: int D cos dw_h = 1
                let area = hemisphere(n, 1000, |h| ndf(distribution, alpha, n.dot(h)) * n.dot(h));
                assert!((area - 1.0).abs() < 2e-3, "{distribution:?} {alpha}: {area}");
                let finish = Finish::Rough { alpha, distribution };
                for theta in [0.0f64, 0.6, 1.2] {
                    let wi = theta.cos() * n + theta.sin() * (0.6 * a + 0.8 * b);
                    // the albedo int f cos dw two ways: quadrature of eval, and the mean
                    // sampled weight; and the density integrates to at most 1
                    let albedo = hemisphere(n, 1000, |wo| eval(finish, n, wi, wo).0 * n.dot(wo));
                    let mass = hemisphere(n, 1000, |wo| eval(finish, n, wi, wo).1);
                    let k = 300;
                    let mut sum = 0.0;
                    for u in grid(k) {
                        if let Some(s) = sample(finish, n, wi, u) {
                            let (f, pdf) = eval(finish, n, wi, s.dir);
                            assert!((s.pdf - pdf).abs() <= 1e-9 * pdf);
                            assert!((s.weight - f * n.dot(s.dir) / pdf).abs() <= 1e-9 * s.weight.max(1.0));
                            sum += s.weight;
                        }
                    }
                    let mean = sum / (k * k) as f64;
                    assert!(albedo <= 1.0 + 2e-3 && mass <= 1.0 + 2e-3, "{albedo} {mass}");
                    assert!(
                        (mean - albedo).abs() < 5e-3,
                        "{distribution:?} alpha {alpha} theta {theta}: {mean} vs {albedo}"
                    );
                }
            }
        }
    }
}
