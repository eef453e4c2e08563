//! Rank-1 lattices: point i is frac(i z / n) for a generating vector z (Sloan & Joe 1994),
//! randomized by a random shift mod 1 (Cranley & Patterson 1976): each `.shift` entry is
//! its lattice under the `+shift` stage's own code, so `lattice.shift` and `lattice+shift`
//! are the same bytes.
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
//! (Hickernell 2002) after the shift: `tent=yes` (a wrapper over the shifted lattice).

use rayon::prelude::*;
use std::ops::RangeInclusive;
use std::sync::{Arc, Mutex, PoisonError};

use crate::construct::{Counts, Randomization};
use crate::sampler::randomize::{randomized_families, shift};
use crate::sampler::registry::SamplerEntry;
use crate::construct::cbc::Weights;
use crate::construct::cbc;
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::spec::{Default, Kind, ParamSpec};
use crate::seed::Seed;

/// The Fibonacci lattice.
#[derive(Debug, Clone, Copy)]
pub struct Fibonacci;

/// The Fibonacci numbers 1, 2, 3, 5, 8, ... up to 2^32, each with its predecessor.
fn fibonacci() -> impl Iterator<Item = (usize, usize)> + Clone {
    std::iter::successors(Some((1usize, 1usize)), |&(f, g)| Some((f + g, f))).take_while(|&(f, _)| f <= 1 << 32)
}

impl Construction for Fibonacci {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Fibonacci {
    fn fill(&self, n: usize, _dims: usize, _seed: Seed, out: &mut [f64]) -> Result<()> {
        let (_, g) = fibonacci().find(|&(f, _)| f == n).expect("a checked count");
        for (i, p) in out.chunks_exact_mut(2).enumerate() {
            p[0] = i as f64 / n as f64;
            p[1] = (i as u128 * g as u128 % n as u128) as f64 / n as f64;
        }
        Ok(())
    }
}

/// A Korobov lattice, its a given or searched.
#[derive(Debug, Clone, Copy)]
pub struct Korobov {
    a: Option<u64>,
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

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let n = shape.n();
        if self.a.is_none() && n > SEARCH_MAX {
            return Err(shape.invalid_count(format!("searching a costs n^2 d / 2: give a=A for n above {SEARCH_MAX}")));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let (n, dims) = (shape.n(), shape.dims());
        let a = self.a.unwrap_or_else(|| korobov_search(n, dims));
        Ok(Box::new(Rank1 { z: korobov_vector(a, n, dims), order: Order::Float(n) }))
    }
}

/// A CBC lattice for the set's n.
#[derive(Debug, Clone, Copy)]
pub struct Cbc {
    weights: Weights,
}

impl Construction for Cbc {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=usize::MAX
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let (n, dims) = (shape.n(), shape.dims());
        let z = cbc::construct(n, dims, self.weights, false)?;
        Ok(Box::new(Rank1 { z, order: Order::Fixed(n) }))
    }
}

/// Which points a rank-1 lattice's vector z makes, point i of dimension j:
#[derive(Debug, Clone, Copy)]
enum Order {
    /// frac(i z_j / n) in floating point (Korobov);
    Float(usize),
    /// frac(i z_j / n) as an exact 64-bit binary fraction (CBC);
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
}

/// The coordinate of the fixed-point fraction `x`: its 53 leading bits.
#[inline]
fn finish(x: u64) -> f64 {
    (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
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
    fn fill(&self, _seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let dims = self.z.len();
        for (i, p) in out.chunks_exact_mut(dims).enumerate() {
            for (x, &zj) in p.iter_mut().zip(&self.z) {
                *x = match self.order {
                    Order::Float(n) => (i as u128 * u128::from(zj) % n as u128) as f64 / n as f64,
                    _ => finish(self.fixed(i as u64, zj)),
                };
            }
        }
        progress.advance(1)
    }

    fn access(&self, _seed: Seed) -> Option<Box<dyn Access + '_>> {
        matches!(self.order, Order::Radical).then(|| Box::new(Sequence { rank1: self }) as _)
    }

    fn sample_at(&self, _seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        matches!(self.order, Order::Radical).then(|| Ok(finish(self.fixed(index, self.z[dim]))))
    }
}

/// Random access to the embedded lattice sequence.
#[derive(Debug)]
struct Sequence<'a> {
    rank1: &'a Rank1,
}

impl Access for Sequence<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(finish(self.rank1.fixed(index, self.rank1.z[dim])))
    }
}

/// The baker's (tent) transform x -> 1 - |2x - 1| (Hickernell 2002) of a lattice's points,
/// after its shift where it has one: `tent=yes`.
#[derive(Debug)]
struct Tent {
    inner: Box<dyn Construction>,
}

/// The tent transform of a coordinate, kept below 1.
#[inline]
fn tent(x: f64) -> f64 {
    (1.0 - (2.0 * x - 1.0).abs()).min(crate::numeric::BELOW_ONE)
}

impl Construction for Tent {
    fn dims(&self) -> RangeInclusive<usize> {
        self.inner.dims()
    }
    fn check_count(&self, shape: &Shape) -> Result<()> {
        self.inner.check_count(shape)
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        Ok(Box::new(Tented(self.inner.prepare(shape)?)))
    }
}

/// A prepared lattice whose points are then tent-transformed.
struct Tented(Box<dyn Prepared>);

impl Prepared for Tented {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        self.0.fill(seed, out, progress)?;
        out.iter_mut().for_each(|x| *x = tent(*x));
        Ok(())
    }
    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(TentedAccess(self.0.access(seed)?)))
    }
    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        Some(self.0.sample_at(seed, index, dim)?.map(tent))
    }
}

/// Random access to a tent-transformed sequence.
#[derive(Debug)]
struct TentedAccess<'a>(Box<dyn Access + 'a>);

impl Access for TentedAccess<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        self.0.sample(index, dim).map(tent)
    }
}

/// A lattice under the entry's randomization (the `+shift` stage's code for `.shift`), then
/// its tent where `tent=yes`: the shift comes before the tent.
fn randomized(lattice: Box<dyn Construction>, tented: bool, randomization: Randomization) -> Box<dyn Construction> {
    let shifted = shift::applied(randomization, |_| lattice);
    if tented { Box::new(Tent { inner: shifted }) } else { shifted }
}

/// Whether a lattice's parameters ask for the tent.
fn tented(p: &crate::spec::Params) -> bool {
    p.word("tent") == "yes"
}

/// The embedded lattice sequence, its vector from a file or constructed.
#[derive(Debug)]
pub struct Embedded {
    vector: Vector,
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
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let z = match &self.vector {
            Vector::Constructed(memo) => memo.first(shape.dims())?,
            Vector::File(z) => z[..shape.dims()].to_vec(),
        };
        Ok(Box::new(Rank1 { z, order: Order::Radical }))
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

fn cbc_sampler(p: &crate::spec::Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(randomized(Box::new(Cbc { weights: weights(p) }), tented(p), randomization))
}

fn embedded_sampler(p: &crate::spec::Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    let vector = match p.path_or_auto("vector") {
        Some(path) => {
            let text = crate::io::read_small_text(path, crate::io::SPEC_FILE_MAX)?;
            Vector::File(Arc::new(parse_vector(&text, path)?))
        }
        None => Vector::Constructed(Constructed::new(weights(p))),
    };
    Ok(randomized(Box::new(Embedded { vector }), tented(p), randomization))
}

fn fibonacci_sampler(_: &crate::spec::Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(randomized(Box::new(Fibonacci), false, randomization))
}

fn korobov_sampler(p: &crate::spec::Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(randomized(Box::new(Korobov { a: p.int_or_auto("a") }), false, randomization))
}

/// The Fibonacci counts.
const FIBONACCI_COUNTS: Counts =
    Counts::Listed { rule: "n must be a Fibonacci number", list: |_, _| Box::new(fibonacci().map(|(f, _)| f)) };

/// The counts of the fast CBC construction: n a prime or a power of 2 up to 2^24 (the
/// nearest ones to n lie within a prime gap, under 200 below 2^24, so the list starts 1000
/// below n).
const CBC_COUNTS: Counts = Counts::Listed {
    rule: "the fast CBC needs n a prime or a power of 2 up to 2^24",
    list: |_, near| Box::new((near.min(cbc::MAX_N + 1).saturating_sub(1000)..=cbc::MAX_N).filter(|&k| cbc::supports(k))),
};

/// The samplers this file registers: each lattice and its shift.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!(
    {
        family: "lattice",
        summary: "embedded rank-1 lattice sequence, frac(phi_2(i) z), nets of 2^k points",
        aliases: ["rank1", "lattice-sequence"],
        params: &[VECTOR, GAMMA, DECAY, TENT],
        counts: Counts::Any("lattices at powers of 2"),
        dims: "any d (a file's: its dimensions)",
        cite: ["hickernell2000", "cools2006", "hickernell2002"],
        build: embedded_sampler,
        randomizations: [shift],
    },
    {
        family: "lattice.cbc",
        summary: "rank-1 lattice, z by fast component-by-component construction",
        aliases: ["cbc"],
        params: &[GAMMA, DECAY, TENT],
        counts: CBC_COUNTS,
        dims: "any d",
        cite: ["nuyens2006", "sloan1994", "hickernell2002"],
        build: cbc_sampler,
        randomizations: [shift],
    },
    {
        family: "lattice.fibonacci",
        summary: "Fibonacci lattice (i/n, frac(i F_(m-1)/n)), n = F_m",
        aliases: ["fibonacci"],
        params: &[],
        counts: FIBONACCI_COUNTS,
        dims: "2",
        cite: ["sloan1994"],
        build: fibonacci_sampler,
        randomizations: [shift],
    },
    {
        family: "lattice.korobov",
        summary: "Korobov rank-1 lattice, z = (1, a, a^2, ...) mod n",
        aliases: ["korobov"],
        params: &[A],
        counts: Counts::Rule("any n (searching a, with a = auto: n <= 2^14)"),
        dims: "any d",
        cite: ["korobov1959", "sloan1994"],
        build: korobov_sampler,
        randomizations: [shift],
    },
);

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
