//! Subr & Kautz 2013 test cases II and III: piecewise constant and piecewise linear
//! functions over a Delaunay triangulation (spade) of sparse random points and the four
//! corners of the square, with a uniform grid of candidate triangles for fast lookup.

use spade::{DelaunayTriangulation, Point2, Triangulation};

use super::Integrand;
use crate::error::{Error, Result};
use crate::seed::{Rng, uniform};

/// A piecewise constant (weights per triangle) or linear (weights per vertex) function.
#[derive(Debug, Clone)]
pub struct Delaunay {
    triangles: Vec<[[f64; 2]; 3]>,
    /// Per triangle (constant) or per triangle corner (linear).
    weights: Vec<[f64; 3]>,
    grid: usize,
    cells: Vec<Vec<u32>>,
}

fn cross(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

impl Delaunay {
    /// Triangulate `points` random points and the corners; weights uniform in [0, 1).
    ///
    /// # Errors
    /// The triangulation fails (it cannot for points in the square; kept typed).
    pub fn random(points: usize, linear: bool, rng: &mut Rng) -> Result<Self> {
        let mut sites = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        sites.extend((0..points).map(|_| [uniform(rng), uniform(rng)]));
        let vertex_weights: Vec<f64> = sites.iter().map(|_| uniform(rng)).collect();
        let t =
            DelaunayTriangulation::<Point2<f64>>::bulk_load(sites.iter().map(|p| Point2::new(p[0], p[1])).collect())
                .map_err(|e| Error::Infeasible { what: "a Delaunay triangulation".into(), reason: format!("{e:?}") })?;
        let mut triangles = Vec::new();
        let mut weights = Vec::new();
        for face in t.inner_faces() {
            let v = face.vertices();
            let tri = v.map(|h| {
                let p = h.position();
                [p.x, p.y]
            });
            triangles.push(tri);
            weights.push(if linear {
                v.map(|h| vertex_weights[h.fix().index()])
            } else {
                let w = uniform(rng);
                [w, w, w]
            });
        }
        Ok(Self::with_grid(triangles, weights))
    }

    fn with_grid(triangles: Vec<[[f64; 2]; 3]>, weights: Vec<[f64; 3]>) -> Self {
        let grid = 16;
        let mut cells = vec![Vec::new(); grid * grid];
        for (i, t) in triangles.iter().enumerate() {
            let lo = |k: usize| {
                ((t.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min) * grid as f64).floor().max(0.0) as usize)
                    .min(grid - 1)
            };
            let hi = |k: usize| {
                ((t.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max) * grid as f64).floor().max(0.0) as usize)
                    .min(grid - 1)
            };
            for cx in lo(0)..=hi(0) {
                for cy in lo(1)..=hi(1) {
                    cells[cx * grid + cy].push(i as u32);
                }
            }
        }
        Delaunay { triangles, weights, grid, cells }
    }

    fn area(t: &[[f64; 2]; 3]) -> f64 {
        cross(t[0], t[1], t[2]).abs() / 2.0
    }
}

impl Integrand for Delaunay {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        let p = [x[0], x[1]];
        let cell = |v: f64| ((v * self.grid as f64) as usize).min(self.grid - 1);
        let candidates = &self.cells[cell(x[0]) * self.grid + cell(x[1])];
        let mut nearest = (f64::NEG_INFINITY, 0.0);
        for &i in candidates {
            let t = &self.triangles[i as usize];
            let area2 = cross(t[0], t[1], t[2]);
            // barycentric coordinates, orientation-free
            let l = [cross(t[1], t[2], p) / area2, cross(t[2], t[0], p) / area2, cross(t[0], t[1], p) / area2];
            let w = &self.weights[i as usize];
            let value = l[0] * w[0] + l[1] * w[1] + l[2] * w[2];
            let margin = l.iter().copied().fold(f64::INFINITY, f64::min);
            if margin >= 0.0 {
                return value;
            }
            // rounding on an edge: keep the triangle the point is least outside of
            if margin > nearest.0 {
                nearest = (margin, value);
            }
        }
        nearest.1
    }
    fn exact(&self) -> f64 {
        self.triangles.iter().zip(&self.weights).map(|(t, w)| Self::area(t) * (w[0] + w[1] + w[2]) / 3.0).sum()
    }
}
