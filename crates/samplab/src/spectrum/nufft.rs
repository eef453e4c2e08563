//! The fast path: a type-1 non-uniform FFT (points to the centred integer frequencies) in
//! 1D and 2D, in the manner of FINUFFT (Barnett, Magland & af Klinteberg 2019): every
//! point spreads an "exponential of semicircle" kernel psi(t) = exp(beta (sqrt(1 - (2t/w)^2) - 1))
//! of width w onto a periodic grid oversampled by 2; one FFT; each frequency divided by the
//! kernel's Fourier transform (computed by Gauss-Legendre quadrature). As in FINUFFT, a
//! point's w kernel values are polynomials in its offset within its grid cell (Chebyshev
//! interpolants, evaluated by Horner's rule for all w at once), the degree the least that
//! keeps them within tol / 1000 of the kernel (or of its jump exp(-beta) at the support's
//! ends); a point away from the grid's seam adds 16 values to each of its w rows (w of them
//! nonzero) without wrapping indices. The grid is real: its rows go through the FFT in
//! pairs, as the real and imaginary parts of one complex row, and only the R kept columns
//! are unpacked and transformed again. The kernel width
//! and shape follow from the tolerance: w = ceil(log10(1/tol)) + 3, beta = 2.30 w, which
//! keeps the largest error against the direct DFT below tol relative to DC for random and
//! structured sets alike (tested).

use rayon::prelude::*;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex as C64;

use super::Complex;
use crate::error::{Error, Result};
use crate::numeric::quadrature::gauss_legendre;
use crate::points::PointSet;

/// The side of the tiles in which the 2D transform's transposes go, and the rows of an
/// FFT task.
const TILE: usize = 16;

/// A planned transform for one resolution and tolerance (reusable across sets).
pub struct Nufft {
    res: usize,
    dims: usize,
    grid: usize,
    width: usize,
    /// The kernel's w values at a point, as polynomials in the point's offset within a grid
    /// cell: `kernel[d][k]` is the coefficient of v^d of value k (zero beyond w).
    kernel: Vec<[f64; 16]>,
    /// 1 / (kernel's Fourier transform) at each output frequency k - R/2.
    correction: Vec<f64>,
    fft: std::sync::Arc<dyn rustfft::Fft<f64>>,
    /// Work buffers of finished transforms, taken by the next ones: a fresh grid of this
    /// size costs a page fault per 4 KiB on first write, and with several threads each fault
    /// is a TLB shootdown on every core (measured: more system time than the transform).
    scratch: std::sync::Mutex<Vec<Scratch>>,
}

/// The buffers of one transform: the real grid, the complex rows and the kept columns.
#[derive(Default)]
struct Scratch {
    real: Vec<f64>,
    rows: Vec<C64<f64>>,
    cols: Vec<C64<f64>>,
}

impl std::fmt::Debug for Nufft {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Nufft").field("res", &self.res).field("width", &self.width).finish_non_exhaustive()
    }
}

impl Nufft {
    /// Plan a transform to `res` frequencies per axis in `dims` (1 or 2) dimensions with
    /// relative tolerance `tol` in [1e-14, 1e-1].
    ///
    /// # Errors
    /// An odd resolution, a tolerance out of range, a dimension other than 1 or 2.
    pub fn new(res: usize, dims: usize, tol: f64) -> Result<Nufft> {
        super::check_res(res)?;
        if !(1e-14..=1e-1).contains(&tol) {
            return Err(Error::Invalid(format!("tolerance {tol}: expected a number in [1e-14, 0.1]")));
        }
        if !(1..=2).contains(&dims) {
            return Err(Error::Invalid(format!("the fast path handles 1D and 2D, not {dims}D")));
        }
        // FINUFFT's w = ceil(log10(1/tol)) + 1 bounds the error of random data; structured
        // sets (grids, nets) add the per-point errors coherently (measured: 15 x tol), so
        // two more points of width make tol a bound on the maximum error for any set
        let width = ((1.0 / tol).log10().ceil() as usize + 3).clamp(2, 16);
        let beta = 2.30 * width as f64;
        let grid = (2 * res).max(2 * width).next_power_of_two();
        let half = (res / 2) as f64;
        let hw = width as f64 / 2.0;
        // the kernel's Fourier transform at frequency k (cycles per unit): psi is defined in
        // grid-index units, so it is evaluated at xi = k / grid
        let psi =
            move |t: f64| if t.abs() >= hw { 0.0 } else { (beta * ((1.0 - (t / hw).powi(2)).sqrt() - 1.0)).exp() };
        // psi is even, so its transform is: one quadrature per distinct |k|
        let ft_at = |k: usize| {
            let xi = k as f64 / grid as f64;
            2.0 * gauss_legendre(|t| psi(t) * (std::f64::consts::TAU * xi * t).cos(), 0.0, hw, 2 * width)
        };
        let inverse: Vec<f64> = (0..=res / 2).map(|k| 1.0 / ft_at(k)).collect();
        let correction = (0..res).map(|i| inverse[(i as f64 - half).abs() as usize]).collect();
        // the kernel jumps by exp(-beta) at its support's ends, which no polynomial follows:
        // the fit aims at tol / 1000, or a few times that jump
        let kernel = kernel_polynomials(&psi, width, (tol / 1000.0).max(4.0 * (-beta).exp()));
        let fft = FftPlanner::new().plan_fft_forward(grid);
        Ok(Nufft { res, dims, grid, width, kernel, correction, fft, scratch: Default::default() })
    }

    /// The FFT of each grid-long row of `rows`, TILE rows to a parallel task (the rows are
    /// independent: the same bits on any thread count).
    fn ffts(&self, rows: &mut [C64<f64>]) {
        let g = self.grid;
        rows.par_chunks_mut(TILE * g).for_each(|chunk| {
            let mut scratch = vec![C64::new(0.0, 0.0); self.fft.get_inplace_scratch_len()];
            self.fft.process_with_scratch(chunk, &mut scratch);
        });
    }

    /// The kernel weights of a point at x on the grid: the first grid index and 16 values
    /// (the first w the kernel's, the rest 0).
    #[inline(always)]
    fn weights(&self, x: f64) -> (i64, [f64; 16]) {
        let g = x * self.grid as f64;
        let first = (g - self.width as f64 / 2.0).ceil();
        // the offset of the first index, first - g + w/2 in [0, 1), mapped to [-1, 1]
        let v = 2.0 * (first - g + self.width as f64 / 2.0) - 1.0;
        let (top, rest) = self.kernel.split_last().expect("a kernel polynomial");
        let mut out = *top;
        for c in rest.iter().rev() {
            for (o, &ck) in out.iter_mut().zip(c) {
                *o = *o * v + ck;
            }
        }
        (first as i64, out)
    }

    /// S(w) = (1/N) sum_j exp(-2 pi i w.x_j) at the centred frequencies, row-major.
    ///
    /// # Errors
    /// The set's dimension is not the planned one.
    pub fn transform(&self, points: &PointSet) -> Result<Vec<Complex>> {
        self.transform_weighted(points, None)
    }

    /// (1/N) sum_j c_j exp(-2 pi i w.x_j) with weights c_j (all 1 when None).
    ///
    /// # Errors
    /// The set's dimension is not the planned one, or the weights do not match the points.
    pub fn transform_weighted(&self, points: &PointSet, weights: Option<&[f64]>) -> Result<Vec<Complex>> {
        if weights.is_some_and(|w| w.len() != points.len()) {
            return Err(Error::Invalid("one weight per point is needed".into()));
        }
        if points.dims() != self.dims {
            return Err(Error::Invalid(format!("planned for {}D points, got {}D", self.dims, points.dims())));
        }
        // the real grid, and as much again for the transform's complex rows and output
        let (g, cells) = (self.grid, (self.grid as u128).pow(self.dims as u32));
        crate::memory::check(|| format!("a non-uniform FFT on a {g}^{} grid", self.dims), 16 * cells)?;
        let mut scratch = self.scratch.lock().map(|mut pool| pool.pop()).ok().flatten().unwrap_or_default();
        let out = self.spread_and_transform(points, weights, &mut scratch);
        if let Ok(mut pool) = self.scratch.lock() {
            pool.push(scratch);
        }
        Ok(out)
    }

    /// The body of [`Nufft::transform_weighted`], in the buffers of `scratch`.
    fn spread_and_transform(&self, points: &PointSet, weights: Option<&[f64]>, scratch: &mut Scratch) -> Vec<Complex> {
        let (g, w) = (self.grid, self.width);
        let wrap = |i: i64| i.rem_euclid(g as i64) as usize;
        // spread into a real grid: 16 values from each first index (the last 16 - w zero)
        // where they fit, index by index around the torus near its seam
        let Scratch { real, rows, cols } = scratch;
        real.clear();
        real.resize(g.pow(self.dims as u32), 0.0);
        let inner = |f: i64| f >= 0 && f as usize + 16 <= g;
        crate::simd::wide(
            #[inline(always)]
            || {
                // a local slice and kernel values by value: no aliasing for the vectorizer to fear
                let real = real.as_mut_slice();
                for (j, p) in points.iter().enumerate() {
                    let c = weights.map_or(1.0, |wt| wt[j]);
                    let (fx, wx) = self.weights(p[0]);
                    if self.dims == 1 {
                        if inner(fx)
                            && let Some(cells) = real[fx as usize..].first_chunk_mut::<16>()
                        {
                            for (cell, &u) in cells.iter_mut().zip(&wx) {
                                *cell += c * u;
                            }
                        } else {
                            for (a, &u) in wx[..w].iter().enumerate() {
                                real[wrap(fx + a as i64)] += c * u;
                            }
                        }
                        continue;
                    }
                    let (fy, wy) = self.weights(p[1]);
                    for (a, &u) in wx[..w].iter().enumerate() {
                        let (cu, row) = (c * u, wrap(fx + a as i64) * g);
                        if inner(fy)
                            && let Some(cells) = real[row + fy as usize..].first_chunk_mut::<16>()
                        {
                            for (cell, &v) in cells.iter_mut().zip(&wy) {
                                *cell += cu * v;
                            }
                        } else {
                            for (b, &v) in wy[..w].iter().enumerate() {
                                real[row + wrap(fy + b as i64)] += cu * v;
                            }
                        }
                    }
                }
            },
        );
        let inv = 1.0 / points.len() as f64;
        let half = (self.res / 2) as i64;
        let at = |k: usize| wrap(k as i64 - half);
        if self.dims == 1 {
            rows.clear();
            rows.extend(real.iter().map(|&v| C64::new(v, 0.0)));
            self.ffts(rows);
            return (0..self.res)
                .map(|i| {
                    let v = rows[at(i)] * (self.correction[i] * inv);
                    [v.re, v.im]
                })
                .collect();
        }
        // the rows are real: rows 2p and 2p + 1 go through one complex FFT as z = a + i b,
        // and A_k = (Z_k + conj Z_-k) / 2, B_k = (Z_k - conj Z_-k) / 2i are unpacked for the
        // R kept columns only
        rows.clear();
        rows.extend(
            real.chunks_exact(2 * g).flat_map(|pair| pair[..g].iter().zip(&pair[g..]).map(|(&a, &b)| C64::new(a, b))),
        );
        self.ffts(rows);
        let z = &*rows;
        // the second pass on the kept columns: gather each into a contiguous row, transform
        // them together, and read the result transposed
        // both transposes go tile by tile (TILE x TILE entries), so that each cache line and
        // page read is used for a whole tile rather than once per entry
        // (each tile of TILE columns, or of TILE output rows, a parallel task)
        cols.clear();
        cols.resize(self.res * g, C64::new(0.0, 0.0));
        cols.par_chunks_mut(TILE * g).enumerate().for_each(|(t, tile)| {
            let j0 = t * TILE;
            for p0 in (0..g / 2).step_by(TILE) {
                for (dj, col) in tile.chunks_exact_mut(g).enumerate() {
                    let (k, minus) = (at(j0 + dj), (g - at(j0 + dj)) % g);
                    for p in p0..(p0 + TILE).min(g / 2) {
                        let (zk, zm) = (z[p * g + k], z[p * g + minus].conj());
                        col[2 * p] = (zk + zm) * 0.5;
                        col[2 * p + 1] = (zk - zm) * C64::new(0.0, -0.5);
                    }
                }
            }
        });
        self.ffts(cols);
        let mut out = vec![[0.0; 2]; self.res * self.res];
        let cols = &*cols;
        out.par_chunks_mut(TILE * self.res).enumerate().for_each(|(t, tile)| {
            let i0 = t * TILE;
            for j0 in (0..self.res).step_by(TILE) {
                for j in j0..(j0 + TILE).min(self.res) {
                    for (di, row) in tile.chunks_exact_mut(self.res).enumerate() {
                        let i = i0 + di;
                        let v = cols[j * g + at(i)] * (self.correction[i] * self.correction[j] * inv);
                        row[j] = [v.re, v.im];
                    }
                }
            }
        });
        out
    }
}

/// The kernel's values at the w grid indices around a point, as polynomials in the point's
/// offset v in [-1, 1] (value k is psi(k - w/2 + (v + 1) / 2)): Chebyshev interpolants,
/// rewritten in powers of v, of the least degree (from w + 2) whose largest error on a fine
/// sample of v is at most `target` (degree 28 at most).
fn kernel_polynomials(psi: &impl Fn(f64) -> f64, width: usize, target: f64) -> Vec<[f64; 16]> {
    let hw = width as f64 / 2.0;
    let value = |k: usize, v: f64| psi(k as f64 - hw + (v + 1.0) / 2.0);
    let mut best: Option<(f64, Vec<[f64; 16]>)> = None;
    for degree in width + 2..=28 {
        let mut coef = vec![[0.0; 16]; degree + 1];
        for k in 0..width {
            for (row, c) in coef.iter_mut().zip(chebyshev_powers(|v| value(k, v), degree)) {
                row[k] = c;
            }
        }
        let err = (0..=100)
            .map(|i| -1.0 + i as f64 / 50.0)
            .flat_map(|v| (0..width).map(move |k| (k, v)))
            .map(|(k, v)| (coef.iter().rev().fold(0.0, |acc, c| acc * v + c[k]) - value(k, v)).abs())
            .fold(0.0, f64::max);
        if best.as_ref().is_none_or(|(e, _)| err < *e) {
            best = Some((err, coef));
        }
        if err <= target {
            break;
        }
    }
    best.expect("at least one degree").1
}

/// The interpolant of f at the degree + 1 Chebyshev points of [-1, 1], as coefficients of
/// 1, v, .., v^degree.
fn chebyshev_powers(f: impl Fn(f64) -> f64, degree: usize) -> Vec<f64> {
    let m = degree + 1;
    let nodes: Vec<f64> = (0..m).map(|i| (std::f64::consts::PI * (i as f64 + 0.5) / m as f64).cos()).collect();
    let values: Vec<f64> = nodes.iter().map(|&x| f(x)).collect();
    // Chebyshev coefficients c_j = (2 / m) sum_i f(x_i) T_j(x_i), c_0 halved
    let cheb: Vec<f64> = (0..m)
        .map(|j| {
            let s: f64 = nodes.iter().zip(&values).map(|(&x, &y)| y * (j as f64 * x.acos()).cos()).sum();
            if j == 0 { s / m as f64 } else { 2.0 * s / m as f64 }
        })
        .collect();
    // T_j in powers of v by T_{j+1} = 2 v T_j - T_{j-1}
    let mut out = vec![0.0; m];
    let (mut prev, mut cur) = (vec![0.0; m], vec![0.0; m]);
    prev[0] = 1.0; // T_0
    if m > 1 {
        cur[1] = 1.0; // T_1
    }
    for (j, &c) in cheb.iter().enumerate() {
        let t = if j == 0 { &prev } else { &cur };
        for (o, &a) in out.iter_mut().zip(t) {
            *o += c * a;
        }
        if j >= 1 {
            let mut next = vec![0.0; m];
            for i in 0..m {
                next[i] = -prev[i] + if i > 0 { 2.0 * cur[i - 1] } else { 0.0 };
            }
            prev = std::mem::replace(&mut cur, next);
        }
    }
    out
}
