//! Render settings as words and numbers, what the CLI's flags and the Python package's
//! keywords carry, turned into [`Options`] in one place (one set of defaults, one set of
//! names and errors). A setting that is wrong is a `samplab::Error::Setting` named as here
//! (`mode`, `pixel_sampler`, ...); front ends map the names to their own flags.

use std::path::Path;

use samplab::Seed;

use crate::error::Result;
use crate::filter::Footprint;
use crate::light::DiskMap;
use crate::mitsuba::Paths;
use crate::render::{Mode, Options, Pattern};
use crate::scene::Scene;
use crate::scenes::{LightKind, builtin};

/// The default light sampler.
pub const SAMPLER: &str = "jitter";
/// The default strategy over the pixel area, the lens, the shutter and the glossy lobe (a
/// point-set sampler).
pub const SECONDARY: &str = "sobol.owen";
/// The default light samples per estimate.
pub const N: usize = 16;
/// The default most segments of a path in path mode (pbrt-v4's default `maxdepth`).
pub const MAX_DEPTH: usize = 5;
/// The pixel sampler path mode draws from when `pixel_sampler` names none (Burley's
/// shuffled Owen-scrambled Sobol' per pixel).
pub const PATH_SAMPLER: &str = "sobol";
/// Estimators, by name (path mode's depth is set by `max_depth`).
pub const MODES: [(&str, Mode); 4] = [
    ("visibility", Mode::Visibility),
    ("direct", Mode::Direct),
    ("obscurance", Mode::Obscurance),
    ("path", Mode::Path { max_depth: MAX_DEPTH as u32 }),
];
/// Pixel footprints, by name.
pub const FOOTPRINTS: [(&str, Footprint); 4] = [
    ("center", Footprint::Centre),
    ("centre", Footprint::Centre),
    ("area", Footprint::Area),
    ("gaussian", Footprint::MITSUBA),
];
/// Light-sample groupings, by name.
pub const PATTERNS: [(&str, Pattern); 2] = [("estimate", Pattern::PerEstimate), ("pixel", Pattern::PerPixel)];

/// Everything a render takes besides the scene, in words and numbers (in JSON, every field
/// optional: a missing one takes its default).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// Light sampler spec.
    pub sampler: String,
    /// Light samples per estimate and light.
    pub n: usize,
    /// Secondary estimates per pixel.
    pub spp: usize,
    /// `visibility`, `direct`, `obscurance` or `path`.
    pub mode: String,
    /// Path mode: the most segments of a path (None: the scene's, a Mitsuba scene's `path`
    /// integrator's `max_depth`, else [`MAX_DEPTH`]).
    pub max_depth: Option<usize>,
    /// `center`, `area` or `gaussian` (None: the scene's, a Mitsuba film's reconstruction
    /// filter, else `center`).
    pub pixel: Option<String>,
    /// Strategy over the pixel area (a point-set sampler: `spp` points per pixel).
    pub area_sampler: String,
    /// A pixel sampler (any name `samplab pixels` takes: `zsobol`, `sobol`, `sobol.owen`,
    /// ...) that draws every dimension of every estimate in place of the strategies; None:
    /// none, except in path mode ([`PATH_SAMPLER`]).
    pub pixel_sampler: Option<String>,
    /// Strategy over the lens.
    pub lens_sampler: String,
    /// Strategy over the shutter.
    pub time_sampler: String,
    /// Strategy over the glossy lobe.
    pub gloss_sampler: String,
    /// `estimate` or `pixel`.
    pub pattern: String,
    /// `concentric`, `polar` or `reject` for every disk light (None: each light's own).
    pub disk_map: Option<String>,
    /// Obscurance range.
    pub range: f64,
    /// Interleaving tile (width, height).
    pub interleave: Option<(usize, usize)>,
    /// Image size (None: the scene's).
    pub res: Option<(usize, usize)>,
    /// Seed.
    pub seed: u64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            sampler: SAMPLER.into(),
            n: N,
            spp: 1,
            mode: "visibility".into(),
            max_depth: None,
            pixel: None,
            area_sampler: SECONDARY.into(),
            pixel_sampler: None,
            lens_sampler: SECONDARY.into(),
            time_sampler: SECONDARY.into(),
            gloss_sampler: SECONDARY.into(),
            pattern: "estimate".into(),
            disk_map: None,
            range: 1.0,
            interleave: None,
            res: None,
            seed: Seed::DEFAULT.0,
        }
    }
}

/// The value `table` gives `word` (case-insensitive), or a setting error listing the words.
fn choose<T: Copy>(name: &'static str, word: &str, table: &[(&str, T)]) -> samplab::Result<T> {
    table.iter().find(|(w, _)| w.eq_ignore_ascii_case(word)).map(|(_, v)| *v).ok_or_else(|| samplab::Error::Setting {
        name,
        value: word.to_string(),
        reason: format!("unknown value (one of: {})", table.iter().map(|(w, _)| *w).collect::<Vec<_>>().join(", ")),
    })
}

/// The sampler `spec` for the setting `name`, its error named by the setting.
fn sampler(name: &'static str, spec: &str) -> samplab::Result<samplab::Sampler> {
    samplab::sampler::build(spec).map_err(|e| samplab::Error::Setting {
        name,
        value: spec.to_string(),
        reason: e.to_string(),
    })
}

impl Settings {
    /// The estimator, with path mode's depth: the one set, else the scene's, else
    /// [`MAX_DEPTH`].
    fn mode(&self, scene: &Scene) -> samplab::Result<Mode> {
        Ok(match choose("mode", &self.mode, &MODES)? {
            Mode::Path { .. } => {
                let depth = self.max_depth.or(scene.max_depth).unwrap_or(MAX_DEPTH);
                crate::path::check_depth(depth)?;
                Mode::Path { max_depth: depth as u32 }
            }
            mode => mode,
        })
    }

    /// The pixel sampler `pixel_sampler` names, prepared for the render; in path mode
    /// [`PATH_SAMPLER`] where it names none. A point-set sampler that is no sequence is
    /// refused with a pointer to `area_sampler`, the strategy over the pixel area.
    fn pixels(&self, scene: &Scene, width: usize, height: usize) -> Result<Option<samplab::pixel::Pixels>> {
        let mode = self.mode(scene)?;
        let spec = match (&self.pixel_sampler, mode) {
            (Some(spec), _) => spec.as_str(),
            (None, Mode::Path { .. }) => PATH_SAMPLER,
            (None, _) => return Ok(None),
        };
        let side = |v: usize| u32::try_from(v).unwrap_or(u32::MAX);
        let film = samplab::pixel::Film {
            width: side(width),
            height: side(height),
            spp: side(self.spp),
            dims: side(crate::render::pixel_dims(self.n, scene.lights.len(), mode)),
        };
        let prepared = samplab::pixel::prepare(spec, film, Seed(self.seed));
        Ok(Some(prepared.map_err(|e| {
            let area = match e {
                samplab::Error::Infeasible { .. } if samplab::sampler::build(spec).is_ok() => {
                    " (the strategy over the pixel area alone is the area sampler)"
                }
                _ => "",
            };
            samplab::Error::Setting { name: "pixel_sampler", value: spec.to_string(), reason: format!("{e}{area}") }
        })?))
    }

    /// Refuse a setting moved from its default where the render would not read it: the
    /// depth outside path mode, the range outside obscurance, and where a pixel sampler
    /// draws every dimension (`pixels`, its spec), the strategies it replaces and, in path
    /// mode, the light samples' count. (A setting left at its default is not looked at.)
    fn unread(&self, mode: Mode, pixels: Option<&str>) -> samplab::Result<()> {
        let path = matches!(mode, Mode::Path { .. });
        let refuse =
            |name: &'static str, value: String, reason: String| Err(samplab::Error::Setting { name, value, reason });
        if let (false, Some(depth)) = (path, self.max_depth) {
            let reason = format!("read in path mode only (this render's mode is {})", self.mode);
            return refuse("max_depth", depth.to_string(), reason);
        }
        if mode != Mode::Obscurance && self.range.to_bits() != 1f64.to_bits() {
            let reason = format!("read in obscurance mode only (this render's mode is {})", self.mode);
            return refuse("range", self.range.to_string(), reason);
        }
        let Some(spec) = pixels else { return Ok(()) };
        let drawn = format!("not read: the pixel sampler {spec} draws every dimension");
        for (name, value, default) in [
            ("sampler", &self.sampler, SAMPLER),
            ("area_sampler", &self.area_sampler, SECONDARY),
            ("lens_sampler", &self.lens_sampler, SECONDARY),
            ("time_sampler", &self.time_sampler, SECONDARY),
            ("gloss_sampler", &self.gloss_sampler, SECONDARY),
        ] {
            if value != default {
                return refuse(name, value.clone(), drawn.clone());
            }
        }
        if path && self.n != N {
            return refuse("n", self.n.to_string(), format!("{drawn}, as many as the path's length needs"));
        }
        Ok(())
    }

    /// The options for rendering `scene` with these settings, every count checked.
    ///
    /// # Errors
    /// An unknown word, a sampler spec that does not parse, a setting the render would not
    /// read, or counts and sizes that [`Options::check`] refuses.
    pub fn options(&self, scene: &Scene) -> Result<Options> {
        let (width, height) = self.res.unwrap_or(scene.resolution);
        let pixels = self.pixels(scene, width, height)?;
        self.unread(self.mode(scene)?, pixels.as_ref().map(samplab::pixel::Pixels::spec))?;
        let options = Options {
            light: sampler("sampler", &self.sampler)?,
            n: self.n,
            spp: self.spp,
            mode: self.mode(scene)?,
            footprint: match &self.pixel {
                Some(word) => choose("pixel", word, &FOOTPRINTS)?,
                None => scene.footprint.unwrap_or(Footprint::Centre),
            },
            area: sampler("area_sampler", &self.area_sampler)?,
            lens: sampler("lens_sampler", &self.lens_sampler)?,
            time: sampler("time_sampler", &self.time_sampler)?,
            gloss: sampler("gloss_sampler", &self.gloss_sampler)?,
            pattern: choose("pattern", &self.pattern, &PATTERNS)?,
            disk_map: self.disk_map.as_deref().map(|m| choose("disk_map", m, &DiskMap::ALL)).transpose()?,
            range: self.range,
            interleave: self.interleave,
            width,
            height,
            seed: Seed(self.seed),
            pixels,
            frame: 0,
        };
        options.check(scene)?;
        Ok(options)
    }
}

/// The scene `name` names: a built-in (lit by `light` if given) or a Mitsuba 3 XML file
/// (whose meshes must be where `paths` allows).
///
/// # Errors
/// An unknown scene or light, a light given for a Mitsuba scene (it brings its own), or a
/// scene file that does not load.
pub fn load_scene(name: &str, light: Option<&str>, paths: Paths) -> Result<Scene> {
    let kind = light.map(LightKind::parse).transpose()?;
    if name.to_ascii_lowercase().ends_with(".xml") {
        if kind.is_some() {
            return Err(crate::error::setting(
                "light",
                light.unwrap_or_default(),
                "a light replaces a built-in scene's light; a Mitsuba scene brings its own",
            ));
        }
        return crate::mitsuba::load(Path::new(name), paths);
    }
    builtin(name, kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The setting `options` refuses for `s` on the spheres scene, if any.
    fn refused(s: &Settings) -> Option<&'static str> {
        let scene = load_scene("spheres", None, Paths::InsideScene).unwrap();
        match s.options(&scene) {
            Ok(_) => None,
            Err(crate::Error::Samplab(samplab::Error::Setting { name, .. })) => Some(name),
            Err(e) => panic!("{s:?}: not a setting error: {e}"),
        }
    }

    #[test]
    fn a_setting_the_render_would_not_read_is_refused_and_read_where_it_applies() {
        let d = || Settings { res: Some((4, 3)), ..Settings::default() };
        let path = || Settings { mode: "path".into(), ..d() };
        let zsobol = || Settings { pixel_sampler: Some("zsobol".into()), ..d() };
        for (s, unread) in [
            (Settings { max_depth: Some(3), ..d() }, "max_depth"),
            (Settings { mode: "direct".into(), range: 2.0, ..d() }, "range"),
            (Settings { range: 0.0, ..path() }, "range"),
            (Settings { n: 4, ..path() }, "n"),
            (Settings { sampler: "halton".into(), ..path() }, "sampler"),
            (Settings { gloss_sampler: "random".into(), ..path() }, "gloss_sampler"),
            (Settings { lens_sampler: "random".into(), ..zsobol() }, "lens_sampler"),
            (Settings { time_sampler: "random".into(), ..zsobol() }, "time_sampler"),
            (Settings { area_sampler: "jitter".into(), ..zsobol() }, "area_sampler"),
            (Settings { pixel_sampler: Some("jitter".into()), ..d() }, "pixel_sampler"),
            (Settings { pixel_sampler: Some("jitter".into()), ..path() }, "pixel_sampler"),
        ] {
            assert_eq!(refused(&s), Some(unread), "{s:?}");
        }
        for s in [
            d(),
            path(),
            zsobol(),
            Settings { max_depth: Some(3), ..path() },
            Settings { mode: "obscurance".into(), range: 2.0, ..d() },
            Settings { n: 4, sampler: "halton".into(), lens_sampler: "random".into(), ..d() },
            Settings { n: 4, ..zsobol() },
            Settings { area_sampler: "jitter".into(), ..d() },
            Settings { pixel_sampler: Some("sobol.owen".into()), ..d() },
            Settings { pixel_sampler: Some("halton".into()), ..path() },
            Settings { disk_map: Some("polar".into()), ..path() },
        ] {
            assert_eq!(refused(&s), None, "{s:?}");
        }
    }
}
