//! How far Cycles' A/B variance estimate can be trusted with each pixel sampler. Cycles'
//! adaptive sampling splits a pixel's samples into two classes (`sample_is_class_A`, after
//! Christensen et al. 2018, section 10.2.1) and reads the pixel's noise from the gap between
//! the class-A half's estimate and the whole's: (I - A)^2 = (A - B)^2 / 4, which for
//! independent halves is an unbiased estimate of the variance of I. Stratified and QMC
//! samples are not independent halves; this measures, for every pixel family, the ratio of
//! the A/B estimate's mean to the variance of I over frames (each frame its own samples),
//! per pixel of a film, on a discontinuous and a smooth 2D integrand in dimensions 0-1.
//! A question no one has measured (issue 93); its one criterion, on independent sampling
//! (the control, where the ratio is 1), is fixed in this file before any run.

use rayon::prelude::*;
use samplab::construct::cycles::sample_is_class_a;
use samplab::pixel::{Film, Pixels, prepare};
use samplab::seed::{Seed, below, uniform};

use super::families;
use crate::criteria::{self, Estimate};
use crate::{Cell, Claim, Ctx, Error, Output, Table};

/// The film, and the frames of each pixel's variance.
const SIDE: u32 = 32;
const FRAMES: u32 = 64;
/// Bootstrap resamples of the pixels for the ratio's standard error.
const RESAMPLES: usize = 200;

/// The two integrands, per pixel: a half-plane edge through a point of the pixel's own
/// (visibility, as a shadow's edge) and a Gaussian bump (shading).
const INTEGRANDS: [&str; 2] = ["edge", "gaussian"];

/// Pixel p's integrand `which` at (x, y): its parameters drawn from the pixel's hash.
fn integrand(which: usize, p: (f64, f64, f64), x: f64, y: f64) -> f64 {
    let (cx, cy, angle) = p;
    if which == 0 {
        f64::from(u8::from((x - cx) * angle.cos() + (y - cy) * angle.sin() > 0.0))
    } else {
        (-((x - cx).powi(2) + (y - cy).powi(2)) / 0.1).exp()
    }
}

/// Per pixel: the mean over frames of (A - B)^2 / 4 and the variance over frames of the
/// pixel's estimate I, for both integrands.
type Pixel = [[f64; 2]; 2];

fn measure_family(p: &Pixels, seed: Seed) -> Vec<Pixel> {
    let spp = p.film().spp;
    (0..SIDE * SIDE)
        .map(|k| {
            let mut rng = seed.derive(u64::from(k)).rng();
            let params = (
                0.25 + 0.5 * uniform(&mut rng),
                0.25 + 0.5 * uniform(&mut rng),
                std::f64::consts::TAU * uniform(&mut rng),
            );
            let pixel = [k % SIDE, k / SIDE];
            let mut out = [[0.0; 2]; 2];
            for (w, o) in out.iter_mut().enumerate() {
                // the variance over frames by Welford's update (a repeated estimate gives 0
                // exactly, not the rounding of a difference of sums)
                let (mut gap, mut mean, mut m2) = (0.0, 0.0, 0.0);
                for frame in 0..FRAMES {
                    let (mut a, mut b, mut na) = (0.0, 0.0, 0u32);
                    for i in 0..spp {
                        let v = integrand(w, params, p.sample(pixel, frame, i, 0), p.sample(pixel, frame, i, 1));
                        if sample_is_class_a(i) {
                            a += v;
                            na += 1;
                        } else {
                            b += v;
                        }
                    }
                    let whole = (a + b) / f64::from(spp);
                    let (a, b) = (a / f64::from(na), b / f64::from(spp - na));
                    gap += (a - b).powi(2) / 4.0;
                    let delta = whole - mean;
                    mean += delta / f64::from(frame + 1);
                    m2 += delta * (whole - mean);
                }
                let n = f64::from(FRAMES);
                *o = [gap / n, m2 / (n - 1.0)];
            }
            out
        })
        .collect()
}

/// The ratio (sum of A/B estimates) / (sum of variances) over `pixels`, for integrand `w`.
fn ratio(pixels: &[Pixel], picks: impl Iterator<Item = usize>, w: usize) -> f64 {
    let (est, var) = picks.fold((0.0, 0.0), |(e, v), k| (e + pixels[k][w][0], v + pixels[k][w][1]));
    est / var
}

/// The ratio and its bootstrap standard error over the pixels.
fn ratio_estimate(pixels: &[Pixel], w: usize, seed: Seed) -> Estimate {
    let value = ratio(pixels, 0..pixels.len(), w);
    let mut rng = seed.rng();
    let n = pixels.len() as u64;
    let draws: Vec<f64> = (0..RESAMPLES)
        .map(|_| {
            let picks: Vec<usize> = (0..n).map(|_| below(&mut rng, n) as usize).collect();
            ratio(pixels, picks.into_iter(), w)
        })
        .collect();
    Estimate::bootstrapped(value, &draws)
}

pub(super) fn ab_variance(ctx: &Ctx) -> Result<Output, Error> {
    let spps: Vec<u32> = ctx.pick(vec![4, 16, 64], vec![4, 16, 64, 256, 1024]);
    let names = families();
    ctx.set_length((names.len() * spps.len()) as u64);
    let tasks: Vec<(&str, u32)> = names.iter().flat_map(|&n| spps.iter().map(move |&s| (n, s))).collect();
    let measured: Vec<Option<Vec<Pixel>>> = tasks
        .par_iter()
        .map(|&(name, spp)| {
            let film = Film { width: SIDE, height: SIDE, spp, dims: 2 };
            let seed = ctx.seed.derive_str(name).derive(u64::from(spp));
            let out = match prepare(&super::scenes::spec(ctx, name), film, seed) {
                Ok(p) => Some(measure_family(&p, seed.derive_str("pixels"))),
                Err(samplab::Error::Setting { name: "spp", .. }) => None,
                Err(e) => return Err(e.into()),
            };
            ctx.advance(1)?;
            Ok(out)
        })
        .collect::<Result<_, Error>>()?;
    let mut rows = Vec::new();
    let mut control = None;
    for (t, &(name, spp)) in tasks.iter().enumerate() {
        let Some(pixels) = &measured[t] else { continue };
        let mut row = vec![Cell::Text(super::scenes::spec(ctx, name)), Cell::Text(spp.to_string())];
        for w in 0..INTEGRANDS.len() {
            let e = ratio_estimate(pixels, w, ctx.seed.derive(t as u64 * 2 + w as u64));
            row.push(Cell::Text(if e.value.is_finite() {
                format!("{:.3} ± {:.3}", e.value, e.se)
            } else {
                "frames repeat".into()
            }));
            if name == "independent" && spp == spps[0] && w == 0 {
                control = Some(e);
            }
        }
        rows.push(row);
    }
    let mut columns = vec!["family".to_string(), "spp".to_string()];
    columns.extend(INTEGRANDS.iter().map(|i| format!("A/B estimate / variance, {i}")));
    let claims = control
        .map(|e| {
            let mut decision = criteria::agrees(e, Estimate::exact(1.0), 0.0);
            decision.criterion = format!("independent at {} spp, the edge: {}", spps[0], decision.criterion);
            vec![Claim {
                id: "ab-unbiased-independent".into(),
                statement: "with independent samples, Cycles' A/B estimate (A - B)^2 / 4 is an unbiased estimate of the pixel's variance: the ratio is 1".into(),
                published: "the definition: two independent halves of the samples".into(),
                ours: format!("{:.3} ± {:.3}", e.value, e.se),
                decision,
                addition: Some("samplab's control for the A/B table (issue 93)".into()),
                ..Claim::default()
            }]
        })
        .unwrap_or_default();
    Ok(Output {
        tables: vec![Table {
            id: "renderer-ab-variance".into(),
            caption: format!(
                "Cycles' A/B variance estimate against the true variance, per family and spp: the mean over {FRAMES} frames of (A - B)^2 / 4 (A, B the means of the class-A and class-B samples, Cycles' sample_is_class_A), summed over the {SIDE} x {SIDE} pixels, over the sum of each pixel's variance of its estimate over the frames; ± a bootstrap standard error over the pixels. Each pixel integrates its own half-plane edge (a visibility step) or Gaussian bump over dimensions 0-1. 1: the estimate is right; below 1 it says less noise than there is (adaptive sampling stops too early), above 1 more"
            ),
            columns,
            rows,
        }],
        claims,
        notes: vec![
            "A family whose frames repeat the same samples (pbrt's Halton sampler takes no frame) has no variance over frames: 'frames repeat'. Above 1, the A/B gap overstates the noise: the two classes are each a worse-stratified half of the pixel's samples, so their gap is larger than the error of the whole, and adaptive sampling with such a sampler stops later than its noise allows.".into(),
        ],
        ..Output::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ratio_is_one_for_independent_halves() {
        // the control: independent samples, where (A - B)^2 / 4 is unbiased for Var(I); the
        // criterion fails a ratio of 4 (the gap squared without its quarter) and of 0.5
        let film = Film { width: SIDE, height: SIDE, spp: 16, dims: 2 };
        let p = prepare("independent", film, Seed(5)).unwrap();
        let e = ratio_estimate(&measure_family(&p, Seed(6)), 0, Seed(7));
        let agrees = |scale: f64| {
            let scaled = Estimate { value: e.value * scale, se: e.se * scale };
            criteria::agrees(scaled, Estimate::exact(1.0), 0.0).verdict
        };
        assert_eq!(agrees(1.0), crate::Verdict::Reproduced, "{e:?}");
        assert_eq!(agrees(4.0), crate::Verdict::NotReproduced);
        assert_eq!(agrees(0.5), crate::Verdict::NotReproduced);
    }
}
