//! Lloyd relaxation (Lloyd 1982): uniform random points, each iteration moving every point
//! to the centroid of its Voronoi cell, towards a centroidal Voronoi tessellation (Du,
//! Faber & Gunzburger 1999). 2D. On the torus the cells are those of the periodic set; in
//! the square they are clipped by its sides.
//!
//! Two ways to find the cells ([`Cells`]), the same cells to rounding:
//! - `delaunay` (the default): spade's Delaunay triangulation of the points and their copies
//!   within a margin of the square: translated by +-1 on the torus, reflected across the
//!   sides in the square (the bisector of a point and its mirror image is the side, so the
//!   cells are clipped exactly). A triangle at a point is kept only when its circumcircle
//!   lies within the copied band (no point outside it can fall inside); otherwise the margin
//!   doubles and the iteration starts again, so the cells are exact for any set. The
//!   triangulation is built on one thread.
//! - `clipped`: each cell on its own, in parallel: the square around the point (the torus's
//!   period, or the unit square) cut by the bisectors of the neighbours a grid gathers
//!   around it, each neighbour nearer than twice the cell's farthest corner so far (no
//!   point beyond can cut it: the security radius of Voronoi cells by clipping, as in Lévy
//!   and Bonneel 2012). The cell is certified when every point that near lies among those
//!   gathered; otherwise a wider ring is gathered, and a set with a cell that reaches a
//!   quarter of the torus (or that eight rings cannot certify) falls back to the
//!   triangulation.

use std::ops::RangeInclusive;

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

use super::poisson::edge_is_torus;
use crate::construct::counts::ANY;
use crate::sampler::registry::{EDGE, SamplerEntry};
use crate::sampler::{Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::About;
use crate::sampler::random::Random;
use crate::seed::{Seed, wrap01};
use crate::spatial::{Grid, torus_gap};
use crate::spec::{Default, Kind, ParamSpec};
use rayon::prelude::*;

/// Lloyd relaxation of uniform random points.
#[derive(Debug, Clone, Copy)]
pub struct Lloyd {
    iterations: usize,
    torus: bool,
    cells: Cells,
}

/// How [`centroids`] finds the Voronoi cells (the module's notes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Cells {
    /// One Delaunay triangulation of the points and their copies (one thread).
    Delaunay,
    /// Each cell by clipping a square with its neighbours' bisectors (in parallel).
    Clipped,
}

/// A triangulated point: a site (index < n) or a copy of one.
#[derive(Debug, Clone, Copy)]
struct Site {
    position: Point2<f64>,
    index: u32,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The centroids of the Voronoi cells of the 2D `points` (interleaved x, y), on the torus
/// or clipped by the unit square, the cells found as `cells` says.
///
/// # Errors
/// Coincident points (a cell would be empty) or a triangulation failure.
pub fn centroids(points: &[f64], torus: bool, cells: Cells) -> Result<Vec<f64>> {
    if cells == Cells::Clipped
        && let Some(c) = clipped_centroids(points, torus)?
    {
        return Ok(c);
    }
    let n = points.len() / 2;
    let mut margin = (4.0 / (n as f64).sqrt()).min(0.5);
    loop {
        if let Some(c) = try_centroids(points, torus, margin)? {
            return Ok(c);
        }
        if margin >= 2.0 {
            return Err(infeasible(format!("the Voronoi cells of {n} points did not close within a margin of 2")));
        }
        margin *= 2.0;
    }
}

/// A relaxation that cannot go on (Voronoi cells that do not close or do not form).
fn infeasible(reason: String) -> Error {
    Error::Infeasible { what: "lloyd".into(), reason }
}

/// Two sites at one place: the Voronoi cell of one is empty.
fn coincident() -> Error {
    infeasible("coincident points: a Voronoi cell is empty".into())
}

/// The centroids with copies within `margin` of the square, or None if a cell's
/// triangles reach beyond them.
fn try_centroids(points: &[f64], torus: bool, margin: f64) -> Result<Option<Vec<f64>>> {
    let n = points.len() / 2;
    let mut sites: Vec<Site> =
        points.chunks_exact(2).enumerate().map(|(i, p)| Site { position: Point2::new(p[0], p[1]), index: i as u32 }).collect();
    // copies: every tile offset (ox, oy), up to 2 tiles away when the margin is that wide
    let reach = margin.ceil() as i32;
    for ox in -reach..=reach {
        for oy in -reach..=reach {
            if (ox, oy) == (0, 0) {
                continue;
            }
            // translated, or reflected: odd tiles are mirror images (-x, 2 - x, ...)
            let copy = |x: f64, o: i32| if torus || o % 2 == 0 { o as f64 + x } else { o as f64 + 1.0 - x };
            for (i, p) in points.chunks_exact(2).enumerate() {
                let (x, y) = (copy(p[0], ox), copy(p[1], oy));
                if (-margin..=1.0 + margin).contains(&x) && (-margin..=1.0 + margin).contains(&y) {
                    sites.push(Site { position: Point2::new(x, y), index: (n + i) as u32 });
                }
            }
        }
    }
    let tri: DelaunayTriangulation<Site> =
        DelaunayTriangulation::bulk_load(sites).map_err(|e| infeasible(format!("Voronoi cells: {e}")))?;
    let mut out = vec![f64::NAN; 2 * n];
    for v in tri.vertices() {
        let site = *v.data();
        if site.index as usize >= n {
            continue;
        }
        let p = site.position;
        // the cell's corners (circumcentres of the triangles around p), relative to p
        let mut corners = Vec::new();
        for e in v.out_edges() {
            let Some(face) = e.face().as_inner() else { return Ok(None) };
            let c = face.circumcenter();
            let r = ((c.x - p.x).powi(2) + (c.y - p.y).powi(2)).sqrt();
            let inside = |t: f64| t - r >= -margin && t + r <= 1.0 + margin;
            if !(inside(c.x) && inside(c.y)) {
                return Ok(None);
            }
            corners.push((c.x - p.x, c.y - p.y));
        }
        let i = site.index as usize;
        (out[2 * i], out[2 * i + 1]) = moved([p.x, p.y], &corners, torus);
    }
    if out.iter().any(|x| x.is_nan()) {
        return Err(coincident());
    }
    Ok(Some(out))
}

/// The point p moved to the centroid of its cell, the polygon `corners` (relative to p, in
/// their order around it; shoelace formula), wrapped onto the torus or kept in the square.
fn moved(p: [f64; 2], corners: &[(f64, f64)], torus: bool) -> (f64, f64) {
    let (mut area, mut cx, mut cy) = (0.0, 0.0, 0.0);
    for (k, &(x0, y0)) in corners.iter().enumerate() {
        let (x1, y1) = corners[(k + 1) % corners.len()];
        let cross = x0 * y1 - x1 * y0;
        area += cross;
        cx += (x0 + x1) * cross;
        cy += (y0 + y1) * cross;
    }
    let (x, y) = (p[0] + cx / (3.0 * area), p[1] + cy / (3.0 * area));
    if torus { (wrap01(x), wrap01(y)) } else { (clamp01(x), clamp01(y)) }
}

/// The centroids with each cell clipped on its own, in parallel ([`Cells::Clipped`]); None
/// when a cell cannot be certified: its farthest corner a quarter of the torus away (the
/// nearest copy of each neighbour no longer suffices), or past the widest ring; the
/// triangulation then takes over.
fn clipped_centroids(points: &[f64], torus: bool) -> Result<Option<Vec<f64>>> {
    let n = points.len() / 2;
    // cells of the grid hold about three points: one ring around a point's cell holds the
    // neighbours that cut a cell of a well-spread set
    let grid = Grid::covering(points, 2, (3.0 / n as f64).sqrt());
    let side = 1.0 / grid.cells() as f64;
    let moved: Vec<Option<(f64, f64)>> = (0..n)
        .into_par_iter()
        .map_init(
            || (Vec::new(), Vec::new(), Vec::new()),
            |(near, corners, next), q| {
                let p = grid.point(q);
                let offset = |o: &[f64]| {
                    if torus { (torus_gap(o[0], p[0]), torus_gap(o[1], p[1])) } else { (o[0] - p[0], o[1] - p[1]) }
                };
                for ring in [1, 2, 4, 8] {
                    // every point within `reach` of p lies in the cells gathered
                    let reach = (ring as f64 * side).min(if torus { 0.5 } else { f64::INFINITY });
                    near.clear();
                    grid.near(q, ring, torus, |cells| {
                        for r in cells.filter(|&r| r != q) {
                            let (dx, dy) = offset(grid.point(r));
                            near.push((dx * dx + dy * dy, dx, dy));
                        }
                    });
                    corners.clear();
                    let (lo, hi) = if torus { ([-0.5; 2], [0.5; 2]) } else { ([-p[0], -p[1]], [1.0 - p[0], 1.0 - p[1]]) };
                    corners.extend([(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]);
                    let farthest = |c: &[(f64, f64)]| c.iter().map(|&(x, y)| x * x + y * y).fold(0.0, f64::max);
                    let mut far = farthest(corners);
                    for &(d2, dx, dy) in near.iter() {
                        if d2 == 0.0 {
                            return Err(coincident());
                        }
                        if d2 >= 4.0 * far {
                            continue;
                        }
                        clip(corners, next, (dx, dy, 0.5 * d2));
                        far = farthest(corners);
                    }
                    if 4.0 * far < reach * reach {
                        return Ok(Some(moved([p[0], p[1]], corners, torus)));
                    }
                    if torus && reach >= 0.5 {
                        break;
                    }
                }
                Ok(None)
            },
        )
        .collect::<Result<_>>()?;
    let mut out = vec![0.0; 2 * n];
    for (q, m) in moved.into_iter().enumerate() {
        let Some((x, y)) = m else { return Ok(None) };
        let i = grid.ids[q] as usize;
        (out[2 * i], out[2 * i + 1]) = (x, y);
    }
    Ok(Some(out))
}

/// The convex polygon `corners` cut to the half-plane x dx + y dy <= h (Sutherland and
/// Hodgman), through the buffer `next`.
fn clip(corners: &mut Vec<(f64, f64)>, next: &mut Vec<(f64, f64)>, (dx, dy, h): (f64, f64, f64)) {
    next.clear();
    let side = |&(x, y): &(f64, f64)| x * dx + y * dy - h;
    for (k, a) in corners.iter().enumerate() {
        let b = &corners[(k + 1) % corners.len()];
        let (fa, fb) = (side(a), side(b));
        if fa <= 0.0 {
            next.push(*a);
        }
        if (fa <= 0.0) != (fb <= 0.0) {
            let t = fa / (fa - fb);
            next.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
        }
    }
    std::mem::swap(corners, next);
}

/// x in [0, 1), a centroid on the square's far side kept inside.
fn clamp01(x: f64) -> f64 {
    x.clamp(0.0, crate::numeric::BELOW_ONE)
}

impl Construction for Lloyd {
    fn dims(&self) -> RangeInclusive<usize> {
        2..=2
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let me = *self;
        let shape = shape.clone();
        Ok(crate::sampler::from_fill_reporting(self.units(), move |seed, out, progress| {
            me.fill_reporting(shape.n(), shape.dims(), seed, out, progress)
        }))
    }
}

impl Lloyd {
    fn units(&self) -> u64 {
        self.iterations as u64
    }
    fn fill_reporting(&self, _n: usize, _dims: usize, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        Random::draw(seed, out);
        for _ in 0..self.iterations {
            let next = centroids(out, self.torus, self.cells)?;
            out.copy_from_slice(&next);
            progress.advance(1)?;
        }
        Ok(())
    }
}

/// The samplers this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new("lloyd", "Lloyd relaxation of random points towards a centroidal Voronoi tessellation")
        .aliases(&["cvt", "lloyd-relaxation"])
        .params(&[
            ParamSpec {
                name: "iterations",
                kind: Kind::Int { min: 0, max: 100_000 },
                default: Default::Int(50),
                doc: "Lloyd steps",
            },
            EDGE,
            ParamSpec {
                name: "cells",
                kind: Kind::Choice(&["delaunay", "clipped"]),
                default: Default::Word("delaunay"),
                doc: "Voronoi cells from one Delaunay triangulation (one thread) or each clipped on its own (in parallel; the same cells to rounding, so other bits)",
            },
        ])
        .cite(&["lloyd1982", "du1999"]),
    counts: ANY,
    randomized: true,
    dims: "2",
    build: |p| {
        Ok(Box::new(Lloyd {
            iterations: p.int("iterations") as usize,
            torus: edge_is_torus(p.word("edge")),
            cells: if p.word("cells") == "clipped" { Cells::Clipped } else { Cells::Delaunay },
        }))
    },
}];
