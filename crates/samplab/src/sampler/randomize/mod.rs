//! Randomizations: what makes a deterministic construction a random one while keeping its
//! structure, and the stage that moves any set's points.
//!
//! - [`crate::construct::scramble`] (shared with the pixel samplers): the randomizations of
//!   the digital sequences (random digit scrambling after Matoušek 1998, Owen's 1995 nested
//!   scrambling by hashing after Burley 2020, and the Cranley & Patterson 1976 shift) and
//!   the hash-based permutations they use; `randomized_families!` (below) declares a
//!   family with the ones it keeps its structure under.
//! - [`micro_jitter`]: `+micro-jitter` after any spec: every point moved by a small uniform
//!   offset (after Roberts 2018).
//! - [`shift`]: `+shift` after any spec: a Cranley–Patterson shift in 64-bit fixed point.
//!
//! The last two are stages ([`STAGES`]): written after any sampler's spec, a saved set's
//! included (`file:path=best.npy+shift`), they randomize the points of the sampler before
//! them, and several may follow one another (`sobol+shift+micro-jitter`).

use crate::error::Result;
use crate::registry::{About, Entry, Registry};
use crate::sampler::{Construction, Sampler};
use crate::spec::{Params, Spec};

pub mod shift;

/// How a stage builds its construction over the sampler before it, from resolved
/// parameters.
pub(crate) type StageBuild = fn(Sampler, &Params) -> Result<Box<dyn Construction>>;

/// A stage: a randomization written after any spec, applied to the points of the sampler
/// before it.
#[derive(Debug)]
pub struct StageEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// The construction over the sampler before it, from resolved parameters.
    pub(crate) build: StageBuild,
}

impl Entry for StageEntry {
    fn about(&self) -> &About {
        &self.about
    }
}

/// The sampler a stage follows, as the stage's construction reads it: a stage makes the
/// counts of the sampler before it, their errors naming the whole spec (the stage's shape),
/// and its tables, their errors naming the sampler that makes them.
#[derive(Debug)]
pub(crate) struct Before(pub(crate) Sampler);

impl Construction for Before {
    fn dims(&self) -> std::ops::RangeInclusive<usize> {
        self.0.dims()
    }
    fn check_count(&self, shape: &crate::sampler::Shape) -> Result<()> {
        self.0.check_count(shape)
    }
    fn prepare(&self, shape: &crate::sampler::Shape) -> Result<Box<dyn crate::sampler::Prepared>> {
        self.0.prepare(shape)
    }
}

/// Every stage.
pub static STAGES: Registry<StageEntry> = Registry::new(
    "stage",
    "STAGES  (after any sampler spec, a saved set's too: SPEC+STAGE[:key=value,...], one after another)",
    &[&[micro_jitter::STAGES, shift::STAGES]],
);

/// `spec` split at its last stage (`sobol+shift+micro-jitter:0.2` into `sobol+shift` and
/// the micro-jitter with its parameters); `None` when it ends in no stage. A '+' whose
/// remainder names no stage (as in 1e+3) does not split.
///
/// # Errors
/// The stage's parameters, malformed or out of range.
pub(crate) fn split(spec: &str) -> Result<Option<(&str, &'static StageEntry, Params)>> {
    for (i, _) in spec.rmatch_indices('+') {
        let Ok(stage) = Spec::parse(&spec[i + 1..]) else { continue };
        if let Ok(entry) = STAGES.lookup(&stage.name) {
            let params = Params::resolve(entry.about.name, entry.about.params, &stage.args)?;
            return Ok(Some((&spec[..i], entry, params)));
        }
    }
    Ok(None)
}

/// The entries of families of digital constructions, declared once per family: the plain
/// construction (with the family's aliases) and one entry per randomization the family
/// lists, named and cited here for every family alike:
/// - `xor`: `family.xor`, random digit scrambling (Matoušek 1998);
/// - `lms`: `family.lms`, linear matrix scrambling and a digital shift (Matoušek 1998);
/// - `owen`: `family.owen` (also `family-owen`), Owen's nested uniform scrambling (Owen
///   1995, 1997), hash-based (Burley 2020);
/// - `shift`: `family.shift` (also `family-shift` and each alias's `-shift`), a
///   Cranley–Patterson shift (Cranley & Patterson 1976): `build` gets
///   `Randomization::Shift` and hands its construction to [`shift::over`], the `+shift`
///   stage's own code (a lattice's tent then wraps the shifted lattice).
///
/// `build(params, randomization)` makes the construction. Adding a randomized family is its
/// file (the construction, a `build`, and one invocation) plus its name in its folder's list.
macro_rules! randomized_families {
    ($({
        family: $family:literal,
        summary: $summary:literal,
        aliases: $aliases:tt,
        params: $params:expr,
        counts: $counts:expr,
        dims: $dims:literal,
        cite: $cite:tt,
        build: $build:expr,
        randomizations: [$($v:ident),+] $(,)?
    }),+ $(,)?) => {
        &[$(
            $crate::sampler::randomize::randomized_families!(@variant none, $family, $summary, $aliases, $params, $counts, $dims, $cite, $build),
            $($crate::sampler::randomize::randomized_families!(@variant $v, $family, $summary, $aliases, $params, $counts, $dims, $cite, $build),)+
        )+]
    };
    (@variant none, $family:literal, $summary:literal, [$($alias:literal),*], $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr) => {
        $crate::sampler::randomize::randomized_families!(@make $family, $summary, &[$($alias),*], $params, $counts, $dims, [$($r),*], $build, None, false)
    };
    (@variant xor, $family:literal, $summary:literal, $aliases:tt, $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr) => {
        $crate::sampler::randomize::randomized_families!(@make concat!($family, ".xor"), concat!($summary, ", random digit scrambling"),
            &[], $params, $counts, $dims, [$($r,)* "matousek1998"], $build, Xor, true)
    };
    (@variant lms, $family:literal, $summary:literal, $aliases:tt, $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr) => {
        $crate::sampler::randomize::randomized_families!(@make concat!($family, ".lms"), concat!($summary, ", linear matrix scrambling and a digital shift"),
            &[], $params, $counts, $dims, [$($r,)* "matousek1998"], $build, Lms, true)
    };
    (@variant owen, $family:literal, $summary:literal, $aliases:tt, $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr) => {
        $crate::sampler::randomize::randomized_families!(@make concat!($family, ".owen"), concat!($summary, ", Owen's nested uniform scrambling (hash-based)"),
            &[concat!($family, "-owen")], $params, $counts, $dims, [$($r,)* "owen1995", "owen1997", "burley2020"], $build, Owen, true)
    };
    (@variant shift, $family:literal, $summary:literal, [$($alias:literal),*], $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr) => {
        $crate::sampler::randomize::randomized_families!(@make concat!($family, ".shift"), concat!($summary, ", Cranley-Patterson shift"),
            &[concat!($family, "-shift") $(, concat!($alias, "-shift"))*], $params, $counts, $dims, [$($r,)* "cranley1976"], $build, Shift, true)
    };
    (@make $name:expr, $summary:expr, $aliases:expr, $params:expr, $counts:expr, $dims:literal, [$($r:literal),*], $build:expr, $randomization:ident, $randomized:literal) => {
        $crate::sampler::SamplerEntry {
            about: $crate::registry::About::new($name, $summary).terse().aliases($aliases).params($params).cite(&[$($r),*]),
            counts: $counts,
            randomized: $randomized,
            dims: $dims,
            build: |p| $build(p, $crate::construct::Randomization::$randomization),
        }
    };
}
pub(crate) use randomized_families;

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> = [micro_jitter];
}
