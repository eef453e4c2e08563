//! Radical-inverse constructions: the Halton sequence (Halton 1960, bases = the first d
//! primes) and the Hammersley set (Hammersley & Handscomb 1964: i/n, then Halton), with
//! the randomizations of [`Randomization`]; Owen scrambling in base b is the nested affine
//! scramble of [`crate::construct::scramble`]'s `OwenDigits` (one hash per non-zero digit beyond a
//! table of the first digits, the endless zero digits after the index's end in one step).
//!
//! A coordinate in base b is sum_j pi_j(a_j) b^-(j+1) over the base-b digits a_j of the
//! index, for P_b = ceil(53 / log2 b) + 1 digit positions (enough to fill an f64); the
//! digits beyond the index's length are zero, but a scramble maps zero to non-zero, so
//! their contribution (the "tail") is precomputed. The sum is always formed from the
//! least significant position up, so the batch path (an odometer that updates only the
//! digits that change) and the random-access path give identical bits.

use std::ops::RangeInclusive;
use std::borrow::Cow;

use crate::numeric::BELOW_ONE;
use crate::sampler::randomize::{randomized_families, shift};
use crate::construct::{counts::ANY, Counts};
use crate::sampler::registry::SamplerEntry;
use crate::construct::radical::{DigitTable, PRIMES};
use crate::construct::scramble::{OwenDigits, Randomization, owen_scramble_u32};
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::Result;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

/// How many dimensions (primes) the Halton sequence supports.
pub const HALTON_MAX_DIMS: usize = PRIMES.len();

/// The most base-b digits of an index (base 2, 64-bit indices).
const MAX_DIGITS: usize = 64;

/// An odometer over the digits of consecutive indices, keeping the partial sums from the
/// most significant digit down, so that stepping to the next index costs O(1) amortized
/// (its state on the stack).
struct Odometer<'a> {
    table: &'a DigitTable,
    /// The index's digits, least significant first; `len` of them.
    digits: [u32; MAX_DIGITS],
    len: usize,
    /// partial[j] = tail[len] + the digits' terms at positions len-1 down to j.
    partial: [f64; MAX_DIGITS + 1],
}

impl<'a> Odometer<'a> {
    fn new(table: &'a DigitTable, start: u64) -> Self {
        let mut od = Odometer { table, digits: [0; MAX_DIGITS], len: 0, partial: [0.0; MAX_DIGITS + 1] };
        let mut i = start;
        while i != 0 {
            od.digits[od.len] = (i % u64::from(table.base)) as u32;
            i /= u64::from(table.base);
            od.len += 1;
        }
        od.refresh(od.len);
        od
    }

    /// Recompute partial sums for positions below `top` (inclusive of top-1 .. 0).
    fn refresh(&mut self, top: usize) {
        let m = self.len;
        self.partial[m] = self.table.tail(m);
        for j in (0..top.min(m)).rev() {
            self.partial[j] = self.partial[j + 1] + self.table.term(j, self.digits[j]);
        }
    }

    fn value(&self) -> f64 {
        self.partial[0].min(BELOW_ONE)
    }

    fn step(&mut self) {
        let mut j = 0;
        loop {
            if j == self.len {
                self.digits[j] = 1;
                self.len += 1;
                self.refresh(j + 1);
                return;
            }
            self.digits[j] += 1;
            if self.digits[j] < self.table.base {
                self.refresh(j + 1);
                return;
            }
            self.digits[j] = 0;
            j += 1;
        }
    }
}

/// One randomized radical-inverse coordinate in a given base: the plan's identity digit
/// table, or (`.xor`) the seed's permuted one.
#[derive(Debug, Clone)]
struct Coordinate<'a> {
    table: Cow<'a, DigitTable>,
    owen: Option<OwenDigits>,
}

impl<'a> Coordinate<'a> {
    /// Coordinate `dim` over the identity table `plain` (its base) for `seed`; an Owen
    /// scramble tabulates at most `bound` prefixes (the count of points to make: tables are
    /// a cache, the bits do not depend on it).
    fn new(plain: &'a DigitTable, randomization: Randomization, seed: Seed, dim: usize, bound: u64) -> Self {
        let s = seed.derive(dim as u64);
        let base = plain.base;
        Coordinate {
            table: match randomization {
                Randomization::Xor => Cow::Owned(DigitTable::new(base, Some(s))),
                _ => Cow::Borrowed(plain),
            },
            owen: (randomization == Randomization::Owen).then(|| OwenDigits::new(base, s.0, bound)),
        }
    }

    fn value(&self, index: u64) -> f64 {
        match &self.owen {
            Some(owen) => owen.value(index),
            None => self.table.value(index),
        }
    }

}

/// Coordinates filled together: a point's row gets a block's values in one pass, so that a
/// high-dimensional set is written row by row rather than column by column (every row's
/// cache line once per block instead of once per coordinate).
const BLOCK: usize = 8;

/// The values of `coords` (the first `None` ends them) for indices start.., written into
/// columns `first..` of the rows of `dims` of `out`.
fn fill_columns(coords: &[Option<Coordinate<'_>>; BLOCK], start: u64, out: &mut [f64], dims: usize, first: usize) {
    let count = coords.iter().take_while(|c| c.is_some()).count();
    let mut odometers: [Option<Odometer<'_>>; BLOCK] = std::array::from_fn(|j| {
        coords[j].as_ref().filter(|c| c.owen.is_none()).map(|c| Odometer::new(&c.table, start))
    });
    for (i, p) in out.chunks_exact_mut(dims).enumerate() {
        for (j, (c, od)) in coords[..count].iter().zip(&mut odometers).enumerate() {
            let c = c.as_ref().expect("the first count coordinates are there");
            p[first + j] = match (&c.owen, od) {
                (Some(owen), _) => owen.value(start + i as u64),
                (None, Some(od)) => {
                    let v = od.value();
                    od.step();
                    v
                }
                (None, None) => unreachable!("an odometer for every coordinate without Owen scrambling"),
            };
        }
    }
}

/// The identity digit tables of the first `count` prime bases, built by a plan.
fn plain_tables(count: usize) -> Vec<DigitTable> {
    PRIMES[..count].iter().map(|&b| DigitTable::new(b, None)).collect()
}

/// The Halton sequence: coordinate j of point i is the (randomized) radical inverse of i
/// in the j-th prime base. Any n; 1..=1024 dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Halton {
    randomization: Randomization,
}

impl Halton {
    /// A Halton sampler with the given randomization.
    pub fn new(randomization: Randomization) -> Self {
        Halton { randomization }
    }
}

impl Construction for Halton {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=HALTON_MAX_DIMS
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        Ok(Box::new(Radical { randomization: self.randomization, n: shape.n(), tables: plain_tables(shape.dims()) }))
    }
}

/// Radical-inverse coordinates planned for a count: the identity digit table of each base.
#[derive(Debug)]
struct Radical {
    randomization: Randomization,
    n: usize,
    tables: Vec<DigitTable>,
}

impl Radical {
    /// Coordinate `dim` (base `PRIMES[dim]`) for `seed`, Owen tables bounded by `bound`.
    fn coordinate(&self, seed: Seed, dim: usize, bound: u64) -> Coordinate<'_> {
        Coordinate::new(&self.tables[dim], self.randomization, seed, dim, bound)
    }

    /// The Halton coordinates of points 0..n into dimensions `first..` of `out`, a block
    /// of coordinates at a time (on the stack: nothing allocated but a scramble's tables).
    fn fill_from(&self, seed: Seed, out: &mut [f64], dims: usize, first: usize) {
        let count = self.tables.len();
        for d0 in (0..count).step_by(BLOCK) {
            let coords = std::array::from_fn(|j| (d0 + j < count).then(|| self.coordinate(seed, d0 + j, self.n as u64)));
            fill_columns(&coords, 0, out, dims, first + d0);
        }
    }
}

impl Prepared for Radical {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        self.fill_from(seed, out, self.tables.len(), 0);
        progress.advance(1)
    }

    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        // Owen tables sized for the planned count, as a fill's (a cache only: the indices
        // past it walk more digits, to the same bits): the largest, 2^16 entries a
        // dimension, took milliseconds to build where 64 points take microseconds
        let coordinates = (0..self.tables.len()).map(|d| self.coordinate(seed, d, self.n as u64)).collect();
        Some(Box::new(HaltonAccess { coordinates }))
    }

    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        // the one coordinate's keys, its Owen tables at their least (a cache only): a value
        // drawn alone (per pixel) builds no other dimension's
        Some(within(index).map(|()| self.coordinate(seed, dim, 1).value(index)))
    }
}

/// Random access to a randomized Halton sequence: each dimension's digit tables, built once.
#[derive(Debug)]
struct HaltonAccess<'a> {
    coordinates: Vec<Coordinate<'a>>,
}

/// The first index past the digit tables: every base's tables hold at least 53 bits of
/// digits (see [`positions`]), and a double holds no more.
const HALTON_INDICES: u64 = 1 << 53;

/// Whether `index` is a Halton index.
fn within(index: u64) -> Result<()> {
    if index >= HALTON_INDICES {
        return Err(crate::error::Error::Setting {
            name: "index",
            value: index.to_string(),
            reason: "Halton points stop at index 2^53 - 1 (further digits exceed double precision)".into(),
        });
    }
    Ok(())
}

impl Access for HaltonAccess<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        within(index)?;
        Ok(self.coordinates[dim].value(index))
    }
}

/// The Hammersley set of n points: (i/n, Halton coordinates 0..d-2 of i). In base 2 with
/// n = 2^m, the 2D set is a (0,m,2)-net. The first coordinate is randomized on its 32-bit
/// binary expansion (XOR or Owen: the centre of its 2^-32 cell) or by a shift, like the
/// others.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hammersley {
    randomization: Randomization,
}

impl Hammersley {
    /// A Hammersley sampler with the given randomization.
    pub fn new(randomization: Randomization) -> Self {
        Hammersley { randomization }
    }
}

impl Construction for Hammersley {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=HALTON_MAX_DIMS + 1
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let halton = Radical { randomization: self.randomization, n: shape.n(), tables: plain_tables(shape.dims() - 1) };
        Ok(Box::new(Planned { halton }))
    }
}

/// A Hammersley set planned for a count: i/n, then the Halton coordinates' tables.
#[derive(Debug)]
struct Planned {
    halton: Radical,
}

impl Prepared for Planned {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let (n, dims) = (self.halton.n, self.halton.tables.len() + 1);
        let s = seed.derive(u64::MAX);
        let bits = s.bits32();
        for (i, p) in out.chunks_exact_mut(dims).enumerate() {
            let fixed = ((i as u128) << 32).div_euclid(n as u128) as u32;
            p[0] = match self.halton.randomization {
                Randomization::None => i as f64 / n as f64,
                Randomization::Xor => crate::construct::cell_centre(fixed ^ bits),
                Randomization::Owen => crate::construct::cell_centre(owen_scramble_u32(fixed, bits)),
                Randomization::Lms | Randomization::Shift => {
                    unreachable!("Hammersley declares no linear matrix scrambling, and its shift is the +shift stage's")
                }
            };
        }
        self.halton.fill_from(seed, out, dims, 1);
        progress.advance(1)
    }
}

/// The construction of each Halton entry.
fn build_halton(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(shift::applied(randomization, |r| Box::new(Halton::new(r))))
}

/// The construction of each Hammersley entry.
fn build_hammersley(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(shift::applied(randomization, |r| Box::new(Hammersley::new(r))))
}

/// The samplers this file registers: Halton and Hammersley with their randomizations.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!(
    {
        family: "halton",
        summary: "Halton sequence, prime bases",
        aliases: [],
        params: &[],
        counts: ANY,
        dims: "1..=1024",
        cite: ["halton1960"],
        build: build_halton,
        randomizations: [xor, owen, shift],
    },
    {
        family: "hammersley",
        summary: "Hammersley set: i/n, then Halton",
        aliases: [],
        params: &[],
        counts: Counts::AtMost { most: 1 << 32, why: "the first coordinate has 32-bit resolution: at most 2^32 points" },
        dims: "1..=1025",
        cite: ["hammersley1964"],
        build: build_hammersley,
        randomizations: [xor, owen, shift],
    },
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_primes() {
        assert_eq!(&PRIMES[..10], &[2, 3, 5, 7, 11, 13, 17, 19, 23, 29]);
        assert_eq!(PRIMES[1023], 8161);
    }

    #[test]
    fn odometer_equals_random_access_bit_for_bit() {
        for base in [2u32, 3, 7, 8161] {
            for r in [Randomization::None, Randomization::Xor] {
                let plain = DigitTable::new(base, None);
                let c = Coordinate::new(&plain, r, Seed(11), 3, 3000);
                let mut out = vec![0.0; 3000];
                let mut block: [Option<Coordinate>; BLOCK] = std::array::from_fn(|_| None);
                block[0] = Some(c.clone());
                fill_columns(&block, 17, &mut out, 1, 0);
                for (i, v) in out.iter().enumerate() {
                    assert_eq!(v.to_bits(), c.value(17 + i as u64).to_bits(), "base {base} {r:?} index {i}");
                }
            }
        }
    }

    #[test]
    fn owen_prefix_tables_are_a_cache_only() {
        // no table, a small one and the largest give the same bits, far indices included
        for base in [2u32, 3, 5, 61, 8161] {
            let plain = DigitTable::new(base, None);
            let make = |bound| Coordinate::new(&plain, Randomization::Owen, Seed(5), 1, bound);
            let (none, some, most) = (make(1), make(40), make(u64::MAX));
            for i in (0..5000u64).chain([1 << 40, (1 << 40) + 7, (1 << 53) - 1, 3u64.pow(33) + 1]) {
                let v = none.value(i);
                assert!((0.0..1.0).contains(&v));
                assert_eq!(v.to_bits(), some.value(i).to_bits(), "base {base} index {i}");
                assert_eq!(v.to_bits(), most.value(i).to_bits(), "base {base} index {i}");
            }
        }
    }

    #[test]
    fn owen_scrambling_is_nested_with_uniform_permutations() {
        // Owen's definition: indices that share their first k digits share the first k
        // scrambled digits, and digit k of two indices that differ there is a uniformly
        // random ordered pair of distinct digits (chi-square over seeds, 1e-4 level)
        // pairs of digits at position k: 0 against 1, and (base > 2) 1 against b - 1
        for (base, k, da, db) in [(2u32, 3u32, 0, 1), (5, 1, 0, 1), (5, 1, 1, 4), (7, 2, 1, 6)] {
            let b = u64::from(base);
            let (i, j) = (4 + b.pow(k) * da + 2 * b.pow(k + 1), 4 + b.pow(k) * db + b.pow(k + 2)); // equal mod b^k
            let cell = |v: f64, depth: u32| (v * (b.pow(depth)) as f64) as u64;
            let seeds = 4000 * base as usize;
            let plain = DigitTable::new(base, None);
            let mut counts = vec![0u32; (b * b) as usize];
            for s in 0..seeds {
                let c = Coordinate::new(&plain, Randomization::Owen, Seed(s as u64), 0, 64);
                let (x, y) = (c.value(i), c.value(j));
                assert_eq!(cell(x, k), cell(y, k), "base {base}: the first {k} digits must agree");
                let (dx, dy) = (cell(x, k + 1) % b, cell(y, k + 1) % b);
                assert_ne!(dx, dy, "base {base}: digit {k} must differ");
                counts[(dx * b + dy) as usize] += 1;
            }
            let expect = seeds as f64 / (b * (b - 1)) as f64;
            let chi2: f64 = (0..b * b)
                .filter(|c| c / b != c % b)
                .map(|c| (f64::from(counts[c as usize]) - expect).powi(2) / expect)
                .sum();
            // chi-square with b(b-1)-1 degrees of freedom: 1e-4 quantiles 15.1 (1), 43.8 (19), 71.3 (41)
            let limit = match base {
                2 => 15.1,
                5 => 43.8,
                _ => 71.3,
            };
            assert!(chi2 < limit, "base {base} ({da} {db}): chi2 {chi2} {counts:?}");
        }
    }
}
