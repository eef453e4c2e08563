//! Independent uniform sampling ("random", "Poisson sampling" in Sbert et al. 2006).

use std::ops::RangeInclusive;

use super::registry::SamplerEntry;
use super::{Construction, Prepared, Shape, Stream};
use crate::construct::counts::ANY;
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
    fn prepare(&self, _shape: &Shape) -> Result<Box<dyn Prepared>> {
        Ok(Box::new(Random))
    }
}

impl Random {
    /// Fill `out` with independent uniform draws for `seed`: draw i is the i-th of the
    /// seed's stream. Beyond one chunk, chunks go in parallel, each from the stream jumped
    /// ahead to its first draw (`advance`, the exact jump of PCG's underlying LCG, Brown
    /// 1994), so the bits are those of one sequence on any thread count; a fill of one
    /// chunk or less stays on the caller's thread (no dispatch, no allocation).
    pub(crate) fn draw(seed: Seed, out: &mut [f64]) {
        use rayon::prelude::*;
        const CHUNK: usize = 1 << 15;
        let rng = seed.rng();
        let fill = |c: usize, chunk: &mut [f64]| {
            let mut rng = rng.clone();
            rng.advance((c * CHUNK) as u128);
            chunk.iter_mut().for_each(|x| *x = uniform(&mut rng));
        };
        if out.len() <= CHUNK {
            fill(0, out);
        } else {
            out.par_chunks_mut(CHUNK).enumerate().for_each(|(c, chunk)| fill(c, chunk));
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallel_draws_are_the_sequence() {
        // around the chunk boundaries, and on one and three threads
        for len in [0, 1, (1 << 15) - 1, 1 << 15, (1 << 15) + 1, 3 * (1 << 15) + 7] {
            let mut rng = Seed(9).rng();
            let sequence: Vec<u64> = (0..len).map(|_| uniform(&mut rng).to_bits()).collect();
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let mut out = vec![0.0; len];
                pool.install(|| Random::draw(Seed(9), &mut out));
                assert!(out.iter().map(|x| x.to_bits()).eq(sequence.iter().copied()), "{len} draws, {threads} threads");
            }
        }
    }
}
