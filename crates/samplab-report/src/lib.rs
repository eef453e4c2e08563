//! # samplab-report
//!
//! Plots, tables, and the reproduction of the four papers samplab builds on (one module
//! per paper). `samplab reproduce` runs the experiments and writes an HTML report with
//! every figure (PNG and SVG) and table (CSV and JSON) beside the published values and
//! the theory, and a verdict on each claim (`claims.json`).
//!
//! The report is written into a temporary folder beside the target and renamed into
//! place when complete, so an interrupted run never leaves a report that looks finished.

#![deny(missing_docs)]

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use samplab::Seed;
use samplab::progress::Progress;
use serde::Serialize;

pub mod atlas;
pub mod coverage;
pub mod criteria;
pub mod html;
pub mod lint;
pub mod paper;
pub mod plot;
pub mod published;

/// Errors of the report crate.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A library error (sampler, metric, ...).
    #[error(transparent)]
    Samplab(#[from] samplab::Error),
    /// A file could not be written.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// The OS error.
        reason: String,
    },
    /// A plot could not be drawn.
    #[error("plot: {0}")]
    Plot(String),
    /// A renderer's error other than the library's (a scene that does not load, ...).
    #[error(transparent)]
    Render(samplab_render::Error),
    /// A paper's coverage (its items in `published.json`, their experiments, claims and
    /// figures) that does not hold together.
    #[error("{paper} coverage: {reason}")]
    Coverage {
        /// The paper's key.
        paper: String,
        /// What does not hold, naming the item.
        reason: String,
    },
    /// What fits none of the typed cases.
    #[error("{0}")]
    Invalid(String),
}

/// Experiment scale: `Fast` (the default, minutes on two cores) or `Full` (the papers' own).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub enum Scale {
    /// Reduced parameters.
    Fast,
    /// The papers' parameters.
    Full,
}

/// What a run tells whoever watches it (a terminal's bars, a Python callback), in order:
/// each experiment starts, says how many units of work it has, advances, and finishes.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Event<'e> {
    /// Experiment `experiment` of paper `paper` started.
    Started {
        /// The paper's key.
        paper: &'e str,
        /// The experiment's id.
        experiment: &'e str,
    },
    /// The running experiment has this many units of work in all.
    Length(u64),
    /// This many more units of the running experiment are done.
    Advanced(u64),
    /// The running experiment finished, after this many seconds.
    Finished(f64),
}

/// Whoever watches a run: called with each [`Event`] and the place of the experiment it
/// concerns in the run (0, 1, .. in the pages' order), from any thread: experiments run
/// side by side, so the events of several interleave.
pub type Watch<'a> = &'a (dyn Fn(usize, Event<'_>) + Sync);

/// A watcher that ignores every event.
pub const UNWATCHED: Watch<'static> = &|_, _| {};

/// What an experiment gets: its scale, seed, the run's watcher and stop flag.
pub struct Ctx<'a> {
    /// The scale.
    pub scale: Scale,
    /// The experiment's own seed (derived from the run's seed and the experiment id).
    pub seed: Seed,
    /// Told of this experiment's length and progress.
    pub watch: Watch<'a>,
    /// Raised to stop the run (Ctrl-C); long library calls are given it.
    pub stop: &'a AtomicBool,
    /// The experiment's place in the run, which the watcher is told with each event.
    pub task: usize,
}

impl Ctx<'_> {
    /// This experiment has `units` units of work in all.
    pub fn set_length(&self, units: u64) {
        (self.watch)(self.task, Event::Length(units));
    }

    /// `units` more units of this experiment are done, without checking the stop flag
    /// (what the library's [`Progress`] reports to).
    pub fn tick(&self, units: u64) {
        (self.watch)(self.task, Event::Advanced(units));
    }

    /// `units` more units of this experiment are done.
    ///
    /// # Errors
    /// [`samplab::Error::Interrupted`] once the run is asked to stop.
    pub fn advance(&self, units: u64) -> Result<(), Error> {
        self.tick(units);
        Ok(Progress::until(self.stop).check()?)
    }

    /// `fast` or `full`, by the scale.
    pub fn pick<T>(&self, fast: T, full: T) -> T {
        if self.scale == Scale::Fast { fast } else { full }
    }
}

/// A table cell.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
#[non_exhaustive]
pub enum Cell {
    /// Text.
    Text(String),
    /// A number shown with `digits` significant decimals.
    Num {
        /// The value.
        value: f64,
        /// Decimals to show.
        #[serde(skip)]
        digits: usize,
    },
    /// Nothing.
    Empty,
}

impl Cell {
    /// A number cell.
    pub fn num(value: f64, digits: usize) -> Cell {
        Cell::Num { value, digits }
    }
    /// The cell as display text.
    pub fn text(&self) -> String {
        match self {
            Cell::Text(t) => t.clone(),
            Cell::Num { value, digits } => format!("{value:.digits$}"),
            Cell::Empty => String::new(),
        }
    }
}

impl From<&str> for Cell {
    fn from(s: &str) -> Cell {
        Cell::Text(s.into())
    }
}

impl From<String> for Cell {
    fn from(s: String) -> Cell {
        Cell::Text(s)
    }
}

/// A table of results.
#[derive(Debug, Clone, Serialize)]
pub struct Table {
    /// File-name stem, unique in the report.
    pub id: String,
    /// What it shows, with the source of any published column.
    pub caption: String,
    /// Column headers.
    pub columns: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<Cell>>,
}

/// A rendered figure.
pub struct Figure {
    /// File-name stem, unique in the report.
    pub id: String,
    /// What it shows.
    pub caption: String,
    /// PNG bytes.
    pub png: Vec<u8>,
    /// SVG text (None for a rendered image, which is only a PNG).
    pub svg: Option<String>,
    /// What the figure lint found ([`lint`]); empty for a clean figure.
    pub lint: Vec<String>,
}

impl Figure {
    /// Render `chart` at `size` as PNG and SVG.
    ///
    /// # Errors
    /// A drawing failure.
    pub fn render(id: &str, caption: &str, chart: &impl plot::Drawable, size: (u32, u32)) -> Result<Figure, Error> {
        let svg = plot::svg(chart, size)?;
        let mut lint = chart.lint();
        lint.extend(lint::svg(&svg));
        Ok(Figure { id: id.into(), caption: caption.into(), png: plot::png(chart, size)?, svg: Some(svg), lint })
    }

    /// A rendered image (already PNG-encoded), shown as it is: enlarged on the page by an
    /// integer factor, nearest neighbour, when narrower than [`lint::MIN_PICTURE_WIDTH`].
    pub fn picture(id: &str, caption: &str, png: Vec<u8>) -> Figure {
        Figure { id: id.into(), caption: caption.into(), png, svg: None, lint: Vec::new() }
    }

    /// The width the page displays the figure at, in CSS pixels: a picture's width times
    /// its enlargement (read from the PNG header); None for a chart, shown as drawn.
    pub fn display_width(&self) -> Option<u32> {
        let header = self.png.get(16..20)?;
        let width = u32::from_be_bytes(header.try_into().ok()?);
        self.svg.is_none().then(|| width * lint::picture_scale(width))
    }
}

pub use criteria::{Decision, Verdict};

/// One of a paper's claims (or one of samplab's own additions), checked.
#[derive(Debug, Clone, Serialize, Default)]
pub struct Claim {
    /// Stable id, unique in its paper, listed by the coverage table of `data/published.json`.
    pub id: String,
    /// The claim in words.
    pub statement: String,
    /// The published number or statement, with its source.
    pub published: String,
    /// Our number.
    pub ours: String,
    /// The closed-form prediction, where there is one.
    pub theory: String,
    /// The verdict and the criterion that gave it.
    #[serde(flatten)]
    pub decision: Decision,
    /// Beside a verdict other than reproduced: a human-written explanation of why ours
    /// differs, naming the experiment in the report that backs it (not shown otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub explanation: Option<String>,
    /// For samplab's own additions (not statements of the paper): their source.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub addition: Option<String>,
    /// Derived, not measured: decided by an identity, algebra, a closed form checked against
    /// itself (a warp inverting its CDF, a limit computed both ways) or a deterministic
    /// sampler at fixed positions, with no random measurement. Reported as "checked" when it
    /// holds and "contradicted" when not, never as a reproduction.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub derived: bool,
}

impl Claim {
    /// The verdict.
    pub fn verdict(&self) -> Verdict {
        self.decision.verdict
    }

    /// The verdict as the report names it: "checked" and "contradicted" for a derived claim
    /// that holds and one that does not.
    pub fn verdict_name(&self) -> &'static str {
        match self.verdict() {
            Verdict::Reproduced if self.derived => "checked",
            Verdict::NotReproduced if self.derived => "contradicted",
            Verdict::Reproduced => "reproduced",
            Verdict::NotReproduced => "not reproduced",
            Verdict::Undecided => "undecided",
        }
    }

    /// The explanation shown beside a verdict other than reproduced: the written one, or
    /// the words "no explanation found".
    pub fn explained(&self) -> Option<&str> {
        match self.verdict() {
            Verdict::Reproduced => None,
            _ => Some(self.explanation.as_deref().unwrap_or(NO_EXPLANATION)),
        }
    }
}

/// The names of the verdicts shown ([`Claim::verdict_name`]), in the order the report
/// counts them.
pub const VERDICT_NAMES: [&str; 5] = ["reproduced", "checked", "not reproduced", "contradicted", "undecided"];

/// How many of `claims` show each verdict, in the order of [`VERDICT_NAMES`].
pub fn tally<'a>(claims: impl IntoIterator<Item = &'a Claim>) -> [usize; 5] {
    let mut counts = [0; 5];
    for c in claims {
        if let Some(k) = VERDICT_NAMES.iter().position(|n| *n == c.verdict_name()) {
            counts[k] += 1;
        }
    }
    counts
}

/// What a claim that is not reproduced says when nobody found why.
pub const NO_EXPLANATION: &str = "no explanation found";

/// What an experiment produces.
#[derive(Default)]
pub struct Output {
    /// Tables.
    pub tables: Vec<Table>,
    /// Figures.
    pub figures: Vec<Figure>,
    /// Claims checked.
    pub claims: Vec<Claim>,
    /// Remarks shown under the experiment (method, parameters, caveats).
    pub notes: Vec<String>,
}

/// One experiment of a paper.
pub struct Experiment {
    /// Stable id (used for seeds and file names).
    pub id: &'static str,
    /// Title.
    pub title: &'static str,
    /// Which tables or figures of the paper it reproduces.
    pub source: &'static str,
    /// The parameters at each scale, in words.
    pub parameters: &'static str,
    /// Run it.
    pub run: fn(&Ctx) -> Result<Output, Error>,
}

/// One paper: its experiments. What each numbered table and figure of the paper maps to
/// (or why it is not attempted) is in the coverage list of `data/published.json`.
pub struct Paper {
    /// Bibliography key (also the page's file name).
    pub key: &'static str,
    /// Short title.
    pub title: &'static str,
    /// Its experiments.
    pub experiments: Vec<Experiment>,
}

/// Options of a reproduction run.
#[derive(Debug, Clone)]
pub struct Options {
    /// Scale.
    pub scale: Scale,
    /// Seed of the whole run.
    pub seed: Seed,
    /// Where the report goes (replaced when the run completes).
    pub out: PathBuf,
    /// Whether `out` may be replaced when samplab did not make it.
    pub replace: samplab::io::Replace,
}

/// The outcome of one experiment, for the pages.
pub struct Done {
    /// The experiment.
    pub experiment: &'static str,
    /// Its title and source.
    pub title: String,
    /// Its parameters.
    pub parameters: String,
    /// When it started, in seconds after the run began.
    pub started: f64,
    /// Seconds it took.
    pub seconds: f64,
    /// What it produced.
    pub output: Output,
}

/// An I/O error on `p`, as the report's error.
pub(crate) fn io_error(p: &Path, e: std::io::Error) -> Error {
    Error::Io { path: p.display().to_string(), reason: e.to_string() }
}

/// Run `papers` and write the report, telling `watch` of each experiment's progress.
/// Returns the claims. The experiments are independent (each has its own seed), so they
/// run side by side on the thread pool, longest first by [`expected_seconds`] (one worker
/// per thread takes the next experiment as it finishes one; each experiment's own
/// parallel work fills the threads the others leave idle); their outputs do not depend on
/// the order. The run stops before the next experiment (and inside the long library
/// calls) once `stop` is raised.
///
/// # Errors
/// An experiment or a write fails (the first in the pages' order is reported), or the run
/// was stopped ([`samplab::Error::Interrupted`]); the target folder is then left as it was.
pub fn reproduce(
    papers: &[&Paper],
    options: &Options,
    stop: &AtomicBool,
    watch: Watch<'_>,
) -> Result<Vec<(String, Claim)>, Error> {
    // refused before the run, not after it
    samplab::io::check_folder(&options.out, options.replace)?;
    let tasks: Vec<(&Paper, &Experiment)> =
        papers.iter().flat_map(|p| p.experiments.iter().map(move |e| (*p, e))).collect();
    let expected = expected_seconds(options.scale);
    let cost = |t: usize| expected.get(&format!("{}/{}", tasks[t].0.key, tasks[t].1.id)).copied().unwrap_or(0.0);
    let mut order: Vec<usize> = (0..tasks.len()).collect();
    order.sort_by(|&a, &b| cost(b).total_cmp(&cost(a)));
    let slots: Vec<std::sync::Mutex<Option<Result<Done, Error>>>> =
        tasks.iter().map(|_| std::sync::Mutex::new(None)).collect();
    let (next, failed) = (std::sync::atomic::AtomicUsize::new(0), AtomicBool::new(false));
    let began = Instant::now();
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads().min(tasks.len()) {
            scope.spawn(|_| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= order.len() || stop.load(Ordering::Relaxed) || failed.load(Ordering::Relaxed) {
                        break;
                    }
                    let (task, (paper, e)) = (order[k], tasks[order[k]]);
                    let ctx = Ctx {
                        scale: options.scale,
                        seed: options.seed.derive_str(&format!("{}/{}", paper.key, e.id)),
                        watch,
                        stop,
                        task,
                    };
                    watch(task, Event::Started { paper: paper.key, experiment: e.id });
                    let start = Instant::now();
                    let done = (e.run)(&ctx).map(|output| Done {
                        experiment: e.id,
                        title: format!("{} — {}", e.title, e.source),
                        parameters: e.parameters.into(),
                        started: start.duration_since(began).as_secs_f64(),
                        seconds: start.elapsed().as_secs_f64(),
                        output,
                    });
                    watch(task, Event::Finished(start.elapsed().as_secs_f64()));
                    failed.fetch_or(done.is_err(), Ordering::Relaxed);
                    *slots[task].lock().unwrap_or_else(std::sync::PoisonError::into_inner) = Some(done);
                }
            });
        }
    });
    let wall = began.elapsed().as_secs_f64();
    let mut done = slots.into_iter().map(|s| s.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner));
    let mut results: Vec<(&Paper, Vec<Done>)> = Vec::new();
    for paper in papers {
        let mut finished = Vec::new();
        for _ in &paper.experiments {
            match done.next().flatten() {
                Some(d) => finished.push(d?),
                // not run: a stop, or an error reported by an experiment later in the pages
                None if stop.load(Ordering::Relaxed) => return Err(samplab::Error::Interrupted.into()),
                None => {}
            }
        }
        results.push((paper, finished));
    }
    if stop.load(Ordering::Relaxed) {
        return Err(samplab::Error::Interrupted.into());
    }
    let mut claims = Vec::new();
    samplab::io::write_folder(&options.out, options.replace, |staging| -> Result<(), Error> {
        for sub in ["figures", "tables"] {
            std::fs::create_dir_all(staging.join(sub)).map_err(|e| io_error(staging, e))?;
        }
        claims = html::write_report(staging, &results, options, wall)?;
        Ok(())
    })?;
    Ok(claims)
}

/// Each experiment's seconds ("paper/experiment") in the last run recorded at `scale`
/// (`data/timings.json`, from a report's `timing.json`; the fast run's where the full
/// scale has none recorded), which order the run: an experiment not listed goes last.
///
/// # Panics
/// Never at run time: the file is compiled in, and a test reads it.
pub fn expected_seconds(scale: Scale) -> std::collections::HashMap<String, f64> {
    let all: serde_json::Value =
        serde_json::from_str(include_str!("../data/timings.json")).expect("data/timings.json is JSON");
    let of = |key: &str| -> std::collections::HashMap<String, f64> {
        all[key]["experiments"]
            .as_object()
            .map(|m| m.iter().filter_map(|(k, v)| Some((k.clone(), v.as_f64()?))).collect())
            .unwrap_or_default()
    };
    let mut seconds = of("fast");
    if scale == Scale::Full {
        seconds.extend(of("full"));
    }
    seconds
}
