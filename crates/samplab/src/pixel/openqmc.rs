//! OpenQMC's six production samplers through `openqmc-rs` (a port that reproduces OpenQMC's
//! values bit for bit against golden vectors from its C++ headers), so that production
//! samplers sit in the same tables as samplab's.

use std::marker::PhantomData;

use openqmc::{Sampler, SamplerImpl};

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
    ($($name:literal => $sampler:ident, $family:literal, $summary:literal;)+) => {
        pub(crate) static ENTRIES: &[PixelEntry] = &[$(PixelEntry {
            about: About::new($name, $summary).cite(&["openqmc"]),
            spp: ANY,
            dims_note: "4D domains",
            max_dims: super::MAX_DIMS,
            mapping: Mapping { kind: MappingKind::External, family: $family, how: HOW },
            build: |_: &Params, _: Film, seed: Seed, _: &Progress<'_>| -> Result<Family> {
                Ok(Family::from(OpenQmc::<openqmc::$sampler>::new(seed)))
            },
        }),+];
    };
}

entries! {
    "openqmc.sobol" => SobolSampler, "sobol", "OpenQMC's SobolSampler: Owen-scrambled Sobol' per pixel";
    "openqmc.sobolbn" => SobolBnSampler, "sobol", "OpenQMC's SobolBnSampler: Sobol' with blue-noise key and rank tables";
    "openqmc.pmj" => PmjSampler, "pmj02", "OpenQMC's PmjSampler: progressive multi-jittered (0,2) from a table";
    "openqmc.pmjbn" => PmjBnSampler, "pmj02", "OpenQMC's PmjBnSampler: pmj with blue-noise key and rank tables";
    "openqmc.lattice" => LatticeSampler, "lattice", "OpenQMC's LatticeSampler: a randomized rank-1 lattice";
    "openqmc.latticebn" => LatticeBnSampler, "lattice", "OpenQMC's LatticeBnSampler: lattice with blue-noise tables";
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
