//! A prediction study: samplers x counts on one or more integrands, predicted (and measured
//! when asked), ranked, with each sampler's small-frequency exponent.

use rayon::prelude::*;

use super::{
    Cache, Predicted, SamplerSpectrum, SmallFrequency, integrand_spectrum, measure_sets, predict, predict_radial,
    small_frequency, spectrum_of_plan,
};
use crate::error::{Error, Result};
use crate::integrand::Integrand;
use crate::progress::Progress;
use crate::sampler::Sampler;
use crate::seed::Seed;

/// Every registered sampler, at its default parameters, that makes sets of `dims`
/// dimensions (what `samplab predict --all` ranks).
pub fn every_sampler(dims: usize) -> Vec<Sampler> {
    crate::sampler::SAMPLERS
        .iter()
        .filter_map(|e| crate::sampler::build(e.about.name).ok())
        .filter(|s| s.dims().contains(&dims))
        .collect()
}

/// A prediction study: samplers x counts on integrands of one dimension, predicted (and
/// measured when asked), ranked per integrand. The sampler spectra are shared by the
/// integrands (and measured sets too), and the (sampler, count) pairs run in parallel.
pub struct Study<'a> {
    /// The samplers.
    pub samplers: &'a [Sampler],
    /// The integrands (one instance each) and their specs.
    pub integrands: &'a [(&'a dyn Integrand, String)],
    /// The counts n.
    pub ns: &'a [usize],
    /// Frequencies per axis of the spectra.
    pub res: usize,
    /// Realizations per measured spectrum.
    pub sets: usize,
    /// Realizations per measured variance, and whether each is shifted; none: not measured.
    pub measure: Option<(usize, bool)>,
    /// The seed; a sampler's sets depend on it, its spec and n only.
    pub seed: Seed,
    /// Where measured sampler spectra are kept between runs; none: measured every time.
    pub cache: Option<&'a Cache>,
}

/// One (integrand, sampler, n) of a study.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// The integrand's spec.
    pub integrand: String,
    /// The sampler's spec.
    pub sampler: String,
    /// Points per estimate.
    pub n: usize,
    /// The predicted variance (the sum over the window's frequencies).
    pub predicted: Predicted,
    /// The radial form of the prediction (the sampler's spectrum averaged over rings).
    pub radial: Predicted,
    /// Where the sampler's spectrum comes from.
    pub spectrum: String,
    /// The measured mean squared error, when asked.
    pub measured: Option<Predicted>,
}

/// One sampler's summary on one integrand: exponents and its rank.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Ranked {
    /// The integrand's spec.
    pub integrand: String,
    /// The sampler's spec.
    pub sampler: String,
    /// 1 for the smallest predicted variance at the largest n.
    pub rank: usize,
    /// The predicted variance at the largest n.
    pub variance: f64,
    /// The slope of log predicted variance against log n (three counts or more).
    pub predicted_exponent: Option<f64>,
    /// The same of the measured mean squared error.
    pub measured_exponent: Option<f64>,
}

/// One sampler's small-frequency exponent over the study's counts, and the best- and
/// worst-case convergence exponents it implies.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Rate {
    /// The sampler's spec.
    pub sampler: String,
    /// The fit; `None` when too few rings fall in its region (small counts only).
    pub small_frequency: Option<SmallFrequency>,
}

/// One integrand of a study.
#[derive(Debug, Clone, serde::Serialize)]
pub struct IntegrandInfo {
    /// Its spec.
    pub spec: String,
    /// Where its spectrum comes from.
    pub spectrum: String,
    /// The estimated error of its spectrum (0 for a closed form).
    pub error: f64,
    /// Var(f).
    pub variance: f64,
}

/// What a study gives.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Outcome {
    /// The integrands, in the order given.
    pub integrands: Vec<IntegrandInfo>,
    /// Every (integrand, sampler, n), integrands slowest, then samplers and counts in the
    /// order given.
    pub rows: Vec<Row>,
    /// Per integrand, the samplers best first.
    pub ranking: Vec<Ranked>,
    /// Per sampler, its small-frequency exponent.
    pub rates: Vec<Rate>,
    /// Samplers left out, with the reason (a count they cannot make).
    pub skipped: Vec<(String, String)>,
}

/// The spectra and measured variances of one (sampler, n).
struct Pair {
    spectrum: SamplerSpectrum,
    /// Per integrand.
    measured: Vec<Option<Predicted>>,
}

impl Study<'_> {
    /// The progress units of [`Study::run`]: one per realization transformed, and one per
    /// realization and integrand measured.
    pub fn units(&self) -> u64 {
        (self.samplers.len() * self.ns.len() * self.per_pair()) as u64
    }

    fn per_pair(&self) -> usize {
        self.sets + self.measure.map_or(0, |(m, _)| m * self.integrands.len())
    }

    fn check(&self) -> Result<usize> {
        let setting = |name, value: usize, reason: &str| {
            Err(Error::Setting { name, value: value.to_string(), reason: reason.into() })
        };
        if let Some(&n) = self.ns.iter().find(|&&n| n == 0) {
            return setting("n", n, "counts must be positive");
        }
        if self.ns.is_empty() {
            return Err(Error::TooFew { what: "a prediction".into(), least: 1, of: "count n", got: 0 });
        }
        if let Some((m, _)) = self.measure.filter(|&(m, _)| m < 2) {
            return setting("measure", m, "a measured variance needs at least 2 realizations");
        }
        let Some((first, _)) = self.integrands.first() else {
            return Err(Error::TooFew { what: "a prediction".into(), least: 1, of: "integrand", got: 0 });
        };
        let dims = first.dims();
        if let Some((f, spec)) = self.integrands.iter().find(|(f, _)| f.dims() != dims) {
            return Err(Error::Dimension {
                what: format!("{spec} (the integrands of one prediction share the first's dimension)"),
                takes: format!("{dims}D"),
                got: f.dims(),
            });
        }
        Ok(dims)
    }

    /// Predict (and measure) every sampler at every count on every integrand; a sampler
    /// that refuses one of the counts is skipped with its reason.
    ///
    /// # Errors
    /// No counts or integrands, a count of 0, fewer than 2 measured realizations, a bad
    /// grid or set count, integrands of different dimensions, or a stop.
    pub fn run(&self, progress: &Progress) -> Result<Outcome> {
        let dims = self.check()?;
        // the spectra (res^d grids of f64: each integrand's, each sampler's mean and
        // batches at each n) and each thread's non-uniform FFT (complex, twice res per
        // axis), refused before any is made
        let cells = (self.res as u128).saturating_pow(dims as u32);
        let grids = self.integrands.len() + (1 + super::BATCHES) * self.samplers.len() * self.ns.len();
        let threads = rayon::current_num_threads() as u128;
        let bytes = cells * 8 * grids as u128 + cells * (1 << dims) * 16 * threads;
        crate::memory::check(|| format!("the spectra of {} frequencies per axis in {dims}D", self.res), bytes)?;
        let fs = self.integrands.iter().map(|(f, _)| integrand_spectrum(*f, self.res)).collect::<Result<Vec<_>>>()?;
        let mut skipped = Vec::new();
        let mut tasks = Vec::new();
        for s in self.samplers {
            match self.ns.iter().map(|&n| s.plan(n, dims)).collect::<Result<Vec<_>>>() {
                Ok(plans) => tasks.extend(plans.into_iter().map(|plan| (s, plan))),
                Err(bad) => {
                    skipped.push((s.spec().to_string(), bad.to_string()));
                    progress.advance((self.ns.len() * self.per_pair()) as u64)?;
                }
            }
        }
        let pairs: Vec<Pair> = tasks
            .par_iter()
            .map(|(s, plan)| {
                let spec = s.spec();
                let seed = self.seed.derive_str(spec).derive(plan.n() as u64);
                let spectrum = spectrum_of_plan(spec, plan, self.res, self.sets, seed, self.cache, progress)?;
                let measured = match self.measure {
                    Some((m, shift)) => {
                        let sets = plan.generate_sets(seed.derive(1), m, &Progress::SILENT)?;
                        let each = self
                            .integrands
                            .iter()
                            .map(|(f, _)| measure_sets(*f, &sets, seed.derive(1), shift, progress));
                        each.map(|r| r.map(Some)).collect::<Result<_>>()?
                    }
                    None => vec![None; self.integrands.len()],
                };
                Ok(Pair { spectrum, measured })
            })
            .collect::<Result<_>>()?;
        let mut rows = Vec::new();
        for (i, ((_, name), f)) in self.integrands.iter().zip(&fs).enumerate() {
            for pair in &pairs {
                let s = &pair.spectrum;
                rows.push(Row {
                    integrand: name.clone(),
                    sampler: s.sampler.clone(),
                    n: s.n,
                    predicted: predict(f, s)?,
                    radial: predict_radial(f, s)?,
                    spectrum: s.source.clone(),
                    measured: pair.measured[i],
                });
            }
        }
        let mut names: Vec<&str> = pairs.iter().map(|p| p.spectrum.sampler.as_str()).collect();
        names.dedup();
        let rates = names
            .iter()
            .map(|&name| {
                let spectra: Vec<&SamplerSpectrum> =
                    pairs.iter().map(|p| &p.spectrum).filter(|s| s.sampler == name).collect();
                Rate { sampler: name.to_string(), small_frequency: small_frequency(&spectra) }
            })
            .collect();
        let ranking = self.integrands.iter().flat_map(|(_, name)| rank(&rows, name)).collect();
        Ok(Outcome {
            integrands: self
                .integrands
                .iter()
                .zip(fs)
                .map(|((_, spec), f)| IntegrandInfo {
                    spec: spec.clone(),
                    spectrum: f.source,
                    error: f.error,
                    variance: f.variance,
                })
                .collect(),
            rows,
            ranking,
            rates,
            skipped,
        })
    }
}

/// The samplers on `integrand`, by predicted variance at the largest n, with exponents.
fn rank(rows: &[Row], integrand: &str) -> Vec<Ranked> {
    let rows: Vec<&Row> = rows.iter().filter(|r| r.integrand == integrand).collect();
    let largest = rows.iter().map(|r| r.n).max().unwrap_or(0);
    let exponent = |name: &str, value: &dyn Fn(&Row) -> Option<f64>| {
        let points: Vec<(f64, f64)> =
            rows.iter().filter(|r| r.sampler == name).filter_map(|r| Some((r.n as f64, value(r)?))).collect();
        crate::experiment::loglog_fit(&points).map(|(slope, _)| slope)
    };
    let mut ranking: Vec<Ranked> = rows
        .iter()
        .filter(|r| r.n == largest)
        .map(|r| Ranked {
            integrand: integrand.to_string(),
            sampler: r.sampler.clone(),
            rank: 0,
            variance: r.predicted.variance,
            predicted_exponent: exponent(&r.sampler, &|r| Some(r.predicted.variance)),
            measured_exponent: exponent(&r.sampler, &|r| r.measured.map(|m| m.variance)),
        })
        .collect();
    ranking.sort_by(|a, b| a.variance.total_cmp(&b.variance).then_with(|| a.sampler.cmp(&b.sampler)));
    ranking.iter_mut().enumerate().for_each(|(i, r)| r.rank = i + 1);
    ranking
}
