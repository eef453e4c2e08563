//! Micro-jittering: any set's points each moved by an independent uniform offset in a cube
//! of side `fraction x h` centred on it, h = n^(-1/d) the mean spacing (1/k exactly for
//! n = k^d), wrapped on the torus. It breaks the lattice-like alignments of a structured
//! set (a Kronecker sequence, a lattice) while keeping most of its uniformity, as Roberts
//! jitters the R_2 sequence by a fraction of its spacing; on the regular grid (the entry on
//! its own) with fraction 1 it is Cook's jittered sampling, with less a partially jittered
//! grid.
//!
//! Written after any sampler spec: `kronecker+micro-jitter:fraction=0.2`,
//! `lattice.cbc.shift+micro-jitter`; fraction 0 gives the sampler's own bytes.

use std::ops::RangeInclusive;

use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use super::StageEntry;
use crate::sampler::{Construction, Prepared, Shape};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Seed, uniform, wrap01};
use crate::spec::{Default, Kind, ParamSpec};

/// A sampler whose points are micro-jittered.
#[derive(Debug)]
pub struct MicroJitter {
    inner: super::Before,
    fraction: f64,
}

/// The mean spacing of n points in d dimensions: 1/k when n = k^d, else n^(-1/d).
fn spacing(n: usize, dims: usize) -> f64 {
    let k = (n as f64).powf(1.0 / dims as f64).round();
    if u32::try_from(dims).ok().and_then(|d| (k as usize).checked_pow(d)) == Some(n) {
        1.0 / k
    } else {
        (n as f64).powf(-1.0 / dims as f64)
    }
}

impl Construction for MicroJitter {
    fn dims(&self) -> RangeInclusive<usize> {
        self.inner.dims()
    }
    fn check_count(&self, shape: &Shape) -> Result<()> {
        self.inner.check_count(shape)
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        // the inner sampler's checks passed with this shape's (the dimension range is its)
        let width = self.fraction * spacing(shape.n(), shape.dims());
        Ok(Box::new(Jittered { inner: self.inner.prepare(shape)?, width }))
    }
}

/// A planned sampler whose points are then micro-jittered by up to `width` / 2 per axis.
struct Jittered {
    inner: Box<dyn Prepared>,
    width: f64,
}

impl Prepared for Jittered {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        self.inner.fill(seed, out, progress)?;
        if self.width == 0.0 {
            return Ok(());
        }
        let mut rng = seed.derive_str("micro-jitter").rng();
        for x in out.iter_mut() {
            *x = wrap01(*x + self.width * (uniform(&mut rng) - 0.5));
        }
        Ok(())
    }
    fn units(&self) -> u64 {
        self.inner.units()
    }
}

const FRACTION: ParamSpec = ParamSpec {
    name: "fraction",
    kind: Kind::Real { min: 0.0, max: 1.0 },
    default: Default::Number(0.1),
    doc: "side of the offset cube, a fraction of the mean spacing n^(-1/d)",
};

/// What the entry and the stage say about themselves.
const ABOUT: About = About::new(
    "micro-jitter",
    "micro-jittering: each point moved uniformly within a fraction of the spacing; written after any spec \
     (sobol+micro-jitter:0.2), alone on the regular grid",
)
.aliases(&["microjitter"])
.params(&[FRACTION])
.cite(&["cook1986", "roberts2018jitter"]);

/// The entry this file registers: micro-jitter alone, on the regular grid.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: ABOUT,
    counts: Counts::Grid,
    randomized: true,
    dims: "1..=64 (after a spec: the sampler's)",
    build: |p| {
        Ok(Box::new(MicroJitter { inner: super::Before(crate::sampler::build("regular")?), fraction: p.real("fraction") }))
    },
}];

/// The stage this file registers: micro-jitter after any spec.
pub(crate) static STAGES: &[StageEntry] =
    &[StageEntry { about: ABOUT, build: |inner, p| Ok(Box::new(MicroJitter { inner: super::Before(inner), fraction: p.real("fraction") })) }];
