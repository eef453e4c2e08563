//! `samplab cubature`: an integral to a stated accuracy, the points doubled until the
//! bound meets the tolerance.

use samplab::Seed;
use samplab::cubature::{Rule, Settings, cubature};
use samplab::integrand::{Family, Integrand};

use crate::bar::Bar;

/// The examples and the rules.
fn after_help() -> String {
    format!(
        "Examples:\n  samplab cubature --integrand keister:d=8 --abs-tol 1e-3\n  samplab cubature --integrand \
         keister:d=8 --abs-tol 1e-3 --rule net\n  samplab cubature --integrand 'expr:exp(-x0*x0-x1*x1)' --abs-tol 1e-6\n  \
         samplab cubature --integrand genz.oscillatory:d=5 --rel-tol 1e-4 --sampler halton.owen --json\n\nRules: \
         replicated (default; probabilistic: Student's t interval at --level over --replications randomizations of a \
         randomized sampler, sobol.owen unless --sampler), net (guaranteed for integrands whose Walsh coefficients \
         decay as Hickernell & Jimenez Rugama 2016's cone asks, on net.lms), lattice (the same with Fourier \
         coefficients of a shifted lattice sequence and the baker's transform, Jimenez Rugama & Hickernell 2016). \
         Outside the cone (a spike the first points miss) a guaranteed bound is wrong.\n\nIntegrands: `samplab \
         list integrands` (d-dimensional ones take the parameter d). {}",
        crate::own::HELP
    )
}

/// Integrate to a tolerance.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Integrand: a family (keister:d=8, genz.gaussian:d=4), expr:FORMULA or image:PATH
    #[arg(long)]
    integrand: String,
    /// The exact integral of an expr: integrand, when known (printed beside the error)
    #[arg(long)]
    exact: Option<f64>,
    /// The bound: replicated, net or lattice
    #[arg(long, default_value = "replicated")]
    rule: String,
    /// Which instance of a random family (its coefficients drawn from the seed)
    #[arg(long, default_value_t = 0)]
    instance: u64,
    /// Stop once the bound is at most max(abs-tol, rel-tol |estimate|)
    #[arg(long, default_value_t = Settings::default().abs_tol)]
    abs_tol: f64,
    /// See --abs-tol
    #[arg(long, default_value_t = 0.0)]
    rel_tol: f64,
    /// The sampler (default: the rule's: sobol.owen, net.lms, lattice.shift)
    #[arg(long)]
    sampler: Option<String>,
    /// Confidence level of the bound, in (0, 1)
    #[arg(long, default_value_t = Settings::default().level)]
    level: f64,
    /// Independent randomizations (at least 2; the replicated rule)
    #[arg(long, default_value_t = Settings::default().replications)]
    replications: usize,
    /// Points per randomization at the start, doubled at each step (default: 256, or 1024
    /// for the guaranteed rules)
    #[arg(long)]
    min_n: Option<usize>,
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
    let (f, name): (Box<dyn Integrand>, String) = match crate::own::parse(&a.integrand, a.exact, false)? {
        Some(f) => (f, a.integrand.clone()),
        None => {
            if a.exact.is_some() {
                anyhow::bail!("--exact: a registered family's integral is known; leave --exact out");
            }
            let family = Family::parse(&a.integrand)?;
            (family.instance(Seed(a.seed), a.instance)?, family.spec())
        }
    };
    let rule = Rule::parse(&a.rule)?;
    let settings = Settings {
        rule,
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
    let steps = (a.max_n.max(1) / settings.min_n().max(1)).max(1).ilog2() as u64 + 1;
    let per_step = if rule == Rule::Replicated { a.replications as u64 } else { 1 };
    let bar = Bar::new(steps * per_step, "steps");
    let c = cubature(f.as_ref(), &settings, &bar.progress())?;
    drop(bar);
    let exact = Some(f.exact()).filter(|e| e.is_finite());
    if a.json {
        println!("{}", serde_json::to_string_pretty(&c.to_json(&name, exact))?);
    } else {
        println!("estimate     {:.12e}", c.estimate);
        println!("bound        {:.3e} ({})", c.bound, c.kind);
        if let Some(exact) = exact {
            println!("exact        {exact:.12e} (error {:.3e})", (c.estimate - exact).abs());
        }
        println!("points       {} (per randomization), {} evaluations, {:.3} s", c.n, c.evaluations, c.seconds);
    }
    if !c.converged {
        eprintln!(
            "samplab: warning: the bound {:.3e} is above the tolerance at --max-n {}: raise --max-n or the tolerance",
            c.bound, a.max_n
        );
    }
    Ok(())
}
