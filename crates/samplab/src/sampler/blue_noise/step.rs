//! Step and single-peak blue noise (Heck, Schlömer & Deussen 2013): 2D point sets on the
//! torus whose radial power spectrum follows a target, reached through the pair correlation
//! function (PCF) the target implies.
//!
//! ## Targets
//!
//! Frequencies a are in units of sqrt(n) and distances rho in units of 1/sqrt(n), so a
//! target does not depend on n. For a radial power spectrum P (P = 1 for white noise), the
//! PCF follows by the 2D Hankel transform (Heck et al. section 4):
//!
//!   g(rho) - 1 = 2 pi int_0^inf (P(a) - 1) J0(2 pi a rho) a da.
//!
//! - **step**: P(a) = H(a - nu), zero below nu and 1 above, in closed form
//!   g(rho) = 1 - nu J1(2 pi nu rho) / rho. g(0) = 1 - pi nu^2, so a step is
//!   realizable (g >= 0) up to nu = 1/sqrt(pi) = 0.564, where the effective Nyquist frequency
//!   (the `nyquist` metric, [`crate::spectrum::aliasing`]) is nu.
//! - **single-peak**: the step smoothed by a Gaussian of standard deviation `width` plus a
//!   Gaussian peak of that width and area `power` at nu: P(a) = Phi((a - nu) / width) +
//!   power phi_width(a - nu); its g in closed form below nu - 8 width (where P = 0 to 1e-15)
//!   and by quadrature (16 panels of Gauss-Legendre) on the 16 widths around nu. A step beyond 0.564 makes g negative near 0; the peak lifts it,
//!   and with `power` = auto the smallest power keeping g >= 0 at every rho in [0, 12] (in
//!   steps of 0.02) is used (g is linear in the power, so that power is a maximum of ratios).
//!   Targets with g < 0 somewhere are refused: a PCF is never negative.
//!
//! ## Matching
//!
//! From a sample-elimination set (Yuksel 2015, 5n candidates: [`super::elimination`]),
//! gradient descent on
//!
//!   E = sum_m (g_hat(r_m) - g_t(r_m))^2 dr,
//!
//! g_hat the Gaussian-kernel PCF estimate of the points ([`crate::spatial::pcf`], kernel
//! `sigma`), at radii r_m from sigma to `reach` in steps dr = sigma / 2, and g_t the target
//! smoothed by the same kernel (the estimator's expectation for a process of PCF g, so
//! the kernel's blur is not fought). Pair distances are binned linearly on nodes sigma / 32
//! apart (a pair's weight split between its two nodes) and the kernel applied node by node,
//! so dE/dd is a step function known exactly from the nodes' sensitivities; each point moves
//! against sum_j dE/dd(d_ij) (x_i - x_j) / d_ij, the exact gradient of E as computed. A step that does not lower E
//! is undone and the step size halved, an accepted one grows it by 1/4, so E falls
//! monotonically. Heck et al. match the target by moving points with a force derived from the
//! difference of the PCFs; samplab descends the exact gradient of the smoothed mismatch, and
//! pairs beyond `reach` + 5 sigma are left out (through the grid of [`crate::spatial`]), so an
//! iteration costs O(n) rather than O(n^2). Sums run in a fixed order: the result does not
//! depend on the thread count.
//!
//! The start matters: matching the PCF within a few spacings barely moves wavelengths of
//! many spacings, so from uniform random points the lowest frequencies keep most of their
//! power (measured at n = 1024, 8 sets: 0.8 of white noise's at |k| = 1), while from
//! sample elimination, whose low frequencies are already suppressed, they end at 0.08.

use std::f64::consts::{PI, TAU};
use std::ops::RangeInclusive;


use super::elimination::SETTLED;
use crate::construct::counts::ANY;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction};
use crate::error::{Error, Result};
use crate::numeric::quadrature::gauss_legendre;
use crate::progress::Progress;
use crate::numeric::normal_cdf;
use crate::registry::About;
use crate::seed::wrap01;
use crate::spatial::{self, Grid, torus_gap};
use crate::spec::{Default, Kind, ParamSpec, Params, Value};
use rayon::prelude::*;

/// A target radial power spectrum (frequencies in units of sqrt(n)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Shape {
    /// P = 0 below `nu`, 1 above.
    Step {
        /// The step's frequency.
        nu: f64,
    },
    /// A Gaussian-smoothed step at `nu` with a Gaussian peak of area `power` there.
    Peak {
        /// The step's and the peak's frequency.
        nu: f64,
        /// The Gaussian's standard deviation.
        width: f64,
        /// The peak's area.
        power: f64,
    },
}

/// 2 pi int_from^to f(a) J0(2 pi a rho) a da, by 16 panels of Gauss-Legendre.
pub fn hankel(f: impl Fn(f64) -> f64, from: f64, to: f64, rho: f64) -> f64 {
    TAU * gauss_legendre(|a| f(a) * libm::j0(TAU * a * rho) * a, from, to, 16)
}

/// The transform of the disk indicator: 2 pi int_0^a J0(2 pi a' rho) a' da' = a J1(2 pi a rho)
/// / rho (pi a^2 at rho = 0).
pub fn disk(a: f64, rho: f64) -> f64 {
    let z = TAU * a * rho;
    if z < 1e-8 { PI * a * a } else { a * libm::j1(z) / rho }
}

fn normal_pdf(x: f64, width: f64) -> f64 {
    (-0.5 * (x / width).powi(2)).exp() / (width * TAU.sqrt())
}

impl Shape {
    /// g - 1 of the smoothed step (no peak) and of a unit peak: below nu - 8 width the smoothed
    /// step's P - 1 is -1 (to 1e-15), in closed form; the rest by quadrature.
    fn parts(nu: f64, width: f64, rho: f64) -> (f64, f64) {
        let (from, to) = ((nu - 8.0 * width).max(0.0), nu + 8.0 * width);
        (
            -disk(from, rho) + hankel(|a| normal_cdf((a - nu) / width) - 1.0, from, to, rho),
            hankel(|a| normal_pdf(a - nu, width), from, to, rho),
        )
    }

    /// The target PCF g at rho (in units of 1/sqrt(n)).
    pub fn pcf(&self, rho: f64) -> f64 {
        match *self {
            Shape::Step { nu } => 1.0 - disk(nu, rho),
            Shape::Peak { nu, width, power } => {
                let (step, peak) = Shape::parts(nu, width, rho);
                1.0 + step + power * peak
            }
        }
    }

    /// The smallest peak power that keeps g >= 0 on rho in [0, 12], or None when no power
    /// does (the quadratures at the 601 radii in parallel, then taken in order).
    pub fn least_power(nu: f64, width: f64) -> Option<f64> {
        let (mut low, mut high) = (0.0f64, f64::INFINITY);
        let parts: Vec<(f64, f64)> = RADII.into_par_iter().map(|i| Shape::parts(nu, width, rho(i))).collect();
        for (step, peak) in parts {
            let base = 1.0 + step;
            if peak > 1e-12 {
                low = low.max(-base / peak);
            } else if peak < -1e-12 {
                high = high.min(base / -peak);
            } else if base < -1e-9 {
                return None;
            }
        }
        (low <= high).then_some(low)
    }

    /// The first rho in [0, 12] (steps of 0.02) where g < -1e-9, if any.
    fn negative_at(&self) -> Option<f64> {
        RADII.into_par_iter().map(rho).find_first(|&rho| self.pcf(rho) < -1e-9)
    }
}

/// The radii at which a target PCF is checked: rho(i) = 0.02 i, i in `RADII`.
const RADII: RangeInclusive<u32> = 0..=600;

fn rho(i: u32) -> f64 {
    f64::from(i) * 0.02
}

/// Points matched to a target PCF by gradient descent.
#[derive(Debug, Clone, Copy)]
pub struct Matched {
    shape: Shape,
    iterations: usize,
    sigma: f64,
    reach: f64,
}

/// Cells per pair reach of the grid the pairs are found through.
const RING: usize = 2;

/// Histogram nodes per kernel width sigma (the radii lie every 16 nodes, from node 32).
const NODES: usize = 32;

/// The descent's setting: the radii, the smoothed target there, and the kernel on the
/// histogram's nodes.
struct Matching {
    n: usize,
    sigma: f64,
    radii: Vec<f64>,
    target: Vec<f64>,
    /// exp(-(j / NODES)^2) for node offsets j in -5 NODES..=5 NODES (index j + 5 NODES).
    kernel: Vec<f64>,
}

/// Pair distances of a set, linearly binned on nodes sigma / 32 apart, with the grid the
/// set was binned through (which the gradient reuses).
struct Measured {
    grid: Grid,
    estimate: Vec<f64>,
}

impl Matching {
    fn new(shape: Shape, n: usize, sigma: f64, reach: f64) -> Matching {
        let s = 1.0 / (n as f64).sqrt();
        let sigma = sigma * s;
        let last = (reach * s).min(0.5 - 5.0 * sigma);
        let radii: Vec<f64> = (0..)
            .map(|m| Matching::radius_node(m) as f64 * sigma / NODES as f64)
            .take_while(|&r| r <= last)
            .collect();
        // the target smoothed by the estimator's kernel: int g(t) k(r - t) t / r dt (each
        // radius's quadratures, of the target's own, on a thread of their own)
        let target = radii
            .par_iter()
            .map(|&r| {
                let (from, to) = ((r - 5.0 * sigma).max(0.0), r + 5.0 * sigma);
                let smoothed = |t: f64| shape.pcf(t / s) * (-((r - t) / sigma).powi(2)).exp() * t;
                gauss_legendre(smoothed, from, to, 4) / (PI.sqrt() * sigma * r)
            })
            .collect();
        let kernel = (0..=10 * NODES).map(|j| (-((j as f64 - 5.0 * NODES as f64) / NODES as f64).powi(2)).exp()).collect();
        Matching { n, sigma, radii, target, kernel }
    }

    /// The histogram's node spacing.
    fn node(&self) -> f64 {
        self.sigma / NODES as f64
    }

    /// The node of radius m.
    fn radius_node(m: usize) -> usize {
        NODES + m * NODES / 2
    }

    /// The farthest pair that matters.
    fn cut(&self) -> f64 {
        self.radii.last().copied().unwrap_or(0.0) + 5.0 * self.sigma
    }

    /// The kernel estimate of the PCF at the radii, from pair distances linearly binned on
    /// the nodes (each pair split between its two nodes).
    fn measure(&self, points: &[f64]) -> Measured {
        let (cut, h) = (self.cut(), self.node());
        let bins = (cut / h) as usize + 2;
        let grid = Grid::within(points, 2, cut, RING);
        let parts = spatial::pairs(
            &grid,
            RING,
            true,
            || vec![0.0; bins],
            |acc, d2| {
                if d2 < cut * cut {
                    let x = d2.sqrt() / h;
                    let i = x as usize;
                    let f = x - i as f64;
                    acc[i] += 1.0 - f;
                    acc[i + 1] += f;
                }
            },
        );
        let mut hist = vec![0.0; bins];
        for part in &parts {
            for (a, b) in hist.iter_mut().zip(part) {
                *a += b;
            }
        }
        // each unordered pair stands for two ordered ones
        let n = self.n as f64;
        let norm = 2.0 / (n * (n - 1.0) * TAU * PI.sqrt() * self.sigma);
        let reach = 5 * NODES;
        let estimate = (0..self.radii.len())
            .map(|m| {
                let c = Matching::radius_node(m);
                let sum: f64 = (c.saturating_sub(reach)..=(c + reach).min(bins - 1)).map(|b| hist[b] * self.kernel[b + reach - c]).sum();
                sum * norm / self.radii[m]
            })
            .collect();
        Measured { grid, estimate }
    }

    /// E for an estimate.
    fn energy(&self, estimate: &[f64]) -> f64 {
        estimate.iter().zip(&self.target).map(|(g, t)| (g - t) * (g - t)).sum::<f64>() * self.sigma / 2.0
    }

    /// dE/dw_b for the weight w_b each node's histogram count carries, for an estimate: a
    /// pair at d between nodes i and i + 1 puts 1 - f on node i and f = d / h - i on node
    /// i + 1, so dE/dd = (T_(i+1) - T_i) / h exactly (the energy is piecewise smooth in d).
    fn table(&self, estimate: &[f64]) -> Vec<f64> {
        let n = self.n as f64;
        let dr = self.sigma / 2.0;
        // a unit of node weight adds 2 k(r - b h) / (n (n - 1) 2 pi r) to g_hat(r)
        let norm = 2.0 / (n * (n - 1.0) * TAU * PI.sqrt() * self.sigma);
        let (bins, reach) = ((self.cut() / self.node()) as usize + 2, 5 * NODES);
        let mut table = vec![0.0; bins];
        for (m, ((g, t), r)) in estimate.iter().zip(&self.target).zip(&self.radii).enumerate() {
            let c = 2.0 * (g - t) * dr * norm / r;
            let centre = Matching::radius_node(m);
            let from = centre.saturating_sub(reach);
            let to = (centre + reach).min(bins - 1);
            for (t, k) in table[from..=to].iter_mut().zip(&self.kernel[from + reach - centre..]) {
                *t += c * k;
            }
        }
        table
    }

    /// The gradient of E with respect to every coordinate (in input order), for the table,
    /// over the pairs of the measured set: each pair once, its push added to both points,
    /// in 16 fixed chunks of points whose sums are added in order.
    fn gradient(&self, measured: &Measured, table: &[f64]) -> Vec<f64> {
        let (cut, h, grid) = (self.cut(), self.node(), &measured.grid);
        let n = grid.len();
        let parts = spatial::indexed_pairs(
            grid,
            RING,
            true,
            n.div_ceil(16),
            || vec![0.0; 2 * n],
            |acc, q, r, d2| {
                if d2 >= cut * cut || d2 == 0.0 {
                    return;
                }
                let d = d2.sqrt();
                let i = (d / h) as usize;
                let slope = (table[i + 1] - table[i]) / (h * d);
                let (p, o) = (grid.point(q), grid.point(r));
                for k in 0..2 {
                    let push = slope * torus_gap(p[k], o[k]);
                    acc[2 * q + k] += push;
                    acc[2 * r + k] -= push;
                }
            },
        );
        let mut sum = vec![0.0; 2 * n];
        for part in &parts {
            for (s, x) in sum.iter_mut().zip(part) {
                *s += x;
            }
        }
        let mut out = vec![0.0; 2 * n];
        for (q, &i) in grid.ids.iter().enumerate() {
            out[2 * i as usize..2 * i as usize + 2].copy_from_slice(&sum[2 * q..2 * q + 2]);
        }
        out
    }
}

impl Matched {
    /// The descent from `points` (the `m.n` points of one set) for `iterations` steps,
    /// advancing `progress` by one per step; returns E before and after.
    fn descend(&self, m: &Matching, points: &mut [f64], progress: &Progress) -> Result<(f64, f64)> {
        let n = m.n;
        let mut current = m.measure(points);
        let first = m.energy(&current.estimate);
        let mut energy = first;
        let mut gradient = m.gradient(&current, &m.table(&current.estimate));
        // the first step moves the most-pushed point by a tenth of the mean spacing
        let largest = gradient.chunks_exact(2).map(|g| g[0].hypot(g[1])).fold(0.0, f64::max);
        if largest == 0.0 {
            progress.advance(self.units())?;
            return Ok((first, energy));
        }
        let mut eta = 0.1 / (n as f64).sqrt() / largest;
        let mut trial = points.to_vec();
        for _ in 0..self.iterations {
            for ((t, &x), &g) in trial.iter_mut().zip(points.iter()).zip(&gradient) {
                *t = wrap01(x - eta * g);
            }
            let next = m.measure(&trial);
            let e = m.energy(&next.estimate);
            if e < energy {
                points.copy_from_slice(&trial);
                (current, energy) = (next, e);
                gradient = m.gradient(&current, &m.table(&current.estimate));
                eta *= 1.25;
            } else {
                eta *= 0.5;
            }
            progress.advance(1)?;
        }
        Ok((first, energy))
    }
}

impl Construction for Matched {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn check_count(&self, shape: &crate::sampler::Shape) -> Result<()> {
        SETTLED.check_count(shape)
    }

    /// The smoothed target (thousands of quadratures of the target PCF) is computed here,
    /// once for every set of the shape.
    fn prepare(&self, shape: &crate::sampler::Shape) -> Result<Box<dyn Prepared>> {
        let (n, dims) = (shape.n(), shape.dims());
        let matching = (n >= 2).then(|| Matching::new(self.shape, n, self.sigma, self.reach));
        let me = *self;
        Ok(crate::sampler::from_fill_reporting(self.units(), move |seed, out, progress| {
            SETTLED.fill(n, dims, seed, out)?;
            match &matching {
                Some(m) => me.descend(m, out, progress).map(drop),
                None => progress.advance(me.units()),
            }
        }))
    }
}

impl Matched {
    fn units(&self) -> u64 {
        self.iterations as u64
    }
}

const ITERATIONS: ParamSpec = ParamSpec {
    name: "iterations",
    kind: Kind::Int { min: 0, max: 1_000_000 },
    default: Default::Int(100),
    doc: "descent steps",
};

const SIGMA: ParamSpec = ParamSpec {
    name: "sigma",
    kind: Kind::Real { min: 0.02, max: 1.0 },
    default: Default::Number(0.1),
    doc: "the PCF estimator's kernel width, in units of the mean spacing 1/sqrt(n)",
};

const REACH: ParamSpec = ParamSpec {
    name: "reach",
    kind: Kind::Real { min: 1.0, max: 50.0 },
    default: Default::Number(6.0),
    doc: "the largest distance matched, in units of 1/sqrt(n) (at most 1/2 - 5 sigma in absolute terms)",
};

fn build(owner: &str, shape: Shape, p: &Params) -> Result<Box<dyn Construction>> {
    if let Some(rho) = shape.negative_at() {
        return Err(Error::Param {
            owner: owner.into(),
            param: "nu".into(),
            reason: format!("the target is not realizable: its PCF is negative at {rho} / sqrt(n)"),
        });
    }
    Ok(Box::new(Matched {
        shape,
        iterations: p.int("iterations") as usize,
        sigma: p.real("sigma"),
        reach: p.real("reach"),
    }))
}

fn build_peak(p: &mut Params) -> Result<Box<dyn Construction>> {
    let (nu, width) = (p.real("nu"), p.real("width"));
    let power = match p.real_or_auto("power") {
        Some(power) => power,
        None => Shape::least_power(nu, width).ok_or_else(|| Error::Param {
            owner: "single-peak".into(),
            param: "nu".into(),
            reason: format!("no peak power makes the PCF of a step at {nu} of width {width} non-negative"),
        })?,
    };
    // the spec names the power chosen
    p.set("power", Value::Number(power));
    build("single-peak", Shape::Peak { nu, width, power }, p)
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("step", "step blue noise: the PCF of a step spectrum matched by gradient descent (2D torus)")
            .params(&[
                ParamSpec {
                    name: "nu",
                    kind: Kind::Real { min: 0.05, max: 0.5641 },
                    default: Default::Number(0.564),
                    doc: "the step's frequency in units of sqrt(n) (realizable up to 1/sqrt(pi) = 0.5642)",
                },
                ITERATIONS,
                SIGMA,
                REACH,
            ])
            .cite(&["heck2013"]),
        counts: ANY,
        randomized: true,
        dims: "2",
        build: |p| build("step", Shape::Step { nu: p.real("nu") }, p),
    },
    SamplerEntry {
        about: About::new("single-peak", "single-peak blue noise: a smoothed step spectrum with one peak, matched through its PCF (2D torus)")
            .aliases(&["singlepeak"])
            .params(&[
                ParamSpec {
                    name: "nu",
                    kind: Kind::Real { min: 0.05, max: 2.0 },
                    default: Default::Number(0.8),
                    doc: "the step's and peak's frequency in units of sqrt(n)",
                },
                ParamSpec {
                    name: "width",
                    kind: Kind::Real { min: 0.005, max: 0.5 },
                    default: Default::Number(0.025),
                    doc: "the Gaussian's standard deviation, in units of sqrt(n)",
                },
                ParamSpec {
                    name: "power",
                    kind: Kind::Real { min: 0.0, max: 100.0 },
                    default: Default::Auto("the least that keeps the target PCF non-negative"),
                    doc: "the peak's area, in units of sqrt(n)",
                },
                ITERATIONS,
                SIGMA,
                REACH,
            ])
            .cite(&["heck2013"]),
        counts: ANY,
        randomized: true,
        dims: "2",
        build: build_peak,
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampler::random::Random;
    use crate::seed::Seed;

    #[test]
    fn the_step_pcf_is_the_hankel_transform_of_the_step() {
        // the closed form against the quadrature of P - 1 = -1 on [0, nu]
        let nu = 0.5;
        for rho in [0.0, 0.3, 0.9, 1.7, 3.1, 5.0] {
            let quadrature = 1.0 + hankel(|_| -1.0, 0.0, nu, rho);
            let closed = Shape::Step { nu }.pcf(rho);
            assert!((quadrature - closed).abs() < 1e-7, "rho {rho}: {quadrature} vs {closed}");
        }
        // g(0) = 1 - pi nu^2: the largest realizable step is 1/sqrt(pi)
        assert!(Shape::Step { nu: 0.5641 }.negative_at().is_none());
        assert_eq!(Shape::Step { nu: 0.5643 }.negative_at(), Some(0.0));
    }

    #[test]
    fn the_least_peak_power_is_the_realizability_edge() {
        let (nu, width) = (0.8, 0.025);
        let power = Shape::least_power(nu, width).unwrap();
        assert!(Shape::Peak { nu, width, power }.negative_at().is_none());
        assert!(Shape::Peak { nu, width, power: 0.98 * power }.negative_at().is_some());
        // with no peak, a step this high is not realizable, and a low one needs no peak
        assert!(Shape::Peak { nu, width, power: 0.0 }.negative_at().is_some());
        assert_eq!(Shape::least_power(0.4, width), Some(0.0));
        let err = crate::sampler::build("single-peak:power=0.1").unwrap_err().to_string();
        assert!(err.contains("not realizable"), "{err}");
    }

    /// The gradient against central differences at every coordinate whose two moves stay on
    /// one smooth piece of the energy. The energy bins each pair's distance linearly on
    /// nodes sigma / 32 apart, so it is smooth between nodes and its slope jumps where a
    /// distance crosses one (or the cut); a central difference straddling such a kink
    /// averages two slopes, and at h = 1e-6 about 9% of the coordinates straddle one (1133
    /// of 12800 over seeds 0-99, 2026-12-06: checking 4 fixed coordinates, as this test
    /// did, failed for about a third of the seeds). Failure probability: none for a correct
    /// gradient (an identity on each piece: over seeds 0-99 no coordinate on one piece missed
    /// it; the points only make the case generic). Least work: one set of 64 points, all 128
    /// coordinates, at least half of them on one piece.
    #[test]
    fn the_gradient_is_the_energy_s_derivative() {
        let n = 64;
        let mut points = vec![0.0; 2 * n];
        Random::draw(Seed(5), &mut points);
        let m = Matching::new(Shape::Step { nu: 0.5 }, n, 0.1, 3.0);
        let energy = |p: &[f64]| m.energy(&m.measure(p).estimate);
        let measured = m.measure(&points);
        let gradient = m.gradient(&measured, &m.table(&measured.estimate));
        let scale = gradient.iter().fold(0.0f64, |a, g| a.max(g.abs()));
        // the smooth piece a set lies on: every pair's node interval, or none past the cut
        let piece = |p: &[f64]| -> Vec<Option<usize>> {
            (0..n)
                .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
                .map(|(a, b)| {
                    let d = torus_gap(p[2 * a], p[2 * b]).hypot(torus_gap(p[2 * a + 1], p[2 * b + 1]));
                    (d < m.cut()).then(|| (d / m.node()) as usize)
                })
                .collect()
        };
        let h = 1e-6;
        let mut checked = 0;
        for c in 0..2 * n {
            let (mut up, mut down) = (points.clone(), points.clone());
            up[c] += h;
            down[c] -= h;
            if piece(&up) != piece(&down) {
                continue;
            }
            checked += 1;
            let numeric = (energy(&up) - energy(&down)) / (2.0 * h);
            assert!((numeric - gradient[c]).abs() < 1e-6 * scale, "coordinate {c}: {numeric} vs {}", gradient[c]);
        }
        // (98-128 of 128 over seeds 0-99)
        assert!(checked >= n, "only {checked} of {} coordinates on one piece", 2 * n);
    }

    /// Failure probability not computed in closed form: over seeds 0-39 the descent ended at
    /// 0.009-0.026 of its starting mismatch (2026-12-06) against a criterion of 0.05, twice
    /// the worst. Fixed seed. Least work: 256 points and 100 iterations, a fraction of a second.
    #[test]
    fn the_descent_lowers_the_mismatch() {
        let n = 256;
        let mut points = vec![0.0; 2 * n];
        Random::draw(Seed(9), &mut points);
        let heck = Matched { shape: Shape::Step { nu: 0.55 }, iterations: 100, sigma: 0.1, reach: 6.0 };
        let matching = Matching::new(heck.shape, n, heck.sigma, heck.reach);
        let (first, last) = heck.descend(&matching, &mut points, &Progress::SILENT).unwrap();
        assert!(last < 0.05 * first, "{first} -> {last}");
    }
}
