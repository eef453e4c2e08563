//! `samplab`: generate, measure and plot sampling patterns for Monte Carlo integration.
//!
//! Thin glue over the `samplab` library. Every error is one line on stderr and exit
//! code 2; nothing is written when a command fails.

use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::{CommandFactory as _, FromArgMatches as _, Parser, Subcommand};

/// A line on stderr; a stderr that cannot be written (closed, full) is not an error.
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($t)*);
    }};
}
pub(crate) use say;

mod alloc;
mod atlas;
mod bar;
mod conform;
mod cubature;
mod discrepancy;
mod generate;
mod image_metrics;
mod integrate;
mod list;
mod mask;
mod own;
mod pixels;
mod plot;
mod predict;
mod render;
mod reproduce;
mod sets;
mod spectrum;
mod study;
mod tvalues;

#[global_allocator]
static ALLOCATOR: alloc::Checked = alloc::Checked;

/// Sampling patterns for Monte Carlo integration in rendering.
#[derive(Parser)]
#[command(
    name = "samplab",
    version,
    about,
    long_about = None,
    max_term_width = 100,
    after_help = "Exit codes: 0 done; 1 a check of `samplab conform` failed (its lines say which); 2 an error\n(one line on stderr: bad input, a refused output, a failed write, stdout closed); 130 stopped by\nCtrl-C, SIGTERM or SIGHUP (nothing written); 141 stdout closed by its reader (a broken pipe, as\n`| head`: quiet, as a process killed by SIGPIPE); 70 a bug.\n\nEnvironment: SAMPLAB_SIMD=baseline|avx2|avx512 limits the vector instructions the hot loops use\n(every tier makes the same bytes; for testing and timing a narrower path)."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Memory the command may use (e.g. 8G, 8GiB, 512MB), instead of what the system reports
    /// available; larger requests are refused, before any work where they can be foreseen
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size, display_order = 900)]
    max_memory: Option<u64>,
}

fn parse_size(text: &str) -> Result<u64, samplab::Error> {
    samplab::memory::parse_size(text)
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the four papers' tables and figures, the samplers-in-the-renderer page and the
    /// predicted-against-measured page, in an HTML report (the main job).
    Reproduce(reproduce::Args),
    /// Every sampler measured the same way: a page per sampler (points, spectrum, PCF,
    /// discrepancy and integration error against n, speed) and a sortable comparison page.
    Atlas(atlas::Args),
    /// List samplers, warps or file formats, with aliases, parameters and references.
    List(list::Args),
    /// Generate point sets with a sampler (text to stdout by default).
    Generate(generate::Args),
    /// Plot a point-set file as a scatter with 1D marginal histograms (PNG or SVG).
    Plot(plot::Args),
    /// Discrepancies (star, extreme, L2 family, diaphony, projected) and spacing statistics
    /// (min-distance, relative radius, PCF, RDF) and aliasing measures (effective Nyquist
    /// frequency, oscillation) of a file or of a sampler's sets.
    Discrepancy(discrepancy::Args),
    /// Bias, variance and convergence exponents of samplers on the papers' test integrands.
    Integrate(integrate::Args),
    /// An integral to a stated accuracy (abs/rel tolerance), with its error bound.
    Cubature(cubature::Args),
    /// Periodogram, expected spectrum and spectrum variance over realizations (Subr & Kautz).
    Spectrum(spectrum::Args),
    /// Predict samplers' variance on an integrand from their spectra (Pilleboue et al. 2015),
    /// rank them, and measure beside the prediction.
    Predict(predict::Args),
    /// Render soft shadows with any strategy per pixel, against a reference (EXR/PNG).
    Render(Box<render::Args>),
    /// Every value a pixel sampler (ZSobol, padded Sobol', PMJ02, blue-noise dithering,
    /// OpenQMC, ...) gives a film, keyed by pixel, frame, sample and dimension (.npy).
    Pixels(pixels::Args),
    /// How a render's error is spread over the screen: RMSE, blurred RMSE beside white
    /// noise's, low-frequency energy, radial error spectrum, flicker over frames.
    ImageMetrics(image_metrics::Args),
    /// A tileable blue-noise mask by void-and-cluster (Ulichney 1993), 1-4 values per pixel,
    /// as .npy or .png (the masks of the dither and pmj02.bn pixel samplers).
    Mask(mask::Args),
    /// The t of every projection of a sampler's nets at b^1 .. b^m points: a digital net's
    /// from its generating matrices, any other set's counted on its points.
    TValues(tvalues::Args),
    /// Referee your own sampler: samples dumped from your implementation checked against
    /// samplab's entry of that name (bit for bit with its seed; range, uniformity, nets and
    /// distinct pixels without); one line per check, exit 1 when one fails.
    Conform(conform::Args),
    /// A study's chunks as separate jobs (a Slurm array, say): plan it, run each chunk
    /// anywhere into one folder, merge them into the bytes one process makes.
    Study(study::Args),
}

/// The exit code of a bug (a panic): 70, EX_SOFTWARE of sysexits.h.
const BUG: u8 = 70;

/// The exit code of a broken pipe on stdout: 128 + SIGPIPE, what a shell reports for a
/// process killed by it.
const BROKEN_PIPE: u8 = 141;

/// Set when stdout was closed at the start (`>&-`): what is printed there is an error.
static STDOUT_CLOSED: AtomicBool = AtomicBool::new(false);

/// Record whether stdout is closed (`>&-`), before Rust's runtime starts: it then gives a
/// closed standard stream `/dev/null`'s descriptor (so that no file opened later takes its
/// number), after which a closed stdout looks like `> /dev/null`.
#[cfg(target_os = "linux")]
#[used]
#[unsafe(link_section = ".init_array")]
static CHECK_STDOUT: extern "C" fn() = check_stdout;

#[cfg(target_os = "linux")]
extern "C" fn check_stdout() {
    // SAFETY: fcntl on a plain descriptor number reads its flags, nothing else.
    if unsafe { libc::fcntl(1, libc::F_GETFD) } == -1 {
        STDOUT_CLOSED.store(true, Ordering::Relaxed);
    }
}

/// The command line, with every value allowed to start with '-' when it is a number, so
/// that `-n -1` is refused by the value's parser, not taken for a flag.
fn parse() -> Result<Cli, clap::Error> {
    let command = Cli::command().mut_subcommands(|sub| {
        sub.mut_args(|a| if a.get_action().takes_values() { a.allow_negative_numbers(true) } else { a })
    });
    Cli::from_arg_matches(&command.try_get_matches()?)
}

/// Help and version on stdout (exit 0, or 2 when stdout cannot take them); every other
/// parse error as one line on stderr, exit 2 (clap's message without its usage block).
fn refuse(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => match emit(None, e.render().to_string().as_bytes()) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => finish(Err(e)),
        },
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            say!("{}", e.render().to_string().trim_end());
            ExitCode::from(2)
        }
        _ => {
            // clap's first paragraph, its lines joined: the message and, for a missing
            // argument, the arguments it names
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .skip_while(|l| l.trim().is_empty())
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let first = if first.is_empty() { "invalid arguments".to_string() } else { first.join(" ") };
            say!("samplab: error: {}; see --help", first.trim_start_matches("error: "));
            ExitCode::from(2)
        }
    }
}

fn main() -> ExitCode {
    let cli = match parse() {
        Ok(cli) => cli,
        Err(e) => return refuse(&e),
    };
    bar::install();
    samplab::memory::set_limit(cli.max_memory);
    alloc::set_limit(cli.max_memory);
    std::panic::set_hook(Box::new(report_bug));
    // the command runs on a thread of rayon's pool, so that each parallel call in it starts
    // on that thread's own queue instead of being handed from the main thread to the pool
    // and back (a sleep and a wake-up per call: `generate elimination -n 100000` on two
    // threads made 1525 context switches run from the main thread, 337 run in the pool);
    // its threads get the main thread's stack size, as the command's recursion did
    let _ = rayon::ThreadPoolBuilder::new().stack_size(STACK).build_global();
    // a panic is a bug: one line asking for a report and exit code 70 (the hook printed it)
    std::panic::catch_unwind(|| rayon::scope(|_| run(cli))).unwrap_or(ExitCode::from(BUG))
}

/// The stack of each of rayon's threads: the main thread's on Linux (8 MiB; rayon's own
/// default is 2 MiB).
const STACK: usize = 8 << 20;

/// One line for a panic, asking for a report; the backtrace only with RUST_BACKTRACE set.
fn report_bug(info: &std::panic::PanicHookInfo<'_>) {
    let payload = info.payload();
    let what = payload.downcast_ref::<&str>().copied().or_else(|| payload.downcast_ref::<String>().map(String::as_str));
    let at = info.location().map_or(String::new(), |l| format!(" at {}:{}", l.file(), l.line()));
    say!(
        "samplab: internal error (a bug): {}{at}; please report it with the command that caused it",
        what.unwrap_or("panic").replace('\n', " ")
    );
    let trace = std::backtrace::Backtrace::capture();
    if trace.status() == std::backtrace::BacktraceStatus::Captured {
        say!("{trace}");
    }
}

fn run(cli: Cli) -> ExitCode {
    // a hidden switch for the test that proves the panic path (exit 70, one line)
    if std::env::var_os("SAMPLAB_TEST_PANIC").is_some() {
        panic!("a panic on purpose (SAMPLAB_TEST_PANIC)");
    }
    // an instruction-set limit the library would ignore is refused here, before any work
    if let Err(e) = samplab::simd::Tier::from_environment() {
        return finish(Err(e.into()));
    }
    finish(match cli.command {
        Command::Reproduce(a) => reproduce::run(&a),
        Command::Atlas(a) => atlas::run(&a),
        Command::List(a) => list::run(&a),
        Command::Generate(a) => generate::run(&a),
        Command::Plot(a) => plot::run(&a),
        Command::Discrepancy(a) => discrepancy::run(&a),
        Command::Integrate(a) => integrate::run(&a),
        Command::Cubature(a) => cubature::run(&a),
        Command::Spectrum(a) => spectrum::run(&a),
        Command::Predict(a) => predict::run(&a),
        Command::Render(a) => render::run(&a),
        Command::Pixels(a) => pixels::run(&a),
        Command::ImageMetrics(a) => image_metrics::run(&a),
        Command::Mask(a) => mask::run(&a),
        Command::TValues(a) => tvalues::run(&a),
        Command::Conform(a) => conform::run(&a),
        Command::Study(a) => study::run(&a),
    })
}

/// The exit code of a command's result, with its one line on stderr.
fn finish(result: anyhow::Result<()>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.chain().any(|c| library(c) == Some(&samplab::Error::Interrupted)) => {
            say!("samplab: interrupted: nothing was written");
            ExitCode::from(bar::STOPPED)
        }
        Err(e) if e.chain().any(|c| c.is::<BrokenPipe>()) => ExitCode::from(BROKEN_PIPE),
        // the lines said which check failed
        Err(e) if e.chain().any(|c| c.is::<conform::Failed>()) => ExitCode::from(1),
        Err(e) => {
            // one line: the chain of causes joined, the library's settings named by their flags
            let msg = e.chain().map(in_flags).collect::<Vec<_>>().join(": ").replace('\n', " ");
            say!("samplab: error: {msg}");
            ExitCode::from(2)
        }
    }
}

/// Stdout's reader went away (a broken pipe): a quiet exit, [`BROKEN_PIPE`].
#[derive(Debug)]
struct BrokenPipe;

impl std::fmt::Display for BrokenPipe {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("standard output: broken pipe")
    }
}

impl std::error::Error for BrokenPipe {}

/// One cause of an error, with the library's names for settings replaced by the flags that
/// set them (`sets` is `--sets`, a work limit is raised by `--max-work`).
fn in_flags(cause: &(dyn std::error::Error + 'static)) -> String {
    match library(cause) {
        Some(samplab::Error::Setting { name, value, reason }) => {
            let flag = if name.len() == 1 { format!("-{name}") } else { format!("--{}", name.replace('_', "-")) };
            format!("{flag} {value}: {reason}")
        }
        Some(e @ samplab::Error::WorkLimit { .. }) => format!("{e}; raise it with --max-work"),
        Some(e @ samplab::Error::Memory { .. }) => format!("{e}; set another limit with --max-memory"),
        Some(samplab::Error::InSet { set, error }) => format!("set {set}: {}", in_flags(&**error)),
        Some(samplab::Error::ForeignEntry { folder, entry }) => {
            format!(
                "{folder}: holds '{entry}', which samplab did not write; name a new folder, or pass --force to replace it"
            )
        }
        _ => match cause.downcast_ref::<samplab_render::Error>() {
            Some(e @ samplab_render::Error::PathOutsideScene { .. }) => {
                format!("{e}; allow it with --allow-paths-outside-scene")
            }
            _ => cause.to_string(),
        },
    }
}

/// The library error a cause is, directly or wrapped by the renderer or the report.
fn library<'e>(cause: &'e (dyn std::error::Error + 'static)) -> Option<&'e samplab::Error> {
    cause.downcast_ref::<samplab::Error>().or_else(|| match cause.downcast_ref::<samplab_render::Error>() {
        Some(samplab_render::Error::Samplab(e)) => Some(e),
        _ => match cause.downcast_ref::<samplab_report::Error>() {
            Some(samplab_report::Error::Samplab(e)) => Some(e),
            _ => None,
        },
    })
}

/// [`samplab::io::refuse_overlap`] over a command's `roles` (its outputs and the files it
/// reads) and the files its sampler specs `specs` read (`net:matrices=`, `file:path=`;
/// [`samplab::sampler::inputs`]). A spec that does not resolve adds no file: building it
/// says why.
pub(crate) fn refuse_overlap(specs: &[&str], roles: &[samplab::io::Role<'_>]) -> anyhow::Result<()> {
    use samplab::io::Role;
    let files: Vec<std::path::PathBuf> =
        specs.iter().flat_map(|s| samplab::sampler::inputs(s).unwrap_or_default()).collect();
    let all: Vec<Role<'_>> =
        files.iter().map(|f| Role::Input("the sampler's file", f)).chain(roles.iter().copied()).collect();
    Ok(samplab::io::refuse_overlap(&all)?)
}

/// Write `bytes` to `path` atomically, or to stdout when there is no path: a stdout that
/// is closed or cannot take them (a full disk) is an error, a broken pipe a quiet exit.
pub(crate) fn emit(path: Option<&std::path::Path>, bytes: &[u8]) -> anyhow::Result<()> {
    use std::io::Write as _;
    match path {
        Some(p) => Ok(samplab::io::write_atomic(p, bytes)?),
        None if STDOUT_CLOSED.load(Ordering::Relaxed) => {
            anyhow::bail!("standard output is closed; nothing was written (use -o FILE, or redirect it)")
        }
        None => {
            let mut out = std::io::stdout().lock();
            match out.write_all(bytes).and_then(|()| out.flush()) {
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Err(BrokenPipe.into()),
                Err(e) => anyhow::bail!("standard output: {e}"),
                Ok(()) => Ok(()),
            }
        }
    }
}
