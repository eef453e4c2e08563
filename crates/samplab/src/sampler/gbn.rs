//! Gaussian blue noise (after Ahmed, Ren & Wonka 2022): uniform random points on the torus
//! moved by gradient descent on the Gaussian pair energy
//!
//!   E = sum_(i < j) exp(-|x_i - x_j|^2 / (2 sigma^2)),
//!
//! sigma = `sigma` x the mean spacing n^(-1/d). Each iteration moves every point by
//! `step` sigma^2 times the negative gradient, sum_j (x_i - x_j) / sigma^2 exp(...): with
//! `step` below one a point moves by less than its neighbours' pull allows, and the energy
//! falls. Pairs farther than 5 sigma (weight below 4e-6) are left out, found through the
//! grid of [`crate::spatial`]; every point's move is a sum in a fixed order, so the result
//! does not depend on the thread count.
//!
//! The same energy drives `kdm`, Fattal's (2011) kernel density model: points whose sum of
//! Gaussian kernels K (standard deviation sigma_K) should equal the uniform density, with
//! energy int (sum_i K(x - x_i) - rho)^2 dx. On the torus the cross terms with the uniform rho
//! are constant, so up to a constant and a factor this is the pair energy above with sigma =
//! sqrt(2) sigma_K (K * K is a Gaussian of twice the variance). Fattal draws point sets
//! from the Gibbs distribution exp(-E / T) by Langevin steps at temperature T: each step
//! moves the points down the gradient, as here, and adds independent normal noise of
//! variance 2 tau per coordinate, tau = `step` sigma^2 T the step's time (T = 0 is plain
//! descent; large T, white noise); the last step adds none. Fattal avoids the slow relaxation
//! of long wavelengths by a multi-scale scheme; samplab starts instead from a sample-elimination
//! set (Yuksel 2015), whose long wavelengths are already settled. The noise is drawn per step
//! from the seed in point order, so the result does not depend on the thread count.

use std::ops::RangeInclusive;

use rayon::prelude::*;

use super::elimination::SETTLED;
use super::random::Random;
use super::registry::{ANY, SamplerEntry};
use super::{Fill, Sampler};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Rng, Seed, normal, wrap01};
use crate::spatial::{Grid, distance2, torus_gap};
use crate::spec::{Default, Kind, ParamSpec};

/// Gaussian blue noise by gradient descent.
#[derive(Debug, Clone, Copy)]
pub struct Gbn {
    iterations: usize,
    sigma: f64,
    step: f64,
}

/// The kernel's reach, in sigmas.
const CUT: f64 = 5.0;

/// The Gaussian pair energy of `points` on the torus with kernel width `sigma`, pairs
/// within 5 sigma.
pub fn energy(points: &[f64], dims: usize, sigma: f64) -> f64 {
    let grid = Grid::covering(points, dims, CUT * sigma);
    let per_point: Vec<f64> = (0..grid.len())
        .into_par_iter()
        .map(|q| {
            let mut e = 0.0;
            grid.near(q, 1, true, |cell| {
                for r in cell.filter(|&r| r > q) {
                    let d2 = distance2(grid.point(q), grid.point(r), true);
                    if d2 < (CUT * sigma).powi(2) {
                        e += (-d2 / (2.0 * sigma * sigma)).exp();
                    }
                }
            });
            e
        })
        .collect();
    per_point.iter().sum()
}

/// One descent step: every point moved by `step` sigma^2 times the energy's negative
/// gradient, on the torus.
pub fn descend(points: &mut [f64], dims: usize, sigma: f64, step: f64) {
    let grid = Grid::covering(points, dims, CUT * sigma);
    let moves: Vec<(u32, Vec<f64>)> = (0..grid.len())
        .into_par_iter()
        .map(|q| {
            let p = grid.point(q);
            let mut push = vec![0.0; dims];
            grid.near(q, 1, true, |cell| {
                for r in cell.filter(|&r| r != q) {
                    let o = grid.point(r);
                    let d2 = distance2(p, o, true);
                    if d2 < (CUT * sigma).powi(2) {
                        let w = (-d2 / (2.0 * sigma * sigma)).exp();
                        for ((m, &x), &y) in push.iter_mut().zip(p).zip(o) {
                            *m += step * torus_gap(x, y) * w;
                        }
                    }
                }
            });
            (grid.ids[q], push)
        })
        .collect();
    for (i, push) in moves {
        for (x, m) in points[i as usize * dims..(i as usize + 1) * dims].iter_mut().zip(push) {
            *x = wrap01(*x + m);
        }
    }
}

/// One Langevin step at temperature `temperature` (module doc): [`descend`], then normal
/// noise of standard deviation sqrt(2 `step` `temperature`) sigma per coordinate, drawn from
/// `rng` in point order.
pub fn langevin(points: &mut [f64], dims: usize, sigma: f64, step: f64, temperature: f64, rng: &mut Rng) {
    descend(points, dims, sigma, step);
    let spread = (2.0 * step * temperature).sqrt() * sigma;
    for x in points.iter_mut() {
        *x = wrap01(*x + spread * normal(rng));
    }
}

impl Sampler for Gbn {
    fn spec(&self) -> String {
        format!("gbn:iterations={},sigma={},step={}", self.iterations, self.sigma, self.step)
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }
}

impl Fill for Gbn {
    fn units(&self) -> u64 {
        self.iterations as u64
    }
    fn fill_reporting(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        Random.fill(n, dims, seed, out)?;
        let sigma = self.sigma * (n as f64).powf(-1.0 / dims as f64);
        for _ in 0..self.iterations {
            descend(out, dims, sigma, self.step);
            progress.advance(1)?;
        }
        Ok(())
    }
}

/// Fattal's kernel density model sampled by Langevin steps (module doc).
#[derive(Debug, Clone, Copy)]
pub struct Kdm {
    iterations: usize,
    sigma: f64,
    temperature: f64,
    step: f64,
}

impl Sampler for Kdm {
    fn spec(&self) -> String {
        format!(
            "kdm:iterations={},sigma={},temperature={},step={}",
            self.iterations, self.sigma, self.temperature, self.step
        )
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }
}

impl Fill for Kdm {
    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        SETTLED.check_count(n, dims)
    }
    fn units(&self) -> u64 {
        self.iterations as u64
    }
    fn fill_reporting(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        SETTLED.fill(n, dims, seed, out)?;
        // the pair energy's width: sqrt(2) times the kernel's
        let sigma = std::f64::consts::SQRT_2 * self.sigma * (n as f64).powf(-1.0 / dims as f64);
        let mut rng = seed.derive_str("kdm noise").rng();
        for it in 0..self.iterations {
            let t = if it + 1 < self.iterations { self.temperature } else { 0.0 };
            langevin(out, dims, sigma, self.step, t, &mut rng);
            progress.advance(1)?;
        }
        Ok(())
    }
}

const STEP: ParamSpec = ParamSpec {
    name: "step",
    kind: Kind::Real { min: 1e-4, max: 1.0 },
    default: Default::Number(0.5),
    doc: "each move, in units of sigma^2 times the gradient",
};

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("gbn", "Gaussian blue noise: gradient descent on a Gaussian pair energy, on the torus")
        .aliases(&["gaussian-blue-noise"])
        .params(&[
            ParamSpec {
                name: "iterations",
                kind: Kind::Int { min: 0, max: 1_000_000 },
                default: Default::Int(100),
                doc: "descent steps",
            },
            ParamSpec {
                name: "sigma",
                kind: Kind::Real { min: 0.05, max: 4.0 },
                default: Default::Number(0.5),
                doc: "the kernel's width, in units of the mean spacing n^(-1/d)",
            },
            STEP,
        ])
        .cite(&["ahmed2022"]),
    counts: ANY,
    dims: "1..=4",
    build: |p| Ok(Box::new(Gbn { iterations: p.int("iterations") as usize, sigma: p.real("sigma"), step: p.real("step") })),
},
SamplerEntry {
    about: About::new("kdm", "Fattal's kernel density model: Langevin steps on the Gaussian pair energy at a temperature, on the torus")
        .aliases(&["fattal"])
        .params(&[
            ParamSpec {
                name: "iterations",
                kind: Kind::Int { min: 1, max: 1_000_000 },
                default: Default::Int(100),
                doc: "Langevin steps (the last without noise)",
            },
            ParamSpec {
                name: "sigma",
                kind: Kind::Real { min: 0.05, max: 4.0 },
                default: Default::Number(0.35),
                doc: "the kernels' width, in units of the mean spacing n^(-1/d)",
            },
            ParamSpec {
                name: "temperature",
                kind: Kind::Real { min: 0.0, max: 100.0 },
                default: Default::Number(0.02),
                doc: "the Gibbs distribution's temperature, in units of the pair energy at distance 0",
            },
            STEP,
        ])
        .cite(&["fattal2011", "yuksel2015"]),
    counts: ANY,
    dims: "1..=4",
    build: |p| {
        Ok(Box::new(Kdm {
            iterations: p.int("iterations") as usize,
            sigma: p.real("sigma"),
            temperature: p.real("temperature"),
            step: p.real("step"),
        }))
    },
}];
