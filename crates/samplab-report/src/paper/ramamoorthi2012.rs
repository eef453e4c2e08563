//! Ramamoorthi, Anderson, Meyer & Nowrouzezahrai 2012, "A theory of Monte Carlo
//! visibility sampling".

use crate::Paper;

/// The paper's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "ramamoorthi2012",
        title: "Ramamoorthi et al. 2012",
        experiments: vec![],
        pending: vec![
            (
                "Figures 3, 4, 6 and 7 (1D visibility: error against discontinuity position and count)",
                "needs the integration harness (issue: integration experiments)",
            ),
            ("Figures 10-11 (pixel-light spectra)", "needs the spectrum module (issue: spectral statistics)"),
            (
                "Figures 8, 13, 16-20 (square, circular and Gaussian lights)",
                "needs the renderer (issue: soft-shadow renderer)",
            ),
        ],
    }
}
