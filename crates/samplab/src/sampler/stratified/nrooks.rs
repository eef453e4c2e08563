//! N-rooks / Latin hypercube sampling (McKay et al. 1979; Shirley 1991 section 2,
//! "separate" or uncorrelated jitter): one point in each of the n slabs of every axis.

use std::ops::RangeInclusive;

use crate::construct::{counts::ANY, Counts};
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::registry::About;
use crate::seed::{Seed, shuffle, uniform};

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

impl Construction for NRooks {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl NRooks {
    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let mut rng = seed.rng();
        let inv = 1.0 / n as f64;
        let mut perm: Vec<u32> = Vec::with_capacity(n);
        for d in 0..dims {
            perm.clear();
            perm.extend(0..n as u32);
            // the centered variant permutes dimension 0 too: its offsets carry no randomness
            if d > 0 || self.centered {
                shuffle(&mut rng, &mut perm);
            }
            for (i, &p) in perm.iter().enumerate() {
                let offset = if self.centered { 0.5 } else { uniform(&mut rng) };
                out[i * dims + d] = ((p as f64 + offset) * inv).min(crate::numeric::BELOW_ONE);
            }
        }
        Ok(())
    }
}

/// Latin hypercubes of strength 2 from orthogonal arrays (Owen 1992; Tang 1993): Bose's
/// OA(p^2, p + 1, p, 2) (p prime; row (a, b) has columns b, a, a + b, a + 2b, ..., a +
/// (p - 1) b mod p), its symbols relabelled by a random permutation per column, then each
/// symbol v's p occurrences in a column replaced by a random permutation of v p .. v p + p - 1
/// and jittered uniformly within their slab. n = p^2 points in d <= p + 1 dimensions: every
/// 1D projection is a Latin hypercube, and every 2D projection has one point in each cell
/// of the p x p grid.
#[derive(Debug, Clone, Copy)]
pub struct OaLhs;

impl Construction for OaLhs {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

fn is_prime(p: usize) -> bool {
    p >= 2 && (2..).take_while(|k| k * k <= p).all(|k| !p.is_multiple_of(k))
}

impl OaLhs {


    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let p = (n as f64).sqrt().round() as usize;
        let mut rng = seed.rng();
        for d in 0..dims {
            let mut relabel: Vec<usize> = (0..p).collect();
            shuffle(&mut rng, &mut relabel);
            // slabs v p .. v p + p - 1, in a random order per symbol
            let mut slabs: Vec<Vec<usize>> = (0..p)
                .map(|v| {
                    let mut s: Vec<usize> = (v * p..(v + 1) * p).collect();
                    shuffle(&mut rng, &mut s);
                    s
                })
                .collect();
            for i in 0..n {
                let (a, b) = (i / p, i % p);
                let symbol = match d {
                    0 => b,
                    1 => a,
                    d => (a + (d - 1) * b) % p,
                };
                let slab = slabs[relabel[symbol]].pop().expect("each symbol occurs p times");
                out[i * dims + d] = ((slab as f64 + uniform(&mut rng)) / n as f64).min(crate::numeric::BELOW_ONE);
            }
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("nrooks", "one point in every slab of every axis (Latin hypercube)")
            .aliases(&["n-rooks", "separate", "lhcube", "latin-hypercube", "lhs", "lhs.scrambled"])
            .cite(&["mckay1979", "shirley1991"]),
        counts: ANY,
        randomized: true,
        dims: "any d",
        build: |_| Ok(Box::new(NRooks { centered: false })),
    },
    SamplerEntry {
        about: About::new("lhs.centered", "Latin hypercube with every point at the centre of its slab")
            .aliases(&["centered-lhs"])
            .cite(&["mckay1979"]),
        counts: ANY,
        randomized: true,
        dims: "any d",
        build: |_| Ok(Box::new(NRooks { centered: true })),
    },
    SamplerEntry {
        about: About::new("lhs.oa", "Latin hypercube of strength 2 from Bose's orthogonal array")
            .aliases(&["oa-lhs"])
            .cite(&["owen1992", "tang1993"]),
        counts: Counts::Listed {
            rule: "n must be p^2 for a prime p >= d - 1",
            list: |dims, _| Box::new((2..).filter(move |&p| is_prime(p) && dims <= p + 1).map(|p| p * p)),
        },
        randomized: true,
        dims: "d <= p + 1",
        build: |_| Ok(Box::new(OaLhs)),
    },
];
