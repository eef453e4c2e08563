//! A saved point set as a sampler: `file:path=FILE[,set=K]` is set K of a point file (any
//! format samplab reads: text, CSV, NumPy `.npy`, JSON) for every seed, so that the stages
//! randomize it: `file:path=best.npy+shift` gives each realization its own
//! Cranley–Patterson shift of an optimized set, `+micro-jitter` its own jitter. Its random
//! access reads the set, so a shifted saved set streams too.

use std::ops::RangeInclusive;
use std::path::Path;
use std::sync::Arc;

use crate::construct::Counts;
use crate::error::{Error, Result};
use crate::numeric::BELOW_ONE;
use crate::points::PointSet;
use crate::progress::Progress;
use crate::registry::About;
use crate::sampler::registry::SamplerEntry;
use crate::sampler::{Access, Construction, Prepared, Shape};
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// Set K of a point file, read when the sampler is built.
#[derive(Debug)]
struct Saved {
    set: Arc<PointSet>,
}

impl Construction for Saved {
    fn dims(&self) -> RangeInclusive<usize> {
        self.set.dims()..=self.set.dims()
    }
    fn check_count(&self, shape: &Shape) -> Result<()> {
        let n = shape.n();
        if n != self.set.len() {
            return Err(shape.invalid_count(format!("the saved set has {} points", self.set.len())));
        }
        Ok(())
    }
    fn prepare(&self, _shape: &Shape) -> Result<Box<dyn Prepared>> {
        Ok(Box::new(Replay { set: Arc::clone(&self.set) }))
    }
}

/// The saved set, the same for every seed.
#[derive(Debug)]
struct Replay {
    set: Arc<PointSet>,
}

impl Prepared for Replay {
    fn fill(&self, _seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        out.copy_from_slice(self.set.as_slice());
        progress.advance(1)
    }
    fn access(&self, _seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(Replay { set: Arc::clone(&self.set) }))
    }
}

impl Access for Replay {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        let point = usize::try_from(index).ok().filter(|&i| i < self.set.len()).ok_or_else(|| Error::Setting {
            name: "index",
            value: index.to_string(),
            reason: format!("the saved set has {} points", self.set.len()),
        })?;
        Ok(self.set.point(point)[dim])
    }
}

/// Read set `set` of the file `path`: every coordinate in [0, 1).
fn read(path: &str, set: u64) -> Result<Saved> {
    let mut sets = crate::io::read_within(Path::new(path), None, &(0.0..=BELOW_ONE))?;
    let count = sets.len();
    let index = usize::try_from(set).ok().filter(|&k| k < count).ok_or_else(|| Error::Param {
        owner: "file".into(),
        param: "set".into(),
        reason: format!("{path} holds {count} set(s): set is 0 to {}", count.saturating_sub(1)),
    })?;
    Ok(Saved { set: Arc::new(sets.swap_remove(index)) })
}

fn build(p: &mut Params) -> Result<Box<dyn Construction>> {
    let path = p.path_or_auto("path").ok_or_else(|| Error::Param {
        owner: "file".into(),
        param: "path".into(),
        reason: "give the point file to read: file:path=FILE".into(),
    })?;
    Ok(Box::new(read(path, p.int("set"))?))
}

/// The sampler this file registers.
pub(crate) static ENTRIES: &[SamplerEntry] = &[SamplerEntry {
    about: About::new(
        "file",
        "a saved point set (set K of a point file), the same for every seed: randomize it with +shift",
    )
    .terse()
    .aliases(&["saved", "points"])
    .params(&[
        ParamSpec {
            name: "path",
            kind: Kind::Path,
            default: Default::Auto("none: the file must be given"),
            doc: "the point file (text, CSV, .npy or JSON; every coordinate in [0, 1))",
        },
        ParamSpec {
            name: "set",
            kind: Kind::Int { min: 0, max: 1 << 32 },
            default: Default::Int(0),
            doc: "which set of the file",
        },
    ]),
    counts: Counts::Rule("n = the saved set's points"),
    randomized: false,
    dims: "the file's",
    build,
}];
