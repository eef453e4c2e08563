//! Area lights: a segment (Ramamoorthi et al. 2012's linear light), a parallelogram (square
//! and rectangle lights), an elliptical disk (circular lights), each optionally with a
//! Gaussian emission falloff (Ramamoorthi et al. 2012, section 5.3), and a triangle (a face of
//! an emitting mesh, uniform).
//!
//! A light maps a point of the unit square (the unit interval for a segment) to a point on
//! the light, area-preserving, so the sampling pattern of a pixel is any samplab point set.

use std::f64::consts::{FRAC_PI_2, PI};

use glam::DVec3;
use samplab::warp::{PolarDisk, RejectDisk, Warp, concentric};

use crate::geometry::{Ray, plane_t};

/// The light's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum LightShape {
    /// A segment from `a` to `b`, emitting equally in all directions (per unit length).
    Segment {
        /// One end.
        a: DVec3,
        /// The other end.
        b: DVec3,
    },
    /// The parallelogram `corner + s u + t v`; it emits on the side of u x v.
    Parallelogram {
        /// One corner.
        corner: DVec3,
        /// First edge.
        u: DVec3,
        /// Second edge.
        v: DVec3,
    },
    /// The ellipse `centre + x u + y v`, x^2 + y^2 <= 1 (a disk when u, v are orthogonal
    /// and equally long); it emits on the side of u x v.
    Disk {
        /// Centre.
        centre: DVec3,
        /// First semi-axis.
        u: DVec3,
        /// Second semi-axis.
        v: DVec3,
    },
    /// The triangle `p + s e1 + t e2`, s, t >= 0, s + t <= 1; it emits on the side of
    /// e1 x e2. It has no falloff (a falloff set on it is not read).
    Triangle {
        /// One vertex.
        p: DVec3,
        /// Edge to the second vertex.
        e1: DVec3,
        /// Edge to the third vertex.
        e2: DVec3,
    },
}

/// The outline of a planar light in its plane's coordinates (s, t) along its two edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Outline {
    /// 0 <= s, t <= 1.
    Parallelogram,
    /// s^2 + t^2 <= 1.
    Disk,
    /// s, t >= 0, s + t <= 1.
    Triangle,
}

/// How the unit square is mapped to a disk light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum DiskMap {
    /// Shirley & Chiu's concentric map (area-preserving, low distortion).
    Concentric,
    /// Polar map r = sqrt(u), phi = 2 pi v (Shirley 1991 section 4).
    Polar,
    /// The bounding square, points outside the disk rejected (Ramamoorthi et al. 2012,
    /// section 7: "rejection sampling, with 25 original samples").
    Reject,
}

impl DiskMap {
    /// Every map, with its command-line name.
    pub const ALL: [(&'static str, DiskMap); 3] =
        [("concentric", DiskMap::Concentric), ("polar", DiskMap::Polar), ("reject", DiskMap::Reject)];
}

/// An area light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Geometry.
    pub shape: LightShape,
    /// Emitted radiance (per unit length for a segment) at the light's centre.
    pub radiance: DVec3,
    /// Gaussian falloff: emission times exp(-(x^2 + y^2) / (2 sigma^2)) in the light's local
    /// coordinates, which run over [-1, 1] from edge to edge (centre to rim for a disk).
    pub falloff: Option<f64>,
    /// Square-to-disk map for disk lights.
    pub disk_map: DiskMap,
    /// The material of the light's surface, when it is one (a Mitsuba emitter shape): it
    /// then blocks rays from both sides, reflects by that material (Mitsuba gives every
    /// emitter shape a BSDF) and emits on its front side only. None (the papers' lights):
    /// a light is seen from its emitting side only, reflects nothing and blocks nothing.
    pub surface: Option<u32>,
}

/// A point on a light.
#[derive(Debug, Clone, Copy)]
pub struct LightPoint {
    /// Position.
    pub position: DVec3,
    /// Falloff at the point (1 without falloff).
    pub weight: f64,
}

impl Light {
    /// Dimensions of its sampling domain: 1 for a segment, 2 otherwise.
    pub fn dims(&self) -> usize {
        if matches!(self.shape, LightShape::Segment { .. }) { 1 } else { 2 }
    }

    /// Area (length for a segment).
    pub fn area(&self) -> f64 {
        match self.shape {
            LightShape::Segment { a, b } => (b - a).length(),
            LightShape::Parallelogram { u, v, .. } => u.cross(v).length(),
            LightShape::Disk { u, v, .. } => PI * u.cross(v).length(),
            LightShape::Triangle { e1, e2, .. } => 0.5 * e1.cross(e2).length(),
        }
    }

    /// The unit normal on the emitting side (None for a segment, which emits all round).
    pub fn normal(&self) -> Option<DVec3> {
        match self.shape {
            LightShape::Segment { .. } => None,
            LightShape::Parallelogram { u, v, .. }
            | LightShape::Disk { u, v, .. }
            | LightShape::Triangle { e1: u, e2: v, .. } => Some(u.cross(v).normalize()),
        }
    }

    /// The centre of the light.
    pub fn centre(&self) -> DVec3 {
        match self.shape {
            LightShape::Segment { a, b } => 0.5 * (a + b),
            LightShape::Parallelogram { corner, u, v } => corner + 0.5 * (u + v),
            LightShape::Disk { centre, .. } => centre,
            LightShape::Triangle { p, e1, e2 } => p + (e1 + e2) / 3.0,
        }
    }

    /// The point for `u` in the unit square (interval), by the light's own disk map; None
    /// when a rejection map drops it.
    #[inline]
    pub fn sample(&self, u: &[f64]) -> Option<LightPoint> {
        self.sample_with(u, self.disk_map)
    }

    /// The point for `u` with the given disk map.
    #[inline(always)]
    pub fn sample_with(&self, u: &[f64], map: DiskMap) -> Option<LightPoint> {
        let (position, x, y) = match self.shape {
            LightShape::Segment { a, b } => (a + u[0] * (b - a), 2.0 * u[0] - 1.0, 0.0),
            LightShape::Parallelogram { corner, u: eu, v: ev } => {
                (corner + u[0] * eu + u[1] * ev, 2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0)
            }
            LightShape::Disk { centre, u: eu, v: ev } => {
                let (x, y) = match map {
                    DiskMap::Concentric => concentric(u[0], u[1]),
                    DiskMap::Polar => {
                        let mut d = [0.0; 2];
                        PolarDisk.forward(u, &mut d);
                        (d[0], d[1])
                    }
                    DiskMap::Reject => {
                        let mut d = [0.0; 2];
                        if !RejectDisk.forward(u, &mut d) {
                            return None;
                        }
                        (d[0], d[1])
                    }
                };
                (centre + x * eu + y * ev, x, y)
            }
            // area-preserving: the square root of the first coordinate sets how far from p
            // the point lies, the second where along that cross-section
            LightShape::Triangle { p, e1, e2 } => {
                let r = u[0].sqrt();
                (p + (r * (1.0 - u[1])) * e1 + (r * u[1]) * e2, 0.0, 0.0)
            }
        };
        Some(LightPoint { position, weight: self.falloff_at(x, y) })
    }

    fn falloff_at(&self, x: f64, y: f64) -> f64 {
        self.falloff.map_or(1.0, |s| (-(x * x + y * y) / (2.0 * s * s)).exp())
    }

    /// The falloff averaged over the light (exact), so that a uniform sample's weight divided
    /// by it is an unbiased estimate of 1.
    pub fn mean_weight(&self) -> f64 {
        let Some(s) = self.falloff else { return 1.0 };
        // mean of exp(-x^2 / 2 s^2) over [-1, 1]
        let line = s * FRAC_PI_2.sqrt() * libm::erf(1.0 / (s * std::f64::consts::SQRT_2));
        match self.shape {
            LightShape::Segment { .. } => line,
            LightShape::Parallelogram { .. } => line * line,
            // (1/pi) * integral over the unit disk of exp(-r^2 / 2 s^2)
            LightShape::Disk { .. } => 2.0 * s * s * (1.0 - (-1.0 / (2.0 * s * s)).exp()),
            LightShape::Triangle { .. } => 1.0,
        }
    }

    /// The geometric factor of light point `y` seen from `x` with unit normal `n`:
    /// cos(theta_x) cos(theta_y) / |y - x|^2 (no light cosine for a segment), zero when
    /// either side faces away.
    #[inline]
    pub fn geometry(&self, x: DVec3, n: DVec3, y: DVec3) -> f64 {
        geometry(self.normal(), x, n, y)
    }

    /// Where a camera ray meets the light (its emitting side), and the radiance seen there.
    pub fn intersect(&self, ray: &Ray, t_max: f64) -> Option<(f64, DVec3)> {
        let t = self.hit(ray.origin, ray.dir, 0.0, t_max);
        (t < t_max).then(|| (t, self.radiance_at(ray.at(t))))
    }

    /// The plane the light lies in: origin, edges and outline (None for a segment, which a
    /// ray never meets).
    #[inline(always)]
    fn plane(&self) -> Option<(DVec3, DVec3, DVec3, Outline)> {
        match self.shape {
            LightShape::Segment { .. } => None,
            LightShape::Parallelogram { corner, u, v } => Some((corner, u, v, Outline::Parallelogram)),
            LightShape::Disk { centre, u, v } => Some((centre, u, v, Outline::Disk)),
            LightShape::Triangle { p, e1, e2 } => Some((p, e1, e2, Outline::Triangle)),
        }
    }

    /// The light's local coordinates of point `p` in its plane (running over [-1, 1] edge
    /// to edge, centre to rim for a disk; 0 on a triangle, which has no falloff) and whether
    /// `p` is on the light.
    #[inline(always)]
    fn local(origin: DVec3, u: DVec3, v: DVec3, outline: Outline, p: DVec3) -> (f64, f64, bool) {
        let n = u.cross(v);
        let w = n / n.length_squared();
        let q = p - origin;
        let (s, r) = (w.dot(q.cross(v)), w.dot(u.cross(q)));
        match outline {
            Outline::Disk => (s, r, s * s + r * r <= 1.0),
            Outline::Parallelogram => {
                (2.0 * s - 1.0, 2.0 * r - 1.0, (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r))
            }
            Outline::Triangle => (0.0, 0.0, s >= 0.0 && r >= 0.0 && s + r <= 1.0),
        }
    }

    /// Where the ray `o + t d` meets the light in (t_min, t_max), or infinity (branch-free,
    /// for packets): its emitting side only, unless it is a surface ([`Light::surface`]),
    /// met from either side.
    #[inline(always)]
    pub(crate) fn hit(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> f64 {
        let Some((origin, u, v, outline)) = self.plane() else { return f64::INFINITY };
        let n = u.cross(v);
        let t = plane_t(o, d, origin, n);
        let (_, _, inside) = Light::local(origin, u, v, outline, o + t * d);
        let facing = self.surface.is_some() || d.dot(n) < 0.0;
        if facing && t > t_min && t < t_max && inside { t } else { f64::INFINITY }
    }

    /// The radiance emitted at point `p` of the light.
    pub(crate) fn radiance_at(&self, p: DVec3) -> DVec3 {
        let Some((origin, u, v, outline)) = self.plane() else { return self.radiance };
        let (x, y, _) = Light::local(origin, u, v, outline, p);
        self.radiance * self.falloff_at(x, y)
    }
}

/// A pattern's points on a light, in the pattern's order, with whether a rejection map kept
/// each.
#[derive(Debug, Clone, Default)]
pub(crate) struct LightPoints {
    points: Vec<LightPoint>,
    kept: Vec<bool>,
}

impl LightPoints {
    /// The points of `light` for `u` (`light.dims()` coordinates each), by its own disk map:
    /// [`Light::sample`] for each, with loops that vectorize (no branch, no optional
    /// result) for the concentric disk and the parallelogram without falloff.
    #[inline(always)]
    pub(crate) fn fill(&mut self, light: &Light, u: &[f64]) {
        let count = u.len() / light.dims();
        self.points.resize(count, LightPoint { position: DVec3::ZERO, weight: 1.0 });
        self.kept.clear();
        self.kept.resize(count, true);
        match (light.shape, light.disk_map, light.falloff) {
            (LightShape::Disk { centre, u: eu, v: ev }, DiskMap::Concentric, None) => {
                for (y, u) in self.points.iter_mut().zip(u.chunks_exact(2)) {
                    let (a, b) = concentric(u[0], u[1]);
                    *y = LightPoint { position: centre + a * eu + b * ev, weight: 1.0 };
                }
            }
            (LightShape::Parallelogram { corner, u: eu, v: ev }, _, None) => {
                for (y, u) in self.points.iter_mut().zip(u.chunks_exact(2)) {
                    *y = LightPoint { position: corner + u[0] * eu + u[1] * ev, weight: 1.0 };
                }
            }
            _ => {
                for ((y, kept), u) in self.points.iter_mut().zip(&mut self.kept).zip(u.chunks_exact(light.dims())) {
                    match light.sample(u) {
                        Some(p) => *y = p,
                        None => *kept = false,
                    }
                }
            }
        }
    }

    /// Point `i`, None where the map rejected it.
    #[inline(always)]
    pub(crate) fn get(&self, i: usize) -> Option<LightPoint> {
        self.kept[i].then_some(self.points[i])
    }
}

/// The geometric factor of [`Light::geometry`] for a light whose emitting side has the unit
/// normal `light_normal` (None: a segment, emitting all round).
#[inline(always)]
pub(crate) fn geometry(light_normal: Option<DVec3>, x: DVec3, n: DVec3, y: DVec3) -> f64 {
    let d = y - x;
    let d2 = d.length_squared();
    let cos_x = n.dot(d);
    // selects rather than early returns, so that loops of it vectorize
    let g = match light_normal {
        None => cos_x / (d2 * d2.sqrt()),
        Some(ny) => {
            let cos_y = -ny.dot(d);
            if cos_y <= 0.0 { 0.0 } else { cos_x * cos_y / (d2 * d2) }
        }
    };
    if cos_x <= 0.0 { 0.0 } else { g }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn disk(falloff: Option<f64>) -> Light {
        Light {
            shape: LightShape::Disk { centre: DVec3::ZERO, u: DVec3::X, v: DVec3::Y },
            radiance: DVec3::ONE,
            falloff,
            disk_map: DiskMap::Concentric,
            surface: None,
        }
    }

    #[test]
    fn mean_weight_is_the_average_falloff() {
        // midpoint rule on a fine grid of the square, through each light's own map
        let shapes = [
            disk(Some(0.4)),
            Light {
                shape: LightShape::Parallelogram { corner: DVec3::ZERO, u: DVec3::X, v: DVec3::Y },
                ..disk(Some(0.3))
            },
            Light { shape: LightShape::Segment { a: DVec3::ZERO, b: DVec3::X }, ..disk(Some(0.5)) },
        ];
        for light in shapes {
            let k = 400;
            let mut sum = 0.0;
            for i in 0..k {
                for j in 0..k {
                    let u = [(i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64];
                    sum += light.sample(&u).unwrap().weight;
                }
            }
            let mean = sum / (k * k) as f64;
            assert!((mean / light.mean_weight() - 1.0).abs() < 1e-4, "{light:?}: {mean}");
        }
    }

    #[test]
    fn camera_rays_see_the_emitting_side_only() {
        let light = disk(None);
        let up = Ray { origin: DVec3::new(0.3, 0.3, -2.0), dir: DVec3::new(0.0, 0.0, 1.0), time: 0.0 };
        assert!(light.intersect(&up, 10.0).is_none(), "u x v = +z: the light emits upward");
        let down = Ray { origin: DVec3::new(0.3, 0.3, 2.0), dir: DVec3::new(0.0, 0.0, -1.0), time: 0.0 };
        assert_eq!(light.intersect(&down, 10.0).map(|h| h.0), Some(2.0));
        let outside = Ray { origin: DVec3::new(0.8, 0.8, 2.0), ..down };
        assert!(light.intersect(&outside, 10.0).is_none());
    }
}
