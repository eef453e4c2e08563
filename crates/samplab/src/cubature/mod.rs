//! Cubature to a stated accuracy: the integral of a function over \[0,1\]^d with an error
//! bound, the number of points doubled until the bound meets the tolerance. Two kinds of
//! bound:
//!
//! - probabilistic ([`Rule::Replicated`]): R independent randomizations of a randomized
//!   sampler (Owen-scrambled Sobol' by default) give R estimates whose mean is the answer,
//!   and Student's t interval at the stated level about it is the bound (replicated
//!   randomized QMC; Owen 1997 for scrambled nets, L'Ecuyer & Lemieux 2002 for the
//!   replicated interval). It assumes the R estimates are close to normal, which holds for
//!   scrambled nets on smooth integrands and by the central limit theorem for independent
//!   points; the coverage test in `tests/cubature.rs` measures it.
//! - guaranteed for a cone of integrands ([`Rule::Net`], [`Rule::Lattice`]): one randomized
//!   digital net or lattice sequence and the decay of its Walsh or Fourier coefficients
//!   (Hickernell & Jimenez Rugama 2016; Jimenez Rugama & Hickernell 2016), see
//!   `guaranteed.rs`.
//!
//! Where the sampler is a sequence (every prefix of its points is its set for that n), a
//! doubling evaluates only the new points.

mod guaranteed;

use std::time::Instant;

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::integrand::Integrand;
use crate::numeric::student_t_quantile;
use crate::progress::Progress;
use crate::sampler;
use crate::seed::Seed;

/// Which bound stops the doubling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum Rule {
    /// Student's t interval over independent randomizations (probabilistic).
    Replicated,
    /// The Walsh-coefficient rule of Hickernell & Jimenez Rugama (2016) on one randomized
    /// digital net in base 2, natural order (`net.lms` by default).
    Net,
    /// The Fourier-coefficient rule of Jimenez Rugama & Hickernell (2016) on one shifted
    /// rank-1 lattice sequence, radical-inverse order, with the baker's transform
    /// (`lattice.shift:tent=yes` by default).
    Lattice,
}

impl Rule {
    /// `replicated`, `net` or `lattice`.
    ///
    /// # Errors
    /// Another name.
    pub fn parse(name: &str) -> Result<Rule> {
        [Rule::Replicated, Rule::Net, Rule::Lattice].into_iter().find(|r| r.name() == name).ok_or_else(|| {
            Error::Setting { name: "rule", value: name.into(), reason: "must be replicated, net or lattice".into() }
        })
    }

    /// Its name, as [`Rule::parse`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Replicated => "replicated",
            Rule::Net => "net",
            Rule::Lattice => "lattice",
        }
    }

    /// Its first n unless told otherwise: 256, or QMCPy's 2^10 for the guaranteed rules
    /// (their map of the coefficients needs levels to sort).
    pub fn default_min_n(self) -> usize {
        if self == Rule::Replicated { 256 } else { 1024 }
    }

    /// The sampler it uses unless told otherwise.
    pub fn default_sampler(self) -> &'static str {
        match self {
            Rule::Replicated => "sobol.owen",
            Rule::Net => "net.lms",
            Rule::Lattice => "lattice.shift:tent=yes",
        }
    }
}

/// What to compute to what accuracy (from JSON: any field, the rest at their defaults).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// The bound.
    pub rule: Rule,
    /// A sampler's spec: a randomized one for [`Rule::Replicated`], a randomized digital
    /// net in base 2 in natural order (`net.lms`, `net.xor`) for [`Rule::Net`], a shifted
    /// lattice sequence for [`Rule::Lattice`]; unset, the rule's default.
    pub sampler: Option<String>,
    /// Stop once the bound is at most `max(abs_tol, rel_tol |estimate|)`.
    pub abs_tol: f64,
    /// See `abs_tol`.
    pub rel_tol: f64,
    /// The confidence level of the bound, in (0, 1).
    pub level: f64,
    /// Independent randomizations, at least 2 (the replicated rule).
    pub replications: usize,
    /// Points per randomization at the start (doubled at each step); a power of two, at
    /// least 2^5, for the guaranteed rules; unset, the rule's default.
    pub min_n: Option<usize>,
    /// The most points per randomization.
    pub max_n: usize,
    /// Randomization r uses `seed.derive(r)` at every step.
    pub seed: Seed,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            rule: Rule::Replicated,
            sampler: None,
            abs_tol: 1e-3,
            rel_tol: 0.0,
            level: 0.99,
            replications: 16,
            min_n: None,
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
    /// The estimate at this n.
    pub estimate: f64,
    /// Its error bound.
    pub bound: f64,
}

/// The integral, its bound and how they were reached.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Cubature {
    /// The estimate of the integral.
    pub estimate: f64,
    /// |integral - estimate| <= bound, in the sense `kind` states.
    pub bound: f64,
    /// What the bound means, in words.
    pub kind: String,
    /// Whether the bound met the tolerance (otherwise `max_n` was reached).
    pub converged: bool,
    /// Points per randomization at the last step.
    pub n: usize,
    /// Function evaluations in all (every step's new points, every randomization).
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
    /// The first n: as set, or the rule's default.
    pub fn min_n(&self) -> usize {
        self.min_n.unwrap_or(self.rule.default_min_n())
    }

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
        let min_n = self.min_n();
        // a value the user did not set is named as the rule's default
        let shown = match self.min_n {
            Some(_) => min_n.to_string(),
            None => format!("{min_n} (the {} rule's default)", self.rule.name()),
        };
        if min_n == 0 || min_n > self.max_n {
            return setting("min_n", shown, &format!("must be in 1..={} (max_n)", self.max_n));
        }
        if self.rule != Rule::Replicated && (!min_n.is_power_of_two() || min_n < 32) {
            return setting("min_n", shown, "the guaranteed rules need a power of two, at least 32");
        }
        Ok(())
    }
}

/// The integral of `f` to the tolerance of `settings`: n points (per randomization) from
/// `min_n`, doubled until the bound meets the tolerance or n would pass `max_n`.
///
/// # Errors
/// Bad settings or sampler; for the replicated rule a deterministic sampler (its
/// randomizations agree, so it has no spread to bound by); for the guaranteed rules a
/// sampler that is not a sequence of their kind; a non-finite value of `f`; the work
/// stopped by `progress`.
///
/// # Panics
/// Never: every rule takes at least one step.
pub fn cubature(f: &dyn Integrand, settings: &Settings, progress: &Progress) -> Result<Cubature> {
    settings.check()?;
    // the last step's memory (the run's largest), refused before the first step
    let (d, last) = (f.dims(), settings.max_n);
    let bytes = match settings.rule {
        Rule::Replicated => replicated_bytes(last, d, settings.replications),
        _ => guaranteed::bytes(last, d),
    };
    crate::memory::check(|| format!("cubature up to max_n = {last} {d}D points (its last step)"), bytes)?;
    let start = Instant::now();
    let spec = settings.sampler.as_deref().unwrap_or(settings.rule.default_sampler());
    let sampler = sampler::build(spec)?;
    let tolerance = |estimate: f64| settings.abs_tol.max(settings.rel_tol * estimate.abs());
    let (steps, converged, evaluations, kind) = match settings.rule {
        Rule::Replicated => replicated(f, &sampler, settings, progress)?,
        rule => {
            let transform = guaranteed_sampler(rule, &sampler, f.dims())?;
            let run = guaranteed::Run { f, transform, min_n: settings.min_n(), max_n: settings.max_n };
            let (steps, converged) =
                run.run(&sampler, settings.seed, |estimate, bound| bound <= tolerance(estimate), progress)?;
            let evaluations = steps.last().map_or(0, |s| s.0);
            let paper = if rule == Rule::Net {
                "Walsh coefficients of a digital net (Hickernell & Jimenez Rugama 2016)"
            } else {
                "Fourier coefficients of a lattice, baker's transform (Jimenez Rugama & Hickernell 2016)"
            };
            let kind = format!(
                "guaranteed only for integrands in the cone of {paper}: fudge 5 2^-m, r = 4, on {spec}; the cone \
                 is not checked, and outside it (a narrow peak the first points miss) the bound can be false"
            );
            let steps = steps.into_iter().map(|(n, estimate, bound)| Step { n, estimate, bound }).collect();
            (steps, converged, evaluations, kind)
        }
    };
    let last: Step = *steps.last().expect("at least one step");
    Ok(Cubature {
        estimate: last.estimate,
        bound: last.bound,
        kind,
        converged,
        n: last.n,
        evaluations,
        steps,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// The relative accuracy of [`reference()`].
pub const REFERENCE_TOL: f64 = 1e-9;

/// The integral of `f` for reference where it is not known: [`cubature`] with the
/// replicated rule's defaults to a relative [`REFERENCE_TOL`], at most 2^22 points x 16
/// randomizations.
///
/// # Errors
/// As [`cubature`]; [`Error::Setting`] (`exact`) when it did not reach that accuracy.
pub fn reference(f: &dyn Integrand, progress: &Progress) -> Result<f64> {
    let settings = Settings { rel_tol: REFERENCE_TOL, abs_tol: 0.0, max_n: 1 << 22, ..Settings::default() };
    let c = cubature(f, &settings, progress)?;
    if !c.converged {
        return Err(Error::Setting {
            name: "exact",
            value: "(not given)".into(),
            reason: format!(
                "the reference integral reached only {:.1e} relative (estimate {:.6e}) at 2^22 points: give exact= \
                 (--exact on the CLI)",
                c.bound / c.estimate.abs(),
                c.estimate
            ),
        });
    }
    Ok(c.estimate)
}

/// The transform a guaranteed rule needs of `sampler`, or why it cannot use it: a net in
/// base 2 (Walsh) or a lattice (Fourier), a sequence in natural order, randomized so that
/// its points are not the same for every seed.
fn guaranteed_sampler(rule: Rule, sampler: &sampler::Sampler, d: usize) -> Result<guaranteed::Transform> {
    let plan = sampler.plan(2, d)?;
    let spec = plan.spec();
    let family = spec.split(':').next().unwrap_or_default();
    let (transform, allowed): (_, &[&str]) = match rule {
        Rule::Net => (guaranteed::Transform::Walsh, &["net.lms", "net.xor"]),
        _ => (guaranteed::Transform::Fourier, &["lattice.shift"]),
    };
    if !allowed.contains(&family) || spec.contains("base=") && !spec.contains("base=2") {
        return Err(Error::Setting {
            name: "sampler",
            value: spec.to_string(),
            reason: format!(
                "the {} rule needs a randomized sequence in natural order of its kind: {}",
                if rule == Rule::Net { "net" } else { "lattice" },
                allowed.join(" or ")
            ),
        });
    }
    Ok(transform)
}

/// What a rule reports: its steps, whether it met the tolerance, the evaluations, its kind.
type Outcome = (Vec<Step>, bool, usize, String);

/// The memory a step of `n` points of the replicated rule takes: each thread holds one
/// randomization's points and values at a time.
fn replicated_bytes(n: usize, d: usize, r: usize) -> u128 {
    n as u128 * (d as u128 + 1) * 8 * r.min(rayon::current_num_threads()) as u128
}

/// The replicated rule: R randomizations, Student's t interval over their means.
fn replicated(
    f: &dyn Integrand,
    sampler: &sampler::Sampler,
    settings: &Settings,
    progress: &Progress,
) -> Result<Outcome> {
    let d = f.dims();
    let r = settings.replications;
    let t = student_t_quantile(0.5 + settings.level / 2.0, (r - 1) as f64);
    let mut steps = Vec::new();
    let mut evaluations = 0;
    let mut n = settings.min_n();
    // each randomization's sum so far (over the first `done` points, a sequence's prefix)
    let mut sums = vec![0.0; r];
    let mut done = 0;
    loop {
        crate::memory::check(
            || format!("cubature of {n} {d}D points x {r} randomizations"),
            replicated_bytes(n, d, r),
        )?;
        let plan = sampler.plan(n, d)?;
        let sequence = plan.access(settings.seed).is_some();
        let from = if sequence { done } else { 0 };
        let runs = (0..r)
            .into_par_iter()
            .map(|k| {
                let points = plan.generate(settings.seed.derive(k as u64))?;
                let mut values = vec![0.0; n - from];
                f.eval_many(&points.as_slice()[from * d..], &mut values);
                if let Some(i) = values.iter().position(|v| !v.is_finite()) {
                    let x = &points.as_slice()[(from + i) * d..(from + i + 1) * d];
                    return Err(guaranteed::non_finite(x, values[i]));
                }
                progress.advance(1)?;
                Ok((values.iter().sum::<f64>(), points.as_slice()[..d].to_vec()))
            })
            .collect::<Result<Vec<(f64, Vec<f64>)>>>()?;
        evaluations += (n - from) * r;
        for (sum, run) in sums.iter_mut().zip(&runs) {
            *sum = if sequence { *sum + run.0 } else { run.0 };
        }
        done = n;
        let means: Vec<f64> = sums.iter().map(|s| s / n as f64).collect();
        let estimate = means.iter().sum::<f64>() / r as f64;
        let variance = means.iter().map(|m| (m - estimate).powi(2)).sum::<f64>() / (r - 1) as f64;
        if runs.iter().all(|run| run.1 == runs[0].1) {
            return Err(Error::Setting {
                name: "sampler",
                value: plan.spec().to_string(),
                reason: "its randomizations give the same estimate: a deterministic sampler has no spread to bound \
                         the error by (use a randomized one: sobol.owen, halton.owen, lattice.shift, random, ...)"
                    .into(),
            });
        }
        let bound = t * (variance / r as f64).sqrt();
        steps.push(Step { n, estimate, bound });
        let converged = bound <= settings.abs_tol.max(settings.rel_tol * estimate.abs());
        if converged || n * 2 > settings.max_n {
            let kind = format!(
                "probabilistic: Student's t interval at level {} over {r} randomizations of {}",
                settings.level,
                plan.spec()
            );
            return Ok((steps, converged, evaluations, kind));
        }
        n *= 2;
    }
}
