//! Subr & Kautz 2013, "Fourier analysis of stochastic sampling strategies for assessing
//! bias and variance in integration": Figures 2, 4 and 11 (spectra and their closed forms),
//! 5 and 6 (bias, variance and convergence exponents on test cases I-III), 7-9 (defocus,
//! soft shadows and motion blur, rendered) and 10 (uniform jitter combined with Gaussian
//! jitter on a zone plate).

mod asymptotics;
mod convergence;
mod jitter_theory;
mod rendered;
mod spectra;
mod zoneplate;

use crate::plot::{LineChart, Series};
use crate::{Experiment, Paper};
use asymptotics::asymptotics;
use convergence::convergence;
use jitter_theory::jitter_theory;
use rendered::{defocus, motion, shadows};
use spectra::spectra;
use zoneplate::zoneplate;

/// The paper's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "subr2013",
        title: "Subr & Kautz 2013",
        experiments: vec![
            Experiment {
                id: "spectra",
                title: "Periodogram, amplitude of the expected spectrum, and variance of the spectrum",
                source: "Figure 2",
                parameters: "256 points, 20 realizations (the paper's); 256 x 256 frequencies (fast) or 512 x 512 (full); non-uniform FFT at tolerance 1e-9",
                run: spectra,
            },
            Experiment {
                id: "jitter-theory",
                title: "Expected spectrum and spectrum variance of Gaussian and box jitter",
                source: "Figures 4 and 11, eqs. 8-11",
                parameters: "closed forms (exact and second order) against measurements of 16 x 16 grids (N = 256): the spectrum's variance over 200 (fast) or 800 (full) jitterings, on 64 x 64 frequencies; eq. 6 on a plane wave over 2000 (fast) or 8000 (full)",
                run: jitter_theory,
            },
            Experiment {
                id: "convergence",
                title: "Bias, variance and convergence exponents on test cases I-III",
                source: "Figures 5 and 6",
                parameters: "12 strategies; 10 instances x 50 realizations (the paper's); N = 16, 64, 256, 1024 (fast) or N = 16, 36, 64, 144, 256, 576, 1024 (full)",
                run: convergence,
            },
            Experiment {
                id: "asymptotics",
                title: "Convergence exponents at larger N on an integrand with edges",
                source: "Figure 6 (samplab's check of its explanation)",
                parameters: "test case I; jitter and Gaussian jitter 0.1, 0.25; 10 instances x 50 realizations; N = 1024 to 9216 (fast) or 36864 (full)",
                run: asymptotics,
            },
            Experiment {
                id: "shadows",
                title: "Soft shadows of a disc light above a square occluder: bias and variance per strategy",
                source: "Figure 8",
                parameters: "N = 16 shadow rays per estimate, 1, 4 and 16 secondary estimates per pixel; 7 strategies; 80 x 60 pixels, 12 seeds (fast) or 160 x 120, 32 seeds (full)",
                run: shadows,
            },
            Experiment {
                id: "defocus",
                title: "Defocus: bias and variance of the strategies over the pixel and lens",
                source: "Figure 7",
                parameters: "16 estimates per pixel; 7 strategies; emissive beads out of focus; 128 x 96 pixels, 12 seeds (fast) or 320 x 240, 32 seeds (full)",
                run: defocus,
            },
            Experiment {
                id: "motion",
                title: "Motion blur: bias and variance of the strategies over the shutter interval",
                source: "Figure 9",
                parameters: "4 and 64 estimates per pixel; 7 strategies (1D); a sphere moving across the frame; 80 x 60 pixels, 12 seeds (fast) or 160 x 120, 32 seeds (full)",
                run: motion,
            },
            Experiment {
                id: "zoneplate",
                title: "Uniform jitter with offset scale alpha combined with Gaussian jitter sigma, on a zone plate",
                source: "Figure 10",
                parameters: "N = 256 (16 x 16); zone plate (1 + cos(200 r^2))/2; 200 (fast) or 1000 (full) realizations per (alpha, sigma)",
                run: zoneplate,
            },
        ],
    }
}

/// The paper's strategy names and our specs. Box jitter "within 0.1 times the width of
/// each stratum" is read as a box 0.1 cells wide (half-width 0.05); the low-discrepancy
/// sets are scrambled, as the paper's Matlab ones were.
pub(super) const STRATEGIES: [(&str, &str); 12] = [
    ("Random", "random"),
    ("Poisson disk", "poisson"),
    ("Jittered", "jitter"),
    ("Sobol", "sobol.owen"),
    ("Halton", "halton.xor"),
    ("LHCube", "nrooks"),
    ("Hammersley", "hammersley.xor"),
    ("BJittered:0.1", "jitter.box:delta=0.05"),
    ("GJittered:0.1", "jitter.gaussian:sigma=0.1"),
    ("GJittered:0.25", "jitter.gaussian:sigma=0.25"),
    ("GJittered:0.5", "jitter.gaussian:sigma=0.5"),
    ("GJittered:1", "jitter.gaussian:sigma=1"),
];

pub(super) const CASES: [(&str, &str); 3] = [
    ("I (binary)", "quad"),
    ("II (piecewise constant)", "delaunay-constant"),
    ("III (piecewise linear)", "delaunay-linear"),
];

/// Whether a row's canonical sampler spec comes from the listed `spec`.
pub(super) fn sampler_spec_matches(spec: &str, canonical: &str) -> bool {
    samplab::sampler::build(spec).map(|s| s.spec() == canonical).unwrap_or(false)
}

/// Relative variance against N on log-log axes (Fig. 5's bottom row and the large-N check).
pub(super) fn variance_chart(title: String, series: Vec<Series>) -> LineChart {
    LineChart {
        title,
        x_label: "N (samples per estimate)".into(),
        y_label: "variance / mean^2".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    }
}
