//! Kronecker (Weyl) sequences: point i is frac(i alpha) for an irrational alpha (Weyl
//! 1916), with Roberts' generalized golden ratio alpha_j = phi_d^-(j+1), phi_d the positive
//! root of x^(d+1) = x + 1 (the R_d sequence, Roberts 2018); randomized by a random shift
//! mod 1 (Cranley & Patterson 1976).
//!
//! Arithmetic is in 64-bit fixed point: alpha_j is held as round(alpha_j 2^64) and point i
//! as i alpha_j mod 2^64, exact modulo 1 for every index, so the coordinates of the 2^40-th
//! point are as good as the first's (a float product i alpha would lose log2(i) bits).

use std::ops::RangeInclusive;

use super::registry::{ANY, SamplerEntry};
use super::{Access, Fill, Sampler, Sequence};
use crate::error::Result;
use crate::registry::About;
use crate::seed::Seed;

/// The R_d sequence, optionally shifted.
#[derive(Debug, Clone, Copy)]
pub struct Kronecker {
    shift: bool,
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
    fn new(dims: usize, shift: bool, seed: Seed) -> Prepared {
        let steps = alphas(dims).into_iter().map(|a| (a * 18_446_744_073_709_551_616.0) as u64).collect();
        let mut rng = seed.rng();
        let shifts = (0..dims).map(|_| if shift { rand_core::Rng::next_u64(&mut rng) } else { 0 }).collect();
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
        if self.shift { "kronecker.shift" } else { "kronecker" }.into()
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }
    fn as_sequence(&self) -> Option<&dyn Sequence> {
        Some(self)
    }
}

impl Fill for Kronecker {
    fn fill(&self, _n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let p = Prepared::new(dims, self.shift, seed);
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
        Ok(Box::new(Prepared::new(dims, self.shift, seed)))
    }
}

impl Access for Prepared {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(self.coordinate(index, dim))
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("kronecker", "Kronecker sequence frac(i alpha), alpha from the generalized golden ratio (R_d)")
            .aliases(&["weyl", "rd", "r2"])
            .cite(&["weyl1916", "roberts2018"]),
        counts: ANY,
        dims: "any d",
        build: |_| Ok(Box::new(Kronecker { shift: false })),
    },
    SamplerEntry {
        about: About::new("kronecker.shift", "the R_d Kronecker sequence with a random shift mod 1")
            .aliases(&["kronecker-shift"])
            .cite(&["weyl1916", "roberts2018", "cranley1976"]),
        counts: ANY,
        dims: "any d",
        build: |_| Ok(Box::new(Kronecker { shift: true })),
    },
];
