//! The rendered-error study, and every study kind behind one description.
//!
//! A rendered-error study renders a scene once per seed and compares each image with the
//! converged reference (`samplab render --reference --json`, one run per seed). Its first
//! chunk (`[]`) renders the reference; every other chunk (`[seed, ...]`) renders its seeds
//! and returns their errors, given the reference's bytes. [`Study`] puts it beside the
//! library's kinds ([`samplab::study::Description`]) so that a front end handles every kind
//! the same way: describe, plan, compute a chunk (with the first chunk's result when
//! [`Study::first_feeds_the_rest`]), merge.

use serde::{Deserialize, Serialize};

use samplab::progress::Progress;
use samplab::study::{Chunk, Description, Merged};

use crate::error::{Error, Result};
use crate::image::Image;
use crate::mitsuba::Paths;
use crate::settings::{Settings, load_scene};

/// What a front end needs to build a study of one kind: its parameters in order (the
/// positional ones first), their types and defaults, how its chunks are sized, and what it
/// computes. A front end's constructor for a kind is generated from this.
#[derive(Debug, Serialize)]
pub struct Kind {
    /// The kind (`kind` of the description).
    pub kind: &'static str,
    /// What the study computes, for the constructor's documentation.
    pub doc: &'static str,
    /// The parameters, in order.
    pub parameters: &'static [Parameter],
    /// The keyword that sizes the chunks, and its default.
    pub per_chunk: (&'static str, usize),
    /// The parameter that collects every other keyword (a render's settings), if any.
    pub rest: Option<&'static str>,
}

/// One parameter of a study kind.
#[derive(Debug, Serialize)]
pub struct Parameter {
    /// Its name (a field of the description).
    pub name: &'static str,
    /// `count`, `counts` (one or several), `name`, `names` (one or several), `seed` (none:
    /// the default seed), `bool`, `float`, `float?` or `name?` (optional).
    pub of: &'static str,
    /// Its default as JSON; none when it must be given.
    pub default: Option<&'static str>,
    /// Whether it may be given by position.
    pub positional: bool,
}

const fn given(name: &'static str, of: &'static str) -> Parameter {
    Parameter { name, of, default: None, positional: true }
}

const fn keyword(name: &'static str, of: &'static str, default: Option<&'static str>) -> Parameter {
    Parameter { name, of, default, positional: false }
}

/// Every study kind.
pub const KINDS: &[Kind] = &[
    Kind {
        kind: "integrate",
        doc: "Integration error of `samplers` x counts `n` on `instances` instances of the integrand family, \
              `sets` realizations each (`samplab integrate`). A unit is one (sampler, count, instance) with all \
              its realizations; a chunk is `units_per_chunk` consecutive units.",
        parameters: &[
            given("samplers", "names"),
            given("integrand", "name"),
            given("n", "counts"),
            keyword("sets", "count", Some("50")),
            keyword("instances", "count", Some("10")),
            keyword("seed", "seed", Some("null")),
        ],
        per_chunk: ("units_per_chunk", 1),
        rest: None,
    },
    Kind {
        kind: "spectrum",
        doc: "Periodogram, expected spectrum and spectrum variance of `sets` realizations of `sampler` \
              (`samplab spectrum`). `sets_per_chunk` must be 16 times a power of two: a chunk is one node of \
              the merge tree.",
        parameters: &[
            given("sampler", "name"),
            given("n", "count"),
            keyword("sets", "count", None),
            keyword("res", "count", None),
            keyword("d", "count", Some("2")),
            keyword("direct", "bool", Some("false")),
            keyword("tolerance", "float", Some("1e-9")),
            keyword("seed", "seed", Some("null")),
        ],
        per_chunk: ("sets_per_chunk", 256),
        rest: None,
    },
    Kind {
        kind: "discrepancy",
        doc: "Discrepancies `metrics` of `sets` realizations of `sampler` (`samplab discrepancy --sampler`), \
              `sets_per_chunk` realizations per chunk.",
        parameters: &[
            given("metrics", "names"),
            given("sampler", "name"),
            given("n", "count"),
            keyword("sets", "count", None),
            keyword("d", "count", Some("2")),
            keyword("seed", "seed", Some("null")),
            keyword("max_work", "float?", Some("null")),
        ],
        per_chunk: ("sets_per_chunk", 100),
        rest: None,
    },
    Kind {
        kind: "render",
        doc: "Error of renders of `scene` (the CLI's settings as keywords) against its converged reference, one \
              render per seed of `seeds` (`samplab render --reference --json` per seed). The reference is a \
              chunk of its own, computed first.",
        parameters: &[
            given("scene", "name"),
            given("seeds", "counts"),
            keyword("light", "name?", Some("null")),
            keyword("reference_samples", "count", Some("1024")),
            keyword("penumbra", "bool", Some("false")),
        ],
        per_chunk: ("seeds_per_chunk", 1),
        rest: Some("settings"),
    },
];

/// Renders of `scene` with `settings`, one per seed of `seeds`, against the reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderStudy {
    /// A built-in scene or a Mitsuba XML file (whose meshes must lie inside its folder).
    pub scene: String,
    /// The light replacing the scene's, if any.
    pub light: Option<String>,
    /// The reference's samples.
    pub reference_samples: usize,
    /// Errors restricted to the reference's penumbra (0 < V < 1).
    pub penumbra: bool,
    /// Everything else; the seed is each chunk's.
    pub settings: Settings,
    /// The seeds, one render each.
    pub seeds: Vec<u64>,
}

/// A study of any kind.
#[derive(Debug, Clone, PartialEq)]
pub enum Study {
    /// Integration, spectrum or discrepancy (the library's kinds).
    Library(Description),
    /// Rendered error.
    Render(Box<RenderStudy>),
}

fn invalid(what: String) -> Error {
    Error::Invalid(what)
}

impl Study {
    /// The study a JSON description names (`{"kind": ..., parameters}`).
    ///
    /// # Errors
    /// JSON that is not a study description, naming what is wrong.
    pub fn from_json(text: &str) -> Result<Study> {
        let bad = |e: serde_json::Error| invalid(format!("not a study description: {e}"));
        let mut value: serde_json::Value = serde_json::from_str(text).map_err(bad)?;
        if value.get("kind").and_then(serde_json::Value::as_str) == Some("render") {
            value.as_object_mut().map(|o| o.remove("kind"));
            Ok(Study::Render(Box::new(serde_json::from_value(value).map_err(bad)?)))
        } else {
            Ok(Study::Library(serde_json::from_value(value).map_err(bad)?))
        }
    }

    /// The description as JSON, `kind` included.
    ///
    /// # Panics
    /// Never: descriptions are plain data.
    pub fn to_json(&self) -> String {
        let mut value = match self {
            Study::Library(d) => serde_json::to_value(d),
            Study::Render(r) => serde_json::to_value(r),
        }
        .expect("plain data");
        if let (Study::Render(_), Some(o)) = (self, value.as_object_mut()) {
            o.insert("kind".into(), "render".into());
        }
        value.to_string()
    }

    /// Whether chunk 0 must be computed first and its bytes given to every other chunk.
    pub fn first_feeds_the_rest(&self) -> bool {
        matches!(self, Study::Render(_))
    }

    /// Checked before any work and cut into chunks of `per_chunk` units, sets or seeds.
    ///
    /// # Errors
    /// The first thing wrong, named.
    pub fn plan(self, per_chunk: usize) -> Result<(Study, Vec<Chunk>)> {
        match self {
            Study::Library(d) => {
                let (d, chunks) = d.plan(per_chunk)?;
                Ok((Study::Library(d), chunks))
            }
            Study::Render(r) => {
                if per_chunk == 0 {
                    return Err(invalid("seeds_per_chunk = 0: must be at least 1".into()));
                }
                if r.seeds.is_empty() {
                    return Err(invalid("seeds: give at least one seed".into()));
                }
                // the scene and the settings, before any render
                let scene = load_scene(&r.scene, r.light.as_deref(), Paths::InsideScene)?;
                r.settings.options(&scene)?.reference(&scene, r.reference_samples)?;
                let chunks =
                    std::iter::once(Vec::new()).chain(r.seeds.chunks(per_chunk).map(<[u64]>::to_vec)).collect();
                Ok((Study::Render(r), chunks))
            }
        }
    }

    /// One chunk's result, as bytes; `first` is chunk 0's result where
    /// [`Study::first_feeds_the_rest`].
    ///
    /// # Errors
    /// A chunk without what it needs, or the computation's error.
    pub fn compute(&self, chunk: &[u64], first: Option<&[u8]>, progress: &Progress) -> Result<Vec<u8>> {
        let r = match self {
            Study::Library(d) => return Ok(d.compute(chunk, progress)?),
            Study::Render(r) => r,
        };
        let scene = load_scene(&r.scene, r.light.as_deref(), Paths::InsideScene)?;
        if chunk.is_empty() {
            let options = r.settings.options(&scene)?.reference(&scene, r.reference_samples)?;
            return Ok(crate::render(&scene, &options, progress)?.image.to_bytes());
        }
        let reference = Image::from_bytes(first.ok_or_else(|| invalid("an error chunk needs the reference".into()))?)?;
        let mut errors = Vec::with_capacity(chunk.len());
        for &seed in chunk {
            let settings = Settings { seed, ..r.settings.clone() };
            let image = crate::render(&scene, &settings.options(&scene)?, progress)?.image;
            errors.push(image.errors(&reference, r.penumbra)?);
        }
        serde_json::to_vec(&errors).map_err(|e| invalid(e.to_string()))
    }

    /// Every chunk's result, in chunk order, into the study's result.
    ///
    /// # Errors
    /// Parts that are not this study's chunks' results.
    pub fn merge(&self, parts: &[Vec<u8>]) -> Result<Merged> {
        let r = match self {
            Study::Library(d) => return Ok(d.merge(parts)?),
            Study::Render(r) => r,
        };
        let mut errors: Vec<serde_json::Map<String, serde_json::Value>> = Vec::new();
        for part in parts.iter().skip(1) {
            let chunk: Vec<serde_json::Map<String, serde_json::Value>> =
                serde_json::from_slice(part).map_err(|e| invalid(format!("a render chunk that is not errors: {e}")))?;
            errors.extend(chunk);
        }
        if errors.len() != r.seeds.len() {
            return Err(invalid(format!("the chunks hold {} renders, not {}", errors.len(), r.seeds.len())));
        }
        let names: Vec<String> = errors.first().map(|e| e.keys().cloned().collect()).unwrap_or_default();
        let column = |name: &str| errors.iter().map(|e| e[name].as_f64().unwrap_or(f64::NAN)).collect::<Vec<f64>>();
        let summary: serde_json::Map<String, serde_json::Value> = names
            .iter()
            .map(|name| {
                let s = samplab::stats::Summary::of(&column(name));
                (name.clone(), serde_json::json!({ "mean": s.mean, "sd": s.sd, "min": s.min, "max": s.max }))
            })
            .collect();
        let mut csv = samplab::io::csv_line(std::iter::once("seed").chain(names.iter().map(String::as_str)));
        for (seed, e) in r.seeds.iter().zip(&errors) {
            csv +=
                &samplab::io::csv_line(std::iter::once(seed.to_string()).chain(names.iter().map(|n| e[n].to_string())));
        }
        let json = serde_json::json!({ "seeds": r.seeds, "errors": errors, "summary": summary });
        Ok(Merged { json: json.to_string(), csv, statistics: None })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(seeds: Vec<u64>) -> Study {
        let settings = Settings { n: 4, res: Some((24, 16)), ..Settings::default() };
        Study::Render(Box::new(RenderStudy {
            scene: "spheres".into(),
            light: None,
            reference_samples: 64,
            penumbra: false,
            settings,
            seeds,
        }))
    }

    /// Chunked, the study's errors are those of each seed's render against the reference,
    /// rendered directly; the description survives its JSON.
    #[test]
    fn chunked_render_errors_equal_the_direct_ones() {
        let (s, chunks) = study(vec![3, 9, 4]).plan(2).unwrap();
        assert_eq!(chunks, vec![vec![], vec![3, 9], vec![4]]);
        assert_eq!(Study::from_json(&s.to_json()).unwrap(), s);
        let first = s.compute(&chunks[0], None, &Progress::SILENT).unwrap();
        let parts: Vec<Vec<u8>> = std::iter::once(first.clone())
            .chain(chunks[1..].iter().map(|c| s.compute(c, Some(&first), &Progress::SILENT).unwrap()))
            .collect();
        let merged: serde_json::Value = serde_json::from_str(&s.merge(&parts).unwrap().json).unwrap();
        let scene = load_scene("spheres", None, Paths::InsideScene).unwrap();
        let Study::Render(r) = &s else { unreachable!() };
        let reference_options = r.settings.options(&scene).unwrap().reference(&scene, 64).unwrap();
        let reference = crate::render(&scene, &reference_options, &Progress::SILENT).unwrap().image;
        assert_eq!(Image::from_bytes(&first).unwrap(), reference);
        for (k, seed) in [3, 9, 4].into_iter().enumerate() {
            let settings = Settings { seed, ..r.settings.clone() };
            let image = crate::render(&scene, &settings.options(&scene).unwrap(), &Progress::SILENT).unwrap().image;
            let rmse = image.errors(&reference, false).unwrap().rmse;
            assert_eq!(merged["errors"][k]["rmse"].as_f64().unwrap().to_bits(), rmse.to_bits(), "seed {seed}");
        }
        assert!(s.compute(&[3], None, &Progress::SILENT).is_err(), "an error chunk without its reference");
    }

    /// Each kind's declared parameters are exactly its description's fields: a front end
    /// built from [`KINDS`] can give every field and nothing else.
    #[test]
    fn every_kind_declares_its_description_fields() {
        let library = |text: &str| Study::from_json(text).unwrap().to_json();
        let examples = [
            library(
                r#"{"kind":"integrate","samplers":["random"],"integrand":"quad","n":[16],"sets":2,"instances":1,"seed":1}"#,
            ),
            library(
                r#"{"kind":"spectrum","sampler":"jitter","n":16,"d":2,"sets":2,"res":8,"direct":false,"tolerance":1e-9,"seed":1}"#,
            ),
            library(
                r#"{"kind":"discrepancy","metrics":["star"],"sampler":"jitter","n":16,"d":2,"sets":2,"seed":1,"max_work":null}"#,
            ),
            study(vec![1]).to_json(),
        ];
        assert_eq!(KINDS.len(), examples.len());
        for (kind, example) in KINDS.iter().zip(&examples) {
            let value: serde_json::Value = serde_json::from_str(example).unwrap();
            let fields: std::collections::BTreeSet<&str> =
                value.as_object().unwrap().keys().map(String::as_str).filter(|k| *k != "kind").collect();
            let declared: std::collections::BTreeSet<&str> =
                kind.parameters.iter().map(|p| p.name).chain(kind.rest).collect();
            assert_eq!(value["kind"], kind.kind);
            assert_eq!(fields, declared, "{}", kind.kind);
            for p in kind.parameters.iter().filter_map(|p| p.default) {
                serde_json::from_str::<serde_json::Value>(p).unwrap();
            }
        }
    }

    #[test]
    fn image_bytes_round_trip_and_bad_bytes_are_refused() {
        let image =
            Image { width: 2, height: 1, rgb: vec![0.5, 1.0, 2.0, 3.0, 4.0, 5.0], visibility: Some(vec![0.0, 1.0]) };
        assert_eq!(Image::from_bytes(&image.to_bytes()).unwrap(), image);
        let plain = Image { visibility: None, ..image.clone() };
        assert_eq!(Image::from_bytes(&plain.to_bytes()).unwrap(), plain);
        let bytes = image.to_bytes();
        assert!(Image::from_bytes(&bytes[..bytes.len() - 1]).is_err());
        assert!(Image::from_bytes(&[0; 5]).is_err());
        assert!(study(vec![]).plan(1).is_err());
        assert!(study(vec![1]).plan(0).is_err());
    }
}
