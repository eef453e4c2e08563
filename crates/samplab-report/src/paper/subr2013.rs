//! Subr & Kautz 2013, "Fourier analysis of stochastic sampling strategies for assessing
//! bias and variance in integration".

use crate::Paper;

/// The paper's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "subr2013",
        title: "Subr & Kautz 2013",
        experiments: vec![],
        pending: vec![
            (
                "Figures 2, 4 and 11 (expected spectrum, spectrum variance, theory)",
                "needs the spectrum module (issue: spectral statistics)",
            ),
            (
                "Figures 5, 6 and 10 (bias, variance and convergence exponents on test cases I-III, zone plate)",
                "needs the integration harness (issue: integration experiments)",
            ),
            ("Figures 7-9 (defocus, soft shadows, motion blur)", "needs the renderer (issue: soft-shadow renderer)"),
        ],
    }
}
