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
use crate::render::{Mode, Options, Pattern, Sampling, Strategies};
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

/// Everything a render takes besides the scene, in words and numbers: the one table of
/// render settings. Its fields are the CLI's flags (with their help and defaults, through
/// clap), Python's keywords and a study's keys (through serde; a missing one takes its
/// default, [`Settings::default`] being clap's defaults), and [`table`] lists them for
/// documentation. A new setting is a new field here, read by [`Settings::options`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, clap::Args)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// Strategy of the light samples (any sampler spec; see `samplab list samplers`)
    #[arg(long, default_value = SAMPLER)]
    pub sampler: String,
    /// Light samples per estimate and light
    #[arg(short, default_value_t = N)]
    pub n: usize,
    /// Secondary estimates per pixel (each one camera ray and n shadow rays per light)
    #[arg(long, default_value_t = 1)]
    pub spp: usize,
    /// visibility (Monte Carlo for visibility only), direct (full light sampling),
    /// obscurance (no lights: the sampler's n points are cosine-weighted directions) or path
    /// (path tracing with next-event estimation and MIS, as Mitsuba 3's `path`; every
    /// dimension from the pixel sampler, `sobol` by default; the light sampler, n and the
    /// other strategies do not apply)
    #[arg(long, default_value = "visibility")]
    pub mode: String,
    /// Path mode: the most segments of a path (Mitsuba's max_depth: 2 is direct lighting);
    /// default: a Mitsuba scene's `path` integrator's max_depth, else 5
    #[arg(long)]
    pub max_depth: Option<usize>,
    /// Camera rays through the pixel centre (center), over its area (area, a box filter) or
    /// over Mitsuba 3's windowed Gaussian filter (gaussian: stddev 0.5 pixel, radius 2);
    /// default: a Mitsuba scene's film filter (box: area), else center
    #[arg(long)]
    pub pixel: Option<String>,
    /// Strategy over the pixel area (spp points; any sampler spec)
    #[arg(long, default_value = SECONDARY)]
    pub area_sampler: String,
    /// A pixel sampler (any name `samplab pixels` takes: zsobol, sobol, sobol.padded,
    /// pmj02.bn, openqmc.sobolbn, a point-set sequence such as sobol.owen or halton.shift per
    /// pixel, ...) that draws every dimension of every estimate (film, lens, time, gloss,
    /// light samples) in place of the light sampler and the other strategies; default: none,
    /// and `sobol` in path mode
    #[arg(long)]
    pub pixel_sampler: Option<String>,
    /// Strategy over the lens (spp points), for scenes with an aperture
    #[arg(long, default_value = SECONDARY)]
    pub lens_sampler: String,
    /// Strategy over the shutter time (spp points), for scenes that move
    #[arg(long, default_value = SECONDARY)]
    pub time_sampler: String,
    /// Strategy over the glossy lobe (spp points), for scenes with an imperfect mirror
    #[arg(long, default_value = SECONDARY)]
    pub gloss_sampler: String,
    /// estimate: an n-point pattern per estimate; pixel: one spp x n pattern per pixel dealt out
    #[arg(long, default_value = "estimate")]
    pub pattern: String,
    /// Square-to-disk map for disk lights: concentric, polar, reject; default: each light's own
    #[arg(long)]
    pub disk_map: Option<String>,
    /// Obscurance mode: the distance beyond which a surface no longer obscures
    #[arg(long, default_value_t = 1.0)]
    pub range: f64,
    /// Interleaved sampling: one area-sampler pattern of spp x W x H points over a tile of
    /// WxH pixels, repeated over the image (needs the area pixel footprint)
    #[arg(long, value_name = "WxH", value_parser = size)]
    pub interleave: Option<(usize, usize)>,
    /// Image size WxH (default: the scene's)
    #[arg(long, value_name = "WxH", value_parser = size)]
    pub res: Option<(usize, usize)>,
    /// Seed of every random choice
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    pub seed: u64,
}

/// A size `WIDTHxHEIGHT` (e.g. `256x192`).
fn size(text: &str) -> std::result::Result<(usize, usize), String> {
    let parse = || {
        let (w, h) = text.split_once(['x', 'X'])?;
        Some((w.trim().parse().ok()?, h.trim().parse().ok()?))
    };
    parse().ok_or_else(|| format!("'{text}' is not WIDTHxHEIGHT (e.g. 256x192)"))
}

/// The settings as clap sees them: the command the flags are parsed by.
fn command() -> clap::Command {
    <Settings as clap::Args>::augment_args(clap::Command::new("settings").no_binary_name(true))
}

impl Default for Settings {
    /// Every setting at its declared default.
    ///
    /// # Panics
    /// Never: every setting has a default or is optional (a test parses none).
    fn default() -> Self {
        let matches = command().try_get_matches_from(std::iter::empty::<&str>()).expect("settings with defaults");
        <Settings as clap::FromArgMatches>::from_arg_matches(&matches).expect("defaults that parse")
    }
}

/// One setting, as the front ends document it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Described {
    /// Its name: the field, Python's keyword, a study's key.
    pub name: String,
    /// Its CLI flag (`--area-sampler`, `-n`).
    pub flag: String,
    /// Its default in words (None: optional, the scene's or none).
    pub default: Option<String>,
    /// What it does.
    pub help: String,
}

/// Every setting, in declaration order, with its flag, default and help.
pub fn table() -> Vec<Described> {
    command()
        .get_arguments()
        .map(|a| Described {
            name: a.get_id().to_string(),
            flag: a.get_long().map_or_else(|| format!("-{}", a.get_short().unwrap_or('?')), |l| format!("--{l}")),
            default: a.get_default_values().first().map(|v| v.to_string_lossy().into_owned()),
            help: a.get_help().map(ToString::to_string).unwrap_or_default(),
        })
        .collect()
}

/// Settings from named values (Python's keywords, a study's keys) over the defaults.
///
/// # Errors
/// A name that is no setting ([`samplab::Error::UnknownName`], with the closest ones), or a
/// value of the wrong type, named.
pub fn from_named(values: serde_json::Map<String, serde_json::Value>) -> samplab::Result<Settings> {
    let names: Vec<String> = table().into_iter().map(|d| d.name).collect();
    if let Some(unknown) = values.keys().find(|k| !names.contains(k)) {
        let suggestions = samplab::error::closest_names(unknown, names.iter().map(String::as_str));
        return Err(samplab::Error::UnknownName { kind: "render setting", name: unknown.clone(), suggestions });
    }
    serde_json::from_value(serde_json::Value::Object(values))
        .map_err(|e| samplab::Error::Parse { location: "render settings".into(), reason: e.to_string() })
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
        let pattern = choose("pattern", &self.pattern, &PATTERNS)?;
        let sampling = match pixels {
            Some(sampler) if pattern == Pattern::PerPixel || self.interleave.is_some() => {
                let reason = "draws each estimate's samples from its own dimensions: it takes patterns per estimate \
                              and no interleaving";
                return Err(crate::error::setting("pixel_sampler", sampler.spec(), reason));
            }
            Some(sampler) => Sampling::Pixels { sampler: Box::new(sampler), frame: 0 },
            None => Sampling::Strategies(Box::new(Strategies {
                light: sampler("sampler", &self.sampler)?,
                area: sampler("area_sampler", &self.area_sampler)?,
                lens: sampler("lens_sampler", &self.lens_sampler)?,
                time: sampler("time_sampler", &self.time_sampler)?,
                gloss: sampler("gloss_sampler", &self.gloss_sampler)?,
                pattern,
                interleave: self.interleave,
            })),
        };
        let options = Options {
            sampling,
            n: self.n,
            spp: self.spp,
            mode: self.mode(scene)?,
            footprint: match &self.pixel {
                Some(word) => choose("pixel", word, &FOOTPRINTS)?,
                None => scene.footprint.unwrap_or(Footprint::Centre),
            },
            disk_map: self.disk_map.as_deref().map(|m| choose("disk_map", m, &DiskMap::ALL)).transpose()?,
            range: self.range,
            width,
            height,
            seed: Seed(self.seed),
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

    /// The one table's three views agree: clap's arguments are serde's fields, in order;
    /// the defaults are clap's (read back through serde); a flag parses into its field;
    /// named values are read over the defaults, an unknown name refused with the closest.
    #[test]
    fn the_settings_table_is_one_for_flags_keywords_and_keys() {
        let fields: Vec<String> = match serde_json::to_value(Settings::default()).unwrap() {
            serde_json::Value::Object(m) => m.keys().cloned().collect(),
            v => panic!("{v}"),
        };
        let mut names: Vec<String> = table().into_iter().map(|d| d.name).collect();
        names.sort();
        let mut sorted = fields.clone();
        sorted.sort();
        assert_eq!(names, sorted);
        let d = Settings::default();
        assert_eq!((d.sampler.as_str(), d.n, d.spp, d.seed), (SAMPLER, N, 1, Seed::DEFAULT.0));
        assert_eq!((d.area_sampler.as_str(), d.range, d.res), (SECONDARY, 1.0, None));
        let parsed = command().try_get_matches_from(["-n", "4", "--res", "32x24", "--area-sampler", "jitter"]).unwrap();
        let parsed = <Settings as clap::FromArgMatches>::from_arg_matches(&parsed).unwrap();
        let named = serde_json::json!({"n": 4, "res": [32, 24], "area_sampler": "jitter"});
        let serde_json::Value::Object(named) = named else { unreachable!() };
        assert_eq!(from_named(named).unwrap(), parsed);
        assert_eq!(parsed, Settings { n: 4, res: Some((32, 24)), area_sampler: "jitter".into(), ..d });
        let mut unknown = serde_json::Map::new();
        unknown.insert("spps".into(), 4.into());
        let e = from_named(unknown).unwrap_err().to_string();
        assert_eq!(e, "unknown render setting 'spps' (did you mean spp, res, seed?)");
    }

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
