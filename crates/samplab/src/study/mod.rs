//! Studies cut into chunks: the integration error of samplers on an integrand family, the
//! spectrum statistics of a sampler, and the discrepancy statistics of a sampler, each
//! described once ([`Description`], serializable), cut into a fixed list of chunks decided
//! by the description alone ([`Description::plan`]), every chunk computed from the
//! description and the chunk only ([`Description::compute`], what a Dask worker runs), and
//! the chunks' results merged in chunk order ([`Description::merge`]) into the JSON and CSV
//! the CLI writes. The Python package schedules the chunks (here or on Dask) and keeps the
//! checkpoints; whatever order the chunks finish in, the bytes are a local run's.
//!
//! The chunks:
//! - integration: units (sampler, count, instance), each with all its M realizations,
//!   `per_chunk` consecutive units a chunk (`[unit, ...]`); units merge in unit order by
//!   the code `samplab integrate` runs;
//! - spectrum: the sets in blocks of [`BLOCK`], merged by a fixed binary tree over the
//!   blocks (Welford within a block, Chan et al.'s pairwise update above); a chunk is one
//!   node of the tree (`[level, index]`, `per_chunk` sets, a power of two times 16), and the
//!   nodes merge upward exactly as a local run merges them;
//! - discrepancy: `per_chunk` consecutive realizations (`[first, end]`), their values
//!   concatenated in set order and summarized with the CLI's compensated sums.
//!
//! Realization k of a study is seeded by `seed.derive(k)` wherever it is computed.
//! A [`Checkpoint`] keeps finished chunks on disk, each checked when read back.

mod checkpoint;
pub use checkpoint::{Checkpoint, fingerprint};

use serde::{Deserialize, Serialize};

use crate::discrepancy::{Limits, Metric};
use crate::error::{Error, Result};
use crate::experiment::UnitStats;
use crate::integrand::Integrand;
use crate::points::PointSet;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spectrum::tree::{BLOCK, Partial, merge_up, nodes_at, root_level};
use crate::spectrum::{Method, Sets, Spectra, Statistics};

/// The most chunks a study is cut into: each is a task of the scheduler.
pub const MAX_CHUNKS: usize = 10_000_000;

/// Bytes of one integration unit's statistics ([`UnitStats::to_bytes`]).
const UNIT_BYTES: usize = 40;

/// What a study computes: its kind and parameters, the same on every machine.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
#[non_exhaustive]
pub enum Description {
    /// `samplab integrate`: every sampler at every count on `instances` instances of the
    /// integrand family, `sets` realizations each.
    Integrate {
        /// Sampler specs.
        samplers: Vec<String>,
        /// The integrand family's spec.
        integrand: String,
        /// Point counts.
        n: Vec<usize>,
        /// Realizations per (sampler, count, instance).
        sets: usize,
        /// Instances of the family.
        instances: usize,
        /// The seed.
        seed: u64,
        /// For an integrand the caller gives (a Python function named `integrand`, passed
        /// to [`Description::compute_with`]): its dimensions.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        d: Option<usize>,
        /// ... and its exact integral.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        exact: Option<f64>,
    },
    /// `samplab spectrum`: periodogram, expected spectrum and spectrum variance.
    Spectrum {
        /// Sampler spec.
        sampler: String,
        /// Points per set.
        n: usize,
        /// Dimensions (1 or 2).
        d: usize,
        /// Realizations.
        sets: usize,
        /// Resolution of each axis.
        res: usize,
        /// The direct DFT rather than the fast path.
        direct: bool,
        /// The fast path's tolerance.
        tolerance: f64,
        /// The seed.
        seed: u64,
    },
    /// `samplab discrepancy --sampler`: metrics of fresh realizations.
    Discrepancy {
        /// Metric specs.
        metrics: Vec<String>,
        /// Sampler spec.
        sampler: String,
        /// Points per set.
        n: usize,
        /// Dimensions.
        d: usize,
        /// Realizations.
        sets: usize,
        /// The seed.
        seed: u64,
        /// The work limit of the exact algorithms (their default when none).
        max_work: Option<f64>,
    },
}

/// A chunk: unit indices (integration), `[level, index]` of a tree node (spectrum) or
/// `[first, end]` sets (discrepancy).
pub type Chunk = Vec<u64>;

/// A study's merged result: what `samplab` writes for it.
#[derive(Debug)]
pub struct Merged {
    /// The JSON the CLI writes: `integrate --json`, `discrepancy --json`, or the
    /// `statistics` of `spectrum.json`.
    pub json: String,
    /// One row per result line: integration rows, per-metric summaries, or `radial.csv`.
    pub csv: String,
    /// The spectrum statistics themselves (spectrum studies).
    pub statistics: Option<Statistics>,
}

/// The refusal of a study's setting `name` = `value`.
fn setting(name: &'static str, value: impl ToString, reason: impl Into<String>) -> Error {
    Error::Setting { name, value: value.to_string(), reason: reason.into() }
}

/// `count` items at `per_chunk` a chunk, refused past [`MAX_CHUNKS`].
fn chunk_count(name: &'static str, items: usize, per_chunk: usize) -> Result<usize> {
    let count = items.div_ceil(per_chunk.max(1));
    if count > MAX_CHUNKS {
        let reason = format!(
            "at {per_chunk} per chunk they make {count} chunks, more than {MAX_CHUNKS}; put more in each chunk"
        );
        return Err(setting(name, items, reason));
    }
    Ok(count)
}

/// At least one of `values`, each a `what`.
fn some<T>(what: &'static str, values: &[T]) -> Result<()> {
    if values.is_empty() {
        return Err(Error::TooFew { what: "a study".into(), least: 1, of: what, got: 0 });
    }
    Ok(())
}

/// The sampler `spec`, checked at `n` points in `d` dimensions.
fn sampler(spec: &str, n: usize, d: usize) -> Result<crate::Sampler> {
    let sampler = crate::sampler::build(spec)?;
    sampler.plan(n, d)?;
    Ok(sampler)
}

/// An integration study's samplers and integrands, built.
struct Integration<'g> {
    samplers: Vec<crate::Sampler>,
    integrand: String,
    source: Source<'g>,
}

/// Where an integration study's integrands come from.
enum Source<'g> {
    /// A registered family.
    Family(crate::integrand::Family),
    /// The caller's function.
    Given(&'g dyn Integrand),
    /// The caller's function, declared but not given (planning and merging evaluate
    /// nothing).
    Declared(Declared),
}

/// A given integrand's declaration: its dimensions and integral, never evaluated.
struct Declared {
    dims: usize,
    exact: f64,
}

impl Integrand for Declared {
    fn dims(&self) -> usize {
        self.dims
    }
    fn eval(&self, _: &[f64]) -> f64 {
        f64::NAN
    }
    fn exact(&self) -> f64 {
        self.exact
    }
}

impl<'g> Integration<'g> {
    /// `given` is the function when the description declares one (`d` and `exact`).
    fn new(description: &Description, given: Option<&'g dyn Integrand>) -> Result<Integration<'g>> {
        let Description::Integrate { samplers, integrand, n, d, exact, .. } = description else {
            unreachable!("an integration study")
        };
        let samplers = samplers.iter().map(|s| crate::sampler::build(s)).collect::<Result<Vec<_>>>()?;
        if n.contains(&0) {
            return Err(setting("n", 0, "counts must be positive"));
        }
        let source = match (d, exact, given) {
            (None, None, None) => Source::Family(crate::integrand::Family::parse(integrand)?),
            (None, None, Some(_)) => {
                return Err(setting("integrand", "a function", "the study declares a family, not a function"));
            }
            (Some(d), Some(exact), given) => {
                if *d == 0 {
                    return Err(setting("d", d, "a given integrand needs d >= 1"));
                }
                if !exact.is_finite() {
                    return Err(setting("exact", exact, "a given integrand needs a finite exact integral"));
                }
                if let Some(f) = given.filter(|f| f.dims() != *d) {
                    return Err(Error::Dimension {
                        what: "the study".into(),
                        takes: format!("{d}D integrands (its d)"),
                        got: f.dims(),
                    });
                }
                given.map_or(Source::Declared(Declared { dims: *d, exact: *exact }), Source::Given)
            }
            (d, _, _) => {
                let missing = if d.is_none() { "d" } else { "exact" };
                return Err(setting(missing, "none", "a given integrand needs both d and exact"));
            }
        };
        Ok(Integration { samplers, integrand: integrand.clone(), source })
    }

    fn study<'a>(&'a self, n: &'a [usize], sets: usize, instances: usize, seed: u64) -> crate::experiment::Study<'a> {
        let family = match &self.source {
            Source::Family(family) => family.into(),
            Source::Given(f) => crate::experiment::Integrands::Given(*f, &self.integrand),
            Source::Declared(declared) => crate::experiment::Integrands::Given(declared, &self.integrand),
        };
        crate::experiment::Study { samplers: &self.samplers, family, ns: n, sets, instances, seed: Seed(seed) }
    }
}

impl Description {
    /// Check the study before any work (every sampler at every count, the settings) and cut
    /// it into chunks of `per_chunk` units / sets; returns the description as the CLI
    /// writes it (a sampler's canonical spec) and the chunks.
    ///
    /// # Errors
    /// The first thing wrong, named.
    pub fn plan(self, per_chunk: usize) -> Result<(Description, Vec<Chunk>)> {
        if per_chunk == 0 {
            let name = match self {
                Description::Integrate { .. } => "units_per_chunk",
                _ => "sets_per_chunk",
            };
            return Err(setting(name, 0, "must be at least 1"));
        }
        match self {
            Description::Integrate { ref samplers, ref n, sets, instances, seed, .. } => {
                some("sampler", samplers)?;
                some("count n", n)?;
                let units = samplers.len() * n.len() * instances;
                chunk_count("units", units, per_chunk)?;
                let built = Integration::new(&self, None)?;
                built.study(n, sets, instances, seed).prepare()?;
                let chunks = (0..units)
                    .step_by(per_chunk)
                    .map(|a| (a..units.min(a.saturating_add(per_chunk))).map(|u| u as u64).collect())
                    .collect();
                Ok((self, chunks))
            }
            Description::Spectrum { ref sampler, n, d, sets, res, direct, tolerance, .. } => {
                let blocks = per_chunk / BLOCK;
                if !per_chunk.is_multiple_of(BLOCK) || !blocks.is_power_of_two() {
                    return Err(setting(
                        "sets_per_chunk",
                        per_chunk,
                        "must be 16 times a power of two (16, 32, 64, ...)",
                    ));
                }
                if sets < 2 {
                    return Err(setting("sets", sets, "the variance of the spectrum needs at least 2 sets"));
                }
                chunk_count("sets", sets, per_chunk)?;
                self::sampler(sampler, n, d)?;
                Spectra::new(res, d, Method::of(direct, tolerance))?;
                let level = blocks.ilog2().min(root_level(sets));
                let chunks = (0..nodes_at(sets, level)).map(|i| vec![u64::from(level), i as u64]).collect();
                Ok((self, chunks))
            }
            Description::Discrepancy { metrics, sampler, n, d, sets, seed, max_work } => {
                if sets == 0 {
                    return Err(setting("sets", 0, "must be at least 1"));
                }
                chunk_count("sets", sets, per_chunk)?;
                some("metric", &metrics)?;
                for m in &metrics {
                    Metric::parse(m)?;
                }
                Limits::new(max_work)?;
                // checked by planning, not by generating a set (a CCVT of 10^6 points is
                // not optimized here)
                let sampler = self::sampler(&sampler, n, d)?.spec().to_string();
                let chunks = (0..sets)
                    .step_by(per_chunk)
                    .map(|a| vec![a as u64, sets.min(a.saturating_add(per_chunk)) as u64])
                    .collect();
                Ok((Description::Discrepancy { metrics, sampler, n, d, sets, seed, max_work }, chunks))
            }
        }
    }

    /// One chunk's partial result, as bytes (what a worker returns and a checkpoint keeps).
    ///
    /// # Errors
    /// A chunk that is not one of this study's, or the computation's error.
    pub fn compute(&self, chunk: &[u64], progress: &Progress) -> Result<Vec<u8>> {
        self.compute_with(chunk, None, progress)
    }

    /// [`Description::compute`] for a study whose integrand the caller gives: `given` is
    /// that function (of the declared `d` dimensions).
    ///
    /// # Errors
    /// As [`Description::compute`]; a function missing where the study declares one, or
    /// given where it declares none.
    pub fn compute_with(&self, chunk: &[u64], given: Option<&dyn Integrand>, progress: &Progress) -> Result<Vec<u8>> {
        use rayon::prelude::*;
        let bad = || setting("chunk", format!("{chunk:?}"), "not a chunk of this study");
        match self {
            Description::Integrate { samplers, n, sets, instances, seed, d, .. } => {
                if d.is_some() && given.is_none() {
                    return Err(setting(
                        "integrand",
                        "none",
                        "the study's integrand is a function: give it to compute a chunk",
                    ));
                }
                let built = Integration::new(self, given)?;
                let study = built.study(n, *sets, *instances, *seed);
                let prepared = study.prepare()?;
                let units = samplers.len() * n.len() * instances;
                if chunk.iter().any(|&u| u >= units as u64) {
                    return Err(bad());
                }
                let stats = chunk
                    .par_iter()
                    .map(|&u| prepared.unit(u as usize, progress).map(|s| s.to_bytes()))
                    .collect::<Result<Vec<_>>>()?;
                Ok(stats.concat())
            }
            Description::Spectrum { sampler, n, d, sets, res, direct, tolerance, seed } => {
                let &[level, index] = chunk else { return Err(bad()) };
                let level = u32::try_from(level).map_err(|_| bad())?;
                if level > root_level(*sets) || index >= nodes_at(*sets, level) as u64 {
                    return Err(bad());
                }
                let sampler = crate::sampler::build(sampler)?;
                let plan = sampler.plan(*n, *d)?;
                let spectra = Spectra::new(*res, *d, Method::of(*direct, *tolerance))?;
                let source = Sets::Generated { plan: &plan, seed: Seed(*seed), m: *sets };
                Ok(spectra.node(&source, level, index as usize, progress)?.to_bytes())
            }
            Description::Discrepancy { metrics, sampler, n, d, sets, seed, max_work } => {
                let &[first, end] = chunk else { return Err(bad()) };
                if first >= end || end > *sets as u64 {
                    return Err(bad());
                }
                let sampler = crate::sampler::build(sampler)?;
                let plan = sampler.plan(*n, *d)?;
                let limits = Limits::new(*max_work)?;
                let stack = plan.stack(Seed(*seed), first..end, progress)?;
                let points: Vec<PointSet> =
                    stack.chunks(n * d).map(|set| PointSet::from_raw(*d, set.to_vec())).collect();
                let mut out = Vec::with_capacity(metrics.len() * points.len() * 8);
                for m in metrics {
                    let m = Metric::parse(m)?;
                    let values = points
                        .par_iter()
                        .enumerate()
                        .map(|(k, s)| {
                            progress.check()?;
                            crate::discrepancy::compute(&m, s, limits.stopped_by(*progress))
                                .map_err(|e| e.in_set(first as usize + k))
                        })
                        .collect::<Result<Vec<f64>>>()?;
                    out.extend(values.iter().flat_map(|v| v.to_le_bytes()));
                }
                Ok(out)
            }
        }
    }

    /// The whole study here: one chunk (the spectrum's tree root), computed and merged.
    ///
    /// # Errors
    /// As [`Description::plan`] and [`Description::compute`].
    pub fn run(self, progress: &Progress) -> Result<Merged> {
        self.run_with(None, progress)
    }

    /// [`Description::run`] with the caller's integrand ([`Description::compute_with`]).
    ///
    /// # Errors
    /// As [`Description::run`] and [`Description::compute_with`].
    pub fn run_with(self, given: Option<&dyn Integrand>, progress: &Progress) -> Result<Merged> {
        let per_chunk = match &self {
            Description::Spectrum { sets, .. } => BLOCK << root_level(*sets),
            _ => usize::MAX,
        };
        let (d, chunks) = self.plan(per_chunk)?;
        let parts = chunks.iter().map(|c| d.compute_with(c, given, progress)).collect::<Result<Vec<_>>>()?;
        d.merge(&parts)
    }

    /// Every chunk's result, in chunk order, into the study's result.
    ///
    /// # Errors
    /// Parts that are not this study's chunks' results.
    ///
    /// # Panics
    /// Never: values are read by chunks of exactly 8 bytes.
    pub fn merge(&self, parts: &[Vec<u8>]) -> Result<Merged> {
        match self {
            Description::Integrate { n, sets, instances, seed, .. } => {
                let built = Integration::new(self, None)?;
                let study = built.study(n, *sets, *instances, *seed);
                let prepared = study.prepare()?;
                let stats = parts
                    .iter()
                    .flat_map(|p| p.chunks(UNIT_BYTES))
                    .map(UnitStats::from_bytes)
                    .collect::<Result<Vec<_>>>()?;
                let rows = prepared.rows(&stats)?;
                Ok(Merged {
                    json: crate::experiment::json(&rows),
                    csv: crate::experiment::csv(&rows),
                    statistics: None,
                })
            }
            Description::Spectrum { res, d, n, .. } => {
                let partials = parts.iter().map(|b| Partial::from_bytes(b)).collect::<Result<Vec<_>>>()?;
                let st = merge_up(partials)?.finish(*res, *d, *n)?;
                let names = crate::spectrum::STATISTICS;
                let curves = crate::spectrum::radials(&st, &names);
                let mut json = Vec::new();
                // writing to memory cannot fail, and the writer writes UTF-8
                crate::spectrum::write_json(&mut json, &st, &names, &curves).expect("JSON written to memory");
                let json = String::from_utf8(json).expect("UTF-8 JSON");
                let csv = crate::spectrum::radial_csv(&st, &names, &curves);
                Ok(Merged { json, csv, statistics: Some(st) })
            }
            Description::Discrepancy { metrics, sampler, n, d, sets, seed, .. } => {
                let k = metrics.len();
                let mut values = vec![Vec::with_capacity(*sets); k];
                for part in parts {
                    if part.is_empty() || part.len() % (8 * k) != 0 {
                        return Err(Error::Parse {
                            location: "a discrepancy chunk".into(),
                            reason: format!("{} bytes for {k} metrics", part.len()),
                        });
                    }
                    let per = part.len() / (8 * k);
                    for (m, row) in part.chunks(8 * per).enumerate() {
                        values[m]
                            .extend(row.chunks_exact(8).map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes"))));
                    }
                }
                if values.iter().any(|v| v.len() != *sets) {
                    return Err(Error::Mismatch {
                        what: "the chunks' sets".into(),
                        expected: sets.to_string(),
                        got: values[0].len().to_string(),
                    });
                }
                let metrics = metrics.iter().map(|m| Metric::parse(m)).collect::<Result<Vec<_>>>()?;
                let source = format!("{sampler} n={n} d={d} sets={sets} seed={seed}");
                Ok(Merged {
                    json: crate::discrepancy::json(&metrics, &values, &vec![*n; *sets], &source),
                    csv: crate::discrepancy::csv(&metrics, &values),
                    statistics: None,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn discrepancy(sets: usize) -> Description {
        Description::Discrepancy {
            metrics: vec!["star".into(), "l2-star".into()],
            sampler: "LHCube".into(),
            n: 16,
            d: 2,
            sets,
            seed: 3,
            max_work: None,
        }
    }

    /// A discrepancy study in chunks of 3 merges to the values computed set by set
    /// directly (set k generated from `seed.derive(k)`), and names the canonical spec.
    #[test]
    fn chunked_discrepancy_equals_the_direct_computation() {
        let (d, chunks) = discrepancy(8).plan(3).unwrap();
        assert_eq!(chunks, vec![vec![0, 3], vec![3, 6], vec![6, 8]]);
        let parts: Vec<Vec<u8>> = chunks.iter().map(|c| d.compute(c, &Progress::SILENT).unwrap()).collect();
        let merged = d.merge(&parts).unwrap();
        let json: serde_json::Value = serde_json::from_str(&merged.json).unwrap();
        assert!(json["source"].as_str().unwrap().starts_with("nrooks n=16 "), "{}", json["source"]);
        let sampler = crate::sampler::build("nrooks").unwrap();
        for (m, metric) in ["star", "l2-star"].iter().enumerate() {
            let metric = Metric::parse(metric).unwrap();
            for k in 0..8 {
                let set = sampler.generate(16, 2, Seed(3).derive(k)).unwrap();
                let direct = crate::discrepancy::compute(&metric, &set, Limits::default()).unwrap();
                assert_eq!(json["metrics"][m]["values"][k as usize].as_f64().unwrap().to_bits(), direct.to_bits());
            }
        }
        assert!(merged.csv.starts_with("metric,mean,sd,max\nstar,"), "{}", merged.csv);
    }

    /// Chunks that are not the study's, and settings that cannot be cut, are refused.
    #[test]
    fn bad_chunks_and_settings_are_refused() {
        let (d, _) = discrepancy(8).plan(3).unwrap();
        for chunk in [vec![6, 9], vec![3, 3], vec![1]] {
            assert!(d.compute(&chunk, &Progress::SILENT).is_err(), "{chunk:?}");
        }
        assert!(discrepancy(8).plan(0).unwrap_err().to_string().contains("sets_per_chunk = 0"));
        // a part of no bytes is refused, not split into chunks of zero values
        assert!(d.merge(&[Vec::new()]).is_err());
        assert!(discrepancy(0).plan(1).is_err());
        let spectrum = |per_chunk| {
            Description::Spectrum {
                sampler: "jitter".into(),
                n: 64,
                d: 2,
                sets: 100,
                res: 16,
                direct: false,
                tolerance: 1e-9,
                seed: 1,
            }
            .plan(per_chunk)
        };
        assert!(spectrum(48).unwrap_err().to_string().contains("16 times a power of two"));
        // 100 sets: 7 blocks of 16 (the last one partial), 4 nodes of 32 sets at level 1
        assert_eq!(spectrum(32).unwrap().1.len(), 4);
    }

    /// The integration rows as CSV quote a spec holding a comma, and print numbers as Rust
    /// does (shortest round trip).
    #[test]
    fn integration_csv_quotes_specs_with_commas() {
        let d = Description::Integrate {
            samplers: vec!["jitter.gaussian:sigma=0.25".into()],
            integrand: "quad".into(),
            n: vec![16],
            sets: 4,
            instances: 2,
            seed: 1,
            d: None,
            exact: None,
        };
        let merged = d.run(&Progress::SILENT).unwrap();
        let line = merged.csv.lines().nth(1).unwrap();
        assert!(line.starts_with("\"jitter.gaussian:sigma=0.25,edge=wrap\",quad,16,"), "{line}");
        assert_eq!(crate::io::csv_line(["a,b", "c\"d", "e"]), "\"a,b\",\"c\"\"d\",e\n");
    }
}
