//! Fattal's (2011) kernel density model, on the pair energy of [`super::gbn`]: points whose sum of
//! Gaussian kernels K (standard deviation sigma_K) should equal the uniform density, with
//! energy int (sum_i K(x - x_i) - rho)^2 dx. On the torus the cross terms with the uniform rho
//! are constant, so up to a constant and a factor this is gbn's pair energy with sigma =
//! sqrt(2) sigma_K (K * K is a Gaussian of twice the variance). Fattal draws point sets
//! from the Gibbs distribution exp(-E / T) by Langevin steps at temperature T: each step
//! moves the points down the gradient, as here, and adds independent normal noise of
//! variance 2 tau per coordinate, tau = `step` sigma^2 T the step's time (T = 0 is plain
//! descent; large T, white noise); the last step adds none. Fattal avoids the slow relaxation
//! of long wavelengths by a multi-scale scheme; samplab starts instead from a sample-elimination
//! set (Yuksel 2015), whose long wavelengths are already settled. The noise is drawn per step
//! from the seed in point order, so the result does not depend on the thread count.

use std::ops::RangeInclusive;

use super::elimination::SETTLED;
use super::gbn::{STEP, langevin};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::construct::counts::ANY;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction, Shape};
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec};

/// Fattal's kernel density model sampled by Langevin steps (module doc).
#[derive(Debug, Clone, Copy)]
pub struct Kdm {
    iterations: usize,
    sigma: f64,
    temperature: f64,
    step: f64,
}

impl Construction for Kdm {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        SETTLED.check_count(shape)
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(self.units(), move |seed, out, progress| {
            me.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
        }))
    }
}

impl Kdm {

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


/// The sampler this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
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
    randomized: true,
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
