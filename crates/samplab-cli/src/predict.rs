//! `samplab predict`: the variance of samplers on an integrand, predicted from their spectra
//! before it is measured (`samplab::predict`).

use samplab::integrand::Family;
use samplab::predict::{Outcome, Study};
use samplab::{Seed, sampler};

use crate::bar::Bar;

fn after_help() -> String {
    format!(
        "The prediction is the variance of the estimator over a random toroidal shift of each set \
         (Pilleboue et al. 2015): sum over frequencies k != 0 of |F(k)|^2 P(k) / n, F the \
         integrand's Fourier coefficients (closed form where known, else an FFT of sampled \
         values), P the sampler's periodogram per point (closed form for random and jitter, \
         else measured over --sets realizations). Exact for shifted sets when the window of \
         --res frequencies per axis holds every frequency where P differs from 1; an \
         approximation otherwise, and for sets used unshifted.\n\n\
         Examples:\n  samplab predict --integrand disk:r=0.3,cx=0.45,cy=0.5 --sampler random --sampler jitter \
         --sampler sobol.owen -n 64,256,1024,4096 --measure\n  samplab predict --integrand cosine:u=3,v=5 --all -n 64,256 \
         --json\n\nIntegrands: {}.",
        samplab::integrand::INTEGRANDS.names()
    )
}

/// Predict the variance of samplers on an integrand from spectra, and rank them.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Sampler specs (repeat the flag for several)
    #[arg(long = "sampler", required_unless_present = "all")]
    samplers: Vec<String>,
    /// Every registered sampler that makes 2D sets (1D ones for a 1D integrand)
    #[arg(long, conflicts_with = "samplers")]
    all: bool,
    /// Integrand, e.g. disk:r=0.25, quad, cosine:u=3,v=5 (instance 0 of the family for the seed)
    #[arg(long)]
    integrand: String,
    /// Point counts n, comma-separated
    #[arg(short, long, value_delimiter = ',', default_values_t = [16, 64, 256, 1024])]
    n: Vec<usize>,
    /// Frequencies per axis of the spectra (even, 4 to 4096)
    #[arg(long, default_value_t = 128)]
    res: usize,
    /// Realizations of each measured sampler spectrum (at least 8)
    #[arg(long, default_value_t = 32)]
    sets: usize,
    /// Also measure the mean squared error, over this many realizations
    #[arg(long, num_args = 0..=1, default_missing_value = "1000")]
    measure: Option<usize>,
    /// Shift each measured realization by a uniform toroidal shift (where the prediction is exact)
    #[arg(long, requires = "measure")]
    shift: bool,
    /// Seed
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let family = Family::parse(&a.integrand)?;
    let f = family.instance(Seed(a.seed), 0)?;
    let samplers = if a.all {
        samplab::predict::every_sampler(f.dims())
    } else {
        a.samplers.iter().map(|s| sampler::build(s)).collect::<Result<Vec<_>, _>>()?
    };
    let study = Study {
        samplers: &samplers,
        integrand: (f.as_ref(), family.spec()),
        ns: &a.n,
        res: a.res,
        sets: a.sets,
        measure: a.measure.map(|m| (m, a.shift)),
        seed: Seed(a.seed),
    };
    let bar = Bar::new(study.units(), "realizations");
    let outcome = study.run(&bar.progress())?;
    drop(bar);
    let out = if a.json { format!("{}\n", serde_json::to_string_pretty(&outcome)?) } else { table(&outcome, a.res) };
    crate::emit(None, out.as_bytes())
}

fn table(o: &Outcome, res: usize) -> String {
    let mut out = format!(
        "# integrand {} (spectrum: {}, estimated error {:.1e}); window {res} frequencies per axis\n\
         {:<36} {:>7} {:>12} {:>9} {:>12} {:>9} {:>7}  spectrum\n",
        o.integrand,
        o.integrand_spectrum,
        o.integrand_error,
        "sampler",
        "n",
        "predicted",
        "+- SE",
        "measured",
        "+- SE",
        "ratio"
    );
    for r in &o.rows {
        let (measured, se, ratio) = r.measured.map_or((String::new(), String::new(), String::new()), |m| {
            (
                format!("{:.4e}", m.variance),
                format!("{:.1e}", m.se),
                format!("{:.3}", r.predicted.variance / m.variance),
            )
        });
        out += &format!(
            "{:<36} {:>7} {:>12.4e} {:>9.1e} {:>12} {:>9} {:>7}  {}\n",
            r.sampler, r.n, r.predicted.variance, r.predicted.se, measured, se, ratio, r.spectrum
        );
    }
    if let Some(n) = o.rows.iter().map(|r| r.n).max() {
        out += &format!(
            "\n# ranking by predicted variance at n = {n}; exponents: slope of log variance against log n\n\
             {:>4} {:<36} {:>12} {:>10} {:>10}\n",
            "rank", "sampler", "variance", "predicted", "measured"
        );
        let slope = |e: Option<f64>| e.map_or(String::new(), |e| format!("{e:.3}"));
        for r in &o.ranking {
            out += &format!(
                "{:>4} {:<36} {:>12.4e} {:>10} {:>10}\n",
                r.rank,
                r.sampler,
                r.variance,
                slope(r.predicted_exponent),
                slope(r.measured_exponent)
            );
        }
    }
    for (name, why) in &o.skipped {
        out += &format!("# skipped {name}: {why}\n");
    }
    out
}
