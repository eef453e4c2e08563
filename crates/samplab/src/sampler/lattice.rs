//! Rank-1 lattices. The Fibonacci lattice (Sloan & Joe 1994, section 5.2): for n = F_m, the
//! m-th Fibonacci number, point i is (i / n, frac(i F_(m-1) / n)), the 2D lattice with the
//! best worst-case error for smooth periodic integrands among rank-1 lattices of its size;
//! randomized by a random shift mod 1 (Cranley & Patterson 1976).

use std::ops::RangeInclusive;

use super::registry::SamplerEntry;
use super::{Fill, Sampler};
use crate::error::{Error, Result};
use crate::registry::About;
use crate::seed::{Seed, uniform};

/// The Fibonacci lattice, optionally shifted.
#[derive(Debug, Clone, Copy)]
pub struct Fibonacci {
    shift: bool,
}

/// The Fibonacci numbers 1, 2, 3, 5, 8, ... up to 2^32, each with its predecessor.
fn fibonacci() -> impl Iterator<Item = (usize, usize)> {
    std::iter::successors(Some((1usize, 1usize)), |&(f, g)| Some((f + g, f))).take_while(|&(f, _)| f <= 1 << 32)
}

impl Sampler for Fibonacci {
    fn spec(&self) -> String {
        if self.shift { "lattice.fibonacci.shift" } else { "lattice.fibonacci" }.into()
    }
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }
}

impl Fill for Fibonacci {
    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        if fibonacci().any(|(f, _)| f == n) {
            return Ok(());
        }
        let below = fibonacci().map(|(f, _)| f).take_while(|&f| f < n).last().unwrap_or(1);
        let above = fibonacci().map(|(f, _)| f).find(|&f| f > n);
        Err(Error::InvalidCount {
            sampler: self.spec(),
            n,
            dims,
            reason: match above {
                Some(a) => format!("n must be a Fibonacci number: try {below} and {a}"),
                None => format!("n must be a Fibonacci number up to 2^32: try {below}"),
            },
        })
    }

    fn fill(&self, n: usize, _dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let (_, g) = fibonacci().find(|&(f, _)| f == n).expect("a checked count");
        let mut rng = seed.rng();
        let shift = if self.shift { [uniform(&mut rng), uniform(&mut rng)] } else { [0.0; 2] };
        let wrap = |x: f64| if x >= 1.0 { x - 1.0 } else { x };
        for (i, p) in out.chunks_exact_mut(2).enumerate() {
            let y = (i as u128 * g as u128 % n as u128) as f64 / n as f64;
            p[0] = wrap(i as f64 / n as f64 + shift[0]);
            p[1] = wrap(y + shift[1]);
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("lattice.fibonacci", "Fibonacci lattice (i/n, frac(i F_(m-1)/n)), n = F_m")
            .aliases(&["fibonacci"])
            .cite(&["sloan1994"]),
        counts: "n a Fibonacci number (1, 2, 3, 5, 8, ...)",
        dims: "2",
        build: |_| Ok(Box::new(Fibonacci { shift: false })),
    },
    SamplerEntry {
        about: About::new("lattice.fibonacci.shift", "the Fibonacci lattice with a random shift mod 1")
            .aliases(&["fibonacci-shift"])
            .cite(&["sloan1994", "cranley1976"]),
        counts: "n a Fibonacci number (1, 2, 3, 5, 8, ...)",
        dims: "2",
        build: |_| Ok(Box::new(Fibonacci { shift: true })),
    },
];
