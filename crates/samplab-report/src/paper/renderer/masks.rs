//! The masks: per family and dimension 0-7, the 1-spp image of sample 0 and its
//! low-frequency energy, the pair (0, 1) as a renderer uses it, and the flicker and x-t
//! slice of dimension 0 over 16 frames ([`samplab::screen::mask_measures`]).

use rayon::prelude::*;
use samplab::pixel::{Film, prepare};
use samplab::screen::{MaskMeasures, mask_measures};

use super::{blue, families, white};
use crate::{Cell, Claim, Ctx, Error, Output, Table};

/// Dimensions measured.
const DIMS: u32 = 8;
/// Frames of the flicker and x-t measures.
const FRAMES: u32 = 16;

/// The families meant to be blue in every dimension they draw.
const PADDED: [&str; 7] =
    ["zsobol", "pmj02.bn", "dither", "heitz2019", "openqmc.sobolbn", "openqmc.pmjbn", "openqmc.latticebn"];

/// The families whose papers claim blue-noise error in screen space, with what they say.
const BLUE_CLAIMS: [(&str, &str); 3] = [
    (
        "zsobol",
        "Ahmed & Wonka 2020, title: \"Screen-space blue-noise diffusion of Monte Carlo sampling error via hierarchical ordering of pixels\"",
    ),
    (
        "heitz2019",
        "Heitz et al. 2019, title: \"A low-discrepancy sampler that distributes Monte Carlo errors as a blue noise in screen space\"",
    ),
    (
        "dither",
        "Georgiev & Fajardo 2016, \"Blue-noise dithered sampling\": a blue-noise mask's values as the per-pixel shifts",
    ),
];

pub(super) fn masks(ctx: &Ctx) -> Result<Output, Error> {
    let side = ctx.pick(128, 256);
    let names = families();
    ctx.set_length(names.len() as u64);
    // the families side by side (preparing one, a mask or an optimization, is serial), and
    // each family's dimensions
    let measured: Vec<(&str, Vec<MaskMeasures>)> = names
        .par_iter()
        .map(|&name| {
            let film = Film { width: side, height: side, spp: 1, dims: DIMS };
            let p = prepare(&super::scenes::spec(ctx, name), film, ctx.seed.derive_str(name))?;
            // the frames for dimension 0's flicker and x-t slice only
            let m = (0..DIMS)
                .into_par_iter()
                .map(|d| mask_measures(&p, d, if d == 0 { FRAMES } else { 1 }))
                .collect::<Result<Vec<_>, _>>()?;
            ctx.advance(1)?;
            Ok((name, m))
        })
        .collect::<Result<_, Error>>()?;
    let rows = measured
        .iter()
        .map(|(name, m)| {
            let mut row = vec![Cell::Text(super::scenes::spec(ctx, name))];
            row.extend(m.iter().map(|d| Cell::num(d.low_frequency, 3)));
            let opt = |v: Option<f64>| v.map_or(Cell::Text("-".into()), |x| Cell::num(x, 3));
            row.extend([opt(m[0].pair_low_frequency), opt(m[0].flicker), opt(m[0].xt_low_frequency)]);
            row
        })
        .collect();
    let claims = claims(&measured, side);
    let mut columns = vec!["family".to_string()];
    columns.extend((0..DIMS).map(|d| format!("d{d}")));
    columns.extend(["pair (0, 1)".to_string(), "flicker d0".to_string(), "x-t d0".to_string()]);
    Ok(Output {
        tables: vec![Table {
            id: "renderer-masks".into(),
            caption: format!(
                "Low-frequency energy (mean power below 1/16 cycle per pixel, 1/8 of Nyquist, over the variance; white noise 1) of each dimension's mask: sample 0 of frame 0, {side} x {side} pixels, 1 spp; pair (0, 1): of the 1-spp images of 8 fixed Heaviside steps in the pair's square; flicker d0: RMS frame-to-frame change of dimension 0's mask over its RMS, 16 frames (independent frames: 1.41, a static pattern: 0); x-t d0: low-frequency energy of row 0 over the 16 frames"
            ),
            columns,
            rows,
        }],
        claims,
        notes: vec![format!(
            "A blue-noise mask has little energy at low frequencies (below {} of white noise's counts as blue here), so that the error of a smooth integrand looks like fine grain, which a blur or the eye removes.",
            super::BLUE
        )],
        ..Output::default()
    })
}

/// Which masks are blue (and independent's white), and whether the padded families' later
/// dimensions are as blue as their first two.
fn claims(measured: &[(&str, Vec<MaskMeasures>)], side: u32) -> Vec<Claim> {
    let energy = |name: &str, d: usize| measured.iter().find(|(n, _)| *n == name).map(|(_, m)| m[d].low_frequency);
    let mut claims = Vec::new();
    for (name, source) in BLUE_CLAIMS {
        let Some(e) = energy(name, 0) else { continue };
        claims.push(Claim {
            id: format!("mask-blue-{name}"),
            statement: format!("{name}: the 1-spp image of dimension 0 is blue noise"),
            published: source.into(),
            ours: format!("low-frequency energy {e:.3} of white noise's ({side} x {side} pixels)"),
            decision: blue(name, e),
            ..Claim::default()
        });
    }
    if let Some(e) = energy("independent", 0) {
        claims.push(Claim {
            id: "mask-white-independent".into(),
            statement: "independent: the 1-spp image of dimension 0 is white noise".into(),
            published: "the definition: values independent per pixel".into(),
            ours: format!("low-frequency energy {e:.3} of white noise's"),
            decision: white("independent", e, side),
            addition: Some("issue 38's check of the measure".into()),
            ..Claim::default()
        });
    }
    // the families meant to be blue: are their later dimensions as blue as the first two?
    for name in PADDED {
        let Some((_, m)) = measured.iter().find(|(n, _)| *n == name) else { continue };
        let first = m[0].low_frequency.max(m[1].low_frequency);
        let (worst, d) =
            (2..DIMS as usize).map(|d| (m[d].low_frequency, d)).fold((0.0, 0), |a, b| if b.0 > a.0 { b } else { a });
        let explanation = name.starts_with("openqmc.").then(|| {
            "OpenQMC's blue-noise samplers draw the first two dimensions of each 4D block from blue-noise tables and randomize the other two per pixel like white noise, what OpenQMC's issue #71 reports (the masks table: d2, d3, d6, d7)".to_string()
        });
        claims.push(Claim {
            id: format!("padded-blue-{name}"),
            statement: format!("{name}: dimensions 2-7 are as blue as dimensions 0-1"),
            published: "a padded or higher-dimensional sampler's later dimensions as blue as its first two, or not (issue 38); OpenQMC's issue #71 reports its *bn samplers' dimensions 2-3 white".into(),
            ours: format!("dimensions 0-1: {first:.3}; worst of 2-7: {worst:.3} (dimension {d})"),
            decision: blue(&format!("{name}, its least blue dimension of 2-7 (dimension {d})"), worst),
            explanation,
            addition: Some("samplab's question, with OpenQMC's issue #71".into()),
            ..Claim::default()
        });
    }
    claims
}
