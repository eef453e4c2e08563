//! Force matrix (Purgathofer, Tobler & Geiler 1994; used for sampling by Sbert et al. 2006,
//! section 3.3): n cells of a fine G^d grid chosen one at a time, each new one where the
//! repulsion energy sum_j f(r_j), f(r) = exp(-(r/s)^p), of the cells already chosen is
//! least (toroidal distance, ties broken at random).

use std::ops::RangeInclusive;

use crate::sampler::registry::{Counts, SamplerEntry};
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::{Seed, below, uniform};
use crate::spec::{Default, Kind, ParamSpec};

/// The force-matrix sampler. `s` is in units of the mean spacing n^(-1/d) of the chosen
/// points; the whole pattern is moved by one uniform offset inside a fine cell
/// (systematic sampling on the fine grid), so estimates with it are unbiased.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceMatrix {
    s: f64,
    p: f64,
    grid: Option<usize>,
}

/// The largest fine grid, in cells.
const MAX_CELLS: usize = 1 << 24;

impl ForceMatrix {
    /// `grid` None means G = ceil(4 n^(1/d)) cells per axis.
    pub(crate) fn new(s: f64, p: f64, grid: Option<usize>) -> Self {
        ForceMatrix { s, p, grid }
    }

    fn grid_size(&self, n: usize, dims: usize) -> usize {
        self.grid.unwrap_or_else(|| (4.0 * (n as f64).powf(1.0 / dims as f64)).ceil() as usize)
    }
}

impl Construction for ForceMatrix {
    fn dims(&self) -> RangeInclusive<usize> {
        1..=4
    }

    fn check_count(&self, n: usize, dims: usize) -> Result<()> {
        let g = self.grid_size(n, dims);
        let cells = g.checked_pow(dims as u32).unwrap_or(usize::MAX);
        if cells > MAX_CELLS {
            return Err(Error::InvalidCount {
                sampler: String::new(),
                n,
                dims,
                reason: format!("the fine grid would have {g}^{dims} cells, more than {MAX_CELLS}"),
            });
        }
        if n > cells {
            return Err(Error::InvalidCount {
                sampler: String::new(),
                n,
                dims,
                reason: format!(
                    "only {cells} cells in the {g}^{dims} grid; use grid >= {}",
                    (n as f64).powf(1.0 / dims as f64).ceil()
                ),
            });
        }
        Ok(())
    }

    fn prepare(&self, shape: Shape) -> Result<Box<dyn Prepared + '_>> {
        Ok(crate::sampler::from_fill_reporting(1, move |seed, out, progress| {
            self.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
        }))
    }
}

impl ForceMatrix {

    fn fill_reporting(&self, n: usize, dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        let g = self.grid_size(n, dims);
        let cells = g.pow(dims as u32);
        let mut rng = seed.rng();
        // energy in units of cells: s_cells = s * spacing * g
        let s_cells = self.s * (n as f64).powf(-1.0 / dims as f64) * g as f64;
        // beyond this many cells f(r) < 1e-17 and cannot change a comparison
        let reach = ((s_cells * 39.2f64.powf(1.0 / self.p)).ceil() as usize).min((g - 1) / 2);
        let mut energy = vec![0.0f64; cells];
        let coords = |c: usize| -> Vec<usize> {
            let mut rest = c;
            let mut v = vec![0; dims];
            for d in (0..dims).rev() {
                v[d] = rest % g;
                rest /= g;
            }
            v
        };
        let span = 2 * reach + 1;
        let window = span.pow(dims as u32);
        let mut chosen = Vec::with_capacity(n);
        for i in 0..n {
            // a stop every 256 points (each point scans every cell: 0.1 s for 256 at 10^5)
            if i % 256 == 0 {
                progress.check()?;
            }
            // least energy among free cells, uniform among exact ties
            let (mut best, mut ties, mut best_e) = (0usize, 0u64, f64::INFINITY);
            for (c, &e) in energy.iter().enumerate() {
                if e < best_e {
                    (best, ties, best_e) = (c, 1, e);
                } else if e == best_e {
                    ties += 1;
                    if below(&mut rng, ties) == 0 {
                        best = c;
                    }
                }
            }
            chosen.push(best);
            let centre = coords(best);
            for w in 0..window {
                let mut rest = w;
                let (mut flat, mut r2) = (0usize, 0.0);
                for &c in centre.iter() {
                    let o = rest % span;
                    rest /= span;
                    let delta = o as f64 - reach as f64;
                    r2 += delta * delta;
                    flat = flat * g + (c + g * (reach + 1) + o - reach) % g;
                }
                energy[flat] += (-(r2.sqrt() / s_cells).powf(self.p)).exp();
            }
            energy[best] = f64::INFINITY;
        }
        let offset: Vec<f64> = (0..dims).map(|_| uniform(&mut rng)).collect();
        for (p, &c) in out.chunks_exact_mut(dims).zip(&chosen) {
            for (d, x) in coords(c).into_iter().enumerate() {
                p[d] = ((x as f64 + offset[d]) / g as f64).min(crate::numeric::BELOW_ONE);
            }
        }
        progress.advance(1)
    }
}

/// The sampler this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("force-matrix", "n cells of a fine grid chosen by least repulsion energy exp(-(r/s)^p)")
        .aliases(&["forcematrix", "forced-random"])
        .params(&[
            ParamSpec {
                name: "s",
                kind: Kind::Real { min: 1e-3, max: 10.0 },
                default: Default::Number(0.5),
                doc: "energy scale, in units of the mean spacing n^(-1/d)",
            },
            ParamSpec {
                name: "p",
                kind: Kind::Real { min: 0.1, max: 16.0 },
                default: Default::Number(2.0),
                doc: "energy exponent",
            },
            ParamSpec {
                name: "grid",
                kind: Kind::Int { min: 1, max: 1 << 24 },
                default: Default::Auto("ceil(4 n^(1/d)) cells per axis"),
                doc: "fine grid cells per axis",
            },
        ])
        .cite(&["sbert2006", "purgathofer1994"]),
    counts: Counts::Rule("n <= G^d"),
    randomized: true,
    dims: "1..=4",
    build: |p| Ok(Box::new(ForceMatrix::new(p.real("s"), p.real("p"), p.int_or_auto("grid").map(|g| g as usize)))),
}];
