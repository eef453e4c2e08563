//! The renderer: per pixel, `spp` secondary estimates, each one camera ray and `n` shadow
//! rays per light, the light samples an `n`-point pattern from any samplab sampler.
//!
//! Every random choice of a pixel is a pure function of (seed, pixel index): rows are
//! rendered in parallel, and the image is the same bytes whatever the thread count.
//!
//! Two estimators (the two modes):
//! - **visibility** (Ramamoorthi et al. 2012, sections 3 and 5.3: "Monte Carlo only for
//!   visibility"): the pixel is U(x) times the emission-weighted visible fraction of the
//!   light, where U(x) is the unoccluded direct lighting by a fixed 16 x 16 midpoint rule
//!   (the same for every strategy, so all the error is the visibility's), and the visible
//!   fraction is sum_i V(x, y_i) L(y_i) / sum_i L(y_i): a Gaussian light's falloff weighs
//!   the sampled visibility as in their eq. 31, and the estimate is exact wherever the
//!   light is wholly visible or wholly hidden;
//! - **direct**: the standard light-sampling estimator, (A/N) sum_i L(y_i) (albedo/pi)
//!   V(x, y_i) cos(theta_x) cos(theta_y) / |x - y_i|^2.
//!
//! With a rejection disk map, the sums run over the accepted samples and divide by their
//! number (Ramamoorthi et al. 2012, section 7, footnote 8).

use std::f64::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;
use samplab::sampler::Sampler;
use samplab::seed::{Seed, permutation, uniform};

use crate::error::{Error, Result};
use crate::geometry::Ray;
use crate::image::Image;
use crate::light::{DiskMap, Light, LightPoint};
use crate::scene::{Finish, Scene, Seen};

/// What each light sample estimates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Monte Carlo for visibility only; unoccluded shading by a fixed quadrature.
    Visibility,
    /// Full direct lighting by light sampling.
    Direct,
}

/// Where in the pixel the camera rays go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Footprint {
    /// Every estimate through the pixel centre.
    Centre,
    /// Over the pixel's area (antialiasing) by the pixel strategy.
    Area,
}

/// How light samples are grouped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pattern {
    /// Each estimate draws its own `n`-point pattern (secondary estimates, Subr & Kautz
    /// 2013 Fig. 8; offsets x points, Sbert et al. 2006 Table 1).
    PerEstimate,
    /// One `spp * n`-point pattern per pixel, dealt to the estimates in a random order
    /// (Cook's pairing of pixel and light samples; Shirley 1991's 16 samples per pixel).
    PerPixel,
}

/// How to render.
#[derive(Debug)]
pub struct Options {
    /// The strategy of the light samples.
    pub light: Box<dyn Sampler>,
    /// Light samples per estimate and light.
    pub n: usize,
    /// Secondary estimates per pixel.
    pub spp: usize,
    /// Estimator.
    pub mode: Mode,
    /// Pixel centre or area.
    pub footprint: Footprint,
    /// Strategy over the pixel area (`spp` points).
    pub pixel: Box<dyn Sampler>,
    /// Strategy over the lens (`spp` points), used when the camera has an aperture; dealt
    /// to the estimates in a random order per pixel, so that it is not correlated with the
    /// pixel strategy.
    pub lens: Box<dyn Sampler>,
    /// Strategy over the shutter interval (`spp` points), used when something moves; dealt
    /// in a random order of its own.
    pub time: Box<dyn Sampler>,
    /// Strategy over the glossy lobe (`spp` points), for the first glossy bounce of each
    /// estimate when a material is glossy; dealt in a random order of its own.
    pub gloss: Box<dyn Sampler>,
    /// Grouping of light samples.
    pub pattern: Pattern,
    /// Disk map override for every disk light (None: each light's own).
    pub disk_map: Option<DiskMap>,
    /// Image width.
    pub width: usize,
    /// Image height.
    pub height: usize,
    /// Seed of every random choice.
    pub seed: Seed,
}

/// Largest image side accepted.
pub const MAX_SIDE: usize = 1 << 14;
/// Mirror and glossy reflections followed before a path is dropped.
const MAX_BOUNCES: usize = 8;
/// Side of the midpoint rule for unoccluded shading in visibility mode.
const QUADRATURE: usize = 16;

/// A rendered image and what it cost.
#[derive(Debug, Clone)]
pub struct Rendered {
    /// The image (with its visibility channel).
    pub image: Image,
    /// Camera rays traced.
    pub camera_rays: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
}

impl Options {
    /// Options with the given light strategy and count and image size: one estimate per
    /// pixel through its centre, visibility mode, Owen-scrambled Sobol' over pixel, lens
    /// and time, the default seed.
    ///
    /// # Errors
    /// A sampler spec that does not parse.
    pub fn new(light: &str, n: usize, width: usize, height: usize) -> Result<Options> {
        let sobol = || samplab::sampler::build("sobol.owen");
        Ok(Options {
            light: samplab::sampler::build(light)?,
            n,
            spp: 1,
            mode: Mode::Visibility,
            footprint: Footprint::Centre,
            pixel: sobol()?,
            lens: sobol()?,
            time: sobol()?,
            gloss: sobol()?,
            pattern: Pattern::PerEstimate,
            disk_map: None,
            width,
            height,
            seed: Seed::DEFAULT,
        })
    }

    /// Check every count and size against the scene before any work.
    ///
    /// # Errors
    /// A zero or oversized image, zero samples, or a sampler that cannot make the counts.
    pub fn check(&self, scene: &Scene) -> Result<()> {
        for (what, v) in [("width", self.width), ("height", self.height)] {
            if v == 0 || v > MAX_SIDE {
                return Err(Error::Invalid(format!("image {what} {v} is out of range 1..={MAX_SIDE}")));
            }
        }
        if self.n == 0 || self.spp == 0 {
            return Err(Error::Invalid("light samples (-n) and estimates per pixel (--spp) must be at least 1".into()));
        }
        let per_pattern = match self.pattern {
            Pattern::PerEstimate => self.n,
            Pattern::PerPixel => {
                self.n.checked_mul(self.spp).ok_or_else(|| Error::Invalid("n x spp overflows".into()))?
            }
        };
        for light in &scene.lights {
            self.light.check(per_pattern, light.dims())?;
        }
        if self.footprint == Footprint::Area {
            self.pixel.check(self.spp, 2)?;
        }
        if scene.camera.aperture > 0.0 {
            self.lens.check(self.spp, 2)?;
        }
        if scene.moving() {
            self.time.check(self.spp, 1)?;
        }
        if scene.glossy() {
            self.gloss.check(self.spp, 2)?;
        }
        Ok(())
    }
}

/// One light prepared for a render.
struct Prepared {
    light: Light,
    /// Midpoint-rule points for the unoccluded shading (visibility mode).
    quadrature: Vec<LightPoint>,
}

/// Per-thread scratch buffers.
#[derive(Default)]
struct Scratch {
    pixel: Vec<f64>,
    lens: Dealt,
    time: Dealt,
    gloss: Dealt,
    light: Vec<f64>,
    /// Per light: the pixel's whole pattern (per-pixel patterns).
    shared: Vec<Dealt>,
}

/// A pixel's pattern of `spp` blocks and the random order they are dealt to its estimates
/// in, so that strategies built alike for different dimensions (Sobol' over the pixel and
/// over the lens, say) are not correlated ("padding").
#[derive(Default)]
struct Dealt {
    points: Vec<f64>,
    order: Vec<u32>,
}

impl Dealt {
    /// Fill with `spp` blocks of `per_block` points of `dims` coordinates from `sampler`
    /// (one pattern, seeded by `key`), and draw the order from `order_key`.
    fn deal(&mut self, sampler: &dyn Sampler, spp: usize, per_block: usize, dims: usize, key: Seed, order_key: Seed) {
        self.points.resize(spp * per_block * dims, 0.0);
        // cannot fail: Options::check accepted these counts
        sampler.fill(spp * per_block, dims, key, &mut self.points).expect("counts checked");
        self.order = permutation(&mut order_key.rng(), spp);
    }

    /// Estimate e's block of `len` values.
    fn block(&self, e: usize, len: usize) -> &[f64] {
        let b = self.order[e] as usize * len;
        &self.points[b..b + len]
    }
}

/// Render `scene`; `progress` is called with the number of rows finished so far.
///
/// # Errors
/// Options that do not fit the scene ([`Options::check`]).
pub fn render(scene: &Scene, options: &Options, progress: &(dyn Fn(usize) + Sync)) -> Result<Rendered> {
    options.check(scene)?;
    let (w, h) = (options.width, options.height);
    let lights: Vec<Prepared> = scene
        .lights
        .iter()
        .map(|&l| {
            let light = Light { disk_map: options.disk_map.unwrap_or(l.disk_map), ..l };
            Prepared { light, quadrature: quadrature(&light) }
        })
        .collect();
    let frame = scene.camera.frame(w, h);
    let keys = Keys::new(options.seed);
    let setup = Setup { lights: &lights, frame: &frame, keys: &keys, moving: scene.moving(), glossy: scene.glossy() };
    let done = AtomicUsize::new(0);
    let mut rgb = vec![0f32; 3 * w * h];
    let mut vis = vec![0f32; w * h];
    let (camera_rays, shadow_rays) = rgb
        .par_chunks_mut(3 * w)
        .zip(vis.par_chunks_mut(w))
        .enumerate()
        .map_init(Scratch::default, |scratch, (row, (rgb_row, vis_row))| {
            let mut rays = (0u64, 0u64);
            for col in 0..w {
                let pixel = Pixel { index: (row * w + col) as u64, col, row };
                let (radiance, visible, r) = render_pixel(scene, options, &setup, pixel, scratch);
                rgb_row[3 * col..3 * col + 3].copy_from_slice(&radiance.as_vec3().to_array());
                vis_row[col] = visible as f32;
                rays.0 += r.0;
                rays.1 += r.1;
            }
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            rays
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    Ok(Rendered { image: Image { width: w, height: h, rgb, visibility: Some(vis) }, camera_rays, shadow_rays })
}

/// The midpoint rule over the light's square (interval), through the concentric map for
/// disks (area-preserving, so equal weights).
fn quadrature(light: &Light) -> Vec<LightPoint> {
    let k = QUADRATURE;
    let mid = |i: usize| (i as f64 + 0.5) / k as f64;
    if light.dims() == 1 {
        (0..k * k)
            .filter_map(|i| light.sample_with(&[(i as f64 + 0.5) / (k * k) as f64], DiskMap::Concentric))
            .collect()
    } else {
        (0..k * k).filter_map(|i| light.sample_with(&[mid(i % k), mid(i / k)], DiskMap::Concentric)).collect()
    }
}

/// Sub-seeds of each purpose.
struct Keys {
    pixel: Seed,
    lens: Seed,
    time: Seed,
    gloss: Seed,
    light: Seed,
    deal: Seed,
}

impl Keys {
    fn new(seed: Seed) -> Keys {
        Keys {
            pixel: seed.derive_str("pixel"),
            lens: seed.derive_str("lens"),
            time: seed.derive_str("time"),
            gloss: seed.derive_str("gloss"),
            light: seed.derive_str("light"),
            deal: seed.derive_str("deal"),
        }
    }
}

/// What every pixel of a render shares.
struct Setup<'a> {
    lights: &'a [Prepared],
    frame: &'a crate::camera::Frame,
    keys: &'a Keys,
    moving: bool,
    glossy: bool,
}

#[derive(Clone, Copy)]
struct Pixel {
    index: u64,
    col: usize,
    row: usize,
}

/// A pixel's radiance, its visible fraction and the (camera, shadow) rays it traced.
fn render_pixel(scene: &Scene, o: &Options, setup: &Setup, px: Pixel, s: &mut Scratch) -> (DVec3, f64, (u64, u64)) {
    let Setup { lights, frame, keys, moving, glossy } = *setup;
    let spp = o.spp;
    if o.footprint == Footprint::Area {
        s.pixel.resize(spp * 2, 0.0);
        // cannot fail: Options::check accepted these counts
        o.pixel.fill(spp, 2, keys.pixel.derive(px.index), &mut s.pixel).expect("counts checked");
    }
    let deal_key = |what: &str| keys.deal.derive(px.index).derive_str(what);
    let lens = scene.camera.aperture > 0.0;
    if lens {
        s.lens.deal(o.lens.as_ref(), spp, 1, 2, keys.lens.derive(px.index), deal_key("lens"));
    }
    if moving {
        s.time.deal(o.time.as_ref(), spp, 1, 1, keys.time.derive(px.index), deal_key("time"));
    }
    if glossy {
        s.gloss.deal(o.gloss.as_ref(), spp, 1, 2, keys.gloss.derive(px.index), deal_key("gloss"));
    }
    if o.pattern == Pattern::PerPixel {
        s.shared.resize_with(lights.len(), Default::default);
        for (l, p) in lights.iter().enumerate() {
            let key = keys.light.derive(px.index).derive(l as u64);
            let order_key = keys.deal.derive(px.index).derive(l as u64);
            s.shared[l].deal(o.light.as_ref(), spp, o.n, p.light.dims(), key, order_key);
        }
    }
    let mut radiance = DVec3::ZERO;
    let mut visible = 0.0;
    let mut rays = (0u64, 0u64);
    for e in 0..spp {
        let (dx, dy) = if o.footprint == Footprint::Area { (s.pixel[2 * e], s.pixel[2 * e + 1]) } else { (0.5, 0.5) };
        let lens_uv = if lens {
            let u = s.lens.block(e, 2);
            [u[0], u[1]]
        } else {
            [0.5, 0.5]
        };
        let time = if moving { s.time.block(e, 1)[0] } else { 0.0 };
        let mut ray =
            frame.ray((px.col as f64 + dx) / o.width as f64, (px.row as f64 + dy) / o.height as f64, lens_uv, time);
        // follow mirror and glossy reflections to the first diffuse surface, with the
        // strategy's gloss sample at the first glossy bounce and independent ones after
        let mut throughput = DVec3::ONE;
        let mut gloss = if glossy {
            let u = s.gloss.block(e, 2);
            Some([u[0], u[1]])
        } else {
            None
        };
        let mut later = None;
        let mut bounces = 0;
        let surface = loop {
            rays.0 += 1;
            let (position, normal, albedo, finish) = match scene.trace(&ray) {
                Seen::Nothing => break None,
                Seen::Light(le) => {
                    radiance += throughput * le;
                    visible += 1.0;
                    break None;
                }
                Seen::Surface { position, normal, albedo, emission, finish } => {
                    radiance += throughput * emission;
                    (position, normal, albedo, finish)
                }
            };
            let dir = match finish {
                Finish::Diffuse => break Some((position, normal, throughput * albedo)),
                _ if bounces == MAX_BOUNCES => break None,
                Finish::Mirror => ray.dir.reflect(normal),
                Finish::Glossy { exponent } => {
                    let u = gloss.take().unwrap_or_else(|| {
                        let rng = later.get_or_insert_with(|| keys.gloss.derive(px.index).derive(e as u64).rng());
                        [uniform(rng), uniform(rng)]
                    });
                    let d = phong_lobe(ray.dir.reflect(normal).normalize(), exponent, u);
                    if d.dot(normal) <= 0.0 {
                        break None;
                    }
                    d
                }
            };
            throughput *= albedo;
            bounces += 1;
            ray = Ray { origin: Scene::offset(position, normal), dir, time };
        };
        let Some((x, n, albedo)) = surface else { continue };
        let brdf = albedo / PI;
        let mut vis_sum = 0.0;
        for (l, p) in lights.iter().enumerate() {
            let dims = p.light.dims();
            let key = keys.light.derive(px.index).derive(l as u64);
            let points: &[f64] = match o.pattern {
                Pattern::PerEstimate => {
                    s.light.resize(o.n * dims, 0.0);
                    o.light.fill(o.n, dims, key.derive(e as u64), &mut s.light).expect("counts checked");
                    &s.light
                }
                Pattern::PerPixel => s.shared[l].block(e, o.n * dims),
            };
            let unoccluded = match o.mode {
                Mode::Visibility => {
                    let g: f64 = p.quadrature.iter().map(|q| q.weight * p.light.geometry(x, n, q.position)).sum();
                    g / p.quadrature.len() as f64
                }
                Mode::Direct => 1.0,
            };
            if unoccluded <= 0.0 {
                continue;
            }
            let (mut accepted, mut shade, mut seen, mut weight) = (0usize, 0.0, 0.0, 0.0);
            for u in points.chunks_exact(dims) {
                let Some(y) = p.light.sample(u) else { continue };
                accepted += 1;
                weight += y.weight;
                let g = if o.mode == Mode::Direct { p.light.geometry(x, n, y.position) } else { 1.0 };
                if g <= 0.0 {
                    continue;
                }
                rays.1 += 1;
                if !scene.occluded(x, n, y.position, time) {
                    shade += y.weight * g;
                    seen += y.weight;
                }
            }
            if accepted == 0 {
                continue;
            }
            let fraction = seen / weight;
            vis_sum += fraction;
            let integral = match o.mode {
                Mode::Visibility => unoccluded * fraction,
                Mode::Direct => shade / accepted as f64,
            };
            radiance += brdf * p.light.radiance * p.light.area() * integral;
        }
        // a scene without lights is all "visible" (nothing to shadow)
        visible += if lights.is_empty() { 1.0 } else { vis_sum / lights.len() as f64 };
    }
    let inv = 1.0 / spp as f64;
    (radiance * inv, visible * inv, rays)
}

/// A direction about the unit `axis` from the normalized Phong lobe (n + 1) / (2 pi)
/// cos^n(alpha) by inversion: cos(alpha) = u0^(1 / (n + 1)), azimuth 2 pi u1.
fn phong_lobe(axis: DVec3, exponent: f64, u: [f64; 2]) -> DVec3 {
    let cos = u[0].powf(1.0 / (exponent + 1.0));
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let (a, b) = axis.any_orthonormal_pair();
    let (s, c) = (2.0 * PI * u[1]).sin_cos();
    (a * c + b * s) * sin + axis * cos
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_phong_lobe_has_the_mean_cosine_of_its_density() {
        // for density (n + 1) / (2 pi) cos^n about the axis, E[cos] = (n + 1) / (n + 2)
        let axis = DVec3::new(0.3, -0.5, 0.8).normalize();
        for exponent in [0.0, 1.0, 4.0, 10.0] {
            let k = 400;
            let mut sum = 0.0;
            for i in 0..k * k {
                let u = [((i % k) as f64 + 0.5) / k as f64, ((i / k) as f64 + 0.5) / k as f64];
                let d = phong_lobe(axis, exponent, u);
                assert!((d.length() - 1.0).abs() < 1e-12);
                sum += d.dot(axis);
            }
            let mean = sum / (k * k) as f64;
            let exact = (exponent + 1.0) / (exponent + 2.0);
            // the midpoint rule errs by about 4e-5 on u^(1/(n+1)); a wrong exponent by 1e-3
            assert!((mean - exact).abs() < 1e-4, "n = {exponent}: {mean} vs {exact}");
        }
    }
}
