//! N-rooks / Latin hypercube sampling (McKay et al. 1979; Shirley 1991 section 2,
//! "separate" or uncorrelated jitter): one point in each of the n slabs of every axis.

use std::ops::RangeInclusive;

use super::registry::{ANY, SamplerEntry};
use super::{Fill, Sampler};
use crate::error::Result;
use crate::registry::About;
use crate::seed::{Seed, below, uniform};

/// Coordinate d of point i is (pi_d(i) + u) / n with pi_d a uniformly random permutation
/// and u uniform in [0,1): every axis-aligned slab of width 1/n holds exactly one point.
/// Dimension 0 uses the identity permutation (points come out sorted by their first
/// coordinate's slab); the other dimensions are permuted independently, which gives the
/// same distribution over sets. Any n, any d.
///
/// Centered (`lhs.centered`): each point at the centre of its slab, (pi_d(i) + 1/2) / n
/// with every dimension permuted, as scipy's `LatinHypercube(scramble=False)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct NRooks {
    centered: bool,
}

impl Sampler for NRooks {
    fn spec(&self) -> String {
        if self.centered { "lhs.centered" } else { "nrooks" }.into()
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }
}

impl Fill for NRooks {
    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let mut rng = seed.rng();
        let inv = 1.0 / n as f64;
        let mut perm: Vec<u32> = Vec::with_capacity(n);
        for d in 0..dims {
            perm.clear();
            perm.extend(0..n as u32);
            // the centered variant permutes dimension 0 too: its offsets carry no randomness
            if d > 0 || self.centered {
                for i in (1..n).rev() {
                    perm.swap(i, below(&mut rng, i as u64 + 1) as usize);
                }
            }
            for (i, &p) in perm.iter().enumerate() {
                let offset = if self.centered { 0.5 } else { uniform(&mut rng) };
                out[i * dims + d] = ((p as f64 + offset) * inv).min(super::grid::BELOW_ONE);
            }
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("nrooks", "one point in every slab of every axis (Latin hypercube)")
            .aliases(&["n-rooks", "separate", "lhcube", "latin-hypercube", "lhs"])
            .cite(&["mckay1979", "shirley1991"]),
        counts: ANY,
        dims: "any d",
        build: |_| Ok(Box::new(NRooks { centered: false })),
    },
    SamplerEntry {
        about: About::new("lhs.centered", "Latin hypercube with every point at the centre of its slab")
            .aliases(&["centered-lhs"])
            .cite(&["mckay1979"]),
        counts: ANY,
        dims: "any d",
        build: |_| Ok(Box::new(NRooks { centered: true })),
    },
];
