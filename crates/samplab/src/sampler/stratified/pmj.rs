//! Progressive multi-jittered (0,2) sequences (Christensen, Kensler & Kilpatrick 2018),
//! generated with the stochastic construction of Helmer, Christensen & Kensler 2021, and
//! correlated multi-jittered sampling (Kensler 2013).

use std::ops::RangeInclusive;

use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::construct::scramble::{hash_unit, permute};
use crate::construct::pmj02::pmj02_digits;
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::registry::About;
use crate::seed::Seed;

/// pmj02: every prefix of 2^m points is a (0,m,2)-net in base 2 (one point in every
/// elementary interval of area 2^-m), and so is every later block of 2^m points: the
/// stochastic construction of [`crate::construct::pmj02`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Pmj02;

impl Construction for Pmj02 {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Pmj02 {
    fn fill(&self, n: usize, _dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        for (p, q) in out.chunks_exact_mut(2).zip(&pmj02_digits(n, seed)) {
            p[0] = crate::construct::cell_centre(q[0]);
            p[1] = crate::construct::cell_centre(q[1]);
        }
        Ok(())
    }
}

/// Correlated multi-jittered sampling (Kensler 2013, section 4): an m x k arrangement of
/// cells (m = floor(sqrt(n)), k = ceil(n / m)), the canonical N-rooks layout shuffled by
/// one permutation per axis shared by all rows (resp. columns), then jittered inside each
/// sub-cell; any n (when n < m*k, a random n of the cells are used). 2D.
#[derive(Debug, Clone, Copy, Default)]
pub struct Cmj;

impl Construction for Cmj {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Cmj {

    fn fill(&self, n: usize, _dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let m = (n as f64).sqrt().floor().max(1.0) as u32;
        let k = (n as u32).div_ceil(m);
        let key = |label: &str| seed.derive_str(label).bits32();
        let (kidx, kx, ky) = (key("cmj index"), key("cmj x"), key("cmj y"));
        let (jx, jy) = (seed.derive_str("cmj jitter x").0, seed.derive_str("cmj jitter y").0);
        for (s, p) in out.chunks_exact_mut(2).enumerate() {
            let s = permute(s as u32, n as u32, kidx);
            let (col, row) = (s % m, s / m);
            let sx = permute(col, m, kx);
            let sy = permute(row, k, ky);
            let (ux, uy) = (hash_unit(u64::from(s), jx), hash_unit(u64::from(s), jy));
            p[0] = ((f64::from(col) + (f64::from(sy) + ux) / f64::from(k)) / f64::from(m)).min(crate::numeric::BELOW_ONE);
            p[1] = ((f64::from(row) + (f64::from(sx) + uy) / f64::from(m)) / f64::from(k)).min(crate::numeric::BELOW_ONE);
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("pmj02", "progressive multi-jittered (0,2) sequence, stochastic construction")
            .aliases(&["pmj"])
            .cite(&["christensen2018", "helmer2021"]),
        counts: Counts::AtMost { most: 1 << 32, why: "32-bit Sobol' points stop at 2^32" },
        randomized: true,
        dims: "2",
        build: |_| Ok(Box::new(Pmj02)),
    },
    SamplerEntry {
        about: About::new("cmj", "correlated multi-jittered sampling")
            .aliases(&["correlated-multi-jittered"])
            .cite(&["kensler2013"]),
        counts: Counts::AtMost { most: u32::MAX as u64, why: "at most 2^32 - 1 points" },
        randomized: true,
        dims: "2",
        build: |_| Ok(Box::new(Cmj)),
    },
];
