//! Any point-set sequence as a pixel sampler: one sequence per pixel, the point set itself
//! under a seed of the pixel's own. `samplab pixels sobol.owen` is `samplab generate
//! sobol.owen` in every pixel: sample i of pixel p in frame f is point i of the set that
//! `samplab generate sobol.owen --seed S` writes, S = [`pixel_seed`]`(seed, p, f)` (set 0 of
//! that seed, `S.derive(0)`, as every realization k is `S.derive(k)`), bit for bit, so a randomization word (`.owen`,
//! `.xor`, `.lms`, `.shift`, `+shift`) means the same scramble through both front doors,
//! and a sequence family added to the point sets is a pixel sampler with no code of its own.

use super::{Family, Film, Keys, PixelSampler, Pixels, independent};
use crate::error::{Error, Result};
use crate::seed::Seed;

/// A point-set sequence planned for a film's samples and dimensions, and the keys that seed
/// each pixel.
#[derive(Debug)]
pub(crate) struct PerPixel {
    plan: crate::sampler::Plan,
    keys: Keys,
}

/// The seed of pixel `pixel` in `frame` under `seed`: a point set served per pixel draws
/// its points as set 0 of this seed (`samplab generate SPEC --seed S`).
pub fn pixel_seed(seed: Seed, pixel: [u32; 2], frame: u32) -> Seed {
    Seed(Keys::new(seed, 0).pixel(pixel, frame))
}

/// The point-set sequence `spec` per pixel (the film checked).
///
/// # Errors
/// An unknown point set, one that is not a sequence with random access, or one that cannot
/// make the film's samples per pixel in its dimensions (the point set's own errors).
pub(crate) fn prepare(spec: &str, film: Film, seed: Seed) -> Result<Pixels> {
    let sampler = crate::sampler::build(spec)?;
    let not_a_sequence = || Error::Infeasible {
        what: sampler.spec().to_string(),
        reason: "a set, not a sequence: a point set serves as a pixel sampler when it is a sequence with random \
                 access (sobol.owen, halton.owen, net.lms, lattice.shift, kronecker, ...)"
            .into(),
    };
    let plan = match sampler.plan(film.spp as usize, film.dims as usize) {
        Ok(plan) => plan,
        // a set that cannot make this count is refused as a set first: no count would do
        Err(e) => {
            let one = sampler.plan(1, film.dims as usize);
            return Err(if one.is_ok_and(|p| p.sample_at(seed, 0, 0).is_none()) { not_a_sequence() } else { e });
        }
    };
    if plan.sample_at(seed, 0, 0).is_none() {
        return Err(not_a_sequence());
    }
    let spec = plan.spec().to_string();
    let inner = Family::from(PerPixel { plan, keys: Keys::new(seed, 0) });
    Ok(Pixels { spec, film, seed, inner, padding: independent::padding(seed) })
}

impl PerPixel {
    /// The seed whose set 0 is the pixel's sequence.
    #[inline]
    fn seed(&self, pixel: [u32; 2], frame: u32) -> Seed {
        Seed(self.keys.pixel(pixel, frame)).derive(0)
    }

    /// Coordinate `dim` of point `index` under `seed`; a key the film does not hold (an
    /// index past the sequence) gives 0.
    #[inline]
    fn value(&self, seed: Seed, index: u32, dim: u32) -> f64 {
        match self.plan.sample_at(seed, u64::from(index), dim as usize) {
            Some(Ok(value)) => value,
            _ => 0.0,
        }
    }
}

impl PixelSampler for PerPixel {
    #[inline]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        self.value(self.seed(pixel, frame), index, dim)
    }

    /// Dimensions `dim .. dim + 4`, the pixel's seed derived once.
    #[inline]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        let seed = self.seed(pixel, frame);
        super::four(|k| self.value(seed, index, dim + k))
    }
}
