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
//! ([`samplab::pixel`], [`Sampling::Pixels`]), as a production renderer draws them: estimate
//! e of pixel (x, y) is sample e, and its dimensions are laid out as [`pixel_dims`] says.

use crate::error::Result;
use crate::filter::Footprint;
use crate::image::Image;
use crate::light::{DiskMap, Light, LightPoint};
use crate::scene::Scene;
use dealing::{Keys, Scratch};
use glam::DVec3;
use integrator::render_pixel;
use lighting::quadrature;
use options::Plans;
use rayon::prelude::*;
use samplab::progress::Progress;
use samplab::sampler::Sampler;
use samplab::seed::Seed;
use samplab::simd::wide;

mod dealing;
mod integrator;
mod lighting;
mod options;

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
    /// pixel sampler ([`Sampling::Pixels`]).
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
    /// Where each estimate's samples come from.
    pub sampling: Sampling,
    /// Light samples per estimate and light.
    pub n: usize,
    /// Secondary estimates per pixel.
    pub spp: usize,
    /// Estimator.
    pub mode: Mode,
    /// Pixel centre or area.
    pub footprint: Footprint,
    /// Disk map override for every disk light (None: each light's own).
    pub disk_map: Option<DiskMap>,
    /// Obscurance mode: the distance beyond which a surface no longer obscures.
    pub range: f64,
    /// Image width.
    pub width: usize,
    /// Image height.
    pub height: usize,
    /// Seed of every random choice.
    pub seed: Seed,
}

/// Where each estimate's samples come from: a point-set strategy per purpose, or one pixel
/// sampler for every dimension, as a production renderer draws them (the two exclude each
/// other).
#[derive(Debug)]
#[non_exhaustive]
pub enum Sampling {
    /// A strategy per purpose.
    Strategies(Box<Strategies>),
    /// A pixel sampler that draws every dimension of every estimate, prepared for this
    /// image, `spp` and at least [`pixel_dims`] dimensions (patterns per estimate, no
    /// interleaving).
    Pixels {
        /// The prepared pixel sampler.
        sampler: Box<samplab::pixel::Pixels>,
        /// The frame it draws (an animation's frame number: each frame its own samples, as
        /// the sampler decorrelates them).
        frame: u32,
    },
}

/// A point-set strategy per purpose of a render's samples.
#[derive(Debug)]
pub struct Strategies {
    /// The strategy of the light samples.
    pub light: Sampler,
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
    /// Interleaved pixel sampling over tiles of (w, h) pixels (area footprint); None: a
    /// pattern per pixel.
    pub interleave: Option<(usize, usize)>,
}

impl Options {
    /// The strategies, where the render draws from them.
    pub fn strategies(&self) -> Option<&Strategies> {
        match &self.sampling {
            Sampling::Strategies(s) => Some(s),
            Sampling::Pixels { .. } => None,
        }
    }

    /// The strategies, to change them (None where a pixel sampler draws every dimension).
    pub fn strategies_mut(&mut self) -> Option<&mut Strategies> {
        match &mut self.sampling {
            Sampling::Strategies(s) => Some(s),
            Sampling::Pixels { .. } => None,
        }
    }

    /// The pixel sampler and its frame, where one draws every dimension.
    pub fn pixel_sampler(&self) -> Option<(&samplab::pixel::Pixels, u32)> {
        match &self.sampling {
            Sampling::Pixels { sampler, frame } => Some((sampler, *frame)),
            Sampling::Strategies(_) => None,
        }
    }

    /// The spec of what draws the light samples: the light strategy, or the pixel sampler.
    pub fn light_source(&self) -> &str {
        match &self.sampling {
            Sampling::Strategies(s) => s.light.spec(),
            Sampling::Pixels { sampler, .. } => sampler.spec(),
        }
    }

    /// The grouping of light samples (per estimate where a pixel sampler draws them).
    pub fn pattern(&self) -> Pattern {
        self.strategies().map_or(Pattern::PerEstimate, |s| s.pattern)
    }
}

/// The dimensions of an estimate drawn from a pixel sampler ([`Sampling::Pixels`]): 0-1 the
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

/// One light prepared for a render.
struct Prepared {
    light: Light,
    /// Its emitting side's unit normal and its area, computed once.
    normal: Option<DVec3>,
    area: f64,
    /// Midpoint-rule points for the unoccluded shading (visibility mode).
    quadrature: Vec<LightPoint>,
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
    let animation_frame = options.pixel_sampler().map_or(0, |(_, frame)| frame);
    let path = options.pixel_sampler().filter(|_| matches!(options.mode, Mode::Path { .. })).map(|(pixels, _)| {
        crate::path::Context {
            scene,
            frame: &frame,
            pixels,
            emitters: &emitters,
            width: w,
            height: h,
            spp: options.spp,
            max_depth: crate::path::Context::depth(options.mode),
            animation_frame,
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
    let light_points = if options.pattern() == Pattern::PerPixel { n * spp } else { n };
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
                let pixel = Pixel { index: (row * w + col) as u64, col, row, frame: animation_frame };
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
