//! Independent uniform sampling ("random", "Poisson sampling" in Sbert et al. 2006).

use std::ops::RangeInclusive;

use super::registry::{ANY, SamplerEntry};
use super::{Construction, Prepared, Shape, Stream};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Rng, Seed, uniform};

/// Every coordinate an independent uniform draw in [0, 1). Any n, any d.
#[derive(Debug, Clone, Copy, Default)]
pub struct Random;

impl Construction for Random {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }
    fn prepare(&self, _shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        Ok(Box::new(Random))
    }
}

impl Random {
    /// Fill `out` with independent uniform draws for `seed`.
    pub(crate) fn draw(seed: Seed, out: &mut [f64]) {
        let mut rng = seed.rng();
        out.iter_mut().for_each(|x| *x = uniform(&mut rng));
    }
}

impl Prepared for Random {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        Random::draw(seed, out);
        progress.advance(1)
    }
    fn stream(&self, seed: Seed) -> Option<Box<dyn Stream + '_>> {
        Some(Box::new(Draws(seed.rng())))
    }
}

/// The draws of a random set, continued chunk after chunk.
struct Draws(Rng);

impl Stream for Draws {
    fn next(&mut self, out: &mut [f64]) -> Result<()> {
        out.iter_mut().for_each(|x| *x = uniform(&mut self.0));
        Ok(())
    }
}

/// The sampler this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("random", "independent uniform points")
        .aliases(&["uniform-random", "poisson-sampling"])
        .cite(&["shirley1991"]),
    counts: ANY,
    randomized: true,
    dims: "any d",
    build: |_| Ok(Box::new(Random)),
}];
