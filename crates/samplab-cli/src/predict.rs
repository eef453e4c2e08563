//! `samplab predict`: the variance of samplers on an integrand, predicted from their spectra
//! before it is measured (`samplab::predict`).

use samplab::integrand::{Family, Grid};
use samplab::predict::{Cache, Outcome, Study};
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
         Examples:\n  samplab predict --integrand disk:r=0.3,cx=0.45,cy=0.5 --sampler random --sampler jitter \\\n      \
         --sampler sobol.owen -n 64,256,1024,4096 --measure\n  samplab predict --integrand cosine:u=3,v=5 --all -n 64,256 \
         --json\n  samplab predict --integrand quad --integrand disk --integrand halfplane --all -n 64,256\n\n\
         The radial column is the same sum with the sampler's spectrum averaged over rings of \
         equal |k| (the form for isotropic samplers). The exponent table fits P(k) ~ c (|k| / \
         sqrt n)^beta over |k| / sqrt n <= 0.25 and gives the variance exponents it implies: \
         -1 - beta/2 on a band-limited integrand (best), -1 - min(beta, 1)/2 on one with a jump \
         along a smooth curve (worst).\n\nIntegrands: {}.",
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
    /// Integrand, e.g. disk:r=0.25, quad, cosine:u=3,v=5 (instance 0 of the family for the
    /// seed); repeat the flag for several (the sampler spectra are shared)
    #[arg(long = "integrand", required_unless_present = "images")]
    integrands: Vec<String>,
    /// An image file (PNG, JPEG, EXR, ...) as an integrand: its luminance on the unit
    /// square, box lookups, first row at y = 0; repeat the flag for several
    #[arg(long = "image")]
    images: Vec<std::path::PathBuf>,
    /// Point counts n, comma-separated
    #[arg(short, long, value_delimiter = ',', default_values_t = [16, 64, 256, 1024])]
    n: Vec<usize>,
    /// Frequencies per axis of the spectra (even, 4 to 4096)
    #[arg(long, default_value_t = 128)]
    res: usize,
    /// Realizations of each measured sampler spectrum (at least 8)
    #[arg(long, default_value_t = 16)]
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
    /// Measure every sampler spectrum again instead of reading those kept from earlier runs
    /// (kept in $SAMPLAB_CACHE, else $XDG_CACHE_HOME/samplab, else ~/.cache/samplab)
    #[arg(long)]
    no_cache: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let mut integrands: Vec<(Box<dyn samplab::integrand::Integrand>, String)> = Vec::new();
    for spec in &a.integrands {
        let family = Family::parse(spec)?;
        integrands.push((family.instance(Seed(a.seed), 0)?, family.spec()));
    }
    for path in &a.images {
        integrands.push((Box::new(image_integrand(path)?), format!("image {}", path.display())));
    }
    let dims = integrands[0].0.dims();
    let samplers = if a.all {
        samplab::predict::every_sampler(dims)
    } else {
        a.samplers.iter().map(|s| sampler::build(s)).collect::<Result<Vec<_>, _>>()?
    };
    let borrowed: Vec<(&dyn samplab::integrand::Integrand, String)> =
        integrands.iter().map(|(f, spec)| (f.as_ref(), spec.clone())).collect();
    let cache = if a.no_cache { None } else { Cache::user() };
    let study = Study {
        samplers: &samplers,
        integrands: &borrowed,
        ns: &a.n,
        res: a.res,
        sets: a.sets,
        measure: a.measure.map(|m| (m, a.shift)),
        seed: Seed(a.seed),
        cache: cache.as_ref(),
    };
    let bar = Bar::new(study.units(), "realizations");
    let outcome = study.run(&bar.progress())?;
    drop(bar);
    let out = if a.json { format!("{}\n", serde_json::to_string_pretty(&outcome)?) } else { table(&outcome, a.res) };
    crate::emit(None, out.as_bytes())
}

fn table(o: &Outcome, res: usize) -> String {
    let mut out = String::new();
    for f in &o.integrands {
        out += &format!(
            "# integrand {} (spectrum: {}, estimated error {:.1e}; Var(f) = {:.4e}); window {res} frequencies per axis\n\
             {:<36} {:>7} {:>12} {:>9} {:>12} {:>12} {:>9} {:>7}  spectrum\n",
            f.spec,
            f.spectrum,
            f.error,
            f.variance,
            "sampler",
            "n",
            "predicted",
            "+- SE",
            "radial",
            "measured",
            "+- SE",
            "ratio"
        );
        for r in o.rows.iter().filter(|r| r.integrand == f.spec) {
            let (measured, se, ratio) = r.measured.map_or((String::new(), String::new(), String::new()), |m| {
                (
                    format!("{:.4e}", m.variance),
                    format!("{:.1e}", m.se),
                    format!("{:.3}", r.predicted.variance / m.variance),
                )
            });
            out += &format!(
                "{:<36} {:>7} {:>12.4e} {:>9.1e} {:>12.4e} {:>12} {:>9} {:>7}  {}\n",
                r.sampler,
                r.n,
                r.predicted.variance,
                r.predicted.se,
                r.radial.variance,
                measured,
                se,
                ratio,
                r.spectrum
            );
        }
        if let Some(n) = o.rows.iter().map(|r| r.n).max() {
            out += &format!(
                "\n# ranking on {} by predicted variance at n = {n}; exponents: slope of log variance against log n\n\
                 {:>4} {:<36} {:>12} {:>10} {:>10}\n",
                f.spec, "rank", "sampler", "variance", "predicted", "measured"
            );
            for r in o.ranking.iter().filter(|r| r.integrand == f.spec) {
                out += &format!(
                    "{:>4} {:<36} {:>12.4e} {:>10} {:>10}\n",
                    r.rank,
                    r.sampler,
                    r.variance,
                    fixed(r.predicted_exponent),
                    fixed(r.measured_exponent)
                );
            }
        }
        out += "\n";
    }
    out += &format!(
        "# small-frequency exponents: P(k) ~ c (|k| / sqrt n)^beta for |k| / sqrt n <= {}, and the variance exponents it implies\n\
         {:<36} {:>8} {:>10} {:>7} {:>10} {:>10}\n",
        samplab::predict::SMALL_FREQUENCY_REACH,
        "sampler",
        "beta",
        "c",
        "rings",
        "best",
        "worst"
    );
    for r in &o.rates {
        out += &match r.small_frequency {
            Some(s) => format!(
                "{:<36} {:>8} {:>10} {:>7} {:>10} {:>10.3}\n",
                r.sampler,
                s.exponent.map_or("zero".into(), |b| format!("{b:.3}")),
                s.constant.map_or("-".into(), |c| format!("{c:.3e}")),
                s.points,
                s.best.map_or("-inf".into(), |b| format!("{b:.3}")),
                s.worst
            ),
            None => format!("{:<36} {:>8}\n", r.sampler, "-"),
        };
    }
    for (name, why) in &o.skipped {
        out += &format!("# skipped {name}: {why}\n");
    }
    out
}

/// An exponent with three decimals, or nothing.
fn fixed(e: Option<f64>) -> String {
    e.map_or(String::new(), |e| format!("{e:.3}"))
}

/// An image file as an integrand: the luminance (Rec. 709) of its linear values, an EXR's as
/// stored and an 8- or 16-bit image's decoded from sRGB, the first row at y = 0.
fn image_integrand(path: &std::path::Path) -> anyhow::Result<Grid> {
    let is_exr = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let (width, height, luminance) = if is_exr {
        let image = samplab_render::Image::read_exr(path)?;
        (image.width, image.height, image.luminance())
    } else {
        let (width, height, encoded) = samplab_render::image::read_png(path)?;
        let linear = |c: f32| samplab_render::image::srgb_to_linear(f64::from(c));
        let values = encoded
            .chunks_exact(3)
            .map(|p| 0.2126 * linear(p[0]) + 0.7152 * linear(p[1]) + 0.0722 * linear(p[2]))
            .collect();
        (width, height, values)
    };
    Grid::new(width, height, luminance).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}
