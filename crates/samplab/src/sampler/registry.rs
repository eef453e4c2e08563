//! The table of samplers: each sampler file declares its entries (canonical names, the
//! papers' aliases, parameters with defaults and ranges, summaries, references, builders)
//! beside its code, and [`SAMPLERS`] lists those files, one line each. `samplab list`,
//! `--help` and the conformance tests are generated from it.

use std::ops::RangeInclusive;

use super::{Access, Construction, Prepared, SAMPLERS, Sampler, Shape, Stream};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::{About, Entry, canonical};
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};
use crate::spectrum::theory::VarianceTheory;

/// One registered sampler.
#[derive(Debug)]
pub struct SamplerEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Which counts n it can make, in words.
    pub counts: &'static str,
    /// Supported dimensions, in words.
    pub dims: &'static str,
    /// Builds the construction from resolved parameters (recording there what it chose
    /// for an `auto` one, where its spec names the choice).
    pub(crate) build: fn(&mut Params) -> Result<Box<dyn Construction>>,
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
    pub fn build(&'static self, params: &Params) -> Result<Box<dyn Sampler>> {
        let mut params = params.clone();
        let construction = (self.build)(&mut params)?;
        Ok(Box::new(Registered { entry: self, params, construction, on: None }))
    }
}

/// A registered sampler: the construction its entry built, with the entry and the
/// parameters it was built from, which give it its spec ([`canonical`]).
#[derive(Debug)]
pub struct Registered {
    entry: &'static SamplerEntry,
    params: Params,
    construction: Box<dyn Construction>,
    /// For a stage written after another spec (`kronecker+micro-jitter`): that spec.
    on: Option<String>,
}

impl Registered {
    /// The stage `entry` with `params` (its `construction`) applied to the sampler of spec
    /// `on`: its spec is `on+stage`.
    pub(crate) fn stage(
        entry: &'static SamplerEntry,
        params: Params,
        construction: Box<dyn Construction>,
        on: String,
    ) -> Self {
        Registered { entry, params, construction, on: Some(on) }
    }

    /// The registry entry this sampler was built from.
    pub fn entry(&self) -> &'static SamplerEntry {
        self.entry
    }

    /// The parameters it was built with (an `auto` one resolved where the spec names it).
    pub fn params(&self) -> &Params {
        &self.params
    }
}

/// `e` with the sampler's name filled in where the construction left it empty.
pub(crate) fn labelled(e: Error, spec: impl FnOnce() -> String) -> Error {
    match e {
        Error::InvalidCount { sampler, n, dims, reason } if sampler.is_empty() => {
            Error::InvalidCount { sampler: spec(), n, dims, reason }
        }
        Error::Infeasible { sampler, reason } if sampler.is_empty() => Error::Infeasible { sampler: spec(), reason },
        other => other,
    }
}

impl Sampler for Registered {
    fn spec(&self) -> String {
        let own = canonical(&self.entry.about, &self.params);
        match &self.on {
            Some(on) => format!("{on}+{own}"),
            None => own,
        }
    }
    fn dims(&self) -> RangeInclusive<usize> {
        self.construction.dims()
    }
    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        self.construction.check_count(n, dims).map_err(|e| labelled(e, || self.spec()))
    }
    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        let inner = self.construction.prepare(shape).map_err(|e| labelled(e, || self.spec()))?;
        Ok(Box::new(Labelled { inner, spec: self.spec() }))
    }
    fn spectrum_theory(&self, n: usize, dims: usize) -> Option<VarianceTheory> {
        self.construction.spectrum_theory(n, dims)
    }
}

/// A construction's prepared state whose errors name the sampler.
struct Labelled<'a> {
    inner: Box<dyn Prepared + 'a>,
    spec: String,
}

impl Prepared for Labelled<'_> {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        self.inner.fill(seed, out, progress).map_err(|e| labelled(e, || self.spec.clone()))
    }
    fn units(&self) -> u64 {
        self.inner.units()
    }
    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        self.inner.access(seed)
    }
    fn stream(&self, seed: Seed) -> Option<Box<dyn Stream + '_>> {
        self.inner.stream(seed)
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
    if let Some((inner, post)) = super::randomize::micro_jitter::split(spec) {
        return super::randomize::micro_jitter::over(build(inner)?, post);
    }
    let (entry, params) = SAMPLERS.resolve(spec)?;
    entry.build(&params)
}
