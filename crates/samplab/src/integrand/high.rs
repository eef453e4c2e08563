//! d-dimensional test integrands with exact integrals over \[0,1\]^d: Genz's six families
//! (Genz 1984), Keister's (Keister 1996), Ishigami's (Ishigami & Homma 1990), and a
//! d-dimensional step and Gaussian. The dimension is the parameter `d`; the random
//! families draw their coefficients per instance.

use std::f64::consts::{PI, TAU};

use super::{Dims, Integrand, IntegrandEntry};
use crate::error::Result;
use crate::numeric::{BELOW_ONE, normal_quantile};
use crate::registry::About;
use crate::seed::{Rng, uniform};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The most dimensions of the families whose exact value is a sum over the 2^d corners.
const CORNER_MOST: u64 = 20;

const fn dims(default: u64, max: u64) -> ParamSpec {
    ParamSpec { name: "d", kind: Kind::Int { min: 1, max }, default: Default::Int(default), doc: "dimensions" }
}

const fn difficulty(default: f64) -> ParamSpec {
    ParamSpec {
        name: "h",
        kind: Kind::Real { min: 1e-3, max: 1e3 },
        default: Default::Number(default),
        doc: "difficulty: the sum of the coefficients a_i (Genz's b_j)",
    }
}

/// `d` from the parameters.
fn d_of(p: &Params) -> usize {
    p.int("d") as usize
}

/// Genz's random coefficients: a_i = h w_i / sum w (w_i uniform, so that the a_i sum to
/// the difficulty h) and shifts u_i uniform in [0, 1).
fn coefficients(p: &Params, rng: &mut Rng) -> (Vec<f64>, Vec<f64>) {
    let d = d_of(p);
    let w: Vec<f64> = (0..d).map(|_| uniform(rng)).collect();
    let u: Vec<f64> = (0..d).map(|_| uniform(rng)).collect();
    let sum: f64 = w.iter().sum();
    (w.iter().map(|x| p.real("h") * x / sum).collect(), u)
}

/// The six families of Genz 1984, each f(x) with coefficients a and shifts u.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Shape {
    /// cos(2 pi u_1 + sum a_i x_i).
    Oscillatory,
    /// prod (a_i^-2 + (x_i - u_i)^2)^-1.
    ProductPeak,
    /// (1 + sum a_i x_i)^-(d+1).
    CornerPeak,
    /// exp(-sum a_i^2 (x_i - u_i)^2).
    Gaussian,
    /// exp(-sum a_i |x_i - u_i|).
    Continuous,
    /// exp(sum a_i x_i) where x_1 <= u_1 and x_2 <= u_2 (x_1 alone in 1D), else 0.
    Discontinuous,
}

/// One instance of a Genz family.
#[derive(Debug, Clone)]
pub struct Genz {
    shape: Shape,
    a: Vec<f64>,
    u: Vec<f64>,
}

impl Genz {
    /// The Genz family `name` (`genz.oscillatory`, ...) with given coefficients a_i and
    /// shifts u_i (the oscillatory family reads u_1 alone), as other libraries fix them.
    ///
    /// # Errors
    /// A name that is not one of Genz's six families; a and u of different lengths, empty,
    /// or not finite; the corner peak with a negative a_i or more than 20 dimensions (its
    /// exact value sums over the 2^d corners).
    pub fn new(name: &str, a: Vec<f64>, u: Vec<f64>) -> Result<Genz> {
        let Some(&(_, shape)) = SHAPES.iter().find(|(n, _)| *n == name) else {
            return Err(crate::Error::UnknownName {
                kind: "Genz family",
                name: name.to_string(),
                suggestions: SHAPES.iter().map(|(n, _)| n.to_string()).collect(),
            });
        };
        let bad = |reason: &str| {
            Err(crate::Error::Setting {
                name: "coefficients",
                value: format!("a {a:?}, u {u:?}"),
                reason: reason.into(),
            })
        };
        if a.is_empty() || a.len() != u.len() || !a.iter().chain(&u).all(|v| v.is_finite()) {
            return bad("a and u must be finite and of the same length, at least 1");
        }
        if shape == Shape::CornerPeak && (a.len() as u64 > CORNER_MOST || a.iter().any(|&v| v < 0.0)) {
            return bad("the corner peak needs a_i >= 0 and at most 20 dimensions");
        }
        Ok(Genz { shape, a, u })
    }

    /// The instance's coefficients a_i and shifts u_i.
    pub fn coefficients(&self) -> (&[f64], &[f64]) {
        (&self.a, &self.u)
    }
}

impl Integrand for Genz {
    fn dims(&self) -> usize {
        self.a.len()
    }

    fn eval(&self, x: &[f64]) -> f64 {
        let (a, u) = (&self.a, &self.u);
        let dot = || a.iter().zip(x).map(|(a, x)| a * x).sum::<f64>();
        match self.shape {
            Shape::Oscillatory => (TAU * u[0] + dot()).cos(),
            Shape::ProductPeak => {
                a.iter().zip(u).zip(x).map(|((a, u), x)| 1.0 / (1.0 / (a * a) + (x - u).powi(2))).product()
            }
            Shape::CornerPeak => (1.0 + dot()).powi(-(a.len() as i32 + 1)),
            Shape::Gaussian => (-a.iter().zip(u).zip(x).map(|((a, u), x)| (a * (x - u)).powi(2)).sum::<f64>()).exp(),
            Shape::Continuous => (-a.iter().zip(u).zip(x).map(|((a, u), x)| a * (x - u).abs()).sum::<f64>()).exp(),
            Shape::Discontinuous => {
                if x.iter().zip(u).take(2).any(|(x, u)| x > u) {
                    0.0
                } else {
                    dot().exp()
                }
            }
        }
    }

    fn exact(&self) -> f64 {
        let (a, u) = (&self.a, &self.u);
        let each = |f: &dyn Fn(f64, f64) -> f64| a.iter().zip(u).map(|(&a, &u)| f(a, u)).product::<f64>();
        match self.shape {
            // Re of exp(2 pi i u_1) prod (exp(i a_j) - 1) / (i a_j)
            Shape::Oscillatory => {
                let (mut im, mut re) = (TAU * u[0]).sin_cos();
                for &a in a {
                    // (exp(i a) - 1) / (i a) = (sin a + i (1 - cos a)) / a, 1 - cos a as
                    // 2 sin^2(a/2) so that a small a loses nothing
                    let (fr, fi) = (a.sin() / a, 2.0 * (a / 2.0).sin().powi(2) / a);
                    (re, im) = (re * fr - im * fi, re * fi + im * fr);
                }
                re
            }
            Shape::ProductPeak => each(&|a, u| a * ((a * (1.0 - u)).atan() + (a * u).atan())),
            Shape::CornerPeak => corner_peak(a),
            Shape::Gaussian => each(&|a, u| PI.sqrt() / (2.0 * a) * (libm::erf(a * (1.0 - u)) + libm::erf(a * u))),
            Shape::Continuous => each(&|a, u| (-(-a * u).exp_m1() - (-a * (1.0 - u)).exp_m1()) / a),
            Shape::Discontinuous => {
                a.iter().enumerate().map(|(i, &a)| (a * if i < 2 { u[i] } else { 1.0 }).exp_m1() / a).product()
            }
        }
    }
}

/// The corner peak's integral over \[0,1\]^d of (1 + a.x)^-(d+1), a_i >= 0, without the
/// cancellation of the sum over the 2^d corners (which loses every digit once the product
/// of the a_i is small: QMCPy's coefficients 0.25, 5e-4, 1e-6 lost seven). From
/// t^-(d+1) = 1/d! integral over s > 0 of s^d exp(-s t), the integral is
/// 1/d! integral over s > 0 of exp(-s) prod_i (1 - exp(-s a_i)) / a_i, every factor
/// positive (expm1; s where a_i = 0). Computed in log s (s = e^y, y in \[-40, ln(2d + 90)\],
/// where the integrand is below 1e-34 of its peak outside), 160 panels of 16-point
/// Gauss-Legendre.
fn corner_peak(a: &[f64]) -> f64 {
    let d = a.len();
    let factorial: f64 = (1..=d).map(|k| k as f64).product();
    let integrand = |y: f64| {
        let s = y.exp();
        let product: f64 = a.iter().map(|&a| if a > 0.0 { -(-s * a).exp_m1() / a } else { s }).product();
        (-s).exp() * product * s
    };
    crate::numeric::quadrature::gauss_legendre(integrand, -40.0, (2.0 * d as f64 + 90.0).ln(), 160) / factorial
}

/// Keister's integrand: the integral over R^d of cos(|t|) exp(-|t|^2), as
/// pi^(d/2) cos(|Phi^-1(x) / sqrt 2|) over the unit cube (Keister 1996).
#[derive(Debug, Clone)]
pub struct Keister {
    d: usize,
}

impl Keister {
    /// The exact integral: the surface of the unit sphere S^(d-1), 2 pi^(d/2) / Gamma(d/2),
    /// times J_(d-1), J_k = integral over r > 0 of r^k cos(r) exp(-r^2). With K_k the same
    /// with sin(r), integrating by parts gives J_k = ((k - 1) J_(k-2) - K_(k-1)) / 2 and
    /// K_k = ((k - 1) K_(k-2) + J_(k-1)) / 2 for k >= 2, from J_0 = sqrt(pi) exp(-1/4) / 2,
    /// K_0 = F(1/2) (Dawson's integral), J_1 = (1 - K_0) / 2 and K_1 = J_0 / 2.
    fn exact_of(d: usize) -> f64 {
        let j0 = PI.sqrt() * (-0.25f64).exp() / 2.0;
        let k0 = dawson_half();
        let (mut j, mut k) = (vec![j0, (1.0 - k0) / 2.0], vec![k0, j0 / 2.0]);
        for n in 2..d {
            j.push(((n - 1) as f64 * j[n - 2] - k[n - 1]) / 2.0);
            k.push(((n - 1) as f64 * k[n - 2] + j[n - 1]) / 2.0);
        }
        let half = d as f64 / 2.0;
        2.0 * PI.powf(half) / libm::tgamma(half) * j[d - 1]
    }
}

/// Dawson's integral F(x) = exp(-x^2) times the integral of exp(t^2) over [0, x], at
/// x = 1/2, by its series sum over n of (-1)^n 2^n x^(2n+1) / (2n+1)!!.
fn dawson_half() -> f64 {
    let x: f64 = 0.5;
    let (mut term, mut sum) = (x, x);
    for n in 1..40 {
        term *= -2.0 * x * x / (2 * n + 1) as f64;
        sum += term;
    }
    sum
}

impl Integrand for Keister {
    fn dims(&self) -> usize {
        self.d
    }

    fn eval(&self, x: &[f64]) -> f64 {
        // a coordinate at 0 (possible for an unrandomized net) is taken at the least
        // positive double, one at 1 (from outside the samplers) below it: Phi^-1 is finite
        let r2: f64 = x.iter().map(|&x| normal_quantile(x.clamp(f64::MIN_POSITIVE, BELOW_ONE)).powi(2) / 2.0).sum();
        PI.powf(self.d as f64 / 2.0) * r2.sqrt().cos()
    }

    fn exact(&self) -> f64 {
        Keister::exact_of(self.d)
    }
}

/// Ishigami's function sin(z_1) + a sin^2(z_2) + b z_3^4 sin(z_1), z = pi (2x - 1) (Ishigami
/// & Homma 1990); its mean is a / 2.
#[derive(Debug, Clone)]
pub struct Ishigami {
    a: f64,
    b: f64,
}

impl Integrand for Ishigami {
    fn dims(&self) -> usize {
        3
    }

    fn eval(&self, x: &[f64]) -> f64 {
        let z = |x: f64| PI * (2.0 * x - 1.0);
        let (z1, z2, z3) = (z(x[0]), z(x[1]), z(x[2]));
        z1.sin() + self.a * z2.sin().powi(2) + self.b * z3.powi(4) * z1.sin()
    }

    fn exact(&self) -> f64 {
        self.a / 2.0
    }
}

/// The reflectance of a normalized Blinn-Phong lobe (Blinn 1977), BRDF (e + 2)/(2 pi)
/// cos^e theta_h, seen along the surface normal, as a renderer estimates it: the unit
/// square mapped to the disk by the concentric map (Shirley & Chiu 1997) and lifted to the
/// hemisphere (Malley's method, pdf cos theta / pi), so the estimator is
/// BRDF x cos theta / pdf = (e + 2)/2 cos^e theta_h, with cos^2 theta_h = (1 + cos theta)/2
/// for the viewer on the normal. It depends on both coordinates through the map.
///
/// The integral is (e + 2) times the integral of w^(e/2) u over u in \[0, 1\], w = (1 + u)/2:
/// substituting u = 2w - 1, 2 (e + 2) \[2 w^(k+2)/(k+2) - w^(k+1)/(k+1)\] from 1/2 to 1 with
/// k = e/2; 1 for e = 0 (Lambert).
#[derive(Debug, Clone)]
pub struct BlinnPhong {
    exponent: f64,
}

impl Integrand for BlinnPhong {
    fn dims(&self) -> usize {
        2
    }

    fn eval(&self, x: &[f64]) -> f64 {
        let (a, b) = crate::warp::concentric(x[0], x[1]);
        let cos_theta = (1.0 - (a * a + b * b)).max(0.0).sqrt();
        // cos^e theta_h = ((1 + cos theta) / 2)^(e/2)
        (self.exponent + 2.0) / 2.0 * ((1.0 + cos_theta) / 2.0).powf(self.exponent / 2.0)
    }

    fn exact(&self) -> f64 {
        let k = self.exponent / 2.0;
        let antiderivative = |w: f64| 2.0 * w.powf(k + 2.0) / (k + 2.0) - w.powf(k + 1.0) / (k + 1.0);
        2.0 * (self.exponent + 2.0) * (antiderivative(1.0) - antiderivative(0.5))
    }
}

/// The indicator of a half-space whose boundary passes through the cube's centre, its
/// normal uniform on the sphere: 1/2 exactly (the cube is symmetric about its centre).
#[derive(Debug, Clone)]
pub struct HalfSpace {
    normal: Vec<f64>,
}

impl Integrand for HalfSpace {
    fn dims(&self) -> usize {
        self.normal.len()
    }

    fn eval(&self, x: &[f64]) -> f64 {
        f64::from(u8::from(self.normal.iter().zip(x).map(|(n, x)| n * (x - 0.5)).sum::<f64>() > 0.0))
    }

    fn exact(&self) -> f64 {
        0.5
    }
}

/// An isotropic Gaussian exp(-|x - c|^2 / (2 sigma^2)) at a uniform random centre c.
#[derive(Debug, Clone)]
pub struct GaussianD {
    sigma: f64,
    centre: Vec<f64>,
}

impl Integrand for GaussianD {
    fn dims(&self) -> usize {
        self.centre.len()
    }

    fn eval(&self, x: &[f64]) -> f64 {
        (-self.centre.iter().zip(x).map(|(c, x)| (x - c).powi(2)).sum::<f64>() / (2.0 * self.sigma * self.sigma)).exp()
    }

    fn exact(&self) -> f64 {
        let s = self.sigma * std::f64::consts::SQRT_2;
        self.centre
            .iter()
            .map(|c| self.sigma * (PI / 2.0).sqrt() * (libm::erf((1.0 - c) / s) + libm::erf(c / s)))
            .product()
    }
}

fn genz(shape: Shape, p: &Params, rng: &mut Rng) -> Result<Box<dyn Integrand>> {
    let (a, u) = coefficients(p, rng);
    Ok(Box::new(Genz { shape, a, u }))
}

/// Instance `k` of Genz family `spec` (`genz.oscillatory:d=4`, ...) with its coefficients
/// exposed.
///
/// # Errors
/// An unknown family or bad parameters; a family that is not Genz's.
pub fn genz_instance(spec: &str, seed: crate::Seed, k: u64) -> Result<Genz> {
    let family = super::Family::parse(spec)?;
    let (a, u) = coefficients(&family.params, &mut seed.derive(k).rng());
    Genz::new(family.entry.about.name, a, u)
}

/// Genz's families by name, in the registry's order.
const SHAPES: [(&str, Shape); 6] = [
    ("genz.oscillatory", Shape::Oscillatory),
    ("genz.product-peak", Shape::ProductPeak),
    ("genz.corner-peak", Shape::CornerPeak),
    ("genz.gaussian", Shape::Gaussian),
    ("genz.continuous", Shape::Continuous),
    ("genz.discontinuous", Shape::Discontinuous),
];

macro_rules! genz_entry {
    ($i:literal, $h:literal, $max:expr, $summary:literal) => {
        IntegrandEntry {
            about: About::new(SHAPES[$i].0, $summary).params(&[dims(2, $max), difficulty($h)]).cite(&["genz1984"]),
            dims: Dims::Param,
            build: |p, rng| genz(SHAPES[$i].1, p, rng),
        }
    };
}

/// The families this file declares.
pub(super) static FAMILIES: &[IntegrandEntry] = &[
    genz_entry!(0, 9.0, 1000, "Genz's oscillatory cos(2 pi u_1 + a.x)"),
    genz_entry!(1, 7.25, 1000, "Genz's product peak prod (a_i^-2 + (x_i - u_i)^2)^-1"),
    genz_entry!(
        2,
        1.85,
        CORNER_MOST,
        "Genz's corner peak (1 + a.x)^-(d+1) (exact value a sum over the 2^d corners: d up to 20)"
    ),
    genz_entry!(3, 7.03, 1000, "Genz's Gaussian exp(-sum a_i^2 (x_i - u_i)^2)"),
    genz_entry!(4, 20.4, 1000, "Genz's continuous exp(-sum a_i |x_i - u_i|), kinked at u"),
    genz_entry!(5, 4.3, 1000, "Genz's discontinuous exp(a.x) on x_1 <= u_1, x_2 <= u_2, 0 elsewhere"),
    IntegrandEntry {
        about: About::new("keister", "Keister's pi^(d/2) cos(|Phi^-1(x) / sqrt 2|): cos(|t|) exp(-|t|^2) over R^d")
            .params(&[dims(3, 1000)])
            .cite(&["keister1996"]),
        dims: Dims::Param,
        build: |p, _| Ok(Box::new(Keister { d: d_of(p) })),
    },
    IntegrandEntry {
        about: About::new("ishigami", "Ishigami's sin z_1 + a sin^2 z_2 + b z_3^4 sin z_1, z = pi (2x - 1); mean a/2")
            .params(&[
                ParamSpec {
                    name: "a",
                    kind: Kind::Real { min: -1e3, max: 1e3 },
                    default: Default::Number(7.0),
                    doc: "a",
                },
                ParamSpec {
                    name: "b",
                    kind: Kind::Real { min: -1e3, max: 1e3 },
                    default: Default::Number(0.1),
                    doc: "b",
                },
            ])
            .cite(&["ishigami1990"]),
        dims: Dims::Fixed(3),
        build: |p, _| Ok(Box::new(Ishigami { a: p.real("a"), b: p.real("b") })),
    },
    IntegrandEntry {
        about: About::new(
            "blinn-phong",
            "reflectance of a normalized Blinn-Phong lobe seen along the normal, sampled by Malley's method (concentric map)",
        )
        .params(&[ParamSpec {
            name: "e",
            kind: Kind::Real { min: 0.0, max: 1e5 },
            default: Default::Number(32.0),
            doc: "the lobe's exponent (0: Lambert)",
        }])
        .cite(&["blinn1977", "shirley1997"]),
        dims: Dims::Fixed(2),
        build: |p, _| Ok(Box::new(BlinnPhong { exponent: p.real("e") })),
    },
    IntegrandEntry {
        about: About::new(
            "heaviside.d",
            "the indicator of a half-space through the cube's centre, its normal uniform on the sphere (exact 1/2)",
        )
        .params(&[dims(2, 1000)]),
        dims: Dims::Param,
        build: |p, rng| {
            let mut normal: Vec<f64> =
                (0..d_of(p)).map(|_| normal_quantile(uniform(rng).max(f64::MIN_POSITIVE))).collect();
            // every draw exactly 1/2 (probability 2^-53d): the first axis
            if normal.iter().all(|&n| n == 0.0) {
                normal[0] = 1.0;
            }
            Ok(Box::new(HalfSpace { normal }))
        },
    },
    IntegrandEntry {
        about: About::new("gaussian.d", "isotropic Gaussian exp(-|x - c|^2 / (2 sigma^2)) at a uniform random centre")
            .params(&[
                dims(2, 1000),
                ParamSpec {
                    name: "sigma",
                    kind: Kind::Real { min: 1e-3, max: 10.0 },
                    default: Default::Number(0.3),
                    doc: "standard deviation",
                },
            ]),
        dims: Dims::Param,
        build: |p, rng| {
            let centre = (0..d_of(p)).map(|_| uniform(rng)).collect();
            Ok(Box::new(GaussianD { sigma: p.real("sigma"), centre }))
        },
    },
];
