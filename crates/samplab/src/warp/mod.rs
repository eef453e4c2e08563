//! Warps from the unit square (or cube) to other domains, each a triple of forward map,
//! density and inverse (as pbrt's `SampleX` / `XPDF` / `InvertXSample`), so that every warp
//! gets round-trip and density tests for free.
//!
//! Densities are with respect to area in the plane (disks, Gaussians, tents) or solid
//! angle (hemispheres, directions with z >= 0).

use std::f64::consts::{FRAC_PI_4, PI, TAU};
use std::fmt::Debug;

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::registry::{About, Entry, Registry};

/// A map from uniform points to another domain, with its density and inverse.
pub trait Warp: Send + Sync + Debug {
    /// Registry name.
    fn name(&self) -> &'static str;
    /// Input dimensions it takes (`None`: any, applied per axis).
    fn input_dims(&self) -> Option<usize>;
    /// Output dimensions for `input` input dimensions.
    fn output_dims(&self, input: usize) -> usize;
    /// Map `u` (in [0,1)^d) to `out`. Returns false when the point is rejected (only for
    /// rejection warps).
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool;
    /// The density of warped points at `x` (zero outside the domain).
    fn density(&self, x: &[f64]) -> f64;
    /// Map a point of the domain back to the square; false when `x` is outside it.
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool;
}

/// Warp every point of `points`; rejected points are dropped.
///
/// # Errors
/// The warp needs a different number of dimensions.
///
/// ```
/// use samplab::{Seed, sampler, warp};
/// let square = sampler::build("jitter").unwrap().generate(64, 2, Seed(1)).unwrap();
/// let disk = warp::apply(warp::lookup("disk.concentric").unwrap(), &square).unwrap();
/// assert!(disk.iter().all(|p| p[0].hypot(p[1]) <= 1.0));
/// ```
pub fn apply(warp: &dyn Warp, points: &PointSet) -> Result<PointSet> {
    if let Some(d) = warp.input_dims()
        && d != points.dims()
    {
        return Err(Error::Dimension {
            what: format!("warp {}", warp.name()),
            takes: format!("{d}D points"),
            got: points.dims(),
        });
    }
    let out_dims = warp.output_dims(points.dims());
    let mut data = Vec::with_capacity(points.len() * out_dims);
    let mut buf = vec![0.0; out_dims];
    for p in points.iter() {
        if warp.forward(p, &mut buf) {
            data.extend_from_slice(&buf);
        }
    }
    Ok(PointSet::from_raw(out_dims, data))
}

/// Square to disk by polar coordinates: r = sqrt(u), phi = 2 pi v (Shirley 1991 section 4).
#[derive(Debug, Clone, Copy)]
pub struct PolarDisk;

/// Shirley–Chiu concentric map from square to disk: area-preserving, low distortion
/// (Shirley & Chiu 1997): concentric squares go to concentric circles.
#[derive(Debug, Clone, Copy)]
pub struct ConcentricDisk;

/// Rejection to the disk: the square mapped to [-1,1)^2, points outside the unit disk dropped.
#[derive(Debug, Clone, Copy)]
pub struct RejectDisk;

/// Tent filter (1-|x|) on [-1,1] per axis, by its inverse CDF (Shirley 1991 section 4,
/// the separable tent (1-|x|)(1-|y|) in 2D). Any dimension.
#[derive(Debug, Clone, Copy)]
pub struct Tent;

/// Standard normal in 2D by the Box–Muller polar map: r = sqrt(-2 ln(1-u)), phi = 2 pi v.
#[derive(Debug, Clone, Copy)]
pub struct Gaussian;

/// Uniform directions on the hemisphere z >= 0: z = u, phi = 2 pi v; density 1/(2 pi) per sr.
#[derive(Debug, Clone, Copy)]
pub struct UniformHemisphere;

/// Cosine-weighted hemisphere (Malley's method: concentric disk, then lift to z =
/// sqrt(1 - r^2)); density cos(theta)/pi per sr.
#[derive(Debug, Clone, Copy)]
pub struct CosineHemisphere;

fn angle01(y: f64, x: f64) -> f64 {
    let a = y.atan2(x) / TAU;
    crate::seed::wrap01(a)
}

impl Warp for PolarDisk {
    fn name(&self) -> &'static str {
        "disk.polar"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        2
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        let r = u[0].sqrt();
        let (s, c) = (TAU * u[1]).sin_cos();
        out[0] = r * c;
        out[1] = r * s;
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        if x[0] * x[0] + x[1] * x[1] < 1.0 { 1.0 / PI } else { 0.0 }
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        let r2 = x[0] * x[0] + x[1] * x[1];
        out[0] = r2;
        out[1] = angle01(x[1], x[0]);
        r2 < 1.0
    }
}

/// 1/k! for k = 0..=16.
const INV_FACTORIAL: [f64; 17] = {
    let mut a = [1.0; 17];
    let mut k = 1;
    while k < 17 {
        a[k] = a[k - 1] / k as f64;
        k += 1;
    }
    a
};

/// sin and cos of |x| <= pi/4 by their Taylor series to x^15 and x^16 (the first omitted
/// terms are below 5e-17 there), each polynomial in x^2 evaluated by Estrin's scheme (pairs,
/// then pairs of pairs) for a short dependency chain: several times faster than libm's
/// `sin_cos`, where the concentric map would otherwise spend most of its time.
#[inline(always)]
fn sin_cos_quarter(x: f64) -> (f64, f64) {
    let f = &INV_FACTORIAL;
    let y = x * x;
    let (y2, y4) = (y * y, y * y * (y * y));
    // sin x / x = sum_k (-1)^k y^k / (2k + 1)!, k = 0..7
    let s = (f[1] - f[3] * y) + y2 * (f[5] - f[7] * y) + y4 * ((f[9] - f[11] * y) + y2 * (f[13] - f[15] * y));
    // cos x = sum_k (-1)^k y^k / (2k)!, k = 0..8
    let c = (f[0] - f[2] * y)
        + y2 * (f[4] - f[6] * y)
        + y4 * ((f[8] - f[10] * y) + y2 * (f[12] - f[14] * y))
        + y4 * y4 * f[16];
    (x * s, c)
}

/// The concentric map (Shirley & Chiu 1997) of (u0, u1) in the unit square to the unit
/// disk: in each of the four triangular regions the angle is pi/4 (b/a), or pi/2 - pi/4 (a/b),
/// so only |psi| <= pi/4 needs sin and cos. Written with selects and no branch, so that a
/// loop of it vectorizes and random samples do not mispredict.
#[inline(always)]
pub fn concentric(u0: f64, u1: f64) -> (f64, f64) {
    let (a, b) = (2.0 * u0 - 1.0, 2.0 * u1 - 1.0);
    let steep = a.abs() <= b.abs();
    let (num, den) = if steep { (a, b) } else { (b, a) };
    // the centre, a = b = 0, goes to 0 (its angle is any)
    let ratio = if den == 0.0 { 0.0 } else { num / den };
    let (s, c) = sin_cos_quarter(FRAC_PI_4 * ratio);
    if steep { (den * s, den * c) } else { (den * c, den * s) }
}

impl Warp for ConcentricDisk {
    fn name(&self) -> &'static str {
        "disk.concentric"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        2
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        (out[0], out[1]) = concentric(u[0], u[1]);
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        PolarDisk.density(x)
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        let r = x[0].hypot(x[1]);
        let mut phi = x[1].atan2(x[0]); // (-pi, pi]
        if phi < -FRAC_PI_4 {
            phi += TAU; // [-pi/4, 7pi/4)
        }
        let (a, b) = if phi < FRAC_PI_4 {
            (r, r * phi / FRAC_PI_4)
        } else if phi < 3.0 * FRAC_PI_4 {
            (-r * (phi - 2.0 * FRAC_PI_4) / FRAC_PI_4, r)
        } else if phi < 5.0 * FRAC_PI_4 {
            (-r, -r * (phi - 4.0 * FRAC_PI_4) / FRAC_PI_4)
        } else {
            (r * (phi - 6.0 * FRAC_PI_4) / FRAC_PI_4, -r)
        };
        out[0] = (a + 1.0) / 2.0;
        out[1] = (b + 1.0) / 2.0;
        r < 1.0
    }
}

impl Warp for RejectDisk {
    fn name(&self) -> &'static str {
        "disk.reject"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        2
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        out[0] = 2.0 * u[0] - 1.0;
        out[1] = 2.0 * u[1] - 1.0;
        out[0] * out[0] + out[1] * out[1] < 1.0
    }
    fn density(&self, x: &[f64]) -> f64 {
        PolarDisk.density(x)
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        out[0] = (x[0] + 1.0) / 2.0;
        out[1] = (x[1] + 1.0) / 2.0;
        x[0] * x[0] + x[1] * x[1] < 1.0
    }
}

/// The tent's inverse CDF on [-1,1].
pub fn tent_inverse_cdf(u: f64) -> f64 {
    if u < 0.5 { (2.0 * u).sqrt() - 1.0 } else { 1.0 - (2.0 - 2.0 * u).sqrt() }
}

/// The tent's CDF on [-1,1].
pub fn tent_cdf(x: f64) -> f64 {
    let x = x.clamp(-1.0, 1.0);
    if x < 0.0 { 0.5 * (1.0 + x) * (1.0 + x) } else { 1.0 - 0.5 * (1.0 - x) * (1.0 - x) }
}

impl Warp for Tent {
    fn name(&self) -> &'static str {
        "tent"
    }
    fn input_dims(&self) -> Option<usize> {
        None
    }
    fn output_dims(&self, input: usize) -> usize {
        input
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        for (o, &x) in out.iter_mut().zip(u) {
            *o = tent_inverse_cdf(x);
        }
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        x.iter().map(|&t| (1.0 - t.abs()).max(0.0)).product()
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        for (o, &t) in out.iter_mut().zip(x) {
            *o = tent_cdf(t);
        }
        x.iter().all(|t| t.abs() <= 1.0)
    }
}

impl Warp for Gaussian {
    fn name(&self) -> &'static str {
        "gaussian"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        2
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        let r = (-2.0 * (-u[0]).ln_1p()).sqrt();
        let (s, c) = (TAU * u[1]).sin_cos();
        out[0] = r * c;
        out[1] = r * s;
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        (-(x[0] * x[0] + x[1] * x[1]) / 2.0).exp() / TAU
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        out[0] = -(-(x[0] * x[0] + x[1] * x[1]) / 2.0).exp_m1();
        out[1] = angle01(x[1], x[0]);
        true
    }
}

impl Warp for UniformHemisphere {
    fn name(&self) -> &'static str {
        "hemisphere.uniform"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        3
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        let z = u[0];
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, c) = (TAU * u[1]).sin_cos();
        out.copy_from_slice(&[r * c, r * s, z]);
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        if x[2] >= 0.0 { 1.0 / TAU } else { 0.0 }
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        out[0] = x[2];
        out[1] = angle01(x[1], x[0]);
        x[2] >= 0.0
    }
}

impl Warp for CosineHemisphere {
    fn name(&self) -> &'static str {
        "hemisphere.cosine"
    }
    fn input_dims(&self) -> Option<usize> {
        Some(2)
    }
    fn output_dims(&self, _: usize) -> usize {
        3
    }
    fn forward(&self, u: &[f64], out: &mut [f64]) -> bool {
        let mut d = [0.0; 2];
        ConcentricDisk.forward(u, &mut d);
        let z = (1.0 - d[0] * d[0] - d[1] * d[1]).max(0.0).sqrt();
        out.copy_from_slice(&[d[0], d[1], z]);
        true
    }
    fn density(&self, x: &[f64]) -> f64 {
        x[2].max(0.0) / PI
    }
    fn inverse(&self, x: &[f64], out: &mut [f64]) -> bool {
        ConcentricDisk.inverse(&x[..2], out);
        x[2] >= 0.0
    }
}

/// One registered warp.
#[derive(Debug)]
pub struct WarpEntry {
    /// Name, aliases, summary, references (warps take no parameters).
    pub about: About,
    /// Input and output dimensions, in words.
    pub dims: &'static str,
    /// The warp.
    pub warp: &'static dyn Warp,
}

impl Entry for WarpEntry {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        vec![format!("dimensions: {}", self.dims)]
    }
}

/// Every registered warp.
pub static WARPS: Registry<WarpEntry> =
    Registry::new("warp", "WARPS  (forward map, density and inverse)", &[&[WARP_ENTRIES]]);

/// The warps this file declares.
static WARP_ENTRIES: &[WarpEntry] = &[
    WarpEntry {
        about: About {
            name: "disk.polar",
            aliases: &["polar"],
            summary: "square to unit disk, r = sqrt(u), phi = 2 pi v",
            params: &[],
            references: &["shirley1991"],
            terse: false,
        },
        dims: "2 -> 2",
        warp: &PolarDisk,
    },
    WarpEntry {
        about: About {
            name: "disk.concentric",
            aliases: &["concentric", "shirley-chiu"],
            summary: "square to unit disk, area-preserving low distortion",
            params: &[],
            references: &["shirley1997"],
            terse: false,
        },
        dims: "2 -> 2",
        warp: &ConcentricDisk,
    },
    WarpEntry {
        about: About {
            name: "disk.reject",
            aliases: &["reject"],
            summary: "keep the points of [-1,1)^2 inside the unit disk",
            params: &[],
            references: &["shirley1991"],
            terse: false,
        },
        dims: "2 -> 2",
        warp: &RejectDisk,
    },
    WarpEntry {
        about: About {
            name: "tent",
            aliases: &["tent-filter"],
            summary: "tent filter (1-|x|) on [-1,1] per axis, inverse CDF",
            params: &[],
            references: &["shirley1991"],
            terse: false,
        },
        dims: "d -> d",
        warp: &Tent,
    },
    WarpEntry {
        about: About {
            name: "gaussian",
            aliases: &["normal", "box-muller"],
            summary: "standard normal in the plane (Box-Muller)",
            params: &[],
            references: &[],
            terse: false,
        },
        dims: "2 -> 2",
        warp: &Gaussian,
    },
    WarpEntry {
        about: About {
            name: "hemisphere.uniform",
            aliases: &["hemisphere"],
            summary: "uniform directions, z >= 0",
            params: &[],
            references: &[],
            terse: false,
        },
        dims: "2 -> 3",
        warp: &UniformHemisphere,
    },
    WarpEntry {
        about: About {
            name: "hemisphere.cosine",
            aliases: &["cosine"],
            summary: "cosine-weighted directions (concentric disk lifted)",
            params: &[],
            references: &["shirley1997", "sbert2006"],
            terse: false,
        },
        dims: "2 -> 3",
        warp: &CosineHemisphere,
    },
];

/// The warp called `name` (canonical or alias, case-insensitive).
///
/// # Errors
/// An unknown name, with the closest known names.
pub fn lookup(name: &str) -> Result<&'static dyn Warp> {
    Ok(WARPS.lookup(name)?.warp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{Seed, uniform};

    fn bijective() -> impl Iterator<Item = &'static WarpEntry> {
        WARPS.iter().filter(|e| e.about.name != "disk.reject")
    }

    #[test]
    fn quarter_sin_cos_matches_libm() {
        for i in 0..=10_000 {
            let x = FRAC_PI_4 * (2.0 * i as f64 / 10_000.0 - 1.0);
            let (s, c) = sin_cos_quarter(x);
            assert!((s - x.sin()).abs() <= 2.3e-16 && (c - x.cos()).abs() <= 2.3e-16, "{x}: {s} {c}");
        }
    }

    #[test]
    fn forward_then_inverse_round_trips() {
        let mut rng = Seed(1).rng();
        for e in WARPS.iter() {
            for _ in 0..2000 {
                let u = [uniform(&mut rng), uniform(&mut rng)];
                let mut x = vec![0.0; e.warp.output_dims(2)];
                if !e.warp.forward(&u, &mut x) {
                    continue;
                }
                let mut back = [0.0; 2];
                assert!(e.warp.inverse(&x, &mut back), "{}: {x:?} outside", e.about.name);
                for d in 0..2 {
                    let diff = (back[d] - u[d]).abs();
                    // angles wrap: 0 and 1 are the same point
                    assert!(diff.min(1.0 - diff) < 1e-9, "{}: {u:?} -> {x:?} -> {back:?}", e.about.name);
                }
            }
        }
    }

    /// density(f(u)) times the area (or solid-angle) Jacobian of f at u is one: the warp
    /// carries the uniform density to the stated one.
    #[test]
    fn density_matches_the_jacobian() {
        let mut rng = Seed(2).rng();
        let h = 1e-6;
        for e in bijective() {
            let m = e.warp.output_dims(2);
            for _ in 0..500 {
                let u = [0.01 + 0.98 * uniform(&mut rng), 0.01 + 0.98 * uniform(&mut rng)];
                let f = |a: f64, b: f64| {
                    let mut x = vec![0.0; m];
                    e.warp.forward(&[a, b], &mut x);
                    x
                };
                let x = f(u[0], u[1]);
                let du: Vec<f64> =
                    f(u[0] + h, u[1]).iter().zip(f(u[0] - h, u[1])).map(|(a, b)| (a - b) / (2.0 * h)).collect();
                let dv: Vec<f64> =
                    f(u[0], u[1] + h).iter().zip(f(u[0], u[1] - h)).map(|(a, b)| (a - b) / (2.0 * h)).collect();
                let jac = if m == 2 {
                    (du[0] * dv[1] - du[1] * dv[0]).abs()
                } else {
                    let c =
                        [du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]];
                    (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
                };
                let product = e.warp.density(&x) * jac;
                assert!((product - 1.0).abs() < 1e-5, "{} at {u:?}: density x jacobian = {product}", e.about.name);
            }
        }
    }

    /// The densities integrate to one over their domains (midpoint rule).
    #[test]
    fn densities_integrate_to_one() {
        let k = 2000;
        let h = 1.0 / k as f64;
        let cell = |i: usize| (i as f64 + 0.5) * h;
        // planar densities over [-L, L]^2
        for (e, half) in
            [("disk.polar", 1.0), ("disk.concentric", 1.0), ("disk.reject", 1.0), ("tent", 1.0), ("gaussian", 9.0)]
        {
            let w = lookup(e).unwrap();
            let mut sum = 0.0;
            for i in 0..k {
                for j in 0..k {
                    let x = [half * (2.0 * cell(i) - 1.0), half * (2.0 * cell(j) - 1.0)];
                    sum += w.density(&x);
                }
            }
            let total = sum * (2.0 * half * h).powi(2);
            assert!((total - 1.0).abs() < 2e-3, "{e}: {total}");
        }
        // hemispheres over (cos theta, phi): d omega = d(cos theta) d phi
        for e in ["hemisphere.uniform", "hemisphere.cosine"] {
            let w = lookup(e).unwrap();
            let mut sum = 0.0;
            for i in 0..k {
                let z = cell(i);
                let r = (1.0 - z * z).sqrt();
                for j in 0..k {
                    let phi = TAU * cell(j);
                    sum += w.density(&[r * phi.cos(), r * phi.sin(), z]);
                }
            }
            let total = sum * h * TAU * h;
            assert!((total - 1.0).abs() < 1e-6, "{e}: {total}");
        }
    }

    #[test]
    fn names_unique_and_lookup_suggests() {
        let mut names: Vec<&str> =
            WARPS.iter().flat_map(|e| std::iter::once(e.about.name).chain(e.about.aliases.iter().copied())).collect();
        let before = names.len();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), before);
        let e = lookup("disk.concentrc").unwrap_err().to_string();
        assert!(e.contains("disk.concentric"), "{e}");
    }
}
