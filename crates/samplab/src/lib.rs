//! # samplab
//!
//! Sampling patterns for Monte Carlo integration in rendering: every strategy of
//! Shirley 1991, Subr & Kautz 2013, Sbert et al. 2006 and Ramamoorthi et al. 2012, plus the
//! modern low-discrepancy sequences, with warps to other domains and point-set I/O.
//!
//! ## Conventions (stated once, here)
//!
//! - Points are `f64`, in the half-open unit cube [0,1)^d, stored row-major in a
//!   [`PointSet`]. Warped sets live in their warp's domain.
//! - Randomness comes only from an explicit [`Seed`]. Realization `k` of a batch is seeded
//!   with `seed.derive(k)` (a hash, never `seed + k`), so results are bit-identical
//!   whatever the thread count. The RNG is PCG64 ([`seed::Rng`]).
//! - Counts are never rounded: a sampler that cannot make exactly `n` points returns an
//!   error naming the nearest counts it can make.
//! - Samplers are named by specs `family[.variant][:key=value,...]`; see
//!   [`sampler::SAMPLERS`] and `samplab list samplers`.
//! - Every method's documentation names its paper (keys in [`bibliography`]).
//!
//! ```
//! use samplab::{Seed, sampler};
//! let jitter = sampler::build("jitter.gaussian:sigma=0.25").unwrap();
//! let points = jitter.generate(256, 2, Seed(7)).unwrap();
//! assert_eq!(points.len(), 256);
//! assert!(points.in_unit_cube());
//! ```

#![deny(missing_docs)]

pub mod bibliography;
pub mod conform;
pub mod construct;
pub mod cubature;
pub(crate) mod dataflow;
pub mod discrepancy;
pub mod error;
pub mod experiment;
pub mod integrand;
pub mod io;
pub mod memory;
pub mod numeric;
pub mod pixel;
pub mod points;
pub mod predict;
pub mod progress;
pub mod registry;
pub mod sampler;
pub mod screen;
pub mod seed;
pub mod simd;
pub mod spatial;
pub mod spec;
pub mod spectrum;
pub mod stats;
pub mod study;
pub mod theory;
pub mod warp;

pub use error::{Error, Result};
pub use points::PointSet;
pub use sampler::{Access, Sampler};
pub use seed::Seed;

/// The guide's Rust examples, compiled and run as doctests (`cargo test --doc`), so that
/// what a reader copies from docs/guide builds. The pages' shell and Python examples are run
/// by samplab-cli's `tests/examples.rs` and samplab-py's `tests/test_examples.py`.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/guide/library.md")]
#[doc = include_str!("../../../docs/guide/pixels.md")]
struct Guide;
