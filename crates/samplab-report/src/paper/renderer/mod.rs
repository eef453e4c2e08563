//! Samplers in the renderer: every pixel sampler family ([`samplab::pixel`]) judged on the
//! screen, beside the four papers. The masks of dimensions 0-7 (1 spp), three scenes (a soft
//! shadow, defocus, a path-traced glossy box) at growing sample counts, and the flicker of
//! their error over 16 frames; the claims of the samplers' own papers, and samplab's
//! questions about them, with criteria fixed in this file before any run.

mod ab;
mod masks;
mod scenes;

use crate::criteria::{self, Decision, Estimate};
use crate::{Experiment, Paper};

/// The page's experiments.
pub fn paper() -> Paper {
    Paper {
        key: "renderer",
        title: "Samplers in the renderer",
        experiments: vec![
            Experiment {
                id: "masks",
                title: "Masks: each dimension's 1-spp image, its spectrum and its flicker",
                source: "Ahmed & Wonka 2020, Heitz et al. 2019, Georgiev & Fajardo 2016 (blue-noise error); OpenQMC's issue #71",
                parameters: "every pixel sampler family, default parameters (heitz2019 on a 32-pixel tile at the fast scale), 1 spp, dimensions 0-7, 16 frames of dimension 0; 128 x 128 pixels (fast) or 256 x 256 (full)",
                run: masks::masks,
            },
            Experiment {
                id: "scenes",
                title: "Three scenes: error against spp, blurred error, error spectra, flicker",
                source: "Ahmed & Wonka 2020, Heitz et al. 2019, Georgiev & Fajardo 2016",
                parameters: "every pixel sampler family on sphere-box (direct lighting, one light sample per estimate), defocus (direct lighting, thin lens) and glossy-box (path tracing, max depth 5), over the pixel area; 1, 4, 16 spp at 64 x 64 pixels (fast) or 1 to 1024 spp at 96 x 96 (full; heitz2019 to 256); references: the pixel sampler sobol at 1024 (fast) or 8192 (full) spp; heitz2019 on a 32-pixel tile (fast) or its default 64 (full); 16 frames at 4 spp for the low-frequency energy and the flicker",
                run: scenes::scenes,
            },
            Experiment {
                id: "ab-variance",
                title: "Cycles' A/B variance estimate, per family",
                source: "Blender Cycles' adaptive sampling (sample_is_class_A, after Christensen et al. 2018, section 10.2.1); samplab's question (issue 93)",
                parameters: "every pixel sampler family at 4, 16, 64 spp (fast) or 4 to 1024 (full); 32 x 32 pixels, 64 frames; per pixel a half-plane edge and a Gaussian bump in dimensions 0-1; the A/B estimate (A - B)^2 / 4 against the variance over the frames; bootstrap over the pixels (200 resamples)",
                run: ab::ab_variance,
            },
        ],
    }
}

/// Every pixel sampler family, by registry name, in the registry's order.
fn families() -> Vec<&'static str> {
    use samplab::registry::Entry;
    samplab::pixel::PIXEL_SAMPLERS.iter().map(|e| e.about().name).collect()
}

/// A colour key and a marker flag per family index, all distinct (the figure lint refuses
/// two series drawn alike).
fn look(i: usize) -> (String, bool) {
    const KEYS: [&str; 16] = [
        "random",
        "regular",
        "jitter",
        "jitter.half",
        "nrooks",
        "poisson",
        "jitter.uniform",
        "halton",
        "sobol",
        "pmj02",
        "hammersley",
        "cmj",
        "jitter.box",
        "force-matrix",
        "regular.rotated",
        "floor",
    ];
    (KEYS[i % KEYS.len()].to_string(), i >= KEYS.len())
}

/// The low-frequency energy of a mask or error below which it counts as blue noise, as a
/// share of white noise's (issue 38's criterion).
pub(crate) const BLUE: f64 = 0.3;

/// "an advantage fades as spp grows": the ratio (to the baseline) at the highest count at
/// least `factor` times the ratio at the lowest.
pub(crate) fn fades(what: &str, low: f64, high: f64, factor: f64) -> Decision {
    criteria::exactly(
        high >= factor * low,
        &format!("{what}: ratio {low:.3} at the fewest samples, {high:.3} at the most, at least {factor} times"),
    )
}

/// "a mask is blue noise": its low-frequency energy below [`BLUE`] of white noise's.
pub(crate) fn blue(what: &str, energy: f64) -> Decision {
    criteria::exactly(
        energy < BLUE,
        &format!("{what}: low-frequency energy {energy:.3} of white noise's, below {BLUE}"),
    )
}

/// "a `side` x `side` mask is white noise": its low-frequency energy within 3 standard errors
/// of white noise's 1. For white noise the periodogram's values are independent exponentials
/// of mean 1, save that f and -f are equal, so the mean over the `count` frequencies below
/// the cutoff has a standard error of sqrt(2 / count): 0.10 at 128 x 128, where the fixed
/// band of 20% it replaces failed about one white mask in twenty.
pub(crate) fn white(what: &str, energy: f64, side: u32) -> Decision {
    let count =
        samplab::screen::low_frequency_count(side as usize, side as usize, samplab::screen::LOW_FREQUENCY_CUTOFF);
    let se = (2.0 / count as f64).sqrt();
    let mut d = criteria::agrees(Estimate { value: energy, se }, Estimate { value: 1.0, se: 0.0 }, 0.0);
    d.criterion = format!(
        "{what}: low-frequency energy of white noise's (standard error {se:.3} over {count} frequencies), {}",
        d.criterion
    );
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Verdict;

    #[test]
    fn the_criteria_can_fail() {
        assert_eq!(fades("x", 0.1, 0.5, 2.0).verdict, Verdict::Reproduced);
        assert_eq!(fades("x", 0.4, 0.5, 2.0).verdict, Verdict::NotReproduced);
        assert_eq!(blue("x", 0.1).verdict, Verdict::Reproduced);
        assert_eq!(blue("x", 0.5).verdict, Verdict::NotReproduced);
        // 128 x 128: about 200 frequencies below 1/16 cycle per pixel, a standard error of 0.1
        assert_eq!(white("x", 1.25, 128).verdict, Verdict::Reproduced);
        assert_eq!(white("x", 0.65, 128).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn a_white_sampler_fails_the_blue_mask_claim_and_a_blue_one_the_white() {
        let film = samplab::pixel::Film { width: 64, height: 64, spp: 1, dims: 2 };
        let energy = |name: &str| {
            let p = samplab::pixel::prepare(name, film, samplab::Seed(3)).unwrap();
            samplab::screen::mask_measures(&p, 0, 1).unwrap().low_frequency
        };
        assert_eq!(blue("independent", energy("independent")).verdict, Verdict::NotReproduced);
        assert_eq!(white("zsobol", energy("zsobol"), 64).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn every_family_has_its_own_look() {
        let n = families().len();
        let looks: Vec<(String, bool)> = (0..n).map(look).collect();
        for (i, a) in looks.iter().enumerate() {
            assert!(!looks[..i].contains(a), "{a:?}");
        }
    }
}
