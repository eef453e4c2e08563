//! `samplab`: generate, measure and plot sampling patterns for Monte Carlo integration.
//!
//! Thin glue over the `samplab` library. Every error is one line on stderr and exit
//! code 2; nothing is written when a command fails.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod bar;
mod discrepancy;
mod generate;
mod integrate;
mod list;
mod plot;
mod render;
mod reproduce;
mod sets;
mod spectrum;

/// Sampling patterns for Monte Carlo integration in rendering.
#[derive(Parser)]
#[command(name = "samplab", version, about, long_about = None, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Memory the command may use (e.g. 8G, 512M), instead of what the system reports
    /// available; larger requests are refused before any work
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size, display_order = 900)]
    max_memory: Option<u64>,
}

fn parse_size(text: &str) -> Result<u64, samplab::Error> {
    samplab::memory::parse_size(text)
}

#[derive(Subcommand)]
enum Command {
    /// Reproduce the four papers' tables and figures in an HTML report (the main job).
    Reproduce(reproduce::Args),
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
    /// Periodogram, expected spectrum and spectrum variance over realizations (Subr & Kautz).
    Spectrum(spectrum::Args),
    /// Render soft shadows with any strategy per pixel, against a reference (EXR/PNG).
    Render(Box<render::Args>),
}

/// The exit code of a bug (a panic): 70, EX_SOFTWARE of sysexits.h.
const BUG: u8 = 70;

fn main() -> ExitCode {
    let cli = Cli::parse();
    bar::install();
    samplab::memory::set_limit(cli.max_memory);
    std::panic::set_hook(Box::new(report_bug));
    // a panic is a bug: one line asking for a report and exit code 70 (the hook printed it)
    std::panic::catch_unwind(|| run(cli)).unwrap_or(ExitCode::from(BUG))
}

/// One line for a panic, asking for a report; the backtrace only with RUST_BACKTRACE set.
fn report_bug(info: &std::panic::PanicHookInfo<'_>) {
    let payload = info.payload();
    let what = payload.downcast_ref::<&str>().copied().or_else(|| payload.downcast_ref::<String>().map(String::as_str));
    let at = info.location().map_or(String::new(), |l| format!(" at {}:{}", l.file(), l.line()));
    eprintln!(
        "samplab: internal error (a bug): {}{at}; please report it with the command that caused it",
        what.unwrap_or("panic").replace('\n', " ")
    );
    let trace = std::backtrace::Backtrace::capture();
    if trace.status() == std::backtrace::BacktraceStatus::Captured {
        eprintln!("{trace}");
    }
}

fn run(cli: Cli) -> ExitCode {
    // a hidden switch for the test that proves the panic path (exit 70, one line)
    if std::env::var_os("SAMPLAB_TEST_PANIC").is_some() {
        panic!("a panic on purpose (SAMPLAB_TEST_PANIC)");
    }
    let result = match cli.command {
        Command::Reproduce(a) => reproduce::run(&a),
        Command::List(a) => list::run(&a),
        Command::Generate(a) => generate::run(&a),
        Command::Plot(a) => plot::run(&a),
        Command::Discrepancy(a) => discrepancy::run(&a),
        Command::Integrate(a) => integrate::run(&a),
        Command::Spectrum(a) => spectrum::run(&a),
        Command::Render(a) => render::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.chain().any(|c| library(c) == Some(&samplab::Error::Interrupted)) => {
            eprintln!("samplab: interrupted: nothing was written");
            ExitCode::from(bar::STOPPED)
        }
        Err(e) => {
            // one line: the chain of causes joined, the library's settings named by their flags
            let msg = e.chain().map(in_flags).collect::<Vec<_>>().join(": ").replace('\n', " ");
            eprintln!("samplab: error: {msg}");
            ExitCode::from(2)
        }
    }
}

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
        _ => cause.to_string(),
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

/// Write `bytes` to `path` atomically, or to stdout when there is no path.
pub(crate) fn emit(path: Option<&std::path::Path>, bytes: &[u8]) -> anyhow::Result<()> {
    use std::io::Write as _;
    match path {
        Some(p) => Ok(samplab::io::write_atomic(p, bytes)?),
        None => {
            let mut out = std::io::stdout().lock();
            match out.write_all(bytes).and_then(|()| out.flush()) {
                // a closed pipe (e.g. `| head`) is not an error of ours
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
                r => Ok(r?),
            }
        }
    }
}
