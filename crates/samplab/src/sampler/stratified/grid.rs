//! The grid family on n = k^d cells: regular, jittered, half-, box- and Gaussian-jittered,
//! uniform jitter (systematic sampling) and its Gaussian combination, and a randomly
//! rotated and translated regular grid.
//!
//! Cells are enumerated row-major: point i sits in cell (i_0, ..., i_{d-1}) with the
//! last coordinate varying fastest. A count that is not a perfect d-th power is an
//! error naming the two nearest valid counts; nothing is rounded.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::construct::counts::exact_root;
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
use crate::numeric::BELOW_ONE;
use crate::registry::About;
use crate::seed::{Rng, Seed, normal, uniform, wrap01};
use crate::spec::{Default, Kind, ParamSpec};
use crate::construct::spectrum_theory::{self as theory, VarianceTheory};

/// How each grid point is displaced inside (or around) its cell. Offsets are fractions of
/// the grid spacing 1/k.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Displacement {
    /// Cell centres (Shirley 1991 "regular").
    Regular,
    /// Uniform in the whole cell (Cook 1986; Shirley 1991 "jittered").
    Jitter,
    /// Uniform in the central half of the cell along each axis (Shirley 1991
    /// "half-jittered"): the box below with delta = 1/4.
    Half,
    /// Uniform in a centred box of half-width `delta`: delta = 0.25 is Shirley's
    /// half-jittered, 0.5 is plain jitter (Subr & Kautz 2013 eqs. 10-11, "BJittered").
    Box {
        /// Half-width of the box, fraction of a cell, in [0, 0.5].
        delta: f64,
    },
    /// Centre plus an independent normal offset of standard deviation `sigma` cells per
    /// coordinate (Subr & Kautz 2013 section 4, "GJittered"). Points that leave the unit
    /// cube are wrapped toroidally (`resample = false`) or their offset is redrawn.
    Gaussian {
        /// Standard deviation, fraction of a cell.
        sigma: f64,
        /// Redraw out-of-cube offsets instead of wrapping.
        resample: bool,
    },
    /// One uniform offset shared by every point (systematic sampling, Sbert et al. 2006;
    /// "uniform jitter", Ramamoorthi et al. 2012); with `offsets` > 1, that many grids of
    /// n / offsets points, each with its own offset (their secondary estimator, section 3.3
    /// and Table 1), one after the other.
    Uniform {
        /// Independent grids, at least 1.
        offsets: usize,
    },
    /// Shared offset alpha*(u - 1/2) plus per-point normal offsets of deviation sigma,
    /// wrapped toroidally (Subr & Kautz 2013 Fig. 10).
    UniformGaussian {
        /// Scale of the shared uniform offset, in [0, 1] cells.
        alpha: f64,
        /// Standard deviation of the per-point offsets, fraction of a cell.
        sigma: f64,
    },
}

/// A grid sampler: `k^d` points, one per cell, displaced by `displacement`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    displacement: Displacement,
}

impl Grid {
    /// A grid sampler displaced by `displacement`.
    pub(crate) fn new(displacement: Displacement) -> Self {
        Grid { displacement }
    }
}

/// The side k of a checked grid count n = k^d.
fn side(n: usize, dims: usize) -> usize {
    exact_root(n, dims).unwrap_or_else(|_| unreachable!("{n} is a checked count of a {dims}D grid"))
}


/// The most dimensions of a grid.
const MAX_DIMS: usize = 64;

impl Construction for Grid {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=MAX_DIMS
    }
    fn spectrum_theory(&self, n: usize, dims: usize) -> Option<VarianceTheory> {
        // displacements are fractions of the spacing 1/k
        let k = (n as f64).powf(1.0 / dims as f64);
        match self.displacement {
            Displacement::Gaussian { sigma, .. } => {
                let s = sigma / k;
                Some(VarianceTheory::new(format!("exact theory (1 - phi^2)/N, Gaussian sigma = {s:.4}"), move |w| {
                    theory::gaussian_variance(w, s, n)
                }))
            }
            Displacement::Box { delta } => {
                let d = delta / k;
                Some(VarianceTheory::new(format!("exact theory (1 - phi^2)/N, box half-width {d:.4}"), move |w| {
                    theory::box_variance(w, d, n)
                }))
            }
            _ => None,
        }
    }

    fn check_count(&self, shape: &Shape) -> Result<()> {
        // the other grids' counts are their entries' (n = k^d)
        match self.displacement {
            Displacement::Uniform { offsets } => {
                per_offset(shape.n(), offsets, shape.dims()).map(|_| ()).map_err(|why| shape.invalid_count(why))
            }
            _ => Ok(()),
        }
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = self.clone();
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Grid {

    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        if let Displacement::Uniform { offsets } = self.displacement
            && offsets > 1 {
                // checked when planned
                let each = n / offsets;
                let one = Grid::new(Displacement::Uniform { offsets: 1 });
                for (j, block) in out.chunks_exact_mut(each * dims).enumerate() {
                    one.fill(each, dims, seed.derive(j as u64), block)?;
                }
                return Ok(());
            }
        let k = side(n, dims);
        let mut rng = seed.rng();
        let inv = 1.0 / k as f64;
        // the shared offset of each axis (grids have at most MAX_DIMS), on the stack
        let mut shared = [0.5; MAX_DIMS];
        for s in &mut shared[..dims] {
            match self.displacement {
                Displacement::Uniform { .. } => *s = uniform(&mut rng),
                Displacement::UniformGaussian { alpha, .. } => *s = 0.5 + alpha * (uniform(&mut rng) - 0.5),
                _ => {}
            }
        }
        // point i's cells are i's digits in base k, the last axis's the lowest: counted up
        // digit by digit, not divided out (with two integer divisions per coordinate, this
        // function had 18% of the samples of `render spheres --spp 64`, 13% without)
        let mut cells = [0usize; MAX_DIMS];
        for p in out.chunks_exact_mut(dims) {
            for d in (0..dims).rev() {
                p[d] = self.place(cells[d] as f64, shared[d], inv, &mut rng);
            }
            for c in cells[..dims].iter_mut().rev() {
                *c += 1;
                if *c < k {
                    break;
                }
                *c = 0;
            }
        }
        Ok(())
    }
}

/// The points of each of `offsets` systematic grids making n (n / offsets = k^d), or why
/// there are none.
fn per_offset(n: usize, offsets: usize, dims: usize) -> std::result::Result<usize, String> {
    if !n.is_multiple_of(offsets) {
        return Err(format!("n must be a multiple of offsets = {offsets}"));
    }
    if offsets == 1 {
        return Counts::Grid.check(n, dims).map(|()| n);
    }
    exact_root(n / offsets, dims).map(|_| n / offsets).map_err(|(lo, hi)| {
        let (lo, hi) = (lo * offsets, hi * offsets);
        format!("each of the {offsets} grids needs k^{dims} points; the nearest valid counts are {lo} and {hi}")
    })
}

impl Grid {
    /// The coordinate of a point in cell `cell` (of width `inv`), drawing from `rng`.
    fn place(&self, cell: f64, shared: f64, inv: f64, rng: &mut Rng) -> f64 {
        let within = |t: f64| ((cell + t) * inv).min(BELOW_ONE);
        match self.displacement {
            Displacement::Regular => within(0.5),
            Displacement::Jitter => within(uniform(rng)),
            Displacement::Half => within(0.25 + 0.5 * uniform(rng)),
            Displacement::Box { delta } => within(0.5 + delta * (2.0 * uniform(rng) - 1.0)),
            Displacement::Uniform { .. } => within(shared),
            Displacement::Gaussian { sigma, resample: false } => wrap01((cell + 0.5 + sigma * normal(rng)) * inv),
            Displacement::Gaussian { sigma, resample: true } => loop {
                let x = (cell + 0.5 + sigma * normal(rng)) * inv;
                if (0.0..1.0).contains(&x) {
                    break x;
                }
            },
            Displacement::UniformGaussian { sigma, .. } => wrap01((cell + shared + sigma * normal(rng)) * inv),
        }
    }
}

/// The cell centres of a regular k x k grid, rotated about the centre by a uniformly random
/// angle, translated by a uniformly random offset and wrapped toroidally (Subr & Kautz 2013
/// section 5: its periodogram looks like blue noise, yet every realization is regular). 2D.
#[derive(Debug, Clone, Copy, Default)]
pub struct RotatedGrid;

impl Construction for RotatedGrid {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl RotatedGrid {

    fn fill(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let k = side(n, dims);
        let mut rng = seed.rng();
        let (s, c) = (TAU * uniform(&mut rng)).sin_cos();
        let (ox, oy) = (uniform(&mut rng), uniform(&mut rng));
        let inv = 1.0 / k as f64;
        for (i, p) in out.chunks_exact_mut(2).enumerate() {
            let x = ((i / k) as f64 + 0.5) * inv - 0.5;
            let y = ((i % k) as f64 + 0.5) * inv - 0.5;
            p[0] = wrap01(c * x - s * y + ox);
            p[1] = wrap01(s * x + c * y + oy);
        }
        Ok(())
    }
}

/// A hexagonal (triangular) lattice on the torus with a uniformly random offset: k points
/// per row at spacing 1/k, r = 2 round(k / sqrt 3) rows (even, so the half-spacing shift of
/// odd rows wraps), which makes the rows' spacing 1/r the closest to the ideal sqrt(3) / (2k)
/// that tiles the torus. n = k r. 2D.
#[derive(Debug, Clone, Copy, Default)]
pub struct Hexagonal;

/// The rows of the hexagonal lattice with k points per row.
fn hex_rows(k: usize) -> usize {
    2 * ((k as f64 / 3f64.sqrt()).round() as usize).max(1)
}

/// The counts k r(k) the hexagonal lattice makes, in increasing order.
fn hex_counts() -> impl Iterator<Item = (usize, usize)> + Clone {
    (1..).map(|k| (k * hex_rows(k), k)).take_while(|&(n, _)| n <= crate::construct::MAX_POINTS)
}

impl Construction for Hexagonal {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill(move |seed, out| me.fill(shape.n(), shape.dims(), seed, out)))
    }
}

impl Hexagonal {


    fn fill(&self, n: usize, _dims: usize, seed: Seed, out: &mut [f64]) -> Result<()> {
        let (_, k) = hex_counts().find(|&(c, _)| c == n).expect("a checked count");
        let r = hex_rows(k);
        let mut rng = seed.rng();
        let (ox, oy) = (uniform(&mut rng), uniform(&mut rng));
        for (i, p) in out.chunks_exact_mut(2).enumerate() {
            let (row, col) = (i / k, i % k);
            let half = if row % 2 == 1 { 0.5 } else { 0.0 };
            p[0] = wrap01((col as f64 + half + ox) / k as f64);
            p[1] = wrap01((row as f64 + oy) / r as f64);
        }
        Ok(())
    }
}

/// A grid entry: counts k^d, dimensions 1..=64.
const fn grid_entry(about: About, build: fn(&mut crate::spec::Params) -> Result<Box<dyn Construction>>) -> SamplerEntry {
    SamplerEntry { about, counts: Counts::Grid, randomized: true, dims: "1..=64", build }
}

const SIGMA: ParamSpec = ParamSpec {
    name: "sigma",
    kind: Kind::Real { min: 0.0, max: 8.0 },
    default: Default::Number(0.25),
    doc: "standard deviation, fraction of the grid spacing",
};

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[
    SamplerEntry {
        about: About::new("regular", "cell centres of a k^d grid").aliases(&["grid", "uniform"]).cite(&["shirley1991"]),
        counts: Counts::Grid,
        randomized: false,
        dims: "1..=64",
        build: |_| Ok(Box::new(Grid::new(Displacement::Regular))),
    },
    SamplerEntry {
        about: About::new("regular.rotated", "regular grid, random rotation and offset, wrapped on the torus")
            .aliases(&["rotated-grid"])
            .cite(&["subr2013"]),
        counts: Counts::Grid,
        randomized: true,
        dims: "2",
        build: |_| Ok(Box::new(RotatedGrid)),
    },
    SamplerEntry {
        about: About::new("hexagonal", "hexagonal lattice on the torus, random offset")
            .aliases(&["hex", "triangular"])
            .cite(&["petersen1962"]),
        counts: Counts::Listed {
            rule: "n must be k x 2 round(k / sqrt 3), k points per row",
            list: |_, _| Box::new(hex_counts().map(|(c, _)| c)),
        },
        randomized: true,
        dims: "2",
        build: |_| Ok(Box::new(Hexagonal)),
    },
    grid_entry(
        About::new("jitter", "one uniform point per grid cell")
            .aliases(&["jittered", "stratified"])
            .cite(&["cook1986", "shirley1991"]),
        |_| Ok(Box::new(Grid::new(Displacement::Jitter))),
    ),
    grid_entry(
        About::new("jitter.half", "uniform in the central half of each cell (per axis)")
            .aliases(&["half-jittered", "halfjittered"])
            .cite(&["shirley1991"]),
        |_| Ok(Box::new(Grid::new(Displacement::Half))),
    ),
    grid_entry(
        About::new("jitter.box", "uniform in a centred box of half-width delta (cells)")
            .aliases(&["bjittered", "box-jitter"])
            .params(&[ParamSpec {
                name: "delta",
                kind: Kind::Real { min: 0.0, max: 0.5 },
                default: Default::Number(0.1),
                doc: "half-width of the box, fraction of a cell",
            }])
            .cite(&["subr2013"]),
        |p| Ok(Box::new(Grid::new(Displacement::Box { delta: p.real("delta") }))),
    ),
    grid_entry(
        About::new("jitter.gaussian", "cell centre plus a normal offset of deviation sigma (cells)")
            .aliases(&["gjittered", "gaussian-jitter"])
            .params(&[
                SIGMA,
                ParamSpec {
                    name: "edge",
                    kind: Kind::Choice(&["wrap", "resample"]),
                    default: Default::Word("wrap"),
                    doc: "points leaving [0,1)^d wrap toroidally, or their offset is redrawn",
                },
            ])
            .cite(&["subr2013"]),
        |p| {
            let displacement = Displacement::Gaussian { sigma: p.real("sigma"), resample: p.word("edge") == "resample" };
            Ok(Box::new(Grid::new(displacement)))
        },
    ),
    SamplerEntry {
        about: About::new(
            "jitter.uniform",
            "the regular grid moved by one shared uniform offset (or several grids, one offset each)",
        )
        .terse()
        .aliases(&["systematic", "uniform-jitter"])
        .params(&[ParamSpec {
            name: "offsets",
            kind: Kind::Int { min: 1, max: 1 << 20 },
            default: Default::Int(1),
            doc: "independent systematic grids of n / offsets points each (Sbert et al. 2006's secondary estimator, Table 1)",
        }])
        .cite(&["sbert2006", "ramamoorthi2012"]),
        counts: Counts::Rule("n = offsets x k^d"),
        randomized: true,
        dims: "1..=64",
        build: |p| {
            let offsets = p.int("offsets") as usize;
            Ok(Box::new(Grid::new(Displacement::Uniform { offsets })))
        },
    },
    grid_entry(
        About::new(
            "jitter.uniform-gaussian",
            "shared offset alpha*(u-1/2) plus per-point normal offsets sigma (cells), wrapped",
        )
        .params(&[
            ParamSpec {
                name: "alpha",
                kind: Kind::Real { min: 0.0, max: 1.0 },
                default: Default::Number(1.0),
                doc: "scale of the shared uniform offset, cells",
            },
            ParamSpec { doc: "standard deviation of the per-point offsets, cells", ..SIGMA },
        ])
        .cite(&["subr2013"]),
        |p| {
            let displacement = Displacement::UniformGaussian { alpha: p.real("alpha"), sigma: p.real("sigma") };
            Ok(Box::new(Grid::new(displacement)))
        },
    ),
];
