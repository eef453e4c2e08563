//! The point sets a measuring command works on: a file, or fresh realizations of a sampler.

use std::ops::RangeInclusive;
use std::path::Path;

use anyhow::bail;
use samplab::io::{self, Format};
use samplab::{PointSet, Seed, sampler};

use crate::bar::Bar;

/// Where the sets come from (flattened into `discrepancy` and `spectrum`).
#[derive(clap::Args)]
pub struct SetSource {
    /// Generate the sets with this sampler instead of reading a file
    #[arg(long)]
    pub sampler: Option<String>,
    /// Points per set (with --sampler)
    #[arg(short, long, requires = "sampler")]
    n: Option<usize>,
    /// Dimensions (with --sampler)
    #[arg(short, long, default_value_t = 2, requires = "sampler")]
    dims: usize,
    /// Number of sets (with --sampler; default 1 for discrepancy, 20 for spectrum)
    #[arg(long, requires = "sampler")]
    sets: Option<usize>,
    /// Seed (with --sampler)
    #[arg(long, default_value_t = Seed::DEFAULT.0, requires = "sampler")]
    seed: u64,
    /// Input format (default: from the file's extension)
    #[arg(long, conflicts_with = "sampler")]
    format: Option<String>,
}

/// Loaded sets: the sets, a one-line description, and the sampler's canonical spec.
pub struct Loaded {
    pub sets: Vec<PointSet>,
    pub source: String,
    pub spec: Option<String>,
}

impl SetSource {
    /// Whether sets are to be generated (so a trailing argument is not a file).
    pub fn generates(&self) -> bool {
        self.sampler.is_some()
    }

    /// The points per set, dimensions and sets to be generated (`default_sets` unless
    /// --sets), when they are to be generated.
    pub fn planned(&self, default_sets: usize) -> Option<(usize, usize, usize)> {
        Some((self.n?, self.dims, self.sets.unwrap_or(default_sets))).filter(|_| self.generates())
    }

    /// Read `file` or generate the sets (`default_sets` realizations unless --sets); a file
    /// with a coordinate outside `domain` is refused with its line.
    pub fn load(
        &self,
        file: Option<&Path>,
        default_sets: usize,
        domain: &RangeInclusive<f64>,
    ) -> anyhow::Result<Loaded> {
        match (&self.sampler, file) {
            (Some(spec), None) => {
                let n = self.n.ok_or_else(|| anyhow::anyhow!("--sampler needs -n"))?;
                let m = self.sets.unwrap_or(default_sets);
                if m == 0 {
                    bail!("--sets must be at least 1");
                }
                let s = sampler::build(spec)?;
                let plan = s.plan(n, self.dims)?;
                let bar = Bar::sets(&plan, m);
                let sets = plan.generate_sets(Seed(self.seed), m, &bar.progress())?;
                drop(bar);
                Ok(Loaded {
                    sets,
                    source: format!("{} n={n} d={} sets={m} seed={}", s.spec(), self.dims, self.seed),
                    spec: Some(s.spec().to_string()),
                })
            }
            (None, Some(path)) => {
                let format = self.format.as_deref().map(Format::from_name).transpose()?;
                let sets = io::read_within(path, format, domain)?;
                Ok(Loaded { sets, source: path.display().to_string(), spec: None })
            }
            (None, None) => bail!("give a point-set file or --sampler SPEC -n N"),
            (Some(_), Some(_)) => bail!("give either a file or --sampler, not both"),
        }
    }
}
