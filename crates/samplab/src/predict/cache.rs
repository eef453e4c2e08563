//! Measured sampler spectra kept between runs: a spectrum is a pure function of the
//! sampler's spec, n, dimension, grid, set count, seed and samplab's version, so one
//! measured once is read back bit for bit instead of measured again.

use std::path::{Path, PathBuf};

use super::SamplerSpectrum;
use crate::seed::Seed;

/// What determines a measured spectrum.
pub(super) struct Key<'a> {
    pub spec: &'a str,
    pub n: usize,
    pub dims: usize,
    pub res: usize,
    pub sets: usize,
    pub seed: Seed,
}

impl Key<'_> {
    /// The key in words, stored in the file and compared on reading (so that two keys
    /// with one hash never mix).
    fn text(&self) -> String {
        format!(
            "samplab {} spectrum of {} at n = {} in {}D, {} frequencies per axis, {} sets, seed {}",
            env!("CARGO_PKG_VERSION"),
            self.spec,
            self.n,
            self.dims,
            self.res,
            self.sets,
            self.seed.0
        )
    }
}

/// A directory of measured spectra (one file each).
#[derive(Debug, Clone)]
pub struct Cache {
    dir: PathBuf,
}

/// The first line of every file.
const MAGIC: &str = "samplab spectrum cache 1";

impl Cache {
    /// The cache in `dir` (made when first written).
    pub fn new(dir: impl Into<PathBuf>) -> Cache {
        Cache { dir: dir.into() }
    }

    /// The user's cache: `$SAMPLAB_CACHE`, else `$XDG_CACHE_HOME/samplab`, else
    /// `$HOME/.cache/samplab`, each with `spectra/` below it; `None` when none is set.
    pub fn user() -> Option<Cache> {
        let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
        let root = var("SAMPLAB_CACHE")
            .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("samplab")))
            .or_else(|| var("HOME").map(|d| d.join(".cache").join("samplab")))?;
        Some(Cache::new(root.join("spectra")))
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    fn path(&self, key: &Key<'_>) -> PathBuf {
        self.dir.join(format!("{:016x}.bin", Seed(0).derive_str(&key.text()).0))
    }

    /// The spectrum stored for `key`; `None` when absent, unreadable or not this key's.
    pub(super) fn load(&self, key: &Key<'_>) -> Option<SamplerSpectrum> {
        let bytes = std::fs::read(self.path(key)).ok()?;
        let header = format!("{MAGIC}\n{}\n", key.text());
        let body = bytes.strip_prefix(header.as_bytes())?;
        let cells = key.res.pow(key.dims as u32);
        // the mean and the batches, whole
        if body.len() != 8 * cells * (1 + super::BATCHES) {
            return None;
        }
        let values: Vec<f64> =
            body.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes"))).collect();
        let mut rows = values.chunks_exact(cells).map(<[f64]>::to_vec);
        let mean = rows.next()?;
        Some(SamplerSpectrum {
            sampler: key.spec.to_string(),
            n: key.n,
            dims: key.dims,
            res: key.res,
            mean,
            batches: rows.collect(),
            source: format!("measured: mean of {} realizations", key.sets),
        })
    }

    /// Keep `s` for `key`, written whole under a temporary name and then renamed, so that
    /// a reader never sees half a file; a cache that cannot be written is left alone (the
    /// spectrum is measured again next time).
    pub(super) fn store(&self, key: &Key<'_>, s: &SamplerSpectrum) {
        let mut bytes = format!("{MAGIC}\n{}\n", key.text()).into_bytes();
        for v in std::iter::once(&s.mean).chain(&s.batches).flatten() {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let path = self.path(key);
        static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let count = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let temporary = path.with_extension(format!("tmp{}-{count}", std::process::id()));
        let written = std::fs::create_dir_all(&self.dir)
            .and_then(|()| std::fs::write(&temporary, &bytes))
            .and_then(|()| std::fs::rename(&temporary, &path));
        if written.is_err() {
            let _ = std::fs::remove_file(&temporary);
        }
    }
}
