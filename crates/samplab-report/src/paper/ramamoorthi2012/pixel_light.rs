//! Section 5: the 2D pixel-light Fourier analysis of a linear light (Figs. 10 and 11).

use samplab::spectrum::pixel_light::{self, Blocker, Pattern, Scene};

use crate::criteria;
use crate::plot::{HeatMap, LineChart, Series};
use crate::{Cell, Claim, Ctx, Error, Figure, Output, Table};

pub(super) fn pixel_light(ctx: &Ctx) -> Result<Output, Error> {
    let (n, beta, pixels, res) = (16usize, 3.0, 512usize, 64usize);
    let scene = Scene { beta, blocker: Blocker::random(6, 0.05, beta, ctx.seed.derive(1)) };
    let bands = pixel_light::banding_frequencies(n, beta, (pixels / 2) as f64);
    let patterns = [
        ("uniform", "regular", Pattern::Uniform),
        ("uniform jitter", "jitter.uniform", Pattern::UniformJitter),
        ("stratified", "jitter", Pattern::Stratified),
    ];
    ctx.progress.set_length(4);
    let mut figures = Vec::new();
    let mut series = Vec::new();
    let mut rows = Vec::new();
    let mut ratios = Vec::new();
    let mut rms = Vec::new();
    // the visibility alone, approximated by dense uniform sampling (256 samples per pixel)
    let dense = pixel_light::analyse(&scene, Pattern::Uniform, pixels, 256, res, ctx.seed.derive(2))?;
    // the paper's layout: pixel (spatial) frequency across, light frequency up
    let heat = |title: &str, values: Vec<f64>| {
        let transposed = (0..res * res).map(|i| values[(i % res) * res + i / res]).collect();
        let mut h = HeatMap::centred(title.into(), "|spectrum|".into(), transposed, res);
        h.x_label = "pixel (spatial) frequency".into();
        h.y_label = "light frequency".into();
        h
    };
    figures.push(Figure::render(
        "ramamoorthi2012-fig10-visibility",
        "Fig. 10(a): spectrum of the visibility V(x, y) = G(x/beta + y(1 - 1/beta)), energy on a sheared line",
        &heat("Fig. 10(a): visibility", dense.product.clone()),
        (760, 640),
    )?);
    ctx.advance(1)?;
    for (i, (name, key, pattern)) in patterns.iter().enumerate() {
        let a = pixel_light::analyse(&scene, *pattern, pixels, n, res, ctx.seed.derive(10 + i as u64))?;
        if *pattern == Pattern::Uniform {
            figures.push(Figure::render(
                "ramamoorthi2012-fig10-pattern",
                "Fig. 10(b): spectrum of uniform sampling: aliases along the light axis at multiples of N",
                &heat("Fig. 10(b): uniform sampling pattern", a.pattern.clone()),
                (760, 640),
            )?);
            figures.push(Figure::render(
                "ramamoorthi2012-fig10-product",
                "Fig. 10(c): visibility times the pattern: replicas of the sheared spectrum",
                &heat("Fig. 10(c): visibility x uniform pattern", a.product.clone()),
                (760, 640),
            )?);
        }
        let ratio = a.banding_ratio(&bands);
        let e_rms = (a.error.iter().map(|e| e * e).sum::<f64>() / pixels as f64).sqrt();
        ratios.push(ratio);
        rms.push(e_rms);
        rows.push(vec![Cell::from(*name), Cell::num(e_rms, 5), Cell::Text(format!("{ratio:.3e}"))]);
        series.push(Series {
            colour_key: Some(key.to_string()),
            ..Series::line(
                *name,
                a.error_spectrum.iter().enumerate().skip(1).map(|(w, &e)| (w as f64, e.max(1e-9))).collect(),
            )
        });
        ctx.advance(1)?;
    }
    let chart = LineChart {
        title: format!(
            "Fig. 10(d)/11: spectrum of the error along the scanline (bands at k N/(beta-1) = {:.0}k)",
            bands[0]
        ),
        x_label: "spatial frequency (cycles per scanline)".into(),
        y_label: "|error spectrum|".into(),
        series,
        log_y: true,
        log_x: false,
        polar: false,
    };
    figures.push(Figure::render("ramamoorthi2012-fig11", "Figs. 10(d) and 11: error spectra along the scanline: uniform sampling has spikes at k N/(beta - 1) (banding); uniform jitter and stratified spread the error into noise", &chart, (900, 520))?);
    let claims = vec![
        Claim {
            id: "banding".into(),
            statement: "Uniform sampling bands at the spatial frequencies k N/(beta - 1); uniform jitter spreads that error into noise".into(),
            published: "eq. 25, Figs. 10-11".into(),
            ours: format!("energy at the banding frequencies over the rest: uniform {:.1e}, uniform jitter {:.2}, stratified {:.2}", ratios[0], ratios[1], ratios[2]),
            theory: format!("k N/(beta - 1) = {}", bands.iter().take(4).map(|f| format!("{f:.0}")).collect::<Vec<_>>().join(", ")),
            decision: criteria::exactly(ratios[0] > 8.0 && ratios[1] < 2.0 && ratios[2] < 2.0, "uniform's energy ratio > 8, uniform jitter's and stratified's < 2"),
            ..Claim::default()
        },
        Claim {
            id: "uniform-jitter-less-noise".into(),
            statement: "Uniform jitter has less error than stratified sampling on the grid-of-bars scanline, approaching uniform sampling".into(),
            published: {
                let f8 = crate::published::table("ramamoorthi2012", "fig8");
                format!("{}: uniform {}% (banding), uniform jitter {}% (none)", f8.source, f8.row("uniform").expect("published")[0], f8.row("uniform jitter").expect("published")[0])
            },
            ours: format!("RMS error: uniform {:.4}, uniform jitter {:.4}, stratified {:.4}", rms[0], rms[1], rms[2]),
            theory: "section 4.2: 1/6 against 1/3 per pair of discontinuities".into(),
            decision: criteria::exactly(rms[1] < rms[2], "uniform jitter's RMS error below stratified's"),
            ..Claim::default()
        },
    ];
    Ok(Output {
        tables: vec![Table { id: "ramamoorthi2012-pixel-light".into(), caption: "RMS error along the scanline and the banding ratio (mean error energy at k N/(beta-1) over the mean elsewhere)".into(), columns: ["pattern", "RMS error", "banding ratio"].map(String::from).to_vec(), rows }],
        figures,
        claims,
        notes: vec!["The estimate per pixel is the mean visibility of its N samples; the exact value integrates the blocker pattern over the light analytically. Spectra over (pixel, light) use the samples as points in [0,1)^2 weighted by visibility.".into()],
    })
}
