//! A scene: camera, diffuse materials, shapes in a BVH, infinite planes, area lights.

use glam::DVec3;

use crate::bvh::Bvh;
use crate::camera::Camera;
use crate::filter::Footprint;
use crate::geometry::{Plane, Ray};
use crate::light::Light;
use crate::packet::{Packet, WIDTH, packets};

/// A surface colour that may vary with position.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
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
    #[inline(always)]
    pub fn at(&self, p: DVec3) -> DVec3 {
        match *self {
            Texture::Constant(c) => c,
            Texture::Checker { even, odd, size, angle } => checker(even, odd, size, angle, p),
        }
    }
}

/// A checkerboard's colour at `p` ([`Texture::Checker`]): out of line, so that its sine and
/// cosine calls do not make the constant case (every hit of most scenes) save registers
/// around them.
#[cold]
#[inline(never)]
fn checker(even: DVec3, odd: DVec3, size: f64, angle: f64, p: DVec3) -> DVec3 {
    let (s, c) = angle.to_radians().sin_cos();
    let (x, z) = (c * p.x - s * p.z, s * p.x + c * p.z);
    let parity = ((x / size).floor() + (z / size).floor()).rem_euclid(2.0);
    if parity < 0.5 { even } else { odd }
}

/// How a surface reflects.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
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
    /// A rough mirror (Mitsuba 3's `roughconductor`, reflecting every wavelength fully):
    /// Walter et al. 2007's microfacet model ([`crate::bsdf`]).
    Rough {
        /// Roughness: the microfacets' slope spread.
        alpha: f64,
        /// Their distribution.
        distribution: Distribution,
    },
}

/// A microfacet distribution (Walter et al. 2007).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Distribution {
    /// Beckmann's.
    Beckmann,
    /// GGX.
    Ggx,
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
    /// Whether it reflects on the front of its surface only (the side its shape's normal
    /// points to), black from behind, as Mitsuba's BSDFs not wrapped in `twosided`; else on
    /// both sides.
    pub front_only: bool,
}

impl Material {
    /// A Lambertian material of constant reflectance that emits nothing and reflects on
    /// both sides.
    pub fn diffuse(albedo: DVec3) -> Material {
        Material {
            albedo: Texture::Constant(albedo),
            emission: Texture::Constant(DVec3::ZERO),
            finish: Finish::Diffuse,
            front_only: false,
        }
    }
}

/// A surface point seen by a camera ray.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Seen {
    /// Nothing: black background.
    Nothing,
    /// An emitter, with the radiance it sends along the ray.
    Light(DVec3),
    /// A surface (a light's too, where the light is one: [`crate::light::Light::surface`]).
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
        /// The light whose surface this is: `emission` is then its radiance toward the ray
        /// (zero from behind), which lights the scene, not only the camera.
        light: Option<u32>,
    },
}

/// A ray's nearest hit.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    /// The ray parameter (infinity for none).
    pub t: f64,
    /// What it hit: a BVH object's index, then the planes', then the lights'; u32::MAX for
    /// nothing.
    pub what: u32,
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
    /// The most segments of a path the scene asks for (a Mitsuba scene's `path` integrator's
    /// `max_depth`), used in path mode unless the render sets its own.
    pub max_depth: Option<usize>,
    /// Where the camera rays go in a pixel unless the render says (a Mitsuba scene's film's
    /// reconstruction filter).
    pub footprint: Option<Footprint>,
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

    /// Each ray's nearest hit, in `hits` (resized to fit), traced by packets
    /// (four rays at a time); [`Scene::seen`] tells what was hit.
    pub fn trace(&self, rays: &[Ray], hits: &mut Vec<Hit>) {
        hits.resize(rays.len(), Hit { t: f64::INFINITY, what: u32::MAX });
        packets(
            rays,
            #[inline(always)]
            |start, p| {
                let lanes = self.trace_packet(p);
                for (i, h) in hits[start..start + p.len()].iter_mut().enumerate() {
                    *h = lanes[i];
                }
            },
        );
    }

    /// The nearest hit of each ray of a packet: the BVH, the planes, then the lights (to be
    /// compiled wide, [`samplab::simd::wide`]).
    #[inline(always)]
    pub(crate) fn trace_packet(&self, p: &Packet) -> [Hit; WIDTH] {
        let planes_from = self.bvh.objects().len();
        let lights_from = (planes_from + self.planes.len()) as u32;
        let (mut t, mut hit) = ([f64::INFINITY; WIDTH], [u32::MAX; WIDTH]);
        self.bvh.trace::<false>(p, 0.0, &mut t, &mut hit);
        for (k, (plane, _)) in self.planes.iter().enumerate() {
            let index = (planes_from + k) as u32;
            p.each::<false>(index, &mut t, &mut hit, |o, d, _, t_max| plane.hit(o, d, 0.0, t_max));
        }
        for (k, light) in self.lights.iter().enumerate() {
            let index = lights_from + k as u32;
            p.each::<false>(index, &mut t, &mut hit, |o, d, _, t_max| light.hit(o, d, 0.0, t_max));
        }
        std::array::from_fn(|i| Hit { t: t[i], what: hit[i] })
    }

    /// What `ray` sees at its nearest hit ([`Scene::trace`]).
    #[inline(always)]
    pub fn seen(&self, ray: &Ray, hit: Hit) -> Seen {
        let position = ray.at(hit.t);
        let Some(material) = self.material_of(hit.what) else {
            let Some(i) = self.light_of(hit.what) else { return Seen::Nothing };
            let light = &self.lights[i];
            let (Some(material), Some(front)) = (light.surface, light.normal()) else {
                return Seen::Light(light.radiance_at(position));
            };
            let behind = front.dot(ray.dir) > 0.0;
            let m = &self.materials[material as usize];
            let black = behind && m.front_only;
            return Seen::Surface {
                position,
                normal: if behind { -front } else { front },
                albedo: if black { DVec3::ZERO } else { m.albedo.at(position) },
                emission: if behind { DVec3::ZERO } else { light.radiance_at(position) },
                finish: m.finish,
                light: Some(i as u32),
            };
        };
        let (normal, behind) = self.facing_normal(hit.what, position, ray);
        let m = &self.materials[material as usize];
        let black = behind && m.front_only;
        Seen::Surface {
            position,
            normal,
            albedo: if black { DVec3::ZERO } else { m.albedo.at(position) },
            emission: m.emission.at(position),
            finish: m.finish,
            light: None,
        }
    }

    /// The material of hit index `what` ([`Hit::what`]) when it names a BVH object or a
    /// plane; None for a light or nothing.
    #[inline(always)]
    pub(crate) fn material_of(&self, what: u32) -> Option<u32> {
        let (objects, i) = (self.bvh.objects(), what as usize);
        if i < objects.len() { Some(objects[i].material) } else { self.planes.get(i - objects.len()).map(|p| p.1) }
    }

    /// The unit normal at `position` of the BVH object or plane `what` ([`Hit::what`]),
    /// facing `ray`'s origin, and whether the ray met the surface from behind.
    #[inline(always)]
    pub(crate) fn facing_normal(&self, what: u32, position: DVec3, ray: &Ray) -> (DVec3, bool) {
        let (objects, i) = (self.bvh.objects().len(), what as usize);
        let normal =
            if i < objects { self.bvh.normal(i, position, ray.time) } else { self.planes[i - objects].0.normal };
        if normal.dot(ray.dir) > 0.0 { (-normal, true) } else { (normal, false) }
    }

    /// The light of hit index `what` ([`Hit::what`]), if it names one.
    #[inline(always)]
    pub(crate) fn light_of(&self, what: u32) -> Option<usize> {
        let shapes = self.bvh.objects().len() + self.planes.len();
        (what as usize).checked_sub(shapes).filter(|&i| i < self.lights.len())
    }

    /// Per hit index of a BVH object or plane: the albedo of a plain surface (diffuse, one
    /// colour, emitting nothing), whose hits need no texture or emission lookup; None for
    /// any other.
    pub(crate) fn plain_albedos(&self) -> Vec<Option<DVec3>> {
        let materials = self.bvh.objects().iter().map(|o| o.material).chain(self.planes.iter().map(|p| p.1));
        materials
            .map(|m| match self.materials[m as usize] {
                Material {
                    albedo: Texture::Constant(albedo),
                    emission: Texture::Constant(DVec3::ZERO),
                    finish: Finish::Diffuse,
                    front_only: false,
                } => Some(albedo),
                _ => None,
            })
            .collect()
    }

    /// Whether any material is glossy or rough (and so needs a gloss sample per estimate).
    pub fn glossy(&self) -> bool {
        self.materials.iter().any(|m| matches!(m.finish, Finish::Glossy { .. } | Finish::Rough { .. }))
    }

    /// The origin of a ray leaving surface point `x` on the side of `n`, off the surface.
    #[inline(always)]
    pub fn offset(x: DVec3, n: DVec3) -> DVec3 {
        x + n * (RAY_EPSILON * (1.0 + x.abs().max_element()) * 100.0)
    }

    /// The shadow ray to light point `y` from `origin`, a surface point moved off the
    /// surface by [`Scene::offset`] (once for all its light samples): it reaches `y` at t = 1.
    #[inline(always)]
    pub fn shadow_ray(origin: DVec3, y: DVec3, time: f64) -> Ray {
        Ray { origin, dir: y - origin, time }
    }

    /// Whether each shadow ray ([`Scene::shadow_ray`]) of a packet is blocked before its
    /// light point (by a shape, a plane or a light that is a surface); a lane not `live` is
    /// not traced and reads blocked (to be compiled wide, [`samplab::simd::wide`]).
    #[inline(always)]
    pub(crate) fn occluded(&self, p: &Packet, live: &[bool; WIDTH]) -> [bool; WIDTH] {
        let mut t = live.map(|l| if l { 1.0 - RAY_EPSILON } else { f64::NEG_INFINITY });
        let mut hit = [0; WIDTH];
        for (plane, _) in &self.planes {
            p.each::<true>(0, &mut t, &mut hit, |o, d, _, t_max| plane.hit(o, d, RAY_EPSILON, t_max));
        }
        for light in self.lights.iter().filter(|l| l.surface.is_some()) {
            p.each::<true>(0, &mut t, &mut hit, |o, d, _, t_max| light.hit(o, d, RAY_EPSILON, t_max));
        }
        self.bvh.trace::<true>(p, RAY_EPSILON, &mut t, &mut hit);
        t.map(|x| x == f64::NEG_INFINITY)
    }
}
