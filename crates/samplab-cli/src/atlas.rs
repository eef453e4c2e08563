//! `samplab atlas`: every sampler measured the same way, one page each and one comparison
//! page.

use std::path::PathBuf;
use std::time::Instant;

use samplab::Seed;
use samplab_report::{Scale, atlas};

/// Build the atlas.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  samplab atlas --out atlas\n  samplab atlas --only sobol.owen,jitter,poisson --out some\n  samplab atlas --report report --out atlas    # list the experiments that use each sampler\n\nWrites DIR/index.html (one sortable table of every sampler on the same measures, and small\nmultiples of their points and spectra), DIR/samplers/NAME.html and NAME.json per registry\nentry, figures as PNG, and DIR/speed.json. Every byte but the speed (--speed) is the same\nfor the same seed on any thread count. The folder appears only when complete."
)]
pub struct Args {
    /// More sets and instances, finer spectra (slower) instead of the fast default
    #[arg(long, conflicts_with = "smoke")]
    full: bool,
    /// The least that draws every page, to check the pages, links and figures (seconds a
    /// sampler: counts up to 1024, two sets, a coarse spectrum); not for reading the numbers
    #[arg(long)]
    smoke: bool,
    /// Only these samplers (comma-separated names or aliases)
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Seed of the whole atlas (each sampler's is derived from it and its name)
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Measure each sampler's generation speed now (up to 2^20 points) instead of showing
    /// the recorded figures; the speeds then differ from run to run
    #[arg(long)]
    speed: bool,
    /// A reproduction report (from `samplab reproduce`) whose experiments are searched for
    /// each sampler
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Output folder (replaced when complete; an existing folder only if samplab made it)
    #[arg(long, default_value = "atlas")]
    out: PathBuf,
    /// Replace the output folder even when it holds files samplab did not write
    #[arg(long)]
    force: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let options = atlas::Options {
        run: samplab_report::Options {
            scale: if a.full { Scale::Full } else { Scale::Fast },
            seed: Seed(a.seed),
            out: a.out.clone(),
            replace: if a.force { samplab::io::Replace::Force } else { samplab::io::Replace::IfOurs },
        },
        only: a.only.clone(),
        measure_speed: a.speed,
        report: a.report.clone(),
        smoke: a.smoke,
    };
    let start = Instant::now();
    let len = if a.only.is_empty() { samplab::sampler::SAMPLERS.iter().count() } else { a.only.len() };
    let bar = crate::bar::Bar::new(len as u64, "samplers");
    let pages = atlas::build(&options, &crate::bar::STOP, &bar.progress())?;
    drop(bar);
    crate::say!(
        "atlas of {pages} samplers in {:.1} s: {}",
        start.elapsed().as_secs_f64(),
        a.out.join("index.html").display()
    );
    Ok(())
}
