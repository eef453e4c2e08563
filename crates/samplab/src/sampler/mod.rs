//! Samplers: every strategy of the four papers plus the modern low-discrepancy ones.
//!
//! Three interfaces, because there are three problems:
//! - [`Sampler::generate`]: a batch of `n` points in `d` dimensions for a seed;
//! - [`Sequence::sample`]: random access to coordinate `dim` of point `index` (for the
//!   progressive sequences: Halton, Sobol); the batch form equals it bit for bit;
//! - [`generate_sets`]: `m` independent realizations in parallel, realization `k` seeded
//!   with `seed.derive(k)`, identical whatever the thread count.
//!
//! Build samplers by spec through [`registry::build`]; `samplab list samplers` prints the
//! table with every name, alias, parameter and reference.

use std::fmt::Debug;
use std::ops::RangeInclusive;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::seed::Seed;

pub mod force_matrix;
pub mod grid;
pub mod nrooks;
pub mod pmj;
pub mod poisson;
pub mod radical;
pub mod random;
pub mod registry;
pub mod scramble;
pub mod sobol;

pub use registry::{SamplerEntry, build, lookup};
pub use scramble::Randomization;

/// The largest point count samplab will allocate for one set (2^32 points).
pub const MAX_POINTS: usize = 1 << 32;

/// A sampling strategy: an immutable value; randomness comes from the seed.
pub trait Sampler: Send + Sync + Debug {
    /// The canonical spec (name and parameters), for messages and headers.
    fn spec(&self) -> String;

    /// The dimensions this method supports.
    fn dims(&self) -> RangeInclusive<usize>;

    /// Whether exactly `n` points can be made in `dims` dimensions; a count the method
    /// cannot make is an error naming the nearest counts that work (never rounded).
    fn check_count(&self, _n: usize, _dims: usize) -> Result<()> {
        Ok(())
    }

    /// Write `n` points of `dims` coordinates into `out` (length `n * dims`), row-major.
    /// Called only after the dimension and count checks passed.
    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()>;

    /// `n` points in [0,1)^dims for `seed`.
    ///
    /// # Errors
    /// An unsupported dimension, a count the method cannot make, or (for Poisson disks) a
    /// radius that does not fit `n` points.
    fn generate(&self, n: usize, dims: usize, seed: Seed) -> Result<PointSet> {
        self.check(n, dims)?;
        let mut data = vec![0.0; n * dims];
        self.fill(n, dims, seed, &mut data)?;
        Ok(PointSet::from_raw(dims, data))
    }

    /// Dimension and count checks, as [`Sampler::generate`] runs them.
    fn check(&self, n: usize, dims: usize) -> Result<()> {
        let range = self.dims();
        if !range.contains(&dims) {
            return Err(Error::InvalidDims {
                sampler: self.spec(),
                dims,
                supported: format!("{}..={}", range.start(), range.end()),
            });
        }
        if n == 0 || n > MAX_POINTS || n.checked_mul(dims).is_none() {
            return Err(Error::InvalidCount {
                sampler: self.spec(),
                n,
                dims,
                reason: format!("n must be in 1..={MAX_POINTS}"),
            });
        }
        self.check_count(n, dims)
    }
}

/// Random access to a progressive sequence: coordinate `dim` of point `index`.
pub trait Sequence: Sampler {
    /// Coordinate `dim` of point `index`, in [0, 1), a pure function of its arguments.
    fn sample(&self, index: u64, dim: usize, seed: Seed) -> f64;
}

/// `m` realizations of `n` points each, in parallel; realization k uses `seed.derive(k)`.
///
/// # Errors
/// As [`Sampler::generate`]; the first failing realization's error is returned.
pub fn generate_sets(sampler: &dyn Sampler, n: usize, dims: usize, seed: Seed, m: usize) -> Result<Vec<PointSet>> {
    sampler.check(n, dims)?;
    (0..m as u64).into_par_iter().map(|k| sampler.generate(n, dims, seed.derive(k))).collect()
}

/// The integer k with k^d == n, if there is one; otherwise the two nearest valid counts.
pub(crate) fn exact_root(n: usize, dims: usize) -> std::result::Result<usize, (usize, usize)> {
    let guess = (n as f64).powf(1.0 / dims as f64).round() as usize;
    let pow = |k: usize| k.checked_pow(dims as u32).unwrap_or(usize::MAX);
    for k in guess.saturating_sub(1)..=guess + 1 {
        if pow(k) == n {
            return Ok(k);
        }
    }
    let mut k = guess.max(1);
    while pow(k) > n && k > 1 {
        k -= 1;
    }
    while pow(k + 1) <= n {
        k += 1;
    }
    Err((pow(k), pow(k + 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_root_names_neighbours() {
        assert_eq!(exact_root(16, 2), Ok(4));
        assert_eq!(exact_root(15, 2), Err((9, 16)));
        assert_eq!(exact_root(27, 3), Ok(3));
        assert_eq!(exact_root(28, 3), Err((27, 64)));
        assert_eq!(exact_root(7, 1), Ok(7));
        assert_eq!(exact_root(2, 2), Err((1, 4)));
    }
}
