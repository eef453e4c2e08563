//! Integration experiments: for each (sampler, integrand instance, N), M realizations of
//! the estimator mean f(x_i); the statistics Subr & Kautz 2013 report (relative mean and
//! relative variance, averaged over instances), the RMSE and N^2 x MSE (Ramamoorthi et
//! al. 2012), beside the papers' closed forms; and least-squares convergence exponents.
//!
//! Realization m of instance k for sampler s at count n is seeded by hashing (seed, s,
//! n, k, m): results are identical whatever the thread count.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::integrand::{Family, Integrand};
use crate::progress::Progress;
use crate::sampler::Sampler;
use crate::seed::Seed;
use crate::theory;

/// A study: samplers x counts on one integrand family.
pub struct Study<'a> {
    /// Samplers by name (their specs).
    pub samplers: &'a [Box<dyn Sampler>],
    /// The integrand family.
    pub family: &'a Family,
    /// The counts N.
    pub ns: &'a [usize],
    /// Realizations per instance (M >= 2).
    pub sets: usize,
    /// Instances of the family (K >= 1).
    pub instances: usize,
    /// The seed.
    pub seed: Seed,
}

/// The statistics of one (sampler, integrand family, N).
#[derive(Debug, Clone, serde::Serialize)]
pub struct Row {
    /// Sampler spec.
    pub sampler: String,
    /// Integrand spec.
    pub integrand: String,
    /// Points per estimate.
    pub n: usize,
    /// Mean over instances of (mean of the estimates / exact).
    pub relative_mean: f64,
    /// Mean over instances of (variance of the estimates / their squared mean), over the
    /// instances whose estimates are not all zero.
    pub relative_variance: f64,
    /// Root of the mean squared error over instances and realizations.
    pub rmse: f64,
    /// N^2 x the mean squared error (Ramamoorthi et al.'s normalization).
    pub normalized_mse: f64,
    /// The closed-form prediction for this row, where one exists.
    pub theory: Option<Prediction>,
}

/// A closed-form prediction of one of a row's statistics.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Prediction {
    /// Which statistic: "relative_variance" or "normalized_mse".
    pub statistic: &'static str,
    /// Its predicted value.
    pub value: f64,
    /// Where the formula comes from.
    pub source: &'static str,
}

/// A fitted convergence exponent: relative variance ~ C N^exponent.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Fit {
    /// Sampler spec.
    pub sampler: String,
    /// Integrand spec.
    pub integrand: String,
    /// The slope of log variance against log N.
    pub exponent: f64,
    /// Its 95% confidence interval (Student t, n - 2 degrees of freedom).
    pub ci: (f64, f64),
}

fn family_of(spec: &str) -> &str {
    spec.split(':').next().unwrap_or(spec)
}

/// The prediction for a sampler on one instance at count n, if the papers give one.
fn predict(sampler: &str, f: &dyn Integrand, n: usize) -> Option<Prediction> {
    let fam = family_of(sampler);
    let p = f.exact();
    let prediction = |statistic, value, source| Some(Prediction { statistic, value, source });
    if let Some(k) = f.discontinuities() {
        let value = theory::visibility_normalized_mse(fam, k)?;
        return prediction("normalized_mse", value, "Ramamoorthi et al. 2012, eqs. 11-12, Figs. 6-7");
    }
    let b = f.boundary_length()?;
    match fam {
        "random" => prediction(
            "relative_variance",
            theory::random_indicator_variance(p, n) / (p * p),
            "p(1-p)/N (Sbert et al. 2006, eq. 12)",
        ),
        "jitter.uniform" if f.dims() == 2 => prediction(
            "relative_variance",
            theory::systematic_variance(b, n) / (p * p),
            "k B u^3, k = 0.0724 (Sbert et al. 2006, eq. 10)",
        ),
        _ => None,
    }
}

/// The estimates of one instance, summarized.
struct InstanceStats {
    mean: f64,
    variance: f64,
    mse: f64,
    exact: f64,
    prediction: Option<Prediction>,
}

/// Run the study; `progress` advances by one per (sampler, N, instance) and is checked
/// before each realization.
///
/// # Errors
/// M < 2, K < 1, a sampler that cannot make a count or dimension, an impossible instance,
/// a stop ([`Error::Interrupted`]).
pub fn run(study: &Study, progress: &Progress) -> Result<Vec<Row>> {
    if study.sets < 2 {
        return Err(Error::Setting {
            name: "sets",
            value: study.sets.to_string(),
            reason: "the variance needs at least 2 realizations".into(),
        });
    }
    if study.instances < 1 {
        return Err(Error::Setting {
            name: "instances",
            value: study.instances.to_string(),
            reason: "at least 1 instance is needed".into(),
        });
    }
    let dims = study.family.entry.dims;
    for s in study.samplers {
        for &n in study.ns {
            s.plan(n, dims)?;
        }
    }
    let instances: Vec<Box<dyn Integrand>> = (0..study.instances as u64)
        .map(|k| study.family.instance(study.seed.derive_str("instances"), k))
        .collect::<Result<_>>()?;
    let mut rows = Vec::new();
    for s in study.samplers {
        let spec = s.spec();
        for &n in study.ns {
            let base = study.seed.derive_str(&spec).derive(n as u64);
            let plan = s.plan(n, dims)?;
            let per: Vec<InstanceStats> = instances
                .par_iter()
                .enumerate()
                .map(|(k, f)| {
                    let exact = f.exact();
                    let estimates: Vec<f64> = (0..study.sets as u64)
                        .into_par_iter()
                        .map(|m| {
                            progress.check()?;
                            let pts = plan.generate(base.derive(k as u64).derive(m))?;
                            Ok(pts.iter().map(|x| f.eval(x)).sum::<f64>() / n as f64)
                        })
                        .collect::<Result<_>>()?;
                    let stats = crate::stats::Summary::of(&estimates);
                    let mse = estimates.iter().map(|e| (e - exact).powi(2)).sum::<f64>() / estimates.len() as f64;
                    progress.advance(1)?;
                    Ok(InstanceStats {
                        mean: stats.mean,
                        variance: stats.sd * stats.sd,
                        mse,
                        exact,
                        prediction: predict(&spec, f.as_ref(), n),
                    })
                })
                .collect::<Result<_>>()?;
            let kf = per.len() as f64;
            let mean_of = |g: &dyn Fn(&InstanceStats) -> f64| per.iter().map(g).sum::<f64>() / kf;
            let mse = mean_of(&|r| r.mse);
            let theory = per[0].prediction.as_ref().map(|p| Prediction {
                value: mean_of(&|r| r.prediction.as_ref().map_or(f64::NAN, |p| p.value)),
                ..p.clone()
            });
            rows.push(Row {
                sampler: spec.clone(),
                integrand: study.family.spec(),
                n,
                relative_mean: mean_of(&|r| r.mean / r.exact),
                // instances whose estimates are all zero have no relative variance: skipped
                relative_variance: {
                    let v: Vec<f64> =
                        per.iter().filter(|r| r.mean != 0.0).map(|r| r.variance / (r.mean * r.mean)).collect();
                    if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 }
                },
                rmse: mse.sqrt(),
                normalized_mse: mse * (n * n) as f64,
                theory,
            });
        }
    }
    Ok(rows)
}

/// Two-sided 97.5% Student t quantiles for 1..=30 degrees of freedom.
const T975: [f64; 30] = [
    12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
    2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042,
];

/// Least-squares slope of ln y against ln x with its 95% confidence interval; None with
/// fewer than three usable points.
pub fn loglog_fit(points: &[(f64, f64)]) -> Option<(f64, (f64, f64))> {
    let pts: Vec<(f64, f64)> =
        points.iter().filter(|(x, y)| *x > 0.0 && *y > 0.0 && y.is_finite()).map(|(x, y)| (x.ln(), y.ln())).collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let slope = sxy / sxx;
    let resid: f64 = pts.iter().map(|p| (p.1 - my - slope * (p.0 - mx)).powi(2)).sum();
    let se = (resid / (n - 2.0) / sxx).sqrt();
    let df = pts.len() - 2;
    let t = if df <= 30 { T975[df - 1] } else { 1.96 };
    Some((slope, (slope - t * se, slope + t * se)))
}

/// The convergence exponent of the relative variance for each sampler in `rows`.
pub fn fits(rows: &[Row]) -> Vec<Fit> {
    let mut out: Vec<Fit> = Vec::new();
    let mut keys: Vec<(&str, &str)> = rows.iter().map(|r| (r.sampler.as_str(), r.integrand.as_str())).collect();
    keys.dedup();
    for (s, i) in keys {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.sampler == s && r.integrand == i)
            .map(|r| (r.n as f64, r.relative_variance))
            .collect();
        if let Some((exponent, ci)) = loglog_fit(&pts) {
            out.push(Fit { sampler: s.into(), integrand: i.into(), exponent, ci });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn fit_recovers_an_exact_power_law() {
        let pts: Vec<(f64, f64)> = [16.0, 64.0, 256.0, 1024.0].iter().map(|&n: &f64| (n, 3.0 * n.powf(-1.5))).collect();
        let (slope, (lo, hi)) = super::loglog_fit(&pts).unwrap();
        assert!((slope + 1.5).abs() < 1e-12 && (hi - lo).abs() < 1e-9);
    }
}
