//! Following each estimate from the camera: the camera ray, specular bounces, the ends of
//! paths handed to the lighting, and the obscurance estimator.

use super::dealing::{Scratch, deal, light_samples};
use super::lighting::{lane, light_ends, set_lane};
use super::{MAX_BOUNCES, Pixel, Setup};
use crate::bsdf::phong_lobe;
use crate::geometry::Ray;
use crate::packet::WIDTH;
use crate::scene::{Finish, Hit, Scene, Seen};
use glam::DVec3;
use samplab::seed::uniform;

/// A path of an estimate being followed: its estimate and the product of the specular
/// reflectances so far.
#[derive(Clone, Copy)]
pub(super) struct Path {
    pub(super) estimate: u32,
    pub(super) throughput: DVec3,
}

/// A pixel's radiance, its visible fraction and the (camera, shadow) rays it traced: its
/// camera rays traced as packets of [`WIDTH`] estimates, then the reflected rays of the
/// mirror and glossy hits wave by wave; the diffuse ends are lit [`WIDTH`] at a time, each
/// light's shadow rays traced as packets. Compiled wide ([`wide`]).
#[inline(always)]
pub(super) fn render_pixel(setup: &Setup, px: Pixel, s: &mut Scratch) -> (DVec3, f64, (u64, u64)) {
    let Setup { scene, options: o, .. } = *setup;
    deal(setup, px, s);
    start(setup, s);
    let (mut camera, mut shadow) = (0, 0);
    for first in (0..o.spp).step_by(WIDTH) {
        let m = WIDTH.min(o.spp - first);
        camera_packet(setup, px, s, first, m);
        let hits = scene.trace_packet(&s.camera);
        for (i, &hit) in hits[..m].iter().enumerate() {
            let (ray, estimate) = (s.camera.ray(i), (first + i) as u32);
            if setup.frame.beyond_far(hit.t) {
                continue;
            }
            // a plain surface (most hits) ends the path without the general lookup; checked
            // here rather than in `visit`, which the reflected waves share: there it cost 4%
            if let Some(&Some(albedo)) = setup.plain.get(hit.what as usize) {
                let position = ray.at(hit.t);
                let (normal, _) = scene.facing_normal(hit.what, position, &ray);
                shadow += end_path(setup, px, s, estimate, position, normal, albedo, ray.time);
                continue;
            }
            shadow += visit(setup, px, s, &ray, hit, Path { estimate, throughput: DVec3::ONE }, 0);
        }
    }
    camera += o.spp as u64;
    for bounces in 1..=MAX_BOUNCES {
        std::mem::swap(&mut s.rays, &mut s.next);
        std::mem::swap(&mut s.paths, &mut s.next_paths);
        s.next.clear();
        s.next_paths.clear();
        if s.rays.is_empty() {
            break;
        }
        camera += s.rays.len() as u64;
        scene.trace(&s.rays, &mut s.hits);
        for k in 0..s.rays.len() {
            let (ray, hit, path) = (s.rays[k], s.hits[k], s.paths[k]);
            shadow += visit(setup, px, s, &ray, hit, path, bounces);
        }
    }
    shadow += light_ends(setup, px, s);
    let radiance = s.radiance.iter().fold(DVec3::ZERO, |a, &r| a + r);
    let visible = s.visible.iter().fold(0.0, |a, &v| a + v);
    let inv = 1.0 / o.spp as f64;
    (radiance * inv, visible * inv, (camera, shadow))
}

/// Clear the per-estimate state for a new pixel.
#[inline(always)]
pub(super) fn start(setup: &Setup, s: &mut Scratch) {
    let spp = setup.options.spp;
    s.radiance.clear();
    s.radiance.resize(spp, DVec3::ZERO);
    s.visible.clear();
    s.visible.resize(spp, 0.0);
    s.next.clear();
    s.next_paths.clear();
    if setup.glossy {
        s.gloss_u.clear();
        s.gloss_u.extend((0..spp).map(|e| {
            let u = s.gloss.block(e, 2);
            Some([u[0], u[1]])
        }));
        s.later.clear();
        s.later.resize(spp, None);
    }
}

/// The camera rays of estimates `first..first + m` in `s.camera`: the samples gathered into
/// lanes first, so that the rays are made in vector lanes.
#[inline(always)]
pub(super) fn camera_packet(setup: &Setup, px: Pixel, s: &mut Scratch, first: usize, m: usize) {
    let Setup { scene, options: o, frame, moving, .. } = *setup;
    let mut film = [[0.5; WIDTH]; 2];
    if o.footprint.spreads() {
        for (i, u) in s.pixel[2 * first..2 * (first + m)].chunks_exact(2).enumerate() {
            [film[0][i], film[1][i]] = o.footprint.offset([u[0], u[1]], px.col, px.row, o.width, o.height);
        }
    }
    let mut lens = [[0.5; WIDTH]; 2];
    if scene.camera.aperture > 0.0 {
        for (i, e) in (first..first + m).enumerate() {
            let u = s.lens.block(e, 2);
            lens[0][i] = u[0];
            lens[1][i] = u[1];
        }
    }
    let mut time = [0.0; WIDTH];
    if moving {
        for (i, e) in (first..first + m).enumerate() {
            time[i] = s.time.block(e, 1)[0];
        }
    }
    let (col, row, w, h) = (px.col as f64, px.row as f64, o.width as f64, o.height as f64);
    for i in 0..m {
        let (x, y) = ((col + film[0][i]) / w, (row + film[1][i]) / h);
        s.camera.set(i, &frame.ray(x, y, [lens[0][i], lens[1][i]], time[i]));
    }
    s.camera.seal(m);
}

/// Follow `path`'s `ray` to its `hit`: a light or a surface's emission adds to its estimate;
/// a diffuse surface ends the path (lighting the ends when [`WIDTH`] are waiting); a
/// mirror or glossy one reflects it into the next wave, with the strategy's gloss sample at
/// the first glossy bounce and independent ones after. Returns the shadow rays traced.
#[inline(always)]
pub(super) fn visit(setup: &Setup, px: Pixel, s: &mut Scratch, ray: &Ray, hit: Hit, path: Path, bounces: usize) -> u64 {
    let Setup { scene, keys, .. } = *setup;
    let e = path.estimate as usize;
    let (position, normal, albedo, finish) = match scene.seen(ray, hit) {
        Seen::Nothing => return 0,
        Seen::Light(le) => {
            s.radiance[e] += path.throughput * le;
            s.visible[e] += 1.0;
            return 0;
        }
        Seen::Surface { position, normal, albedo, emission, finish, light } => {
            s.radiance[e] += path.throughput * emission;
            if light.is_some() && emission != DVec3::ZERO {
                s.visible[e] += 1.0;
            }
            (position, normal, albedo, finish)
        }
    };
    let (dir, weight) = match finish {
        Finish::Diffuse => {
            return end_path(setup, px, s, path.estimate, position, normal, path.throughput * albedo, ray.time);
        }
        _ if bounces == MAX_BOUNCES => return 0,
        Finish::Mirror => (ray.dir.reflect(normal), 1.0),
        Finish::Glossy { .. } | Finish::Rough { .. } => {
            let u = s.gloss_u[e].take().unwrap_or_else(|| {
                let rng = s.later[e].get_or_insert_with(|| keys.gloss.derive(px.index).derive(e as u64).rng());
                [uniform(rng), uniform(rng)]
            });
            if let Finish::Glossy { exponent } = finish {
                let d = phong_lobe(ray.dir.reflect(normal).normalize(), exponent, u);
                if d.dot(normal) <= 0.0 {
                    return 0;
                }
                (d, 1.0)
            } else {
                match crate::bsdf::sample(finish, normal, -ray.dir.normalize(), u) {
                    Some(b) => (b.dir, b.weight),
                    None => return 0,
                }
            }
        }
    };
    s.next.push(Ray { origin: Scene::offset(position, normal), dir, time: ray.time });
    s.next_paths.push(Path { estimate: path.estimate, throughput: path.throughput * albedo * weight });
    0
}

/// End estimate `estimate`'s path at a diffuse surface point (position, normal facing the
/// path, throughput x albedo, time), lighting the waiting ends when [`WIDTH`] are waiting.
/// Returns the shadow rays traced.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn end_path(
    setup: &Setup,
    px: Pixel,
    s: &mut Scratch,
    estimate: u32,
    position: DVec3,
    normal: DVec3,
    albedo: DVec3,
    time: f64,
) -> u64 {
    let ends = &mut s.ends;
    let k = ends.len;
    ends.estimate[k] = estimate;
    set_lane(&mut ends.position, k, position);
    set_lane(&mut ends.normal, k, normal);
    set_lane(&mut ends.albedo, k, albedo);
    ends.time[k] = time;
    ends.len = k + 1;
    if k + 1 == WIDTH { light_ends(setup, px, s) } else { 0 }
}

/// The obscurance of the waiting ends (see the module's documentation): per end, its
/// estimate's n directions traced together; the end's estimate gains albedo x W and its
/// visible channel W. Returns the rays traced.
pub(super) fn obscure_ends(setup: &Setup, px: Pixel, s: &mut Scratch) -> u64 {
    let Setup { scene, options: o, keys, plans, .. } = *setup;
    let m = s.ends.len;
    for k in 0..m {
        let e = s.ends.estimate[k] as usize;
        let (x, normal) = (lane(&s.ends.position, k), lane(&s.ends.normal, k));
        match o.pixel_sampler().map(|(p, _)| p) {
            Some(pixels) => light_samples(pixels, px, e, 0, o.n, 2, &mut s.light),
            None => {
                s.light.resize(o.n * 2, 0.0);
                if let Err(e) = plans.light[0].fill(keys.light.derive(px.index).derive(e as u64), &mut s.light) {
                    s.failed.get_or_insert(e);
                }
            }
        }
        let origin = Scene::offset(x, normal);
        s.probes.clear();
        s.probes.extend(s.light.chunks_exact(2).map(|u| Ray {
            origin,
            dir: phong_lobe(normal, 1.0, [u[0], u[1]]),
            time: s.ends.time[k],
        }));
        scene.trace(&s.probes, &mut s.probe_hits);
        let rho = |(ray, &hit): (&Ray, &Hit)| match scene.seen(ray, hit) {
            Seen::Surface { .. } if hit.t < o.range => (hit.t / o.range).sqrt(),
            _ => 1.0,
        };
        let w = s.probes.iter().zip(&s.probe_hits).map(rho).sum::<f64>() / o.n as f64;
        s.radiance[e] += lane(&s.ends.albedo, k) * w;
        s.visible[e] += w;
    }
    s.ends.len = 0;
    (m * o.n) as u64
}
