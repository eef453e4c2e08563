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

/// The integrands of a study: instances of a registered family, or one integrand given by
/// the caller (a Python function, say) with its name.
#[derive(Clone, Copy)]
#[non_exhaustive]
pub enum Integrands<'a> {
    /// Instance k of the family for the study's seed.
    Family(&'a Family),
    /// The same integrand for every instance.
    Given(&'a dyn Integrand, &'a str),
}

impl<'a> From<&'a Family> for Integrands<'a> {
    fn from(family: &'a Family) -> Self {
        Integrands::Family(family)
    }
}

impl<'a> Integrands<'a> {
    /// Their dimensions.
    pub fn dims(&self) -> usize {
        match self {
            Integrands::Family(f) => f.dims(),
            Integrands::Given(f, _) => f.dims(),
        }
    }

    /// The family's canonical spec, or the given integrand's name.
    pub fn spec(&self) -> String {
        match self {
            Integrands::Family(f) => f.spec(),
            Integrands::Given(_, name) => (*name).to_string(),
        }
    }

    fn instance(&self, seed: Seed, k: u64) -> Result<Box<dyn Integrand + 'a>> {
        match *self {
            Integrands::Family(f) => f.instance(seed, k),
            Integrands::Given(f, _) => Ok(Box::new(Borrowed(f))),
        }
    }
}

/// A borrowed integrand as an owned one (every method forwarded).
struct Borrowed<'a>(&'a dyn Integrand);

impl Integrand for Borrowed<'_> {
    fn dims(&self) -> usize {
        self.0.dims()
    }
    fn eval(&self, x: &[f64]) -> f64 {
        self.0.eval(x)
    }
    fn eval_many(&self, points: &[f64], out: &mut [f64]) {
        self.0.eval_many(points, out);
    }
    fn exact(&self) -> f64 {
        self.0.exact()
    }
    fn boundary_length(&self) -> Option<f64> {
        self.0.boundary_length()
    }
    fn discontinuities(&self) -> Option<usize> {
        self.0.discontinuities()
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        self.0.fourier(k)
    }
    fn exact_square(&self) -> Option<f64> {
        self.0.exact_square()
    }
}

/// A study: samplers x counts on one integrand family.
pub struct Study<'a> {
    /// Samplers by name (their specs).
    pub samplers: &'a [Sampler],
    /// The integrands.
    pub family: Integrands<'a>,
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
    /// Its standard error: the standard deviation over the instances over sqrt(instances)
    /// (the instances are independent draws of the family; the spread holds both the
    /// estimates' noise and the instances' own biases); NaN for a single instance. Where
    /// the ratio has heavy tails (a family whose integral can come near 0, such as `step`,
    /// makes mean / exact unbounded) the sample deviation understates the spread: on
    /// `step` at N = 16 the relative mean scattered 1.5 times its stated error over 100
    /// seeds.
    pub relative_mean_se: f64,
    /// Mean over instances of (variance of the estimates / their squared mean), over the
    /// instances whose estimates are not all zero.
    pub relative_variance: f64,
    /// Its standard error over those instances, as `relative_mean_se`.
    pub relative_variance_se: f64,
    /// Root of the mean squared error over instances and realizations.
    pub rmse: f64,
    /// N^2 x the mean squared error (Ramamoorthi et al.'s normalization).
    pub normalized_mse: f64,
    /// Its standard error, N^2 x the mean squared errors' over the instances, as
    /// `relative_mean_se`.
    pub normalized_mse_se: f64,
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

/// `{"rows": [...], "fits": [...]}`, as `samplab integrate --json` prints it.
///
/// # Panics
/// Never: plain fields and numbers always make JSON.
pub fn json(rows: &[Row]) -> String {
    let v = serde_json::json!({ "rows": rows, "fits": fits(rows) });
    format!("{}\n", serde_json::to_string_pretty(&v).expect("JSON of plain numbers"))
}

/// The rows as CSV: sampler, integrand, n, the four statistics, the closed-form
/// prediction's statistic and value where there is one, and the standard errors of the
/// relative mean, the relative variance and the normalized mean squared error (last, so
/// that the earlier columns keep their places; numbers as Rust prints them).
pub fn csv(rows: &[Row]) -> String {
    let mut out = crate::io::csv_line([
        "sampler",
        "integrand",
        "n",
        "relative_mean",
        "relative_variance",
        "rmse",
        "normalized_mse",
        "theory_statistic",
        "theory_value",
        "relative_mean_se",
        "relative_variance_se",
        "normalized_mse_se",
    ]);
    for r in rows {
        let (statistic, value) = r
            .theory
            .as_ref()
            .map_or((String::new(), String::new()), |t| (t.statistic.into(), format!("{:?}", t.value)));
        out += &crate::io::csv_line([
            r.sampler.clone(),
            r.integrand.clone(),
            r.n.to_string(),
            format!("{:?}", r.relative_mean),
            format!("{:?}", r.relative_variance),
            format!("{:?}", r.rmse),
            format!("{:?}", r.normalized_mse),
            statistic,
            value,
            format!("{:?}", r.relative_mean_se),
            format!("{:?}", r.relative_variance_se),
            format!("{:?}", r.normalized_mse_se),
        ]);
    }
    out
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

/// The estimates of one unit of a study (one sampler, count and instance), summarized: what
/// a chunk of a distributed study returns ([`Prepared::unit`]), merged by [`Prepared::rows`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitStats {
    /// Mean of the M estimates.
    pub mean: f64,
    /// Their variance (divisor M - 1).
    pub variance: f64,
    /// Their mean squared error against the exact integral.
    pub mse: f64,
    /// The exact integral of the instance.
    pub exact: f64,
    /// The closed-form prediction's value for this instance (NaN where there is none).
    pub prediction: f64,
}

impl UnitStats {
    /// Bytes: the five numbers as little-endian f64, in field order (exact, NaN included).
    pub fn to_bytes(&self) -> [u8; 40] {
        let mut out = [0u8; 40];
        for (chunk, v) in out.chunks_exact_mut(8).zip([self.mean, self.variance, self.mse, self.exact, self.prediction])
        {
            chunk.copy_from_slice(&v.to_le_bytes());
        }
        out
    }

    /// The inverse of [`UnitStats::to_bytes`].
    ///
    /// # Errors
    /// [`Error::Invalid`] when `bytes` is not 40 long.
    ///
    /// # Panics
    /// Never: the length is checked first.
    pub fn from_bytes(bytes: &[u8]) -> Result<UnitStats> {
        if bytes.len() != 40 {
            return Err(Error::Parse {
                location: "a unit's statistics".into(),
                reason: format!("{} bytes, expected 40", bytes.len()),
            });
        }
        let v: Vec<f64> =
            bytes.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().expect("8-byte chunks"))).collect();
        Ok(UnitStats { mean: v[0], variance: v[1], mse: v[2], exact: v[3], prediction: v[4] })
    }
}

/// A study checked and prepared: its instances drawn, every (sampler, count) planned.
pub struct Prepared<'s> {
    study: &'s Study<'s>,
    instances: Vec<Box<dyn Integrand + 's>>,
}

impl<'a> Study<'a> {
    /// Check the study (M >= 2, K >= 1, every sampler at every count) and draw its
    /// instances.
    ///
    /// # Errors
    /// M < 2, K < 1, a sampler that cannot make a count or dimension, an impossible
    /// instance, realizations whose estimates do not fit in memory.
    pub fn prepare(&'a self) -> Result<Prepared<'a>> {
        if self.sets < 2 {
            return Err(Error::Setting {
                name: "sets",
                value: self.sets.to_string(),
                reason: "the variance needs at least 2 realizations".into(),
            });
        }
        if self.instances < 1 {
            return Err(Error::Setting {
                name: "instances",
                value: self.instances.to_string(),
                reason: "at least 1 instance is needed".into(),
            });
        }
        // each unit in flight holds its M estimates
        let threads = rayon::current_num_threads() as u128;
        crate::memory::check(
            || format!("{} realizations on {threads} threads", self.sets),
            8 * self.sets as u128 * threads,
        )?;
        // each instance (a boxed integrand, at most a few hundred bytes) and each unit's
        // statistics (a few numbers), before any is made
        let units = self.samplers.len() as u128 * self.ns.len() as u128 * self.instances as u128;
        crate::memory::check(
            || format!("{} instances and {units} units", self.instances),
            256 * self.instances as u128 + 64 * units,
        )?;
        let dims = self.family.dims();
        for s in self.samplers {
            for &n in self.ns {
                s.plan(n, dims)?;
            }
        }
        let instances = (0..self.instances as u64).map(|k| self.instance(k)).collect::<Result<_>>()?;
        Ok(Prepared { study: self, instances })
    }

    /// Instance `k` of the study's family, the integrand its units with instance `k`
    /// integrate.
    ///
    /// # Errors
    /// An impossible instance (as the family's).
    pub fn instance(&self, k: u64) -> Result<Box<dyn Integrand + 'a>> {
        self.family.instance(self.seed.derive_str("instances"), k)
    }
}

impl Prepared<'_> {
    /// The number of units: samplers x counts x instances. Unit u is sampler
    /// `u / (counts x instances)`, count `u / instances % counts`, instance `u % instances`.
    pub fn units(&self) -> usize {
        self.study.samplers.len() * self.study.ns.len() * self.study.instances
    }

    /// (sampler, count index, instance) of unit `u`.
    fn split(&self, u: usize) -> (usize, usize, usize) {
        let k = self.study.instances;
        (u / (k * self.study.ns.len()), u / k % self.study.ns.len(), u % k)
    }

    /// Unit `u`: its M realizations (in parallel; realization m seeded by hashing the seed,
    /// the sampler, the count, the instance and m), summarized. `progress` is checked
    /// before each realization.
    ///
    /// # Errors
    /// `u` out of range ([`Error::Setting`]), a sampler's fill, a stop.
    pub fn unit(&self, u: usize, progress: &Progress) -> Result<UnitStats> {
        if u >= self.units() {
            return Err(Error::Setting {
                name: "unit",
                value: u.to_string(),
                reason: format!("past the study's {} units", self.units()),
            });
        }
        let (s, c, k) = self.split(u);
        let (sampler, n, f) = (&self.study.samplers[s], self.study.ns[c], &self.instances[k]);
        let spec = sampler.spec();
        let base = self.study.seed.derive_str(spec).derive(n as u64).derive(k as u64);
        let plan = sampler.plan(n, self.study.family.dims())?;
        let exact = f.exact();
        let estimates: Vec<f64> = (0..self.study.sets as u64)
            .into_par_iter()
            .map(|m| {
                progress.check()?;
                let pts = plan.generate(base.derive(m))?;
                // in one batch (a Python integrand is called once per realization)
                let mut values = vec![0.0; n];
                f.eval_many(pts.as_slice(), &mut values);
                Ok(values.iter().sum::<f64>() / n as f64)
            })
            .collect::<Result<_>>()?;
        let stats = crate::stats::Summary::of(&estimates);
        let mse = estimates.iter().map(|e| (e - exact).powi(2)).sum::<f64>() / estimates.len() as f64;
        Ok(UnitStats {
            mean: stats.mean,
            variance: stats.sd * stats.sd,
            mse,
            exact,
            prediction: predict(spec, f.as_ref(), n).map_or(f64::NAN, |p| p.value),
        })
    }

    /// Every unit's statistics, in unit order (the units in parallel). `progress` advances
    /// by one per unit and is checked before each realization.
    ///
    /// # Errors
    /// As [`Prepared::unit`].
    pub fn every_unit(&self, progress: &Progress) -> Result<Vec<UnitStats>> {
        (0..self.units())
            .into_par_iter()
            .map(|u| {
                let stats = self.unit(u, progress)?;
                progress.advance(1)?;
                Ok(stats)
            })
            .collect()
    }

    /// The rows from every unit's statistics, in unit order (the merge of a study computed
    /// in pieces: the same arithmetic in the same order as [`run`], so the same bits).
    ///
    /// # Errors
    /// [`Error::Mismatch`] when `units` is not one per unit.
    pub fn rows(&self, units: &[UnitStats]) -> Result<Vec<Row>> {
        if units.len() != self.units() {
            return Err(Error::Mismatch {
                what: "the unit results".into(),
                expected: format!("one per unit of the study, {}", self.units()),
                got: units.len().to_string(),
            });
        }
        let pairs = self.study.samplers.iter().flat_map(|s| self.study.ns.iter().map(move |&n| (s.spec(), n)));
        Ok(pairs.zip(units.chunks_exact(self.study.instances)).map(|((spec, n), per)| self.row(spec, n, per)).collect())
    }

    /// The row of (sampler `spec`, count `n`) from its instances' statistics.
    fn row(&self, spec: &str, n: usize, per: &[UnitStats]) -> Row {
        let kf = per.len() as f64;
        let mean_of = |g: &dyn Fn(&UnitStats) -> f64| per.iter().map(g).sum::<f64>() / kf;
        let mse = mean_of(&|r| r.mse);
        // the standard error of a mean over the instances; NaN for fewer than two
        let se = |v: &[f64]| if v.len() > 1 { crate::stats::Summary::of(v).standard_error() } else { f64::NAN };
        let theory =
            predict(spec, self.instances[0].as_ref(), n).map(|p| Prediction { value: mean_of(&|r| r.prediction), ..p });
        // instances whose estimates are all zero have no relative variance: skipped
        let relative_variances: Vec<f64> =
            per.iter().filter(|r| r.mean != 0.0).map(|r| r.variance / (r.mean * r.mean)).collect();
        Row {
            sampler: spec.to_string(),
            integrand: self.study.family.spec(),
            n,
            relative_mean: mean_of(&|r| r.mean / r.exact),
            relative_mean_se: se(&per.iter().map(|r| r.mean / r.exact).collect::<Vec<_>>()),
            relative_variance: if relative_variances.is_empty() {
                f64::NAN
            } else {
                relative_variances.iter().sum::<f64>() / relative_variances.len() as f64
            },
            relative_variance_se: se(&relative_variances),
            rmse: mse.sqrt(),
            normalized_mse: mse * (n * n) as f64,
            normalized_mse_se: se(&per.iter().map(|r| r.mse).collect::<Vec<_>>()) * (n * n) as f64,
            theory,
        }
    }
}

/// Run the study: every unit (in parallel), then [`Prepared::rows`]. `progress` advances by
/// one per unit (sampler, N, instance) and is checked before each realization.
///
/// # Errors
/// As [`Study::prepare`] and [`Prepared::unit`].
pub fn run(study: &Study, progress: &Progress) -> Result<Vec<Row>> {
    let prepared = study.prepare()?;
    prepared.rows(&prepared.every_unit(progress)?)
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
