//! An integrand given by values on a grid: an image (the integral of a texture, as a
//! renderer integrates an environment map), or a function tabulated on a grid.

use rustfft::num_complex::Complex;

use super::{Integrand, phase, sinc};
use crate::error::{Error, Result};

/// Values on a w x h grid over the unit square with box (nearest-cell) lookups: cell
/// (i, j), value `values[j * w + i]`, covers [i/w, (i+1)/w) x [j/h, (j+1)/h) (the first row
/// at y = 0). Its integral, the integral of its square and its Fourier coefficients are
/// exact: F(k) = DFT(k mod (w, h)) exp(-pi i (kx/w + ky/h)) sinc(pi kx/w) sinc(pi ky/h) / (w h),
/// the DFT of the values times the transform of one cell.
#[derive(Debug, Clone)]
pub struct Grid {
    width: usize,
    height: usize,
    values: Vec<f64>,
    /// The values' DFT, in the FFT's order.
    transform: Vec<Complex<f64>>,
    mean: f64,
    square: f64,
}

/// The largest grid taken (2^26 cells: the transform is 1 GiB).
const MAX_CELLS: usize = 1 << 26;

impl Grid {
    /// The grid of `width` x `height` `values` (row-major, the first row at y = 0).
    ///
    /// # Errors
    /// An empty or oversized grid, a length that is not width x height, or a value that is
    /// not finite (named by its cell).
    pub fn new(width: usize, height: usize, values: Vec<f64>) -> Result<Grid> {
        let cells = width.checked_mul(height).filter(|&c| c > 0 && c <= MAX_CELLS);
        let Some(cells) = cells else {
            return Err(Error::Setting {
                name: "cells",
                value: format!("{width} x {height}"),
                reason: format!("a grid integrand takes 1 to {MAX_CELLS} cells"),
            });
        };
        if values.len() != cells {
            return Err(Error::Mismatch {
                what: format!("the values of a {width} x {height} grid"),
                expected: cells.to_string(),
                got: values.len().to_string(),
            });
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(Error::NotFinite {
                what: format!("grid cell ({}, {})", i % width, i / width),
                value: values[i],
            });
        }
        let mean = values.iter().sum::<f64>() / cells as f64;
        let square = values.iter().map(|v| v * v).sum::<f64>() / cells as f64;
        let transform = crate::screen::dft(width, height, values.iter().map(|&v| Complex::new(v, 0.0)).collect());
        Ok(Grid { width, height, values, transform, mean, square })
    }

    /// Width and height.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }
}

impl Integrand for Grid {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let cell = |t: f64, m: usize| ((t * m as f64) as usize).min(m - 1);
        self.values[cell(x[1], self.height) * self.width + cell(x[0], self.width)]
    }
    fn exact(&self) -> f64 {
        self.mean
    }
    fn exact_square(&self) -> Option<f64> {
        Some(self.square)
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        let (w, h) = (self.width as f64, self.height as f64);
        let index =
            k[1].rem_euclid(self.height as i64) as usize * self.width + k[0].rem_euclid(self.width as i64) as usize;
        let d = self.transform[index];
        let [c, s] = phase((k[0] as f64 / w + k[1] as f64 / h) / 2.0);
        let scale =
            sinc(std::f64::consts::PI * k[0] as f64 / w) * sinc(std::f64::consts::PI * k[1] as f64 / h) / (w * h);
        Some([(d.re * c - d.im * s) * scale, (d.re * s + d.im * c) * scale])
    }
}
