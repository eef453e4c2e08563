//! The table of samplers: each sampler file declares its entries (canonical names, the
//! papers' aliases, parameters with defaults and ranges, summaries, references, builders)
//! beside its code, and [`SAMPLERS`] lists those files, one line each. `samplab list`,
//! `--help` and the conformance tests are generated from it.

use super::{Construction, SAMPLERS, Sampler};
use crate::construct::Counts;
use crate::error::Result;
use crate::registry::{About, Entry, canonical};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// One registered sampler.
#[derive(Debug)]
pub struct SamplerEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Which counts n it can make.
    pub counts: Counts,
    /// Whether its points depend on the seed (false for the deterministic constructions).
    pub randomized: bool,
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
        vec![format!("counts: {}; dimensions: {}", self.counts.describe(), self.dims)]
    }
}

impl SamplerEntry {
    /// Build this entry's sampler from resolved parameters: its construction under the spec
    /// the entry and the parameters give ([`canonical`], after the construction recorded
    /// what it chose for an `auto` one).
    ///
    /// # Errors
    /// Parameters that are valid one by one but not together.
    pub fn build(&'static self, params: &Params) -> Result<Sampler> {
        let mut params = params.clone();
        let construction = (self.build)(&mut params)?;
        Ok(Sampler::registered(canonical(&self.about, &params), Some(self.counts), construction))
    }
}

/// The distance rule of the Poisson-disk samplers.
pub(crate) const EDGE: ParamSpec = ParamSpec {
    name: "edge",
    kind: Kind::Choice(&["torus", "plain"]),
    default: Default::Word("torus"),
    doc: "distance measured on the torus (wraps around) or inside the square",
};

/// Build a sampler from a spec such as `jitter.gaussian:sigma=0.25` or `GJittered:0.25`,
/// followed by any stages (`sobol+shift`, `kronecker+micro-jitter:0.2`,
/// `file:path=best.npy+shift`: [`super::randomize::STAGES`]).
///
/// # Errors
/// A malformed spec, an unknown name (with suggestions), or bad parameters.
///
/// ```
/// let s = samplab::sampler::build("GJittered:0.25").unwrap();
/// assert_eq!(s.spec(), "jitter.gaussian:sigma=0.25,edge=wrap");
/// assert!(samplab::sampler::build("jitter.gaussian:sigma=-1").is_err());
/// ```
pub fn build(spec: &str) -> Result<Sampler> {
    if let Some((before, stage, params)) = super::randomize::split(spec)? {
        let inner = build(before)?;
        let spec = format!("{}+{}", inner.spec(), canonical(&stage.about, &params));
        return Ok(Sampler::registered(spec, None, (stage.build)(inner, &params)?));
    }
    let (entry, params) = SAMPLERS.resolve(spec)?;
    entry.build(&params)
}

/// The files a sampler spec reads (`file:path=`, `net:matrices=`, `lattice:vector=`, its
/// stages' too), so that a command can refuse to write over one of them.
///
/// # Errors
/// As [`build`], for a spec that does not resolve.
///
/// ```
/// let files = samplab::sampler::inputs("net:matrices=m.txt+shift").unwrap();
/// assert_eq!(files, [std::path::PathBuf::from("m.txt")]);
/// assert!(samplab::sampler::inputs("sobol").unwrap().is_empty());
/// ```
pub fn inputs(spec: &str) -> Result<Vec<std::path::PathBuf>> {
    if let Some((before, stage, params)) = super::randomize::split(spec)? {
        let mut files = inputs(before)?;
        files.extend(params.paths(stage.about.params));
        return Ok(files);
    }
    let (entry, params) = SAMPLERS.resolve(spec)?;
    Ok(params.paths(entry.about().params))
}

/// Whether a sampler spec's points depend on the seed: its entry's flag, or any stage after
/// it (every stage draws from the seed).
///
/// # Errors
/// As [`build`], for a spec that does not resolve.
///
/// ```
/// assert!(samplab::sampler::randomized("sobol.owen").unwrap());
/// assert!(!samplab::sampler::randomized("sobol").unwrap());
/// assert!(samplab::sampler::randomized("sobol+shift").unwrap());
/// ```
pub fn randomized(spec: &str) -> Result<bool> {
    if super::randomize::split(spec)?.is_some() {
        return Ok(true);
    }
    Ok(SAMPLERS.resolve(spec)?.0.randomized)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two numbers a count error names ("... 9 and 16", "try 8 and 13").
    fn named(e: &str) -> Vec<usize> {
        let words: Vec<usize> = e.split(|c: char| !c.is_ascii_digit()).filter_map(|w| w.parse().ok()).collect();
        words[words.len() - 2..].to_vec()
    }

    #[test]
    fn counts_check_name_the_nearest_and_find_the_first_by_brute_force() {
        let squares = |n: usize, d: u32| (1..=n).any(|k| k.pow(d) == n);
        for d in 1..=3u32 {
            for n in 1..=300 {
                let got = Counts::Grid.check(n, d as usize);
                assert_eq!(got.is_ok(), squares(n, d), "grid {n} {d}D");
                if let Err(e) = got {
                    let [lo, hi] = named(&e)[..] else { panic!("{e}") };
                    assert!(lo < n && n < hi && squares(lo, d) && squares(hi, d), "{e}");
                    assert!((lo + 1..hi).all(|m| !squares(m, d)), "{e}: a nearer count");
                }
                let first = (n..).find(|&m| squares(m, d)).unwrap();
                assert_eq!(Counts::Grid.first_from(n, d as usize), Some(first));
            }
        }
        let fib = Counts::Listed { rule: "fib", list: |_, _| Box::new([1, 2, 3, 5, 8, 13, 21].into_iter()) };
        assert!(fib.check(8, 2).is_ok());
        let e = fib.check(9, 2).unwrap_err();
        assert!(e.to_string().ends_with("fib: try 8 and 13"), "{e}");
        assert!(fib.check(30, 2).unwrap_err().to_string().ends_with("fib: try 21"));
        assert_eq!(fib.first_from(9, 2), Some(13));
        assert_eq!(fib.first_from(22, 2), None);
        let most = Counts::AtMost { most: 10, why: "ten" };
        assert!(most.check(10, 1).is_ok() && most.check(11, 1).unwrap_err().to_string().ends_with("ten"));
        assert_eq!(most.first_from(3, 1), Some(3));
        assert_eq!(Counts::Rule("words").first_from(3, 1), None);
        assert_eq!(fib.describe(), "fib (in 2D: 1, 2, 3, 5, 8, 13, 21, ...)");
    }
}
