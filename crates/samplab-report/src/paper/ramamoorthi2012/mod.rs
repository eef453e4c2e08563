//! Ramamoorthi, Anderson, Meyer & Nowrouzezahrai 2012, "A theory of Monte Carlo
//! visibility sampling": 1D visibility over a linear light (section 4, Figs. 3, 4, 6, 7),
//! and rendered soft shadows from linear, square, circular and Gaussian lights (sections
//! 4.2.3, 6, 7 and 8; Figs. 8, 13, 16-21).

mod pixel_light;
mod rendered;
mod spectra;
mod visibility;

use crate::{Experiment, Paper};
use pixel_light::pixel_light;
use rendered::{complex_occluder, error_vs_n, grids_lights, grids_linear, planar_lights};
use spectra::{gaussian_light, square_light};
use visibility::{discontinuities, error_vs_position, section8, tables};

/// The paper's experiments: the 1D and spectral ones, then the rendered ones.
pub fn paper() -> Paper {
    let mut experiments = one_dimensional();
    experiments.extend(rendered_shadows());
    Paper { key: "ramamoorthi2012", title: "Ramamoorthi et al. 2012", experiments }
}

/// The experiments on 1D visibility and on spectra (sections 4, 5 and 8).
fn one_dimensional() -> Vec<Experiment> {
    vec![
        Experiment {
            id: "error-vs-position",
            title: "Error against the discontinuity's position",
            source: "Figures 3 and 4",
            parameters: "N = 8 samples; 400 positions of the discontinuity; 400 (fast) or 4000 (full) realizations per position for the random strategies",
            run: error_vs_position,
        },
        Experiment {
            id: "tables",
            title: "Theory and simulation, one and two discontinuities",
            source: "Figures 4 and 6",
            parameters: "N = 256; 4000 (fast) or 40000 (full) random visibility functions",
            run: tables,
        },
        Experiment {
            id: "pixel-light",
            title: "Pixel-light Fourier analysis of a linear light",
            source: "Figures 10-11, section 5",
            parameters: "a scanline of 512 pixels, N = 16 light samples each, blocker of 6 bars at depth ratio beta = 3; spectra on 64 x 64 integer frequencies (non-uniform FFT, tolerance 1e-9)",
            run: pixel_light,
        },
        Experiment {
            id: "gaussian-light",
            title: "One discontinuity under a constant and a Gaussian linear light",
            source: "Figure 12",
            parameters: "N = 16; 20000 (fast) or 200000 (full) edges per strategy; spectrum by a 2^14-point midpoint rule",
            run: gaussian_light,
        },
        Experiment {
            id: "square-light",
            title: "An aligned edge on a square light: the sampling comb and the Gaussian",
            source: "Figures 14 and 15",
            parameters: "N = 25 (5 x 5); 20000 (fast) or 200000 (full) edges per strategy; spectra on 64 x 64 integer frequencies",
            run: square_light,
        },
        Experiment {
            id: "discontinuities",
            title: "Normalized variance against the number of discontinuities",
            source: "Figure 7",
            parameters: "N = 256; 1000 trials (the paper's) at both scales; up to 7 and up to 100 discontinuities",
            run: discontinuities,
        },
        Experiment {
            id: "section-8",
            title: "Poisson disk and per-pixel shifted Halton against stratified sampling and uniform jitter",
            source: "Section 8",
            parameters: "1D visibility with 1, 2, 3, 5, 10 and 20 discontinuities; Poisson disk (dart throwing, relative radius 0.7) at N = 256; Halton (base 2, a random offset per estimate) against uniform jitter at N = 256 and 200; 1000 trials x 2 realizations",
            run: section8,
        },
    ]
}

/// The rendered soft shadows (sections 4.2.3, 6 and 7).
fn rendered_shadows() -> Vec<Experiment> {
    vec![
        Experiment {
            id: "grids-linear",
            title: "Rendered soft shadows of three grids from a linear light",
            source: "Figure 8, section 4.2.3",
            parameters: "16 light samples per pixel (visibility mode, pixel centres); 96 x 72 (fast) or 256 x 192 (full) pixels; 4 (fast) or 8 (full) seeds; reference 2048 (fast) or 8192 (full) Owen-scrambled Sobol' samples",
            run: grids_linear,
        },
        Experiment {
            id: "planar-lights",
            title: "Square, circular and Gaussian lights: stratified against uniform jitter",
            source: "Figures 13, 16 and 18, section 6",
            parameters: "25 light samples per pixel (disk lights: rejection from the 5 x 5 pattern, about 20 kept, as the paper's section 7); spheres and sphere-box scenes; 96 x 72 (fast) or 256 x 192 (full); 3 (fast) or 8 (full) seeds; reference 2048 (fast) or 8192 (full) samples",
            run: planar_lights,
        },
        Experiment {
            id: "grids-lights",
            title: "The grids under circular, square and Gaussian lights",
            source: "Figures 17 and 19",
            parameters: "both grid geometries; circular light 25 samples (rejection, about 20 kept; Halton with the Shirley-Chiu warp 25), square and Gaussian 16; 96 x 72 (fast) or 256 x 192 (full); 3 (fast) or 8 (full) seeds; reference 2048 (fast) or 8192 (full) samples",
            run: grids_lights,
        },
        Experiment {
            id: "error-vs-n",
            title: "Error against the number of samples, grids scene",
            source: "Figure 20",
            parameters: "both grid geometries; circular (rejection) and Gaussian lights; N = 4 .. 64 (squares); 64 x 48 (fast) or 160 x 120 (full); 2 (fast) or 6 (full) seeds",
            run: error_vs_n,
        },
        Experiment {
            id: "complex-occluder",
            title: "Very complex shadows: random, stratified and uniform jitter against N",
            source: "Figure 21",
            parameters: "the fibers scene (400 thin random fibres) in place of the unpublished tentacles; circular (rejection) and square lights; N = 4, 16, 64; 64 x 48 (fast) or 160 x 120 (full); 3 (fast) or 6 (full) seeds; reference 1024 (fast) or 8192 (full) samples",
            run: complex_occluder,
        },
    ]
}

/// The paper's names for our samplers, in 1D.
const STRATEGIES: [(&str, &str); 4] =
    [("uniform", "regular"), ("stratified", "jitter"), ("uniform jitter", "jitter.uniform"), ("Halton", "halton")];
