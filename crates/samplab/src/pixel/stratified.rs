//! Jittered strata per pixel with dimension padding (Cook 1986; as pbrt's
//! `StratifiedSampler`, with hashed permutations instead of its stream of draws).

use super::{Family, Film, Pairs, PixelEntry, Keys, rekey, Mapping, MappingKind};
use crate::construct::counts::ANY;
use crate::error::Result;
use crate::numeric::BELOW_ONE;
use crate::registry::About;
use crate::construct::scramble::permute;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "stratified",
        "jittered a x b strata per pixel for each pair of dimensions, a the largest divisor of spp \
         not above its square root",
    )
    .aliases(&["pixel.stratified", "stratified.padded"])
    .cite(&["cook1986", "pharr2023", "kensler2013"]),
    spp: ANY,
    dims_note: "pairs of 2D strata",
    max_dims: super::MAX_DIMS,
    mapping: Mapping {
        kind: MappingKind::Padded,
        family: "jitter",
        how: "dimensions 2k, 2k+1 put sample i in stratum pi(i) of an a x b grid, \
              jittered, pi a hashed permutation of (seed, pixel, frame, k); every pair of a pixel's \
              samples is stratified, different pairs are independent",
    },
    build,
}];

#[derive(Debug)]
pub(crate) struct Stratified {
    keys: Keys,
    spp: u32,
    /// Columns (x strata) and rows (y strata), columns >= rows.
    columns: u32,
    rows: u32,
}

fn build(_: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let rows = (1..=film.spp.isqrt()).rev().find(|a| film.spp.is_multiple_of(*a)).unwrap_or(1);
    Ok(Family::from(Stratified { keys: Keys::new(seed, 0), spp: film.spp, columns: film.spp / rows, rows }))
}

impl Pairs for Stratified {
    /// The pixel's key.
    type Key = u64;

    fn key(&self, pixel: [u32; 2], frame: u32, _: u32) -> u64 {
        self.keys.pixel(pixel, frame)
    }

    #[inline(always)]
    fn pair(&self, key: u64, _: [u32; 2], _: u32, index: u32, dim: u32) -> [f64; 2] {
        let key = rekey(key, u64::from(dim / 2));
        let stratum = permute(index % self.spp, self.spp, key as u32);
        let jitter = rekey(key, u64::from(index) + 1);
        let (cx, cy) = (stratum % self.columns, stratum / self.columns);
        // the quotient can round up to 1 when a side has more than 2^22 cells
        let u = |cell: u32, bits: u64, cells: u32| {
            ((f64::from(cell) + crate::construct::unit(bits as u32)) / f64::from(cells)).min(BELOW_ONE)
        };
        [u(cx, jitter, self.columns), u(cy, jitter >> 32, self.rows)]
    }
}

