//! OpenQMC's six production samplers through `openqmc-rs` (a port that reproduces OpenQMC's
//! values bit for bit against golden vectors from its C++ headers), so that production
//! samplers sit in the same tables as samplab's; and its `SobolSampler` as its pull request
//! #108 remade it, on the SZ matrices ([`crate::construct::sz`]): `openqmc-rs`'s state,
//! domains and scrambles, the matrices of dimensions 2 and 3 samplab's (checked bit for bit
//! against a fixture of the values that source prints, `tests/fixtures/openqmc_sz.txt`).

use std::marker::PhantomData;

use openqmc::owen::scramble_and_reverse;
use openqmc::permute::reverse_and_shuffle;
use openqmc::rotate::rotate_bytes;
use openqmc::{Sampler, SamplerImpl, State64Bit, pcg};

use super::{one_by_one, Family, Film, Mapping, MappingKind, PixelEntry, PixelSampler};
use crate::construct::{counts::ANY, unit};
use crate::error::Result;
use crate::registry::About;
use crate::progress::Progress;
use crate::seed::Seed;
use crate::spec::Params;

const HOW: &str = "Sampler::new(x, y, frame, index).new_domain(seed).new_domain(d / 4) \
                       draws dimensions 4(d / 4) .. 4(d / 4) + 3 (the seed's low 32 bits as the key); \
                       indices stratified up to 2^16";

macro_rules! entries {
    ($($name:literal => $sampler:ty, $family:literal, [$($cite:literal),+], $summary:literal;)+) => {
        pub(crate) static ENTRIES: &[PixelEntry] = &[$(PixelEntry {
            about: About::new($name, $summary).cite(&[$($cite),+]),
            spp: ANY,
            dims_note: "4D domains",
            max_dims: super::MAX_DIMS,
            mapping: Mapping { kind: MappingKind::External, family: $family, how: HOW },
            build: |_: &Params, _: Film, seed: Seed, _: &Progress<'_>| -> Result<Family> {
                Ok(Family::from(OpenQmc::<$sampler>::new(seed)))
            },
        }),+];
    };
}

entries! {
    "openqmc.sobol" => openqmc::SobolSampler, "sobol", ["openqmc"], "OpenQMC's SobolSampler: Owen-scrambled Sobol' per pixel";
    "openqmc.sobolbn" => openqmc::SobolBnSampler, "sobol", ["openqmc"], "OpenQMC's SobolBnSampler: Sobol' with blue-noise key and rank tables";
    "openqmc.pmj" => openqmc::PmjSampler, "pmj02", ["openqmc"], "OpenQMC's PmjSampler: progressive multi-jittered (0,2) from a table";
    "openqmc.pmjbn" => openqmc::PmjBnSampler, "pmj02", ["openqmc"], "OpenQMC's PmjBnSampler: pmj with blue-noise key and rank tables";
    "openqmc.lattice" => openqmc::LatticeSampler, "lattice", ["openqmc"], "OpenQMC's LatticeSampler: a randomized rank-1 lattice";
    "openqmc.latticebn" => openqmc::LatticeBnSampler, "lattice", ["openqmc"], "OpenQMC's LatticeBnSampler: lattice with blue-noise tables";
    "openqmc.sz" => SzSampler, "sz", ["openqmc", "ahmed2025sz"], "OpenQMC's SobolSampler since its PR #108: Owen-scrambled SZ per pixel";
}

/// The 16-bit SZ matrices as OpenQMC's draw reads them: for each dimension and each byte
/// (low, high) of the bit-reversed 16-bit index, the XOR of the columns its set bits select,
/// with the value's digits reversed (bit b the digit of weight 2^-(b+1)), as
/// `openqmc::owen::scramble_and_reverse` takes them. Bit k of the reversed index is digit
/// 15 - k of the index.
const SZ_TABLES: [[[u16; 256]; 2]; 4] = {
    let mut tables = [[[0u16; 256]; 2]; 4];
    let mut d = 0;
    while d < 4 {
        let mut half = 0;
        while half < 2 {
            let mut byte = 0;
            while byte < 256 {
                let mut value = 0u16;
                let mut k = 0;
                while k < 8 {
                    if byte >> k & 1 == 1 {
                        let column = crate::construct::sz::SZ[d][15 - (k + 8 * half)];
                        value ^= ((column >> 16) as u16).reverse_bits();
                    }
                    k += 1;
                }
                tables[d][half][byte] = value;
                byte += 1;
            }
            half += 1;
        }
        d += 1;
    }
    tables
};

/// OpenQMC's `SobolSampler` after its pull request #108: the state and domain tree of
/// `openqmc::SobolImpl`, its index shuffle and Owen scramble (Burley 2020), the SZ matrices.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SzImpl {
    state: State64Bit,
}

/// [`SzImpl`] behind OpenQMC's domain-tree interface.
pub(crate) type SzSampler = Sampler<SzImpl>;

impl SamplerImpl for SzImpl {
    #[inline]
    fn from_pixel(x: i32, y: i32, frame: i32, index: i32) -> Self {
        SzImpl { state: State64Bit::new(x, y, frame, index).pixel_decorrelate() }
    }

    #[inline]
    fn new_domain(&self, key: i32) -> Self {
        SzImpl { state: self.state.new_domain(key) }
    }

    #[inline]
    fn new_domain_split(&self, key: i32, size: i32, index: i32) -> Self {
        SzImpl { state: self.state.new_domain_split(key, size, index) }
    }

    #[inline]
    fn new_domain_distrib(&self, key: i32, index: i32) -> Self {
        SzImpl { state: self.state.new_domain_distrib(key, index) }
    }

    #[inline]
    fn draw_block(&self) -> [u32; 4] {
        let seed = pcg::output(self.state.pattern_id);
        let reversed = (reverse_and_shuffle(u32::from(self.state.sample_id), seed) >> 16) as usize;
        std::array::from_fn(|d| {
            let value = SZ_TABLES[d][0][reversed & 0xff] ^ SZ_TABLES[d][1][reversed >> 8];
            scramble_and_reverse(u32::from(value), rotate_bytes(seed, d as i32))
        })
    }

    #[inline]
    fn draw_rnd_block(&self) -> [u32; 4] {
        self.state.draw_rnd::<4>()
    }

    #[inline]
    fn rng(&self) -> pcg::Rng {
        self.state.rng()
    }
}

/// One OpenQMC sampler type, keyed by samplab's seed.
pub(crate) struct OpenQmc<S> {
    key: i32,
    kind: PhantomData<fn() -> S>,
}

impl<S> std::fmt::Debug for OpenQmc<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "OpenQmc({})", std::any::type_name::<S>())
    }
}

impl<T: SamplerImpl> OpenQmc<Sampler<T>> {
    fn new(seed: Seed) -> Self {
        OpenQmc { key: seed.0 as u32 as i32, kind: PhantomData }
    }

    /// The 4D block of domain `block`.
    #[inline(always)]
    fn block(&self, pixel: [u32; 2], frame: u32, index: u32, block: u32) -> [u32; 4] {
        Sampler::<T>::new(pixel[0] as i32, pixel[1] as i32, frame as i32, index as i32)
            .new_domain(self.key)
            .new_domain(block as i32)
            .draw_sample::<4>()
    }
}

impl<T: SamplerImpl + 'static> PixelSampler for OpenQmc<Sampler<T>> {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        unit(self.block(pixel, frame, index, dim / 4)[(dim % 4) as usize])
    }

    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        if !dim.is_multiple_of(4) {
            return one_by_one(self, pixel, frame, index, dim);
        }
        self.block(pixel, frame, index, dim / 4).map(unit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sz_tables_in_dimensions_0_and_1_are_openqmc_rs_sobol() {
        // dimensions 0 and 1 of SZ are Sobol's, which openqmc-rs reads from OpenQMC's own
        // table: every 16-bit index gives the same value; dimensions 2 and 3 differ
        for (d, same) in [(0, true), (1, true), (2, false), (3, false)] {
            let equal = (0..=u16::MAX).all(|i| {
                let ours = SZ_TABLES[d][0][usize::from(i & 0xff)] ^ SZ_TABLES[d][1][usize::from(i >> 8)];
                ours == openqmc::owen::sobol_reversed_index(i, d)
            });
            assert_eq!(equal, same, "dimension {d}");
        }
    }
}
