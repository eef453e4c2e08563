//! A rank-1 lattice sequence per pixel: the embedded lattice of Cools, Kuo & Nuyens 2006
//! (fast CBC, Nuyens & Cools 2006) in radical-inverse order, the index shuffled per pixel
//! as Burley 2020 shuffles Sobol', and a random shift per pixel and dimension (Cranley &
//! Patterson 1976).

use super::{four, Family, Film, Keys, PixelEntry, PixelSampler, Mapping, MappingKind};
use crate::construct::unit;
use crate::error::Result;
use crate::registry::About;
use crate::construct::cbc::{self, Weights};
use crate::construct::scramble::owen_scramble_u32;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

/// log2 of the points the generating vector is constructed for (each pixel's first 2^m
/// samples, m up to this, are a shifted lattice chosen for 2^m points).
const M: u32 = 16;

pub(crate) static ENTRIES: &[PixelEntry] = &[PixelEntry {
    about: About::new(
        "lattice",
        "a rank-1 lattice sequence per pixel: the embedded fast-CBC lattice for 2^16 points in radical-inverse \
         order, the index shuffled and every dimension shifted by hashes of (seed, pixel, frame)",
    )
    .aliases(&["pixel.lattice"])
    .cite(&["cools2006", "nuyens2006", "burley2020", "cranley1976"]),
    spp: super::Counts::Any("each pixel's first 2^m samples a shifted lattice, m up to 16"),
    dims_note: "a CBC vector made when prepared: about 0.2 s for 64 dimensions",
    max_dims: 1024,
    mapping: Mapping {
        kind: MappingKind::PerPixel,
        family: "lattice",
        how: "the index nested-uniform scrambled by the pixel's hash maps samples \
              0..2^m to an aligned block of the radical-inverse order, itself a shifted lattice of 2^m \
              points; then a random shift per dimension; value = frac(phi_2(i) z_d + shift)",
    },
    build,
}];

#[derive(Debug)]
pub(crate) struct Lattice {
    keys: Keys,
    z: Vec<u32>,
}

fn build(_: &Params, film: Film, seed: Seed, _: &Progress<'_>) -> Result<Family> {
    let z = cbc::construct(1 << M, film.dims as usize, Weights::decaying(2.0), true)?;
    Ok(Family::from(Lattice { keys: Keys::new(seed, film.dims), z: z.into_iter().map(|zj| zj as u32).collect() }))
}

impl Lattice {
    /// The pixel's key and phi_2 of its shuffled index, as 32-bit fixed point.
    #[inline(always)]
    fn radical(&self, pixel: [u32; 2], frame: u32, index: u32) -> (u32, u32) {
        let key = self.keys.pixel(pixel, frame);
        (key as u32, owen_scramble_u32(index, (key >> 32) as u32).reverse_bits())
    }

    /// frac(phi_2(i) z_d + shift_d), exact in 32-bit fixed point.
    #[inline(always)]
    fn value(&self, key: u32, radical: u32, dim: u32) -> f64 {
        unit(radical.wrapping_mul(self.z[dim as usize]).wrapping_add(self.keys.dim(key, dim)))
    }
}

impl PixelSampler for Lattice {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        let (key, r) = self.radical(pixel, frame, index);
        self.value(key, r, dim)
    }

    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        let (key, r) = self.radical(pixel, frame, index);
        four(|k| self.value(key, r, dim + k))
    }
}
