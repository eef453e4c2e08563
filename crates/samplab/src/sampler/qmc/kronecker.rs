//! Kronecker (Weyl) sequences: point i is frac(i alpha) for an irrational alpha (Weyl
//! 1916), with Roberts' generalized golden ratio alpha_j = phi_d^-(j+1), phi_d the positive
//! root of x^(d+1) = x + 1 (the R_d sequence, Roberts 2018), or the alphas a user gives
//! (`kronecker:alpha=0.4142135623730951/0.7320508075688772`: the fractional parts of sqrt 2
//! and sqrt 3, say); randomized by a random shift mod 1 (Cranley & Patterson 1976).
//!
//! Arithmetic is in 64-bit fixed point: alpha_j is held as round(alpha_j 2^64) and point i
//! as i alpha_j mod 2^64, exact modulo 1 for every index, so the coordinates of the 2^40-th
//! point are as good as the first's (a float product i alpha would lose log2(i) bits).

use std::ops::RangeInclusive;

use crate::construct::counts::ANY;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec};

/// The R_d sequence or a Kronecker sequence of given alphas, optionally shifted.
#[derive(Debug, Clone)]
pub struct Kronecker {
    shift: bool,
    /// The user's alphas (None: R_d for whatever dimension is asked).
    alphas: Option<Vec<f64>>,
}

/// alpha_j = phi_d^-(j+1) for j < d, phi_d the root of x^(d+1) = x + 1 above 1 (Newton's
/// method from 2, which decreases monotonically to it).
pub fn alphas(dims: usize) -> Vec<f64> {
    let p = (dims + 1) as i32;
    let mut x = 2.0f64;
    for _ in 0..200 {
        let next = x - (x.powi(p) - x - 1.0) / (f64::from(p) * x.powi(p - 1) - 1.0);
        if next >= x {
            break;
        }
        x = next;
    }
    (1..=dims).map(|j| x.powi(-(j as i32))).collect()
}

/// A Kronecker sequence prepared for a dimension: the fixed-point increments.
#[derive(Debug)]
struct Steps<'a> {
    kronecker: &'a Kronecker,
    steps: Vec<u64>,
}

/// Random access for one seed: the increments and the seed's shifts.
#[derive(Debug)]
struct Shifted<'a> {
    steps: &'a [u64],
    shifts: Vec<u64>,
}

/// Coordinate `index` of the dimension with increment `step` and shift `shift`: the 53
/// leading bits of index x step + shift mod 2^64.
#[inline]
fn coordinate(index: u64, step: u64, shift: u64) -> f64 {
    let x = index.wrapping_mul(step).wrapping_add(shift);
    (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

impl Steps<'_> {
    /// The shift of each dimension in turn, drawn from the seed's one stream.
    fn shifts(&self, seed: Seed) -> impl Iterator<Item = u64> {
        let (mut rng, shift) = (seed.rng(), self.kronecker.shift);
        (0..self.steps.len()).map(move |_| if shift { rand_core::Rng::next_u64(&mut rng) } else { 0 })
    }
}

impl Prepared for Steps<'_> {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        // dimension by dimension, so the shifts need no buffer
        let dims = self.steps.len();
        for (d, (&step, shift)) in self.steps.iter().zip(self.shifts(seed)).enumerate() {
            for (i, point) in out.chunks_exact_mut(dims).enumerate() {
                point[d] = coordinate(i as u64, step, shift);
            }
        }
        progress.advance(1)
    }

    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(Shifted { steps: &self.steps, shifts: self.shifts(seed).collect() }))
    }
}

impl Access for Shifted<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(coordinate(index, self.steps[dim], self.shifts[dim]))
    }
}

impl Construction for Kronecker {
    fn dims(&self) -> RangeInclusive<usize> {
        // given alphas fix the dimension: one per axis, none left unused
        self.alphas.as_ref().map_or(1..=usize::MAX, |a| a.len()..=a.len())
    }
    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        let fixed = |a: f64| (a * 18_446_744_073_709_551_616.0) as u64;
        let steps = match &self.alphas {
            Some(given) => given[..shape.dims()].iter().map(|&a| fixed(a)).collect(),
            None => alphas(shape.dims()).into_iter().map(fixed).collect(),
        };
        Ok(Box::new(Steps { kronecker: self, steps }))
    }
}

const ALPHA: ParamSpec = ParamSpec {
    name: "alpha",
    kind: Kind::Reals { min: 0.0, max: 1.0 },
    default: Default::Auto("R_d: phi_d^-1, ..., phi_d^-d"),
    doc: "the increment of each dimension (irrational in theory; 53 bits here), one per dimension",
};

fn build(p: &crate::spec::Params, shift: bool, owner: &str) -> Result<Box<dyn Construction>> {
    let alphas = p.reals_or_auto("alpha").map(<[f64]>::to_vec);
    if let Some(a) = alphas.as_ref().and_then(|a| a.iter().find(|&&a| a == 0.0 || a == 1.0)) {
        return Err(Error::Param {
            owner: owner.into(),
            param: "alpha".into(),
            reason: format!("{a} makes every point's coordinate the same; expected a number strictly between 0 and 1"),
        });
    }
    Ok(Box::new(Kronecker { shift, alphas }))
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("kronecker", "Kronecker sequence frac(i alpha), alpha from the generalized golden ratio (R_d) or given").terse()
            .aliases(&["weyl", "rd", "r2"])
            .params(&[ALPHA])
            .cite(&["weyl1916", "roberts2018"]),
        counts: ANY,
        randomized: false,
        dims: "any d (d <= the alphas given)",
        build: |p| build(p, false, "kronecker"),
    },
    SamplerEntry {
        about: About::new("kronecker.shift", "the Kronecker sequence (R_d or given alphas) with a random shift mod 1").terse()
            .aliases(&["kronecker-shift"])
            .params(&[ALPHA])
            .cite(&["weyl1916", "roberts2018", "cranley1976"]),
        counts: ANY,
        randomized: true,
        dims: "any d (d <= the alphas given)",
        build: |p| build(p, true, "kronecker.shift"),
    },
];
