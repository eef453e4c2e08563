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

use crate::construct::Randomization;
use crate::construct::counts::ANY;
use crate::sampler::randomize::{randomized_families, shift};
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec};

/// The R_d sequence or a Kronecker sequence of given alphas.
#[derive(Debug, Clone)]
pub struct Kronecker {
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
struct Steps {
    steps: Vec<u64>,
}

/// Coordinate `index` of the dimension with increment `step`: the 53 leading bits of
/// index x step mod 2^64.
#[inline]
fn coordinate(index: u64, step: u64) -> f64 {
    (index.wrapping_mul(step) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

impl Prepared for Steps {
    fn fill(&self, _seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let dims = self.steps.len();
        for (i, point) in out.chunks_exact_mut(dims).enumerate() {
            for (x, &step) in point.iter_mut().zip(&self.steps) {
                *x = coordinate(i as u64, step);
            }
        }
        progress.advance(1)
    }

    fn access(&self, _seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(Steps { steps: self.steps.clone() }))
    }

    fn sample_at(&self, _seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        Some(Ok(coordinate(index, self.steps[dim])))
    }
}

impl Access for Steps {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(coordinate(index, self.steps[dim]))
    }
}

impl Construction for Kronecker {
    fn dims(&self) -> RangeInclusive<usize> {
        // given alphas fix the dimension: one per axis, none left unused
        self.alphas.as_ref().map_or(1..=usize::MAX, |a| a.len()..=a.len())
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let fixed = |a: f64| (a * 18_446_744_073_709_551_616.0) as u64;
        let steps = match &self.alphas {
            Some(given) => given[..shape.dims()].iter().map(|&a| fixed(a)).collect(),
            None => alphas(shape.dims()).into_iter().map(fixed).collect(),
        };
        Ok(Box::new(Steps { steps }))
    }
}

const ALPHA: ParamSpec = ParamSpec {
    name: "alpha",
    kind: Kind::Reals { min: 0.0, max: 1.0 },
    default: Default::Auto("R_d: phi_d^-1, ..., phi_d^-d"),
    doc: "the increment of each dimension (irrational in theory; 53 bits here), one per dimension",
};

/// The construction of each entry: the sequence, shifted by the `+shift` stage's code for
/// `kronecker.shift`.
fn build(p: &crate::spec::Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    let alphas = p.reals_or_auto("alpha").map(<[f64]>::to_vec);
    if let Some(a) = alphas.as_ref().and_then(|a| a.iter().find(|&&a| a == 0.0 || a == 1.0)) {
        return Err(Error::Param {
            owner: if randomization == Randomization::Shift { "kronecker.shift" } else { "kronecker" }.into(),
            param: "alpha".into(),
            reason: format!("{a} makes every point's coordinate the same; expected a number strictly between 0 and 1"),
        });
    }
    Ok(shift::applied(randomization, |_| Box::new(Kronecker { alphas })))
}

/// The samplers this file registers: the sequence and its shift.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!({
    family: "kronecker",
    summary: "Kronecker sequence frac(i alpha), alpha from the generalized golden ratio (R_d) or given",
    aliases: ["weyl", "rd", "r2"],
    params: &[ALPHA],
    counts: ANY,
    dims: "any d (d <= the alphas given)",
    cite: ["weyl1916", "roberts2018"],
    build: build,
    randomizations: [shift],
});
