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
//! - CBC lattices (`lattice.cbc`): z by the fast component-by-component construction of
//!   Nuyens & Cools (2006) for product weights, n a prime or a power of 2 ([`crate::construct::cbc`]).
//! - The embedded lattice sequence (`lattice`): point i is frac(phi_2(i) z), phi_2 the
//!   radical inverse in base 2, so every prefix of 2^k points is the lattice of 2^k points
//!   (Hickernell, Hong, L'Ecuyer & Lemieux 2000); z from a file (`vector=FILE`) or by the
//!   embedded fast CBC of Cools, Kuo & Nuyens (2006) for up to 2^20 points.
//!
//! The CBC lattice and the sequence take the baker's (tent) transform x -> 1 - |2x - 1|
//! (Hickernell 2002) after the shift: `tent=yes`.

use rayon::prelude::*;
use std::ops::RangeInclusive;
use std::sync::{Arc, Mutex, PoisonError};

use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::construct::cbc::Weights;
use crate::construct::cbc;
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::About;
use crate::spec::{Default, Kind, ParamSpec};
use crate::seed::{Seed, uniform};

/// The Fibonacci lattice, optionally shifted.
#[derive(Debug, Clone, Copy)]
pub struct Fibonacci {
    shift: bool,
}

/// The Fibonacci numbers 1, 2, 3, 5, 8, ... up to 2^32, each with its predecessor.
fn fibonacci() -> impl Iterator<Item = (usize, usize)> + Clone {
    std::iter::successors(Some((1usize, 1usize)), |&(f, g)| Some((f + g, f))).take_while(|&(f, _)| f <= 1 << 32)
}

impl Construction for Fibonacci {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        Ok(crate::sampler::from_fill(move |seed, out| self.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Fibonacci {
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

/// The generating vector (1, a, a^2, ...) mod n.
fn korobov_vector(a: u64, n: usize, dims: usize) -> Vec<u64> {
    let n = n as u128;
    std::iter::successors(Some(1u128 % n), |z| Some(z * u128::from(a) % n)).take(dims).map(|z| z as u64).collect()
}

/// The worst-case error P_2 of the lattice with generating vector `z` (module docs).
pub fn p2(z: &[u64], n: usize) -> f64 {
    let b2 = |x: f64| x * x - x + 1.0 / 6.0;
    let c = 2.0 * std::f64::consts::PI * std::f64::consts::PI;
    let m = n as u64;
    // i z_j mod n, stepped from one i to the next by z_j mod n (no products, no division;
    // n = 0 sums nothing)
    let step: Vec<u64> = z.iter().map(|&zj| zj.checked_rem(m).unwrap_or(0)).collect();
    let mut r = vec![0u64; z.len()];
    let sum: f64 = (0..n)
        .map(|_| {
            let term = r.iter().map(|&rj| 1.0 + c * b2(rj as f64 / n as f64)).product::<f64>();
            for (rj, &s) in r.iter_mut().zip(&step) {
                *rj = if *rj >= m - s { *rj - (m - s) } else { *rj + s };
            }
            term
        })
        .sum();
    sum / n as f64 - 1.0
}

/// The a in 1..=n/2 (all of 1..n for n < 4) with the smallest P_2, the first on ties (the
/// candidates in parallel; the least (P_2, a) is the same whatever the threads).
pub fn korobov_search(n: usize, dims: usize) -> u64 {
    let last = if n < 4 { n.saturating_sub(1).max(1) } else { n / 2 };
    let least = |x: (f64, u64), y: (f64, u64)| if y.0 < x.0 || (y.0 == x.0 && y.1 < x.1) { y } else { x };
    (1..=last as u64)
        .into_par_iter()
        .map(|a| (p2(&korobov_vector(a, n, dims), n), a))
        .filter(|e| !e.0.is_nan())
        .reduce(|| (f64::INFINITY, 1), least)
        .1
}

impl Construction for Korobov {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }

    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        if self.a.is_none() && n > SEARCH_MAX {
            return Err(Error::InvalidCount {
                sampler: String::new(),
                n,
                dims,
                reason: format!("searching a costs n^2 d / 2: give a=A for n above {SEARCH_MAX}"),
            });
        }
        Ok(())
    }

    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        let (n, dims) = (shape.n(), shape.dims());
        let a = self.a.unwrap_or_else(|| korobov_search(n, dims));
        Ok(Box::new(Rank1 { z: korobov_vector(a, n, dims), order: Order::Float(n), shift: self.shift, tent: false }))
    }
}

/// A CBC lattice for the set's n, optionally shifted and tent-transformed.
#[derive(Debug, Clone, Copy)]
pub struct Cbc {
    weights: Weights,
    shift: bool,
    tent: bool,
}

impl Construction for Cbc {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }

    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        let (n, dims) = (shape.n(), shape.dims());
        let z = cbc::construct(n, dims, self.weights, false)?;
        Ok(Box::new(Rank1 { z, order: Order::Fixed(n), shift: self.shift, tent: self.tent }))
    }
}

/// Which points a rank-1 lattice's vector z makes, point i of dimension j:
#[derive(Debug, Clone, Copy)]
enum Order {
    /// frac(i z_j / n) in floating point, shifted in floating point (Korobov);
    Float(usize),
    /// frac(i z_j / n) as an exact 64-bit binary fraction, shifted in fixed point (CBC);
    Fixed(usize),
    /// frac(phi_2(i) z_j), phi_2(i) 2^64 being i's bits reversed, in fixed point (the
    /// embedded sequence: with n = 2^m and i < n the lattice point k z / n of k = phi_2(i) n).
    Radical,
}

/// A rank-1 lattice prepared for a count and dimension: its generating vector.
#[derive(Debug)]
struct Rank1 {
    z: Vec<u64>,
    order: Order,
    shift: bool,
    tent: bool,
}

/// The seed's shifts of `dims` dimensions in turn, one 64-bit draw each, from the seed's
/// one stream (zero when not shifted).
fn fixed_shifts(seed: Seed, dims: usize, shift: bool) -> impl Iterator<Item = u64> {
    let mut rng = seed.rng();
    (0..dims).map(move |_| if shift { rand_core::Rng::next_u64(&mut rng) } else { 0 })
}

/// The coordinate of the fixed-point fraction `x`: shifted mod 1 by `shift` (exactly, in
/// fixed point), then tent-transformed.
#[inline]
fn finish(x: u64, shift: u64, tent: bool) -> f64 {
    let x = (x.wrapping_add(shift) >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    if tent { (1.0 - (2.0 * x - 1.0).abs()).min(crate::numeric::BELOW_ONE) } else { x }
}

impl Rank1 {
    /// Point i's fixed-point fraction in the dimension of z_j (Order::Fixed and Radical).
    #[inline]
    fn fixed(&self, i: u64, zj: u64) -> u64 {
        match self.order {
            Order::Fixed(n) => (((u128::from(i) * u128::from(zj) % n as u128) << 64) / n as u128) as u64,
            _ => i.reverse_bits().wrapping_mul(zj),
        }
    }
}

impl Prepared for Rank1 {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        // point by point over a block of up to BLOCK dimensions at a time, each block's
        // shifts drawn in turn into the stack: one pass over the output per block, where a
        // pass per dimension went d times over memory, and no buffer on the heap
        const BLOCK: usize = 64;
        let dims = self.z.len();
        // the seed's one stream: a uniform per dimension (Float) or its 64 bits (fixed point)
        let mut rng = seed.rng();
        let mut fixed = fixed_shifts(seed, dims, self.shift);
        for (b, zs) in self.z.chunks(BLOCK).enumerate() {
            let first = b * BLOCK;
            if let Order::Float(n) = self.order {
                let mut shifts = [0.0; BLOCK];
                for u in &mut shifts[..zs.len()] {
                    *u = if self.shift { uniform(&mut rng) } else { 0.0 };
                }
                for (i, p) in out.chunks_exact_mut(dims).enumerate() {
                    for ((x, &zj), &u) in p[first..first + zs.len()].iter_mut().zip(zs).zip(&shifts) {
                        *x = wrap((i as u128 * u128::from(zj) % n as u128) as f64 / n as f64 + u);
                    }
                }
            } else {
                let mut shifts = [0u64; BLOCK];
                for (s, draw) in shifts.iter_mut().zip(fixed.by_ref().take(zs.len())) {
                    *s = draw;
                }
                for (i, p) in out.chunks_exact_mut(dims).enumerate() {
                    for ((x, &zj), &shift) in p[first..first + zs.len()].iter_mut().zip(zs).zip(&shifts) {
                        *x = finish(self.fixed(i as u64, zj), shift, self.tent);
                    }
                }
            }
        }
        progress.advance(1)
    }

    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        matches!(self.order, Order::Radical)
            .then(|| Box::new(Sequence { rank1: self, shifts: fixed_shifts(seed, self.z.len(), self.shift).collect() }) as _)
    }
}

/// Random access to the embedded lattice sequence for one seed: its shifts.
#[derive(Debug)]
struct Sequence<'a> {
    rank1: &'a Rank1,
    shifts: Vec<u64>,
}

impl Access for Sequence<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(finish(self.rank1.fixed(index, self.rank1.z[dim]), self.shifts[dim], self.rank1.tent))
    }
}

/// The embedded lattice sequence, its vector from a file or constructed.
#[derive(Debug)]
pub struct Embedded {
    vector: Vector,
    shift: bool,
    tent: bool,
}

/// The embedded vector for the default weights (gamma_j = j^-2), its first 128 components
/// as the construction makes them, stored: the construction for 2^20 points takes about
/// 0.05 s per component (1.4 s for 32, on one thread of this 2-core machine, 2026-11-27).
const STORED: &str = include_str!("../../../data/lattice-cbc-2_20-decay2.txt");

/// The default weights of the embedded constructions (`gamma` and `decay`'s defaults).
const DEFAULT_WEIGHTS: Weights = Weights { first: 1.0, decay: 2.0 };

/// The embedded fast CBC vector for 2^20 points with these weights, kept by the sampler
/// that owns it (never by the process): the longest made so far. Construction is component
/// by component, so the vector for d dimensions is the first d components of any longer
/// one, and a cubature that plans n = 1024, 2048, ... on one sampler pays it once.
#[derive(Debug)]
struct Constructed {
    weights: Weights,
    longest: Mutex<Arc<Vec<u64>>>,
}

impl Constructed {
    fn new(weights: Weights) -> Constructed {
        Constructed { weights, longest: Mutex::default() }
    }

    /// The first `dims` components.
    ///
    /// The memo is locked only to read and to store, never across a construction: the
    /// construction runs on rayon's pool, and a caller that held the lock while it waited
    /// for the pool deadlocked when the pool's threads were themselves waiting for the lock
    /// (a cubature on a lattice rule run from inside a parallel loop: the test suite hung
    /// so). Two plans may then construct the same vector side by side; either result is
    /// the same, and the longer is kept.
    fn first(&self, dims: usize) -> Result<Vec<u64>> {
        let memo = || self.longest.lock().unwrap_or_else(PoisonError::into_inner);
        let mut z = Arc::clone(&memo());
        if z.is_empty() && self.weights == DEFAULT_WEIGHTS {
            z = Arc::new(parse_vector(STORED, "data/lattice-cbc-2_20-decay2.txt")?);
        }
        if z.len() < dims {
            z = Arc::new(cbc::construct(1 << EMBEDDED_M, dims, self.weights, true)?);
        }
        let mut kept = memo();
        if kept.len() < z.len() {
            *kept = Arc::clone(&z);
        }
        Ok(z[..dims].to_vec())
    }
}

/// Where an embedded sequence's generating vector comes from.
#[derive(Debug)]
enum Vector {
    /// The embedded fast CBC for 2^20 points.
    Constructed(Constructed),
    /// Read from a file.
    File(Arc<Vec<u64>>),
}

/// log2 of the point count the constructed vectors are made for.
const EMBEDDED_M: u32 = 20;

impl Construction for Embedded {
    fn dims(&self) -> RangeInclusive<usize> {
        match &self.vector {
            Vector::Constructed(_) => 1..=usize::MAX,
            Vector::File(z) => 1..=z.len(),
        }
    }
    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        let z = match &self.vector {
            Vector::Constructed(memo) => memo.first(shape.dims())?,
            Vector::File(z) => z[..shape.dims()].to_vec(),
        };
        Ok(Box::new(Rank1 { z, order: Order::Radical, shift: self.shift, tent: self.tent }))
    }
}

/// Read a generating vector in the LDData lattice format: `#` comments; the dimensions s
/// and the largest point count n (a power of 2), one per line; then z_1 .. z_s, one per line.
///
/// # Errors
/// A malformed file, with its line.
pub fn parse_vector(text: &str, source: &str) -> Result<Vec<u64>> {
    let bad = |line: usize, reason: String| Error::Parse { location: format!("{source}:{line}"), reason };
    let mut numbers = Vec::new();
    for (line, l) in text.lines().enumerate().map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim())) {
        if !l.is_empty() {
            numbers.push((line, l.parse::<u64>().map_err(|_| bad(line, format!("{} is not a whole number", crate::error::excerpt(l))))?));
        }
    }
    let [(_, dims), (line, n), ..] = numbers[..] else {
        return Err(bad(0, "the file ends before its dimensions and point count".into()));
    };
    if !n.is_power_of_two() {
        return Err(bad(line, format!("the point count {n} is not a power of 2")));
    }
    let z: Vec<u64> = numbers[2..].iter().map(|&(_, z)| z).collect();
    if z.len() as u64 != dims || dims == 0 {
        return Err(bad(0, format!("{} components where the header announces {dims}", z.len())));
    }
    if let Some(&(line, zj)) = numbers[2..].iter().find(|(_, zj)| *zj >= n) {
        return Err(bad(line, format!("component {zj} is not below the point count {n}")));
    }
    Ok(z)
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

/// The product weights' decay of the CBC constructions.
const DECAY: ParamSpec = ParamSpec {
    name: "decay",
    kind: Kind::Real { min: 0.0, max: 16.0 },
    default: Default::Number(2.0),
    doc: "product weights gamma_j = gamma j^-decay of the worst-case error the construction minimizes",
};

/// The product weights' scale of the CBC constructions.
const GAMMA: ParamSpec = ParamSpec {
    name: "gamma",
    kind: Kind::Real { min: 1e-6, max: 1e6 },
    default: Default::Number(1.0),
    doc: "the first weight gamma_1 (gamma=0.7,decay=0 is Lattice Builder's product:0.7)",
};

fn weights(p: &crate::spec::Params) -> Weights {
    Weights { first: p.real("gamma"), decay: p.real("decay") }
}

/// The baker's transform option.
const TENT: ParamSpec = ParamSpec {
    name: "tent",
    kind: Kind::Choice(&["no", "yes"]),
    default: Default::Word("no"),
    doc: "apply the baker's (tent) transform 1 - |2x - 1| after the shift",
};

/// The embedded sequence's vector file.
const VECTOR: ParamSpec = ParamSpec {
    name: "vector",
    kind: Kind::Path,
    default: Default::Auto("the embedded fast CBC for 2^20 points (weights gamma j^-decay)"),
    doc: "a generating vector in the LDData lattice format (docs/guide/cli.md: lattice generating vectors)",
};

fn cbc_sampler(p: &crate::spec::Params, shift: bool) -> Result<Box<dyn Construction>> {
    Ok(Box::new(Cbc { weights: weights(p), shift, tent: p.word("tent") == "yes" }))
}

fn embedded_sampler(p: &crate::spec::Params, shift: bool) -> Result<Box<dyn Construction>> {
    let vector = match p.path_or_auto("vector") {
        Some(path) => {
            let text = crate::io::read_small_text(path, crate::io::SPEC_FILE_MAX)?;
            Vector::File(Arc::new(parse_vector(&text, path)?))
        }
        None => Vector::Constructed(Constructed::new(weights(p))),
    };
    Ok(Box::new(Embedded { vector, shift, tent: p.word("tent") == "yes" }))
}

/// The counts of the fast CBC construction: n a prime or a power of 2 up to 2^24 (the
/// nearest ones to n lie within a prime gap, under 200 below 2^24, so the list starts 1000
/// below n).
const CBC_COUNTS: Counts = Counts::Listed {
    rule: "the fast CBC needs n a prime or a power of 2 up to 2^24",
    list: |_, near| Box::new((near.min(cbc::MAX_N + 1).saturating_sub(1000)..=cbc::MAX_N).filter(|&k| cbc::supports(k))),
};

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("lattice", "embedded rank-1 lattice sequence, frac(phi_2(i) z), nets of 2^k points").terse()
            .aliases(&["rank1", "lattice-sequence"])
            .params(&[VECTOR, GAMMA, DECAY, TENT])
            .cite(&["hickernell2000", "cools2006", "hickernell2002"]),
        counts: Counts::Any("lattices at powers of 2"),
        randomized: false,
        dims: "any d (a file's: its dimensions)",
        build: |p| embedded_sampler(p, false),
    },
    SamplerEntry {
        about: About::new("lattice.shift", "the embedded lattice sequence with a random shift mod 1").terse()
            .aliases(&["lattice-shift"])
            .params(&[VECTOR, GAMMA, DECAY, TENT])
            .cite(&["hickernell2000", "cools2006", "cranley1976"]),
        counts: Counts::Any("lattices at powers of 2"),
        randomized: true,
        dims: "any d (a file's: its dimensions)",
        build: |p| embedded_sampler(p, true),
    },
    SamplerEntry {
        about: About::new("lattice.cbc", "rank-1 lattice, z by fast component-by-component construction").terse()
            .aliases(&["cbc"])
            .params(&[GAMMA, DECAY, TENT])
            .cite(&["nuyens2006", "sloan1994", "hickernell2002"]),
        counts: CBC_COUNTS,
        randomized: false,
        dims: "any d",
        build: |p| cbc_sampler(p, false),
    },
    SamplerEntry {
        about: About::new("lattice.cbc.shift", "the CBC lattice with a random shift mod 1").terse()
            .aliases(&["cbc-shift"])
            .params(&[GAMMA, DECAY, TENT])
            .cite(&["nuyens2006", "sloan1994", "cranley1976"]),
        counts: CBC_COUNTS,
        randomized: true,
        dims: "any d",
        build: |p| cbc_sampler(p, true),
    },
    SamplerEntry {
        about: About::new("lattice.fibonacci", "Fibonacci lattice (i/n, frac(i F_(m-1)/n)), n = F_m").terse()
            .aliases(&["fibonacci"])
            .cite(&["sloan1994"]),
        counts: Counts::Listed { rule: "n must be a Fibonacci number", list: |_, _| Box::new(fibonacci().map(|(f, _)| f)) },
        randomized: false,
        dims: "2",
        build: |_| Ok(Box::new(Fibonacci { shift: false })),
    },
    SamplerEntry {
        about: About::new("lattice.fibonacci.shift", "the Fibonacci lattice with a random shift mod 1").terse()
            .aliases(&["fibonacci-shift"])
            .cite(&["sloan1994", "cranley1976"]),
        counts: Counts::Listed { rule: "n must be a Fibonacci number", list: |_, _| Box::new(fibonacci().map(|(f, _)| f)) },
        randomized: true,
        dims: "2",
        build: |_| Ok(Box::new(Fibonacci { shift: true })),
    },
    SamplerEntry {
        about: About::new("lattice.korobov", "Korobov rank-1 lattice, z = (1, a, a^2, ...) mod n").terse()
            .aliases(&["korobov"])
            .params(&[A])
            .cite(&["korobov1959", "sloan1994"]),
        counts: Counts::Rule("any n (searching a, with a = auto: n <= 2^14)"),
        randomized: false,
        dims: "any d",
        build: |p| Ok(Box::new(Korobov { a: p.int_or_auto("a"), shift: false })),
    },
    SamplerEntry {
        about: About::new("lattice.korobov.shift", "the Korobov lattice with a random shift mod 1").terse()
            .aliases(&["korobov-shift"])
            .params(&[A])
            .cite(&["korobov1959", "sloan1994", "cranley1976"]),
        counts: Counts::Rule("any n (searching a, with a = auto: n <= 2^14)"),
        randomized: true,
        dims: "any d",
        build: |p| Ok(Box::new(Korobov { a: p.int_or_auto("a"), shift: true })),
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    /// The cache's premise: the embedded CBC vector for d dimensions is the first d
    /// components of the one for more.
    #[test]
    fn constructed_vectors_are_prefixes() {
        let weights = Weights::decaying(2.0);
        let long = cbc::construct(1 << 12, 6, weights, true).unwrap();
        let short = cbc::construct(1 << 12, 3, weights, true).unwrap();
        assert_eq!(short[..], long[..3]);
    }

    #[test]
    fn the_stored_weights_are_the_parameters_defaults() {
        assert!(matches!(GAMMA.default, Default::Number(g) if g == DEFAULT_WEIGHTS.first));
        assert!(matches!(DECAY.default, Default::Number(d) if d == DEFAULT_WEIGHTS.decay));
    }

    #[test]
    #[ignore = "slow tier (run by .ci/run): 128 components of the construction for 2^20 points"]
    fn stored_vector_is_the_construction() {
        let stored = parse_vector(STORED, "stored").unwrap();
        assert_eq!(stored.len(), 128);
        assert_eq!(stored, cbc::construct(1 << EMBEDDED_M, stored.len(), DEFAULT_WEIGHTS, true).unwrap());
    }
}
