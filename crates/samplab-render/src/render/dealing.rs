//! Dealing each pixel its samples: the strategies' patterns (per estimate or per pixel,
//! interleaved over a tile) or a pixel sampler's dimensions, into per-thread scratch.

use super::integrator::Path;
use super::lighting::{Ends, Shadows};
use super::{FIRST_LIGHT_DIM, Pattern, Pixel, Setup};
use crate::geometry::Ray;
use crate::light::LightPoints;
use crate::packet::Packet;
use crate::scene::Hit;
use glam::DVec3;
use samplab::sampler::Plan;
use samplab::seed::{Rng, Seed, shuffle};

/// Per-thread scratch buffers.
#[derive(Default)]
pub(super) struct Scratch {
    /// The first fill of this pixel that failed (a Poisson-disk sampler that could not place
    /// its points for a seed): the render stops with it after the pixel.
    pub(super) failed: Option<samplab::Error>,
    pub(super) pixel: Vec<f64>,
    pub(super) lens: Dealt,
    pub(super) time: Dealt,
    pub(super) gloss: Dealt,
    /// An estimate's light pattern and its points on the light (per-estimate patterns).
    pub(super) light: Vec<f64>,
    pub(super) light_points: LightPoints,
    /// Per light: the pixel's whole pattern and its points on the light (per-pixel patterns).
    pub(super) shared: Vec<Dealt>,
    pub(super) shared_points: Vec<LightPoints>,
    /// Per estimate: the radiance gathered so far, and the visible fraction of the lights
    /// (1 where a light is seen directly).
    pub(super) radiance: Vec<DVec3>,
    pub(super) visible: Vec<f64>,
    /// Per estimate, when a material is glossy: the strategy's gloss sample until the first
    /// glossy bounce takes it, and independent samples for later glossy bounces.
    pub(super) gloss_u: Vec<Option<[f64; 2]>>,
    pub(super) later: Vec<Option<Rng>>,
    /// A packet of camera rays.
    pub(super) camera: Packet,
    /// The reflected rays of the current wave and their paths, and the next wave's.
    pub(super) rays: Vec<Ray>,
    pub(super) paths: Vec<Path>,
    pub(super) next: Vec<Ray>,
    pub(super) next_paths: Vec<Path>,
    pub(super) hits: Vec<Hit>,
    /// Paths ended on a diffuse surface, waiting for their light samples.
    pub(super) ends: Ends,
    /// Shadow rays waiting to be traced.
    pub(super) shadows: Shadows,
    /// Obscurance rays of one end and their hits.
    pub(super) probes: Vec<Ray>,
    pub(super) probe_hits: Vec<Hit>,
    /// Path mode's buffers.
    pub(super) path: crate::path::Scratch,
}

/// A pixel's pattern of `spp` blocks and the random order they are dealt to its estimates
/// in, so that strategies built alike for different dimensions (Sobol' over the pixel and
/// over the lens, say) are not correlated ("padding").
#[derive(Default)]
pub(super) struct Dealt {
    pub(super) points: Vec<f64>,
    pub(super) order: Vec<u32>,
}

impl Dealt {
    /// Fill with the `spp` blocks of `plan` (one pattern, seeded by `key`), and draw the
    /// order from `order_key`.
    pub(super) fn deal(&mut self, plan: &Plan, spp: usize, key: Seed, order_key: Seed) -> samplab::Result<()> {
        self.points.resize(plan.n() * plan.dims(), 0.0);
        plan.fill(key, &mut self.points)?;
        self.order.clear();
        self.order.extend(0..spp as u32);
        shuffle(&mut order_key.rng(), &mut self.order);
        Ok(())
    }

    /// Where estimate e's block starts, in blocks of `len`.
    pub(super) fn start(&self, e: usize, len: usize) -> usize {
        self.order[e] as usize * len
    }

    /// Fill with dimensions `first .. first + len` of the pixel's `spp` samples from the
    /// pixel sampler `p`, in their own order.
    pub(super) fn keyed(&mut self, p: &samplab::pixel::Pixels, px: Pixel, spp: usize, first: u32, len: u32) {
        self.points.clear();
        for e in 0..spp as u32 {
            self.points.extend((first..first + len).map(|d| p.sample(px.at(), px.frame, e, d)));
        }
        self.order.clear();
        self.order.extend(0..spp as u32);
    }

    /// Estimate e's block of `len` values.
    pub(super) fn block(&self, e: usize, len: usize) -> &[f64] {
        let b = self.start(e, len);
        &self.points[b..b + len]
    }
}

/// Sub-seeds of each purpose.
pub(super) struct Keys {
    pub(super) pixel: Seed,
    pub(super) lens: Seed,
    pub(super) time: Seed,
    pub(super) gloss: Seed,
    pub(super) light: Seed,
    pub(super) deal: Seed,
}

impl Keys {
    pub(super) fn new(seed: Seed) -> Keys {
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

/// Draw the pixel's patterns: pixel area, lens, time, gloss, and the per-pixel light
/// patterns with their points on the lights.
#[inline(always)]
pub(super) fn deal(setup: &Setup, px: Pixel, s: &mut Scratch) {
    if let Err(e) = try_deal(setup, px, s) {
        s.failed.get_or_insert(e);
    }
}

pub(super) fn try_deal(setup: &Setup, px: Pixel, s: &mut Scratch) -> samplab::Result<()> {
    let Setup { options: o, lights, keys, plans, .. } = *setup;
    let spp = o.spp;
    if let Some((p, _)) = o.pixel_sampler() {
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
    if o.pattern() == Pattern::PerPixel {
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

/// Estimate `e`'s `n` samples (`dims` values each) of light `l` from a pixel sampler, laid
/// out as [`pixel_dims`] says, into `out`.
pub(super) fn light_samples(
    p: &samplab::pixel::Pixels,
    px: Pixel,
    e: usize,
    l: usize,
    n: usize,
    dims: usize,
    out: &mut Vec<f64>,
) {
    out.clear();
    for j in 0..n {
        let first = FIRST_LIGHT_DIM + 2 * (l * n + j) as u32;
        out.extend((first..first + dims as u32).map(|d| p.sample(px.at(), px.frame, e as u32, d)));
    }
}
