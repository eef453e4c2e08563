//! The error of an estimator predicted from spectra, before it is measured (Pilleboue,
//! Singh, Coeurjolly, Kazhdan & Ostromoukhov 2015, "Variance analysis for Monte Carlo
//! integration": variance as the integrand's power spectrum weighted by the sampler's).
//!
//! ## What is predicted, and when it is exact
//!
//! On the unit torus an integrand is f(x) = sum_k F(k) exp(2 pi i k.x) over integer
//! frequencies k. A set of n points x_j moved by one uniform random toroidal shift u (a
//! Cranley-Patterson rotation; Pilleboue et al.'s homogenization) gives the unbiased
//! estimate (1/n) sum_j f(x_j + u), whose variance over u is, exactly,
//!
//! ```text
//! Var = (1/n) sum_{k != 0} |F(k)|^2 P(k),    P(k) = |sum_j exp(-2 pi i k.x_j)|^2 / n,
//! ```
//!
//! P the set's periodogram per point (1 at every k for white noise), averaged over the
//! sampler's realizations when the sampler is random. Written from the variance of f,
//! `Var(f) = sum_{k != 0} |F(k)|^2` (Parseval), and summed over the frequencies of a
//! window W (|k_i| < R/2, the spectrum grid of [`crate::spectrum`]):
//!
//! ```text
//! Var = (1/n) [ Var(f) + sum_{k in W, k != 0} |F(k)|^2 (P(k) - 1) ]  + (1/n) sum_{k not in W} |F(k)|^2 (P(k) - 1)
//! ```
//!
//! [`predict`] gives the first term. It is **exact** for a shifted set when P = 1 outside
//! the window (white noise at every n; any set on a trigonometric integrand whose
//! frequencies lie in the window), and an **approximation** otherwise: the last term is
//! left out (for jittered sampling P - 1 falls off as |k|^-2 outside the window; a lattice
//! or a net has P = n at its dual points, which the window must hold), and a sampler used
//! without the shift (as `integrate` does) has the shifted sampler's variance only on
//! average over the integrand's translations.
//!
//! The integrand's coefficients come in closed form where one exists
//! ([`Integrand::fourier`]: disks, polygons and half-planes by the divergence theorem,
//! plane waves, separable exponentials), otherwise from the FFT of f at the midpoints of
//! a fine grid, with the change between that grid and one of half its side stated as the
//! error of the estimate. The sampler's P comes in closed form for `random` (1) and
//! `jitter` (1 - sinc^2(pi k_x/m) sinc^2(pi k_y/m) on an m x m grid), otherwise from the
//! periodograms of its realizations (the spectrum module's non-uniform FFT at 1e-13), with a
//! standard error from batch means; a [`Cache`] keeps measured ones between runs.
//!
//! [`predict_radial`] is the same sum with P averaged over rings of equal |k| (the form for
//! isotropic samplers), and [`small_frequency`] fits the radial spectrum near zero frequency
//! across counts, P ~ c (|k| / sqrt n)^beta, for the best- and worst-case convergence
//! exponents of Pilleboue et al.'s analysis. [`Study`] runs samplers x counts x integrands.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::integrand::Integrand;
use crate::points::PointSet;
use crate::progress::Progress;
use crate::sampler::Sampler;
use crate::seed::Seed;
use crate::spectrum::{Method, periodogram};

mod cache;
mod study;

pub use cache::Cache;
pub use study::{Outcome, Ranked, Rate, Row, Study, every_sampler};

/// The tolerance of the sampler periodograms: far below any variance predicted.
const TOLERANCE: f64 = 1e-13;

/// Batches of realizations for the standard error of a measured spectrum's prediction.
const BATCHES: usize = 8;

/// The integrand's power |F(k)|^2 on the spectrum grid, and its variance.
#[derive(Debug, Clone)]
pub struct IntegrandSpectrum {
    /// Dimensions (1 or 2).
    pub dims: usize,
    /// Resolution R per axis (even): index i is frequency i - R/2, the first axis slowest.
    pub res: usize,
    /// |F(k)|^2 at every frequency of the grid (0 at DC).
    pub power: Vec<f64>,
    /// Var(f) = the integral of f^2 less the integral's square.
    pub variance: f64,
    /// Where the coefficients come from, in words.
    pub source: String,
    /// The estimated error of `power` and `variance` (0 for closed forms): the largest
    /// change of a predicted `variance + sum power (P - 1)` between the fine grid and one
    /// of half its side, for P = 0 and P = 2 at every frequency.
    pub error: f64,
}

/// The frequencies of the centred grid, in row-major order (first axis slowest).
fn frequencies(res: usize, dims: usize) -> impl Iterator<Item = [i64; 2]> {
    let h = (res / 2) as i64;
    let count = res.pow(dims as u32);
    (0..count).map(move |i| if dims == 1 { [i as i64 - h, 0] } else { [(i / res) as i64 - h, (i % res) as i64 - h] })
}

fn check_res(res: usize) -> Result<()> {
    if res < 4 || res % 2 == 1 || res > 4096 {
        return Err(Error::Setting {
            name: "res",
            value: res.to_string(),
            reason: "the spectrum grid is an even 4 to 4096 frequencies per axis".into(),
        });
    }
    Ok(())
}

fn check_sets(sets: usize) -> Result<()> {
    if sets < BATCHES {
        return Err(Error::Setting {
            name: "sets",
            value: sets.to_string(),
            reason: format!("a measured spectrum needs at least {BATCHES} realizations"),
        });
    }
    Ok(())
}

/// The power spectrum of `f` on the grid of `res` frequencies per axis.
///
/// # Errors
/// A resolution out of range, or an integrand that is not 1D or 2D.
pub fn integrand_spectrum(f: &dyn Integrand, res: usize) -> Result<IntegrandSpectrum> {
    check_res(res)?;
    let dims = f.dims();
    if !(1..=2).contains(&dims) {
        return Err(Error::Dimension { what: "prediction".into(), takes: "1D and 2D integrands".into(), got: dims });
    }
    if let (Some(_), Some(square)) = (f.fourier([0, 0]), f.exact_square()) {
        let power = frequencies(res, dims)
            .map(|k| if k == [0, 0] { 0.0 } else { f.fourier(k).map_or(0.0, |[re, im]| re * re + im * im) })
            .collect();
        let mean = f.exact();
        return Ok(IntegrandSpectrum {
            dims,
            res,
            power,
            variance: square - mean * mean,
            source: "closed form".into(),
            error: 0.0,
        });
    }
    // the finest grid that stays cheap: 2^16 values in 1D, 1024^2 or (8R)^2 in 2D
    let fine = if dims == 1 { (64 * res).max(1 << 16) } else { (8 * res).max(1024) };
    let (power, variance) = sampled(f, res, fine)?;
    let (coarse_power, coarse_variance) = sampled(f, res, fine / 2)?;
    let change = |p: f64| {
        let sum = |v: f64, w: &[f64]| v + w.iter().map(|x| x * (p - 1.0)).sum::<f64>();
        (sum(variance, &power) - sum(coarse_variance, &coarse_power)).abs()
    };
    let error = change(0.0).max(change(2.0));
    Ok(IntegrandSpectrum {
        dims,
        res,
        power,
        variance,
        source: format!("FFT of f at the midpoints of a {fine}^{dims} grid"),
        error,
    })
}

/// |F(k)|^2 on the grid and Var(f), from f at the midpoints of a `side`^d grid.
fn sampled(f: &dyn Integrand, res: usize, side: usize) -> Result<(Vec<f64>, f64)> {
    let dims = f.dims();
    let at = |i: usize| (i as f64 + 0.5) / side as f64;
    let rows = if dims == 1 { 1 } else { side };
    let values: Vec<f64> = (0..rows)
        .into_par_iter()
        .flat_map_iter(|r| {
            let mut points = Vec::with_capacity(side * dims);
            for c in 0..side {
                points.push(at(c));
                if dims == 2 {
                    points.push(at(r));
                }
            }
            let mut row = vec![0.0; side];
            f.eval_many(&points, &mut row);
            row
        })
        .collect();
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        let (c, r) = (i % side, i / side);
        let point = if dims == 1 { format!("{}", at(c)) } else { format!("({}, {})", at(c), at(r)) };
        return Err(Error::NotFinite { what: format!("the integrand at {point}"), value: values[i] });
    }
    let plane = crate::screen::Plane::new(side, rows, values)?;
    // |DFT|^2 / cells, of the values less their mean: |F(k)|^2 = that / cells
    let cells = (side * rows) as f64;
    let fft = plane.power();
    let wrap = |k: i64| k.rem_euclid(side as i64) as usize;
    let power = frequencies(res, dims)
        .map(|k| {
            // the plane's rows are y (the second axis), its columns x
            let index = if dims == 1 { wrap(k[0]) } else { wrap(k[1]) * side + wrap(k[0]) };
            fft[index] / cells
        })
        .collect();
    Ok((power, plane.variance()))
}

/// A sampler's periodogram per point P(k) = n |S(k)|^2 at one count, averaged over its
/// realizations, with batch means for the standard error of what it predicts.
#[derive(Debug, Clone)]
pub struct SamplerSpectrum {
    /// The sampler's spec.
    pub sampler: String,
    /// Points per set.
    pub n: usize,
    /// Dimensions.
    pub dims: usize,
    /// Resolution per axis.
    pub res: usize,
    /// P(k) averaged over the realizations (or in closed form).
    pub mean: Vec<f64>,
    /// P(k) averaged within each of 8 batches of realizations; empty for a
    /// closed form.
    batches: Vec<Vec<f64>>,
    /// Where P comes from, in words.
    pub source: String,
}

/// The spectrum of `sampler` at `n` points in `dims` dimensions: in closed form for
/// `random` and `jitter`, otherwise from `sets` realizations (at least 8, in 8 batches for the standard error);
/// `progress` advances by one per realization transformed.
///
/// # Errors
/// A count the sampler refuses, a bad resolution, fewer than 8 sets, or a stop.
pub fn sampler_spectrum(
    sampler: &Sampler,
    n: usize,
    dims: usize,
    res: usize,
    sets: usize,
    seed: Seed,
    progress: &Progress,
) -> Result<SamplerSpectrum> {
    spectrum_of_plan(sampler.spec(), &sampler.plan(n, dims)?, res, sets, seed, None, progress)
}

/// [`sampler_spectrum`] of a plan, through `cache` when given (a measured spectrum found
/// there is not measured again; one measured is kept there); `progress` advances by
/// `sets` in all.
fn spectrum_of_plan(
    spec: &str,
    plan: &crate::sampler::Plan,
    res: usize,
    sets: usize,
    seed: Seed,
    cache: Option<&Cache>,
    progress: &Progress,
) -> Result<SamplerSpectrum> {
    check_res(res)?;
    check_sets(sets)?;
    let (n, dims) = (plan.n(), plan.dims());
    if let Some(s) = closed_form(spec, n, dims, res) {
        progress.advance(sets as u64)?;
        return Ok(s);
    }
    let key = cache::Key { spec, n, dims, res, sets, seed, source: cache::SOURCE };
    if let Some(found) = cache.and_then(|c| c.load(&key)) {
        progress.advance(sets as u64)?;
        return Ok(found);
    }
    let generated = plan.generate_sets(seed, sets, &Progress::SILENT)?;
    let measured = spectrum_of_sets(spec, &generated, res, progress)?;
    if let Some(c) = cache {
        c.store(&key, &measured);
    }
    Ok(measured)
}

/// The spectrum of `spec` at `n` points in `dims` dimensions on a window of `res`
/// frequencies per axis, where a closed form is known: `random` (1, white noise) and
/// `jitter` (1 - prod sinc^2(pi k_i / m) for m^d strata, one uniform point in each); None
/// for any other sampler.
pub fn closed_form(spec: &str, n: usize, dims: usize, res: usize) -> Option<SamplerSpectrum> {
    let closed = |mean: Vec<f64>, source: &str| SamplerSpectrum {
        sampler: spec.to_string(),
        n,
        dims,
        res,
        mean,
        batches: Vec::new(),
        source: source.into(),
    };
    match spec {
        "random" => Some(closed(vec![1.0; res.pow(dims as u32)], "closed form: 1 (white noise)")),
        "jitter" => {
            let m = (n as f64).powf(1.0 / dims as f64).round();
            let sinc2 = |k: i64| {
                let t = std::f64::consts::PI * k as f64 / m;
                if k == 0 { 1.0 } else { (t.sin() / t).powi(2) }
            };
            let p = frequencies(res, dims)
                .map(|k| if k == [0, 0] { 0.0 } else { 1.0 - sinc2(k[0]) * if dims == 2 { sinc2(k[1]) } else { 1.0 } })
                .collect();
            Some(closed(p, "closed form: 1 - prod sinc^2(pi k_i / m), m^d strata"))
        }
        _ => None,
    }
}

/// The measured spectrum of the sets `sets` of the sampler `spec` (all of one size and
/// dimension, at least 8): their mean periodogram per point, and 8 batch means;
/// `progress` advances by one per set.
///
/// # Errors
/// Fewer than 8 sets, sets of different shapes, a bad resolution, or a stop.
pub fn spectrum_of_sets(spec: &str, sets: &[PointSet], res: usize, progress: &Progress) -> Result<SamplerSpectrum> {
    check_res(res)?;
    check_sets(sets.len())?;
    let (n, dims) = crate::spectrum::Sets::Given(sets).shape()?;
    let method = Method::Fast { tol: TOLERANCE };
    let each: Vec<Vec<f64>> = sets
        .par_iter()
        .map(|set| {
            let p = periodogram(set, res, method)?;
            progress.advance(1)?;
            Ok(p.into_iter().map(|s| s * n as f64).collect())
        })
        .collect::<Result<_>>()?;
    let average = |sets: &[Vec<f64>]| -> Vec<f64> {
        let mut sum = vec![0.0; sets[0].len()];
        for p in sets {
            sum.iter_mut().zip(p).for_each(|(s, v)| *s += v);
        }
        sum.iter().map(|s| s / sets.len() as f64).collect()
    };
    let batches = each.chunks(sets.len() / BATCHES).take(BATCHES).map(average).collect();
    Ok(SamplerSpectrum {
        sampler: spec.to_string(),
        n,
        dims,
        res,
        mean: average(&each),
        batches,
        source: format!("measured: mean of {} realizations", sets.len()),
    })
}

/// A predicted variance and its standard error (from the batches of a measured spectrum;
/// 0 for a closed form or a deterministic set).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Predicted {
    /// The predicted variance of the shifted estimator.
    pub variance: f64,
    /// Its standard error.
    pub se: f64,
}

/// The predicted variance of `sampler`'s shifted estimator of `f` (the module's formula,
/// summed over the integer frequencies of the window).
///
/// # Errors
/// Spectra of different grids or dimensions.
pub fn predict(f: &IntegrandSpectrum, s: &SamplerSpectrum) -> Result<Predicted> {
    weighted(f, s, |p| p.to_vec())
}

/// The radial form of [`predict`], for isotropic samplers (Pilleboue et al. 2015's
/// radially averaged spectra): P replaced at each frequency by its mean over the ring of
/// frequencies of the same rounded radius round(|k|), so that only the sampler's radial
/// spectrum enters, weighted by the integrand's power summed over each ring. It equals the
/// torus sum when P is constant on rings (an isotropic expected spectrum), and differs from
/// it by the sampler's anisotropy otherwise (a grid, a lattice).
///
/// # Errors
/// Spectra of different grids or dimensions.
pub fn predict_radial(f: &IntegrandSpectrum, s: &SamplerSpectrum) -> Result<Predicted> {
    let rings = Rings::new(s.res, s.dims);
    weighted(f, s, |p| {
        let means = rings.means(p);
        rings.of.iter().map(|&r| means[r]).collect()
    })
}

/// (1/n) [Var(f) + sum |F|^2 (P - 1)] for P = `view` of the sampler's mean periodogram, with
/// the standard error from the same of its batches.
fn weighted(f: &IntegrandSpectrum, s: &SamplerSpectrum, view: impl Fn(&[f64]) -> Vec<f64>) -> Result<Predicted> {
    if f.res != s.res || f.dims != s.dims {
        return Err(Error::Mismatch {
            what: "the sampler's spectrum".into(),
            expected: format!("{}D at resolution {}, as the integrand's", f.dims, f.res),
            got: format!("{}D at resolution {}", s.dims, s.res),
        });
    }
    let one = |p: &[f64]| {
        let correction: f64 = f.power.iter().zip(view(p)).map(|(w, p)| w * (p - 1.0)).sum();
        (f.variance + correction) / s.n as f64
    };
    let variance = one(&s.mean);
    let se = if s.batches.len() >= 2 {
        let values: Vec<f64> = s.batches.iter().map(|b| one(b)).collect();
        let m = values.iter().sum::<f64>() / values.len() as f64;
        let var = values.iter().map(|v| (v - m).powi(2)).sum::<f64>() / (values.len() - 1) as f64;
        (var / values.len() as f64).sqrt()
    } else {
        0.0
    };
    Ok(Predicted { variance, se })
}

/// The rings round(|k|) = r of the frequency grid.
struct Rings {
    /// The ring of each frequency, in grid order.
    of: Vec<usize>,
    /// Frequencies per ring.
    count: Vec<usize>,
}

impl Rings {
    fn new(res: usize, dims: usize) -> Rings {
        let of: Vec<usize> =
            frequencies(res, dims).map(|k| (k[0] as f64).hypot(k[1] as f64).round() as usize).collect();
        let mut count = vec![0; of.iter().max().map_or(0, |m| m + 1)];
        of.iter().for_each(|&r| count[r] += 1);
        Rings { of, count }
    }

    /// The mean of `p` over each ring.
    fn means(&self, p: &[f64]) -> Vec<f64> {
        let mut sum = vec![0.0; self.count.len()];
        self.of.iter().zip(p).for_each(|(&r, v)| sum[r] += v);
        sum.iter().zip(&self.count).map(|(s, &c)| s / c as f64).collect()
    }
}

/// How far (in |k| / sqrt(n)) the small-frequency fit reaches: well inside the region where
/// a stratified pattern's spectrum still rises as a power.
pub const SMALL_FREQUENCY_REACH: f64 = 0.25;

/// A radial mean below this counts as zero (a zero region, as a lattice's).
const ZERO: f64 = 1e-10;

/// The small-frequency behaviour of a sampler's expected spectrum, P(k) ~ c (|k| /
/// sqrt(n))^beta for |k| / sqrt(n) <= [`SMALL_FREQUENCY_REACH`] (a spectrum whose shape
/// scales with sqrt(n), as a stationary pattern's does), and the convergence exponents it
/// implies (the analysis of Pilleboue et al. 2015).
///
/// With |F(k)|^2 ~ |k|^-a, the variance (1/n) sum |F|^2 P falls as n^(-1 - beta/2) while the
/// small frequencies dominate (beta < a - d) and as n^(-1 - (a - d)/2) once the integrand's
/// tail does. A band-limited integrand (a trigonometric polynomial) is the best case,
/// n^(-1 - beta/2); an integrand with a jump along a smooth curve (a = d + 1: the disk, the
/// half-plane) the worst case of the piecewise-smooth ones, n^(-1 - min(beta, 1)/2).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SmallFrequency {
    /// beta; `None` when P vanishes on every ring of the fit region (a zero region).
    pub exponent: Option<f64>,
    /// c; `None` with a zero region.
    pub constant: Option<f64>,
    /// The (count, ring) points fitted, zeros included.
    pub points: usize,
    /// The predicted exponent of the variance on a band-limited integrand; `None`: faster
    /// than any power of n (a zero region), until it reaches the integrand's band.
    pub best: Option<f64>,
    /// The predicted exponent on an integrand with a jump along a smooth curve.
    pub worst: f64,
}

/// The small-frequency fit over the spectra of one sampler at several counts: the log of
/// the radial spectrum (P averaged over each ring round(|k|) = r >= 1, so over every
/// direction) against the log of the ring's root mean square |k| / sqrt(n), by least
/// squares over the rings within reach; `None` when fewer than 3 rings are nonzero in a
/// region that is not all zero.
pub fn small_frequency(spectra: &[&SamplerSpectrum]) -> Option<SmallFrequency> {
    let mut points = Vec::new();
    let mut zeros = 0;
    for s in spectra {
        let rings = Rings::new(s.res, s.dims);
        let root = (s.n as f64).sqrt();
        let squares =
            rings.means(&frequencies(s.res, s.dims).map(|k| (k[0] * k[0] + k[1] * k[1]) as f64).collect::<Vec<_>>());
        for (r, (&p, &square)) in rings.means(&s.mean).iter().zip(&squares).enumerate().skip(1) {
            let t = square.sqrt() / root;
            // only whole rings: those inside the window's inscribed circle
            if t > SMALL_FREQUENCY_REACH || 2 * r >= s.res {
                continue;
            }
            if p <= ZERO { zeros += 1 } else { points.push((t, p)) }
        }
    }
    if points.is_empty() && zeros >= 3 {
        return Some(SmallFrequency { exponent: None, constant: None, points: zeros, best: None, worst: -1.5 });
    }
    let (beta, _) = crate::experiment::loglog_fit(&points)?;
    let logs: Vec<f64> = points.iter().map(|(t, p)| p.ln() - beta * t.ln()).collect();
    let constant = (logs.iter().sum::<f64>() / logs.len() as f64).exp();
    Some(SmallFrequency {
        exponent: Some(beta),
        constant: Some(constant),
        points: points.len() + zeros,
        best: Some(-1.0 - beta / 2.0),
        worst: -1.0 - beta.clamp(0.0, 1.0) / 2.0,
    })
}

/// The measured mean squared error of the estimator (1/n) sum f(x_j) over `sets`
/// realizations (each moved by its own uniform toroidal shift when `shift`), and its
/// standard error; `progress` advances by one per realization.
///
/// # Errors
/// A count the sampler refuses, dimensions that differ from the integrand's, or a stop.
pub fn measure(
    sampler: &Sampler,
    f: &dyn Integrand,
    n: usize,
    sets: usize,
    seed: Seed,
    shift: bool,
    progress: &Progress,
) -> Result<Predicted> {
    let generated = sampler.plan(n, f.dims())?.generate_sets(seed, sets, &Progress::SILENT)?;
    measure_sets(f, &generated, seed, shift, progress)
}

/// [`measure`] on given sets (at least 2), set m shifted by a uniform toroidal shift drawn
/// from `seed` and m when `shift`; `progress` advances by one per set.
///
/// # Errors
/// Fewer than 2 sets, sets of another dimension than the integrand, or a stop.
pub fn measure_sets(
    f: &dyn Integrand,
    sets: &[PointSet],
    seed: Seed,
    shift: bool,
    progress: &Progress,
) -> Result<Predicted> {
    let dims = f.dims();
    if sets.len() < 2 {
        return Err(Error::TooFew { what: "a measured variance".into(), least: 2, of: "set", got: sets.len() });
    }
    if let Some(s) = sets.iter().find(|s| s.dims() != dims) {
        return Err(Error::Dimension {
            what: format!("a {dims}D integrand"),
            takes: format!("{dims}D sets"),
            got: s.dims(),
        });
    }
    let exact = f.exact();
    let errors: Vec<f64> = sets
        .par_iter()
        .enumerate()
        .map(|(m, set)| {
            let u: Vec<f64> = if shift {
                let mut rng = seed.derive_str("measure shift").derive(m as u64).rng();
                (0..dims).map(|_| crate::seed::uniform(&mut rng)).collect()
            } else {
                vec![0.0; dims]
            };
            progress.advance(1)?;
            Ok((estimate(f, set, &u) - exact).powi(2))
        })
        .collect::<Result<_>>()?;
    let count = errors.len() as f64;
    let mse = errors.iter().sum::<f64>() / count;
    let var = errors.iter().map(|e| (e - mse).powi(2)).sum::<f64>() / (count - 1.0);
    Ok(Predicted { variance: mse, se: (var / count).sqrt() })
}

/// (1/n) sum f(x_j + u mod 1).
fn estimate(f: &dyn Integrand, set: &PointSet, u: &[f64]) -> f64 {
    let points: Vec<f64> = set
        .iter()
        .flat_map(|p| {
            p.iter().zip(u).map(|(pi, ui)| {
                let s = pi + ui;
                if s >= 1.0 { s - 1.0 } else { s }
            })
        })
        .collect();
    let mut values = vec![0.0; set.len()];
    f.eval_many(&points, &mut values);
    values.iter().sum::<f64>() / set.len() as f64
}
