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
//!
//! A third estimator ignores the lights: **obscurance** (Zhukov et al. 1998; Iones et al.
//! 2003; sampled systematically by Sbert et al. 2006, Fig. 7), ambient light of unit
//! radiance reaching x unless an occluder is near: W(x) = (1/pi) int rho(d(x, w)) cos dw,
//! with d the distance to the first surface along w and rho(d) = sqrt(d / range) below the
//! range, 1 beyond it (and for no surface). Each estimate takes the light strategy's n-point
//! pattern in the unit square as n cosine-weighted directions (cos = sqrt(u0), azimuth
//! 2 pi u1) and is albedo x the mean of rho.
//!
//! Pixel samples come from a pattern per pixel, or, interleaved (Keller & Heidrich 2001;
//! Sbert et al. 2006 Fig. 4), from one pattern of spp x w x h points over a tile of w x h
//! pixels repeated over the image: each pixel takes the spp points in its cell of the tile.
//!
//! Or every dimension of every estimate comes from one pixel sampler
//! ([`samplab::pixel`], [`Options::pixels`]), as a production renderer draws them: estimate
//! e of pixel (x, y) is sample e, and its dimensions are laid out as [`pixel_dims`] says.

use std::f64::consts::PI;

use glam::DVec3;
use rayon::prelude::*;
use samplab::progress::Progress;
use samplab::sampler::{Plan, Sampler};
use samplab::seed::{Rng, Seed, shuffle, uniform};

use crate::bsdf::phong_lobe;
use crate::error::{Error, Result, setting};
use crate::filter::Footprint;
use crate::geometry::Ray;
use crate::image::Image;
use crate::light::{DiskMap, Light, LightPoint, LightPoints, geometry};
use crate::packet::{Packet, WIDTH};
use crate::scene::{Finish, Hit, Scene, Seen};
use samplab::simd::wide;

/// What each light sample estimates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Mode {
    /// Monte Carlo for visibility only; unoccluded shading by a fixed quadrature.
    Visibility,
    /// Full direct lighting by light sampling.
    Direct,
    /// Obscurance: no lights; the strategy's pattern gives cosine-weighted directions.
    Obscurance,
    /// Path tracing with next-event estimation ([`crate::path`]), every dimension from a
    /// pixel sampler ([`Options::pixels`]).
    Path {
        /// Most segments of a path (Mitsuba's `max_depth`: 2 is direct lighting).
        max_depth: u32,
    },
}

/// How light samples are grouped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
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
    pub light: Sampler,
    /// Light samples per estimate and light.
    pub n: usize,
    /// Secondary estimates per pixel.
    pub spp: usize,
    /// Estimator.
    pub mode: Mode,
    /// Pixel centre or area.
    pub footprint: Footprint,
    /// Strategy over the pixel area (`spp` points).
    pub area: Sampler,
    /// Strategy over the lens (`spp` points), used when the camera has an aperture; dealt
    /// to the estimates in a random order per pixel, so that it is not correlated with the
    /// pixel strategy.
    pub lens: Sampler,
    /// Strategy over the shutter interval (`spp` points), used when something moves; dealt
    /// in a random order of its own.
    pub time: Sampler,
    /// Strategy over the glossy lobe (`spp` points), for the first glossy bounce of each
    /// estimate when a material is glossy; dealt in a random order of its own.
    pub gloss: Sampler,
    /// Grouping of light samples.
    pub pattern: Pattern,
    /// Disk map override for every disk light (None: each light's own).
    pub disk_map: Option<DiskMap>,
    /// Obscurance mode: the distance beyond which a surface no longer obscures.
    pub range: f64,
    /// Interleaved pixel sampling over tiles of (w, h) pixels (area footprint); None: a
    /// pattern per pixel.
    pub interleave: Option<(usize, usize)>,
    /// Image width.
    pub width: usize,
    /// Image height.
    pub height: usize,
    /// Seed of every random choice.
    pub seed: Seed,
    /// A pixel sampler that draws every dimension instead of the strategies above
    /// (`light`, `area`, `lens`, `time`, `gloss`), prepared for this image, `spp` and at
    /// least [`pixel_dims`] dimensions; it takes patterns per estimate and no interleaving.
    pub pixels: Option<samplab::pixel::Pixels>,
    /// The frame the pixel sampler draws (an animation's frame number: each frame its own
    /// samples, as the sampler decorrelates them).
    pub frame: u32,
}

/// The dimensions of an estimate drawn from a pixel sampler ([`Options::pixels`]): 0-1 the
/// film position in the pixel, 2-3 the lens, 4 the shutter time, 5 unused, 6-7 the first
/// glossy bounce, then 2 per light sample from [`FIRST_LIGHT_DIM`] on (light l's sample j
/// at 8 + 2 (l n + j), its first `dims` used), or per obscurance direction. Returns how
/// many dimensions that makes for `n` samples of each of `lights` lights (one set of
/// directions for obscurance). Path mode lays its dimensions out as [`crate::path`] says.
pub fn pixel_dims(n: usize, lights: usize, mode: Mode) -> usize {
    if let Mode::Path { max_depth } = mode {
        return crate::path::dims(max_depth as usize);
    }
    let sets = if mode == Mode::Obscurance { 1 } else { lights };
    FIRST_LIGHT_DIM as usize + 2 * n * sets
}

/// The first light dimension of a pixel sampler's estimate ([`pixel_dims`]).
pub const FIRST_LIGHT_DIM: u32 = 8;

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
            area: sobol()?,
            lens: sobol()?,
            time: sobol()?,
            gloss: sobol()?,
            pattern: Pattern::PerEstimate,
            disk_map: None,
            range: 1.0,
            interleave: None,
            width,
            height,
            seed: Seed::DEFAULT,
            pixels: None,
            frame: 0,
        })
    }

    /// This render made converged, for a reference: `light` (a sampler spec) with
    /// `light_samples` per estimate, Owen-scrambled Sobol' over the pixel, lens, shutter and
    /// gloss, one pattern per estimate, no interleaving, and `spp` estimates per pixel; the
    /// same image, mode, footprint, disk map, range and seed.
    ///
    /// # Errors
    /// A light spec that does not parse.
    pub fn converged(&self, light: &str, light_samples: usize, spp: usize) -> Result<Options> {
        let mut o = Options::new(light, light_samples, self.width, self.height)?;
        o.spp = spp;
        o.mode = self.mode;
        o.footprint = self.footprint;
        o.disk_map = self.disk_map;
        o.range = self.range;
        o.seed = self.seed;
        Ok(o)
    }

    /// The reference `samplab render` measures against when none is given: converged with
    /// Owen-scrambled Sobol' light samples (`light_samples` per estimate), 64 estimates per
    /// pixel (or this render's spp if more) when the estimates sample something (pixel area,
    /// lens or shutter) and 1 otherwise, seeded from this render's seed. In path mode:
    /// `light_samples` estimates per pixel from the pixel sampler `sobol` (Owen-scrambled
    /// Sobol' per pixel).
    ///
    /// # Errors
    /// As [`Options::converged`].
    pub fn reference(&self, scene: &Scene, light_samples: usize) -> Result<Options> {
        if let Mode::Path { max_depth } = self.mode {
            let mut o = self.converged("sobol.owen", 1, light_samples)?;
            o.seed = self.seed.derive_str("reference");
            let side = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
            let film = samplab::pixel::Film {
                width: side(self.width),
                height: side(self.height),
                spp: side(light_samples),
                dims: side(crate::path::dims(max_depth as usize)),
            };
            o.pixels = Some(samplab::pixel::prepare("sobol", film, o.seed)?);
            return Ok(o);
        }
        let needs_estimates = self.footprint.spreads() || scene.camera.aperture > 0.0 || scene.moving();
        let spp = if needs_estimates { self.spp.max(64) } else { 1 };
        let mut o = self.converged("sobol.owen", light_samples, spp)?;
        o.seed = self.seed.derive_str("reference");
        Ok(o)
    }

    /// Check every count and size against the scene before any work.
    ///
    /// # Errors
    /// A zero or oversized image, zero samples, or a sampler that cannot make the counts.
    pub fn check(&self, scene: &Scene) -> Result<()> {
        self.plans(scene).map(|_| ())
    }

    /// Every sampler of the render planned for its counts: the checks of
    /// [`Options::check`], done once.
    fn plans(&self, scene: &Scene) -> Result<Plans> {
        if [self.width, self.height].iter().any(|&v| v == 0 || v > MAX_SIDE) {
            let size = format!("{}x{}", self.width, self.height);
            return Err(setting("res", size, format!("each side must be in 1..={MAX_SIDE}")));
        }
        for (name, v, what) in [("n", self.n, "light samples per estimate"), ("spp", self.spp, "estimates per pixel")] {
            if v == 0 {
                return Err(setting(name, v, format!("{what} must be at least 1")));
            }
        }
        let per_pattern = match self.pattern {
            Pattern::PerEstimate => self.n,
            Pattern::PerPixel => {
                self.n.checked_mul(self.spp).ok_or_else(|| setting("spp", self.spp, "n x spp overflows"))?
            }
        };
        if self.mode == Mode::Obscurance {
            if !(self.range.is_finite() && self.range > 0.0) {
                return Err(setting("range", self.range, "the obscurance range must be a positive number"));
            }
            if self.pattern == Pattern::PerPixel {
                return Err(setting("pattern", "pixel", "obscurance takes a pattern per estimate"));
            }
        }
        if let Mode::Path { max_depth } = self.mode {
            crate::path::check_depth(max_depth as usize)?;
            if self.pixels.is_none() {
                return Err(setting("pixel_sampler", "none", "path mode draws every dimension from a pixel sampler"));
            }
        }
        if let Some(p) = &self.pixels {
            return self.pixel_sampler_plans(p, scene);
        }
        let light = if self.mode == Mode::Obscurance {
            vec![self.light.plan(self.n, 2)?]
        } else {
            scene.lights.iter().map(|l| self.light.plan(per_pattern, l.dims())).collect::<samplab::Result<_>>()?
        };
        let mut pixel = None;
        if self.footprint.spreads() {
            if self.interleave.is_none() {
                pixel = Some(self.area.plan(self.spp, 2)?);
            }
        } else if let Some((w, h)) = self.interleave {
            let reason = "interleaved sampling spreads samples over pixel areas: it needs the area footprint";
            return Err(setting("interleave", format!("{w}x{h}"), reason));
        }
        Ok(Plans {
            light,
            pixel,
            tile: self.tile()?,
            lens: plan_if(scene.camera.aperture > 0.0, &self.lens, self.spp, 2)?,
            time: plan_if(scene.moving(), &self.time, self.spp, 1)?,
            gloss: plan_if(scene.glossy(), &self.gloss, self.spp, 2)?,
        })
    }
}

impl Options {
    /// The checks of a render whose every dimension comes from the pixel sampler `p`; no
    /// strategy is planned.
    fn pixel_sampler_plans(&self, p: &samplab::pixel::Pixels, scene: &Scene) -> Result<Plans> {
        if self.pattern == Pattern::PerPixel || self.interleave.is_some() {
            let reason = "draws each estimate's samples from its own dimensions: it takes patterns per estimate and no \
                          interleaving";
            return Err(setting("pixel_sampler", p.spec(), reason));
        }
        let film = p.film();
        let need = pixel_dims(self.n, scene.lights.len(), self.mode);
        if (film.width as usize, film.height as usize, film.spp as usize) != (self.width, self.height, self.spp)
            || (film.dims as usize) < need
        {
            return Err(Error::Samplab(samplab::Error::Mismatch {
                what: format!("the pixel sampler {}", p.spec()),
                expected: format!("{}x{} pixels, {} spp, {need} dimensions or more", self.width, self.height, self.spp),
                got: format!("{}x{} pixels, {} spp, {} dimensions", film.width, film.height, film.spp, film.dims),
            }));
        }
        Ok(Plans { light: Vec::new(), pixel: None, tile: None, lens: None, time: None, gloss: None })
    }
}

/// `sampler` planned for `n` points in `dims` dimensions where `on`, else None.
fn plan_if(on: bool, sampler: &Sampler, n: usize, dims: usize) -> samplab::Result<Option<Plan>> {
    on.then(|| sampler.plan(n, dims)).transpose()
}

/// The render's samplers planned for their counts (None where the scene needs none).
struct Plans {
    /// Per light (one for obscurance directions): n points, or n x spp for patterns per pixel.
    light: Vec<Plan>,
    /// Over the pixel area, without interleaving.
    pixel: Option<Plan>,
    /// The interleaving tile, drawn once.
    tile: Option<Tile>,
    lens: Option<Plan>,
    time: Option<Plan>,
    gloss: Option<Plan>,
}

/// The largest interleaving tile side, in pixels.
pub const MAX_TILE: usize = 64;

/// An interleaving tile: per pixel cell (row-major), its spp points in pixel coordinates.
struct Tile {
    width: usize,
    height: usize,
    spp: usize,
    points: Vec<f64>,
}

impl Tile {
    /// The points of pixel (col, row).
    fn cell(&self, col: usize, row: usize) -> &[f64] {
        let c = (row % self.height) * self.width + col % self.width;
        &self.points[2 * self.spp * c..2 * self.spp * (c + 1)]
    }
}

impl Options {
    /// The interleaving tile, its pattern drawn once from the pixel strategy (None without
    /// interleaving).
    ///
    /// # Errors
    /// A tile side out of 1..=[`MAX_TILE`], or a pattern that does not put exactly `spp`
    /// points in every pixel of the tile.
    fn tile(&self) -> Result<Option<Tile>> {
        let Some((width, height)) = self.interleave else { return Ok(None) };
        if !(1..=MAX_TILE).contains(&width) || !(1..=MAX_TILE).contains(&height) {
            return Err(setting(
                "interleave",
                format!("{width}x{height}"),
                format!("each side must be in 1..={MAX_TILE}"),
            ));
        }
        let cells = width * height;
        let total = self.spp * cells;
        let pattern = self.area.plan(total, 2)?.generate(self.seed.derive_str("pixel"))?.into_vec();
        let mut by_cell: Vec<Vec<f64>> = vec![Vec::with_capacity(2 * self.spp); cells];
        for p in pattern.chunks_exact(2) {
            let (x, y) = (p[0] * width as f64, p[1] * height as f64);
            let (c, r) = ((x as usize).min(width - 1), (y as usize).min(height - 1));
            by_cell[r * width + c].extend([x - c as f64, y - r as f64]);
        }
        if let Some((i, cell)) = by_cell.iter().enumerate().find(|(_, c)| c.len() != 2 * self.spp) {
            let reason = format!(
                "interleaved sampling: it puts {} of its {total} points in pixel ({}, {}) of the {width}x{height} tile, \
                 not spp = {}",
                cell.len() / 2,
                i % width,
                i / width,
                self.spp
            );
            return Err(setting("area_sampler", self.area.spec(), reason));
        }
        Ok(Some(Tile { width, height, spp: self.spp, points: by_cell.concat() }))
    }
}

/// One light prepared for a render.
struct Prepared {
    light: Light,
    /// Its emitting side's unit normal and its area, computed once.
    normal: Option<DVec3>,
    area: f64,
    /// Midpoint-rule points for the unoccluded shading (visibility mode).
    quadrature: Vec<LightPoint>,
}

/// Per-thread scratch buffers.
#[derive(Default)]
struct Scratch {
    /// The first fill of this pixel that failed (a Poisson-disk sampler that could not place
    /// its points for a seed): the render stops with it after the pixel.
    failed: Option<samplab::Error>,
    pixel: Vec<f64>,
    lens: Dealt,
    time: Dealt,
    gloss: Dealt,
    /// An estimate's light pattern and its points on the light (per-estimate patterns).
    light: Vec<f64>,
    light_points: LightPoints,
    /// Per light: the pixel's whole pattern and its points on the light (per-pixel patterns).
    shared: Vec<Dealt>,
    shared_points: Vec<LightPoints>,
    /// Per estimate: the radiance gathered so far, and the visible fraction of the lights
    /// (1 where a light is seen directly).
    radiance: Vec<DVec3>,
    visible: Vec<f64>,
    /// Per estimate, when a material is glossy: the strategy's gloss sample until the first
    /// glossy bounce takes it, and independent samples for later glossy bounces.
    gloss_u: Vec<Option<[f64; 2]>>,
    later: Vec<Option<Rng>>,
    /// A packet of camera rays.
    camera: Packet,
    /// The reflected rays of the current wave and their paths, and the next wave's.
    rays: Vec<Ray>,
    paths: Vec<Path>,
    next: Vec<Ray>,
    next_paths: Vec<Path>,
    hits: Vec<Hit>,
    /// Paths ended on a diffuse surface, waiting for their light samples.
    ends: Ends,
    /// Shadow rays waiting to be traced.
    shadows: Shadows,
    /// Obscurance rays of one end and their hits.
    probes: Vec<Ray>,
    probe_hits: Vec<Hit>,
    /// Path mode's buffers.
    path: crate::path::Scratch,
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
    /// Fill with the `spp` blocks of `plan` (one pattern, seeded by `key`), and draw the
    /// order from `order_key`.
    fn deal(&mut self, plan: &Plan, spp: usize, key: Seed, order_key: Seed) -> samplab::Result<()> {
        self.points.resize(plan.n() * plan.dims(), 0.0);
        plan.fill(key, &mut self.points)?;
        self.order.clear();
        self.order.extend(0..spp as u32);
        shuffle(&mut order_key.rng(), &mut self.order);
        Ok(())
    }

    /// Where estimate e's block starts, in blocks of `len`.
    fn start(&self, e: usize, len: usize) -> usize {
        self.order[e] as usize * len
    }

    /// Fill with dimensions `first .. first + len` of the pixel's `spp` samples from the
    /// pixel sampler `p`, in their own order.
    fn keyed(&mut self, p: &samplab::pixel::Pixels, px: Pixel, spp: usize, first: u32, len: u32) {
        self.points.clear();
        for e in 0..spp as u32 {
            self.points.extend((first..first + len).map(|d| p.sample(px.at(), px.frame, e, d)));
        }
        self.order.clear();
        self.order.extend(0..spp as u32);
    }

    /// Estimate e's block of `len` values.
    fn block(&self, e: usize, len: usize) -> &[f64] {
        let b = self.start(e, len);
        &self.points[b..b + len]
    }
}

/// Render `scene`; `progress` advances by one per row finished and is checked at every
/// pixel.
///
/// # Errors
/// Options that do not fit the scene ([`Options::check`]), an image that does not fit in
/// memory, a stop ([`samplab::Error::Interrupted`]).
pub fn render(scene: &Scene, options: &Options, progress: &Progress) -> Result<Rendered> {
    let plans = options.plans(scene)?;
    let (w, h) = (options.width, options.height);
    let lights: Vec<Prepared> = scene
        .lights
        .iter()
        .map(|&l| {
            let light = Light { disk_map: options.disk_map.unwrap_or(l.disk_map), ..l };
            Prepared { light, normal: light.normal(), area: light.area(), quadrature: quadrature(&light) }
        })
        .collect();
    let frame = scene.camera.frame(w, h);
    let emitters = crate::path::Emitter::all(scene, options.disk_map);
    let path = options.pixels.as_ref().filter(|_| matches!(options.mode, Mode::Path { .. })).map(|pixels| {
        crate::path::Context {
            scene,
            frame: &frame,
            pixels,
            emitters: &emitters,
            width: w,
            height: h,
            spp: options.spp,
            max_depth: crate::path::Context::depth(options.mode),
            animation_frame: options.frame,
            footprint: options.footprint,
        }
    });
    let keys = Keys::new(options.seed);
    let setup = Setup {
        scene,
        options,
        lights: &lights,
        frame: &frame,
        keys: &keys,
        moving: scene.moving(),
        glossy: scene.glossy(),
        plain: scene.plain_albedos(),
        plans: &plans,
        path: path.as_ref(),
    };
    let image = || format!("a {w}x{h} image");
    samplab::memory::check(image, 16 * w as u128 * h as u128)?;
    // each thread holds one pixel's points: up to 3 coordinates of every light point and
    // its place on the light (with the flag of whether it is kept), and the pixel, lens,
    // shutter and lobe points of every estimate
    let (n, spp) = (options.n as u128, options.spp as u128);
    let light_points = if options.pattern == Pattern::PerPixel { n * spp } else { n };
    let per_point = 8 * 3 + std::mem::size_of::<crate::light::LightPoint>() as u128 + 1;
    let per_thread = per_point * light_points * scene.lights.len().max(1) as u128 + 8 * 7 * spp;
    let threads = rayon::current_num_threads() as u128;
    samplab::memory::check(
        || format!("the points of one pixel ({n} light x {spp} spp) on {threads} threads"),
        threads * per_thread,
    )?;
    let mut rgb = samplab::memory::zeroed(image, 3 * w * h)?;
    let mut vis = samplab::memory::zeroed(image, w * h)?;
    // a row at a time: rows differ in cost, and a thread left with a run of costly rows at
    // the end ran alone for half a second of a 7.5 s render (512x512 at 64 spp, two threads)
    let (camera_rays, shadow_rays) = rgb
        .par_chunks_mut(3 * w)
        .zip(vis.par_chunks_mut(w))
        .enumerate()
        .with_max_len(1)
        .map_init(Scratch::default, |scratch, (row, (rgb_row, vis_row))| -> Result<(u64, u64)> {
            let mut rays = (0u64, 0u64);
            for col in 0..w {
                progress.check()?;
                let pixel = Pixel { index: (row * w + col) as u64, col, row, frame: options.frame };
                let (radiance, visible, r) = match setup.path {
                    Some(c) => wide(
                        #[inline(always)]
                        || crate::path::pixel(c, col, row, &mut scratch.path),
                    ),
                    None => wide(
                        #[inline(always)]
                        || render_pixel(&setup, pixel, scratch),
                    ),
                };
                if let Some(e) = scratch.failed.take() {
                    return Err(e.into());
                }
                rgb_row[3 * col..3 * col + 3].copy_from_slice(&radiance.as_vec3().to_array());
                vis_row[col] = visible as f32;
                rays.0 += r.0;
                rays.1 += r.1;
            }
            progress.advance(1)?;
            Ok(rays)
        })
        .try_reduce(|| (0, 0), |a, b| Ok((a.0 + b.0, a.1 + b.1)))?;
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

/// The unoccluded shading of the light at `x` (normal `n`) by its midpoint rule: the mean of
/// the weighted geometric factor, summed in 8 interleaved partial sums (a fixed order, the
/// same value on every thread count and instruction set) so that the loop vectorizes.
fn unoccluded(p: &Prepared, x: DVec3, n: DVec3) -> f64 {
    const LANES: usize = 8;
    #[inline(always)]
    fn sum(points: &[LightPoint], f: impl Fn(&LightPoint) -> f64) -> [f64; LANES] {
        let mut acc = [0.0; LANES];
        let mut chunks = points.chunks_exact(LANES);
        for c in &mut chunks {
            for (a, q) in acc.iter_mut().zip(c) {
                *a += f(q);
            }
        }
        for (a, q) in acc.iter_mut().zip(chunks.remainder()) {
            *a += f(q);
        }
        acc
    }
    let q = &p.quadrature;
    // the light's normal (or none) fixed outside the loop, so that each loop is branch-free
    let acc = wide(
        #[inline(always)]
        || match p.normal {
            Some(ny) => sum(q, |q| q.weight * geometry(Some(ny), x, n, q.position)),
            None => sum(q, |q| q.weight * geometry(None, x, n, q.position)),
        },
    );
    acc.iter().sum::<f64>() / q.len() as f64
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
    scene: &'a Scene,
    options: &'a Options,
    lights: &'a [Prepared],
    frame: &'a crate::camera::Frame,
    keys: &'a Keys,
    moving: bool,
    glossy: bool,
    /// [`Scene::plain_albedos`].
    plain: Vec<Option<DVec3>>,
    /// The samplers planned for their counts, and the interleaving tile.
    plans: &'a Plans,
    /// In path mode, what its pixels share.
    path: Option<&'a crate::path::Context<'a>>,
}

#[derive(Clone, Copy)]
struct Pixel {
    index: u64,
    col: usize,
    row: usize,
    /// The pixel sampler's frame.
    frame: u32,
}

impl Pixel {
    /// Its (x, y) key for a pixel sampler.
    fn at(self) -> [u32; 2] {
        [self.col as u32, self.row as u32]
    }
}

/// A path of an estimate being followed: its estimate and the product of the specular
/// reflectances so far.
#[derive(Clone, Copy)]
struct Path {
    estimate: u32,
    throughput: DVec3,
}

/// Up to [`WIDTH`] paths ended on a diffuse surface, lit together when full: per lane, the
/// estimate, position, normal facing the path, throughput x albedo and shutter time, in
/// structure-of-arrays form so that their lighting runs in vector lanes.
struct Ends {
    len: usize,
    estimate: [u32; WIDTH],
    position: Lanes3,
    normal: Lanes3,
    albedo: Lanes3,
    time: [f64; WIDTH],
}

/// Three coordinates in lanes.
type Lanes3 = [[f64; WIDTH]; 3];

/// Lanes of zeros (arrays as wide as [`WIDTH`] have no `Default`).
const ZEROS: [f64; WIDTH] = [0.0; WIDTH];

impl Default for Ends {
    fn default() -> Ends {
        Ends { len: 0, estimate: [0; WIDTH], position: [ZEROS; 3], normal: [ZEROS; 3], albedo: [ZEROS; 3], time: ZEROS }
    }
}

impl Default for Shadows {
    fn default() -> Shadows {
        Shadows {
            len: 0,
            end: [0; WIDTH],
            point: [ZEROS; 3],
            weight: ZEROS,
            kept: [false; WIDTH],
            packet: Packet::default(),
        }
    }
}

impl Default for Sums {
    fn default() -> Sums {
        Sums { unoccluded: ZEROS, accepted: [0; WIDTH], weight: ZEROS, shade: ZEROS, seen: ZEROS }
    }
}

/// Vector `k` of `lanes`.
#[inline(always)]
fn lane(lanes: &Lanes3, k: usize) -> DVec3 {
    DVec3::new(lanes[0][k], lanes[1][k], lanes[2][k])
}

/// Put `v` in lane `k`.
#[inline(always)]
fn set_lane(lanes: &mut Lanes3, k: usize, v: DVec3) {
    for (c, x) in lanes.iter_mut().zip(v.to_array()) {
        c[k] = x;
    }
}

/// Up to [`WIDTH`] light samples waiting for their shadow rays, traced as one packet: per
/// lane, the end it belongs to (a lane of [`Ends`]), the light point, its falloff weight and
/// whether it is kept (a lane not kept is dead: no ray).
struct Shadows {
    len: usize,
    end: [u32; WIDTH],
    point: Lanes3,
    weight: [f64; WIDTH],
    kept: [bool; WIDTH],
    packet: Packet,
}

/// One light's sums over the samples of each lane of [`Ends`].
struct Sums {
    /// Unoccluded shading (visibility mode; 1 in direct mode).
    unoccluded: [f64; WIDTH],
    /// Samples the disk map kept, and their summed falloff weight.
    accepted: [u32; WIDTH],
    weight: [f64; WIDTH],
    /// Over the unblocked samples: weight x geometric factor, and weight.
    shade: [f64; WIDTH],
    seen: [f64; WIDTH],
}

/// What a light's samples need of it and of the ends they light.
struct Lighting<'a> {
    scene: &'a Scene,
    ends: &'a Ends,
    /// Each end's shadow-ray origin, moved off its surface.
    origin: &'a Lanes3,
    /// The light's normal (None: a segment); whether the geometric factor weighs samples.
    normal: Option<DVec3>,
    direct: bool,
}

impl Shadows {
    /// Queue light point `y` of weight `weight` for end `end`.
    #[inline(always)]
    fn push(&mut self, end: usize, y: DVec3, weight: f64) {
        let i = self.len;
        self.set(i, end, y, weight, true);
        self.len = i + 1;
    }

    /// Lane `i`: light point `y` of weight `weight` for end `end`, kept or not.
    #[inline(always)]
    fn set(&mut self, i: usize, end: usize, y: DVec3, weight: f64, kept: bool) {
        self.end[i] = end as u32;
        set_lane(&mut self.point, i, y);
        self.weight[i] = weight;
        self.kept[i] = kept;
    }

    /// Lanes `0..n` of the packet: the shadow ray of each queued sample, whose end is
    /// `end(j)`, with its geometric factor and whether the sample is kept with a positive
    /// factor.
    #[inline(always)]
    fn rays(
        &mut self,
        at: &Lighting,
        n: usize,
        end: impl Fn(usize) -> usize,
        factor: &mut [f64; WIDTH],
        live: &mut [bool; WIDTH],
    ) {
        for j in 0..n {
            let k = end(j);
            let (x, y) = (lane(&at.ends.position, k), lane(&self.point, j));
            let g = if at.direct { geometry(at.normal, x, lane(&at.ends.normal, k), y) } else { 1.0 };
            factor[j] = g;
            live[j] = self.kept[j] && g > 0.0;
            self.packet.set(j, &Scene::shadow_ray(lane(at.origin, k), y, at.ends.time[k]));
        }
    }

    /// Trace the queued samples' shadow rays and add each unblocked one to its end's sums,
    /// in the order queued: the rays and geometric factors made in vector lanes, a sample not
    /// kept or whose factor is not positive left out (a dead lane). Returns the rays traced.
    #[inline(always)]
    fn trace(&mut self, at: &Lighting, sums: &mut Sums) -> u64 {
        let n = self.len;
        if n == 0 {
            return 0;
        }
        let (mut factor, mut live) = ([0.0; WIDTH], [false; WIDTH]);
        let end = self.end;
        // one sample per end (the usual case) puts end j in lane j: no gathers, and the loop
        // vectorizes
        if end[..n].iter().enumerate().all(|(j, &k)| k as usize == j) {
            self.rays(at, n, |j| j, &mut factor, &mut live);
        } else {
            self.rays(at, n, |j| end[j] as usize, &mut factor, &mut live);
        }
        self.packet.seal(n);
        let blocked = at.scene.occluded(&self.packet, &live);
        for (j, _) in blocked[..n].iter().enumerate().filter(|(_, b)| !**b) {
            let k = self.end[j] as usize;
            sums.shade[k] += self.weight[j] * factor[j];
            sums.seen[k] += self.weight[j];
        }
        self.len = 0;
        live[..n].iter().filter(|&&l| l).count() as u64
    }
}

/// A pixel's radiance, its visible fraction and the (camera, shadow) rays it traced: its
/// camera rays traced as packets of [`WIDTH`] estimates, then the reflected rays of the
/// mirror and glossy hits wave by wave; the diffuse ends are lit [`WIDTH`] at a time, each
/// light's shadow rays traced as packets. Compiled wide ([`wide`]).
#[inline(always)]
fn render_pixel(setup: &Setup, px: Pixel, s: &mut Scratch) -> (DVec3, f64, (u64, u64)) {
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

/// Draw the pixel's patterns: pixel area, lens, time, gloss, and the per-pixel light
/// patterns with their points on the lights.
#[inline(always)]
fn deal(setup: &Setup, px: Pixel, s: &mut Scratch) {
    if let Err(e) = try_deal(setup, px, s) {
        s.failed.get_or_insert(e);
    }
}

fn try_deal(setup: &Setup, px: Pixel, s: &mut Scratch) -> samplab::Result<()> {
    let Setup { options: o, lights, keys, plans, .. } = *setup;
    let spp = o.spp;
    if let Some(p) = &o.pixels {
        if o.footprint.spreads() {
            s.pixel.clear();
            s.pixel.extend((0..spp as u32).flat_map(|e| [0, 1].map(|d| p.sample(px.at(), px.frame, e, d))));
        }
        let scene = setup.scene;
        for (on, dealt, first, len) in [
            (scene.camera.aperture > 0.0, &mut s.lens, 2, 2),
            (setup.moving, &mut s.time, 4, 1),
            (setup.glossy, &mut s.gloss, 6, 2),
        ] {
            if on {
                dealt.keyed(p, px, spp, first, len);
            }
        }
        return Ok(());
    }
    if o.footprint.spreads() {
        s.pixel.resize(spp * 2, 0.0);
        match (&plans.tile, &plans.pixel) {
            (Some(t), _) => s.pixel.copy_from_slice(t.cell(px.col, px.row)),
            (None, Some(plan)) => plan.fill(keys.pixel.derive(px.index), &mut s.pixel)?,
            (None, None) => unreachable!("the area footprint has a pixel plan or a tile"),
        }
    }
    let deal_key = |what: &str| keys.deal.derive(px.index).derive_str(what);
    if let Some(plan) = &plans.lens {
        s.lens.deal(plan, spp, keys.lens.derive(px.index), deal_key("lens"))?;
    }
    if let Some(plan) = &plans.time {
        s.time.deal(plan, spp, keys.time.derive(px.index), deal_key("time"))?;
    }
    if let Some(plan) = &plans.gloss {
        s.gloss.deal(plan, spp, keys.gloss.derive(px.index), deal_key("gloss"))?;
    }
    if o.pattern == Pattern::PerPixel {
        s.shared.resize_with(lights.len(), Default::default);
        for (l, plan) in plans.light.iter().enumerate() {
            let key = keys.light.derive(px.index).derive(l as u64);
            let order_key = keys.deal.derive(px.index).derive(l as u64);
            s.shared[l].deal(plan, spp, key, order_key)?;
        }
        s.shared_points.resize_with(lights.len(), Default::default);
        for ((p, dealt), points) in lights.iter().zip(&s.shared).zip(&mut s.shared_points) {
            points.fill(&p.light, &dealt.points);
        }
    }
    Ok(())
}

/// Clear the per-estimate state for a new pixel.
#[inline(always)]
fn start(setup: &Setup, s: &mut Scratch) {
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
fn camera_packet(setup: &Setup, px: Pixel, s: &mut Scratch, first: usize, m: usize) {
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
fn visit(setup: &Setup, px: Pixel, s: &mut Scratch, ray: &Ray, hit: Hit, path: Path, bounces: usize) -> u64 {
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
fn end_path(
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

/// Light the waiting ends: for each light in turn, each end's light samples, their shadow
/// rays traced by packets, and the end's share added to its estimate; then each estimate's
/// visible fraction. The per-end arithmetic runs in vector lanes. Returns the shadow rays
/// traced.
#[inline(always)]
fn light_ends(setup: &Setup, px: Pixel, s: &mut Scratch) -> u64 {
    let Setup { scene, options: o, lights, keys, plans, .. } = *setup;
    let (ends, m) = (&s.ends, s.ends.len);
    if m == 0 {
        return 0;
    }
    if o.mode == Mode::Obscurance {
        return obscure_ends(setup, px, s);
    }
    let mut origin = [ZEROS; 3];
    for k in 0..m {
        set_lane(&mut origin, k, Scene::offset(lane(&ends.position, k), lane(&ends.normal, k)));
    }
    let mut traced = 0;
    let mut visible = [0.0; WIDTH];
    for (l, p) in lights.iter().enumerate() {
        let at = Lighting { scene, ends, origin: &origin, normal: p.normal, direct: o.mode == Mode::Direct };
        let mut sums = Sums::default();
        for k in 0..m {
            sums.unoccluded[k] = match o.mode {
                Mode::Visibility => unoccluded(p, lane(&ends.position, k), lane(&ends.normal, k)),
                Mode::Direct | Mode::Obscurance | Mode::Path { .. } => 1.0,
            };
        }
        if o.pattern == Pattern::PerPixel && o.n == 1 {
            // one sample per end (Cook's pairing of a pixel's samples): end k's in lane k, a
            // rejected or unlit one a dead lane
            let (dealt, points) = (&s.shared[l], &s.shared_points[l]);
            for k in 0..m {
                let y = points.get(dealt.start(ends.estimate[k] as usize, 1));
                let kept = sums.unoccluded[k] > 0.0 && y.is_some();
                let y = y.unwrap_or(LightPoint { position: DVec3::ZERO, weight: 0.0 });
                sums.accepted[k] = u32::from(kept);
                sums.weight[k] = if kept { y.weight } else { 0.0 };
                s.shadows.set(k, k, y.position, y.weight, kept);
            }
            s.shadows.len = m;
        } else {
            for k in 0..m {
                let e = ends.estimate[k] as usize;
                if sums.unoccluded[k] <= 0.0 {
                    continue;
                }
                let (points, range) = match o.pattern {
                    Pattern::PerEstimate => {
                        let (dims, key) = (p.light.dims(), keys.light.derive(px.index).derive(l as u64));
                        match &o.pixels {
                            Some(pixels) => light_samples(pixels, px, e, l, o.n, dims, &mut s.light),
                            None => {
                                s.light.resize(o.n * dims, 0.0);
                                if let Err(e) = plans.light[l].fill(key.derive(e as u64), &mut s.light) {
                                    s.failed.get_or_insert(e);
                                }
                            }
                        }
                        s.light_points.fill(&p.light, &s.light);
                        (&s.light_points, 0..o.n)
                    }
                    Pattern::PerPixel => {
                        let b = s.shared[l].start(e, o.n);
                        (&s.shared_points[l], b..b + o.n)
                    }
                };
                for i in range {
                    let Some(y) = points.get(i) else { continue };
                    sums.accepted[k] += 1;
                    sums.weight[k] += y.weight;
                    s.shadows.push(k, y.position, y.weight);
                    if s.shadows.len == WIDTH {
                        traced += s.shadows.trace(&at, &mut sums);
                    }
                }
            }
        }
        traced += s.shadows.trace(&at, &mut sums);
        let mut share = [ZEROS; 3];
        for (k, v) in visible[..m].iter_mut().enumerate() {
            let fraction = sums.seen[k] / sums.weight[k];
            *v += if sums.accepted[k] > 0 { fraction } else { 0.0 };
            let integral = match o.mode {
                Mode::Visibility => sums.unoccluded[k] * fraction,
                Mode::Direct | Mode::Obscurance | Mode::Path { .. } => sums.shade[k] / sums.accepted[k] as f64,
            };
            set_lane(&mut share, k, lane(&ends.albedo, k) / PI * p.light.radiance * p.area * integral);
        }
        for k in (0..m).filter(|&k| sums.accepted[k] > 0) {
            s.radiance[ends.estimate[k] as usize] += lane(&share, k);
        }
    }
    // a scene without lights is all "visible" (nothing to shadow)
    for v in &mut visible[..m] {
        *v = if lights.is_empty() { 1.0 } else { *v / lights.len() as f64 };
    }
    for (&e, &v) in ends.estimate[..m].iter().zip(&visible) {
        s.visible[e as usize] += v;
    }
    s.ends.len = 0;
    traced
}

/// The obscurance of the waiting ends (see the module's documentation): per end, its
/// estimate's n directions traced together; the end's estimate gains albedo x W and its
/// visible channel W. Returns the rays traced.
fn obscure_ends(setup: &Setup, px: Pixel, s: &mut Scratch) -> u64 {
    let Setup { scene, options: o, keys, plans, .. } = *setup;
    let m = s.ends.len;
    for k in 0..m {
        let e = s.ends.estimate[k] as usize;
        let (x, normal) = (lane(&s.ends.position, k), lane(&s.ends.normal, k));
        match &o.pixels {
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

/// Estimate `e`'s `n` samples (`dims` values each) of light `l` from a pixel sampler, laid
/// out as [`pixel_dims`] says, into `out`.
fn light_samples(p: &samplab::pixel::Pixels, px: Pixel, e: usize, l: usize, n: usize, dims: usize, out: &mut Vec<f64>) {
    out.clear();
    for j in 0..n {
        let first = FIRST_LIGHT_DIM + 2 * (l * n + j) as u32;
        out.extend((first..first + dims as u32).map(|d| p.sample(px.at(), px.frame, e as u32, d)));
    }
}
