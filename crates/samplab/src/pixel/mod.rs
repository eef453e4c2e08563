//! Pixel samplers: samples as renderers draw them, one number at a time, keyed by
//! (seed, pixel, frame, index, dimension).
//!
//! A renderer asks, for pixel p, sample i of that pixel and dimension d (film position,
//! lens, time, light, each bounce), for one value in [0, 1), in any order and from many
//! threads. A [`Pixels`] answers [`Pixels::sample`] as a pure function of those keys: random
//! access, O(1) or O(log) per value, no allocation, shared across threads by reference.
//! It is prepared once for a [`Film`] (resolution, samples per pixel, dimensions), which is
//! where tables are built (a PMJ02 pool, a blue-noise mask).
//!
//! How a point-set family becomes a pixel sampler is part of its entry, typed
//! ([`PixelEntry::mapping`], a [`MappingKind`]):
//! - one sequence per pixel, decorrelated by hashes of (seed, pixel, frame): `sobol` and
//!   `lattice` shuffle the index per pixel (Burley 2020), so each pixel's first 2^m
//!   samples are an aligned block of the sequence, still a net or a shifted lattice;
//! - dimension padding: each pair of dimensions from its own randomization of a 2D pattern
//!   (`sobol.padded`, `stratified`, `pmj02`, as pbrt-v4's padded samplers), against a true
//!   high-dimensional sequence (`sobol`: dimension d is Sobol' dimension d);
//! - screen-space orderings and masks: `zsobol` (Morton-ordered pixels, Ahmed & Wonka
//!   2020, pbrt-v4's values bit for bit), `dither` and `pmj02.bn` (one toroidal shift per
//!   pixel from a blue-noise [`mask`], Georgiev & Fajardo 2016), OpenQMC's `*bn` tables;
//! - OpenQMC's six samplers as OpenQMC defines them (`openqmc.*`, through `openqmc-rs`);
//! - any point-set sequence whose spec is not a pixel sampler's name (`sobol.owen`,
//!   `halton.owen`, `net.lms`, `lattice.shift`, `SPEC+shift`): one sequence per pixel, the
//!   point set itself under the pixel's seed ([`pixel_seed`], [`per_pixel`]), so a
//!   randomization word names one scramble through both front doors. After a pixel
//!   sampler's own name, `.none`, `.xor` and `.owen` set its `randomize` (`zsobol.owen`).
//!
//! ```
//! use samplab::{Seed, pixel};
//! let film = pixel::Film { width: 64, height: 32, spp: 16, dims: 8 };
//! let zsobol = pixel::prepare("zsobol", film, Seed(7))?;
//! let u = zsobol.sample([3, 5], 0, 2, 4);
//! assert!((0.0..1.0).contains(&u));
//! // the same keys give the same value, whatever thread asks
//! assert_eq!(u, std::thread::scope(|s| s.spawn(|| zsobol.sample([3, 5], 0, 2, 4)).join().unwrap()));
//! # Ok::<(), samplab::Error>(())
//! ```
//!
//! [`Pixels`] dispatches to its family by a match, so a draw is inlined into the caller's
//! loop; [`Pixels::visit`] hands the family's own type to code generic over
//! [`PixelSampler`], compiled once per family (the fastest way to draw many values).
//!
//! [`PIXEL_SAMPLERS`] (and `samplab list pixels`) is the table of families.

use std::fmt::Debug;

use rayon::prelude::*;

use crate::construct::Counts;
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::registry::{About, Entry, canonical};
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

pub mod mask;
mod sequence;

pub use sequence::pixel_seed;

crate::registry::registry_files! {
    /// Every pixel sampler family, in listing order.
    pub static PIXEL_SAMPLERS: Registry<PixelEntry> = ("pixel sampler",
        "PIXEL SAMPLERS  (spec: name[.none|.xor|.owen][:key=value,...], or a point-set sequence per pixel: sobol.owen, \
         halton.owen, lattice.shift, ...; values keyed by seed, pixel, frame, index, dimension)")
        from [independent, stratified, sobol, zsobol, halton, pmj, lattice, dither, heitz, openqmc, cycles];
}

/// The most dimensions a pixel sampler is prepared for.
pub const MAX_DIMS: u32 = 1 << 16;

/// The largest side of a film, in pixels.
pub const MAX_SIDE: u32 = 1 << 16;

/// What a pixel sampler is prepared for: the film's resolution, the samples per pixel and
/// the dimensions drawn per sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Film {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Dimensions per sample.
    pub dims: u32,
}

impl Film {
    /// Whether the film is valid on its own: sides in 1..=[`MAX_SIDE`] (the setting `res`),
    /// spp at least 1, dimensions in 1..=[`MAX_DIMS`].
    ///
    /// # Errors
    /// [`Error::Setting`] naming the setting out of range.
    pub fn check(&self) -> Result<()> {
        let bad = |name, value: u32, reason: &str| {
            Err(Error::Setting { name, value: value.to_string(), reason: reason.into() })
        };
        if [self.width, self.height].iter().any(|&side| side == 0 || side > MAX_SIDE) {
            return Err(Error::Setting {
                name: "res",
                value: format!("{}x{}", self.width, self.height),
                reason: format!("a film side is 1 to {MAX_SIDE} pixels"),
            });
        }
        if self.spp == 0 {
            return bad("spp", 0, "at least one sample per pixel");
        }
        if self.dims == 0 || self.dims > MAX_DIMS {
            return bad("dims", self.dims, &format!("1 to {MAX_DIMS} dimensions"));
        }
        Ok(())
    }
}

/// A prepared family: the value of every (pixel, frame, index, dimension) for one seed.
///
/// Implementations are pure: no interior state changes, so one value may be shared by
/// every render thread. Keys outside the film (`index >= spp`, `dim >= dims`, a pixel
/// off the film) are the caller's to avoid; [`Pixels::try_sample`] checks them.
pub trait PixelSampler: Send + Sync + Debug {
    /// Dimension `dim` of sample `index` of `pixel` (x, y) in `frame`, in [0, 1).
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64;

    /// Dimensions `dim .. dim + 4` at once (the families that compute a pair or a block
    /// together override it).
    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        four(|k| self.sample(pixel, frame, index, dim + k))
    }
}

/// Code generic over the pixel sampler it is given: see [`Pixels::visit`].
pub trait Visit {
    /// What the visit returns.
    type Output;
    /// Runs with the prepared family as its own type.
    fn visit<S: PixelSampler>(self, sampler: &S) -> Self::Output;
}

/// Every prepared family's type, one variant each: [`Pixels`] dispatches on it by a match
/// (the draws inlined, no virtual call) and [`Pixels::visit`] hands the type to generic code.
macro_rules! families {
    ($($variant:ident($ty:ty)),+ $(,)?) => {
        #[derive(Debug)]
        pub(crate) enum Family {
            $($variant($ty)),+
        }

        $(impl From<$ty> for Family {
            fn from(s: $ty) -> Family {
                Family::$variant(s)
            }
        })+

        impl Family {
            #[inline]
            fn visit<V: Visit>(&self, visitor: V) -> V::Output {
                match self {
                    $(Family::$variant(s) => visitor.visit(s)),+
                }
            }
        }

        impl PixelSampler for Family {
            #[inline]
            fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
                match self {
                    $(Family::$variant(s) => s.sample(pixel, frame, index, dim)),+
                }
            }

            #[inline]
            fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
                match self {
                    $(Family::$variant(s) => s.sample4(pixel, frame, index, dim)),+
                }
            }
        }
    };
}

families! {
    Independent(independent::Independent),
    Stratified(stratified::Stratified),
    Sobol(sobol::Burley),
    Padded(sobol::Padded),
    ZSobol(zsobol::ZSobol),
    Halton(halton::Halton),
    Pmj(pmj::Pmj),
    Lattice(lattice::Lattice),
    Dither(dither::Dither),
    Heitz(heitz::Heitz),
    OpenQmcSobol(openqmc::OpenQmc<::openqmc::SobolSampler>),
    OpenQmcSobolBn(openqmc::OpenQmc<::openqmc::SobolBnSampler>),
    OpenQmcPmj(openqmc::OpenQmc<::openqmc::PmjSampler>),
    OpenQmcPmjBn(openqmc::OpenQmc<::openqmc::PmjBnSampler>),
    OpenQmcLattice(openqmc::OpenQmc<::openqmc::LatticeSampler>),
    OpenQmcLatticeBn(openqmc::OpenQmc<::openqmc::LatticeBnSampler>),
    OpenQmcSz(openqmc::OpenQmc<openqmc::SzSampler>),
    Cycles(cycles::Cycles),
    Sequence(sequence::PerPixel),
}

/// A family that computes its dimensions in pairs (2k, 2k + 1), one 2D pattern each: it is
/// a [`PixelSampler`] through this.
pub(crate) trait Pairs: Send + Sync + Debug {
    /// What one sample's pairs share (a pixel's key, a Morton index), computed once per draw.
    type Key: Copy;

    /// The key of sample `index` of `pixel` in `frame`.
    fn key(&self, pixel: [u32; 2], frame: u32, index: u32) -> Self::Key;

    /// Dimensions `first` and `first + 1` of that sample (`first` even).
    fn pair(&self, key: Self::Key, pixel: [u32; 2], frame: u32, index: u32, first: u32) -> [f64; 2];

    /// Dimensions `first .. first + 4` (a family that computes two pairs faster together
    /// overrides it).
    #[inline(always)]
    fn two_pairs(&self, key: Self::Key, pixel: [u32; 2], frame: u32, index: u32, first: u32) -> [f64; 4] {
        let [a, b] = self.pair(key, pixel, frame, index, first);
        let [c, d] = self.pair(key, pixel, frame, index, first + 2);
        [a, b, c, d]
    }
}

impl<T: Pairs> PixelSampler for T {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        let key = self.key(pixel, frame, index);
        self.pair(key, pixel, frame, index, dim & !1)[(dim & 1) as usize]
    }

    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        if dim & 1 == 1 {
            return one_by_one(self, pixel, frame, index, dim);
        }
        self.two_pairs(self.key(pixel, frame, index), pixel, frame, index, dim)
    }
}

/// A registered pixel sampler family.
#[derive(Debug)]
pub struct PixelEntry {
    /// Name, aliases, summary, parameters, references.
    pub about: About,
    /// Which sample counts per pixel it takes, and where it stratifies.
    pub spp: Counts,
    /// The most dimensions (at most [`MAX_DIMS`]).
    pub max_dims: u32,
    /// What limits or groups the dimensions, in words ("the Joe-Kuo table", "pairs of 2D
    /// Sobol'"), or empty; the listing's dimensions are derived from it and `max_dims`.
    pub dims_note: &'static str,
    /// How a point-set family becomes this pixel sampler.
    pub mapping: Mapping,
    /// Builds the prepared sampler for a film and a seed (the film already checked).
    pub(crate) build: fn(&Params, Film, Seed, &Progress<'_>) -> Result<Family>,
}

impl PixelEntry {
    /// The dimensions it draws, in words: "any" or "1 to N", and the note.
    pub fn dims(&self) -> String {
        let range = if self.max_dims == MAX_DIMS { "any".to_string() } else { format!("1 to {}", self.max_dims) };
        if self.dims_note.is_empty() { range } else { format!("{range} ({})", self.dims_note) }
    }
}

/// How a pixel sampler draws a point-set family: the kind of mapping, the family (a name
/// in [`crate::sampler::SAMPLERS`]'s listing, its construction in [`crate::construct`]), and
/// the particulars in words. The listing's line is printed from it.
#[derive(Debug, Clone, Copy)]
pub struct Mapping {
    /// The kind of mapping.
    pub kind: MappingKind,
    /// The point-set family whose construction it draws.
    pub family: &'static str,
    /// The particulars, in words.
    pub how: &'static str,
}

/// The ways a point-set family becomes a pixel sampler.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum MappingKind {
    /// No structure to map: every value a hash of the keys.
    Hashed,
    /// One sequence per pixel, decorrelated by hashes of (seed, pixel, frame).
    PerPixel,
    /// Dimension padding: each pair (or block) of dimensions from its own randomization of
    /// a low-dimensional pattern.
    Padded,
    /// A screen-space ordering: one sequence (or its keys) spread over the film's pixels.
    ScreenOrder,
    /// A screen-space mask: one toroidal shift per pixel from a blue-noise mask.
    Mask,
    /// Another library's samplers, as it defines them.
    External,
}

impl MappingKind {
    /// In words, for the listing.
    pub fn words(self) -> &'static str {
        match self {
            MappingKind::Hashed => "hashed values",
            MappingKind::PerPixel => "one sequence per pixel",
            MappingKind::Padded => "dimension padding",
            MappingKind::ScreenOrder => "screen-space ordering",
            MappingKind::Mask => "screen-space mask",
            MappingKind::External => "another library's own",
        }
    }
}

impl Entry for PixelEntry {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        let Mapping { kind, family, how } = self.mapping;
        vec![
            format!("spp: {}; dimensions: {}", self.spp.describe(), self.dims()),
            format!("mapping: {} of {family}: {how}", kind.words()),
        ]
    }
}

/// A pixel sampler prepared for a film and a seed, with its spec.
#[derive(Debug)]
pub struct Pixels {
    spec: String,
    film: Film,
    seed: Seed,
    inner: Family,
    /// The values past the film's dimensions ([`Pixels::sample_padded`]).
    padding: independent::Independent,
}

/// Prepare the pixel sampler `spec` (e.g. `zsobol`, `sobol.padded:randomize=owen`) for a
/// film and a seed.
///
/// # Errors
/// An unknown name or bad parameters, a film out of range, a sample count the family does
/// not take, or more dimensions than it draws.
pub fn prepare(spec: &str, film: Film, seed: Seed) -> Result<Pixels> {
    prepare_with(spec, film, seed, &Progress::SILENT)
}

/// [`prepare`], stopped when `progress` says so (the optimized families take seconds).
///
/// # Errors
/// As [`prepare`], or [`Error::Interrupted`].
pub fn prepare_with(spec: &str, film: Film, seed: Seed, progress: &Progress<'_>) -> Result<Pixels> {
    let (entry, params) = match PIXEL_SAMPLERS.resolve(spec) {
        Ok(found) => found,
        Err(unknown @ Error::UnknownName { .. }) => {
            film.check()?;
            match sequence::prepare(spec, film, seed) {
                Err(Error::UnknownName { kind: "sampler", .. }) => {}
                done => return done,
            }
            PIXEL_SAMPLERS.resolve(&with_randomization(spec).ok_or(unknown)?)?
        }
        Err(other) => return Err(other),
    };
    let spec = canonical(&entry.about, &params);
    film.check()?;
    entry.spp.check(film.spp as usize, 2).map_err(|reason| Error::Setting {
        name: "spp",
        value: film.spp.to_string(),
        reason: format!("{spec}: {reason}"),
    })?;
    if film.dims > entry.max_dims {
        return Err(Error::InvalidDims { sampler: spec, dims: film.dims as usize, supported: entry.dims() });
    }
    let inner = (entry.build)(&params, film, seed, progress)?;
    Ok(Pixels { spec, film, seed, inner, padding: independent::padding(seed) })
}

/// The point-set sequence `spec` (`sobol`, `sobol.owen`, `halton.owen`, ...) served per pixel
/// ([`pixel_seed`]), even where a pixel sampler has the same name (`sobol` here is the
/// unscrambled Sobol' sequence, the same in every pixel, not the pixel sampler `sobol`).
///
/// # Errors
/// An unknown point set, one that is not a sequence with random access, a film out of
/// range, or a count or dimension the sequence does not make.
pub fn per_pixel(spec: &str, film: Film, seed: Seed) -> Result<Pixels> {
    film.check()?;
    sequence::prepare(spec, film, seed)
}

/// The point sets' randomization words and the `randomize` value each is in pbrt's
/// samplers: pbrt's FastOwen is the point sets' hash-based Owen scramble (`.owen`, the same
/// hash), its XOR their random digit scrambling in base 2 (`.xor`).
const RANDOMIZATION_WORDS: &[(&str, &str)] = &[("none", "none"), ("xor", "xor"), ("owen", "fastowen")];

/// `spec`, a randomization word after a pixel sampler's name (`zsobol.owen`,
/// `sobol.padded.xor:...`), written with that sampler's `randomize` parameter; `None` for
/// any other spec.
fn with_randomization(spec: &str) -> Option<String> {
    let (name, args) = spec.split_once(':').map_or((spec, None), |(n, a)| (n, Some(a)));
    name.rsplit_once('.').and_then(|(family, word)| {
        let entry = PIXEL_SAMPLERS.lookup(family).ok()?;
        let offered = match entry.about.params.iter().find(|p| p.name == "randomize")?.kind {
            Kind::Choice(words) => words,
            _ => return None,
        };
        let &(_, chosen) =
            RANDOMIZATION_WORDS.iter().find(|(w, v)| w.eq_ignore_ascii_case(word) && offered.contains(v))?;
        Some(match args {
            Some(args) => format!("{family}:{args},randomize={chosen}"),
            None => format!("{family}:randomize={chosen}"),
        })
    })
}

impl Pixels {
    /// The canonical spec.
    pub fn spec(&self) -> &str {
        &self.spec
    }

    /// The film it was prepared for.
    pub fn film(&self) -> Film {
        self.film
    }

    /// The seed it was prepared with.
    pub fn seed(&self) -> Seed {
        self.seed
    }

    /// Dimension `dim` of sample `index` of `pixel` (x, y) in `frame`, in [0, 1): the hot
    /// path, unchecked (keys outside the film give some value, never a panic in release).
    #[inline]
    pub fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        self.inner.sample(pixel, frame, index, dim)
    }

    /// The tables that the header-only C++ families (`crates/samplab-c/include/samplab/samplers.hpp`)
    /// read for this family, made when it was prepared: `pmj02`'s pool (16 x spp points of
    /// four 32-bit coordinates, entry-major), and for `pmj02.bn` its pool then its mask's two
    /// channels in 32-bit fixed point (size x size x 2, row-major); empty for the other
    /// families (the header computes theirs, or holds them).
    pub fn header_tables(&self) -> Vec<u32> {
        match &self.inner {
            Family::Pmj(p) => p.header_tables(),
            _ => Vec::new(),
        }
    }

    /// Dimensions `dim .. dim + 4` of one sample.
    #[inline]
    pub fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        self.inner.sample4(pixel, frame, index, dim)
    }

    /// Hands the prepared family, as its own type, to `visitor`: code generic over
    /// [`PixelSampler`] (a renderer's pixel loop) is then compiled once per family, and
    /// every draw inlined into it, with no dispatch per value.
    ///
    /// ```
    /// use samplab::{Seed, pixel::{self, PixelSampler, Visit}};
    /// /// The mean of dimension 0 over a film's samples.
    /// struct Mean(pixel::Film);
    /// impl Visit for Mean {
    ///     type Output = f64;
    ///     fn visit<S: PixelSampler>(self, s: &S) -> f64 {
    ///         let f = self.0;
    ///         let mut sum = 0.0;
    ///         for y in 0..f.height { for x in 0..f.width { for i in 0..f.spp { sum += s.sample([x, y], 0, i, 0); } } }
    ///         sum / f64::from(f.width * f.height * f.spp)
    ///     }
    /// }
    /// let film = pixel::Film { width: 8, height: 8, spp: 4, dims: 2 };
    /// let p = pixel::prepare("sobol", film, Seed(3))?;
    /// assert!((p.visit(Mean(film)) - 0.5).abs() < 0.05);
    /// # Ok::<(), samplab::Error>(())
    /// ```
    #[inline]
    pub fn visit<V: Visit>(&self, visitor: V) -> V::Output {
        self.inner.visit(visitor)
    }

    /// [`Pixels::sample`] with every key checked against the film.
    ///
    /// # Errors
    /// [`Error::Setting`] naming the key out of range.
    pub fn try_sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> Result<f64> {
        let f = self.film;
        for (name, value, end) in
            [("x", pixel[0], f.width), ("y", pixel[1], f.height), ("index", index, f.spp), ("dim", dim, f.dims)]
        {
            if value >= end {
                return Err(Error::Setting { name, value: value.to_string(), reason: format!("must be below {end}") });
            }
        }
        Ok(self.sample(pixel, frame, index, dim))
    }

    /// [`Pixels::try_sample`], except that a dimension past the film's is not an error but
    /// padding: independent uniform values (53 random bits) hashed from the seed, pixel,
    /// frame, index and dimension, as the `independent` family draws them under a seed of
    /// their own. A renderer with no depth limit (Russian roulette) never runs out of
    /// dimensions; past the budget it gets random sampling, not the family's structure.
    ///
    /// # Errors
    /// [`Error::Setting`] naming `x`, `y` or `index` when it lies outside the film.
    pub fn sample_padded(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> Result<f64> {
        if dim >= self.film.dims {
            self.try_sample(pixel, frame, index, 0)?;
            return Ok(self.padding.sample(pixel, frame, index, dim));
        }
        self.try_sample(pixel, frame, index, dim)
    }

    /// The image of dimension `dim` of sample `index` in `frame`, one value per pixel of
    /// the film: the sampler's mask for that dimension ([`crate::screen`] measures it).
    ///
    /// # Errors
    /// [`Error::Setting`] naming `index` or `dim` when it lies outside the film.
    pub fn mask(&self, frame: u32, index: u32, dim: u32) -> Result<crate::screen::Plane> {
        let f = self.film;
        self.try_sample([0, 0], frame, index, dim)?;
        let values =
            (0..f.height).flat_map(|y| (0..f.width).map(move |x| self.sample([x, y], frame, index, dim))).collect();
        crate::screen::Plane::new(f.width as usize, f.height as usize, values)
    }

    /// How many values `frames` frames of the whole film hold.
    ///
    /// # Errors
    /// [`Error::Setting`] when the count overflows memory's address space.
    pub fn values(&self, frames: u32) -> Result<usize> {
        let f = self.film;
        [f.width, f.height, f.spp, f.dims]
            .iter()
            .try_fold(frames as usize, |acc, &k| acc.checked_mul(k as usize))
            .filter(|&n| n <= isize::MAX as usize / 8)
            .ok_or_else(|| Error::Setting {
                name: "frames",
                value: frames.to_string(),
                reason: "frames x width x height x spp x dims values do not fit in memory".into(),
            })
    }

    /// Every value of `frames` frames, in the order (frame, y, x, index, dim): an array of
    /// shape (frames, height, width, spp, dims). Rows are filled in parallel; the values do
    /// not depend on the thread count.
    ///
    /// # Errors
    /// As [`Pixels::values`], or a refused allocation ([`crate::memory`]).
    pub fn fill(&self, frames: u32) -> Result<Vec<f64>> {
        self.fill_with(frames, &Progress::SILENT)
    }

    /// [`Pixels::fill`], stopped when `progress` says so (checked every row).
    ///
    /// # Errors
    /// As [`Pixels::fill`], or [`Error::Interrupted`].
    pub fn fill_with(&self, frames: u32, progress: &Progress<'_>) -> Result<Vec<f64>> {
        let total = self.values(frames)?;
        let mut out = crate::memory::zeroed::<f64>(|| format!("{total} pixel sampler values"), total)?;
        let f = self.film;
        let row = f.width as usize * f.spp as usize * f.dims as usize;
        if row == 0 {
            return Ok(out);
        }
        out.par_chunks_mut(row).enumerate().try_for_each(|(r, values)| {
            progress.check()?;
            let (frame, y) = ((r / f.height as usize) as u32, (r % f.height as usize) as u32);
            let mut k = 0;
            for x in 0..f.width {
                for i in 0..f.spp {
                    let mut d = 0;
                    while d + 4 <= f.dims {
                        values[k..k + 4].copy_from_slice(&self.sample4([x, y], frame, i, d));
                        k += 4;
                        d += 4;
                    }
                    for d in d..f.dims {
                        values[k] = self.sample([x, y], frame, i, d);
                        k += 1;
                    }
                }
            }
            Ok::<(), Error>(())
        })?;
        Ok(out)
    }
}

/// The keys a family's randomization starts from, prepared from the seed: one 64-bit hash
/// per (pixel, frame), and one word per dimension that [`Keys::dim`] combines with a
/// pixel's key in a few operations (as Burley 2020 combines seeds), so a draw costs one
/// 64-bit hash however many dimensions it takes.
#[derive(Debug, Clone)]
pub(crate) struct Keys {
    base: u64,
    pub(crate) dims: Vec<u32>,
}

impl Keys {
    /// Keys for `seed` and `dims` dimensions.
    pub(crate) fn new(seed: Seed, dims: u32) -> Keys {
        let base = crate::seed::mix64(seed.0 ^ 0x51_7CC1_B727_220A);
        Keys { base, dims: (0..dims).map(|d| (rekey(base, u64::from(d) + 1) >> 32) as u32).collect() }
    }

    /// The key of (pixel, frame).
    #[inline(always)]
    pub(crate) fn pixel(&self, pixel: [u32; 2], frame: u32) -> u64 {
        let p = (u64::from(pixel[1]) << 32) | u64::from(pixel[0]);
        crate::seed::mix64(
            self.base ^ p.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ u64::from(frame).wrapping_mul(0xC2B2_AE3D_27D4_EB4F),
        )
    }

    /// The key of a whole frame (for the families whose pattern is shared by every pixel).
    #[inline(always)]
    pub(crate) fn frame(&self, frame: u32) -> u64 {
        crate::seed::mix64(self.base ^ 0xA076_1D64_78BD_642F ^ u64::from(frame).wrapping_mul(0xC2B2_AE3D_27D4_EB4F))
    }

    /// A 32-bit key for dimension `dim` of the pixel whose key's low word is `key`.
    #[inline(always)]
    pub(crate) fn dim(&self, key: u32, dim: u32) -> u32 {
        Keys::combine(key, self.dims[dim as usize])
    }

    /// [`Keys::dim`] from the dimension's word `h`.
    #[inline(always)]
    pub(crate) fn combine(key: u32, h: u32) -> u32 {
        key ^ h.wrapping_add(0x9E37_79B9).wrapping_add(key << 6).wrapping_add(key >> 2)
    }
}

/// A further hash of a key with a word (a dimension, a sample index).
#[inline]
pub(crate) fn rekey(key: u64, word: u64) -> u64 {
    crate::seed::mix64(key.wrapping_add(word.wrapping_mul(0x9E37_79B9_7F4A_7C15)))
}

/// `[f(0), f(1), f(2), f(3)]`, written out: `std::array::from_fn` is not always inlined,
/// and a call per draw cost the hot path a quarter of its speed (`bench/compare pixels`).
#[inline(always)]
pub(crate) fn four<T>(mut f: impl FnMut(u32) -> T) -> [T; 4] {
    [f(0), f(1), f(2), f(3)]
}

/// Dimensions `dim .. dim + 4` drawn one at a time: the rare path of the families that draw
/// aligned blocks (a block that starts mid-pair, past the last dimension), kept out of line
/// so that it does not weigh on the hot one.
#[cold]
#[inline(never)]
pub(crate) fn one_by_one<S: PixelSampler + ?Sized>(
    s: &S,
    pixel: [u32; 2],
    frame: u32,
    index: u32,
    dim: u32,
) -> [f64; 4] {
    four(|k| s.sample(pixel, frame, index, dim + k))
}

/// The `randomize` parameter of the pbrt-compatible families (`sobol.padded`, `zsobol`).
pub(crate) const RANDOMIZE: ParamSpec = ParamSpec {
    name: "randomize",
    kind: Kind::Choice(&["none", "xor", "fastowen", "owen"]),
    default: Default::Word("fastowen"),
    doc: "pbrt-v4's RandomizeStrategy: none, xor (PermuteDigits), fastowen (FastOwen), owen (Owen)",
};

/// spp a power of two.
pub(crate) const POWER_OF_TWO_SPP: Counts =
    Counts::Listed { rule: "spp a power of two", list: |_, _| Box::new((0..32).map(|k| 1usize << k)) };

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_is_consistent_and_every_family_prepares() {
        assert_eq!(PIXEL_SAMPLERS.problems(), Vec::<String>::new());
        let film = Film { width: 5, height: 3, spp: 4, dims: 6 };
        for e in PIXEL_SAMPLERS.iter() {
            let p = prepare(e.about.name, film, Seed(1)).unwrap();
            assert_eq!(prepare(p.spec(), film, Seed(1)).unwrap().spec(), p.spec(), "spec round trip");
            let v = p.fill(2).unwrap();
            assert_eq!(v.len(), 2 * 5 * 3 * 4 * 6);
            assert!(v.iter().all(|x| (0.0..1.0).contains(x)), "{}", e.about.name);
        }
    }

    #[test]
    fn bad_films_and_keys_are_named() {
        let film = Film { width: 4, height: 4, spp: 3, dims: 2 };
        let e = prepare("zsobol", film, Seed(1)).unwrap_err().to_string();
        assert_eq!(e, "spp = 3: zsobol: spp a power of two: try 2 and 4");
        let e = prepare("sobol", Film { dims: 5000, ..film }, Seed(1)).unwrap_err().to_string();
        assert!(e.contains("5000D is not supported"), "{e}");
        let e = prepare("zsobol", Film { width: 0, ..film }, Seed(1)).unwrap_err().to_string();
        assert!(e.starts_with("res = 0x4: a film side"), "{e}");
        let p = prepare("independent", film, Seed(1)).unwrap();
        assert_eq!(p.try_sample([0, 4], 0, 0, 0).unwrap_err().to_string(), "y = 4: must be below 4");
        assert_eq!(p.try_sample([0, 0], 0, 0, 1).unwrap(), p.sample([0, 0], 0, 0, 1));
    }
}
