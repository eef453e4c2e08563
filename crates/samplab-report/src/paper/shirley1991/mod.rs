//! Shirley 1991, "Discrepancy as a quality measure for sample distributions": Tables 1-4
//! (pixel luminance errors on the checker, checker-45, ball and all images), Tables 5, 6
//! and 7 (star, RMS and Stroud discrepancies of 100 sets of 16 points per strategy) and
//! the projected discrepancy of section 3.1 and the conclusion's open question.

mod discrepancies;
mod images;
mod nonuniform;

use samplab::discrepancy::{self, Limits, Metric};
use samplab::{PointSet, Seed, sampler};

use crate::{Error, Experiment, Paper};
use discrepancies::{projected, tables};
use images::pixel_errors;
use nonuniform::nonuniform;

/// The paper's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "shirley1991",
        title: "Shirley 1991",
        experiments: vec![
            Experiment {
                id: "pixel-errors",
                title: "Pixel luminance errors of 16 samples per pixel",
                source: "Tables 1, 2, 3 and 4",
                parameters: "128 x 96 pixels (the paper's), 16 samples per pixel from each strategy over the pixel area (and, for the ball and all, the same strategy over each light, the lens and the gloss, dealt to the pixel samples in random orders); 4 (fast) or 8 (full) seeds per strategy; errors of the displayed images (clamped to [0, 1]); reference 256 (fast) or 1024 (full) Owen-scrambled Sobol' samples per pixel",
                run: pixel_errors,
            },
            Experiment {
                id: "tables-5-7",
                title: "Discrepancies of the sampling strategies",
                source: "Tables 5, 6 and 7",
                parameters: "100 sets of 16 points per strategy at both scales (the paper's own); 20000 (fast) or 100000 (full) sets of half-jittered and separate points to order their S; Poisson disks by dart throwing with distances measured inside the square",
                run: tables,
            },
            Experiment {
                id: "nonuniform",
                title: "Non-uniform sample distributions: warps and the generalized discrepancy",
                source: "Section 4, eqs. 1-2, Figures 7 and 8",
                parameters: "16 jittered points (one set drawn); 100 sets of 16 points per strategy for the generalized discrepancy, by brute force over every critical rectangle",
                run: nonuniform,
            },
            Experiment {
                id: "projected",
                title: "Projected discrepancy against direction",
                source: "Section 3.1 and the conclusion's open question",
                parameters: "100 sets of 16 points; directions every 1 degree (fast) or 0.5 degrees (full); extreme 1D discrepancy of the projections against their exact distribution",
                run: projected,
            },
        ],
    }
}

/// Shirley's strategies: his name and our spec.
pub(super) const STRATEGIES: [(&str, &str); 7] = [
    ("separate", "nrooks"),
    ("half-jittered", "jitter.half"),
    ("jittered", "jitter"),
    ("poisson (d = 0.2)", "poisson:radius=0.2,edge=plain"),
    ("regular", "regular"),
    ("poisson (d = 0.1)", "poisson:radius=0.1,edge=plain"),
    ("random", "random"),
];

pub(super) const SETS: usize = 100;

/// Lattice for the restricted Stroud discrepancy: corners at multiples of 1/20.
pub(super) const LATTICE: usize = 20;
pub(super) const N: usize = 16;

pub(super) fn sets_of(spec: &str, seed: Seed) -> Result<Vec<PointSet>, Error> {
    let s = sampler::build(spec)?;
    Ok(sampler::generate_sets(&s, N, 2, seed, SETS)?)
}

pub(super) fn metric_values(sets: &[PointSet], m: &Metric) -> Result<Vec<f64>, Error> {
    use rayon::prelude::*;
    Ok(sets.par_iter().map(|s| discrepancy::compute(m, s, Limits::default())).collect::<Result<_, _>>()?)
}
