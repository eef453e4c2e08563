//! `samplab integrate`: bias, variance and convergence of samplers on test integrands.

use std::path::PathBuf;

use anyhow::bail;
use samplab::experiment::{self, Fit, Integrands, Row, Study};
use samplab::integrand::Family;
use samplab::io::Role;
use samplab::{Seed, sampler};
use samplab_report::plot::{self as draw, LineChart, Series};

use crate::bar::Bar;

/// The examples and the integrands (from the integrand registry).
fn after_help() -> String {
    format!(
        "Examples:\n  samplab integrate --sampler random --sampler jitter --integrand quad -n 16,64,256,1024 \\\n      \
         --sets 50 --instances 10\n  samplab integrate --sampler regular --sampler jitter --sampler jitter.uniform \\\n      \
         --integrand box -n 256 --sets 2 --instances 1000 --json\n  samplab integrate --sampler sobol.owen \
         --sampler random \\\n      --integrand 'expr:exp(-x0*x0-x1*x1)' -n 64,256,1024\n\nIntegrands: {} (1D ones take 1D samplers). \
         `samplab list integrands` lists them with their parameters. {}",
        samplab::integrand::INTEGRANDS.names(),
        crate::own::HELP
    )
}

/// Run an integration experiment.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Sampler specs (repeat the flag for several)
    #[arg(long = "sampler", required = true)]
    samplers: Vec<String>,
    /// Integrand family (quad, disk:r=0.25, steps:k=5), expr:FORMULA or image:PATH
    #[arg(long)]
    integrand: String,
    /// The exact integral of an expr: integrand (otherwise computed by cubature to a
    /// relative 1e-9)
    #[arg(long)]
    exact: Option<f64>,
    /// Point counts N, comma-separated
    #[arg(short, long, value_delimiter = ',', required = true)]
    n: Vec<usize>,
    /// Realizations M of the estimator per instance (at least 2)
    #[arg(long, default_value_t = 50)]
    sets: usize,
    /// Instances K of the integrand family (default 10; 1 for your own integrand, which is
    /// one function)
    #[arg(long)]
    instances: Option<usize>,
    /// Seed
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Print JSON ({"rows": [...], "fits": [...]}) instead of a table
    #[arg(long)]
    json: bool,
    /// Write a log-log plot of relative variance against N (.png or .svg)
    #[arg(long)]
    plot: Option<PathBuf>,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    if let Some(p) = &a.plot {
        samplab::io::check_file(p)?;
        let specs: Vec<&str> = a.samplers.iter().map(String::as_str).collect();
        crate::refuse_overlap(&specs, &[Role::File("--plot", p)])?;
    }
    let own = crate::own::parse(&a.integrand, a.exact, true)?;
    let family = match &own {
        Some(_) => None,
        None if a.exact.is_some() => bail!("--exact: a registered family's integral is known; leave --exact out"),
        None => Some(Family::parse(&a.integrand)?),
    };
    let integrands = match (&own, &family) {
        (Some(f), _) => Integrands::Given(f.as_ref(), &a.integrand),
        (None, Some(family)) => Integrands::Family(family),
        (None, None) => unreachable!("one or the other"),
    };
    let samplers = a.samplers.iter().map(|s| sampler::build(s)).collect::<Result<Vec<_>, _>>()?;
    if a.n.contains(&0) {
        bail!("-n: counts must be positive");
    }
    if let Some(p) = &a.plot
        && !matches!(p.extension().and_then(|e| e.to_str()), Some("png" | "svg"))
    {
        bail!("--plot {}: must end in .png or .svg", p.display());
    }
    let instances = a.instances.unwrap_or(if own.is_some() { 1 } else { 10 });
    let study =
        Study { samplers: &samplers, family: integrands, ns: &a.n, sets: a.sets, instances, seed: Seed(a.seed) };
    let bar = Bar::new((samplers.len() * a.n.len() * instances) as u64, "instances");
    let rows = experiment::run(&study, &bar.progress())?;
    drop(bar);
    let fits = experiment::fits(&rows);
    if let Some(path) = &a.plot {
        let chart = loglog_chart(&rows, &fits, &integrands.spec());
        let bytes = if path.extension().is_some_and(|e| e == "svg") {
            draw::svg(&chart, (900, 600))?.into_bytes()
        } else {
            draw::png(&chart, (900, 600))?
        };
        samplab::io::write_atomic(path, &bytes)?;
    }
    let out = if a.json { samplab::experiment::json(&rows) } else { table(&rows, &fits) };
    crate::emit(None, out.as_bytes())
}

fn table(rows: &[Row], fits: &[Fit]) -> String {
    let mut out = format!(
        "# integrand {}\n{:<32} {:>7} {:>13} {:>13} {:>12} {:>12} {:>16}\n",
        rows[0].integrand, "sampler", "N", "rel. mean", "rel. variance", "RMSE", "N^2 MSE", "theory"
    );
    for r in rows {
        let theory = r.theory.as_ref().map_or(String::new(), |t| {
            format!("{} {:.4e}", if t.statistic == "normalized_mse" { "N2MSE" } else { "relvar" }, t.value)
        });
        out += &format!(
            "{:<32} {:>7} {:>13.6} {:>13.4e} {:>12.4e} {:>12.5} {:>16}\n",
            r.sampler, r.n, r.relative_mean, r.relative_variance, r.rmse, r.normalized_mse, theory
        );
    }
    if !fits.is_empty() {
        out += "\n# convergence: relative variance ~ N^exponent (95% interval)\n";
        for f in fits {
            out += &format!("{:<32} {:>8.4} [{:.4}, {:.4}]\n", f.sampler, f.exponent, f.ci.0, f.ci.1);
        }
    }
    out
}

fn loglog_chart(rows: &[Row], fits: &[Fit], integrand: &str) -> LineChart {
    let mut series = Vec::new();
    let mut names: Vec<&str> = rows.iter().map(|r| r.sampler.as_str()).collect();
    names.dedup();
    for name in names {
        let slope =
            fits.iter().find(|f| f.sampler == name).map_or(String::new(), |f| format!(" (slope {:.2})", f.exponent));
        let pts = rows.iter().filter(|r| r.sampler == name).map(|r| (r.n as f64, r.relative_variance)).collect();
        series.push(Series {
            markers: false,
            ..Series { colour_key: Some(name.to_string()), ..Series::line(format!("{name}{slope}"), pts) }
        });
    }
    LineChart {
        title: format!("Relative variance against N — {integrand}"),
        x_label: "N (samples per estimate)".into(),
        y_label: "relative variance".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    }
}
