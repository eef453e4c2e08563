//! Rays, bounding boxes and the shapes the testbed traces: spheres (optionally moving, for
//! motion blur), parallelograms, disks, triangles, and infinite planes.

use glam::DVec3;

/// A ray `origin + t * dir` at a shutter `time` in [0, 1).
#[derive(Debug, Clone, Copy)]
pub struct Ray {
    /// Where it starts.
    pub origin: DVec3,
    /// Its direction (not necessarily unit length; shadow rays reach the light at t = 1).
    pub dir: DVec3,
    /// Shutter time in [0, 1), for moving shapes.
    pub time: f64,
}

impl Ray {
    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box (the identity of `union`).
    pub const EMPTY: Aabb = Aabb { min: DVec3::INFINITY, max: DVec3::NEG_INFINITY };

    /// The smallest box holding both.
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// The smallest box holding `self` and `p`.
    pub fn grow(self, p: DVec3) -> Aabb {
        Aabb { min: self.min.min(p), max: self.max.max(p) }
    }

    /// Half the surface area (the SAH cost only needs ratios).
    pub fn half_area(&self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// The centre.
    pub fn centre(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// Slab test: the entry distance if the ray meets the box within (0, t_max).
    #[inline]
    pub fn hit(&self, origin: DVec3, inv_dir: DVec3, t_max: f64) -> Option<f64> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1).max_element().max(0.0);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some(near)
    }
}

/// A traceable shape.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Shape {
    /// A sphere whose centre moves linearly: `centre + time * velocity`.
    Sphere {
        /// Centre at time 0.
        centre: DVec3,
        /// Radius.
        radius: f64,
        /// Displacement over the whole shutter interval.
        velocity: DVec3,
    },
    /// The parallelogram `corner + s u + t v`, s, t in [0, 1]; its normal is u x v.
    Parallelogram {
        /// One corner.
        corner: DVec3,
        /// First edge.
        u: DVec3,
        /// Second edge.
        v: DVec3,
    },
    /// A flat disk.
    Disk {
        /// Centre.
        centre: DVec3,
        /// Unit normal.
        normal: DVec3,
        /// Radius.
        radius: f64,
    },
    /// A triangle `p + a e1 + b e2`, a, b >= 0, a + b <= 1.
    Triangle {
        /// First vertex.
        p: DVec3,
        /// Second vertex minus the first.
        e1: DVec3,
        /// Third vertex minus the first.
        e2: DVec3,
    },
}

impl Shape {
    /// The box holding the shape over the whole shutter interval.
    pub fn bounds(&self) -> Aabb {
        match *self {
            Shape::Sphere { centre, radius, velocity } => {
                let r = DVec3::splat(radius);
                let end = centre + velocity;
                Aabb { min: centre.min(end) - r, max: centre.max(end) + r }
            }
            Shape::Parallelogram { corner, u, v } => {
                Aabb::EMPTY.grow(corner).grow(corner + u).grow(corner + v).grow(corner + u + v)
            }
            Shape::Disk { centre, normal, radius } => {
                // the extent of a circle along axis i is radius * sqrt(1 - n_i^2)
                let e = radius * (DVec3::ONE - normal * normal).max(DVec3::ZERO).map(f64::sqrt);
                Aabb { min: centre - e, max: centre + e }
            }
            Shape::Triangle { p, e1, e2 } => Aabb::EMPTY.grow(p).grow(p + e1).grow(p + e2),
        }
    }

    /// The ray parameter of the nearest intersection in (t_min, t_max).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let t = self.hit(ray.origin, ray.dir, ray.time, t_min, t_max);
        (t < t_max).then_some(t)
    }

    /// The nearest intersection in (t_min, t_max) of the ray `o + t d` at shutter `time`,
    /// or infinity.
    #[inline(always)]
    pub(crate) fn hit(&self, o: DVec3, d: DVec3, time: f64, t_min: f64, t_max: f64) -> f64 {
        match *self {
            Shape::Sphere { centre, radius, velocity } => {
                sphere_hit(centre, radius, velocity, o, d, time, t_min, t_max)
            }
            Shape::Parallelogram { corner, u, v } => edge_hit(corner, u, v, true, o, d, t_min, t_max),
            Shape::Disk { centre, normal, radius } => disk_hit(centre, normal, radius, o, d, t_min, t_max),
            Shape::Triangle { p, e1, e2 } => edge_hit(p, e1, e2, false, o, d, t_min, t_max),
        }
    }
}

/// A shape's unit geometric normal (not flipped toward any ray), prepared once so that a
/// hit costs no branch on the shape's kind: a sphere's points away from its centre at the
/// hit's time, a flat shape's is stored.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Normal {
    centre: DVec3,
    velocity: DVec3,
    radius: f64,
    flat: DVec3,
    sphere: bool,
}

impl Normal {
    /// The normal of `shape`.
    pub(crate) fn of(shape: &Shape) -> Normal {
        let flat =
            |n: DVec3| Normal { centre: DVec3::ZERO, velocity: DVec3::ZERO, radius: 1.0, flat: n, sphere: false };
        match *shape {
            Shape::Sphere { centre, radius, velocity } => {
                Normal { centre, velocity, radius, flat: DVec3::ZERO, sphere: true }
            }
            Shape::Parallelogram { u: e1, v: e2, .. } | Shape::Triangle { e1, e2, .. } => {
                flat(e1.cross(e2).normalize())
            }
            Shape::Disk { normal, .. } => flat(normal),
        }
    }

    /// The normal at the surface point `p` at shutter `time`.
    #[inline(always)]
    pub(crate) fn at(&self, p: DVec3, time: f64) -> DVec3 {
        let radial = (p - (self.centre + time * self.velocity)) / self.radius;
        if self.sphere { radial } else { self.flat }
    }
}

// Each shape's intersection, written once and branch-free, so that a loop over the lanes
// of a packet (crate::packet) vectorizes: the nearest t in (t_min, t_max), or infinity.

/// A sphere whose centre moves by `velocity` over the shutter interval; the numerically
/// stable pair of roots.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn sphere_hit(c: DVec3, r: f64, v: DVec3, o: DVec3, d: DVec3, time: f64, t_min: f64, t_max: f64) -> f64 {
    let inside = |t: f64| t > t_min && t < t_max;
    let oc = o - (c + time * v);
    let a = d.length_squared();
    let half_b = oc.dot(d);
    let cterm = oc.length_squared() - r * r;
    let disc = half_b * half_b - a * cterm;
    let q = -(half_b + disc.max(0.0).sqrt().copysign(half_b));
    let (t0, t1) = (q / a, cterm / q);
    let (t0, t1) = if t0 > t1 { (t1, t0) } else { (t0, t1) };
    let t = if inside(t0) { t0 } else { t1 };
    if disc >= 0.0 && inside(t) { t } else { f64::INFINITY }
}

/// The triangle `p + a e1 + b e2` (a, b >= 0, a + b <= 1) or, with `parallelogram`, the
/// parallelogram (a, b in [0, 1]), by Moller & Trumbore 1997.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn edge_hit(
    p: DVec3,
    e1: DVec3,
    e2: DVec3,
    parallelogram: bool,
    o: DVec3,
    d: DVec3,
    t_min: f64,
    t_max: f64,
) -> f64 {
    let pv = d.cross(e2);
    let det = e1.dot(pv);
    // a ray parallel to the plane makes every coordinate NaN, which no test below accepts
    let inv = if det == 0.0 { f64::NAN } else { 1.0 / det };
    let tv = o - p;
    let qv = tv.cross(e1);
    let (t, a, b) = (e2.dot(qv) * inv, tv.dot(pv) * inv, d.dot(qv) * inv);
    let within =
        (0.0..=1.0).contains(&a) && if parallelogram { (0.0..=1.0).contains(&b) } else { !(b < 0.0 || a + b > 1.0) };
    if within && t > t_min && t < t_max { t } else { f64::INFINITY }
}

/// A flat disk.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn disk_hit(c: DVec3, n: DVec3, r: f64, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> f64 {
    let t = plane_t(o, d, c, n);
    let within = (o + t * d - c).length_squared() <= r * r;
    if within && t > t_min && t < t_max { t } else { f64::INFINITY }
}

/// The ray parameter where `o + t d` crosses the plane through `point` with normal `n`
/// (NaN or infinite when the ray is parallel to it).
#[inline(always)]
pub(crate) fn plane_t(o: DVec3, d: DVec3, point: DVec3, n: DVec3) -> f64 {
    (point - o).dot(n) / d.dot(n)
}

/// An infinite plane (the papers' ground planes and Shirley's checkerboard).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// A point on it.
    pub point: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl Plane {
    /// The ray parameter of the intersection, if in (t_min, t_max).
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let t = self.hit(ray.origin, ray.dir, t_min, t_max);
        (t < t_max).then_some(t)
    }

    /// The crossing of `o + t d` in (t_min, t_max), or infinity (branch-free).
    #[inline(always)]
    pub(crate) fn hit(&self, o: DVec3, d: DVec3, t_min: f64, t_max: f64) -> f64 {
        let t = plane_t(o, d, self.point, self.normal);
        if t > t_min && t < t_max { t } else { f64::INFINITY }
    }
}

/// An orthonormal pair perpendicular to the unit vector `n` (Duff et al. 2017).
pub fn basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), DVec3::new(b, sign + n.y * n.y * a, -n.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray { origin: DVec3::from(o), dir: DVec3::from(d), time: 0.0 }
    }

    #[test]
    fn every_shape_is_hit_where_its_definition_says() {
        let r = ray([0.2, 0.3, 5.0], [0.0, 0.0, -1.0]);
        let sphere = Shape::Sphere { centre: DVec3::ZERO, radius: 1.0, velocity: DVec3::ZERO };
        let t = sphere.intersect(&r, 0.0, f64::INFINITY).unwrap();
        assert!((t - (5.0 - (1.0f64 - 0.04 - 0.09).sqrt())).abs() < 1e-12);
        let quad = Shape::Parallelogram { corner: DVec3::ZERO, u: DVec3::X, v: DVec3::Y };
        assert!((quad.intersect(&r, 0.0, 10.0).unwrap() - 5.0).abs() < 1e-12);
        let outside = ray([1.2, 0.3, 5.0], [0.0, 0.0, -1.0]);
        assert!(quad.intersect(&outside, 0.0, 10.0).is_none());
        let disk = Shape::Disk { centre: DVec3::ZERO, normal: DVec3::Z, radius: 0.37 };
        assert!(disk.intersect(&r, 0.0, 10.0).is_some());
        let small = Shape::Disk { centre: DVec3::ZERO, normal: DVec3::Z, radius: 0.36 };
        assert!(small.intersect(&r, 0.0, 10.0).is_none());
        let tri = Shape::Triangle { p: DVec3::ZERO, e1: DVec3::X, e2: DVec3::Y };
        assert!(tri.intersect(&r, 0.0, 10.0).is_some());
        assert!(tri.intersect(&ray([0.6, 0.6, 5.0], [0.0, 0.0, -1.0]), 0.0, 10.0).is_none());
        // t range is exclusive: a blocker beyond t_max is no blocker
        assert!(quad.intersect(&r, 0.0, 4.9).is_none());
    }

    #[test]
    fn moving_sphere_is_where_the_time_puts_it() {
        let s = Shape::Sphere { centre: DVec3::ZERO, radius: 0.5, velocity: DVec3::new(2.0, 0.0, 0.0) };
        let mut r = ray([2.0, 0.0, 5.0], [0.0, 0.0, -1.0]);
        assert!(s.intersect(&r, 0.0, 10.0).is_none());
        r.time = 0.999;
        assert!(s.intersect(&r, 0.0, 10.0).is_some());
        let b = s.bounds();
        assert_eq!(b.min.x, -0.5);
        assert_eq!(b.max.x, 2.5);
    }

    #[test]
    fn bounds_hold_the_shape() {
        let n = DVec3::new(1.0, 2.0, 3.0).normalize();
        let d = Shape::Disk { centre: DVec3::ONE, normal: n, radius: 2.0 };
        let (a, b) = basis(n);
        let bb = d.bounds();
        for k in 0..64 {
            let phi = k as f64 * std::f64::consts::TAU / 64.0;
            let p = DVec3::ONE + 2.0 * (phi.cos() * a + phi.sin() * b);
            assert!(p.cmpge(bb.min - 1e-12).all() && p.cmple(bb.max + 1e-12).all());
        }
        assert!((a.dot(n)).abs() < 1e-15 && (b.dot(n)).abs() < 1e-15 && (a.dot(b)).abs() < 1e-15);
    }
}
