//! `samplab reproduce`: run the papers' experiments and write the HTML report.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::bail;
use samplab::Seed;
use samplab_report::{Options, Scale, paper};

/// Reproduce the papers' tables and figures.
#[derive(clap::Args)]
#[command(
    after_help = "Writes DIR/index.html (a summary linking one page per paper), figures as PNG and SVG,\ntables as CSV and JSON, and DIR/claims.json. The report appears only when complete."
)]
pub struct Args {
    /// Run at the papers' own scales (slower) instead of the fast default
    #[arg(long)]
    full: bool,
    /// Only these pages (comma-separated keys: shirley1991, subr2013, sbert2006, ramamoorthi2012,
    /// renderer, prediction)
    #[arg(long, value_delimiter = ',')]
    only: Vec<String>,
    /// Seed of the whole run
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Output folder (replaced when the run completes; an existing folder only if samplab
    /// made it)
    #[arg(long, default_value = "report")]
    out: PathBuf,
    /// Replace the output folder even when it holds files samplab did not write
    #[arg(long)]
    force: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let all = paper::all();
    for key in &a.only {
        if !all.iter().any(|p| p.key == key) {
            bail!("--only: unknown paper '{key}' (papers: {})", paper::keys().join(", "));
        }
    }
    let chosen: Vec<_> = all.iter().filter(|p| a.only.is_empty() || a.only.iter().any(|k| k == p.key)).collect();
    let options = Options {
        scale: if a.full { Scale::Full } else { Scale::Fast },
        seed: Seed(a.seed),
        out: a.out.clone(),
        replace: if a.force { samplab::io::Replace::Force } else { samplab::io::Replace::IfOurs },
    };
    let start = Instant::now();
    let bars = crate::bar::Experiments::new();
    let claims = samplab_report::reproduce(&chosen, &options, &crate::bar::STOP, &|task, e| bars.show(task, e))?;
    let [reproduced, checked, failed, contradicted, undecided] = samplab_report::tally(claims.iter().map(|(_, c)| c));
    let explained =
        claims.iter().filter(|(_, c)| c.verdict_name() == "not reproduced" && c.explanation.is_some()).count();
    crate::say!(
        "{} claims: {reproduced} reproduced, {checked} checked (derived), {failed} not reproduced ({explained} of them explained), {contradicted} contradicted (derived), {undecided} undecided; {:.1} s. Report: {}",
        claims.len(),
        start.elapsed().as_secs_f64(),
        a.out.join("index.html").display()
    );
    Ok(())
}
