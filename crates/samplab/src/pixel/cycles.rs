//! Blender Cycles' five sampling patterns (its `kernel/sample/pattern.h` and the settings
//! `scene/integrator.cpp` derives), bit for bit against a fixture of the values Cycles' own
//! source prints (`tests/fixtures/cycles_patterns.txt`): shuffled Owen-scrambled Sobol' per pixel
//! (`sobol_burley`), 256 precomputed 4D tables shuffled per pixel and dimension, with its
//! scrambling distance (`tabulated_sobol`), and one Sobol' sequence over the screen whose
//! per-pixel sections follow a scrambled Morton curve, for blue-noise error
//! (`blue_noise_pure`, `blue_noise_first`, `blue_noise_round`).
//!
//! Dimension d is component d % 2 of Cycles' 2D draw (`path_rng_2D`) for the dimension set
//! d / 2 (its kernel draws pairs and triples, never 4D); the seed's low 32 bits are Cycles' seed, and frame f > 0 draws with
//! `hash_uint2(seed, f)`, the seed Cycles gives each frame of its pixel jitter.

use std::sync::Arc;

use super::{Family, Film, Mapping, MappingKind, PixelEntry, PixelSampler};
use crate::construct::counts::ANY;
use crate::construct::cycles::{
    SobolBurley, hash_iqnt2d, hash_shuffle, hash_uint, hash_uint2, hash_wang_seeded, morton2d, nested_uniform_scramble,
    nested_uniform_scramble_base4, tabulated_sobol, to_unit,
};
use crate::error::Result;
use crate::progress::Progress;
use crate::registry::About;
use crate::seed::Seed;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The tabulated patterns: how many, and their least and most points (Cycles' constants).
const PATTERNS: u32 = 256;
const MIN_TABLE: u32 = 256;
const MAX_TABLE: u32 = 8192;

/// The scrambling distance of the tabulated patterns.
const SCRAMBLING: ParamSpec = ParamSpec {
    name: "scrambling",
    kind: Kind::Real { min: 0.0, max: 1.0 },
    default: Default::Number(1.0),
    doc: "Cycles' scrambling distance: below 1, every pixel reads the same shuffled tables and \
          each adds its own Cranley-Patterson shift of at most this much per dimension",
};

/// Which pattern.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Pattern {
    SobolBurley,
    Tabulated,
    BluePure,
    BlueFirst,
    BlueRound,
}

const HOW: &str = "Cycles' path_rng_2D(rng_pixel, sample, d / 2) draws dimensions 2(d / 2) and 2(d / 2) + 1";

macro_rules! entries {
    ($($name:literal, $pattern:ident, $params:expr, $summary:literal;)+) => {
        pub(crate) static ENTRIES: &[PixelEntry] = &[$(PixelEntry {
            about: About::new($name, $summary).params($params).cite(&["cycles"]),
            spp: ANY,
            dims_note: "2D domains",
            max_dims: super::MAX_DIMS,
            mapping: Mapping { kind: MappingKind::External, family: "sobol", how: HOW },
            build: |p: &Params, film: Film, seed: Seed, _: &Progress<'_>| -> Result<Family> {
                Ok(Family::from(Cycles::new(Pattern::$pattern, p, film, seed)))
            },
        }),+];
    };
}

entries! {
    "cycles.sobol-burley", SobolBurley, &[],
        "Cycles' Sobol-Burley: shuffled Owen-scrambled Sobol' per pixel, 4D padded";
    "cycles.tabulated-sobol", Tabulated, &[SCRAMBLING],
        "Cycles' tabulated Sobol': 256 precomputed Owen-scrambled Sobol' 4D tables, shuffled per pixel";
    "cycles.blue-noise-pure", BluePure, &[],
        "Cycles' blue noise (pure): one Sobol' sequence over the screen along a scrambled Morton curve";
    "cycles.blue-noise-first", BlueFirst, &[],
        "Cycles' blue noise (first): a 1-spp blue-noise sequence for sample 0, another for the rest";
    "cycles.blue-noise-round", BlueRound, &[],
        "Cycles' blue noise (round): pure, each pixel's section rounded up to a power of two";
}

/// One Cycles pattern under the settings Cycles derives from the film's sample count and
/// the seed.
#[derive(Debug)]
pub(crate) struct Cycles {
    /// Sobol-Burley, tabulated, or blue noise (round is pure with a rounded length).
    pattern: Pattern,
    /// The seed as given, and frame 0's (the blue-noise patterns hash it).
    seed: u32,
    seed0: u32,
    /// The shuffled index mask of Sobol-Burley.
    mask: u32,
    /// The samples of one pixel's section of the blue-noise sequence.
    length: u32,
    /// Tabulated: the scrambling distance, the points per table and the tables.
    scrambling: f32,
    size: u32,
    tables: Arc<[[f32; 4]]>,
    /// Sobol' dimensions 0-3 (the other patterns).
    sobol: SobolBurley,
}

/// Cycles' `next_power_of_two`: the least power of two above x (1 for 0).
fn next_power_of_two(x: u32) -> u32 {
    if x == 0 { 1 } else { 1u32.checked_shl(32 - x.leading_zeros()).unwrap_or(0) }
}

impl Cycles {
    fn new(pattern: Pattern, p: &Params, film: Film, seed: Seed) -> Cycles {
        let spp = film.spp.min(1 << 24);
        let mut length = spp;
        if pattern == Pattern::BlueRound && !spp.is_power_of_two() {
            length = next_power_of_two(spp);
        }
        if pattern == Pattern::BlueFirst {
            length -= 1;
        }
        let (scrambling, size, tables) = if pattern == Pattern::Tabulated {
            let size = next_power_of_two(spp - 1).clamp(MIN_TABLE, MAX_TABLE);
            let tables: Vec<[f32; 4]> = (0..PATTERNS).flat_map(|j| tabulated_sobol(size as usize, j)).collect();
            (p.real("scrambling") as f32, size, tables.into())
        } else {
            (1.0, 0, Arc::from(Vec::new()))
        };
        let given = seed.0 as u32;
        Cycles {
            pattern,
            seed: given,
            seed0: if matches!(pattern, Pattern::SobolBurley | Pattern::Tabulated) { given } else { hash_uint(given) },
            mask: (next_power_of_two(spp - 1).wrapping_sub(1)).reverse_bits(),
            length,
            scrambling,
            size,
            tables,
            sobol: SobolBurley::new(),
        }
    }

    /// The integrator's seed for a frame: the seed (hashed for the blue-noise patterns) in
    /// frame 0, `hash_uint2(seed, frame)` after.
    #[inline(always)]
    fn kernel_seed(&self, frame: u32) -> u32 {
        if frame == 0 { self.seed0 } else { hash_uint2(self.seed, frame) }
    }

    /// The 2D draw of dimension set `set` (`path_rng_2D`).
    #[inline(always)]
    fn block(&self, [x, y]: [u32; 2], frame: u32, sample: u32, set: u32) -> [f32; 2] {
        let seed = self.kernel_seed(frame);
        match self.pattern {
            Pattern::SobolBurley => self.sobol.sample_2d(sample, set, hash_iqnt2d(x, y) ^ seed, self.mask),
            Pattern::Tabulated => self.tabulated(hash_iqnt2d(x, y) ^ seed, seed, sample, set),
            Pattern::BluePure | Pattern::BlueRound | Pattern::BlueFirst => {
                let pixel = nested_uniform_scramble_base4(morton2d(x, y), seed);
                if self.pattern == Pattern::BlueFirst && sample == 0 {
                    return self.sobol.sample_2d(pixel, set, 0x0cd0_519f, u32::MAX);
                }
                let first = u32::from(self.pattern == Pattern::BlueFirst);
                self.sobol.sample_2d((sample - first).wrapping_add(pixel.wrapping_mul(self.length)), set, 0, u32::MAX)
            }
        }
    }

    /// A tabulated 2D draw (`tabulated_sobol_sample_2D`: the first two values of the
    /// table's 4D point).
    #[inline(always)]
    fn tabulated(&self, rng_hash: u32, kernel_seed: u32, sample: u32, set: u32) -> [f32; 2] {
        let seed = if self.scrambling < 1.0 { kernel_seed } else { rng_hash };
        let pattern = hash_shuffle(set, PATTERNS, seed);
        let mask = self.size - 1;
        let shuffled = nested_uniform_scramble(sample, hash_wang_seeded(set, seed));
        let sample = (sample & !mask) | (shuffled & mask);
        // Cycles' `% (size * 256)` of 32-bit arithmetic: the tables' length, a power of two
        // that divides 2^32, so a mask of the exact sum
        let index = (pattern as usize * self.size as usize + sample as usize) & (self.tables.len() - 1);
        let point = self.tables[index];
        let mut v = [point[0], point[1]];
        if self.scrambling < 1.0 {
            for (k, x) in v.iter_mut().enumerate() {
                let jitter = to_unit(hash_wang_seeded(set, rng_hash ^ JITTER_KEYS[k])) * self.scrambling;
                *x += jitter;
                *x -= x.floor();
            }
        }
        v
    }
}

/// The keys of the two dimensions' scrambling-distance shifts.
const JITTER_KEYS: [u32; 2] = [0, 0xca0e_1151];

impl PixelSampler for Cycles {
    #[inline(always)]
    fn sample(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> f64 {
        f64::from(self.block(pixel, frame, index, dim / 2)[(dim % 2) as usize])
    }

    #[inline(always)]
    fn sample4(&self, pixel: [u32; 2], frame: u32, index: u32, dim: u32) -> [f64; 4] {
        if !dim.is_multiple_of(2) {
            return super::one_by_one(self, pixel, frame, index, dim);
        }
        let ([a, b], [c, d]) = (self.block(pixel, frame, index, dim / 2), self.block(pixel, frame, index, dim / 2 + 1));
        [a, b, c, d].map(f64::from)
    }
}
