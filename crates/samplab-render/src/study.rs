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
use serde_json::Value;

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
              its realizations; a chunk is `units_per_chunk` consecutive units. The integrand may be your own \
              vectorized function (x of shape (n, d)) with its dimensions `d` and integral `exact`; Dask \
              workers receive it pickled (cloudpickle), so it must not depend on state only this process has.",
        parameters: &[
            given("samplers", "names"),
            given("integrand", "name"),
            given("n", "counts"),
            keyword("sets", "count", Some("50")),
            keyword("instances", "count", Some("10")),
            keyword("seed", "seed", Some("null")),
            keyword("d", "count?", Some("null")),
            keyword("exact", "float?", Some("null")),
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

impl Kind {
    /// The kind named `kind`.
    ///
    /// # Errors
    /// An unknown kind, with the known ones.
    pub fn named(kind: &str) -> Result<&'static Kind> {
        KINDS.iter().find(|k| k.kind == kind).ok_or_else(|| {
            samplab::Error::UnknownName {
                kind: "study kind",
                name: kind.to_string(),
                suggestions: KINDS.iter().map(|k| k.kind.to_string()).collect(),
            }
            .into()
        })
    }

    /// The study a front end's arguments describe, and its chunk size: `arguments` holds
    /// the kind's parameters by name (a declared default where one is absent), its chunk
    /// keyword and, for a kind with a `rest`, every other keyword, side by side with them
    /// (as a constructor's keywords: `{"scene": "spheres", "n": 4}`, `n` a render
    /// setting); a kind without a `rest` refuses any other keyword. Each value
    /// is read by its declared type: a count is a whole number in [0, 2^64) (a float such
    /// as 64.0 or a bool is refused), `counts` and `names` take one value or a list, a
    /// `seed` of null is the default seed.
    ///
    /// # Errors
    /// The first argument that is missing, of the wrong type or (without a `rest`) unknown,
    /// named.
    ///
    /// # Panics
    /// Never: the declared defaults are JSON (a test reads every one).
    pub fn read(&self, arguments: &serde_json::Map<String, Value>) -> Result<(Study, usize)> {
        let mut description = serde_json::Map::new();
        description.insert("kind".into(), self.kind.into());
        for p in self.parameters {
            let default = p.default.map(|d| serde_json::from_str::<Value>(d).expect("declared defaults are JSON"));
            let value = arguments
                .get(p.name)
                .cloned()
                .or(default)
                .ok_or_else(|| Error::from(setting(p.name, &Value::Null, "must be given")))?;
            description.insert(p.name.into(), typed(p.of, p.name, &value)?);
        }
        let (name, default) = self.per_chunk;
        let declared = |k: &str| k == "kind" || k == name || self.parameters.iter().any(|p| p.name == k);
        let mut others = arguments.iter().filter(|(k, _)| !declared(k));
        if let Some(rest) = self.rest {
            let others: serde_json::Map<String, Value> = others.map(|(k, v)| (k.clone(), v.clone())).collect();
            if let Some(seed) = others.get("seed") {
                return Err(setting("seed", seed, "give the seeds as `seeds`").into());
            }
            description.insert(rest.into(), Value::Object(others));
        } else if let Some((unknown, _)) = others.next() {
            let known = self.parameters.iter().map(|p| p.name).chain([name]);
            let suggestions = samplab::error::closest_names(unknown, known);
            return Err(
                samplab::Error::UnknownName { kind: "study parameter", name: unknown.clone(), suggestions }.into()
            );
        }
        let per_chunk = match arguments.get(name) {
            Some(v) => usize::try_from(count(name, v)?.as_u64().unwrap_or(0)).unwrap_or(usize::MAX),
            None => default,
        };
        Ok((Study::from_value(Value::Object(description))?, per_chunk))
    }
}

/// The study a front end's arguments describe (a JSON object: `kind` and the arguments
/// [`Kind::read`] takes), and its chunk size.
///
/// # Errors
/// Text that is not a JSON object, an unknown kind, or [`Kind::read`]'s errors.
pub fn read(arguments: &str) -> Result<(Study, usize)> {
    let bad = |e: serde_json::Error| parse("a study's arguments", e);
    let arguments: serde_json::Map<String, Value> = serde_json::from_str(arguments).map_err(bad)?;
    let kind = arguments.get("kind").and_then(Value::as_str).unwrap_or_default();
    Kind::named(kind)?.read(&arguments)
}

fn setting(name: &'static str, value: &Value, reason: &str) -> samplab::Error {
    samplab::Error::Setting { name, value: value.to_string(), reason: reason.to_string() }
}

/// A count: a whole number in [0, 2^64).
fn count(name: &'static str, v: &Value) -> std::result::Result<Value, samplab::Error> {
    match v.as_f64() {
        _ if v.is_u64() => Ok(v.clone()),
        // a negative integer, or one past 2^64 (which JSON readers hold as a float)
        Some(x) if v.is_i64() || (x.fract() == 0.0 && x.abs() >= 18_446_744_073_709_551_616.0) => {
            Err(setting(name, v, "out of range [0, 2^64)"))
        }
        _ => Err(setting(name, v, "must be a whole number")),
    }
}

fn text(name: &'static str, v: &Value) -> std::result::Result<Value, samplab::Error> {
    if v.is_string() { Ok(v.clone()) } else { Err(setting(name, v, "must be a name (a string)")) }
}

/// `value` read as parameter `name` of type `of` (see [`Parameter::of`]).
fn typed(of: &str, name: &'static str, value: &Value) -> std::result::Result<Value, samplab::Error> {
    let one_or_many = |each: fn(&'static str, &Value) -> std::result::Result<Value, samplab::Error>| match value {
        Value::Array(items) => {
            items.iter().map(|v| each(name, v)).collect::<std::result::Result<Vec<_>, _>>().map(Value::Array)
        }
        v => Ok(Value::Array(vec![each(name, v)?])),
    };
    match (of, value) {
        ("counts", _) => one_or_many(count),
        ("names", _) => one_or_many(text),
        ("seed", Value::Null) => Ok(samplab::Seed::DEFAULT.0.into()),
        ("name?" | "float?" | "count?", Value::Null)
        | ("bool", Value::Bool(_))
        | ("float" | "float?", Value::Number(_)) => Ok(value.clone()),
        ("count" | "count?" | "seed", _) => count(name, value),
        ("name" | "name?", _) => text(name, value),
        ("bool", _) => Err(setting(name, value, "must be true or false")),
        _ => Err(setting(name, value, "must be a number")),
    }
}

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
#[non_exhaustive]
pub enum Study {
    /// Integration, spectrum or discrepancy (the library's kinds).
    Library(Description),
    /// Rendered error.
    Render(Box<RenderStudy>),
}

/// The refusal of JSON that is not `what`.
fn parse(what: &str, e: impl std::fmt::Display) -> Error {
    Error::Samplab(samplab::Error::Parse { location: what.into(), reason: e.to_string() })
}

impl Study {
    /// The study a JSON description names (`{"kind": ..., parameters}`).
    ///
    /// # Errors
    /// JSON that is not a study description, naming what is wrong.
    pub fn from_json(text: &str) -> Result<Study> {
        Study::from_value(serde_json::from_str(text).map_err(|e| parse("a study description", e))?)
    }

    fn from_value(mut value: Value) -> Result<Study> {
        let bad = |e: serde_json::Error| parse("a study description", e);
        if value.get("kind").and_then(Value::as_str) == Some("render") {
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
                    return Err(crate::error::setting("seeds_per_chunk", 0, "must be at least 1"));
                }
                if r.seeds.is_empty() {
                    return Err(
                        samplab::Error::TooFew { what: "a render study".into(), least: 1, of: "seed", got: 0 }.into()
                    );
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
    /// [`Study::first_feeds_the_rest`]; `given` the caller's integrand where an integration
    /// study declares one.
    ///
    /// # Errors
    /// A chunk without what it needs, or the computation's error.
    ///
    /// # Panics
    /// Never: a list of the errors' numbers always serializes.
    pub fn compute(
        &self,
        chunk: &[u64],
        first: Option<&[u8]>,
        given: Option<&dyn samplab::integrand::Integrand>,
        progress: &Progress,
    ) -> Result<Vec<u8>> {
        let r = match self {
            Study::Library(d) => return Ok(d.compute_with(chunk, given, progress)?),
            Study::Render(r) => r,
        };
        let scene = load_scene(&r.scene, r.light.as_deref(), Paths::InsideScene)?;
        if chunk.is_empty() {
            let options = r.settings.options(&scene)?.reference(&scene, r.reference_samples)?;
            return Ok(crate::render(&scene, &options, progress)?.image.to_bytes());
        }
        let none = || samplab::Error::TooFew { what: "an error chunk".into(), least: 1, of: "reference image", got: 0 };
        let reference = Image::from_bytes(first.ok_or_else(none)?)?;
        let mut errors = Vec::with_capacity(chunk.len());
        for &seed in chunk {
            let settings = Settings { seed, ..r.settings.clone() };
            let image = crate::render(&scene, &settings.options(&scene)?, progress)?.image;
            errors.push(image.errors(&reference, r.penumbra)?);
        }
        // a list of maps of names to numbers always serializes
        Ok(serde_json::to_vec(&errors).expect("errors as JSON"))
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
        let mut errors: Vec<serde_json::Map<String, Value>> = Vec::new();
        for part in parts.iter().skip(1) {
            let chunk: Vec<serde_json::Map<String, Value>> =
                serde_json::from_slice(part).map_err(|e| parse("a render chunk's errors", e))?;
            errors.extend(chunk);
        }
        if errors.len() != r.seeds.len() {
            return Err(Error::Samplab(samplab::Error::Mismatch {
                what: "the chunks' renders".into(),
                expected: r.seeds.len().to_string(),
                got: errors.len().to_string(),
            }));
        }
        let names: Vec<String> = errors.first().map(|e| e.keys().cloned().collect()).unwrap_or_default();
        let column = |name: &str| errors.iter().map(|e| e[name].as_f64().unwrap_or(f64::NAN)).collect::<Vec<f64>>();
        let summary: serde_json::Map<String, Value> = names
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
mod tests;
