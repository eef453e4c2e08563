//! An image as a 2D integrand, as a renderer integrates an environment map or a texture:
//! texel (i, j) covers \[i/w, (i+1)/w\] x \[j/h, (j+1)/h\], row j = 0 at the top (x1 = 0), and
//! a lookup reads either the texel under the point (box) or the four around it weighted by
//! distance (bilinear, clamped to the edge).
//!
//! Both integrate to the mean texel value. For the box lookup it is the definition; for the
//! bilinear one, along each axis the half-texels at the two edges are constant and each
//! interior span between texel centres is a trapezoid, so every texel's weight is exactly
//! 1/w (and 1/h along the other axis).

use super::Integrand;
use crate::error::{Error, Result};

/// How a point reads the texels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Lookup {
    /// The texel under the point (nearest).
    Box,
    /// The four texels around the point, by distance to their centres; clamped to the edge.
    Bilinear,
}

impl Lookup {
    /// `box` or `bilinear`.
    ///
    /// # Errors
    /// Another name.
    pub fn parse(name: &str) -> Result<Lookup> {
        match name {
            "box" | "nearest" => Ok(Lookup::Box),
            "bilinear" => Ok(Lookup::Bilinear),
            _ => Err(Error::Setting { name: "lookup", value: name.into(), reason: "must be box or bilinear".into() }),
        }
    }
}

/// A w x h image of finite values as an integrand over the unit square.
#[derive(Debug, Clone)]
pub struct Texture {
    width: usize,
    height: usize,
    texels: Vec<f64>,
    lookup: Lookup,
    mean: f64,
}

impl Texture {
    /// Row-major texels from the top left.
    ///
    /// # Errors
    /// No texels, a length other than `width * height`, or a non-finite texel (named by its
    /// column and row).
    pub fn new(width: usize, height: usize, texels: Vec<f64>, lookup: Lookup) -> Result<Texture> {
        if width == 0 || height == 0 || texels.len() != width * height {
            return Err(Error::Setting {
                name: "image",
                value: format!("{width}x{height} with {} texels", texels.len()),
                reason: "needs at least one texel and width x height of them".into(),
            });
        }
        if let Some(i) = texels.iter().position(|t| !t.is_finite()) {
            return Err(Error::Setting {
                name: "image",
                value: format!("texel ({}, {}) = {}", i % width, i / width, texels[i]),
                reason: "every texel must be finite".into(),
            });
        }
        let mean = crate::stats::Summary::of(&texels).mean;
        Ok(Texture { width, height, texels, lookup, mean })
    }

    fn texel(&self, i: usize, j: usize) -> f64 {
        self.texels[j * self.width + i]
    }
}

/// The texel index under coordinate t of an axis of n texels, kept inside.
fn nearest(t: f64, n: usize) -> usize {
    ((t * n as f64) as usize).min(n - 1)
}

/// The two texels around coordinate t and the weight of the second (clamped to the edge).
fn around(t: f64, n: usize) -> (usize, usize, f64) {
    let s = (t * n as f64 - 0.5).clamp(0.0, (n - 1) as f64);
    let lo = (s as usize).min(n - 1);
    let hi = (lo + 1).min(n - 1);
    (lo, hi, s - lo as f64)
}

impl Integrand for Texture {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        match self.lookup {
            Lookup::Box => self.texel(nearest(x[0], self.width), nearest(x[1], self.height)),
            Lookup::Bilinear => {
                let (i0, i1, a) = around(x[0], self.width);
                let (j0, j1, b) = around(x[1], self.height);
                let top = self.texel(i0, j0) * (1.0 - a) + self.texel(i1, j0) * a;
                let bottom = self.texel(i0, j1) * (1.0 - a) + self.texel(i1, j1) * a;
                top * (1.0 - b) + bottom * b
            }
        }
    }
    fn exact(&self) -> f64 {
        self.mean
    }
}
