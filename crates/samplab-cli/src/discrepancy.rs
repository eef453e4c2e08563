//! `samplab discrepancy`: metrics of a point-set file or of fresh realizations of a sampler.

use std::path::PathBuf;

use anyhow::{Context, bail};
use rayon::prelude::*;
use samplab::PointSet;
use samplab::discrepancy::{self, Limits, Metric};

use crate::bar::Bar;

/// The examples and the metrics (from the metric registry).
fn after_help() -> String {
    format!(
        "Examples:\n  samplab discrepancy star l2-star extreme --sampler nrooks -n 16 --sets 100\n  \
         samplab discrepancy star centered points.txt --json\n  \
         samplab discrepancy projected:angle=30,kind=extreme --sampler jitter -n 64\n\n\
         Metrics: {}.\nValues are never squared (scipy returns CD, WD and MD squared). \
         `samplab list metrics` lists every metric with its parameters.",
        discrepancy::METRICS.names()
    )
}

/// Compute discrepancies.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Metrics (see below), then optionally a point-set file
    #[arg(required = true, num_args = 1..)]
    items: Vec<String>,
    #[command(flatten)]
    source: crate::sets::SetSource,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Raise the work limit of the exact algorithms (steps, e.g. 1e12)
    #[arg(long)]
    max_work: Option<f64>,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    // the last item is a file when it is not a metric
    let (metric_items, file) = match a.items.split_last() {
        Some((last, rest)) if Metric::parse(last).is_err() && !a.source.generates() => {
            (rest, Some(PathBuf::from(last)))
        }
        _ => (&a.items[..], None),
    };
    if metric_items.is_empty() {
        bail!("name at least one metric before the file (e.g. star)");
    }
    let metrics: Vec<Metric> = metric_items.iter().map(|m| Metric::parse(m)).collect::<Result<_, _>>()?;
    let limits = Limits::new(a.max_work)?;
    // the sets to make and the metrics' work on them, refused before any is made
    if let Some((n, d, sets)) = a.source.planned(1) {
        let concurrent = sets.saturating_mul(metrics.len()).min(rayon::current_num_threads()) as u128;
        let working = metrics.iter().map(|m| m.memory(n)).max().unwrap_or(0);
        let bytes = (n as u128 * d as u128 * 8).saturating_mul(sets as u128) + working * concurrent;
        samplab::memory::check(|| format!("the metrics of {sets} set(s) of {n} {d}D points"), bytes)?;
    }
    let crate::sets::Loaded { sets, source, .. } = a.source.load(file.as_deref(), 1, &(0.0..=1.0))?;
    let bar = Bar::new((sets.len() * metrics.len()) as u64, "evaluations");
    let progress = bar.progress();
    // values[m][k]: metric m on set k, computed in parallel (the metrics too, so that one's
    // serial parts overlap another's work), deterministic; the first metric's error first
    let values: Vec<anyhow::Result<Vec<f64>>> = metrics
        .par_iter()
        .map(|m| {
            sets.par_iter()
                .enumerate()
                .map(|(k, s)| {
                    progress.check()?;
                    let v =
                        discrepancy::compute(m, s, limits.stopped_by(progress)).with_context(|| format!("set {k}"))?;
                    progress.advance(1)?;
                    Ok(v)
                })
                .collect::<anyhow::Result<Vec<f64>>>()
        })
        .collect();
    let values: Vec<Vec<f64>> = values.into_iter().collect::<anyhow::Result<_>>()?;
    drop(bar);
    let out = if a.json {
        discrepancy::json(&metrics, &values, &sets.iter().map(PointSet::len).collect::<Vec<_>>(), &source)
    } else {
        table(&metrics, &values, &source)
    };
    crate::emit(None, out.as_bytes())
}

/// Mean, standard deviation (n - 1) and maximum.
fn summary(v: &[f64]) -> (f64, f64, f64) {
    let s = samplab::stats::Summary::of(v);
    (s.mean, s.sd, s.max)
}

fn table(metrics: &[Metric], values: &[Vec<f64>], source: &str) -> String {
    let mut out = format!("# {source}\n");
    let names: Vec<String> = metrics
        .iter()
        .map(|m| if m.entry().lower_bound { format!("{} (lower bound)", m.spec()) } else { m.spec() })
        .collect();
    if values[0].len() == 1 {
        for (name, v) in names.iter().zip(values) {
            out += &format!("{name:<28} {:.10}\n", v[0]);
        }
    } else {
        out += &format!("{:<28} {:>14} {:>14} {:>14}\n", "metric", "mean", "sd", "max");
        for (name, v) in names.iter().zip(values) {
            let (mean, sd, max) = summary(v);
            out += &format!("{name:<28} {mean:>14.8} {sd:>14.8} {max:>14.8}\n");
        }
    }
    out
}
