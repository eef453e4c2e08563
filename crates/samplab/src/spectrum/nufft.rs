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
use crate::memory::Pool;
use crate::numeric::quadrature::gauss_legendre;
use crate::points::PointSet;

/// The side of the tiles in which the 2D transform's transposes go, and the rows of an
/// FFT task.
const TILE: usize = 16;

/// The bytes of a band of the 2D grid's complex rows: a band stays in a core's cache from
/// spreading to FFT. Its real rows are the most that fit, a power of two from 16 to 64
/// (16 rows are 256 KiB at R = 1024); a point meets two bands when its w rows cross a
/// border, so wider bands spread fewer points twice.
const BAND_BYTES: usize = 1 << 17;

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
    /// Work buffers of finished transforms, taken by the next ones.
    scratch: Pool<Scratch>,
}

/// The buffers of one transform: the real grid (1D), the complex rows and the bands'
/// lists of points (2D).
#[derive(Default)]
struct Scratch {
    real: Vec<f64>,
    rows: Vec<C64<f64>>,
    bands: Bands,
}

/// The points met by each band of rows: band b's are `members[start[b]..start[b + 1]]`.
#[derive(Default)]
struct Bands {
    start: Vec<usize>,
    /// Each member's (x, y, weight).
    members: Vec<[f64; 3]>,
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
            return Err(Error::Setting {
                name: "tol",
                value: tol.to_string(),
                reason: "expected a number in [1e-14, 0.1]".into(),
            });
        }
        if !(1..=2).contains(&dims) {
            return Err(Error::Dimension { what: "the fast spectrum".into(), takes: "1D and 2D".into(), got: dims });
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

    /// The kernel weights of a point at x on the grid: the first grid index and 16 values
    /// (the first w the kernel's, the rest 0).
    #[inline(always)]
    fn weights(&self, x: f64) -> (i64, [f64; 16]) {
        let [out] = self.weights_of::<1, 16>([x]);
        out
    }

    /// [`Nufft::weights`] of N coordinates at once, the first L >= w values only (the rest
    /// 0): their Horner steps interleaved, so that the N chains of dependent
    /// multiplications and additions overlap.
    #[inline(always)]
    fn weights_of<const N: usize, const L: usize>(&self, xs: [f64; N]) -> [(i64, [f64; 16]); N] {
        let half = self.width as f64 / 2.0;
        let first = xs.map(|x| (x * self.grid as f64 - half).ceil());
        // the offset of the first index, first - g + w/2 in [0, 1), mapped to [-1, 1]
        let v: [f64; N] = std::array::from_fn(|i| 2.0 * (first[i] - xs[i] * self.grid as f64 + half) - 1.0);
        let (top, rest) = self.kernel.split_last().expect("a kernel polynomial");
        let mut out = [[0.0; 16]; N];
        for o in &mut out {
            o[..L].copy_from_slice(&top[..L]);
        }
        for c in rest.iter().rev() {
            for (o, &v) in out.iter_mut().zip(&v) {
                for (o, &ck) in o[..L].iter_mut().zip(&c[..L]) {
                    *o = *o * v + ck;
                }
            }
        }
        std::array::from_fn(|i| (first[i] as i64, out[i]))
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
    /// The set's dimension is not the planned one, or the weights do not match the points
    /// or are not all finite.
    pub fn transform_weighted(&self, points: &PointSet, weights: Option<&[f64]>) -> Result<Vec<Complex>> {
        let mut out = Vec::new();
        self.transform_into(points, weights, &mut out)?;
        Ok(out)
    }

    /// [`Nufft::transform_weighted`] into `out`, whose memory is reused when it is of the
    /// right size (a fresh 16 MiB buffer per set costs its page faults, which on several
    /// threads serialize on the process's page tables).
    pub(crate) fn transform_into(
        &self,
        points: &PointSet,
        weights: Option<&[f64]>,
        out: &mut Vec<Complex>,
    ) -> Result<()> {
        if let Some(w) = weights.filter(|w| w.len() != points.len()) {
            return Err(Error::Mismatch {
                what: "the weights".into(),
                expected: format!("one per point, {}", points.len()),
                got: w.len().to_string(),
            });
        }
        if let Some((j, &c)) = weights.and_then(|w| w.iter().enumerate().find(|(_, c)| !c.is_finite())) {
            return Err(Error::NotFinite { what: format!("weight {j}"), value: c });
        }
        if points.dims() != self.dims {
            return Err(Error::Dimension {
                what: "this transform".into(),
                takes: format!("{}D points (as planned)", self.dims),
                got: points.dims(),
            });
        }
        // the complex rows (8 bytes a grid cell) and the output (at most 4), with room
        let (g, cells) = (self.grid, (self.grid as u128).pow(self.dims as u32));
        crate::memory::check(|| format!("a non-uniform FFT on a {g}^{} grid", self.dims), 16 * cells)?;
        let mut scratch = self.scratch.take().unwrap_or_default();
        self.spread_and_transform(points, weights, &mut scratch, out);
        self.scratch.give([scratch]);
        Ok(())
    }

    /// The grid index of the first of the w cells a point at x spreads onto.
    #[inline(always)]
    fn first(&self, x: f64) -> f64 {
        (x * self.grid as f64 - self.width as f64 / 2.0).ceil()
    }

    /// The body of [`Nufft::transform_weighted`], in the buffers of `scratch`, into `out`.
    fn spread_and_transform(
        &self,
        points: &PointSet,
        weights: Option<&[f64]>,
        scratch: &mut Scratch,
        out: &mut Vec<Complex>,
    ) {
        let g = self.grid;
        // the grid's side is a power of two: an index wraps around the torus by a mask
        let wrap = |i: i64| (i & (g as i64 - 1)) as usize;
        let Scratch { real, rows, bands } = scratch;
        let inv = 1.0 / points.len() as f64;
        let half = (self.res / 2) as i64;
        let at = |k: usize| wrap(k as i64 - half);
        if self.dims == 1 {
            // spread into a real grid: 16 values from each first index (the last 16 - w
            // zero) where they fit, index by index around the torus near its seam
            real.clear();
            real.resize(g, 0.0);
            crate::simd::wide(
                #[inline(always)]
                || {
                    let real = real.as_mut_slice();
                    for (j, p) in points.iter().enumerate() {
                        let c = weights.map_or(1.0, |wt| wt[j]);
                        let (fx, wx) = self.weights(p[0]);
                        if fx >= 0
                            && fx as usize + 16 <= g
                            && let Some(cells) = real[fx as usize..].first_chunk_mut::<16>()
                        {
                            for (cell, &u) in cells.iter_mut().zip(&wx) {
                                *cell += c * u;
                            }
                        } else {
                            for (a, &u) in wx[..self.width].iter().enumerate() {
                                real[wrap(fx + a as i64)] += c * u;
                            }
                        }
                    }
                },
            );
            rows.clear();
            rows.extend(real.iter().map(|&v| C64::new(v, 0.0)));
            self.fft.process(rows);
            out.clear();
            out.extend((0..self.res).map(|i| {
                let v = rows[at(i)] * (self.correction[i] * inv);
                [v.re, v.im]
            }));
            return;
        }
        self.spread_rows(points, weights, rows, bands);
        let z = &*rows;
        // the second pass, TILE kept columns at a time (a parallel task each): gather them
        // into contiguous rows, transform them while they are in the core's cache, and
        // write them transposed into the output (TILE x 16 bytes contiguous per row)
        out.resize(self.res * self.res, [0.0; 2]);
        let res = self.res;
        let target = crate::memory::Disjoint(out.as_mut_ptr());
        let scratch_len = self.fft.get_inplace_scratch_len();
        (0..res.div_ceil(TILE)).into_par_iter().for_each_init(
            || (vec![C64::new(0.0, 0.0); TILE * g], vec![C64::new(0.0, 0.0); scratch_len]),
            |(tile, scratch), t| {
                let j0 = t * TILE;
                let tile = &mut tile[..TILE.min(res - j0) * g];
                // each cache line of z read serves a whole tile of TILE x TILE entries
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
                self.fft.process_with_scratch(tile, scratch);
                for i in 0..res {
                    for (dj, col) in tile.chunks_exact(g).enumerate() {
                        let j = j0 + dj;
                        let v = col[at(i)] * (self.correction[i] * self.correction[j] * inv);
                        // SAFETY: i * res + j is inside `out` (i, j < res), and the tasks
                        // write disjoint columns j; `out` outlives the parallel loop
                        unsafe { target.write(i * res + j, [v.re, v.im]) };
                    }
                }
            },
        );
    }

    /// The 2D grid's rows after their FFT, into `rows`. The grid is real: real rows 2p and
    /// 2p + 1 are the real and imaginary parts of complex row p, which goes through one
    /// complex FFT (A_k = (Z_k + conj Z_-k) / 2 and B_k = (Z_k - conj Z_-k) / 2i are
    /// unpacked later, for the R kept columns only).
    ///
    /// The grid is made band by band (16 to 64 real rows, a parallel task each): the points
    /// whose w rows meet the band are copied, in index order, into the band's list (a
    /// counting sort, so that a band reads its points from contiguous memory), and spread
    /// onto the band's complex rows: a point's two real rows 2p and 2p + 1 are one update
    /// of complex row p, 16 cells y-wise at once where they do not cross the seam (real
    /// part c u_2p v_k, imaginary part c u_2p+1 v_k; a row the point does not meet adds
    /// zeros). The band's rows are then transformed while they are still in the core's
    /// cache. Every cell gets the same additions in the same order as from a whole grid
    /// filled point by point (adding a zero leaves a sum that starts at +0 unchanged), so
    /// the bits do not depend on the bands nor the threads.
    fn spread_rows(&self, points: &PointSet, weights: Option<&[f64]>, rows: &mut Vec<C64<f64>>, bands: &mut Bands) {
        let (g, w) = (self.grid, self.width);
        let row_bytes = g * std::mem::size_of::<C64<f64>>();
        let band = (2 * BAND_BYTES / row_bytes).clamp(16, 64).min(g);
        // the grid's side is a power of two: an index wraps around the torus by a mask
        let wrap = |i: i64| (i & (g as i64 - 1)) as usize;
        // the bands met by each point's rows: at most two, as a band is at least w rows
        // (or the whole grid)
        let met = |p: &[f64]| {
            let fx = self.first(p[0]) as i64;
            let (b0, b1) = (wrap(fx) / band, wrap(fx + w as i64 - 1) / band);
            (b0, (b1 != b0).then_some(b1))
        };
        let Bands { start, members } = bands;
        start.clear();
        start.resize(g / band + 1, 0);
        for p in points.iter() {
            let (b0, b1) = met(p);
            start[b0 + 1] += 1;
            if let Some(b1) = b1 {
                start[b1 + 1] += 1;
            }
        }
        for b in 1..start.len() {
            start[b] += start[b - 1];
        }
        members.clear();
        members.resize(start[g / band], [0.0; 3]);
        let mut next = start.clone();
        for (j, p) in points.iter().enumerate() {
            let (b0, b1) = met(p);
            let c = weights.map_or(1.0, |wt| wt[j]);
            for b in std::iter::once(b0).chain(b1) {
                members[next[b]] = [p[0], p[1], c];
                next[b] += 1;
            }
        }
        let (start, members) = (&*start, &*members);
        // each band clears its own rows, in cache
        rows.resize(g / 2 * g, C64::new(0.0, 0.0));
        let scratch_len = self.fft.get_inplace_scratch_len();
        rows.par_chunks_mut(band / 2 * g).enumerate().for_each_init(
            || vec![C64::new(0.0, 0.0); scratch_len],
            |scratch, (b, chunk)| {
                chunk.fill(C64::new(0.0, 0.0));
                let r0 = (b * band) as i64;
                let list = &members[start[b]..start[b + 1]];
                // the kernel's lanes rounded up to a vector of 4: zeros beyond w cost nothing
                crate::simd::wide(
                    #[inline(always)]
                    || match self.width.next_multiple_of(4) {
                        ..=4 => self.spread_band::<4>(list, chunk, r0, band),
                        5..=8 => self.spread_band::<8>(list, chunk, r0, band),
                        9..=12 => self.spread_band::<12>(list, chunk, r0, band),
                        _ => self.spread_band::<16>(list, chunk, r0, band),
                    },
                );
                self.fft.process_with_scratch(chunk, scratch);
            },
        );
    }

    /// Spread a band's points (x, y, weight) onto its complex rows `chunk` (real rows r0..
    /// r0 + band): L of each point's 16 kernel values y-wise (L >= w; the rest are zero).
    #[inline(always)]
    fn spread_band<const L: usize>(&self, list: &[[f64; 3]], chunk: &mut [C64<f64>], r0: i64, band: usize) {
        let (g, w) = (self.grid, self.width);
        let wrap = |i: i64| (i & (g as i64 - 1)) as usize;
        for &[x, y, c] in list {
            let [(fx, wx), (fy, wy)] = self.weights_of::<2, L>([x, y]);
            // the point's weights c u_a on the band's real rows, paired as (real part,
            // imaginary part) of each complex row q met: its rows are consecutive, so each
            // q is met by one or two consecutive a
            let mut pairs = [(0usize, [0.0f64; 2]); 9];
            let mut met = 0;
            for (a, &u) in wx[..w].iter().enumerate() {
                let r = wrap(fx + a as i64) as i64 - r0;
                if (0..band as i64).contains(&r) {
                    let (q, part) = (r as usize / 2, r as usize % 2);
                    if met == 0 || pairs[met - 1].0 != q {
                        pairs[met] = (q, [0.0; 2]);
                        met += 1;
                    }
                    pairs[met - 1].1[part] = c * u;
                }
            }
            // the L values y-wise, each twice (real and imaginary parts)
            let mut twice = [0.0f64; 32];
            for (k, &v) in wy[..L].iter().enumerate() {
                twice[2 * k] = v;
                twice[2 * k + 1] = v;
            }
            let inner = fy >= 0 && fy as usize + 16 <= g;
            for &(q, pair) in &pairs[..met] {
                let row = &mut chunk[q * g..(q + 1) * g];
                if inner {
                    let cells = as_reals(&mut row[fy as usize..fy as usize + 16]);
                    for (i, (cell, &v)) in cells[..2 * L].iter_mut().zip(&twice[..2 * L]).enumerate() {
                        *cell += pair[i % 2] * v;
                    }
                } else {
                    for (k, &v) in wy[..w].iter().enumerate() {
                        let cell = &mut row[wrap(fy + k as i64)];
                        cell.re += pair[0] * v;
                        cell.im += pair[1] * v;
                    }
                }
            }
        }
    }
}

/// 16 complex cells as 32 reals (real and imaginary parts interleaved, as `Complex<f64>`
/// lays them out).
#[inline(always)]
fn as_reals(cells: &mut [C64<f64>]) -> &mut [f64; 32] {
    let cells: &mut [C64<f64>; 16] = cells.try_into().expect("16 cells");
    // SAFETY: Complex<f64> is repr(C) { re, im }: 16 of them are 32 f64 in that order,
    // with the same alignment
    unsafe { &mut *(cells as *mut [C64<f64>; 16]).cast::<[f64; 32]>() }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The rows after their FFT as the definition makes them: one whole real grid, filled
    /// point by point (each of a point's w x w cells gets (c u_a) v_b), rows 2p and 2p + 1
    /// packed into complex row p, each row transformed.
    fn whole_grid_rows(plan: &Nufft, points: &PointSet, weights: Option<&[f64]>) -> Vec<C64<f64>> {
        let (g, w) = (plan.grid, plan.width);
        let wrap = |i: i64| i.rem_euclid(g as i64) as usize;
        let mut real = vec![0.0; g * g];
        for (j, p) in points.iter().enumerate() {
            let c = weights.map_or(1.0, |wt| wt[j]);
            let ((fx, wx), (fy, wy)) = (plan.weights(p[0]), plan.weights(p[1]));
            for a in 0..w {
                for b in 0..w {
                    real[wrap(fx + a as i64) * g + wrap(fy + b as i64)] += c * wx[a] * wy[b];
                }
            }
        }
        let mut rows: Vec<C64<f64>> =
            real.chunks_exact(2 * g).flat_map(|pair| (0..g).map(move |k| C64::new(pair[k], pair[g + k]))).collect();
        for row in rows.chunks_exact_mut(g) {
            plan.fft.process(row);
        }
        rows
    }

    #[test]
    fn weights_must_be_finite() {
        let plan = Nufft::new(8, 2, 1e-6).unwrap();
        let points = PointSet::new(2, vec![0.1, 0.2, 0.3, 0.4]).unwrap();
        for bad in [f64::NAN, f64::INFINITY] {
            let err = plan.transform_weighted(&points, Some(&[1.0, bad])).unwrap_err().to_string();
            assert!(err.contains("weight 1 is") && err.contains("not a finite number"), "{err}");
        }
        assert!(plan.transform_weighted(&points, Some(&[1.0, -2.0])).is_ok());
    }

    #[test]
    fn bands_give_the_bits_of_one_whole_grid() {
        // points everywhere, and on both seams and band borders; widths 4 to 16; grids of
        // one band (g = 8, 16) to many (g = 256)
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for (res, tol) in [(2, 1e-1), (4, 1e-3), (8, 1e-9), (16, 1e-12), (100, 1e-9), (128, 1e-14)] {
            let plan = Nufft::new(res, 2, tol).unwrap();
            let g = plan.grid as f64;
            let mut data = Vec::new();
            for k in 0..300 {
                let edge = [0.0, 1.0 - 1e-12, 0.5 / g, 1.0 - 3.0 / g, 16.0 / g, 15.5 / g];
                let (x, y) = if k < 36 { (edge[k % 6], edge[k / 6]) } else { (next(), next()) };
                data.extend([x, y]);
            }
            let points = PointSet::new(2, data).unwrap();
            let weights: Vec<f64> = (0..points.len()).map(|_| next() * 2.0 - 1.0).collect();
            for weights in [None, Some(weights.as_slice())] {
                let mut rows = Vec::new();
                plan.spread_rows(&points, weights, &mut rows, &mut Bands::default());
                let reference = whole_grid_rows(&plan, &points, weights);
                assert_eq!(rows.len(), reference.len());
                for (i, (a, b)) in rows.iter().zip(&reference).enumerate() {
                    assert!(
                        a.re.to_bits() == b.re.to_bits() && a.im.to_bits() == b.im.to_bits(),
                        "R = {res}, tol {tol}, weighted {}: cell {i}: {a} against {b}",
                        weights.is_some()
                    );
                }
            }
        }
    }
}
