//! `samplab list`: tables generated from the registries.

use std::fmt::Write as _;

use samplab::bibliography;
use samplab::io::FORMATS;
use samplab::sampler::registry;
use samplab::spec::ParamSpec;
use samplab::warp::WARPS;

/// What to list.
#[derive(clap::Args)]
pub struct Args {
    /// samplers, warps, metrics, integrands, formats or references (all when omitted)
    #[arg(value_parser = ["samplers", "warps", "metrics", "integrands", "formats", "references"])]
    what: Option<String>,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let all = args.what.is_none();
    let want = |w: &str| all || args.what.as_deref() == Some(w);
    let mut out = String::new();
    if want("samplers") {
        out.push_str("SAMPLERS  (spec: name[:key=value,...] or name[:value,...] in the order listed)\n\n");
        for e in registry::entries() {
            writeln!(out, "{}  —  {}", e.name, e.summary).unwrap();
            aliases(&mut out, &e.aliases);
            writeln!(out, "    counts: {}; dimensions: {}", e.counts, e.dims).unwrap();
            params(&mut out, e.params);
            writeln!(out, "    references: {}", e.references.join(", ")).unwrap();
        }
        out.push('\n');
    }
    if want("warps") {
        out.push_str("WARPS  (forward map, density and inverse)\n\n");
        for e in WARPS {
            writeln!(out, "{}  —  {}  [{}]", e.name, e.summary, e.dims).unwrap();
            aliases(&mut out, e.aliases);
            if !e.references.is_empty() {
                writeln!(out, "    references: {}", e.references.join(", ")).unwrap();
            }
        }
        out.push('\n');
    }
    if want("metrics") {
        out.push_str("METRICS  (values are never squared)\n\n");
        for e in samplab::discrepancy::METRICS {
            writeln!(
                out,
                "{}  —  {}{}{}",
                e.name,
                e.summary,
                if e.l2 { " [L2, closed form]" } else { "" },
                if e.shift_invariant { " [toroidal-shift invariant]" } else { "" }
            )
            .unwrap();
            if e.lower_bound {
                writeln!(out, "    a lower bound, not the exact value").unwrap();
            }
            aliases(&mut out, e.aliases);
            params(&mut out, e.params);
        }
        out.push('\n');
    }
    if want("integrands") {
        out.push_str("INTEGRANDS  (exact integrals; random families draw instance k from a hashed seed)\n\n");
        for e in samplab::integrand::INTEGRANDS {
            writeln!(out, "{}  —  {}  [{}D]", e.name, e.summary, e.dims).unwrap();
            aliases(&mut out, e.aliases);
            params(&mut out, e.params);
        }
        out.push('\n');
    }
    if want("formats") {
        out.push_str("FORMATS\n\n");
        for (name, _, doc) in FORMATS {
            writeln!(out, "{name}  —  {doc}").unwrap();
        }
        out.push('\n');
    }
    if want("references") {
        out.push_str("REFERENCES\n\n");
        for r in bibliography::ALL {
            writeln!(out, "{}  {}", r.key, r.citation).unwrap();
        }
    }
    crate::emit(None, out.trim_end().as_bytes())?;
    crate::emit(None, b"\n")
}

/// The "aliases:" line of an entry, when it has any.
fn aliases(out: &mut String, list: &[&str]) {
    if !list.is_empty() {
        writeln!(out, "    aliases: {}", list.join(", ")).unwrap();
    }
}

/// One line per parameter: name, default, valid range, meaning.
fn params(out: &mut String, list: &[ParamSpec]) {
    for p in list {
        writeln!(out, "    {} = {}  ({}): {}", p.name, p.default_text(), p.range_text(), p.doc).unwrap();
    }
}
