//! Constructions: the mathematics that the two front doors share.
//!
//! samplab hands out samples through two front doors: point sets ([`crate::sampler`]: n
//! points in d dimensions, made whole, for measurement and integration) and pixel samplers
//! ([`crate::pixel`]: one value per (seed, pixel, frame, index, dimension), as a renderer
//! draws them). Both are built from the constructions here, each written once; the front
//! doors import this module and never each other.
//!
//! ```text
//!   studies        experiment, study, predict, cubature, conform
//!   measures       discrepancy, spectrum, spatial, screen, theory, stats, integrand, warp, io
//!   front doors    sampler (point sets)            pixel (per-pixel draws)
//!   constructions  construct: sobol, sobol3, sz, xi, cascaded, radical, scramble, pbrt,
//!                  cycles, pmj02, cbc, counts, spectrum_theory
//!   base           numeric, seed, simd, progress, memory, error, spec, registry, points
//! ```
//!
//! The test `layers_import_only_downward` (`tests/architecture.rs`) reads the sources and
//! holds the rules: the base imports only the base, this module only the base, `sampler`
//! and `pixel` never each other and nothing above them but the edges ARCHITECTURE.md
//! lists, and none of the three keeps process-wide state. ARCHITECTURE.md at the repository's root draws
//! the map for the whole workspace, lists the edges that still cross the layers upward, and
//! says where each kind of change goes: a new generating matrix, digit table, scramble,
//! hash or search here, in the file of its kind, with the paper and equation it implements;
//! a family that serves either front door in `sampler/` or `pixel/`, reading it from here.
//!
//! The pieces:
//! - [`sobol`]: Sobol' generating matrices (Joe & Kuo 2008) and their byte tables;
//! - [`joe_kuo`]: the reader of Joe & Kuo's direction-number files (the baked-in table's,
//!   at build time, and any a user brings);
//! - [`radical`]: the first primes and radical-inverse digit tables (identity or permuted);
//! - [`scramble`]: the randomizations' vocabulary ([`Randomization`]) and the scrambles
//!   (Owen's nested uniform scramble by hashing, digit permutations in any base);
//! - [`curve`]: the Hilbert curve's order of the screen's pixels (beside pbrt's Morton order);
//! - [`cycles`]: Blender Cycles' hashes, scrambles and tables, bit for bit;
//! - [`pbrt`]: pbrt-v4's hashes, permutation, Morton order and scrambles, bit for bit;
//! - [`pmj02`]: the stochastic pmj02 construction (Helmer et al. 2021);
//! - [`sz`]: the SZ generating matrices (Ahmed et al. 2025), a (0, 4)-sequence in base 4;
//! - [`sobol3`]: Sobol's construction over GF(3) from a table in the format of the
//!   quad-optimized sequences (Ostromoukhov et al. 2024);
//! - [`xi`]: the xi-sequence's matrices (Ahmed et al. 2023), a 2D (0, 2)-sequence;
//! - [`cascaded`]: Cascaded Sobol' (Paulin et al. 2021), consecutive pairs (0, m, 2)-nets;
//! - [`cbc`]: fast component-by-component searches for rank-1 lattices (Nuyens & Cools 2006);
//! - [`counts`]: which counts a construction makes ([`Counts`]);
//! - [`spectrum_theory`]: the closed-form spectra of jittered sampling (Subr & Kautz 2013),
//!   a construction's own theory beside its measured spectra;
//! - fixed point to the unit interval: [`unit()`] and [`cell_centre`].

pub mod cascaded;
pub mod cbc;
pub mod counts;
pub mod curve;
pub mod cycles;
pub mod joe_kuo;
pub mod pbrt;
pub mod pmj02;
pub mod radical;
pub mod scramble;
pub mod sobol;
pub mod sobol3;
pub mod spectrum_theory;
pub mod sz;
pub mod xi;

pub use counts::{Counts, MAX_POINTS};
pub use scramble::Randomization;

/// 32 bits of fixed point to [0, 1), exactly: the left end of the cell [v, v + 1) 2^-32.
#[inline(always)]
pub fn unit(bits: u32) -> f64 {
    f64::from(bits) * (1.0 / 4_294_967_296.0)
}

/// The centre of the cell [v, v + 1) 2^-32: where a randomized sampler with 32 random bits
/// per coordinate (Owen-scrambled or digitally shifted Sobol', pmj02) puts a coordinate, so
/// that it lies in the open interval (0, 1) and an integrand never sees 0 (Phi^-1(0) is
/// -inf). A scrambled net's points are uniform over their cells; the centre keeps every
/// point in its elementary interval (the net stays a net) and its bias is below the
/// truncation's, which the cell's left end had.
#[inline(always)]
pub fn cell_centre(v: u32) -> f64 {
    (f64::from(v) + 0.5) * (1.0 / 4_294_967_296.0)
}
