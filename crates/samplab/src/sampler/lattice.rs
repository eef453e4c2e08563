//! Rank-1 lattices: point i is frac(i z / n) for a generating vector z (Sloan & Joe 1994),
//! randomized by a random shift mod 1 (Cranley & Patterson 1976).
//!
//! - The Fibonacci lattice (Sloan & Joe section 5.2): n = F_m, the m-th Fibonacci number,
//!   z = (1, F_(m-1)).
//! - Korobov lattices (Korobov 1959; Sloan & Joe section 5.4): z = (1, a, a^2, ...) mod n,
//!   for a given a, or the a in 1..=n/2 that minimizes the worst-case error P_2 of the
//!   weighted Korobov space with alpha = 2 (Sloan & Joe eq. 5.9): P_2(z) = -1 + (1/n)
//!   sum_i prod_j (1 + 2 pi^2 B_2({i z_j / n})), B_2(x) = x^2 - x + 1/6. The search costs
//!   n^2 d / 2, so it is offered up to n = 2^14 and its result is remembered per (n, d).

use std::ops::RangeInclusive;
use std::sync::Mutex;

use super::registry::{ANY, SamplerEntry};
use super::{Fill, Sampler};
use crate::error::{Error, Result};
use crate::registry::About;
use crate::spec::{Default, Kind, ParamSpec};
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
        for (i, p) in out.chunks_exact_mut(2).enumerate() {
            let y = (i as u128 * g as u128 % n as u128) as f64 / n as f64;
            p[0] = wrap(i as f64 / n as f64 + shift[0]);
            p[1] = wrap(y + shift[1]);
        }
        Ok(())
    }
}

/// A Korobov lattice, its a given or searched, optionally shifted.
#[derive(Debug, Clone, Copy)]
pub struct Korobov {
    a: Option<u64>,
    shift: bool,
}

/// The largest n whose a is searched.
const SEARCH_MAX: usize = 1 << 14;

/// Searched generators, per (n, d): the search is deterministic, so remembering it only
/// saves time.
static SEARCHED: Mutex<Vec<((usize, usize), u64)>> = Mutex::new(Vec::new());

/// The generating vector (1, a, a^2, ...) mod n.
fn korobov_vector(a: u64, n: usize, dims: usize) -> Vec<u64> {
    let n = n as u128;
    std::iter::successors(Some(1u128 % n), |z| Some(z * u128::from(a) % n)).take(dims).map(|z| z as u64).collect()
}

/// The worst-case error P_2 of the lattice with generating vector `z` (module docs).
pub fn p2(z: &[u64], n: usize) -> f64 {
    let b2 = |x: f64| x * x - x + 1.0 / 6.0;
    let c = 2.0 * std::f64::consts::PI * std::f64::consts::PI;
    let sum: f64 = (0..n as u128)
        .map(|i| z.iter().map(|&zj| 1.0 + c * b2((i * u128::from(zj) % n as u128) as f64 / n as f64)).product::<f64>())
        .sum();
    sum / n as f64 - 1.0
}

/// The a in 1..=n/2 (all of 1..n for n < 4) with the smallest P_2, the first on ties.
pub fn korobov_search(n: usize, dims: usize) -> u64 {
    if let Some(&(_, a)) = SEARCHED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).iter().find(|(key, _)| *key == (n, dims)) {
        return a;
    }
    let last = if n < 4 { n.saturating_sub(1).max(1) } else { n / 2 };
    let mut best = (f64::INFINITY, 1u64);
    for a in 1..=last as u64 {
        let e = p2(&korobov_vector(a, n, dims), n);
        if e < best.0 {
            best = (e, a);
        }
    }
    SEARCHED.lock().unwrap_or_else(std::sync::PoisonError::into_inner).push(((n, dims), best.1));
    best.1
}

impl Sampler for Korobov {
    fn spec(&self) -> String {
        let name = if self.shift { "lattice.korobov.shift" } else { "lattice.korobov" };
        match self.a {
            Some(a) => format!("{name}:a={a}"),
            None => name.into(),
        }
    }
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }
}

impl Fill for Korobov {
    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        if self.a.is_none() && n > SEARCH_MAX {
            return Err(Error::InvalidCount {
                sampler: self.spec(),
                n,
                dims,
                reason: format!("searching a costs n^2 d / 2: give a=A for n above {SEARCH_MAX}"),
            });
        }
        Ok(())
    }

    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let a = self.a.unwrap_or_else(|| korobov_search(n, dims));
        let z = korobov_vector(a, n, dims);
        let mut rng = seed.rng();
        let shift: Vec<f64> = (0..dims).map(|_| if self.shift { uniform(&mut rng) } else { 0.0 }).collect();
        for (i, p) in out.chunks_exact_mut(dims).enumerate() {
            for ((x, &zj), &u) in p.iter_mut().zip(&z).zip(&shift) {
                *x = wrap((i as u128 * u128::from(zj) % n as u128) as f64 / n as f64 + u);
            }
        }
        Ok(())
    }
}

/// x in [0, 2) taken mod 1.
fn wrap(x: f64) -> f64 {
    if x >= 1.0 { x - 1.0 } else { x }
}

/// Korobov's generator parameter.
const A: ParamSpec = ParamSpec {
    name: "a",
    kind: Kind::Int { min: 1, max: 1 << 32 },
    default: Default::Auto("the a in 1..=n/2 with the smallest P_2 (n up to 2^14)"),
    doc: "generator: z = (1, a, a^2, ...) mod n",
};

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
    SamplerEntry {
        about: About::new("lattice.korobov", "Korobov rank-1 lattice, z = (1, a, a^2, ...) mod n")
            .aliases(&["korobov"])
            .params(&[A])
            .cite(&["korobov1959", "sloan1994"]),
        counts: ANY,
        dims: "any d",
        build: |p| Ok(Box::new(Korobov { a: p.int_or_auto("a"), shift: false })),
    },
    SamplerEntry {
        about: About::new("lattice.korobov.shift", "the Korobov lattice with a random shift mod 1")
            .aliases(&["korobov-shift"])
            .params(&[A])
            .cite(&["korobov1959", "sloan1994", "cranley1976"]),
        counts: ANY,
        dims: "any d",
        build: |p| Ok(Box::new(Korobov { a: p.int_or_auto("a"), shift: true })),
    },
];
