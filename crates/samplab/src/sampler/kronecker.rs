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

use super::registry::{ANY, SamplerEntry};
use super::{Access, Fill, Sampler, Sequence};
use crate::error::{Error, Result};
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

/// The fixed-point increments and shifts of a prepared sequence.
#[derive(Debug)]
struct Prepared {
    steps: Vec<u64>,
    shifts: Vec<u64>,
}

impl Prepared {
    fn new(k: &Kronecker, dims: usize, seed: Seed) -> Prepared {
        let fixed = |a: f64| (a * 18_446_744_073_709_551_616.0) as u64;
        let steps = match &k.alphas {
            Some(given) => given[..dims].iter().map(|&a| fixed(a)).collect(),
            None => alphas(dims).into_iter().map(fixed).collect(),
        };
        let mut rng = seed.rng();
        let shifts = (0..dims).map(|_| if k.shift { rand_core::Rng::next_u64(&mut rng) } else { 0 }).collect();
        Prepared { steps, shifts }
    }

    #[inline]
    fn coordinate(&self, index: u64, dim: usize) -> f64 {
        let x = index.wrapping_mul(self.steps[dim]).wrapping_add(self.shifts[dim]);
        (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

impl Sampler for Kronecker {
    fn spec(&self) -> String {
        let name = if self.shift { "kronecker.shift" } else { "kronecker" };
        match &self.alphas {
            Some(a) => format!("{name}:alpha={}", a.iter().map(f64::to_string).collect::<Vec<_>>().join("/")),
            None => name.into(),
        }
    }
    fn dims(&self) -> RangeInclusive<usize> {
        // given alphas fix the dimension: one per axis, none left unused
        self.alphas.as_ref().map_or(1..=usize::MAX, |a| a.len()..=a.len())
    }
    fn as_sequence(&self) -> Option<&dyn Sequence> {
        Some(self)
    }
}

impl Fill for Kronecker {
    fn fill(&self, _n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let p = Prepared::new(self, dims, seed);
        for (i, point) in out.chunks_exact_mut(dims).enumerate() {
            for (d, x) in point.iter_mut().enumerate() {
                *x = p.coordinate(i as u64, d);
            }
        }
        Ok(())
    }
}

impl Sequence for Kronecker {
    fn access(&self, dims: usize, seed: Seed) -> Result<Box<dyn Access + '_>> {
        (self as &dyn Sampler).plan(1, dims)?;
        Ok(Box::new(Prepared::new(self, dims, seed)))
    }
}

impl Access for Prepared {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(self.coordinate(index, dim))
    }
}

const ALPHA: ParamSpec = ParamSpec {
    name: "alpha",
    kind: Kind::Reals { min: 0.0, max: 1.0 },
    default: Default::Auto("R_d: phi_d^-1, ..., phi_d^-d"),
    doc: "the increment of each dimension (irrational in theory; 53 bits here), one per dimension",
};

fn build(p: &crate::spec::Params, shift: bool, owner: &str) -> Result<Box<dyn Sampler>> {
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
        about: About::new("kronecker", "Kronecker sequence frac(i alpha), alpha from the generalized golden ratio (R_d) or given")
            .aliases(&["weyl", "rd", "r2"])
            .params(&[ALPHA])
            .cite(&["weyl1916", "roberts2018"]),
        counts: ANY,
        dims: "any d (d <= the alphas given)",
        build: |p| build(p, false, "kronecker"),
    },
    SamplerEntry {
        about: About::new("kronecker.shift", "the Kronecker sequence (R_d or given alphas) with a random shift mod 1")
            .aliases(&["kronecker-shift"])
            .params(&[ALPHA])
            .cite(&["weyl1916", "roberts2018", "cranley1976"]),
        counts: ANY,
        dims: "any d (d <= the alphas given)",
        build: |p| build(p, true, "kronecker.shift"),
    },
];
