//! Test integrands with exact integrals: the papers' test cases (Subr & Kautz 2013
//! section 4.2, Sbert et al. 2006 section 3.1, Ramamoorthi et al. 2012 section 4) and a
//! few classics. Random families are instantiated from a seed: instance k of a family
//! uses `seed.derive(k)`.
//!
//! 2D integrands live on the unit square, 1D ones on the unit interval; every `exact()`
//! is the integral over that domain, in closed form or (for the zone plate) by a
//! documented high-accuracy quadrature.

use std::f64::consts::{PI, TAU};

use crate::error::{Error, Result};
use crate::registry::{About, Entry, Registry, canonical};
use crate::seed::{Rng, Seed, uniform};
use crate::spec::{Default, Kind, ParamSpec, Params};

mod delaunay;
mod expr;
mod grid;
mod high;
mod texture;
use crate::numeric::quadrature;

pub use delaunay::Delaunay;
pub use expr::{Expr, MAX_NESTING};
pub use grid::Grid;
pub use high::{BlinnPhong, GaussianD, Genz, HalfSpace, Ishigami, Keister, genz_instance};
pub use texture::{Lookup, Texture};

/// A function on \[0,1\]^d with a known integral.
pub trait Integrand: Send + Sync {
    /// Dimensions.
    fn dims(&self) -> usize;
    /// The value at `x`.
    fn eval(&self, x: &[f64]) -> f64;
    /// The values at many points, `dims()` coordinates each in `points`, into `out` (one
    /// per point); the default calls [`Integrand::eval`] on each. An integrand that is
    /// cheaper in batches (a vectorized Python function) overrides it.
    fn eval_many(&self, points: &[f64], out: &mut [f64]) {
        for (x, o) in points.chunks_exact(self.dims()).zip(out) {
            *o = self.eval(x);
        }
    }
    /// The exact integral over \[0,1\]^d.
    fn exact(&self) -> f64;
    /// For an indicator function: the length of its region's boundary inside the domain
    /// (Sbert et al.'s B), which the systematic-sampling law k B u^3 needs.
    fn boundary_length(&self) -> Option<f64> {
        None
    }
    /// For 1D visibility: the number of discontinuities (Ramamoorthi et al.'s theory).
    fn discontinuities(&self) -> Option<usize> {
        None
    }
    /// The Fourier coefficient F(k) = integral of f(x) exp(-2 pi i k.x) over the domain, as
    /// (re, im), at integer frequency k (`[k, 0]` in 1D), where a closed form is known
    /// ([`crate::predict`] uses it; with `exact_square`).
    fn fourier(&self, _k: [i64; 2]) -> Option<[f64; 2]> {
        None
    }
    /// The integral of f^2 over the domain, where a closed form is known.
    fn exact_square(&self) -> Option<f64> {
        None
    }
}

/// A closure as an integrand: any `Fn(&[f64]) -> f64` of `dims` coordinates, its integral
/// unknown (NaN) unless stated.
///
/// ```
/// use samplab::cubature::{Settings, cubature};
/// use samplab::integrand::Closure;
/// use samplab::progress::Progress;
/// let f = Closure::new(2, |x: &[f64]| x[0] * x[1]).with_exact(0.25);
/// let c = cubature(&f, &Settings { abs_tol: 1e-4, ..Settings::default() }, &Progress::SILENT).unwrap();
/// assert!(c.converged && (c.estimate - 0.25).abs() < 1e-4);
/// ```
pub struct Closure<F> {
    dims: usize,
    f: F,
    exact: f64,
}

impl<F: Fn(&[f64]) -> f64 + Send + Sync> Closure<F> {
    /// `f` over \[0,1\]^dims.
    pub fn new(dims: usize, f: F) -> Closure<F> {
        Closure { dims, f, exact: f64::NAN }
    }

    /// The same with its exact integral stated.
    #[must_use]
    pub fn with_exact(self, exact: f64) -> Closure<F> {
        Closure { exact, ..self }
    }
}

impl<F: Fn(&[f64]) -> f64 + Send + Sync> Integrand for Closure<F> {
    fn dims(&self) -> usize {
        self.dims
    }
    fn eval(&self, x: &[f64]) -> f64 {
        (self.f)(x)
    }
    fn exact(&self) -> f64 {
        self.exact
    }
}

/// exp(-2 pi i t) as (re, im).
fn phase(t: f64) -> [f64; 2] {
    let (s, c) = (TAU * t).sin_cos();
    [c, -s]
}

/// sin(z) / z.
fn sinc(z: f64) -> f64 {
    if z.abs() < 1e-8 { 1.0 - z * z / 6.0 } else { z.sin() / z }
}

/// The Fourier coefficient of a polygon's indicator (vertices counter-clockwise), by the
/// divergence theorem: for k != 0, F(k) = i / (2 pi |k|^2) sum over edges a -> b of
/// (k_x dy - k_y dx) exp(-2 pi i k.m) sinc(pi k.(b - a)), m the edge's midpoint; F(0) the
/// area (shoelace).
fn polygon_fourier(v: &[[f64; 2]], k: [i64; 2]) -> [f64; 2] {
    let edges = || (0..v.len()).map(|i| (v[i], v[(i + 1) % v.len()]));
    if k == [0, 0] {
        return [edges().map(|(a, b)| a[0] * b[1] - b[0] * a[1]).sum::<f64>() / 2.0, 0.0];
    }
    let (kx, ky) = (k[0] as f64, k[1] as f64);
    let mut sum = [0.0, 0.0];
    for (a, b) in edges() {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let weight = (kx * dy - ky * dx) * sinc(PI * (kx * dx + ky * dy));
        let [c, s] = phase(kx * (a[0] + b[0]) / 2.0 + ky * (a[1] + b[1]) / 2.0);
        sum[0] += weight * c;
        sum[1] += weight * s;
    }
    // times i / (2 pi |k|^2): (re, im) -> (-im, re)
    let scale = 1.0 / (TAU * (kx * kx + ky * ky));
    [-sum[1] * scale, sum[0] * scale]
}

/// Test case I of Subr & Kautz 2013: 0 inside a quad whose four vertices lie one on each
/// side of the unit square, 1 outside. Exact: 1 - the quad's area (shoelace formula).
#[derive(Debug, Clone)]
pub struct Quad {
    v: [[f64; 2]; 4],
}

impl Quad {
    /// The quad with vertices at (a,0), (1,b), (c,1), (0,d).
    pub fn new(a: f64, b: f64, c: f64, d: f64) -> Self {
        Quad { v: [[a, 0.0], [1.0, b], [c, 1.0], [0.0, d]] }
    }
    fn random(rng: &mut Rng) -> Self {
        Quad::new(uniform(rng), uniform(rng), uniform(rng), uniform(rng))
    }
    fn area(&self) -> f64 {
        (0..4).map(|i| self.v[i][0] * self.v[(i + 1) % 4][1] - self.v[(i + 1) % 4][0] * self.v[i][1]).sum::<f64>() / 2.0
    }
}

impl Integrand for Quad {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        // counter-clockwise convex quad: inside when left of every edge
        let inside = (0..4).all(|i| {
            let (a, b) = (self.v[i], self.v[(i + 1) % 4]);
            (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]) >= 0.0
        });
        if inside { 0.0 } else { 1.0 }
    }
    fn exact(&self) -> f64 {
        1.0 - self.area()
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        // 1 less the quad's indicator
        let [re, im] = polygon_fourier(&self.v, k);
        Some(if k == [0, 0] { [1.0 - re, 0.0] } else { [-re, -im] })
    }
    fn exact_square(&self) -> Option<f64> {
        Some(self.exact())
    }
    fn boundary_length(&self) -> Option<f64> {
        Some((0..4).map(|i| (self.v[(i + 1) % 4][0] - self.v[i][0]).hypot(self.v[(i + 1) % 4][1] - self.v[i][1])).sum())
    }
}

/// The indicator of a disk of radius r centred at c, inside the unit square (Sbert et
/// al. 2006's circle). Exact: pi r^2.
#[derive(Debug, Clone)]
pub struct Disk {
    centre: [f64; 2],
    radius: f64,
}

impl Integrand for Disk {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let (dx, dy) = (x[0] - self.centre[0], x[1] - self.centre[1]);
        if dx * dx + dy * dy < self.radius * self.radius { 1.0 } else { 0.0 }
    }
    fn exact(&self) -> f64 {
        PI * self.radius * self.radius
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        // the disk lies inside the square: r J1(2 pi r |k|) / |k|, moved to the centre
        let norm = (k[0] as f64).hypot(k[1] as f64);
        if norm == 0.0 {
            return Some([self.exact(), 0.0]);
        }
        let amplitude = self.radius * libm::j1(TAU * self.radius * norm) / norm;
        let [c, s] = phase(k[0] as f64 * self.centre[0] + k[1] as f64 * self.centre[1]);
        Some([amplitude * c, amplitude * s])
    }
    fn exact_square(&self) -> Option<f64> {
        Some(self.exact())
    }
    fn boundary_length(&self) -> Option<f64> {
        Some(TAU * self.radius)
    }
}

/// The indicator of the half-plane n.(x - p) > 0 through the point p at angle theta
/// (normal n = (cos theta, sin theta)). Exact: the area of the clipped square (shoelace).
#[derive(Debug, Clone)]
pub struct HalfPlane {
    normal: [f64; 2],
    point: [f64; 2],
}

impl HalfPlane {
    /// The half-plane n.(x - p) > 0.
    pub(crate) fn new(normal: [f64; 2], point: [f64; 2]) -> HalfPlane {
        HalfPlane { normal, point }
    }
    fn side(&self, x: &[f64]) -> f64 {
        self.normal[0] * (x[0] - self.point[0]) + self.normal[1] * (x[1] - self.point[1])
    }
    /// The unit square clipped to the half-plane (Sutherland-Hodgman).
    fn clipped(&self) -> Vec<[f64; 2]> {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let mut out = Vec::new();
        for i in 0..4 {
            let (a, b) = (square[i], square[(i + 1) % 4]);
            let (sa, sb) = (self.side(&a), self.side(&b));
            if sa > 0.0 {
                out.push(a);
            }
            if (sa > 0.0) != (sb > 0.0) {
                let t = sa / (sa - sb);
                out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
            }
        }
        out
    }
}

impl Integrand for HalfPlane {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        if self.side(x) > 0.0 { 1.0 } else { 0.0 }
    }
    fn exact(&self) -> f64 {
        polygon_fourier(&self.clipped(), [0, 0])[0]
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        Some(polygon_fourier(&self.clipped(), k))
    }
    fn exact_square(&self) -> Option<f64> {
        Some(self.exact())
    }
    fn boundary_length(&self) -> Option<f64> {
        // the clipped polygon's edges that lie on the line
        let p = self.clipped();
        Some(
            (0..p.len())
                .map(|i| (p[i], p[(i + 1) % p.len()]))
                .filter(|(a, b)| self.side(a).abs() < 1e-12 && self.side(b).abs() < 1e-12)
                .map(|(a, b)| (b[0] - a[0]).hypot(b[1] - a[1]))
                .sum(),
        )
    }
}

/// An isotropic Gaussian exp(-|x - c|^2 / (2 sigma^2)). Exact through erf.
#[derive(Debug, Clone)]
pub struct Gaussian {
    centre: [f64; 2],
    sigma: f64,
}

impl Integrand for Gaussian {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let r2 = (x[0] - self.centre[0]).powi(2) + (x[1] - self.centre[1]).powi(2);
        (-r2 / (2.0 * self.sigma * self.sigma)).exp()
    }
    fn exact(&self) -> f64 {
        let s = self.sigma * 2f64.sqrt();
        let axis = |c: f64| self.sigma * (PI / 2.0).sqrt() * (libm::erf((1.0 - c) / s) + libm::erf(c / s));
        axis(self.centre[0]) * axis(self.centre[1])
    }
}

/// A smooth, non-periodic function exp(a x + b y) (the regime where jittered sampling
/// converges as N^-2 in 2D). Exact: (e^a - 1)/a * (e^b - 1)/b.
#[derive(Debug, Clone)]
pub struct Smooth {
    a: f64,
    b: f64,
}

impl Integrand for Smooth {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        (self.a * x[0] + self.b * x[1]).exp()
    }
    fn exact(&self) -> f64 {
        (self.a.exp_m1() / self.a) * (self.b.exp_m1() / self.b)
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        // separable: the integral of exp(a x - 2 pi i k x) over [0, 1] is (e^a - 1) / (a - 2 pi i k)
        let axis = |a: f64, k: i64| {
            let w = TAU * k as f64;
            let d = a * a + w * w;
            [a.exp_m1() * a / d, a.exp_m1() * w / d]
        };
        let ([p, q], [r, s]) = (axis(self.a, k[0]), axis(self.b, k[1]));
        Some([p * r - q * s, p * s + q * r])
    }
    fn exact_square(&self) -> Option<f64> {
        Some(((2.0 * self.a).exp_m1() / (2.0 * self.a)) * ((2.0 * self.b).exp_m1() / (2.0 * self.b)))
    }
}

/// The zone plate (1 + cos(a r^2)) / 2, r measured from the square's centre (Subr &
/// Kautz 2013 Fig. 10). Exact: (1 + C^2 - S^2) / 2 with C, S the integrals of cos(a t^2)
/// and sin(a t^2) over [-1/2, 1/2], by composite 16-point Gauss-Legendre quadrature
/// with a panel per quarter oscillation (relative error below 1e-13).
#[derive(Debug, Clone)]
pub struct ZonePlate {
    a: f64,
}

impl Integrand for ZonePlate {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let r2 = (x[0] - 0.5).powi(2) + (x[1] - 0.5).powi(2);
        0.5 * (1.0 + (self.a * r2).cos())
    }
    fn exact(&self) -> f64 {
        let panels = 16 + (self.a / 2.0).ceil() as usize;
        let c = quadrature::gauss_legendre(|t| (self.a * t * t).cos(), -0.5, 0.5, panels);
        let s = quadrature::gauss_legendre(|t| (self.a * t * t).sin(), -0.5, 0.5, panels);
        0.5 * (1.0 + c * c - s * s)
    }
}

/// A plane wave (1 + cos(2 pi (u x + v y) + phase)) / 2 of integer frequency (u, v): all
/// its energy at one frequency, where a sampler's expected spectrum says whether it aliases
/// (Subr & Kautz 2013 eq. 4: a grid of k x k points at (u, v) = (k, 0) sees a constant).
pub struct Cosine {
    u: f64,
    v: f64,
    phase: f64,
}

impl Integrand for Cosine {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        0.5 * (1.0 + (std::f64::consts::TAU * (self.u * x[0] + self.v * x[1]) + self.phase).cos())
    }
    fn exact(&self) -> f64 {
        // a whole number of periods along a nonzero frequency integrates to 0
        if self.u == 0.0 && self.v == 0.0 { 0.5 * (1.0 + self.phase.cos()) } else { 0.5 }
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        // 1/2 + e^{i phase}/4 at (u, v) + e^{-i phase}/4 at -(u, v)
        let (kx, ky) = (k[0] as f64, k[1] as f64);
        Some(if k == [0, 0] {
            [self.exact(), 0.0]
        } else if (kx, ky) == (self.u, self.v) {
            [self.phase.cos() / 4.0, self.phase.sin() / 4.0]
        } else if (kx, ky) == (-self.u, -self.v) {
            [self.phase.cos() / 4.0, -self.phase.sin() / 4.0]
        } else {
            [0.0, 0.0]
        })
    }
    fn exact_square(&self) -> Option<f64> {
        Some(if self.u == 0.0 && self.v == 0.0 { self.exact().powi(2) } else { 0.375 })
    }
}

/// 1D visibility over a linear light (Ramamoorthi et al. 2012 section 4): 1 where the
/// light is visible. Visibility starts at 1 (for `Step`, H(y - y0): 0 below y0) and
/// flips at each discontinuity.
#[derive(Debug, Clone)]
pub struct Visibility {
    /// Sorted discontinuity positions.
    edges: Vec<f64>,
    /// Value before the first discontinuity.
    start: f64,
}

impl Integrand for Visibility {
    fn dims(&self) -> usize {
        1
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let flips = self.edges.partition_point(|&e| e <= x[0]);
        if flips % 2 == 0 { self.start } else { 1.0 - self.start }
    }
    fn exact(&self) -> f64 {
        let mut bounds = vec![0.0];
        bounds.extend(&self.edges);
        bounds.push(1.0);
        bounds
            .windows(2)
            .enumerate()
            .map(|(i, w)| (w[1] - w[0]) * if i % 2 == 0 { self.start } else { 1.0 - self.start })
            .sum()
    }
    fn discontinuities(&self) -> Option<usize> {
        Some(self.edges.len())
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        // the integral of exp(-2 pi i k x) over [a, b] is (e(a) - e(b)) / (2 pi i k)
        if k[0] == 0 {
            return Some([self.exact(), 0.0]);
        }
        let mut bounds = vec![0.0];
        bounds.extend(&self.edges);
        bounds.push(1.0);
        let mut sum = [0.0, 0.0];
        for (i, w) in bounds.windows(2).enumerate() {
            let value = if i % 2 == 0 { self.start } else { 1.0 - self.start };
            let ([ca, sa], [cb, sb]) = (phase(k[0] as f64 * w[0]), phase(k[0] as f64 * w[1]));
            sum[0] += value * (ca - cb);
            sum[1] += value * (sa - sb);
        }
        // divided by 2 pi i k: (re, im) -> (im, -re) / (2 pi k)
        let scale = 1.0 / (TAU * k[0] as f64);
        Some([sum[1] * scale, -sum[0] * scale])
    }
    fn exact_square(&self) -> Option<f64> {
        Some(self.exact())
    }
}

/// One registered integrand family.
pub struct IntegrandEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Dimensions.
    pub dims: Dims,
    build: fn(&Params, &mut Rng) -> Result<Box<dyn Integrand>>,
}

/// How many dimensions a family's integrands have.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Dims {
    /// Always this many.
    Fixed(usize),
    /// The family's parameter `d`.
    Param,
}

impl std::fmt::Debug for IntegrandEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("IntegrandEntry").field("name", &self.about.name).finish_non_exhaustive()
    }
}

impl Entry for IntegrandEntry {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        match self.dims {
            Dims::Fixed(d) => vec![format!("dimensions: {d}")],
            Dims::Param => vec!["dimensions: the parameter d".to_string()],
        }
    }
}

/// Every integrand family.
pub static INTEGRANDS: Registry<IntegrandEntry> = Registry::new(
    "integrand",
    "INTEGRANDS  (exact integrals; random families draw instance k from a hashed seed)",
    &[&[FAMILIES, high::FAMILIES]],
);

const fn auto(name: &'static str, min: f64, max: f64, how: &'static str, doc: &'static str) -> ParamSpec {
    ParamSpec { name, kind: Kind::Real { min, max }, default: Default::Auto(how), doc }
}

fn or_random(p: &Params, name: &str, rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    // always draw, so that fixing one parameter leaves the others' streams unchanged
    let r = lo + (hi - lo) * uniform(rng);
    p.real_or_auto(name).unwrap_or(r)
}

/// The Delaunay test cases' one parameter.
const DELAUNAY_POINTS: ParamSpec = ParamSpec {
    name: "points",
    kind: Kind::Int { min: 0, max: 10_000 },
    default: Default::Int(8),
    doc: "random points besides the four corners",
};

/// The families this file declares.
static FAMILIES: &[IntegrandEntry] = &[
    IntegrandEntry {
        about: About {
            name: "quad",
            aliases: &["test-i", "occlusion"],
            summary: "Subr & Kautz test case I: 0 inside a random quad with one vertex on each side, 1 outside",
            params: &[],
            references: &["subr2013"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |_, rng| Ok(Box::new(Quad::random(rng))),
    },
    IntegrandEntry {
        about: About {
            name: "delaunay-constant",
            aliases: &["test-ii"],
            summary: "Subr & Kautz test case II: piecewise constant over a Delaunay triangulation of sparse random points and the corners",
            params: &[DELAUNAY_POINTS],
            references: &["subr2013"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| Ok(Box::new(Delaunay::random(p.int("points") as usize, false, rng)?)),
    },
    IntegrandEntry {
        about: About {
            name: "delaunay-linear",
            aliases: &["test-iii"],
            summary: "Subr & Kautz test case III: piecewise linear over a Delaunay triangulation, random weights per vertex",
            params: &[DELAUNAY_POINTS],
            references: &["subr2013"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| Ok(Box::new(Delaunay::random(p.int("points") as usize, true, rng)?)),
    },
    IntegrandEntry {
        about: About {
            name: "zoneplate",
            aliases: &["zone-plate"],
            summary: "zone plate (1 + cos(a r^2)) / 2 about the square's centre",
            params: &[ParamSpec {
                name: "a",
                kind: Kind::Real { min: 0.0, max: 1e5 },
                default: Default::Number(200.0),
                doc: "chirp rate, radians per unit r^2",
            }],
            references: &["subr2013"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, _| Ok(Box::new(ZonePlate { a: p.real("a") })),
    },
    IntegrandEntry {
        about: About {
            name: "cosine",
            aliases: &["plane-wave"],
            summary: "plane wave (1 + cos(2 pi (u x + v y) + phase)) / 2 of integer frequency (u, v)",
            params: &[
                ParamSpec {
                    name: "u",
                    kind: Kind::Int { min: 0, max: 100_000 },
                    default: Default::Int(16),
                    doc: "cycles across x",
                },
                ParamSpec {
                    name: "v",
                    kind: Kind::Int { min: 0, max: 100_000 },
                    default: Default::Int(0),
                    doc: "cycles across y",
                },
                auto("phase", 0.0, std::f64::consts::TAU, "uniform", "phase, radians"),
            ],
            references: &["subr2013"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| {
            let phase = or_random(p, "phase", rng, 0.0, std::f64::consts::TAU);
            Ok(Box::new(Cosine { u: p.int("u") as f64, v: p.int("v") as f64, phase }))
        },
    },
    IntegrandEntry {
        about: About {
            name: "disk",
            aliases: &["circle"],
            summary: "indicator of a disk inside the square (Sbert et al.'s circle)",
            params: &[
                auto(
                    "r",
                    0.0,
                    0.5,
                    "uniform in [0.1, 0.4], so that averages cover the radius (Sbert et al.'s Zitterbewegung)",
                    "radius",
                ),
                auto("cx", 0.0, 1.0, "random, keeping the disk inside the square", "centre x"),
                auto("cy", 0.0, 1.0, "random, keeping the disk inside the square", "centre y"),
            ],
            references: &["sbert2006"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| {
            let r = or_random(p, "r", rng, 0.1, 0.4);
            let (cx, cy) = (or_random(p, "cx", rng, r, 1.0 - r), or_random(p, "cy", rng, r, 1.0 - r));
            if cx < r || cx > 1.0 - r || cy < r || cy > 1.0 - r {
                return Err(Error::Param {
                    owner: "disk".into(),
                    param: "cx, cy".into(),
                    reason: format!("a disk of radius {r} at ({cx}, {cy}) leaves the square"),
                });
            }
            Ok(Box::new(Disk { centre: [cx, cy], radius: r }))
        },
    },
    IntegrandEntry {
        about: About {
            name: "halfplane",
            aliases: &["edge"],
            summary: "indicator of a half-plane at a random angle through a random point",
            params: &[
                auto("angle", -360.0, 360.0, "uniform", "direction of the normal, degrees"),
                auto("x", 0.0, 1.0, "uniform", "a point on the line, x"),
                auto("y", 0.0, 1.0, "uniform", "a point on the line, y"),
            ],
            references: &["sbert2006"],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| {
            let angle = or_random(p, "angle", rng, 0.0, 360.0).to_radians();
            let point = [or_random(p, "x", rng, 0.0, 1.0), or_random(p, "y", rng, 0.0, 1.0)];
            Ok(Box::new(HalfPlane { normal: [angle.cos(), angle.sin()], point }))
        },
    },
    IntegrandEntry {
        about: About {
            name: "gaussian",
            aliases: &[],
            summary: "isotropic Gaussian bump at a random centre",
            params: &[
                ParamSpec {
                    name: "sigma",
                    kind: Kind::Real { min: 1e-3, max: 10.0 },
                    default: Default::Number(0.15),
                    doc: "standard deviation",
                },
                auto("cx", 0.0, 1.0, "uniform", "centre x"),
                auto("cy", 0.0, 1.0, "uniform", "centre y"),
            ],
            references: &[],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |p, rng| {
            Ok(Box::new(Gaussian {
                sigma: p.real("sigma"),
                centre: [or_random(p, "cx", rng, 0.0, 1.0), or_random(p, "cy", rng, 0.0, 1.0)],
            }))
        },
    },
    IntegrandEntry {
        about: About {
            name: "smooth",
            aliases: &["exp"],
            summary: "smooth non-periodic exp(a x + b y), a and b uniform in [0.5, 2]",
            params: &[],
            references: &[],
            terse: false,
        },
        dims: Dims::Fixed(2),
        build: |_, rng| Ok(Box::new(Smooth { a: 0.5 + 1.5 * uniform(rng), b: 0.5 + 1.5 * uniform(rng) })),
    },
    IntegrandEntry {
        about: About {
            name: "step",
            aliases: &["heaviside"],
            summary: "1D visibility H(y - y0): one discontinuity (Ramamoorthi et al. eq. 5)",
            params: &[auto("y0", 0.0, 1.0, "uniform", "discontinuity")],
            references: &["ramamoorthi2012"],
            terse: false,
        },
        dims: Dims::Fixed(1),
        build: |p, rng| Ok(Box::new(Visibility { edges: vec![or_random(p, "y0", rng, 0.0, 1.0)], start: 0.0 })),
    },
    IntegrandEntry {
        about: About {
            name: "box",
            aliases: &["boxcar"],
            summary: "1D visibility H(y - y0) - H(y - z0): two discontinuities (Ramamoorthi et al. eq. 13)",
            params: &[
                auto("y0", 0.0, 1.0, "the smaller of two uniform draws", "first discontinuity"),
                auto("z0", 0.0, 1.0, "the larger", "second discontinuity"),
            ],
            references: &["ramamoorthi2012"],
            terse: false,
        },
        dims: Dims::Fixed(1),
        build: |p, rng| {
            let (a, b) = (or_random(p, "y0", rng, 0.0, 1.0), or_random(p, "z0", rng, 0.0, 1.0));
            let (y0, z0) = if p.real_or_auto("y0").is_some() || p.real_or_auto("z0").is_some() {
                (a, b)
            } else {
                (a.min(b), a.max(b))
            };
            if z0 < y0 {
                return Err(Error::Param {
                    owner: "box".into(),
                    param: "z0".into(),
                    reason: format!("z0 = {z0} is below y0 = {y0}"),
                });
            }
            Ok(Box::new(Visibility { edges: vec![y0, z0], start: 0.0 }))
        },
    },
    IntegrandEntry {
        about: About {
            name: "steps",
            aliases: &["discontinuities"],
            summary: "1D visibility with k discontinuities at uniform random positions (Ramamoorthi et al. Fig. 7)",
            params: &[ParamSpec {
                name: "k",
                kind: Kind::Int { min: 0, max: 100_000 },
                default: Default::Int(3),
                doc: "number of discontinuities",
            }],
            references: &["ramamoorthi2012"],
            terse: false,
        },
        dims: Dims::Fixed(1),
        build: |p, rng| {
            let k = p.int("k") as usize;
            let mut edges: Vec<f64> = (0..k).map(|_| uniform(rng)).collect();
            edges.sort_by(f64::total_cmp);
            Ok(Box::new(Visibility { edges, start: 0.0 }))
        },
    },
];

/// A parsed integrand family: its entry and resolved parameters.
///
/// ```
/// use samplab::Seed;
/// use samplab::integrand::Family;
/// let disks = Family::parse("disk:r=0.25").unwrap();
/// let f = disks.instance(Seed(3), 0).unwrap(); // instance 0: a random centre
/// assert!((f.exact() - std::f64::consts::PI / 16.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct Family {
    /// The registry entry.
    pub entry: &'static IntegrandEntry,
    params: Params,
}

impl Family {
    /// Parse `quad`, `disk:r=0.2`, `steps:k=5`, ...
    ///
    /// # Errors
    /// An unknown name (with suggestions) or bad parameters.
    pub fn parse(text: &str) -> Result<Family> {
        let (entry, params) = INTEGRANDS.resolve(text)?;
        Ok(Family { entry, params })
    }

    /// The canonical spec.
    pub fn spec(&self) -> String {
        canonical(&self.entry.about, &self.params)
    }

    /// The dimensions of its integrands.
    pub fn dims(&self) -> usize {
        match self.entry.dims {
            Dims::Fixed(d) => d,
            Dims::Param => self.params.int("d") as usize,
        }
    }

    /// Instance `k` of the family for `seed`.
    ///
    /// # Errors
    /// Parameters that make an impossible instance (e.g. a disk leaving the square).
    pub fn instance(&self, seed: Seed, k: u64) -> Result<Box<dyn Integrand>> {
        (self.entry.build)(&self.params, &mut seed.derive(k).rng())
    }
}
