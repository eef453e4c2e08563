//! The table of samplers: canonical names, the papers' aliases, parameters with defaults
//! and ranges, one-line summaries, references, and builders. `samplab list`, `--help`
//! and the conformance tests are generated from it.

use std::sync::LazyLock;

use super::Sampler;
use super::force_matrix::ForceMatrix;
use super::grid::{Displacement, Grid, RotatedGrid};
use super::nrooks::NRooks;
use super::pmj::{Cmj, Pmj02};
use super::poisson::{Bridson, DartThrowing, Maximal, edge_is_torus};
use super::radical::{Halton, Hammersley};
use super::random::Random;
use super::scramble::Randomization;
use super::sobol::Sobol;
use crate::error::{Error, Result, closest_names};
use crate::spec::{Default, Kind, ParamSpec, Params, Spec};

/// A function that builds a sampler from resolved parameters.
pub type Builder = Box<dyn Fn(&Params) -> Result<Box<dyn Sampler>> + Send + Sync>;

/// One registered sampler.
pub struct SamplerEntry {
    /// Canonical name (`family[.variant]`).
    pub name: String,
    /// Other accepted names, e.g. the papers' own.
    pub aliases: Vec<&'static str>,
    /// One line: what it does.
    pub summary: String,
    /// Which counts n it can make.
    pub counts: &'static str,
    /// Supported dimensions, in words.
    pub dims: &'static str,
    /// Parameters in positional order.
    pub params: &'static [ParamSpec],
    /// Bibliography keys.
    pub references: Vec<&'static str>,
    build: Builder,
}

impl std::fmt::Debug for SamplerEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SamplerEntry").field("name", &self.name).finish_non_exhaustive()
    }
}

const GRID: &str = "n = k^d";
const ANY: &str = "any n";

const EDGE: ParamSpec = ParamSpec {
    name: "edge",
    kind: Kind::Choice(&["torus", "plain"]),
    default: Default::Word("torus"),
    doc: "distance measured on the torus (wraps around) or inside the square",
};

macro_rules! entry {
    ($name:expr, [$($alias:expr),*], $summary:expr, $counts:expr, $dims:expr, $params:expr, [$($r:expr),*], $build:expr) => {
        SamplerEntry {
            name: $name.to_string(),
            aliases: vec![$($alias),*],
            summary: $summary.to_string(),
            counts: $counts,
            dims: $dims,
            params: $params,
            references: vec![$($r),*],
            build: Box::new($build),
        }
    };
}

fn grid(name: &'static str, d: Displacement) -> Result<Box<dyn Sampler>> {
    Ok(Box::new(Grid::new(name, d)))
}

fn number(p: &Params, name: &str) -> f64 {
    p.number(name).expect("declared with a numeric default")
}

static REGISTRY: LazyLock<Vec<SamplerEntry>> = LazyLock::new(|| {
    let mut r = vec![
        entry!(
            "random",
            ["uniform-random", "poisson-sampling"],
            "independent uniform points",
            ANY,
            "any d",
            &[],
            ["shirley1991"],
            |_| Ok(Box::new(Random))
        ),
        entry!(
            "regular",
            ["grid", "uniform"],
            "cell centres of a k^d grid",
            GRID,
            "1..=64",
            &[],
            ["shirley1991"],
            |_| grid("regular", Displacement::Regular)
        ),
        entry!(
            "regular.rotated",
            ["rotated-grid"],
            "regular grid, random rotation and offset, wrapped on the torus",
            GRID,
            "2",
            &[],
            ["subr2013"],
            |_| Ok(Box::new(RotatedGrid))
        ),
        entry!(
            "jitter",
            ["jittered", "stratified"],
            "one uniform point per grid cell",
            GRID,
            "1..=64",
            &[],
            ["cook1986", "shirley1991"],
            |_| grid("jitter", Displacement::Jitter)
        ),
        entry!(
            "jitter.half",
            ["half-jittered", "halfjittered"],
            "uniform in the central half of each cell (per axis)",
            GRID,
            "1..=64",
            &[],
            ["shirley1991"],
            |_| grid("jitter.half", Displacement::Half)
        ),
        entry!(
            "jitter.box",
            ["bjittered", "box-jitter"],
            "uniform in a centred box of half-width delta (cells)",
            GRID,
            "1..=64",
            &[ParamSpec {
                name: "delta",
                kind: Kind::Real { min: 0.0, max: 0.5 },
                default: Default::Number(0.1),
                doc: "half-width of the box, fraction of a cell"
            }],
            ["subr2013"],
            |p| grid("jitter.box", Displacement::Box { delta: number(p, "delta") })
        ),
        entry!(
            "jitter.gaussian",
            ["gjittered", "gaussian-jitter"],
            "cell centre plus a normal offset of deviation sigma (cells)",
            GRID,
            "1..=64",
            &[
                ParamSpec {
                    name: "sigma",
                    kind: Kind::Real { min: 0.0, max: 8.0 },
                    default: Default::Number(0.25),
                    doc: "standard deviation, fraction of the grid spacing"
                },
                ParamSpec {
                    name: "edge",
                    kind: Kind::Choice(&["wrap", "resample"]),
                    default: Default::Word("wrap"),
                    doc: "points leaving [0,1)^d wrap toroidally, or their offset is redrawn"
                }
            ],
            ["subr2013"],
            |p| grid(
                "jitter.gaussian",
                Displacement::Gaussian { sigma: number(p, "sigma"), resample: p.word("edge") == "resample" }
            )
        ),
        entry!(
            "jitter.uniform",
            ["systematic", "uniform-jitter"],
            "the regular grid moved by one shared uniform offset (or several grids, one offset each)",
            "n = offsets x k^d",
            "1..=64",
            &[ParamSpec {
                name: "offsets",
                kind: Kind::Int { min: 1, max: 1 << 20 },
                default: Default::Number(1.0),
                doc: "independent systematic grids of n / offsets points each (Sbert et al. 2006's secondary estimator, Table 1)"
            }],
            ["sbert2006", "ramamoorthi2012"],
            |p| grid("jitter.uniform", Displacement::Uniform { offsets: number(p, "offsets") as usize })
        ),
        entry!(
            "jitter.uniform-gaussian",
            [],
            "shared offset alpha*(u-1/2) plus per-point normal offsets sigma (cells), wrapped",
            GRID,
            "1..=64",
            &[
                ParamSpec {
                    name: "alpha",
                    kind: Kind::Real { min: 0.0, max: 1.0 },
                    default: Default::Number(1.0),
                    doc: "scale of the shared uniform offset, cells"
                },
                ParamSpec {
                    name: "sigma",
                    kind: Kind::Real { min: 0.0, max: 8.0 },
                    default: Default::Number(0.25),
                    doc: "standard deviation of the per-point offsets, cells"
                }
            ],
            ["subr2013"],
            |p| grid(
                "jitter.uniform-gaussian",
                Displacement::UniformGaussian { alpha: number(p, "alpha"), sigma: number(p, "sigma") }
            )
        ),
        entry!(
            "nrooks",
            ["n-rooks", "separate", "lhcube", "latin-hypercube", "lhs"],
            "one point in every slab of every axis (Latin hypercube)",
            ANY,
            "any d",
            &[],
            ["mckay1979", "shirley1991"],
            |_| Ok(Box::new(NRooks))
        ),
        entry!(
            "poisson",
            ["poisson-disk", "dart-throwing"],
            "dart throwing with a minimum distance",
            ANY,
            "1..=4",
            &[
                ParamSpec {
                    name: "radius",
                    kind: Kind::Real { min: 1e-9, max: 1.0 },
                    default: Default::Auto("0.7 x the packing radius of n points"),
                    doc: "minimum distance between points"
                },
                EDGE,
                ParamSpec {
                    name: "attempts",
                    kind: Kind::Int { min: 1, max: 1_000_000_000 },
                    default: Default::Number(100_000.0),
                    doc: "consecutive misses before a try is abandoned (16 tries)"
                }
            ],
            ["cook1986", "shirley1991"],
            |p| Ok(Box::new(DartThrowing::new(
                p.number("radius"),
                edge_is_torus(p.word("edge")),
                number(p, "attempts") as u64
            )))
        ),
        entry!(
            "poisson.fast",
            ["bridson"],
            "Bridson's O(n) Poisson disk: fill, then keep a random n",
            ANY,
            "2",
            &[
                ParamSpec {
                    name: "radius",
                    kind: Kind::Real { min: 1e-6, max: 1.0 },
                    default: Default::Auto("0.72 x the packing radius of n points"),
                    doc: "minimum distance between points"
                },
                EDGE,
                ParamSpec {
                    name: "k",
                    kind: Kind::Int { min: 1, max: 10_000 },
                    default: Default::Number(30.0),
                    doc: "candidates tried around each active point"
                }
            ],
            ["bridson2007"],
            |p| Ok(Box::new(Bridson::new(p.number("radius"), edge_is_torus(p.word("edge")), number(p, "k") as u32)))
        ),
        entry!(
            "poisson.maximal",
            ["maximal-poisson"],
            "maximal Poisson disk: no room for another point; radius found for exactly n",
            ANY,
            "2",
            &[EDGE],
            ["ebeida2012", "bridson2007"],
            |p| Ok(Box::new(Maximal::new(edge_is_torus(p.word("edge")))))
        ),
        entry!(
            "pmj02",
            ["pmj"],
            "progressive multi-jittered (0,2) sequence, stochastic construction",
            "any n (nets at powers of two)",
            "2",
            &[],
            ["christensen2018", "helmer2021"],
            |_| Ok(Box::new(Pmj02))
        ),
        entry!(
            "cmj",
            ["correlated-multi-jittered"],
            "correlated multi-jittered sampling",
            ANY,
            "2",
            &[],
            ["kensler2013"],
            |_| Ok(Box::new(Cmj))
        ),
        entry!(
            "force-matrix",
            ["forcematrix"],
            "n cells of a fine grid chosen by least repulsion energy exp(-(r/s)^p)",
            "n <= G^d",
            "1..=4",
            &[
                ParamSpec {
                    name: "s",
                    kind: Kind::Real { min: 1e-3, max: 10.0 },
                    default: Default::Number(0.5),
                    doc: "energy scale, in units of the mean spacing n^(-1/d)"
                },
                ParamSpec {
                    name: "p",
                    kind: Kind::Real { min: 0.1, max: 16.0 },
                    default: Default::Number(2.0),
                    doc: "energy exponent"
                },
                ParamSpec {
                    name: "grid",
                    kind: Kind::Int { min: 1, max: 1 << 24 },
                    default: Default::Auto("ceil(4 n^(1/d)) cells per axis"),
                    doc: "fine grid cells per axis"
                }
            ],
            ["sbert2006", "purgathofer1994"],
            |p| Ok(Box::new(ForceMatrix::new(number(p, "s"), number(p, "p"), p.number("grid").map(|g| g as usize))))
        ),
    ];
    for rnd in [Randomization::None, Randomization::Xor, Randomization::Owen, Randomization::Shift] {
        let suffix = |family: &str| {
            if rnd == Randomization::None { family.to_string() } else { format!("{family}.{}", rnd.suffix()) }
        };
        let how = match rnd {
            Randomization::None => "",
            Randomization::Xor => ", random digit scrambling",
            Randomization::Owen => ", Owen scrambling (hash-based)",
            Randomization::Shift => ", Cranley-Patterson shift",
        };
        let cite = match rnd {
            Randomization::None => None,
            Randomization::Xor => Some("matousek1998"),
            Randomization::Owen => Some("burley2020"),
            Randomization::Shift => Some("cranley1976"),
        };
        let refs = |base: &'static str| std::iter::once(base).chain(cite).collect::<Vec<_>>();
        let aliases = |a: &'static str| {
            if rnd == Randomization::Owen { vec![a] } else { vec![] }
        };
        r.push(
            SamplerEntry {
                aliases: aliases("sobol-owen"),
                ..entry!(
                    suffix("sobol"),
                    [],
                    format!("Sobol' sequence, Joe-Kuo directions{how}"),
                    "n <= 2^32 (nets at powers of two)",
                    "1..=1024",
                    &[],
                    [],
                    move |_| Ok(Box::new(Sobol::new(rnd)))
                )
            }
            .with_refs(refs("sobol1967"), "joe2008"),
        );
        r.push(
            SamplerEntry {
                aliases: aliases("halton-owen"),
                ..entry!(
                    suffix("halton"),
                    [],
                    format!("Halton sequence, prime bases{how}"),
                    ANY,
                    "1..=1024",
                    &[],
                    [],
                    move |_| Ok(Box::new(Halton::new(rnd)))
                )
            }
            .with_refs(refs("halton1960"), ""),
        );
        r.push(
            SamplerEntry {
                aliases: aliases("hammersley-owen"),
                ..entry!(
                    suffix("hammersley"),
                    [],
                    format!("Hammersley set: i/n, then Halton{how}"),
                    "n <= 2^32",
                    "1..=1025",
                    &[],
                    [],
                    move |_| Ok(Box::new(Hammersley::new(rnd)))
                )
            }
            .with_refs(refs("hammersley1964"), ""),
        );
    }
    r
});

impl SamplerEntry {
    fn with_refs(mut self, mut refs: Vec<&'static str>, extra: &'static str) -> Self {
        if !extra.is_empty() {
            refs.insert(1, extra);
        }
        self.references = refs;
        self
    }

    /// Build this entry's sampler from a parsed spec's arguments.
    ///
    /// # Errors
    /// Unknown, repeated, malformed or out-of-range parameters.
    pub fn build(&self, args: &[(Option<String>, String)]) -> Result<Box<dyn Sampler>> {
        let params = Params::resolve(&self.name, self.params, args)?;
        (self.build)(&params)
    }
}

/// Every registered sampler, in listing order.
pub fn entries() -> &'static [SamplerEntry] {
    &REGISTRY
}

/// The entry called `name` (canonical or alias, case-insensitive).
///
/// # Errors
/// An unknown name, with the closest known names as suggestions.
pub fn lookup(name: &str) -> Result<&'static SamplerEntry> {
    let want = name.to_ascii_lowercase();
    entries().iter().find(|e| e.name == want || e.aliases.iter().any(|a| *a == want)).ok_or_else(|| {
        Error::UnknownName {
            kind: "sampler",
            name: name.to_string(),
            suggestions: closest_names(
                name,
                entries().iter().flat_map(|e| std::iter::once(e.name.as_str()).chain(e.aliases.iter().copied())),
            ),
        }
    })
}

/// Build a sampler from a spec such as `jitter.gaussian:sigma=0.25` or `GJittered:0.25`.
///
/// # Errors
/// A malformed spec, an unknown name, or bad parameters.
pub fn build(spec: &str) -> Result<Box<dyn Sampler>> {
    let spec = Spec::parse(spec)?;
    lookup(&spec.name)?.build(&spec.args)
}
