//! Refereeing a sampler someone wrote: samples dumped from their implementation, checked
//! against what samplab's entry of the same name promises (`samplab conform`). Each check
//! is fixed here, before any user's data, and gives pass or fail with the number behind it:
//!
//! - `range`: every value in [0, 1) (a float conversion that rounds 1 - 2^-32 up to 1.0
//!   fails here);
//! - `reference` (with a seed): every value equals samplab's for the same key, bit for bit
//!   (or within a given number of units in the last place); a file of single-precision
//!   values is compared with samplab's rounded to the nearest single and kept below 1 (the
//!   conversion pbrt-v4 and Cycles make), a file of 32-bit fixed-point values (every value a
//!   multiple of 2^-32: a `uint32` array) with samplab's cut to 32 bits;
//! - `uniform`: each dimension, pooled over the sets, against the uniform distribution by
//!   Kolmogorov-Smirnov (the asymptotic distribution with Stephens' 1970 correction): fails
//!   when the smallest p-value is below 0.001 / d (Bonferroni over the d dimensions);
//! - `independent` (where samplab's own sets pass it): each pair of consecutive dimensions'
//!   Pearson correlation r over every point, against independence: fails when |r| sqrt N
//!   passes 5 (N points; a seed shared across dimensions fails here);
//! - `unbiased` (30 sets or pixels or more, where samplab's own pass it): the integrals of
//!   x_j (1/2) and x_j x_(j+1) (1/4), each set's estimate its mean, the mean over the sets
//!   against the exact value in standard errors of that mean: fails past 5 (values cut to a
//!   few bits fail here, though every dimension still looks uniform);
//! - `nets`: every prefix of b^m points (of the first 64 sets), each pair of consecutive
//!   dimensions counted interval by interval, has no larger t than samplab promises: its
//!   generating matrices' t for a digital net's point sets (every scramble samplab offers
//!   keeps it), else a (0, m, 2)-net in base 2 wherever each of 64 of samplab's own sets (32
//!   pixels at least; point sets of at most 2^17 values) is one (a pixel family's nets; a dimension off by one in the padding
//!   fails here without a seed);
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
#[non_exhaustive]
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
        Layout::frames(width, height, frame..frame + 1)
    }

    /// Every pixel of a `width` x `height` film at each of `frames`, frame by frame, row by
    /// row: the order of `samplab pixels`' array (frames, height, width, spp, dims).
    pub fn frames(width: u32, height: u32, frames: std::ops::Range<u32>) -> Layout {
        let keys = frames.flat_map(|f| (0..height).flat_map(move |y| (0..width).map(move |x| [x, y, f]))).collect();
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
#[non_exhaustive]
pub enum Precision {
    /// As the values are found: single precision when every value is a single (a float32
    /// file), 32-bit fixed point when every value is a multiple of 2^-32, else double.
    Found,
    /// Single precision: both sides rounded to the nearest single (a text file of singles
    /// written as decimals).
    Single,
}

/// What the user's samples claim to be.
#[derive(Debug, Clone, PartialEq)]
pub struct Claim<'a> {
    /// samplab's entry: a point-set spec, or with a pixel layout a pixel family's.
    pub spec: &'a str,
    /// How the sets map to samplab's keys.
    pub layout: Layout,
    /// The seed they were made with: the `reference` check's (none: that check is left out).
    pub seed: Option<Seed>,
    /// How `reference` compares.
    pub precision: Precision,
    /// How many units in the last place (of the precision compared) a value may be off.
    pub ulps: u64,
}

impl<'a> Claim<'a> {
    /// `spec`'s realizations, no seed, compared bit for bit as found.
    pub fn sets(spec: &'a str) -> Claim<'a> {
        Claim { spec, layout: Layout::Sets, seed: None, precision: Precision::Found, ulps: 0 }
    }
}

/// The bound on |r| sqrt N (`independent`) and on |z| (`unbiased`).
const SIGMAS: f64 = 5.0;

/// The fewest sets `unbiased` measures a standard error from.
const UNBIASED_SETS: usize = 30;

/// The p-value below which `uniform` fails, before the Bonferroni division by d.
const UNIFORM_ALPHA: f64 = 1e-3;

/// The checks of `sets` (the user's values: one set per realization or pixel, each n
/// points in d dimensions) as what `claim` says they are; stopped when `progress` says so.
///
/// # Errors
/// An unknown `spec`, sets of different shapes, a layout whose pixels do not match the sets
/// or lie off the film, a shape the sampler cannot make, more memory than allowed, or a
/// stop ([`Error::Interrupted`]).
pub fn conform(sets: &[PointSet], claim: &Claim<'_>, progress: &Progress<'_>) -> Result<Vec<Check>> {
    let (n, d) = shape(sets)?;
    let layout = &claim.layout;
    let reference = Reference::new(claim.spec, layout, sets.len(), n, d)?;
    let mut checks = vec![range(sets)];
    if let Some(seed) = claim.seed {
        checks.push(matches(sets, &reference.made(seed, progress)?, claim));
    }
    progress.check()?;
    checks.push(uniform(sets));
    // samplab's own sets under its default seed: a statistical check applies where they pass it
    let own = reference.made(Seed::DEFAULT, progress)?;
    if d > 1 && independent(&own).passed {
        checks.push(independent(sets));
    }
    if sets.len() >= UNBIASED_SETS && unbiased(&own).passed {
        checks.push(unbiased(sets));
    }
    if let Some(check) = nets(sets, &reference, &own, progress)? {
        checks.push(check);
    }
    if sets.len() > 1 && own[0] != own[1] {
        checks.push(distinct(sets, layout));
    }
    Ok(checks)
}

/// The common (n, d) of the sets.
fn shape(sets: &[PointSet]) -> Result<(usize, usize)> {
    if sets.is_empty() {
        return Err(Error::TooFew { what: "conform".into(), least: 1, of: "set", got: 0 });
    }
    crate::spectrum::Sets::Given(sets).shape()
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
                    return Err(Error::Mismatch {
                        what: "conform's pixels".into(),
                        expected: format!("one per set, {m}"),
                        got: keys.len().to_string(),
                    });
                }
                if let Some(p) = keys.iter().find(|p| p[0] >= *width || p[1] >= *height) {
                    return Err(Error::Setting {
                        name: "res",
                        value: format!("{width}x{height}"),
                        reason: format!("pixel ({}, {}) is off the film", p[0], p[1]),
                    });
                }
                let count = |v: usize, name: &'static str| {
                    u32::try_from(v).map_err(|_| Error::Setting {
                        name,
                        value: v.to_string(),
                        reason: "more per pixel than 2^32 - 1".into(),
                    })
                };
                let film = Film { width: *width, height: *height, spp: count(n, "spp")?, dims: count(d, "dims")? };
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

/// The precision a `reference` comparison runs at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Compared {
    Double,
    Single,
    Fixed32,
}

impl Compared {
    /// What the values and the claim say.
    fn of(sets: &[PointSet], precision: Precision) -> Compared {
        let all = |f: &dyn Fn(f64) -> bool| sets.iter().all(|s| s.as_slice().iter().all(|&x| f(x)));
        if precision == Precision::Single || all(&|x| f64::from(x as f32) == x) {
            Compared::Single
        } else if all(&|x| (x * 4_294_967_296.0).fract() == 0.0) {
            Compared::Fixed32
        } else {
            Compared::Double
        }
    }

    /// samplab's value as such a file holds it: itself, the nearest single below 1, or cut
    /// to 32 bits.
    fn ours(self, x: f64) -> f64 {
        match self {
            Compared::Double => x,
            Compared::Single => f64::from((x as f32).min(1.0 - f32::EPSILON / 2.0)),
            Compared::Fixed32 => (x * 4_294_967_296.0).floor() / 4_294_967_296.0,
        }
    }

    /// The user's value at this precision (a single written as a decimal, read back).
    fn theirs(self, x: f64) -> f64 {
        if self == Compared::Single { f64::from(x as f32) } else { x }
    }

    /// How many units in the last place apart two values are, at this precision.
    fn ulps(self, a: f64, b: f64) -> u64 {
        // the bit patterns of floats ordered as integers (negative ones mirrored below 0)
        fn ordered(bits: i64, sign: i64) -> i64 {
            if bits < 0 { sign - bits } else { bits }
        }
        match self {
            Compared::Double => ordered(a.to_bits() as i64, i64::MIN).abs_diff(ordered(b.to_bits() as i64, i64::MIN)),
            Compared::Single => {
                let bits = |x: f64| i64::from((x as f32).to_bits() as i32);
                ordered(bits(a), i64::from(i32::MIN)).abs_diff(ordered(bits(b), i64::from(i32::MIN)))
            }
            Compared::Fixed32 => ((a - b).abs() * 4_294_967_296.0) as u64,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Compared::Double => "double precision",
            Compared::Single => "single precision",
            Compared::Fixed32 => "32-bit fixed point",
        }
    }
}

fn matches(sets: &[PointSet], ours: &[PointSet], claim: &Claim<'_>) -> Check {
    let compared = Compared::of(sets, claim.precision);
    let mut differ = 0usize;
    let mut first = None;
    for (k, (theirs, ours)) in sets.iter().zip(ours).enumerate() {
        for (i, (&t, &o)) in theirs.as_slice().iter().zip(ours.as_slice()).enumerate() {
            let (t, o) = (compared.theirs(t), compared.ours(o));
            if compared.ulps(t, o) > claim.ulps {
                differ += 1;
                first.get_or_insert((k, i / theirs.dims(), i % theirs.dims(), t, o));
            }
        }
    }
    let within = if claim.ulps == 0 { "bit for bit".to_string() } else { format!("within {} ulps", claim.ulps) };
    let precision = compared.name();
    let detail = match first {
        None => format!("every value equals samplab's, {within} ({precision})"),
        Some((k, i, j, t, o)) => format!(
            "{differ} values differ from samplab's ({within}, {precision}); the first: {}, sample {i}, dimension {j}: {t:?} where samplab has {o:?}",
            key(&claim.layout, k)
        ),
    };
    Check { name: "reference", passed: differ == 0, number: differ as f64, detail }
}

/// Pearson's correlation of two equally long columns (0 where one is constant).
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (&x, &y) in a.iter().zip(b) {
        sab += (x - ma) * (y - mb);
        saa += (x - ma) * (x - ma);
        sbb += (y - mb) * (y - mb);
    }
    if saa == 0.0 || sbb == 0.0 { 0.0 } else { sab / (saa * sbb).sqrt() }
}

fn independent(sets: &[PointSet]) -> Check {
    let d = sets[0].dims();
    let column = |j: usize| -> Vec<f64> { sets.iter().flat_map(|s| s.iter().map(move |p| p[j])).collect() };
    let n = sets.iter().map(PointSet::len).sum::<usize>() as f64;
    let (mut worst, mut at) = (0.0f64, (0, 0.0));
    for j in 0..d - 1 {
        let r = correlation(&column(j), &column(j + 1));
        if r.abs() * n.sqrt() >= worst {
            (worst, at) = (r.abs() * n.sqrt(), (j, r));
        }
    }
    let (j, r) = at;
    let detail = format!(
        "the largest correlation of consecutive dimensions, {j}-{}: r = {r:.3e}, |r| sqrt N = {worst:.3} (N = {n}), against {SIGMAS}",
        j + 1
    );
    Check { name: "independent", passed: worst <= SIGMAS, number: worst, detail }
}

fn unbiased(sets: &[PointSet]) -> Check {
    let d = sets[0].dims();
    let m = sets.len() as f64;
    // x_j (1/2) and x_j x_(j+1) (1/4): an integrand's name, its exact value, its value at p
    type Integrand = (String, f64, Box<dyn Fn(&[f64]) -> f64>);
    let singles = (0..d).map(|j| -> Integrand { (format!("x_{j}"), 0.5, Box::new(move |p: &[f64]| p[j])) });
    let pairs = (0..d.saturating_sub(1))
        .map(|j| -> Integrand { (format!("x_{j} x_{}", j + 1), 0.25, Box::new(move |p: &[f64]| p[j] * p[j + 1])) });
    let mut worst: Option<(f64, String, f64, f64)> = None;
    for (name, exact, f) in singles.chain(pairs) {
        let estimates: Vec<f64> = sets.iter().map(|s| s.iter().map(&f).sum::<f64>() / s.len() as f64).collect();
        let mean = estimates.iter().sum::<f64>() / m;
        let se = (estimates.iter().map(|e| (e - mean) * (e - mean)).sum::<f64>() / (m - 1.0) / m).sqrt();
        let z = match (mean - exact).abs() {
            0.0 => 0.0,
            off if se == 0.0 => f64::INFINITY * off,
            off => off / se,
        };
        if worst.as_ref().is_none_or(|w| z > w.0) {
            worst = Some((z, name, mean, exact));
        }
    }
    let (z, name, mean, exact) = worst.expect("one dimension at least");
    let detail = format!(
        "the largest |z| over the means of {m} estimates, {name}: {mean:.6} against {exact}, |z| = {z:.3}, against {SIGMAS}"
    );
    Check { name: "unbiased", passed: z <= SIGMAS, number: z, detail }
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

/// The most sets of the user's `nets` counts, and how many of samplab's own it reads a
/// promise from where there are no matrices.
const NETS_SETS: usize = 64;

/// The fewest own sets a promise without matrices is read from: a pair of random points is
/// a (0, 1, 2)-net one time in four, so 32 sets all being one is a structure (4^-32).
const NETS_OWN: usize = 32;

/// The most values of samplab's own point sets `nets` makes for a promise without matrices
/// (32 MiB; larger sets are not given one).
const NETS_OWN_VALUES: usize = 1 << 22;

/// `nets`: each pair (j, j + 1) of every prefix of b^m points of the user's first 64 sets
/// no worse a net than samplab promises: its generating matrices' t (a digital net's point
/// sets, in its base), else a (0, m, 2)-net in base 2 where every one of its own 64 sets
/// (pixels: its own values of the user's first 64 pixels; 32 at least, and for point sets
/// as many as fit 2^22 values) is one. None for a set of fewer than 2 points or of one
/// dimension, or without matrices and without 32 own sets.
fn nets(sets: &[PointSet], reference: &Reference, own: &[PointSet], progress: &Progress<'_>) -> Result<Option<Check>> {
    let (n, d) = (sets[0].len(), sets[0].dims());
    if n < 2 || d < 2 {
        return Ok(None);
    }
    let (plan, own) = match reference {
        Reference::Sets { sampler, .. } => {
            let plan = sampler.plan(n, d)?;
            // as many own sets as fit NETS_OWN_VALUES, up to NETS_SETS
            let fit = NETS_SETS.min(NETS_OWN_VALUES / (n * d));
            let own = if plan.generating_matrices().is_some() || fit < NETS_OWN {
                Vec::new()
            } else {
                plan.generate_sets(Seed::DEFAULT, fit, progress)?
            };
            (Some(plan), own)
        }
        Reference::Pixels { .. } => (None, own.iter().take(NETS_SETS).cloned().collect()),
    };
    let matrices = plan.as_ref().and_then(crate::sampler::Plan::generating_matrices);
    if matrices.is_none() && own.len() < NETS_OWN {
        return Ok(None);
    }
    let b = matrices.map_or(2, |m| m.base() as usize);
    let most = matrices.map_or(usize::MAX, crate::sampler::qmc::net::Matrices::cols);
    let limits = Limits::default();
    let pair = |s: &PointSet, j: usize, count: usize| -> Result<PointSet> {
        PointSet::new(2, s.iter().take(count).flat_map(|p| [p[j], p[j + 1]]).collect())
    };
    let mut worst: Option<(usize, usize, usize, usize, usize)> = None;
    let mut excess = 0usize;
    for m in (1..).take_while(|&m| b.checked_pow(m as u32).is_some_and(|p| p <= n) && m <= most) {
        let count = b.pow(m as u32);
        for j in 0..d - 1 {
            progress.check()?;
            let promised = match matrices {
                Some(matrices) => tvalue::of_matrices(matrices, &[j, j + 1], m, &limits)?,
                None => {
                    let mut ts = own.iter().map(|s| pair(s, j, count).map(|p| tvalue::counted(&p, b, m)));
                    if ts.try_fold(true, |all, t| t.map(|t| all && t == 0))? { 0 } else { continue }
                }
            };
            for (k, s) in sets.iter().enumerate().take(NETS_SETS) {
                let t = tvalue::counted(&pair(s, j, count)?, b, m);
                if t > promised && t - promised > excess {
                    excess = t - promised;
                    worst = Some((k, m, j, t, promised));
                }
            }
        }
    }
    let whose = if matrices.is_some() { "samplab's matrices" } else { "samplab's own sets" };
    let detail = match worst {
        None => format!("every prefix of {b}^m points: each pair (j, j + 1) no worse than {whose}"),
        Some((k, m, j, t, promised)) => {
            format!("set {k}, {b}^{m} points, dimensions {j}-{}: t = {t} where {whose} give {promised}", j + 1)
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
