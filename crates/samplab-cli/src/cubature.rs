//! `samplab cubature`: an integral to a stated accuracy, the points doubled until the
//! bound meets the tolerance.

use samplab::Seed;
use samplab::cubature::{Settings, cubature};
use samplab::integrand::Family;

use crate::bar::Bar;

/// The examples.
const AFTER_HELP: &str = "Examples:\n  samplab cubature --integrand keister:d=8 --abs-tol 1e-3\n  samplab cubature \
     --integrand genz.oscillatory:d=5 --rel-tol 1e-4 --sampler halton.owen --json\n\nThe bound is probabilistic: \
     Student's t interval at --level over --replications randomizations of a randomized sampler. Integrands: `samplab \
     list integrands` (d-dimensional ones take the parameter d).";

/// Integrate to a tolerance.
#[derive(clap::Args)]
#[command(after_help = AFTER_HELP)]
pub struct Args {
    /// Integrand family, e.g. keister:d=8, genz.gaussian:d=4
    #[arg(long)]
    integrand: String,
    /// Which instance of a random family (its coefficients drawn from the seed)
    #[arg(long, default_value_t = 0)]
    instance: u64,
    /// Stop once the bound is at most max(abs-tol, rel-tol |estimate|)
    #[arg(long, default_value_t = Settings::default().abs_tol)]
    abs_tol: f64,
    /// See --abs-tol
    #[arg(long, default_value_t = 0.0)]
    rel_tol: f64,
    /// A randomized sampler
    #[arg(long, default_value_t = Settings::default().sampler)]
    sampler: String,
    /// Confidence level of the bound, in (0, 1)
    #[arg(long, default_value_t = Settings::default().level)]
    level: f64,
    /// Independent randomizations (at least 2)
    #[arg(long, default_value_t = Settings::default().replications)]
    replications: usize,
    /// Points per randomization at the start (doubled at each step)
    #[arg(long, default_value_t = Settings::default().min_n)]
    min_n: usize,
    /// The most points per randomization
    #[arg(long, default_value_t = Settings::default().max_n)]
    max_n: usize,
    /// Seed
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Print JSON instead of text
    #[arg(long)]
    json: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let family = Family::parse(&a.integrand)?;
    let f = family.instance(Seed(a.seed), a.instance)?;
    let settings = Settings {
        sampler: a.sampler.clone(),
        abs_tol: a.abs_tol,
        rel_tol: a.rel_tol,
        level: a.level,
        replications: a.replications,
        min_n: a.min_n,
        max_n: a.max_n,
        seed: Seed(a.seed),
    };
    // at most one step per doubling from min_n to max_n, each a randomization at a time
    let steps = (a.max_n.max(1) / a.min_n.max(1)).max(1).ilog2() as u64 + 1;
    let bar = Bar::new(steps * a.replications as u64, "randomizations");
    let c = cubature(f.as_ref(), &settings, &bar.progress())?;
    drop(bar);
    let exact = f.exact();
    if a.json {
        println!("{}", serde_json::to_string_pretty(&c.to_json(&family.spec(), Some(exact)))?);
    } else {
        println!("estimate     {:.12e}", c.estimate);
        println!("bound        {:.3e} ({})", c.bound, c.kind);
        println!("exact        {exact:.12e} (error {:.3e})", (c.estimate - exact).abs());
        println!("points       {} per randomization, {} evaluations, {:.3} s", c.n, c.evaluations, c.seconds);
    }
    if !c.converged {
        eprintln!(
            "samplab: warning: the bound {:.3e} is above the tolerance at --max-n {}: raise --max-n or the tolerance",
            c.bound, a.max_n
        );
    }
    Ok(())
}
