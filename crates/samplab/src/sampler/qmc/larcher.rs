//! The Larcher–Pillichshammer points (Larcher & Pillichshammer 2003): the digital net in base
//! 2 whose first generating matrix puts the index's digits in reverse order (point i of n at
//! x = i/n, as Hammersley's) and whose second is the upper triangular matrix of ones, so
//! that digit r of y (weight 2^-(r+1)) is the parity of the index's digits r, r+1, ... For
//! n = 2^m the set is a (0, m, 2)-net in base 2; the paper finds it among the 2D nets of
//! least star discrepancy. Randomized as Hammersley is: on each coordinate's 32 bits (a
//! digital shift, or Owen's nested scramble by hashing), or by the `+shift` stage.

use std::ops::RangeInclusive;

use crate::construct::scramble::{Randomization, owen_scramble_u32};
use crate::construct::{Counts, cell_centre, unit};
use crate::error::Result;
use crate::sampler::randomize::{randomized_families, shift};
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Construction, Prepared, Shape};
use crate::spec::Params;

/// The 32-bit binary expansion of y for index `i`: bit 31 - r is the parity of bits r..32 of
/// `i`, the product of the upper triangular matrix of ones with the index's digits.
pub(crate) fn lp_bits(i: u32) -> u32 {
    // suffix parities: after the five steps, bit r is the XOR of bits r, r+1, ... of i
    let mut p = i;
    for s in [1, 2, 4, 8, 16] {
        p ^= p >> s;
    }
    p.reverse_bits()
}

/// The Larcher–Pillichshammer set with a randomization (none, XOR or Owen; the shift is the
/// `+shift` stage's).
#[derive(Debug, Clone, Copy, PartialEq)]
struct LarcherPillichshammer {
    randomization: Randomization,
}

impl Construction for LarcherPillichshammer {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let (me, n) = (*self, shape.n());
        Ok(crate::sampler::from_fill(move |seed, out| {
            let (bx, by) = (seed.derive(0).bits32(), seed.derive(1).bits32());
            for (i, p) in out.chunks_exact_mut(2).enumerate() {
                let x = ((i as u128) << 32).div_euclid(n as u128) as u32;
                let y = lp_bits(i as u32);
                (p[0], p[1]) = match me.randomization {
                    Randomization::None => (i as f64 / n as f64, unit(y)),
                    Randomization::Xor => (cell_centre(x ^ bx), cell_centre(y ^ by)),
                    Randomization::Owen => (cell_centre(owen_scramble_u32(x, bx)), cell_centre(owen_scramble_u32(y, by))),
                    Randomization::Lms | Randomization::Shift => {
                        unreachable!("declares no linear matrix scrambling, and its shift is the +shift stage's")
                    }
                };
            }
            Ok(())
        }))
    }
}

/// The construction of each entry.
fn build(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(shift::applied(randomization, |randomization| Box::new(LarcherPillichshammer { randomization })))
}

/// The samplers this file registers: the set plain and with its randomizations.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!({
    family: "larcher-pillichshammer",
    summary: "Larcher-Pillichshammer set: i/n, then the upper triangular matrix of ones in base 2",
    aliases: ["lp"],
    params: &[],
    counts: Counts::AtMost { most: 1 << 32, why: "the coordinates have 32-bit resolution: at most 2^32 points" },
    dims: "2",
    cite: ["larcher2003"],
    build: build,
    randomizations: [xor, owen, shift],
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lp_bits_are_the_upper_triangular_matrix_of_ones_times_the_digits() {
        // the matrix product written out: digit r of y is the sum mod 2 of digits k >= r of i
        for i in (0..4096u32).chain([u32::MAX, 0x8000_0001, 0xDEAD_BEEF]) {
            let want = (0..32).fold(0u32, |y, r| {
                let parity = (r..32).map(|k| i >> k & 1).sum::<u32>() & 1;
                y | parity << (31 - r)
            });
            assert_eq!(lp_bits(i), want, "{i}");
        }
    }

    /// Whether the points (i / 2^m, y_i) put one point in every elementary interval
    /// 2^-a x 2^-(m-a): a (0, m, 2)-net, counted by brute force.
    fn is_02_net(y: impl Fn(u32) -> u32, m: u32) -> bool {
        (0..=m).all(|a| {
            let b = m - a;
            let mut seen = vec![false; 1 << m];
            (0..1u32 << m).all(|i| {
                // x = i / 2^m: its first a digits are the index's top a; y's first b digits
                let (x_cell, y_cell) = (i >> b, (u64::from(y(i)) >> (32 - b)) as u32);
                !std::mem::replace(&mut seen[((x_cell << b) | y_cell) as usize], true)
            })
        })
    }

    #[test]
    fn the_set_is_a_02_net_and_a_perturbed_matrix_is_not() {
        for m in 1..=10 {
            assert!(is_02_net(lp_bits, m), "m = {m}");
        }
        // the matrix with one diagonal digit dropped (digit 2 the parity of digits 3, 4, ...)
        let perturbed = |i: u32| lp_bits(i) ^ ((i >> 2 & 1) << 29);
        assert!((3..=10).all(|m| !is_02_net(perturbed, m)));
    }
}
