//! Independent uniform sampling ("random", "Poisson sampling" in Sbert et al. 2006).

use std::ops::RangeInclusive;

use super::registry::{ANY, SamplerEntry};
use super::{Fill, Sampler, Stream};
use crate::error::Result;
use crate::registry::About;
use crate::seed::{Rng, Seed, uniform};

/// Every coordinate an independent uniform draw in [0, 1). Any n, any d.
#[derive(Debug, Clone, Copy, Default)]
pub struct Random;

impl Sampler for Random {
    fn spec(&self) -> String {
        "random".into()
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }
    fn stream(&self, _dims: usize, seed: Seed) -> Option<Box<dyn Stream>> {
        Some(Box::new(Draws(seed.rng())))
    }
}

/// The draws of [`Random::fill`], continued chunk after chunk.
struct Draws(Rng);

impl Stream for Draws {
    fn next(&mut self, out: &mut [f64]) -> Result<()> {
        out.iter_mut().for_each(|x| *x = uniform(&mut self.0));
        Ok(())
    }
}

impl Fill for Random {
    fn fill(&self, _n: usize, _dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let mut rng = seed.rng();
        out.iter_mut().for_each(|x| *x = uniform(&mut rng));
        Ok(())
    }
}

/// The sampler this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("random", "independent uniform points")
        .aliases(&["uniform-random", "poisson-sampling"])
        .cite(&["shirley1991"]),
    counts: ANY,
    dims: "any d",
    build: |_| Ok(Box::new(Random)),
}];
