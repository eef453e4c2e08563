//! `samplab t-values`: the t of every projection of a sampler's nets, count by count.

use samplab::Seed;
use samplab::discrepancy::Limits;
use samplab::discrepancy::tvalue::{ProjectionTable, projection_table};

use crate::bar::Bar;

/// The t of each projection of a sampler's nets.
#[derive(clap::Args)]
#[command(after_help = "A digital net's t (net, faure, niederreiter, sz, cascaded, xi, and \
                  their .xor, .lms and .owen) comes from its generating matrices, by ranks over GF(b) \
                  (Niederreiter 1992, theorem 4.28): the t of its points under every such scramble. Any \
                  other sampler's is counted on the points of one set (--seed), interval by interval, in \
                  --base. t = 0 is the best a projection can do.\n\nExamples:\n  \
                  samplab t-values net -d 8 --m 16 --projection consecutive\n  \
                  samplab t-values cascaded -d 6 --m 12 --projection pairs --json\n  \
                  samplab t-values pmj02 --m 10 --projection all")]
pub struct Args {
    /// Sampler spec, e.g. sobol, net:directions=FILE, cascaded.owen, pmj02
    spec: String,
    /// Dimensions
    #[arg(short, long, default_value_t = 2)]
    dims: usize,
    /// The largest m: the nets of b^1 .. b^m points
    #[arg(long, default_value_t = 12)]
    m: usize,
    /// Projections: all (the whole set), pairs (every 2D projection), consecutive (the pairs
    /// (j, j + 1)) or quadruples (j .. j + 3)
    #[arg(long, default_value = "consecutive")]
    projection: String,
    /// The base of a sampler without generating matrices (a digital net's is its own)
    #[arg(long)]
    base: Option<u32>,
    /// Seed of the set whose points are counted (samplers without generating matrices)
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Raise the work limit (steps, e.g. 1e12)
    #[arg(long)]
    max_work: Option<f64>,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    if a.m == 0 {
        anyhow::bail!("--m 0: the nets start at m = 1");
    }
    let sampler = samplab::sampler::build(&a.spec)?;
    let bar = Bar::new(a.m as u64, "counts");
    let limits = Limits::new(a.max_work)?.stopped_by(bar.progress());
    let table = projection_table(&sampler, a.dims, a.m, &a.projection, a.base, Seed(a.seed), &limits)?;
    drop(bar);
    let (spec, seed) = (sampler.spec(), Seed(a.seed));
    let out = if a.json { table.json(spec, seed) } else { text(&table, &table.source(spec, seed)) };
    crate::emit(None, out.as_bytes())
}

fn axes(a: &[usize]) -> String {
    a.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
}

fn text(table: &ProjectionTable, source: &str) -> String {
    let mut out = format!("# {source}\n{:<12}", "axes");
    let most = table.t.first().map_or(0, Vec::len);
    for m in 1..=most {
        out += &format!(" {:>3}", format!("m{m}"));
    }
    out += "  worst\n";
    for (a, row) in table.axes.iter().zip(&table.t) {
        out += &format!("{:<12}", axes(a));
        row.iter().for_each(|t| out += &format!(" {t:>3}"));
        out += &format!("  {:>5}\n", row.iter().max().unwrap_or(&0));
    }
    out
}
