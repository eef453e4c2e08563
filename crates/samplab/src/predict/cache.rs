//! Measured sampler spectra kept between runs: a spectrum is a pure function of the
//! sampler's spec, n, dimension, grid, set count, seed and samplab's source (its digest,
//! made at build time, not only its version), so one measured once is read back bit for
//! bit instead of measured again.
//!
//! A cache folder may be shared (a cluster's scratch), so nothing in it is trusted: an
//! entry is read only when it is a regular file (not a link, a FIFO or a device) of exactly
//! the size its key implies, and its SHA-256 matches; anything else is measured again and
//! replaced. Entries are written to an exclusively created temporary with an unpredictable
//! name and renamed into place, so two writers leave one whole entry.

use std::io::Read as _;
use std::path::{Path, PathBuf};

use sha2::{Digest as _, Sha256};

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
    /// The build's source digest ([`SOURCE`]).
    pub source: &'a str,
}

/// This build's source digest: a digest of samplab's `src/` and `data/`, made by build.rs.
pub(super) const SOURCE: &str = env!("SAMPLAB_SOURCE_DIGEST");

impl Key<'_> {
    /// The key in words, stored in the file and compared on reading (so that two keys
    /// with one hash never mix).
    fn text(&self) -> String {
        format!(
            "samplab {} (source {}) spectrum of {} at n = {} in {}D, {} frequencies per axis, {} sets, seed {}",
            env!("CARGO_PKG_VERSION"),
            self.source,
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
const MAGIC: &str = "samplab spectrum cache 2";

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

    /// The spectrum stored for `key`; `None` when absent, unreadable, damaged, not a
    /// regular file of the expected size, or not this key's (module docs).
    pub(super) fn load(&self, key: &Key<'_>) -> Option<SamplerSpectrum> {
        let cells = key.res.checked_pow(u32::try_from(key.dims).ok()?)?;
        let header = format!("{MAGIC}\n{}\n", key.text());
        let size = header.len() + 8 * cells * (1 + super::BATCHES) + 32;
        let bytes = read_entry(&self.path(key), size)?;
        let (content, digest) = bytes.split_at(size - 32);
        if Sha256::digest(content).as_slice() != digest {
            return None;
        }
        let body = content.strip_prefix(header.as_bytes())?;
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

    /// Keep `s` for `key` (module docs); a cache that cannot be written is left alone (the
    /// spectrum is measured again next time).
    pub(super) fn store(&self, key: &Key<'_>, s: &SamplerSpectrum) {
        let mut bytes = format!("{MAGIC}\n{}\n", key.text()).into_bytes();
        for v in std::iter::once(&s.mean).chain(&s.batches).flatten() {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let digest = Sha256::digest(&bytes);
        bytes.extend_from_slice(&digest);
        if std::fs::create_dir_all(&self.dir).is_ok() {
            let _ = crate::io::replace_entry(&self.path(key), &bytes);
        }
    }
}

/// The whole of the entry `path` when it is a regular file (not followed through a link,
/// never opened when it is a FIFO or a device) of exactly `size` bytes.
fn read_entry(path: &Path, size: usize) -> Option<Vec<u8>> {
    let is_entry = |m: &std::fs::Metadata| m.is_file() && m.len() == size as u64;
    if !is_entry(&std::fs::symlink_metadata(path).ok()?) {
        return None;
    }
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        // a FIFO swapped in after the check must not block the open
        options.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let file = options.open(path).ok()?;
    if !is_entry(&file.metadata().ok()?) {
        return None;
    }
    let mut bytes = Vec::with_capacity(size);
    file.take(size as u64 + 1).read_to_end(&mut bytes).ok()?;
    (bytes.len() == size).then_some(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spectrum(res: usize, salt: f64) -> SamplerSpectrum {
        let row = |b: usize| (0..res * res).map(|i| salt + (i * (b + 3)) as f64 / 7.0).collect::<Vec<f64>>();
        SamplerSpectrum {
            sampler: "jitter".into(),
            n: 16,
            dims: 2,
            res,
            mean: row(0),
            batches: (1..=super::super::BATCHES).map(row).collect(),
            source: "measured: mean of 16 realizations".into(),
        }
    }

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("samplab-cache-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn an_entry_is_read_back_bit_for_bit_and_never_by_another_build() {
        let dir = folder("builds");
        let cache = Cache::new(&dir);
        let key = |source| Key { spec: "jitter", n: 16, dims: 2, res: 4, sets: 16, seed: Seed(3), source };
        let (ours, older) = (key("aaaa"), key("bbbb"));
        let s = spectrum(4, 0.5);
        cache.store(&ours, &s);
        let back = cache.load(&ours).expect("stored");
        assert_eq!(
            back.mean.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
            s.mean.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        );
        assert_eq!(back.batches, s.batches);
        // another build's key finds nothing, even with this build's entry at its name
        assert!(cache.load(&older).is_none());
        std::fs::copy(cache.path(&ours), cache.path(&older)).unwrap();
        assert!(cache.load(&older).is_none(), "an entry of another source read as this one's");
        // a changed value (the checksum) or a changed length is measured again
        let mut bytes = std::fs::read(cache.path(&ours)).unwrap();
        let at = bytes.len() - 40;
        bytes[at] ^= 1;
        std::fs::write(cache.path(&ours), &bytes).unwrap();
        assert!(cache.load(&ours).is_none());
        bytes.pop();
        std::fs::write(cache.path(&ours), &bytes).unwrap();
        assert!(cache.load(&ours).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
