//! The path-traced mode ([`Mode::Path`]): each estimate a path of at most `max_depth`
//! segments from the camera (Kajiya 1986), with next-event estimation at every vertex that
//! is not a mirror and multiple importance sampling of the light and the BSDF by the power
//! heuristic (Veach & Guibas 1995, eq. 12), no Russian roulette: the same estimator as
//! Mitsuba 3's `path` integrator with `max_depth` and no roulette, so the converged images
//! agree (tests/path.rs).
//!
//! `max_depth` counts segments as Mitsuba does: 1 sees only what emits, 2 adds direct
//! lighting, each more one bounce. A surface's self-emission (a material's `emission`) is
//! seen from the camera only, as in the other modes; a light reflects by its material where
//! it is a surface ([`Light::surface`], a Mitsuba emitter shape), and nothing otherwise.
//!
//! Every dimension comes from the render's pixel sampler, keyed by (pixel, estimate,
//! dimension): 0-1 the film position, 2-3 the lens, 4 the shutter time, then per vertex k
//! (k = 0 the camera ray's hit) six from `FIRST_LIGHT_DIM + 6 k`: the light point (2), the
//! BSDF direction (2), the choice among the lights (1), one unused ([`dims`]).

use glam::DVec3;
use samplab::pixel::Pixels;

use crate::bsdf;
use crate::camera::Frame;
use crate::filter::Footprint;
use crate::geometry::Ray;
use crate::light::{DiskMap, Light, LightShape};
use crate::packet::{Packet, WIDTH};
use crate::render::{FIRST_LIGHT_DIM, Mode};
use crate::scene::{Finish, Hit, Scene, Seen};

/// Dimensions each path vertex takes.
pub const VERTEX_DIMS: u32 = 6;

/// Largest `max_depth` accepted.
pub const MAX_DEPTH: usize = 64;

/// Refuse a `max_depth` outside 1..=[`MAX_DEPTH`].
///
/// # Errors
/// The setting `max_depth`, out of range.
pub fn check_depth(max_depth: usize) -> samplab::Result<()> {
    if (1..=MAX_DEPTH).contains(&max_depth) {
        return Ok(());
    }
    let reason = format!("the most segments of a path must be in 1..={MAX_DEPTH}");
    Err(samplab::Error::Setting { name: "max_depth", value: max_depth.to_string(), reason })
}

/// The dimensions a path of at most `max_depth` segments draws: the camera's 8, then
/// [`VERTEX_DIMS`] for each of the `max_depth - 1` vertices that may scatter.
pub fn dims(max_depth: usize) -> usize {
    FIRST_LIGHT_DIM as usize + VERTEX_DIMS as usize * max_depth.saturating_sub(1)
}

/// A light prepared for next-event estimation.
pub(crate) struct Emitter {
    light: Light,
    normal: Option<DVec3>,
    /// Density per unit area of one light sample landing at a given point of this light:
    /// the chance of choosing it x the chance its disk map keeps a sample / its area.
    density: f64,
}

impl Emitter {
    /// Every light of the scene, with the disk map `map` where given.
    pub(crate) fn all(scene: &Scene, map: Option<DiskMap>) -> Vec<Emitter> {
        let share = 1.0 / scene.lights.len().max(1) as f64;
        scene
            .lights
            .iter()
            .map(|&l| {
                let light = Light { disk_map: map.unwrap_or(l.disk_map), ..l };
                let rejecting = light.disk_map == DiskMap::Reject && matches!(light.shape, LightShape::Disk { .. });
                let kept = if rejecting { std::f64::consts::FRAC_PI_4 } else { 1.0 };
                Emitter { light, normal: light.normal(), density: share * kept / light.area() }
            })
            .collect()
    }

    /// Solid-angle density of reaching a point of this light at `distance`, seen at cosine
    /// `cos` from its normal, by light sampling.
    fn pdf(&self, distance: f64, cos: f64) -> f64 {
        self.density * distance * distance / cos
    }
}

/// What every pixel of a path-traced render shares.
pub(crate) struct Context<'a> {
    pub scene: &'a Scene,
    pub frame: &'a Frame,
    pub pixels: &'a Pixels,
    pub emitters: &'a [Emitter],
    pub width: usize,
    pub height: usize,
    pub spp: usize,
    pub max_depth: usize,
    pub footprint: Footprint,
    /// The pixel sampler's frame.
    pub animation_frame: u32,
}

impl Context<'_> {
    /// The maximum depth of `mode` (a path mode).
    pub(crate) fn depth(mode: Mode) -> usize {
        match mode {
            Mode::Path { max_depth } => max_depth as usize,
            _ => 0,
        }
    }
}

/// A path being followed: its estimate, its throughput, and the solid-angle density of the
/// BSDF sample that made its ray (0 for a camera or mirror ray: no light sampling competed).
#[derive(Clone, Copy)]
struct State {
    estimate: u32,
    throughput: DVec3,
    pdf: f64,
}

/// A light sample waiting for its shadow ray: its estimate, the ray, what it adds if
/// unblocked, and whether it was taken at the camera ray's hit (for the visibility channel).
#[derive(Clone, Copy)]
struct Shadow {
    estimate: u32,
    ray: Ray,
    add: DVec3,
    first: bool,
}

/// Per-thread buffers.
#[derive(Default)]
pub(crate) struct Scratch {
    rays: Vec<Ray>,
    states: Vec<State>,
    hits: Vec<Hit>,
    next_rays: Vec<Ray>,
    next_states: Vec<State>,
    shadows: Vec<Shadow>,
    packet: Packet,
    radiance: Vec<DVec3>,
    visible: Vec<f64>,
}

/// The power heuristic's weight of a sample of density `a` against one of density `b`.
fn power(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 > 0.0 { a2 / (a2 + b2) } else { 0.0 }
}

/// A pixel's radiance, its visible fraction (estimates that see a light or whose first light
/// sample is unblocked) and its (path, shadow) rays: the estimates' paths followed wave by
/// wave, every wave's rays and shadow rays traced in packets.
#[inline(always)]
pub(crate) fn pixel(c: &Context, col: usize, row: usize, s: &mut Scratch) -> (DVec3, f64, (u64, u64)) {
    let (scene, at) = (c.scene, [col as u32, row as u32]);
    let sample = |e: u32, d: u32| c.pixels.sample(at, c.animation_frame, e, d);
    let moving = scene.moving();
    s.radiance.clear();
    s.radiance.resize(c.spp, DVec3::ZERO);
    s.visible.clear();
    s.visible.resize(c.spp, 0.0);
    s.rays.clear();
    s.states.clear();
    for e in 0..c.spp as u32 {
        let u = if c.footprint.spreads() { [sample(e, 0), sample(e, 1)] } else { [0.5; 2] };
        let film = c.footprint.offset(u, col, row, c.width, c.height);
        let lens = if scene.camera.aperture > 0.0 { [sample(e, 2), sample(e, 3)] } else { [0.5, 0.5] };
        let time = if moving { sample(e, 4) } else { 0.0 };
        let (x, y) = ((col as f64 + film[0]) / c.width as f64, (row as f64 + film[1]) / c.height as f64);
        s.rays.push(c.frame.ray(x, y, lens, time));
        s.states.push(State { estimate: e, throughput: DVec3::ONE, pdf: 0.0 });
    }
    let (mut traced, mut shadow_rays) = (0u64, 0u64);
    for depth in 0..c.max_depth {
        if s.rays.is_empty() {
            break;
        }
        traced += s.rays.len() as u64;
        scene.trace(&s.rays, &mut s.hits);
        s.next_rays.clear();
        s.next_states.clear();
        for k in 0..s.rays.len() {
            let (ray, hit, st) = (s.rays[k], s.hits[k], s.states[k]);
            if depth == 0 && c.frame.beyond_far(hit.t) {
                continue;
            }
            let e = st.estimate as usize;
            // what a light sends along the ray, weighted against the light sample that could
            // have found it (none after a camera or mirror ray)
            let emitted = |light: usize, le: DVec3| {
                let mut w = 1.0;
                if st.pdf > 0.0 {
                    let em = &c.emitters[light];
                    let distance = hit.t * ray.dir.length();
                    let cos = em.normal.map_or(1.0, |n| -n.dot(ray.dir.normalize()));
                    w = power(st.pdf, em.pdf(distance, cos));
                }
                st.throughput * le * w
            };
            match scene.seen(&ray, hit) {
                Seen::Nothing => {}
                Seen::Light(le) => {
                    s.radiance[e] += emitted(scene.light_of(hit.what).unwrap_or_default(), le);
                    if depth == 0 {
                        s.visible[e] = 1.0;
                    }
                }
                Seen::Surface { position, normal, albedo, emission, finish, light } => {
                    match light {
                        Some(l) if emission != DVec3::ZERO => {
                            s.radiance[e] += emitted(l as usize, emission);
                            if depth == 0 {
                                s.visible[e] = 1.0;
                            }
                        }
                        None if depth == 0 => s.radiance[e] += st.throughput * emission,
                        _ => {}
                    }
                    // a black light (or one met from behind) ends the path
                    if light.is_some() && albedo == DVec3::ZERO {
                        continue;
                    }
                    if depth + 1 >= c.max_depth {
                        continue;
                    }
                    let wi = -ray.dir.normalize();
                    let origin = Scene::offset(position, normal);
                    let first = FIRST_LIGHT_DIM + VERTEX_DIMS * depth as u32;
                    let throughput = st.throughput * albedo;
                    if finish == Finish::Mirror {
                        s.next_rays.push(Ray { origin, dir: ray.dir.reflect(normal), time: ray.time });
                        s.next_states.push(State { pdf: 0.0, throughput, ..st });
                        continue;
                    }
                    if !c.emitters.is_empty() {
                        let pick = sample(st.estimate, first + 4) * c.emitters.len() as f64;
                        let em = &c.emitters[(pick as usize).min(c.emitters.len() - 1)];
                        let u = [sample(st.estimate, first), sample(st.estimate, first + 1)];
                        if let Some(y) = em.light.sample(&u[..em.light.dims()]) {
                            let d = y.position - position;
                            let distance = d.length();
                            let wo = d / distance;
                            let cos_y = em.normal.map_or(1.0, |n| -n.dot(wo));
                            let (f, pdf) = bsdf::eval(finish, normal, wi, wo);
                            if cos_y > 0.0 && f > 0.0 {
                                let light_pdf = em.pdf(distance, cos_y);
                                let w = if em.normal.is_some() { power(light_pdf, pdf) } else { 1.0 };
                                let le = em.light.radiance * y.weight;
                                let add = throughput * le * (f * normal.dot(wo) * w / light_pdf);
                                let ray = Scene::shadow_ray(origin, y.position, ray.time);
                                s.shadows.push(Shadow { estimate: st.estimate, ray, add, first: depth == 0 });
                            }
                        }
                    }
                    let u = [sample(st.estimate, first + 2), sample(st.estimate, first + 3)];
                    if let Some(b) = bsdf::sample(finish, normal, wi, u) {
                        s.next_rays.push(Ray { origin, dir: b.dir, time: ray.time });
                        s.next_states.push(State { throughput: throughput * b.weight, pdf: b.pdf, ..st });
                    }
                }
            }
        }
        shadow_rays += trace_shadows(scene, s);
        std::mem::swap(&mut s.rays, &mut s.next_rays);
        std::mem::swap(&mut s.states, &mut s.next_states);
    }
    let radiance = s.radiance.iter().fold(DVec3::ZERO, |a, &r| a + r);
    let visible = s.visible.iter().sum::<f64>();
    let inv = 1.0 / c.spp as f64;
    (radiance * inv, visible * inv, (traced, shadow_rays))
}

/// Trace the waiting shadow rays in packets, adding each unblocked one to its estimate in
/// the order queued. Returns how many were traced.
#[inline(always)]
fn trace_shadows(scene: &Scene, s: &mut Scratch) -> u64 {
    let live = [true; WIDTH];
    for chunk in s.shadows.chunks(WIDTH) {
        for (j, sh) in chunk.iter().enumerate() {
            s.packet.set(j, &sh.ray);
        }
        s.packet.seal(chunk.len());
        let mut lanes = live;
        lanes[chunk.len()..].fill(false);
        let blocked = scene.occluded(&s.packet, &lanes);
        for (sh, _) in chunk.iter().zip(blocked).filter(|(_, b)| !b) {
            s.radiance[sh.estimate as usize] += sh.add;
            if sh.first {
                s.visible[sh.estimate as usize] = 1.0;
            }
        }
    }
    let n = s.shadows.len() as u64;
    s.shadows.clear();
    n
}
