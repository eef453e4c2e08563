//! A scene: camera, diffuse materials, shapes in a BVH, infinite planes, area lights.

use glam::DVec3;

use crate::bvh::Bvh;
use crate::camera::Camera;
use crate::geometry::{Plane, Ray};
use crate::light::Light;

/// A surface colour that may vary with position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Texture {
    /// One colour.
    Constant(DVec3),
    /// A checkerboard in the world x-z plane (Shirley 1991's "checker"; rotated by `angle`
    /// degrees about the y axis for "checker-45").
    Checker {
        /// Colour of the even squares.
        even: DVec3,
        /// Colour of the odd squares.
        odd: DVec3,
        /// Side of a square.
        size: f64,
        /// Rotation about y, degrees.
        angle: f64,
    },
}

impl Texture {
    /// The colour at `p`.
    #[inline]
    pub fn at(&self, p: DVec3) -> DVec3 {
        match *self {
            Texture::Constant(c) => c,
            Texture::Checker { even, odd, size, angle } => {
                let (s, c) = angle.to_radians().sin_cos();
                let (x, z) = (c * p.x - s * p.z, s * p.x + c * p.z);
                let parity = ((x / size).floor() + (z / size).floor()).rem_euclid(2.0);
                if parity < 0.5 { even } else { odd }
            }
        }
    }
}

/// How a surface reflects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Finish {
    /// Lambertian: reflected radiance = albedo / pi x irradiance.
    Diffuse,
    /// A perfect mirror reflecting `albedo` of the radiance from the mirror direction.
    Mirror,
    /// An imperfect mirror (Cook, Porter & Carpenter 1984's gloss): the reflected direction
    /// spread about the mirror direction by the normalized Phong lobe
    /// (n + 1) / (2 pi) cos^n, sampled with one 2D sample per estimate.
    Glossy {
        /// The Phong exponent n: larger is sharper.
        exponent: f64,
    },
}

/// A material: a finish with its reflectance, plus a self-emission that lights nothing
/// else (Shirley's unlit checkerboards, bright beads).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Reflectance (diffuse or specular, as the finish says).
    pub albedo: Texture,
    /// Radiance the surface emits toward the camera.
    pub emission: Texture,
    /// How it reflects.
    pub finish: Finish,
}

impl Material {
    /// A Lambertian material of constant reflectance that emits nothing.
    pub fn diffuse(albedo: DVec3) -> Material {
        Material {
            albedo: Texture::Constant(albedo),
            emission: Texture::Constant(DVec3::ZERO),
            finish: Finish::Diffuse,
        }
    }
}

/// A surface point seen by a camera ray.
#[derive(Debug, Clone, Copy)]
pub enum Seen {
    /// Nothing: black background.
    Nothing,
    /// An emitter, with the radiance it sends along the ray.
    Light(DVec3),
    /// A surface.
    Surface {
        /// Position.
        position: DVec3,
        /// Unit normal facing the ray's origin.
        normal: DVec3,
        /// Reflectance there.
        albedo: DVec3,
        /// Self-emitted radiance there.
        emission: DVec3,
        /// How it reflects.
        finish: Finish,
    },
}

/// Everything a render needs.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The camera.
    pub camera: Camera,
    /// Materials, indexed by objects and planes.
    pub materials: Vec<Material>,
    /// Bounded shapes.
    pub bvh: Bvh,
    /// Infinite planes and their materials.
    pub planes: Vec<(Plane, u32)>,
    /// Area lights.
    pub lights: Vec<Light>,
    /// Suggested image size.
    pub resolution: (usize, usize),
}

/// Relative offset of shadow-ray origins and ends, against self-intersection.
const RAY_EPSILON: f64 = 1e-9;

impl Scene {
    /// Whether any shape moves during the shutter interval.
    pub fn moving(&self) -> bool {
        self.bvh
            .objects()
            .iter()
            .any(|o| matches!(o.shape, crate::geometry::Shape::Sphere { velocity, .. } if velocity != DVec3::ZERO))
    }

    /// The number of bounded shapes.
    pub fn shapes(&self) -> usize {
        self.bvh.objects().len()
    }

    /// What a camera ray sees first.
    pub fn trace(&self, ray: &Ray) -> Seen {
        let mut t_max = f64::INFINITY;
        let mut hit: Option<(f64, DVec3, u32)> = None;
        if let Some((t, o)) = self.bvh.closest(ray, 0.0, t_max) {
            t_max = t;
            hit = Some((t, o.shape.normal(ray.at(t), ray.time), o.material));
        }
        for (plane, material) in &self.planes {
            if let Some(t) = plane.intersect(ray, 0.0, t_max) {
                t_max = t;
                hit = Some((t, plane.normal, *material));
            }
        }
        let mut light_hit = None;
        for light in &self.lights {
            if let Some((t, radiance)) = light.intersect(ray, t_max) {
                t_max = t;
                light_hit = Some(radiance);
            }
        }
        if let Some(radiance) = light_hit {
            return Seen::Light(radiance);
        }
        let Some((t, normal, material)) = hit else { return Seen::Nothing };
        let position = ray.at(t);
        let normal = if normal.dot(ray.dir) > 0.0 { -normal } else { normal };
        let m = &self.materials[material as usize];
        Seen::Surface {
            position,
            normal,
            albedo: m.albedo.at(position),
            emission: m.emission.at(position),
            finish: m.finish,
        }
    }

    /// Whether any material is glossy (and so needs a gloss sample per estimate).
    pub fn glossy(&self) -> bool {
        self.materials.iter().any(|m| matches!(m.finish, Finish::Glossy { .. }))
    }

    /// The origin of a ray leaving surface point `x` on the side of `n`, off the surface.
    #[inline]
    pub fn offset(x: DVec3, n: DVec3) -> DVec3 {
        x + n * (RAY_EPSILON * (1.0 + x.abs().max_element()) * 100.0)
    }

    /// Whether the segment from surface point `x` (normal `n`) to light point `y` is blocked.
    #[inline]
    pub fn occluded(&self, x: DVec3, n: DVec3, y: DVec3, time: f64) -> bool {
        let origin = Scene::offset(x, n);
        let ray = Ray { origin, dir: y - origin, time };
        let t_max = 1.0 - RAY_EPSILON;
        self.planes.iter().any(|(p, _)| p.intersect(&ray, RAY_EPSILON, t_max).is_some())
            || self.bvh.occluded(&ray, RAY_EPSILON, t_max)
    }
}
