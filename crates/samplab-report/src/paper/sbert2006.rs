//! Sbert, Rigau, Feixas & Neumann 2006, "Systematic sampling in image synthesis".

use crate::Paper;

/// The paper's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "sbert2006",
        title: "Sbert et al. 2006",
        experiments: vec![],
        pending: vec![
            (
                "Figure 3 and the k B u^3 law (efficiency of systematic and stratified sampling of a circle's area)",
                "needs the integration harness (issue: integration experiments)",
            ),
            ("Table 1 (MSE of offsets x points per pixel)", "needs the renderer (issue: soft-shadow renderer)"),
        ],
    }
}
