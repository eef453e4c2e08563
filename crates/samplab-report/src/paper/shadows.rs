//! What the rendering experiments share: references, errors over seeds, and images.

use std::sync::atomic::AtomicBool;

use samplab::progress::Progress;
use samplab::seed::Seed;
use samplab_render::light::DiskMap;
use samplab_render::scenes::{LightKind, builtin};
use samplab_render::{Errors, Footprint, Image, Mode, Options, Pattern, Sampling, Scene, Strategies, render};

use crate::{Error, Figure};

/// One rendering configuration of an experiment.
#[derive(Clone, Copy)]
pub(crate) struct Setup<'a> {
    /// The run's stop flag, which every render polls (a reference at full scale takes
    /// minutes).
    pub stop: &'a AtomicBool,
    pub scene: &'a Scene,
    pub size: (usize, usize),
    pub mode: Mode,
    pub footprint: Footprint,
    pub pattern: Pattern,
    pub disk_map: DiskMap,
    /// Strategy over the pixel area (area footprint only).
    pub pixel: &'a str,
    /// Interleave the pixel strategy over tiles of (w, h) pixels (area footprint only).
    pub interleave: Option<(usize, usize)>,
    /// Strategy over the lens (scenes with an aperture only).
    pub lens: &'a str,
    /// Strategy over the shutter interval (scenes that move only).
    pub time: &'a str,
    /// Strategy over the glossy lobe (scenes with an imperfect mirror only).
    pub gloss: &'a str,
    /// Obscurance mode: the distance beyond which a surface no longer obscures.
    pub range: f64,
    /// Compare images as displayed (channels clamped to [0, 1]), as Shirley 1991 does.
    pub displayed: bool,
}

impl<'a> Setup<'a> {
    /// Visibility mode through pixel centres (Ramamoorthi et al. 2012, section 7).
    pub fn visibility(stop: &'a AtomicBool, scene: &'a Scene, size: (usize, usize), disk_map: DiskMap) -> Setup<'a> {
        Setup {
            stop,
            scene,
            size,
            mode: Mode::Visibility,
            footprint: Footprint::Centre,
            pattern: Pattern::PerEstimate,
            disk_map,
            pixel: "sobol.owen",
            interleave: None,
            lens: "sobol.owen",
            time: "sobol.owen",
            gloss: "sobol.owen",
            range: 1.0,
            displayed: false,
        }
    }

    fn options(&self, light: &str, n: usize, spp: usize, seed: Seed) -> Result<Options, Error> {
        let build = |spec: &str| samplab::sampler::build(spec).map_err(Error::from);
        let mut o = Options::new("sobol.owen", n, self.size.0, self.size.1).map_err(render_error)?;
        o.sampling = Sampling::Strategies(Box::new(Strategies {
            light: build(light)?,
            area: build(self.pixel)?,
            lens: build(self.lens)?,
            time: build(self.time)?,
            gloss: build(self.gloss)?,
            pattern: self.pattern,
            interleave: self.interleave,
        }));
        o.spp = spp;
        o.mode = self.mode;
        o.footprint = self.footprint;
        o.range = self.range;
        o.disk_map = Some(self.disk_map);
        o.seed = seed;
        Ok(o)
    }

    /// Render with `light` x `n` light samples and `spp` estimates per pixel.
    pub fn render(&self, light: &str, n: usize, spp: usize, seed: Seed) -> Result<Image, Error> {
        let o = self.options(light, n, spp, seed)?;
        Ok(render(self.scene, &o, &Progress::until(self.stop)).map_err(render_error)?.image)
    }

    /// A converged reference: Owen-scrambled Sobol' with `n` light samples and `spp`
    /// estimates ([`Options::converged`]).
    pub fn reference(&self, n: usize, spp: usize, seed: Seed) -> Result<Image, Error> {
        self.converged("sobol.owen", n, spp, seed)
    }

    /// This set-up rendered converged ([`Options::converged`]): `light` x `n` light samples,
    /// Owen-scrambled Sobol' over the pixel, lens, time and gloss, one pattern per estimate.
    pub fn converged(&self, light: &str, n: usize, spp: usize, seed: Seed) -> Result<Image, Error> {
        let o = self.options(light, n, spp, seed)?.converged(light, n, spp).map_err(render_error)?;
        Ok(render(self.scene, &o, &Progress::until(self.stop)).map_err(render_error)?.image)
    }

    /// Errors against `reference` of each of `seeds` renders (seed k derived from `seed`).
    pub fn errors_each(
        &self,
        reference: &Image,
        light: &str,
        n: usize,
        spp: usize,
        seeds: u64,
        seed: Seed,
    ) -> Result<Vec<Errors>, Error> {
        (0..seeds)
            .map(|s| {
                let img = self.render(light, n, spp, seed.derive(s))?;
                let e = if self.displayed {
                    img.clamped().errors(&reference.clamped(), false)
                } else {
                    img.errors(reference, false)
                };
                e.map_err(render_error)
            })
            .collect()
    }
}

/// A built-in scene (`kind`: its light, None for the scene's own).
pub(crate) fn scene(name: &str, kind: Option<LightKind>) -> Result<Scene, Error> {
    builtin(name, kind).map_err(render_error)
}

/// A renderer's error as the report's (a stop stays a stop).
pub(crate) fn render_error(e: samplab_render::Error) -> Error {
    match e {
        samplab_render::Error::Samplab(e) => Error::Samplab(e),
        e => Error::Render(e),
    }
}

/// The mean MSE of several renders and its standard error.
pub(crate) fn mse_estimate(all: &[Errors]) -> crate::criteria::Estimate {
    crate::criteria::Estimate::mean_of(&samplab::stats::Summary::of(&all.iter().map(|e| e.mse).collect::<Vec<_>>()))
}

/// Field-wise mean of several error summaries.
pub(crate) fn mean(all: &[Errors]) -> Errors {
    let m = |f: fn(&Errors) -> f64| all.iter().map(f).sum::<f64>() / all.len() as f64;
    Errors {
        pixels: all[0].pixels,
        mse: m(|e| e.mse),
        rmse: m(|e| e.rmse),
        relative: m(|e| e.relative),
        mean_abs: m(|e| e.mean_abs),
        sd_abs: m(|e| e.sd_abs),
        max_abs: m(|e| e.max_abs),
        mean_signed: m(|e| e.mean_signed),
    }
}

fn png(img: &samplab_render::image::Srgb8) -> Result<Vec<u8>, Error> {
    img.png().map_err(|e| Error::Plot(e.to_string()))
}

/// A rendered image as a figure (sRGB PNG).
pub(crate) fn picture(id: &str, caption: &str, img: &Image) -> Result<Figure, Error> {
    Ok(Figure::picture(id, caption, png(&img.to_srgb())?))
}

/// A rendered image as a figure, its values stretched linearly from `[lo, hi]` to black
/// and white before the sRGB curve: for quantities such as obscurances that fill only the
/// top of [0, 1] and would show nearly white.
pub(crate) fn picture_stretched(id: &str, caption: &str, img: &Image, (lo, hi): (f32, f32)) -> Result<Figure, Error> {
    let span = (hi - lo).max(f32::EPSILON);
    let rgb = img.rgb.iter().map(|&v| ((v - lo) / span).clamp(0.0, 1.0)).collect();
    picture(id, caption, &Image { rgb, visibility: None, ..*img })
}

/// The least and greatest value of an image's channels.
pub(crate) fn value_range(img: &Image) -> (f32, f32) {
    img.rgb.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)))
}

/// A signed error image (red: too bright, green: too dark, times `scale`) as a figure.
pub(crate) fn error_picture(
    id: &str,
    caption: &str,
    img: &Image,
    reference: &Image,
    scale: f64,
) -> Result<Figure, Error> {
    Ok(Figure::picture(id, caption, png(&img.error_image(reference, scale).map_err(render_error)?)?))
}
