//! Independent uniform values: the baseline every pixel sampler is measured against.

use super::{Family, Film, PixelEntry, PixelSampler, Keys, rekey, Mapping, MappingKind};
use crate::construct::counts::ANY;
use crate::error::Result;
use crate::registry::About;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new("independent", "independent uniform values, 53 random bits each, hashed from every key")
        .aliases(&["pixel.independent"])
        .cite(&["cook1986"]),
    spp: ANY,
    dims_note: "",
    max_dims: super::MAX_DIMS,
    mapping: Mapping {
        kind: MappingKind::Hashed,
        family: "random",
        how: "every value is a hash of (seed, pixel, frame, index, dimension)",
    },
    build,
}];

#[derive(Debug)]
pub(crate) struct Independent(Keys);

fn build(_: &Params, _: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    Ok(Family::from(Independent(Keys::new(seed, 0))))
}

/// The padding of every family past its film's dimensions ([`super::Pixels::sample_padded`]):
/// independent values under a seed derived from `seed`, so that they are not the
/// `independent` family's own values.
pub(crate) fn padding(seed: Seed) -> Independent {
    Independent(Keys::new(seed.derive_str("pixel padding"), 0))
}

impl PixelSampler for Independent {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        let h = rekey(self.0.pixel(pixel, frame), (u64::from(index) << 32) | u64::from(dim));
        (h >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}
