//! `samplab list`: the tables are the registries' own listings.

use std::fmt::Write as _;

use samplab::bibliography;

/// What to list.
#[derive(clap::Args)]
pub struct Args {
    /// samplers, stages, pixels (pixel samplers), warps, metrics, integrands, formats, scenes or
    /// references (all when omitted)
    #[arg(value_parser = ["samplers", "stages", "pixels", "warps", "metrics", "integrands", "formats", "scenes", "references"])]
    what: Option<String>,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let want = |w: &str| args.what.as_deref().is_none_or(|what| what == w);
    let mut out = String::new();
    for (what, listing) in [
        ("samplers", samplab::sampler::SAMPLERS.listing()),
        ("stages", samplab::sampler::randomize::STAGES.listing()),
        ("pixels", samplab::pixel::PIXEL_SAMPLERS.listing()),
        ("warps", samplab::warp::WARPS.listing()),
        ("metrics", samplab::discrepancy::METRICS.listing()),
        ("integrands", samplab::integrand::INTEGRANDS.listing()),
        ("formats", samplab::io::FORMATS.listing()),
        ("scenes", samplab_render::scenes::SCENES.listing()),
    ] {
        if want(what) {
            out.push_str(&listing);
            out.push('\n');
        }
    }
    if want("references") {
        out.push_str("REFERENCES\n\n");
        for r in bibliography::ALL {
            writeln!(out, "{}  {}", r.key, r.citation).expect("writing to a String");
        }
    }
    crate::emit(None, out.trim_end().as_bytes())?;
    crate::emit(None, b"\n")
}
