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
//! The same energy drives [`super::kdm`], Fattal's kernel density model.

use std::ops::RangeInclusive;

use rayon::prelude::*;

use crate::sampler::random::Random;
use crate::construct::counts::ANY;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction, Shape};
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
///
/// # Panics
/// `dims` outside 1..=4 (the samplers' dimensions).
pub fn descend(points: &mut [f64], dims: usize, sigma: f64, step: f64) {
    match dims {
        1 => descend_in::<1>(points, sigma, step),
        2 => descend_in::<2>(points, sigma, step),
        3 => descend_in::<3>(points, sigma, step),
        4 => descend_in::<4>(points, sigma, step),
        _ => panic!("a descent in {dims} dimensions: 1 to 4 are made"),
    }
}

/// [`descend`] in D dimensions (so that the distances and moves unroll).
fn descend_in<const D: usize>(points: &mut [f64], sigma: f64, step: f64) {
    let grid = Grid::covering(points, D, CUT * sigma);
    let at = |q: usize| -> &[f64; D] { grid.point(q).try_into().expect("D coordinates") };
    let moves: Vec<(u32, [f64; D])> = (0..grid.len())
        .into_par_iter()
        .map(|q| {
            let p = at(q);
            let mut push = [0.0; D];
            grid.near(q, 1, true, |cell| {
                for r in cell.filter(|&r| r != q) {
                    let o = at(r);
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
        for (x, m) in points[i as usize * D..(i as usize + 1) * D].iter_mut().zip(push) {
            *x = wrap01(*x + m);
        }
    }
}

/// One Langevin step at temperature `temperature` (module doc): [`descend`], then normal
/// noise of standard deviation sqrt(2 `step` `temperature`) sigma per coordinate, drawn from
/// `rng` in point order.
///
/// # Panics
/// As [`descend`].
pub fn langevin(points: &mut [f64], dims: usize, sigma: f64, step: f64, temperature: f64, rng: &mut Rng) {
    descend(points, dims, sigma, step);
    let spread = (2.0 * step * temperature).sqrt() * sigma;
    for x in points.iter_mut() {
        *x = wrap01(*x + spread * normal(rng));
    }
}

impl Construction for Gbn {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(self.units(), move |seed, out, progress| {
            me.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
        }))
    }
}

impl Gbn {
    fn units(&self) -> u64 {
        self.iterations as u64
    }
    fn fill_reporting(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        Random::draw(seed, out);
        let sigma = self.sigma * (n as f64).powf(-1.0 / dims as f64);
        for _ in 0..self.iterations {
            descend(out, dims, sigma, self.step);
            progress.advance(1)?;
        }
        Ok(())
    }
}

/// The step of the descent (and of `kdm`'s Langevin steps).
pub(crate) const STEP: ParamSpec = ParamSpec {
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
    randomized: true,
    dims: "1..=4",
    build: |p| Ok(Box::new(Gbn { iterations: p.int("iterations") as usize, sigma: p.real("sigma"), step: p.real("step") })),
}];

