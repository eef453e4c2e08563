//! The table of samplers: each sampler file declares its entries (canonical names, the
//! papers' aliases, parameters with defaults and ranges, summaries, references, builders)
//! beside its code, and [`SAMPLERS`] lists those files, one line each. `samplab list`,
//! `--help` and the conformance tests are generated from it.

use super::{SAMPLERS, Sampler};
use crate::error::Result;
use crate::registry::{About, Entry};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// One registered sampler.
#[derive(Debug)]
pub struct SamplerEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Which counts n it can make, in words.
    pub counts: &'static str,
    /// Supported dimensions, in words.
    pub dims: &'static str,
    /// Builds the sampler from resolved parameters.
    pub(crate) build: fn(&Params) -> Result<Box<dyn Sampler>>,
}

impl Entry for SamplerEntry {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        vec![format!("counts: {}; dimensions: {}", self.counts, self.dims)]
    }
}

impl SamplerEntry {
    /// Build this entry's sampler from resolved parameters.
    ///
    /// # Errors
    /// Parameters that are valid one by one but not together.
    pub fn build(&self, params: &Params) -> Result<Box<dyn Sampler>> {
        (self.build)(params)
    }
}

/// Counts of the grid family.
pub(crate) const GRID: &str = "n = k^d";
/// Any count.
pub(crate) const ANY: &str = "any n";

/// The distance rule of the Poisson-disk samplers.
pub(crate) const EDGE: ParamSpec = ParamSpec {
    name: "edge",
    kind: Kind::Choice(&["torus", "plain"]),
    default: Default::Word("torus"),
    doc: "distance measured on the torus (wraps around) or inside the square",
};

/// The entries of progressive sequences `$ty` (built by `<$ty>::new(Randomization)`), four
/// per family: plain, random digit scrambling (`.xor`), Owen scrambling (`.owen`, alias
/// `family-owen`) and a Cranley-Patterson shift (`.shift`), each citing its randomization.
macro_rules! randomized_entries {
    ($(($ty:ty, $family:literal, $summary:literal, $counts:expr, $dims:expr, [$($r:literal),*])),+ $(,)?) => {
        &[$(
            SamplerEntry {
                about: About::new($family, $summary).cite(&[$($r),*]),
                counts: $counts,
                dims: $dims,
                build: |_| Ok(Box::new(<$ty>::new(Randomization::None))),
            },
            SamplerEntry {
                about: About::new(concat!($family, ".xor"), concat!($summary, ", random digit scrambling"))
                    .cite(&[$($r,)* "matousek1998"]),
                counts: $counts,
                dims: $dims,
                build: |_| Ok(Box::new(<$ty>::new(Randomization::Xor))),
            },
            SamplerEntry {
                about: About::new(concat!($family, ".owen"), concat!($summary, ", Owen scrambling (hash-based)"))
                    .aliases(&[concat!($family, "-owen")])
                    .cite(&[$($r,)* "owen1995", "burley2020"]),
                counts: $counts,
                dims: $dims,
                build: |_| Ok(Box::new(<$ty>::new(Randomization::Owen))),
            },
            SamplerEntry {
                about: About::new(concat!($family, ".shift"), concat!($summary, ", Cranley-Patterson shift"))
                    .cite(&[$($r,)* "cranley1976"]),
                counts: $counts,
                dims: $dims,
                build: |_| Ok(Box::new(<$ty>::new(Randomization::Shift))),
            },
        )+]
    };
}
pub(crate) use randomized_entries;

/// Build a sampler from a spec such as `jitter.gaussian:sigma=0.25` or `GJittered:0.25`.
///
/// # Errors
/// A malformed spec, an unknown name (with suggestions), or bad parameters.
///
/// ```
/// let s = samplab::sampler::build("GJittered:0.25").unwrap();
/// assert_eq!(s.spec(), "jitter.gaussian:sigma=0.25,edge=wrap");
/// assert!(samplab::sampler::build("jitter.gaussian:sigma=-1").is_err());
/// ```
pub fn build(spec: &str) -> Result<Box<dyn Sampler>> {
    if let Some((inner, post)) = super::micro_jitter::split(spec) {
        return super::micro_jitter::over(build(inner)?, post);
    }
    let (entry, params) = SAMPLERS.resolve(spec)?;
    entry.build(&params)
}
