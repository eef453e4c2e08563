//! The atlas (`samplab atlas`): every registered sampler measured the same way, one page
//! per sampler entry and one comparison page, generated from the registry.
//!
//! Each sampler is built at its default parameters and measured in 2D:
//!
//! - its points at 256 and 1024, and the same sets warped to the disk (Shirley & Chiu's
//!   concentric map);
//! - the power spectrum (periodogram, the mean of |S(w)|^2 over the sets) at 1024 points as
//!   a heat map and a radial curve, and the pair correlation function (Heck et al.'s
//!   Gaussian-kernel estimator) averaged over the same sets;
//! - the star and L2-star discrepancies against n, and the RMSE of the estimate of three
//!   integrands (smooth, one edge, a disk), each with its fitted log-log slope;
//! - its generation speed (recorded by `samplab atlas --speed`, see [`Speed`]).
//!
//! Counts: each sampler makes the first count it admits from each of 16, 64, ..., 16384.
//! Sets: the sampler's seed is the run's seed derived with the sampler's name, and the
//! sets of a count are the ones `samplab discrepancy --sampler NAME -n N --sets S --seed K`
//! makes (the page prints K): the atlas's discrepancies are the CLI's, bit for bit, and its
//! radial spectrum is `samplab spectrum`'s. A deterministic construction is measured on one
//! set (two for the spectrum, whose variance needs two).
//!
//! Everything but the speed is a function of the seed and the scale: the same bytes on any
//! thread count (the samplers are measured in parallel and written in registry order).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;
use samplab::construct::Counts;
use samplab::discrepancy::{self, Limits, Metric};
use samplab::integrand::Family;
use samplab::progress::Progress;
use samplab::sampler::{SAMPLERS, SamplerEntry};
use samplab::{PointSet, Sampler, Seed, spatial, spectrum, warp};
use serde::{Deserialize, Serialize};

use crate::html::{STYLE, escape, write};
use crate::plot::{self, HeatMap, LineChart, Scatter, Series};
use crate::{Error, Scale};

/// The counts the atlas aims at; each sampler makes the first count from each it admits.
pub const COUNTS: [usize; 6] = [16, 64, 256, 1024, 4096, 16384];

/// The count of the spectrum, the pair correlation and the comparison's single values.
const AT: usize = 1024;

/// The integrands (a registered family, and what it stands for).
pub const INTEGRANDS: [(&str, &str); 3] = [("smooth", "smooth"), ("halfplane", "edge"), ("disk", "disk")];

/// Radii of the pair correlation, in mean spacings 1/sqrt(n), and its kernel width.
const PCF_RADII: usize = 60;
const PCF_REACH: f64 = 3.0;
const PCF_SIGMA: f64 = 0.125;

/// What an atlas run is asked for.
#[derive(Debug, Clone)]
pub struct Options {
    /// The scale (fast: minutes on two cores; full: more sets and instances, finer
    /// spectra), the seed (each sampler's is derived from it with the sampler's name), the
    /// folder to write (replaced when complete) and whether it may be replaced, as a
    /// reproduction's.
    pub run: crate::Options,
    /// Only these samplers (canonical names or aliases); every entry when empty.
    pub only: Vec<String>,
    /// Measure each sampler's speed now instead of showing the recorded figures.
    pub measure_speed: bool,
    /// A reproduction report (`samplab reproduce --out DIR`) whose experiments are searched
    /// for each sampler, to list where the reproduction uses it.
    pub report: Option<PathBuf>,
    /// The least that draws every page (CI's check of the pages, links and figures): the
    /// counts up to 1024, two sets and two instances of each integrand, a coarse spectrum;
    /// `run.scale` is then not read.
    pub smoke: bool,
}

/// How much the atlas measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Level {
    Smoke,
    Fast,
    Full,
}

impl Level {
    fn of(options: &Options) -> Level {
        match (options.smoke, options.run.scale) {
            (true, _) => Level::Smoke,
            (false, Scale::Fast) => Level::Fast,
            (false, Scale::Full) => Level::Full,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Level::Smoke => "smoke",
            Level::Fast => "fast",
            Level::Full => "full",
        }
    }

    /// The counts aimed at.
    fn counts(self) -> &'static [usize] {
        if self == Level::Smoke { &COUNTS[..4] } else { &COUNTS }
    }

    /// Sets per count: more at the small counts, where one set says least.
    fn sets_at(self, n: usize) -> usize {
        match (self, n) {
            (Level::Smoke, _) => 2,
            (Level::Fast, ..=1024) => 24,
            (Level::Fast, ..=4096) => 8,
            (Level::Fast, _) => 4,
            (Level::Full, ..=1024) => 64,
            (Level::Full, ..=4096) => 32,
            (Level::Full, _) => 16,
        }
    }

    /// Instances of each integrand family, each estimated on every set.
    fn instances(self) -> u64 {
        match self {
            Level::Smoke => 2,
            Level::Fast => 8,
            Level::Full => 32,
        }
    }

    /// Frequencies per axis of the spectrum.
    fn resolution(self) -> usize {
        match self {
            Level::Smoke => 64,
            Level::Fast => 128,
            Level::Full => 256,
        }
    }
}

/// One count's measurements.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// The count aimed at.
    pub target: usize,
    /// The count made.
    pub n: usize,
    /// Sets measured.
    pub sets: usize,
    /// Mean star discrepancy over the sets.
    pub star: f64,
    /// Mean L2-star discrepancy over the sets.
    pub l2_star: f64,
    /// RMSE of each integrand's estimate (in [`INTEGRANDS`] order) over instances and sets.
    pub rmse: Vec<f64>,
}

/// A fitted log-log slope with its 95% interval.
#[derive(Debug, Clone, Serialize)]
pub struct Slope {
    /// What was fitted ("star", "l2-star", "rmse smooth", ...).
    pub of: String,
    /// The slope.
    pub slope: f64,
    /// Its 95% confidence interval.
    pub ci: (f64, f64),
}

/// A sampler's measurements, as `samplers/NAME.json` holds them.
#[derive(Debug, Clone, Serialize)]
pub struct Measured {
    /// The canonical spec measured (the entry at its defaults).
    pub spec: String,
    /// The seed given to every `generate_sets` call (the CLI's `--seed`).
    pub seed: u64,
    /// Per count.
    pub rows: Vec<Row>,
    /// The slopes against n.
    pub slopes: Vec<Slope>,
    /// The count of the single values below.
    pub n: usize,
    /// Sets of the spectrum and the pair correlation.
    pub spectrum_sets: usize,
    /// Frequencies per axis of the spectrum.
    pub res: usize,
    /// The radial mean of the periodogram, bins 1..R/2-1 (frequency = bin), as `samplab
    /// spectrum` writes it: S(w) = (1/n) sum exp(-2 pi i w.x), so white noise is 1/n.
    pub radial: Vec<f64>,
    /// Mean of n times the radial periodogram over 0 < |w| <= sqrt(n)/2: the energy left at
    /// low frequencies (0 for a perfect blue noise, 1 for white noise).
    pub low_frequency_energy: f64,
    /// Mean effective Nyquist frequency over the sets (the `nyquist` metric).
    pub nyquist: f64,
    /// Mean relative radius over the sets (the `relative-radius` metric).
    pub relative_radius: f64,
    /// The largest t, in base 2, of the sets as (t, m, 2)-nets (the `t-value` metric), when
    /// n is a power of 2: t = 0 is a (0, m, 2)-net, t = m no stratification at all.
    pub t_value: Option<f64>,
    /// Radii (absolute, on the unit torus) and the mean pair correlation there.
    pub pcf: Vec<(f64, f64)>,
}

/// A sampler's speed: points per second making one set of `n` points.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Speed {
    /// The largest count timed (2^20, or less where one set took over a second).
    pub n: usize,
    /// Seconds for one set of `n` points (the best of the runs).
    pub seconds: f64,
}

/// The speeds the pages show and where they come from.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Speeds {
    /// Where and when they were measured.
    pub measured: String,
    /// Per sampler name.
    pub samplers: std::collections::BTreeMap<String, Speed>,
}

/// The speeds recorded with the sources (`data/atlas_speed.json`, from `samplab atlas
/// --speed`'s `speed.json`).
///
/// # Panics
/// Never at run time: the file is compiled in, and a test reads it.
pub fn recorded_speeds() -> Speeds {
    serde_json::from_str(include_str!("../data/atlas_speed.json")).expect("data/atlas_speed.json is valid")
}

/// Where the reproduction uses a sampler: a paper, one of its experiments, and the claims
/// that experiment decides.
#[derive(Debug, Clone, Serialize)]
pub struct Use {
    /// The paper's key (its page is `KEY.html` in the report).
    pub paper: String,
    /// The experiment's id (its section's anchor).
    pub experiment: String,
    /// The experiment's title.
    pub title: String,
    /// The claims the paper's coverage list gives that experiment.
    pub claims: Vec<String>,
}

/// One sampler's page: its entry, and its measurements or why there are none.
struct Page {
    entry: &'static SamplerEntry,
    measured: Result<Measured, String>,
    figures: Vec<(String, String, Vec<u8>)>,
    uses: Vec<Use>,
}

/// The file-name stem of a sampler's page and figures.
fn stem(entry: &SamplerEntry) -> &'static str {
    entry.about.name
}

/// Build the atlas into `options.run.out`, telling `progress` of each sampler measured (one
/// unit per sampler; it is checked for a stop inside the long work). Returns the number of
/// pages written.
///
/// # Errors
/// An unknown `--only` name, a sampler failing at a count it declares (a bug: reported,
/// not hidden), a plot or write failure, a stop ([`samplab::Error::Interrupted`]); the
/// target folder is then left as it was.
pub fn build(options: &Options, stop: &AtomicBool, progress: &Progress) -> Result<usize, Error> {
    samplab::io::check_folder(&options.run.out, options.run.replace)?;
    if let Some(report) = &options.report {
        use samplab::io::Role;
        samplab::io::refuse_overlap(&[Role::Input("the report", report), Role::Folder("the atlas", &options.run.out)])?;
    }
    let mut entries: Vec<&'static SamplerEntry> = if options.only.is_empty() {
        SAMPLERS.iter().collect()
    } else {
        options.only.iter().map(|name| SAMPLERS.lookup(name)).collect::<Result<_, _>>()?
    };
    // a sampler named twice (by two of its names) has one page
    let mut seen = Vec::new();
    entries.retain(|e| !seen.contains(&e.about.name) && (seen.push(e.about.name), true).1);
    let speeds = if options.measure_speed { measure_speeds(&entries, stop)? } else { recorded_speeds() };
    let report_uses = match &options.report {
        Some(dir) => uses_in_report(dir)?,
        None => Vec::new(),
    };
    let pages: Vec<Page> = entries
        .par_iter()
        .map(|&entry| {
            let measured = match measure(entry, Level::of(options), options.run.seed, &Progress::until(stop)) {
                // an entry that needs a file (its parameters) has nothing to measure alone
                Err(Error::Samplab(e))
                    if e != samplab::Error::Interrupted
                        && entry.about.params.iter().any(|p| matches!(p.kind, samplab::spec::Kind::Path)) =>
                {
                    Err(e.to_string())
                }
                other => Ok(other?),
            };
            let (measured, figures) = match measured {
                Ok((m, drawn)) => {
                    let figures = figures(entry, &m, &drawn)?;
                    (Ok(m), figures)
                }
                Err(why) => (Err(why), Vec::new()),
            };
            let uses =
                report_uses.iter().filter(|(names, _)| names.contains(&entry.about.name)).map(|(_, u)| u.clone());
            progress.advance(1)?;
            Ok(Page { entry, measured, figures, uses: uses.collect() })
        })
        .collect::<Result<_, Error>>()?;
    if stop.load(Ordering::Relaxed) {
        return Err(samplab::Error::Interrupted.into());
    }
    samplab::io::write_folder(&options.run.out, options.run.replace, |dir| write_atlas(dir, &pages, &speeds, options))?;
    Ok(pages.len())
}

/// The first count from `target` that the sampler can make in 2D (`target` itself where
/// the counts are a rule of the parameters).
fn count_from(entry: &SamplerEntry, sampler: &Sampler, target: usize) -> Option<usize> {
    let n = match entry.counts {
        Counts::Rule(_) => target,
        counts => counts.first_from(target, 2)?,
    };
    sampler.plan(n, 2).is_ok().then_some(n)
}

/// The mean of `metric` over `sets`, each computed as `samplab discrepancy` does.
fn mean_metric(metric: &str, sets: &[PointSet]) -> Result<f64, Error> {
    Ok(samplab::stats::Summary::of(&metric_values(metric, sets)?).mean)
}

/// The largest value of `metric` over `sets`.
fn max_metric(metric: &str, sets: &[PointSet]) -> Result<f64, Error> {
    Ok(samplab::stats::Summary::of(&metric_values(metric, sets)?).max)
}

/// `metric` of each of `sets`.
fn metric_values(metric: &str, sets: &[PointSet]) -> Result<Vec<f64>, Error> {
    let metric = Metric::parse(metric)?;
    let limits = Limits::new(None)?;
    Ok(sets.iter().map(|s| discrepancy::compute(&metric, s, limits)).collect::<Result<_, _>>()?)
}

/// What the figures need beyond the numbers: set 0 at each pictured count, and the
/// periodogram's grid.
struct Drawn {
    sets: Vec<(usize, PointSet)>,
    periodogram: Vec<f64>,
}

/// Measure one sampler (its entry at the default parameters).
fn measure(
    entry: &'static SamplerEntry,
    level: Level,
    seed: Seed,
    progress: &Progress,
) -> Result<(Measured, Drawn), Error> {
    let (_, params) = SAMPLERS.resolve(entry.about.name)?;
    let sampler = entry.build(&params)?;
    let seed = seed.derive_str(entry.about.name);
    let families: Vec<Family> = INTEGRANDS.iter().map(|(f, _)| Family::parse(f)).collect::<Result<_, _>>()?;
    let integrands = families
        .iter()
        .map(|f| (0..level.instances()).map(|k| f.instance(seed.derive_str("integrands"), k)).collect())
        .collect::<Result<Vec<Vec<_>>, _>>()?;
    let mut rows = Vec::new();
    let mut at: Option<Vec<PointSet>> = None;
    let mut pictured = Vec::new();
    for &target in level.counts() {
        let Some(n) = count_from(entry, &sampler, target) else { continue };
        if rows.iter().any(|r: &Row| r.n == n) {
            continue;
        }
        let m = if entry.randomized { level.sets_at(target) } else { 1 };
        let plan = sampler.plan(n, 2)?;
        let sets = plan.generate_sets(seed, if target == AT { m.max(2) } else { m }, progress)?;
        rows.push(Row {
            target,
            n,
            sets: m,
            star: mean_metric("star", &sets[..m])?,
            l2_star: mean_metric("l2-star", &sets[..m])?,
            rmse: integrands.iter().map(|fs| rmse(fs, &sets[..m])).collect(),
        });
        if target == 256 || target == AT {
            pictured.push((target, sets[0].clone()));
        }
        if target == AT {
            at = Some(sets);
        }
        progress.check()?;
    }
    let sets = at.ok_or_else(|| samplab::Error::Infeasible {
        what: entry.about.name.into(),
        reason: format!("no count near {AT} in 2D"),
    })?;
    let n = sets[0].len();
    let res = level.resolution();
    let st = spectrum::statistics(&sets, res, spectrum::Method::of(false, 1e-9))?;
    let (radial, _) = spectrum::radial(&st.periodogram, res, 2);
    let low = (n as f64).sqrt() / 2.0;
    let lows: Vec<f64> = radial.iter().enumerate().filter(|(b, _)| (*b + 1) as f64 <= low).map(|(_, v)| *v).collect();
    let measured = Measured {
        spec: sampler.spec().to_string(),
        seed: seed.0,
        n,
        spectrum_sets: sets.len(),
        res,
        low_frequency_energy: n as f64 * lows.iter().sum::<f64>() / lows.len().max(1) as f64,
        nyquist: mean_metric("nyquist", &sets)?,
        relative_radius: mean_metric("relative-radius", &sets)?,
        t_value: if n.is_power_of_two() { Some(max_metric("t-value", &sets)?) } else { None },
        pcf: pair_correlation(&sets)?,
        radial,
        slopes: slopes(&rows),
        rows,
    };
    Ok((measured, Drawn { sets: pictured, periodogram: st.periodogram }))
}

/// The RMSE of the estimates of the integrands `fs` (instances of one family) over `sets`.
fn rmse(fs: &[Box<dyn samplab::integrand::Integrand>], sets: &[PointSet]) -> f64 {
    let mut sum = 0.0;
    for f in fs {
        for set in sets {
            let mut values = vec![0.0; set.len()];
            f.eval_many(set.as_slice(), &mut values);
            sum += (values.iter().sum::<f64>() / set.len() as f64 - f.exact()).powi(2);
        }
    }
    (sum / (fs.len() * sets.len()) as f64).sqrt()
}

/// The mean pair correlation of `sets` at [`PCF_RADII`] radii up to [`PCF_REACH`] mean
/// spacings, kernel width [`PCF_SIGMA`] spacings: (absolute radius, g).
fn pair_correlation(sets: &[PointSet]) -> Result<Vec<(f64, f64)>, Error> {
    let spacing = 1.0 / (sets[0].len() as f64).sqrt();
    let radii: Vec<f64> = (1..=PCF_RADII).map(|i| PCF_REACH * spacing * i as f64 / PCF_RADII as f64).collect();
    let mut pcf = vec![0.0; PCF_RADII];
    for set in sets {
        for (acc, g) in pcf.iter_mut().zip(spatial::pcf(set, &radii, PCF_SIGMA * spacing)?) {
            *acc += g / sets.len() as f64;
        }
    }
    Ok(radii.into_iter().zip(pcf).collect())
}

/// The log-log slopes against n of the discrepancies and of each integrand's RMSE.
fn slopes(rows: &[Row]) -> Vec<Slope> {
    let mut out = Vec::new();
    let mut fit = |of: String, y: &dyn Fn(&Row) -> f64| {
        let pts: Vec<(f64, f64)> = rows.iter().map(|r| (r.n as f64, y(r))).collect();
        if let Some((slope, ci)) = samplab::experiment::loglog_fit(&pts) {
            out.push(Slope { of, slope, ci });
        }
    };
    fit("star".into(), &|r| r.star);
    fit("l2-star".into(), &|r| r.l2_star);
    for (i, (_, what)) in INTEGRANDS.iter().enumerate() {
        fit(format!("rmse {what}"), &|r| r.rmse[i]);
    }
    out
}

/// Time one set of each sampler at 2^10, 2^12, ... up to 2^20 points (the first count
/// admitted from each), stopping after a set that takes over a second; the best of three
/// runs below a tenth of a second.
fn measure_speeds(entries: &[&'static SamplerEntry], stop: &AtomicBool) -> Result<Speeds, Error> {
    let mut samplers = std::collections::BTreeMap::new();
    for &entry in entries {
        let Ok((_, params)) = SAMPLERS.resolve(entry.about.name) else { continue };
        let Ok(sampler) = entry.build(&params) else { continue };
        let mut best: Option<Speed> = None;
        for k in (10..=20).step_by(2) {
            let Some(n) = count_from(entry, &sampler, 1 << k) else { break };
            let plan = sampler.plan(n, 2)?;
            let mut seconds = f64::INFINITY;
            for run in 0..3u64 {
                let start = std::time::Instant::now();
                plan.generate(Seed(run))?;
                seconds = seconds.min(start.elapsed().as_secs_f64());
                if stop.load(Ordering::Relaxed) {
                    return Err(samplab::Error::Interrupted.into());
                }
                if seconds > 0.1 {
                    break;
                }
            }
            best = Some(Speed { n, seconds });
            if seconds > 1.0 {
                break;
            }
        }
        if let Some(s) = best {
            samplers.insert(entry.about.name.to_string(), s);
        }
    }
    let measured = format!(
        "measured by samplab atlas --speed (samplab {}, {} thread(s), {})",
        env!("CARGO_PKG_VERSION"),
        rayon::current_num_threads(),
        std::env::consts::ARCH
    );
    Ok(Speeds { measured, samplers })
}

/// The experiments of a reproduction report (`DIR/PAPER.html`, for the papers it has) that
/// use each sampler: an experiment uses the samplers whose canonical name or alias is the
/// text of one of its table cells or of a legend label in one of its SVG figures (up to the
/// spec's first ':' or space).
fn uses_in_report(dir: &Path) -> Result<Vec<(Vec<&'static str>, Use)>, Error> {
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| crate::io_error(p, e));
    let papers = crate::paper::all();
    if !papers.iter().any(|paper| dir.join(format!("{}.html", paper.key)).is_file()) {
        let what = if dir.is_dir() {
            "holds no paper's page"
        } else if dir.exists() {
            "is not a folder"
        } else {
            "does not exist"
        };
        let reason = format!("{what}; the report is the folder `samplab reproduce --out DIR` writes");
        return Err(crate::io_error(dir, std::io::Error::other(reason)));
    }
    let mut out = Vec::new();
    for paper in papers {
        let path = dir.join(format!("{}.html", paper.key));
        // a report of some papers (`--only`) has no page for the others
        if !path.is_file() {
            continue;
        }
        let html = read(&path)?;
        for e in &paper.experiments {
            let start = format!("<h2 id=\"{}\">", e.id);
            let Some(at) = html.find(&start) else { continue };
            let section = &html[at + start.len()..];
            let section = &section[..section.find("<h2 id=").unwrap_or(section.len())];
            let mut texts: Vec<String> = between(section, "<td>", "</td>").map(str::to_string).collect();
            for svg in between(section, "href=\"figures/", ".svg\"") {
                let svg = read(&dir.join(format!("figures/{svg}.svg")))?;
                texts.extend(between(&svg, "\">", "</text>").map(|t| t.rsplit('>').next().unwrap_or(t).to_string()));
            }
            let mut names: Vec<&'static str> = texts
                .iter()
                .filter_map(|t| {
                    let word = t.trim().split([':', ' ', '+']).next().unwrap_or("");
                    SAMPLERS.lookup(word).ok().map(|s| s.about.name)
                })
                .collect();
            names.sort_unstable();
            names.dedup();
            let title = section.split("</h2>").next().unwrap_or("").to_string();
            let claims = crate::coverage::items(paper.key)
                .into_iter()
                .filter(|it| it.experiment.as_deref() == Some(e.id))
                .flat_map(|it| it.claims)
                .collect();
            out.push((names, Use { paper: paper.key.into(), experiment: e.id.into(), title, claims }));
        }
    }
    Ok(out)
}

/// The pieces of `text` between each `open` and the next `close`.
fn between<'t>(text: &'t str, open: &'t str, close: &'t str) -> impl Iterator<Item = &'t str> + 't {
    text.split(open).skip(1).filter_map(move |s| s.find(close).map(|e| &s[..e]))
}

/// A sampler's figures: (file name, caption, PNG bytes).
fn figures(entry: &SamplerEntry, m: &Measured, drawn: &Drawn) -> Result<Vec<(String, String, Vec<u8>)>, Error> {
    let name = stem(entry);
    let mut out = point_figures(name, drawn)?;
    out.extend(spectral_figures(name, m, drawn)?);
    out.extend(convergence_figures(name, m)?);
    Ok(out)
}

/// One figure: (file name, caption, PNG bytes).
type Fig = (String, String, Vec<u8>);

/// Set 0 at each pictured count, in the square and on the disk.
fn point_figures(name: &str, drawn: &Drawn) -> Result<Vec<Fig>, Error> {
    let mut out = Vec::new();
    let disk = warp::lookup("disk.concentric")?;
    for (target, set) in &drawn.sets {
        let n = set.len();
        let scatter = Scatter { set, axes: [0, 1], grid: None, title: format!("{n} points") };
        out.push((
            format!("{name}-points-{target}.png"),
            format!("{n} points (set 0)"),
            plot::png(&scatter, (420, 420))?,
        ));
        let warped = warp::apply(disk, set)?;
        let scatter = Scatter { set: &warped, axes: [0, 1], grid: None, title: format!("{n} points on the disk") };
        out.push((
            format!("{name}-disk-{target}.png"),
            format!("the same {n} points on the disk (concentric map)"),
            plot::png(&scatter, (420, 420))?,
        ));
    }
    Ok(out)
}

/// The power spectrum as a heat map and a radial curve, and the pair correlation.
fn spectral_figures(name: &str, m: &Measured, drawn: &Drawn) -> Result<Vec<Fig>, Error> {
    let mut out = Vec::new();
    let heat = HeatMap::centred(
        format!("power spectrum, {} points, {} sets", m.n, m.spectrum_sets),
        "n x periodogram".into(),
        drawn.periodogram.iter().map(|p| p * m.n as f64).collect(),
        m.res,
    );
    out.push((
        format!("{name}-spectrum.png"),
        format!(
            "power spectrum (n times the periodogram: white noise is 1) of {} points, mean over {} sets, log scale",
            m.n, m.spectrum_sets
        ),
        plot::png(&heat, (480, 420))?,
    ));
    let nu = (m.n as f64).sqrt();
    let radial = LineChart {
        title: "radial power spectrum".into(),
        x_label: "frequency / sqrt(n)".into(),
        y_label: "n x periodogram".into(),
        series: vec![
            Series::line(
                name,
                m.radial.iter().enumerate().map(|(b, v)| ((b + 1) as f64 / nu, v * m.n as f64)).collect(),
            ),
            Series {
                dashed: true,
                ..Series::line("white noise", vec![(1.0 / nu, 1.0), (m.radial.len() as f64 / nu, 1.0)])
            },
        ],
        log_y: false,
        log_x: false,
        polar: false,
    };
    out.push((
        format!("{name}-radial.png"),
        "radial mean of the power spectrum (white noise is 1)".into(),
        plot::png(&radial, (560, 340))?,
    ));
    let pcf = LineChart {
        title: "pair correlation function".into(),
        x_label: "distance x sqrt(n)".into(),
        y_label: "g(r)".into(),
        series: vec![
            Series::line(name, m.pcf.iter().map(|(r, g)| (r * nu, *g)).collect()),
            Series { dashed: true, ..Series::line("uniform random", vec![(0.0, 1.0), (PCF_REACH, 1.0)]) },
        ],
        log_y: false,
        log_x: false,
        polar: false,
    };
    out.push((
        format!("{name}-pcf.png"),
        format!("pair correlation at {} points, mean over {} sets", m.n, m.spectrum_sets),
        plot::png(&pcf, (560, 340))?,
    ));
    Ok(out)
}

/// The discrepancies and the integration errors against n.
fn convergence_figures(name: &str, m: &Measured) -> Result<Vec<Fig>, Error> {
    let mut out = Vec::new();
    let marked = |label: &str, pts: Vec<(f64, f64)>| Series { markers: true, ..Series::line(label, pts) };
    let reference = |label: &str, y0: f64, slope: f64| {
        let ns = [m.rows[0].n as f64, m.rows[m.rows.len() - 1].n as f64];
        Series { dashed: true, ..Series::line(label, ns.iter().map(|&n| (n, y0 * (n / ns[0]).powf(slope))).collect()) }
    };
    let first = &m.rows[0];
    let disc = LineChart {
        title: "discrepancy".into(),
        x_label: "n".into(),
        y_label: "discrepancy".into(),
        series: vec![
            marked("star", m.rows.iter().map(|r| (r.n as f64, r.star)).collect()),
            marked("L2-star", m.rows.iter().map(|r| (r.n as f64, r.l2_star)).collect()),
            reference("n^-1/2", first.star, -0.5),
            reference("n^-1", first.star, -1.0),
        ],
        log_y: true,
        log_x: true,
        polar: false,
    };
    out.push((
        format!("{name}-discrepancy.png"),
        "star and L2-star discrepancy against n".into(),
        plot::png(&disc, (560, 380))?,
    ));
    let mut series: Vec<Series> = INTEGRANDS
        .iter()
        .enumerate()
        .map(|(i, (_, what))| marked(what, m.rows.iter().map(|r| (r.n as f64, r.rmse[i])).collect()))
        .collect();
    series.push(reference("n^-1/2", first.rmse[0].max(first.rmse[1]), -0.5));
    let error = LineChart {
        title: "integration error".into(),
        x_label: "n".into(),
        y_label: "RMSE".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    };
    out.push((
        format!("{name}-error.png"),
        "RMSE of the estimate against n: a smooth integrand, one with an edge (a half-plane), a disk".into(),
        plot::png(&error, (560, 380))?,
    ));
    Ok(out)
}

/// A page of the atlas; `root` leads from the page to the atlas's folder.
fn page(title: &str, root: &str, body: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><link rel=\"stylesheet\" href=\"{root}style.css\"></head>\n<body><nav><a href=\"{root}index.html\">atlas: every sampler side by side</a></nav>\n<h1>{t}</h1>\n{body}</body></html>\n",
        t = escape(title)
    )
}

fn speed_text(speed: Option<&Speed>) -> String {
    speed.map_or("not measured".into(), |s| {
        format!("{:.3e} points/s (one set of {} points in {:.4} s)", s.n as f64 / s.seconds, s.n, s.seconds)
    })
}

/// Every file of the atlas.
fn write_atlas(dir: &Path, pages: &[Page], speeds: &Speeds, options: &Options) -> Result<(), Error> {
    for sub in ["samplers", "figures"] {
        std::fs::create_dir_all(dir.join(sub)).map_err(|e| crate::io_error(dir, e))?;
    }
    write(&dir.join("style.css"), format!("{STYLE}{ATLAS_STYLE}").as_bytes())?;
    write(&dir.join("speed.json"), serde_json::to_string_pretty(speeds).expect("plain data").as_bytes())?;
    for p in pages {
        for (file, _, png) in &p.figures {
            write(&dir.join("figures").join(file), png)?;
        }
        if let Ok(m) = &p.measured {
            write(
                &dir.join(format!("samplers/{}.json", stem(p.entry))),
                serde_json::to_string_pretty(m).expect("plain data").as_bytes(),
            )?;
        }
        let html = sampler_page(p, speeds, options);
        write(&dir.join(format!("samplers/{}.html", stem(p.entry))), html.as_bytes())?;
    }
    write(&dir.join("index.html"), comparison_page(pages, speeds, options).as_bytes())
}

const ATLAS_STYLE: &str = ".figs{display:flex;flex-wrap:wrap;gap:.6em}.figs figure{margin:0}.figs img{max-width:100%}
.multiples{display:grid;grid-template-columns:repeat(auto-fill,minmax(150px,1fr));gap:.5em}
.multiples a{font-size:.8em;text-decoration:none;color:#222}.multiples img{width:100%;border:1px solid #ddd}
th[data-sort]{cursor:pointer}th[data-sort]:after{content:' \\2195';color:#999}
";

fn scale_words(options: &Options) -> String {
    format!("scale {}, seed {}", Level::of(options).name(), options.run.seed.0)
}

/// The way from `from` (a folder) to `to`, both made absolute, as a relative URL.
fn relative(from: &Path, to: &Path) -> String {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let (from, to) = (absolute(from), absolute(to));
    let (a, b): (Vec<_>, Vec<_>) = (from.components().collect(), to.components().collect());
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut parts: Vec<String> = vec!["..".into(); a.len() - common];
    parts.extend(b[common..].iter().map(|c| c.as_os_str().to_string_lossy().to_string()));
    if parts.is_empty() { ".".into() } else { parts.join("/") }
}

fn sampler_page(p: &Page, speeds: &Speeds, options: &Options) -> String {
    let a = &p.entry.about;
    let mut h = format!("<p>{}</p>\n<table>", escape(a.summary));
    let mut row = |k: &str, v: String| {
        let _ = writeln!(h, "<tr><th>{k}</th><td style=\"text-align:left\">{v}</td></tr>");
    };
    if !a.aliases.is_empty() {
        row("aliases", escape(&a.aliases.join(", ")));
    }
    row("counts", escape(&p.entry.counts.describe()));
    row("dimensions", escape(p.entry.dims));
    row(
        "randomized",
        if p.entry.randomized {
            "yes: every seed gives other points".into()
        } else {
            "no: the same points for every seed".into()
        },
    );
    for prm in a.params {
        row(
            &format!("parameter <code>{}</code>", escape(prm.name)),
            format!("{} (default {}): {}", escape(&prm.range_text()), escape(&prm.default_text()), escape(prm.doc)),
        );
    }
    let refs: Vec<String> = a
        .references
        .iter()
        .map(|k| samplab::bibliography::lookup(k).map_or_else(|| escape(k), |r| escape(r.citation)))
        .collect();
    if !refs.is_empty() {
        row("references", refs.join("<br>"));
    }
    row(
        "speed",
        escape(&speed_text(speeds.samplers.get(a.name)))
            + &format!(" <span class=\"caption\">{}</span>", escape(&speeds.measured)),
    );
    h.push_str("</table>\n");
    match &p.measured {
        Err(why) => {
            let _ = writeln!(h, "<p class=\"note\">Not measured: it needs its parameters ({}).</p>", escape(why));
        }
        Ok(m) => h.push_str(&measured_html(p, m, options)),
    }
    h.push_str(&uses_html(p, options));
    page(a.name, "../", &h)
}

/// A measured sampler's figures, numbers and the commands that give the same numbers.
fn measured_html(p: &Page, m: &Measured, options: &Options) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "<h2>Measured</h2>\n<p>Spec <code>{}</code> in 2D, {}. The same sets from the command line: <code>samplab discrepancy star l2-star --sampler {} -n N --sets S --seed {}</code>; the spectrum: <code>samplab spectrum --sampler {} -n {} --sets {} --seed {} --res {}</code>. <a href=\"{}.json\">All numbers (JSON)</a>.</p>",
        escape(&m.spec),
        scale_words(options),
        escape(&m.spec),
        m.seed,
        escape(&m.spec),
        m.n,
        m.spectrum_sets,
        m.seed,
        m.res,
        stem(p.entry)
    );
    h.push_str("<div class=\"figs\">\n");
    for (file, caption, _) in &p.figures {
        let _ = writeln!(
            h,
            "<figure><img src=\"../figures/{f}\" alt=\"{c}\"><figcaption>{c}</figcaption></figure>",
            f = escape(file),
            c = escape(caption)
        );
    }
    h.push_str("</div>\n<table><tr><th>n aimed at</th><th>n</th><th>sets</th><th>star</th><th>L2-star</th>");
    for (_, what) in INTEGRANDS {
        let _ = write!(h, "<th>RMSE {what}</th>");
    }
    h.push_str("</tr>\n");
    for r in &m.rows {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.4e}</td><td>{:.4e}</td>",
            r.target, r.n, r.sets, r.star, r.l2_star
        );
        for e in &r.rmse {
            let _ = write!(h, "<td>{e:.3e}</td>");
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n<table><tr><th>log-log slope against n</th><th>slope</th><th>95% interval</th></tr>\n");
    for s in &m.slopes {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td>{:.2}</td><td>[{:.2}, {:.2}]</td></tr>",
            escape(&s.of),
            s.slope,
            s.ci.0,
            s.ci.1
        );
    }
    let _ = writeln!(
        h,
        "</table>\n<p>At {} points: low-frequency energy {:.3} (mean periodogram over 0 &lt; |w| &le; sqrt(n)/2; white noise 1), effective Nyquist frequency {:.3}, relative radius {:.3}; {}.</p>",
        m.n,
        m.low_frequency_energy,
        m.nyquist,
        m.relative_radius,
        m.t_value.map_or("no t-value (n is not a power of 2)".into(), |t| format!(
            "t-value {t} in base 2, the largest over the sets (t = 0: a (0, m, 2)-net; <code>samplab t-values</code> gives each count's)"
        ))
    );
    h
}

/// Where the reproduction uses the sampler, from the report given to `--report`.
fn uses_html(p: &Page, options: &Options) -> String {
    let mut h = String::from("<h2>In the reproduction</h2>\n");
    let report = options.report.as_ref().map_or(String::new(), |r| relative(&options.run.out.join("samplers"), r));
    if options.report.is_none() {
        h.push_str("<p>(built without a reproduction report: <code>samplab atlas --report DIR</code> lists the experiments that use it)</p>\n");
    } else if p.uses.is_empty() {
        h.push_str("<p>No experiment of the reproduction names it in a table or a figure legend.</p>\n");
    } else {
        h.push_str("<ul>\n");
        for u in &p.uses {
            let _ = write!(
                h,
                "<li><a href=\"{report}/{paper}.html#{id}\">{paper}: {title}</a>",
                report = escape(&report),
                paper = escape(&u.paper),
                id = escape(&u.experiment),
                title = u.title
            );
            if !u.claims.is_empty() {
                h.push_str("; claims: ");
                let links: Vec<String> = u
                    .claims
                    .iter()
                    .map(|c| {
                        format!(
                            "<a href=\"{}/{}.html#claim-{c}\">{c}</a>",
                            escape(&report),
                            escape(&u.paper),
                            c = escape(c)
                        )
                    })
                    .collect();
                h.push_str(&links.join(", "));
            }
            h.push_str("</li>\n");
        }
        h.push_str("</ul>\n");
    }
    h
}

fn comparison_page(pages: &[Page], speeds: &Speeds, options: &Options) -> String {
    let mut h = format!(
        "<p>Every sampler of samplab's registry, at its default parameters, measured the same way in 2D ({}). Click a column to sort. Slopes are log-log fits against n = 16 to 16384; single values are at 1024 points (or the first count from 1024 the sampler makes); the t-value is the largest t over those sets as (t, m, 2)-nets in base 2 (t = 0 at best), where the count is a power of 2. Speed: {}.</p>\n",
        scale_words(options),
        escape(&speeds.measured)
    );
    h.push_str("<table id=\"compare\"><thead><tr><th data-sort=\"t\">sampler</th><th data-sort=\"t\">randomized</th><th data-sort=\"n\">star slope</th><th data-sort=\"n\">L2-star slope</th>");
    for (_, what) in INTEGRANDS {
        let _ = write!(h, "<th data-sort=\"n\">RMSE slope, {what}</th>");
    }
    h.push_str("<th data-sort=\"n\">star at 1024</th><th data-sort=\"n\">L2-star at 1024</th><th data-sort=\"n\">low-frequency energy</th><th data-sort=\"n\">effective Nyquist</th><th data-sort=\"n\">relative radius</th><th data-sort=\"n\">t-value at 1024</th><th data-sort=\"n\">points/s</th></tr></thead><tbody>\n");
    let num = |v: Option<f64>, digits: usize| {
        v.filter(|x| x.is_finite())
            .map_or("<td data-v=\"\">-</td>".into(), |x| format!("<td data-v=\"{x}\">{x:.digits$}</td>"))
    };
    for p in pages {
        let name = stem(p.entry);
        let _ = write!(
            h,
            "<tr><td><a href=\"samplers/{name}.html\">{name}</a></td><td>{}</td>",
            if p.entry.randomized { "yes" } else { "no" }
        );
        let m = p.measured.as_ref().ok();
        let slope = |of: &str| m.and_then(|m| m.slopes.iter().find(|s| s.of == of)).map(|s| s.slope);
        for of in
            ["star", "l2-star"].into_iter().map(String::from).chain(INTEGRANDS.iter().map(|(_, w)| format!("rmse {w}")))
        {
            h += &num(slope(&of), 2);
        }
        let at = m.and_then(|m| m.rows.iter().find(|r| r.target == AT));
        h += &num(at.map(|r| r.star), 5);
        h += &num(at.map(|r| r.l2_star), 5);
        h += &num(m.map(|m| m.low_frequency_energy), 3);
        h += &num(m.map(|m| m.nyquist), 3);
        h += &num(m.map(|m| m.relative_radius), 3);
        h += &num(m.and_then(|m| m.t_value), 0);
        let speed = speeds.samplers.get(name).map(|s| s.n as f64 / s.seconds);
        h += &speed
            .filter(|x| x.is_finite())
            .map_or("<td data-v=\"\">-</td>".into(), |x| format!("<td data-v=\"{x}\">{x:.2e}</td>"));
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody></table>\n<h2>Points at 1024</h2>\n<div class=\"multiples\">\n");
    let multiples = |h: &mut String, kind: &str| {
        for p in pages {
            let name = stem(p.entry);
            if let Some((file, _, _)) = p.figures.iter().find(|(f, _, _)| f.ends_with(kind)) {
                let _ = writeln!(
                    h,
                    "<a href=\"samplers/{name}.html\"><img src=\"figures/{file}\" alt=\"{name}\" loading=\"lazy\"><br>{name}</a>"
                );
            }
        }
    };
    multiples(&mut h, "-points-1024.png");
    h.push_str("</div>\n<h2>Power spectra at 1024</h2>\n<div class=\"multiples\">\n");
    multiples(&mut h, "-spectrum.png");
    h.push_str("</div>\n");
    h.push_str(SORT_SCRIPT);
    page("samplab atlas: every sampler side by side", "", &h)
}

/// Sorting the comparison table by a column (numbers by their full value, names as text).
const SORT_SCRIPT: &str = "<script>
document.querySelectorAll('#compare th[data-sort]').forEach(function (th, col) {
  th.addEventListener('click', function () {
    var body = th.closest('table').tBodies[0], rows = Array.prototype.slice.call(body.rows);
    var up = th.dataset.dir !== 'up'; th.dataset.dir = up ? 'up' : 'down';
    var key = function (r) { var c = r.cells[col]; return c.dataset.v !== undefined ? (c.dataset.v === '' ? NaN : Number(c.dataset.v)) : c.textContent; };
    rows.sort(function (a, b) {
      var x = key(a), y = key(b);
      if (typeof x === 'number') { if (isNaN(x)) return 1; if (isNaN(y)) return -1; return up ? x - y : y - x; }
      return up ? x.localeCompare(y) : y.localeCompare(x);
    });
    rows.forEach(function (r) { body.appendChild(r); });
  });
});
</script>
";
