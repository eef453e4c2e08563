//! Force matrix (Purgathofer, Tobler & Geiler 1994; used for sampling by Sbert et al. 2006,
//! section 3.3): n cells of a fine G^d grid chosen one at a time, each new one where the
//! repulsion energy sum_j f(r_j), f(r) = exp(-(r/s)^p), of the cells already chosen is
//! least (toroidal distance, ties broken at random).

use std::ops::RangeInclusive;

use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::Result;
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

/// Cells per block whose least energy is kept (a point's choice scans only the blocks that
/// can hold it).
const BLOCK: usize = 512;

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

    fn check_count(&self, shape: &Shape) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let g = self.grid_size(n, dims);
        let cells = g.checked_pow(dims as u32).unwrap_or(usize::MAX);
        if cells > MAX_CELLS {
            return Err(shape.invalid_count(format!("the fine grid would have {g}^{dims} cells, more than {MAX_CELLS}")));
        }
        if n > cells {
            return Err(shape.invalid_count(format!(
                    "only {cells} cells in the {g}^{dims} grid; use grid >= {}",
                    (n as f64).powf(1.0 / dims as f64).ceil()
                )));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = self.clone();
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(1, move |seed, out, progress| {
            me.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
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
        // the least energy of each block of BLOCK cells
        let mut least = vec![0.0f64; cells.div_ceil(BLOCK)];
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
        // f(r) at each offset of the window (the first axis the fastest), whatever its centre
        let kernel: Vec<f64> = (0..window)
            .map(|w| {
                let mut rest = w;
                let mut r2 = 0.0;
                for _ in 0..dims {
                    let delta = (rest % span) as f64 - reach as f64;
                    rest /= span;
                    r2 += delta * delta;
                }
                (-(r2.sqrt() / s_cells).powf(self.p)).exp()
            })
            .collect();
        let mut chosen = Vec::with_capacity(n);
        let mut touched = Vec::with_capacity(window + 1);
        for i in 0..n {
            // a stop every 256 points
            if i % 256 == 0 {
                progress.check()?;
            }
            // least energy among free cells, uniform among exact ties, in cell order; a block
            // whose least energy is above the best so far holds neither a lower energy nor a
            // tie (no draw), so only the others are scanned
            let (mut best, mut ties, mut best_e) = (0usize, 0u64, f64::INFINITY);
            for (b, &m) in least.iter().enumerate() {
                if m > best_e {
                    continue;
                }
                let start = b * BLOCK;
                for (c, &e) in energy[start..(start + BLOCK).min(cells)].iter().enumerate() {
                    if e < best_e {
                        (best, ties, best_e) = (start + c, 1, e);
                    } else if e == best_e {
                        ties += 1;
                        if below(&mut rng, ties) == 0 {
                            best = start + c;
                        }
                    }
                }
            }
            chosen.push(best);
            let centre = coords(best);
            touched.clear();
            for (w, &f) in kernel.iter().enumerate() {
                let mut rest = w;
                let mut flat = 0usize;
                for &c in &centre {
                    let o = rest % span;
                    rest /= span;
                    flat = flat * g + (c + g * (reach + 1) + o - reach) % g;
                }
                energy[flat] += f;
                touched.push(flat / BLOCK);
            }
            energy[best] = f64::INFINITY;
            touched.push(best / BLOCK);
            touched.sort_unstable();
            touched.dedup();
            for &b in &touched {
                least[b] = energy[b * BLOCK..((b + 1) * BLOCK).min(cells)].iter().fold(f64::INFINITY, |m, &e| m.min(e));
            }
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
