//! Cubature to a stated accuracy: the integral of a function over \[0,1\]^d with an error
//! bound, the number of points doubled until the bound meets the tolerance.
//!
//! The bound is probabilistic: R independent randomizations of a randomized sampler
//! (Owen-scrambled Sobol' by default) give R estimates whose mean is the answer, and
//! Student's t interval at the stated level about it is the bound (replicated randomized
//! QMC; Owen 1997 for scrambled nets, L'Ecuyer & Lemieux 2002 for the replicated interval).
//! It assumes the R estimates are close to normal, which holds for scrambled nets on
//! smooth integrands and by the central limit theorem for independent points; the
//! coverage test in `tests/cubature.rs` measures it.

use std::time::Instant;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::integrand::Integrand;
use crate::numeric::student_t_quantile;
use crate::progress::Progress;
use crate::sampler;
use crate::seed::Seed;

/// What to compute to what accuracy (from JSON: any field, the rest at their defaults).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// A randomized sampler's spec.
    pub sampler: String,
    /// Stop once the bound is at most `max(abs_tol, rel_tol |estimate|)`.
    pub abs_tol: f64,
    /// See `abs_tol`.
    pub rel_tol: f64,
    /// The confidence level of the bound, in (0, 1).
    pub level: f64,
    /// Independent randomizations, at least 2.
    pub replications: usize,
    /// Points per randomization at the start (doubled at each step).
    pub min_n: usize,
    /// The most points per randomization.
    pub max_n: usize,
    /// Randomization r uses `seed.derive(r)` at every step.
    pub seed: Seed,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            sampler: "sobol.owen".into(),
            abs_tol: 1e-3,
            rel_tol: 0.0,
            level: 0.99,
            replications: 16,
            min_n: 256,
            max_n: 1 << 20,
            seed: Seed::DEFAULT,
        }
    }
}

/// One step of the doubling: points per randomization, the estimate and its bound.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Step {
    /// Points per randomization.
    pub n: usize,
    /// The mean of the randomizations' estimates.
    pub estimate: f64,
    /// Half the width of Student's t interval at the level.
    pub bound: f64,
}

/// The integral, its bound and how they were reached.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Cubature {
    /// The estimate of the integral.
    pub estimate: f64,
    /// |integral - estimate| <= bound with probability about `level`.
    pub bound: f64,
    /// What the bound means, in words.
    pub kind: String,
    /// Whether the bound met the tolerance (otherwise `max_n` was reached).
    pub converged: bool,
    /// Points per randomization at the last step.
    pub n: usize,
    /// Function evaluations in all (every step's points, every randomization).
    pub evaluations: usize,
    /// Each step.
    pub steps: Vec<Step>,
    /// Wall time in seconds.
    pub seconds: f64,
}

impl Cubature {
    /// As `samplab cubature --json` prints it: these fields, the integrand's name and its
    /// exact integral where known (null otherwise).
    ///
    /// # Panics
    /// Never: the result is plain data.
    pub fn to_json(&self, integrand: &str, exact: Option<f64>) -> serde_json::Value {
        let mut value = serde_json::to_value(self).expect("plain data");
        value["integrand"] = integrand.into();
        value["exact"] = exact.filter(|e| e.is_finite()).map_or(serde_json::Value::Null, Into::into);
        value
    }
}

impl Settings {
    fn check(&self) -> Result<()> {
        let setting = |name: &'static str, value: String, reason: &str| {
            Err(Error::Setting { name, value, reason: reason.to_string() })
        };
        if !(self.abs_tol >= 0.0 && self.rel_tol >= 0.0) || self.abs_tol + self.rel_tol <= 0.0 {
            return setting(
                "abs_tol",
                format!("{} (rel_tol {})", self.abs_tol, self.rel_tol),
                "the tolerances must be at least 0, and one of them above 0",
            );
        }
        if !(self.level > 0.0 && self.level < 1.0) {
            return setting("level", self.level.to_string(), "must be in (0, 1)");
        }
        if self.replications < 2 {
            return setting("replications", self.replications.to_string(), "must be at least 2 (a spread needs two)");
        }
        if self.min_n == 0 || self.min_n > self.max_n {
            return setting("min_n", self.min_n.to_string(), &format!("must be in 1..={} (max_n)", self.max_n));
        }
        Ok(())
    }
}

/// The integral of `f` to the tolerance of `settings`: n points per randomization from
/// `min_n`, doubled until the bound meets the tolerance or n would pass `max_n`.
///
/// # Errors
/// Bad settings or sampler; a deterministic sampler (its randomizations agree, so it has
/// no spread to bound by); the work stopped by `progress`.
pub fn cubature(f: &dyn Integrand, settings: &Settings, progress: &Progress) -> Result<Cubature> {
    settings.check()?;
    let start = Instant::now();
    let sampler = sampler::build(&settings.sampler)?;
    let d = f.dims();
    let r = settings.replications;
    let t = student_t_quantile(0.5 + settings.level / 2.0, (r - 1) as f64);
    let mut steps = Vec::new();
    let mut evaluations = 0;
    let mut n = settings.min_n;
    loop {
        let plan = sampler.plan(n, d)?;
        // each randomization's estimate, and its first point
        let runs = (0..r)
            .into_par_iter()
            .map(|k| {
                let points = plan.generate(settings.seed.derive(k as u64))?;
                let mut values = vec![0.0; n];
                f.eval_many(points.as_slice(), &mut values);
                progress.advance(1)?;
                Ok((values.iter().sum::<f64>() / n as f64, points.as_slice()[..d].to_vec()))
            })
            .collect::<Result<Vec<(f64, Vec<f64>)>>>()?;
        evaluations += n * r;
        let means: Vec<f64> = runs.iter().map(|run| run.0).collect();
        let estimate = means.iter().sum::<f64>() / r as f64;
        let variance = means.iter().map(|m| (m - estimate).powi(2)).sum::<f64>() / (r - 1) as f64;
        if runs.iter().all(|run| run.1 == runs[0].1) {
            return Err(Error::Setting {
                name: "sampler",
                value: plan.spec(),
                reason: "its randomizations give the same estimate: a deterministic sampler has no spread to bound \
                         the error by (use a randomized one: sobol.owen, halton.owen, lattice.shift, random, ...)"
                    .into(),
            });
        }
        let bound = t * (variance / r as f64).sqrt();
        steps.push(Step { n, estimate, bound });
        let converged = bound <= settings.abs_tol.max(settings.rel_tol * estimate.abs());
        if converged || n * 2 > settings.max_n {
            return Ok(Cubature {
                estimate,
                bound,
                kind: format!(
                    "probabilistic: Student's t interval at level {} over {r} randomizations of {}",
                    settings.level,
                    plan.spec()
                ),
                converged,
                n,
                evaluations,
                steps,
                seconds: start.elapsed().as_secs_f64(),
            });
        }
        n *= 2;
    }
}
