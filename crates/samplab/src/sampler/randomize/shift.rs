//! The Cranley–Patterson shift (Cranley & Patterson 1976) as a stage on any set: every
//! coordinate of every point moved by one uniform offset per axis, modulo 1. The shift is
//! done in 64-bit fixed point: a coordinate x becomes the 53 leading bits of
//! (x 2^64 + u_j) mod 2^64, u_j the axis's 64 random bits, so the shifted set is exactly a
//! toroidal translate of the set (a floating-point x + u rounds, and may round up to 1).
//! A shifted sequence keeps its random access: `sobol+shift` streams and extends.
//!
//! Written after any spec: `lattice.cbc+shift`, `file:path=best.npy+shift` (randomizing a
//! saved, optimized set, each realization by its own shift).

use std::ops::RangeInclusive;

use super::StageEntry;
use crate::construct::Randomization;
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::sampler::{Access, Construction, Prepared, Shape, Stream};
use crate::seed::{Rng, Seed};

/// A construction whose sets are shifted: the `+shift` stage, and every `family.shift`
/// entry ([`over`]).
#[derive(Debug)]
struct Shift {
    inner: Box<dyn Construction>,
}

/// `inner`'s sets under a Cranley–Patterson shift: the one code path of `SPEC+shift` and of
/// the families' `.shift` entries (`randomized_families!`), so `lattice.shift` and
/// `lattice+shift` are the same bytes.
pub(crate) fn over(inner: Box<dyn Construction>) -> Box<dyn Construction> {
    Box::new(Shift { inner })
}

/// The construction `make` gives for an entry's `randomization`, where
/// `Randomization::Shift` is the plain construction under [`over`]: a family's `.shift`
/// entry (`randomized_families!`) through the stage's code, so no family shifts its own
/// points.
pub(crate) fn applied(
    randomization: Randomization,
    make: impl FnOnce(Randomization) -> Box<dyn Construction>,
) -> Box<dyn Construction> {
    if randomization == Randomization::Shift { over(make(Randomization::None)) } else { make(randomization) }
}

/// `x` in [0, 1) shifted by the 64-bit fraction `u`, mod 1, to 53 bits.
#[inline]
fn shifted(x: f64, u: u64) -> f64 {
    // x < 1 has at most 53 significant bits: x 2^64 is exact down to 2^-64 of the unit
    let fixed = (x * 18_446_744_073_709_551_616.0) as u64;
    (fixed.wrapping_add(u) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// The offsets' stream of a seed: axis j's offset is its j-th draw.
fn offsets(seed: Seed) -> Rng {
    seed.derive_str("shift").rng()
}

fn next(rng: &mut Rng) -> u64 {
    rand_core::Rng::next_u64(rng)
}

/// Axis `dim`'s offset alone: the stream's draw `dim`.
fn offset(seed: Seed, dim: usize) -> u64 {
    let mut rng = offsets(seed);
    for _ in 0..dim {
        next(&mut rng);
    }
    next(&mut rng)
}

impl Construction for Shift {
    fn dims(&self) -> RangeInclusive<usize> {
        self.inner.dims()
    }
    fn check_count(&self, shape: &Shape) -> Result<()> {
        self.inner.check_count(shape)
    }
    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        Ok(Box::new(Shifted { inner: self.inner.prepare(shape)?, dims: shape.dims() }))
    }
}

/// A planned sampler whose sets are then shifted.
struct Shifted {
    inner: Box<dyn Prepared>,
    dims: usize,
}

impl Prepared for Shifted {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        self.inner.fill(seed, out, progress)?;
        // axis by axis, each drawing its offset in turn: no buffer
        let mut rng = offsets(seed);
        for d in 0..self.dims {
            let u = next(&mut rng);
            for p in out.chunks_exact_mut(self.dims) {
                p[d] = shifted(p[d], u);
            }
        }
        Ok(())
    }
    fn units(&self) -> u64 {
        self.inner.units()
    }
    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        let inner = self.inner.access(seed)?;
        let mut rng = offsets(seed);
        Some(Box::new(ShiftedAccess { inner, offsets: (0..self.dims).map(|_| next(&mut rng)).collect() }))
    }
    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        let value = self.inner.sample_at(seed, index, dim)?;
        let offset = offset(seed, dim);
        Some(value.map(|x| shifted(x, offset)))
    }
    fn stream(&self, seed: Seed) -> Option<Box<dyn Stream + '_>> {
        let inner = self.inner.stream(seed)?;
        let mut rng = offsets(seed);
        Some(Box::new(ShiftedStream { inner, offsets: (0..self.dims).map(|_| next(&mut rng)).collect() }))
    }
}

/// Random access to a shifted sequence.
#[derive(Debug)]
struct ShiftedAccess<'a> {
    inner: Box<dyn Access + 'a>,
    offsets: Vec<u64>,
}

impl Access for ShiftedAccess<'_> {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        Ok(shifted(self.inner.sample(index, dim)?, self.offsets[dim]))
    }
}

/// A shifted set made chunk by chunk.
struct ShiftedStream<'a> {
    inner: Box<dyn Stream + 'a>,
    offsets: Vec<u64>,
}

impl Stream for ShiftedStream<'_> {
    fn next(&mut self, out: &mut [f64]) -> Result<()> {
        self.inner.next(out)?;
        for p in out.chunks_exact_mut(self.offsets.len()) {
            for (x, &u) in p.iter_mut().zip(&self.offsets) {
                *x = shifted(*x, u);
            }
        }
        Ok(())
    }
}

/// The stage this file registers.
pub(crate) static STAGES: &[StageEntry] = &[StageEntry {
    about: About::new(
        "shift",
        "Cranley-Patterson shift of any set: one uniform offset per axis, mod 1, in 64-bit fixed point",
    )
    .aliases(&["cranley-patterson", "rotation"])
    .cite(&["cranley1976"]),
    build: |inner, _| Ok(over(Box::new(super::Before(inner)))),
}];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_shift_is_exact_in_fixed_point_and_stays_below_one() {
        // a coordinate just below one shifted by almost a whole period wraps to just below
        // it again, exactly; a float sum would round to 1.0 or lose the low bits
        let below = 1.0 - f64::EPSILON / 2.0;
        assert_eq!(shifted(below, u64::MAX - 2047), below - f64::EPSILON / 2.0);
        assert_eq!(shifted(0.25, 1 << 62), 0.5);
        assert_eq!(shifted(0.75, 1 << 62), 0.0);
        // the differences between points are kept exactly, mod 1 (a translate of the set)
        let xs = [0.0, 0.125, 0.3, 0.999];
        for u in [3u64, 1 << 63, 0xdead_beef_1234_5678] {
            let ys: Vec<f64> = xs.iter().map(|&x| shifted(x, u)).collect();
            assert!(ys.iter().all(|y| (0.0..1.0).contains(y)));
            for (i, j) in [(0, 1), (1, 2), (2, 3)] {
                let d = (ys[j] - ys[i]).rem_euclid(1.0);
                assert!((d - (xs[j] - xs[i])).abs() < 1e-15, "{u}: {d}");
            }
        }
    }
}
