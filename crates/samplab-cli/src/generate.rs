//! `samplab generate`: point sets from any registered sampler, optionally warped.

use std::path::PathBuf;

use anyhow::Context as _;
use samplab::io::{self, Format, Role};
use samplab::{Seed, sampler, warp};

use crate::bar::Bar;

/// The examples, the samplers and the warps (from their registries).
fn after_help() -> String {
    format!(
        "Examples:\n  samplab generate jitter.gaussian:sigma=0.25 -n 256 -d 2 --seed 7\n  \
         samplab generate sobol.owen -n 1024 --sets 100 -o sobol.npy\n  \
         samplab generate jitter -n 64 --warp disk.concentric\n  \
         samplab generate file:path=best.npy+shift -n 256 --sets 100    # a saved set, shifted per set\n\n\
         Samplers: {}.\nStages (after any spec, one after another): {}.\nWarps: {}.\n\
         `samplab list samplers` (and `list stages`) lists each with its parameters and references.",
        samplab::sampler::SAMPLERS.names(),
        samplab::sampler::randomize::STAGES.names(),
        samplab::warp::WARPS.names()
    )
}

/// Generate point sets.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Sampler spec, e.g. jitter, sobol.owen, poisson:radius=0.05, GJittered:0.25
    spec: String,
    /// Number of points per set
    #[arg(short, long)]
    n: usize,
    /// Dimensions
    #[arg(short, long, default_value_t = 2)]
    dims: usize,
    /// Seed (set k uses a sub-seed hashed from it); the default is printed in the header
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Number of independent sets (realizations)
    #[arg(long, default_value_t = 1)]
    sets: usize,
    /// Warp the points, e.g. disk.concentric, tent, hemisphere.cosine
    #[arg(long)]
    warp: Option<String>,
    /// Output file (stdout when omitted or `-`); written atomically
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// text, csv, npy or json (default: from the output's extension, else text)
    #[arg(long)]
    format: Option<String>,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let s = sampler::build(&a.spec)?;
    let w = a.warp.as_deref().map(warp::lookup).transpose()?;
    // `-o -` is standard output, as when -o is omitted (the command-line convention)
    let output = a.output.as_deref().filter(|p| p.as_os_str() != "-");
    if let Some(p) = output {
        samplab::io::check_file(p)?;
        crate::refuse_overlap(&[&a.spec], &[Role::File("-o", p)])?;
    }
    let format = match &a.format {
        Some(f) => Format::from_name(f)?,
        None => output.map_or(Format::Text, Format::from_path),
    };
    if a.sets == 0 {
        anyhow::bail!("--sets must be at least 1");
    }
    if format == Format::Npy && output.is_none() {
        anyhow::bail!("--format npy is binary: give an output file with -o");
    }
    let plan = s.plan(a.n, a.dims)?;
    let seed = Seed(a.seed);
    let header = vec![format!(
        "samplab {} generate {} n={} d={} seed={} sets={}{}",
        env!("CARGO_PKG_VERSION"),
        s.spec(),
        a.n,
        a.dims,
        a.seed,
        a.sets,
        w.map_or(String::new(), |w| format!(" warp={}", w.name()))
    )];
    // the points and their encoding, in memory at once
    let points = a.n as u128 * a.sets as u128;
    let need = 8 * points * a.dims as u128 + io::encoded_size(format, points as usize, a.dims);
    let what = || format!("{} {}D points and their {} file", points, a.dims, io::format_name(format));
    if need > u128::from(samplab::memory::available())
        && let (Some(path), 1, None) = (output, a.sets, w)
        && format != Format::Json
        && let Some(mut stream) = plan.stream(seed.derive(0))
    {
        // one set larger than memory, from a sampler that makes its points in order: written
        // chunk by chunk, the same bytes
        let bar = Bar::new(io::stream_chunks(a.n) as u64, "chunks");
        let mut fill = |out: &mut [f64]| stream.next(out);
        return Ok(io::write_stream(path, format, &header, (a.n, a.dims), &mut fill, &bar.progress())?);
    }
    samplab::memory::check(what, need)?;
    let bar = Bar::sets(&plan, a.sets);
    let sets = plan.generate_sets(seed, a.sets, &bar.progress())?;
    drop(bar);
    let sets = match w {
        Some(w) => sets.iter().map(|p| warp::apply(w, p)).collect::<Result<Vec<_>, _>>()?,
        None => sets,
    };
    let bytes = io::encode(&sets, format, &header)?;
    crate::emit(output, &bytes).with_context(|| "writing the points")
}
