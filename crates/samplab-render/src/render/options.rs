//! The checks of a render's options and the plans of its samplers, made once before any
//! pixel: counts, the tile of interleaved sampling, a pixel sampler's film.

use super::{MAX_SIDE, Mode, Options, Pattern, Sampling, Strategies, pixel_dims};
use crate::error::{Error, Result, setting};
use crate::filter::Footprint;
use crate::scene::Scene;
use samplab::sampler::{Plan, Sampler};
use samplab::seed::Seed;

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
            sampling: Sampling::Strategies(Box::new(Strategies {
                light: samplab::sampler::build(light)?,
                area: sobol()?,
                lens: sobol()?,
                time: sobol()?,
                gloss: sobol()?,
                pattern: Pattern::PerEstimate,
                interleave: None,
            })),
            n,
            spp: 1,
            mode: Mode::Visibility,
            footprint: Footprint::Centre,
            disk_map: None,
            range: 1.0,
            width,
            height,
            seed: Seed::DEFAULT,
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
            o.sampling =
                Sampling::Pixels { sampler: Box::new(samplab::pixel::prepare("sobol", film, o.seed)?), frame: 0 };
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
    pub(super) fn plans(&self, scene: &Scene) -> Result<Plans> {
        if [self.width, self.height].iter().any(|&v| v == 0 || v > MAX_SIDE) {
            let size = format!("{}x{}", self.width, self.height);
            return Err(setting("res", size, format!("each side must be in 1..={MAX_SIDE}")));
        }
        for (name, v, what) in [("n", self.n, "light samples per estimate"), ("spp", self.spp, "estimates per pixel")] {
            if v == 0 {
                return Err(setting(name, v, format!("{what} must be at least 1")));
            }
        }
        let per_pattern = match self.pattern() {
            Pattern::PerEstimate => self.n,
            Pattern::PerPixel => {
                self.n.checked_mul(self.spp).ok_or_else(|| setting("spp", self.spp, "n x spp overflows"))?
            }
        };
        if self.mode == Mode::Obscurance {
            if !(self.range.is_finite() && self.range > 0.0) {
                return Err(setting("range", self.range, "the obscurance range must be a positive number"));
            }
            if self.pattern() == Pattern::PerPixel {
                return Err(setting("pattern", "pixel", "obscurance takes a pattern per estimate"));
            }
        }
        if let Mode::Path { max_depth } = self.mode {
            crate::path::check_depth(max_depth as usize)?;
            if self.pixel_sampler().is_none() {
                return Err(setting("pixel_sampler", "none", "path mode draws every dimension from a pixel sampler"));
            }
        }
        let s = match &self.sampling {
            Sampling::Pixels { sampler, .. } => return self.pixel_sampler_plans(sampler, scene),
            Sampling::Strategies(s) => s,
        };
        let light = if self.mode == Mode::Obscurance {
            vec![s.light.plan(self.n, 2)?]
        } else {
            scene.lights.iter().map(|l| s.light.plan(per_pattern, l.dims())).collect::<samplab::Result<_>>()?
        };
        let mut pixel = None;
        if self.footprint.spreads() {
            if s.interleave.is_none() {
                pixel = Some(s.area.plan(self.spp, 2)?);
            }
        } else if let Some((w, h)) = s.interleave {
            let reason = "interleaved sampling spreads samples over pixel areas: it needs the area footprint";
            return Err(setting("interleave", format!("{w}x{h}"), reason));
        }
        Ok(Plans {
            light,
            pixel,
            tile: self.tile(s)?,
            lens: plan_if(scene.camera.aperture > 0.0, &s.lens, self.spp, 2)?,
            time: plan_if(scene.moving(), &s.time, self.spp, 1)?,
            gloss: plan_if(scene.glossy(), &s.gloss, self.spp, 2)?,
        })
    }
}

impl Options {
    /// The checks of a render whose every dimension comes from the pixel sampler `p`; no
    /// strategy is planned.
    pub(super) fn pixel_sampler_plans(&self, p: &samplab::pixel::Pixels, scene: &Scene) -> Result<Plans> {
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
pub(super) fn plan_if(on: bool, sampler: &Sampler, n: usize, dims: usize) -> samplab::Result<Option<Plan>> {
    on.then(|| sampler.plan(n, dims)).transpose()
}

/// The render's samplers planned for their counts (None where the scene needs none).
pub(super) struct Plans {
    /// Per light (one for obscurance directions): n points, or n x spp for patterns per pixel.
    pub(super) light: Vec<Plan>,
    /// Over the pixel area, without interleaving.
    pub(super) pixel: Option<Plan>,
    /// The interleaving tile, drawn once.
    pub(super) tile: Option<Tile>,
    pub(super) lens: Option<Plan>,
    pub(super) time: Option<Plan>,
    pub(super) gloss: Option<Plan>,
}

/// The largest interleaving tile side, in pixels.
pub const MAX_TILE: usize = 64;

/// An interleaving tile: per pixel cell (row-major), its spp points in pixel coordinates.
pub(super) struct Tile {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) spp: usize,
    pub(super) points: Vec<f64>,
}

impl Tile {
    /// The points of pixel (col, row).
    pub(super) fn cell(&self, col: usize, row: usize) -> &[f64] {
        let c = (row % self.height) * self.width + col % self.width;
        &self.points[2 * self.spp * c..2 * self.spp * (c + 1)]
    }
}

impl Options {
    /// The interleaving tile of the strategies `s`, its pattern drawn once from the pixel
    /// strategy (None without interleaving).
    ///
    /// # Errors
    /// A tile side out of 1..=[`MAX_TILE`], or a pattern that does not put exactly `spp`
    /// points in every pixel of the tile.
    pub(super) fn tile(&self, s: &Strategies) -> Result<Option<Tile>> {
        let Some((width, height)) = s.interleave else { return Ok(None) };
        if !(1..=MAX_TILE).contains(&width) || !(1..=MAX_TILE).contains(&height) {
            return Err(setting(
                "interleave",
                format!("{width}x{height}"),
                format!("each side must be in 1..={MAX_TILE}"),
            ));
        }
        let cells = width * height;
        let total = self.spp * cells;
        let pattern = s.area.plan(total, 2)?.generate(self.seed.derive_str("pixel"))?.into_vec();
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
            return Err(setting("area_sampler", s.area.spec(), reason));
        }
        Ok(Some(Tile { width, height, spp: self.spp, points: by_cell.concat() }))
    }
}
