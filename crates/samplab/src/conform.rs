//! Refereeing a sampler someone wrote: samples dumped from their implementation, checked
//! against what samplab's entry of the same name promises (`samplab conform`). Each check
//! is fixed here, before any user's data, and gives pass or fail with the number behind it:
//!
//! - `range`: every value in [0, 1) (a float conversion that rounds 1 - 2^-32 up to 1.0
//!   fails here);
//! - `reference` (with a seed): every value equals samplab's for the same key, bit for bit;
//!   a file of single-precision values is compared with samplab's rounded to the nearest
//!   single and kept below 1 (the conversion pbrt-v4 and Cycles make);
//! - `uniform`: each dimension, pooled over the sets, against the uniform distribution by
//!   Kolmogorov-Smirnov (the asymptotic distribution with Stephens' 1970 correction): fails
//!   when the smallest p-value is below 0.001 / d (Bonferroni over the d dimensions);
//! - `nets` (a digital net's point sets): every prefix of b^m points, each pair of
//!   consecutive dimensions counted interval by interval, has no larger t than samplab's
//!   generating matrices give (every scramble samplab offers keeps it);
//! - `distinct` (several sets or pixels, where samplab's own differ): no set equals an
//!   earlier one (a seed shared across pixels or realizations fails here).

use crate::discrepancy::{Limits, tvalue};
use crate::error::{Error, Result};
use crate::pixel::Film;
use crate::points::PointSet;
use crate::progress::Progress;
use crate::seed::Seed;

/// How the user's sets map to samplab's keys.
#[derive(Debug, Clone, PartialEq)]
pub enum Layout {
    /// Realizations of a point set: set k is samplab's made with `seed.derive(k)` (the sets
    /// `samplab generate --sets` writes).
    Sets,
    /// Pixels of a film `width` x `height`: set k is the samples of pixel (x, y) at frame f,
    /// `keys[k] = [x, y, f]`.
    Pixels {
        /// The film's width.
        width: u32,
        /// The film's height.
        height: u32,
        /// Each set's pixel and frame.
        keys: Vec<[u32; 3]>,
    },
}

impl Layout {
    /// Every pixel of a `width` x `height` film in row-major order (y, then x), at `frame`.
    pub fn film(width: u32, height: u32, frame: u32) -> Layout {
        let keys = (0..height).flat_map(|y| (0..width).map(move |x| [x, y, frame])).collect();
        Layout::Pixels { width, height, keys }
    }
}

/// One check's outcome.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Check {
    /// Its name (`range`, `reference`, `uniform`, `nets`, `distinct`).
    pub name: &'static str,
    /// Whether it passed.
    pub passed: bool,
    /// The number behind it (values outside, values that differ, the smallest p-value, the
    /// largest excess of t, sets repeated).
    pub number: f64,
    /// The number and the first failing key, in words.
    pub detail: String,
}

/// How the `reference` check compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// As the values are found: single precision when every value is a single (a float32
    /// file), else double.
    Found,
    /// Single precision: both sides rounded to the nearest single (a text file of singles
    /// written as decimals).
    Single,
}

/// The p-value below which `uniform` fails, before the Bonferroni division by d.
const UNIFORM_ALPHA: f64 = 1e-3;

/// The checks of `sets` (the user's values: one set per realization or pixel, each n
/// points in d dimensions) as samplab's `spec` laid out by `layout`, with `seed` the
/// `reference` check's (none: that check is left out), compared at `precision`; stopped
/// when `progress` says so.
///
/// # Errors
/// An unknown `spec`, sets of different shapes, a layout whose pixels do not match the sets
/// or lie off the film, a shape the sampler cannot make, more memory than allowed, or a
/// stop ([`Error::Interrupted`]).
pub fn conform(
    sets: &[PointSet],
    spec: &str,
    layout: &Layout,
    seed: Option<Seed>,
    precision: Precision,
    progress: &Progress<'_>,
) -> Result<Vec<Check>> {
    let (n, d) = shape(sets)?;
    let reference = Reference::new(spec, layout, sets.len(), n, d)?;
    let mut checks = vec![range(sets)];
    if let Some(seed) = seed {
        checks.push(matches(sets, &reference.made(seed, progress)?, layout, precision));
    }
    progress.check()?;
    checks.push(uniform(sets));
    if let Some(check) = nets(sets, &reference, progress)? {
        checks.push(check);
    }
    if sets.len() > 1 && reference.varies(progress)? {
        checks.push(distinct(sets, layout));
    }
    Ok(checks)
}

/// The common (n, d) of the sets.
fn shape(sets: &[PointSet]) -> Result<(usize, usize)> {
    let first = sets.first().ok_or_else(|| Error::Invalid("conform: no sets".into()))?;
    let (n, d) = (first.len(), first.dims());
    if let Some(k) = sets.iter().position(|s| (s.len(), s.dims()) != (n, d)) {
        let (m, e) = (sets[k].len(), sets[k].dims());
        return Err(Error::Invalid(format!("conform: set {k} has {m} points in {e}D, set 0 {n} in {d}D")));
    }
    Ok((n, d))
}

/// samplab's side: the point-set sampler or the prepared pixel family.
enum Reference {
    Sets { sampler: crate::Sampler, m: usize, n: usize, d: usize },
    Pixels { spec: String, film: Film, keys: Vec<[u32; 3]> },
}

impl Reference {
    fn new(spec: &str, layout: &Layout, m: usize, n: usize, d: usize) -> Result<Reference> {
        Ok(match layout {
            Layout::Sets => {
                let sampler = crate::sampler::build(spec)?;
                sampler.plan(n, d)?;
                Reference::Sets { sampler, m, n, d }
            }
            Layout::Pixels { width, height, keys } => {
                if keys.len() != m {
                    return Err(Error::Invalid(format!("conform: {} pixels for {m} sets", keys.len())));
                }
                if let Some(p) = keys.iter().find(|p| p[0] >= *width || p[1] >= *height) {
                    return Err(Error::Invalid(format!(
                        "conform: pixel ({}, {}) off a {width} x {height} film",
                        p[0], p[1]
                    )));
                }
                let count = |v: usize, what: &str| {
                    u32::try_from(v).map_err(|_| Error::Invalid(format!("conform: {v} {what} per pixel")))
                };
                let film =
                    Film { width: *width, height: *height, spp: count(n, "samples")?, dims: count(d, "dimensions")? };
                Reference::Pixels { spec: spec.into(), film, keys: keys.clone() }
            }
        })
    }

    /// samplab's values for every set under `seed`.
    fn made(&self, seed: Seed, progress: &Progress<'_>) -> Result<Vec<PointSet>> {
        match self {
            Reference::Sets { sampler, m, n, d } => sampler.plan(*n, *d)?.generate_sets(seed, *m, progress),
            Reference::Pixels { spec, film, keys } => {
                let p = crate::pixel::prepare_with(spec, *film, seed, progress)?;
                keys.iter()
                    .map(|&[x, y, frame]| {
                        progress.check()?;
                        let values = (0..film.spp)
                            .flat_map(|i| (0..film.dims).map(move |j| (i, j)))
                            .map(|(i, j)| p.sample([x, y], frame, i, j))
                            .collect();
                        PointSet::new(film.dims as usize, values)
                    })
                    .collect()
            }
        }
    }

    /// Whether samplab's own first two sets (or pixels) differ under one seed.
    fn varies(&self, progress: &Progress<'_>) -> Result<bool> {
        let made = match self {
            Reference::Sets { sampler, n, d, .. } => sampler.plan(*n, *d)?.generate_sets(Seed::DEFAULT, 2, progress)?,
            Reference::Pixels { spec, film, keys } => {
                let two = Reference::Pixels { spec: spec.clone(), film: *film, keys: keys[..2].to_vec() };
                two.made(Seed::DEFAULT, progress)?
            }
        };
        Ok(made[0] != made[1])
    }
}

/// The words for set k's key.
fn key(layout: &Layout, k: usize) -> String {
    match layout {
        Layout::Sets => format!("set {k}"),
        Layout::Pixels { keys, .. } => format!("pixel ({}, {}) at frame {}", keys[k][0], keys[k][1], keys[k][2]),
    }
}

fn range(sets: &[PointSet]) -> Check {
    let outside = |x: &f64| !(0.0..1.0).contains(x);
    let count = sets.iter().map(|s| s.as_slice().iter().filter(|x| outside(x)).count()).sum::<usize>();
    let first = sets.iter().enumerate().find_map(|(k, s)| {
        s.as_slice().iter().position(outside).map(|i| (k, i / s.dims(), i % s.dims(), s.as_slice()[i]))
    });
    let detail = match first {
        None => "every value in [0, 1)".into(),
        Some((k, i, j, x)) => {
            format!("{count} values outside [0, 1); the first: set {k}, sample {i}, dimension {j} is {x:?}")
        }
    };
    Check { name: "range", passed: count == 0, number: count as f64, detail }
}

/// samplab's value as the user's file holds it: itself, or the nearest single below 1.
fn as_single(x: f64) -> f64 {
    f64::from((x as f32).min(1.0 - f32::EPSILON / 2.0))
}

fn matches(sets: &[PointSet], ours: &[PointSet], layout: &Layout, precision: Precision) -> Check {
    // a file whose every value is a single was written in single precision
    let single =
        precision == Precision::Single || sets.iter().all(|s| s.as_slice().iter().all(|&x| f64::from(x as f32) == x));
    let convert = |x: f64| if single { as_single(x) } else { x };
    let theirs_as = |x: f64| if precision == Precision::Single { f64::from(x as f32) } else { x };
    let mut differ = 0usize;
    let mut first = None;
    for (k, (theirs, ours)) in sets.iter().zip(ours).enumerate() {
        for (i, (&t, &o)) in theirs.as_slice().iter().zip(ours.as_slice()).enumerate() {
            let t = theirs_as(t);
            if t.to_bits() != convert(o).to_bits() {
                differ += 1;
                first.get_or_insert((k, i / theirs.dims(), i % theirs.dims(), t, convert(o)));
            }
        }
    }
    let precision = if single { "single precision" } else { "double precision" };
    let detail = match first {
        None => format!("every value equals samplab's, bit for bit ({precision})"),
        Some((k, i, j, t, o)) => format!(
            "{differ} values differ from samplab's ({precision}); the first: {}, sample {i}, dimension {j}: {t:?} where samplab has {o:?}",
            key(layout, k)
        ),
    };
    Check { name: "reference", passed: differ == 0, number: differ as f64, detail }
}

/// The Kolmogorov-Smirnov p-value of the statistic `dn` over `n` values: the asymptotic
/// distribution Q(x) = 2 sum_k (-1)^(k-1) exp(-2 k^2 x^2) at x = (sqrt n + 0.12 + 0.11 /
/// sqrt n) dn (Stephens 1970).
fn ks_p_value(dn: f64, n: usize) -> f64 {
    let root = (n as f64).sqrt();
    let x = (root + 0.12 + 0.11 / root) * dn;
    if x < 0.2 {
        return 1.0;
    }
    let sum: f64 = (1..=100)
        .map(|k| {
            let k = f64::from(k);
            (if k % 2.0 == 1.0 { 2.0 } else { -2.0 }) * (-2.0 * k * k * x * x).exp()
        })
        .sum();
    sum.clamp(0.0, 1.0)
}

fn uniform(sets: &[PointSet]) -> Check {
    let d = sets[0].dims();
    let mut worst = (1.0f64, 0usize, 0.0f64);
    for j in 0..d {
        let mut v: Vec<f64> = sets.iter().flat_map(|s| s.iter().map(move |p| p[j])).collect();
        v.sort_by(f64::total_cmp);
        let n = v.len() as f64;
        let dn = v
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                let cdf = x.clamp(0.0, 1.0);
                (cdf - i as f64 / n).max((i + 1) as f64 / n - cdf)
            })
            .fold(0.0, f64::max);
        let p = ks_p_value(dn, v.len());
        if p < worst.0 || j == 0 {
            worst = (p, j, dn);
        }
    }
    let (p, j, dn) = worst;
    let bound = UNIFORM_ALPHA / d as f64;
    let detail =
        format!("the smallest Kolmogorov-Smirnov p-value, dimension {j}: {p:.3e} (D = {dn:.3e}), against {bound:.1e}");
    Check { name: "uniform", passed: p >= bound, number: p, detail }
}

/// `nets` for a digital net's point sets, else none.
fn nets(sets: &[PointSet], reference: &Reference, progress: &Progress<'_>) -> Result<Option<Check>> {
    let Reference::Sets { sampler, n, d, .. } = reference else { return Ok(None) };
    let plan = sampler.plan(*n, *d)?;
    let Some(matrices) = plan.generating_matrices() else { return Ok(None) };
    let b = matrices.base() as usize;
    let limits = Limits::default();
    let mut worst: Option<(usize, usize, usize, usize, usize)> = None;
    let mut excess = 0usize;
    for m in (1..).take_while(|&m| b.checked_pow(m as u32).is_some_and(|p| p <= *n) && m <= matrices.cols()) {
        let count = b.pow(m as u32);
        for j in 0..d.saturating_sub(1) {
            progress.check()?;
            let promised = tvalue::of_matrices(matrices, &[j, j + 1], m, &limits)?;
            for (k, s) in sets.iter().enumerate() {
                let pair: Vec<f64> = s.iter().take(count).flat_map(|p| [p[j], p[j + 1]]).collect();
                let t = tvalue::counted(&PointSet::new(2, pair)?, b, m);
                if t > promised && t - promised > excess {
                    excess = t - promised;
                    worst = Some((k, m, j, t, promised));
                }
            }
        }
    }
    let detail = match worst {
        None => format!("every prefix of {b}^m points: each pair (j, j + 1) no worse than samplab's matrices"),
        Some((k, m, j, t, promised)) => {
            format!(
                "set {k}, {b}^{m} points, dimensions {j}-{}: t = {t} where samplab's matrices give {promised}",
                j + 1
            )
        }
    };
    Ok(Some(Check { name: "nets", passed: excess == 0, number: excess as f64, detail }))
}

fn distinct(sets: &[PointSet], layout: &Layout) -> Check {
    let mut seen: std::collections::HashMap<Vec<u64>, usize> = std::collections::HashMap::new();
    let mut repeated = 0usize;
    let mut first = None;
    for (k, s) in sets.iter().enumerate() {
        let bits: Vec<u64> = s.as_slice().iter().map(|x| x.to_bits()).collect();
        match seen.get(&bits) {
            Some(&earlier) => {
                repeated += 1;
                first.get_or_insert((earlier, k));
            }
            None => {
                seen.insert(bits, k);
            }
        }
    }
    let detail = match first {
        None => format!("all {} differ, as samplab's do", sets.len()),
        Some((a, b)) => format!(
            "{repeated} repeat an earlier one, as samplab's do not; the first: {} equals {}",
            key(layout, b),
            key(layout, a)
        ),
    };
    Check { name: "distinct", passed: repeated == 0, number: repeated as f64, detail }
}
