//! Blue-noise dithered sampling (Georgiev & Fajardo 2016): every pixel draws the same
//! Owen-scrambled Sobol' samples, each pixel toroidally shifted by its value in a
//! blue-noise mask (void-and-cluster, [`super::mask`]), so that neighbouring pixels' errors
//! are negatively correlated and the error spreads as blue noise over the screen.

use super::mask::Mask;
use crate::construct::sobol::{ByteTables, byte_tables, owen_digits, reversed_digits};
use super::{four, Family, Film, Keys, PixelEntry, PixelSampler, Mapping, MappingKind};
use crate::construct::unit;
use crate::error::Result;
use crate::registry::About;
use crate::construct::sobol::SOBOL_MAX_DIMS;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The mask side parameter of the mask-shifted families.
pub(super) const MASK: ParamSpec = ParamSpec {
    name: "mask",
    kind: Kind::Int { min: 4, max: super::mask::MAX_SIZE as u64 },
    default: Default::Int(64),
    doc: "side of the void-and-cluster blue-noise mask, in pixels (it tiles the screen)",
};

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "dither",
        "blue-noise dithered sampling: one Owen-scrambled Sobol' set for every pixel, each pair of \
         dimensions toroidally shifted by a two-channel void-and-cluster mask",
    )
    .aliases(&["dithered", "georgiev-fajardo"])
    .params(&[MASK])
    .cite(&["georgiev2016", "ulichney1993", "burley2020"]),
    spp: super::Counts::Any("the shared set a net at powers of two; shifts keep it a toroidal translate"),
    dims_note: "the Joe-Kuo table",
    max_dims: SOBOL_MAX_DIMS as u32,
    mapping: Mapping {
        kind: MappingKind::Mask,
        family: "sobol",
        how: "one toroidal shift per pixel and pair of dimensions: the mask value at the pixel, the \
              mask itself shifted by a hash of (seed, frame, pair), so pairs and frames see unrelated \
              parts of the same blue noise; the set is the same in every pixel of a frame",
    },
    build,
}];

/// Per-pixel toroidal shifts read from a two-channel blue-noise mask.
#[derive(Debug)]
pub(super) struct Shifts {
    mask: Mask,
    keys: Keys,
}

impl Shifts {
    /// A mask of side `size` for `seed`, and the keys of `pairs` pairs of dimensions.
    pub(super) fn new(size: usize, seed: Seed, pairs: u32) -> Result<Shifts> {
        let mask = Mask::void_and_cluster(size, 2, seed.derive_str("dither mask"))?;
        Ok(Shifts { mask, keys: Keys::new(seed.derive_str("dither offsets"), pairs) })
    }

    /// The shift of `pixel` for the dimension pair `pair` in `frame`, as 32-bit fixed point:
    /// the mask read at the pixel plus an offset keyed by (frame, pair).
    #[inline]
    pub(super) fn shift(&self, pixel: [u32; 2], frame: u32, pair: u32) -> [u32; 2] {
        let f = self.keys.frame(frame);
        let (ox, oy) = (self.keys.dim(f as u32, pair), self.keys.dim((f >> 32) as u32, pair));
        let (x, y) = (pixel[0].wrapping_add(ox), pixel[1].wrapping_add(oy));
        [fixed(self.mask.value(x, y, 0)), fixed(self.mask.value(x, y, 1))]
    }

    /// The mask's values in 32-bit fixed point, row-major, its two channels last.
    pub(super) fn fixed_mask(&self) -> impl Iterator<Item = u32> + '_ {
        self.mask.values().iter().map(|&v| fixed(v))
    }
}

/// A mask value in [0, 1) as 32-bit fixed point (truncated).
#[inline]
fn fixed(v: f64) -> u32 {
    (v * 4_294_967_296.0) as u32
}

#[derive(Debug)]
pub(crate) struct Dither {
    keys: Keys,
    tables: Vec<ByteTables>,
    shifts: Shifts,
}

fn build(p: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    Ok(Family::from(Dither {
        keys: Keys::new(seed, film.dims),
        tables: (0..film.dims as usize).map(byte_tables).collect(),
        shifts: Shifts::new(p.int("mask") as usize, seed, film.dims.div_ceil(2))?,
    }))
}

impl Dither {
    /// Dimension `dim` of sample `index`: the frame's scramble (`frame_key`, shared by every
    /// pixel), shifted by `shift`, the pixel's shift of the dimension's pair.
    #[inline(always)]
    fn value(&self, frame_key: u64, index: u32, dim: u32, shift: [u32; 2]) -> f64 {
        let key = self.keys.dim(frame_key as u32, dim);
        let x = owen_digits(reversed_digits(&self.tables[dim as usize], index), key);
        unit(x.wrapping_add(shift[(dim & 1) as usize]))
    }
}

impl PixelSampler for Dither {
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        self.value(self.keys.frame(frame), index, dim, self.shifts.shift(pixel, frame, dim / 2))
    }

    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        // one frame key and one shift per pair, not per value
        let frame_key = self.keys.frame(frame);
        let mut shift = self.shifts.shift(pixel, frame, dim / 2);
        four(|k| {
            let d = dim + k;
            if k > 0 && d & 1 == 0 {
                shift = self.shifts.shift(pixel, frame, d / 2);
            }
            self.value(frame_key, index, d, shift)
        })
    }
}
