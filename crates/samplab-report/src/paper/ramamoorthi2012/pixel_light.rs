//! Section 5: the 2D pixel-light Fourier analysis of a linear light (Figs. 10 and 11).

use samplab::spectrum::pixel_light::{self, Blocker, Pattern, Scene};

use samplab::stats::Summary;

use crate::criteria::{self, Estimate};
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
    ctx.set_length(4);
    let mut series = Vec::new();
    let mut rows = Vec::new();
    let mut shares = Vec::new();
    let mut mse = Vec::new();
    let mut figures = visibility_figures(&scene, res)?;
    ctx.advance(1)?;
    for (i, (name, key, pattern)) in patterns.iter().enumerate() {
        let a = pixel_light::analyse(&scene, *pattern, pixels, n, res, ctx.seed.derive(10 + i as u64))?;
        figures.extend(pattern_figures(name, *pattern, &a, pixels, n, res)?);
        let share = a.banding_share(&bands);
        let squared: Vec<f64> = a.error.iter().map(|e| e * e).collect();
        let m = Summary::of(&squared);
        shares.push(share);
        mse.push(Estimate::mean_of(&m));
        rows.push(vec![
            Cell::from(*name),
            Cell::num(m.mean.sqrt(), 5),
            Cell::num(m.mean, 7),
            Cell::num(m.standard_error(), 7),
            Cell::num(share.0, 4),
        ]);
        series.push((*name, *key, a.error_spectrum.clone()));
        ctx.advance(1)?;
    }
    let series = spectrum_series(&series);
    let fraction = shares[0].1;
    let chart = LineChart {
        title: format!(
            "Figs. 10(d), 11(e-f): error spectrum along the scanline (bands at k N/(beta-1) = {:.0}k)",
            bands[0]
        ),
        x_label: "spatial frequency (cycles per scanline)".into(),
        y_label: "|error spectrum|".into(),
        series,
        log_y: true,
        log_x: false,
        polar: false,
    };
    figures.push(Figure::render("ramamoorthi2012-fig11", "Figs. 10(d) and 11(e-f): error spectra along the scanline: uniform sampling has spikes at k N/(beta - 1) (banding); uniform jitter and stratified spread the error into noise", &chart, (900, 520))?);
    let claims = claims(&shares, &mse, &bands, pixels);
    Ok(Output {
        tables: vec![Table { id: "ramamoorthi2012-pixel-light".into(), caption: format!("Error along the scanline per pattern: RMS, mean squared error per pixel with its standard error over the {pixels} pixels, and the share of the error energy (non-zero frequencies) at the banding frequencies k N/(beta-1), which are {:.1}% of the frequencies", 100.0 * fraction), columns: ["pattern", "RMS error", "MSE", "SE of MSE", "banding share"].map(String::from).to_vec(), rows }],
        figures,
        claims,
        notes: vec!["The estimate per pixel is the mean visibility of its N samples; the exact value integrates the blocker pattern over the light analytically. Spectra over (pixel, light) use the samples as points in [0,1)^2 weighted by visibility.".into()],
    })
}

/// The error spectra's curves (frequency 0 left out): each pattern's non-zero values as a
/// line (as markers where it has zeros), and the frequencies where its spectrum is zero
/// (below 1e-12 of the largest value drawn: uniform sampling's error lives on its bands
/// alone) as markers at a floor a decade under the least non-zero value, named as such,
/// instead of a line at an arbitrary floor.
fn spectrum_series(spectra: &[(&str, &str, Vec<f64>)]) -> Vec<Series> {
    let largest = spectra.iter().flat_map(|s| s.2.iter().skip(1)).fold(0.0f64, |a, &e| a.max(e));
    let zero = |e: f64| e <= 1e-12 * largest;
    let least =
        spectra.iter().flat_map(|s| s.2.iter().skip(1)).filter(|&&e| !zero(e)).fold(f64::INFINITY, |a, &e| a.min(e));
    let floor = 10f64.powf((least.log10() - 1.0).floor());
    let mut series = Vec::new();
    for (name, key, spectrum) in spectra {
        let at = |keep: bool| spectrum.iter().enumerate().skip(1).filter(move |&(_, &e)| zero(e) != keep);
        let zeros: Vec<(f64, f64)> = at(false).map(|(w, _)| (w as f64, floor)).collect();
        // a spectrum with zeros between its values is marked point by point, not joined
        // into a curve it does not have
        series.push(Series {
            markers: !zeros.is_empty(),
            colour_key: Some(key.to_string()),
            ..Series::line(*name, at(true).map(|(w, &e)| (w as f64, e)).collect())
        });
        if !zeros.is_empty() {
            series.push(Series {
                markers: true,
                colour_key: Some("floor".into()),
                ..Series::line(format!("{name}: exactly 0 (drawn at {floor:.0e})"), zeros)
            });
        }
    }
    series
}

/// A spectrum over (pixel, light) in the paper's layout: pixel (spatial) frequency across,
/// light frequency up.
fn heat(title: &str, values: Vec<f64>, res: usize) -> HeatMap {
    let transposed = (0..res * res).map(|i| values[(i % res) * res + i / res]).collect();
    let mut h = HeatMap::centred(title.into(), "|spectrum|".into(), transposed, res);
    h.x_label = "pixel (spatial) frequency".into();
    h.y_label = "light frequency".into();
    h
}

/// Fig. 9(b), the visibility itself over (pixel, light), and Fig. 10(a), its spectrum.
fn visibility_figures(scene: &Scene, res: usize) -> Result<Vec<Figure>, Error> {
    // Fig. 9(b): the visibility itself over (pixel, light)
    let side = 200;
    let visibility: Vec<f64> = (0..side * side)
        .map(|k| {
            scene.visibility(
                (k % side) as f64 / side as f64 + 0.5 / side as f64,
                (k / side) as f64 / side as f64 + 0.5 / side as f64,
            )
        })
        .collect();
    let fig9 = Figure::render(
        "ramamoorthi2012-fig9",
        "Fig. 9(b): the visibility V(x, y) of the random blocker (6 bars) at depth ratio beta = 3, pixel x across, light y up: constant along lines of slope 1/(1 - beta) = -1/2",
        &HeatMap {
            title: "Fig. 9(b): visibility V(x, y)".into(),
            label: "V".into(),
            values: visibility,
            rows: side,
            cols: side,
            x_range: (0.0, 1.0),
            y_range: (0.0, 1.0),
            x_label: "pixel x".into(),
            y_label: "light y".into(),
            log: false,
        },
        (700, 600),
    )?;
    let fig10 = Figure::render(
        "ramamoorthi2012-fig10-visibility",
        "Fig. 10(a): spectrum of the visibility V(x, y) = G(x/beta + y(1 - 1/beta)) (V on a 512 x 512 lattice under a Hann window, so that the square's edges leak no energy along the axes): energy on a sheared line",
        &heat("Fig. 10(a): visibility", pixel_light::visibility_spectrum(scene, 512, res)?, res),
        (760, 640),
    )?;
    Ok(vec![fig9, fig10])
}

/// Figs. 10(b-c) and 11(a-d): one sampling pattern's spectrum, and the visibility's times it.
fn pattern_figures(
    name: &str,
    pattern: Pattern,
    a: &pixel_light::Analysis,
    pixels: usize,
    n: usize,
    res: usize,
) -> Result<[Figure; 2], Error> {
    let (fig, panels) = match pattern {
        Pattern::Uniform => ("fig10", ["(b)", "(c)"]),
        Pattern::UniformJitter => ("fig11-uniform-jitter", ["(a)", "(b)"]),
        Pattern::Stratified => ("fig11-stratified", ["(c)", "(d)"]),
    };
    let number = if pattern == Pattern::Uniform { "10" } else { "11" };
    let spectrum = Figure::render(
        &format!("ramamoorthi2012-{fig}-pattern"),
        &format!(
            "Fig. {number}{}: spectrum of the {name} sampling pattern ({pixels} pixels x {n} light samples){}",
            panels[0],
            match pattern {
                Pattern::Uniform => ": aliases along the light axis at multiples of N",
                Pattern::UniformJitter => ": the same light frequencies as uniform, energy over all pixel frequencies",
                Pattern::Stratified => ": noise, with a band gap around the origin smaller than uniform jitter's",
            }
        ),
        &heat(&format!("Fig. {number}{}: {name} pattern", panels[0]), a.pattern.clone(), res),
        (760, 640),
    )?;
    let product = Figure::render(
        &format!("ramamoorthi2012-{fig}-product"),
        &format!("Fig. {number}{}: visibility times the {name} pattern", panels[1]),
        &heat(&format!("Fig. {number}{}: visibility x {name}", panels[1]), a.product.clone(), res),
        (760, 640),
    )?;
    Ok([spectrum, product])
}

/// Banding at k N/(beta - 1) and the error of the three patterns.
fn claims(shares: &[(f64, f64)], mse: &[Estimate], bands: &[f64], pixels: usize) -> Vec<Claim> {
    let fraction = shares[0].1;
    vec![
        Claim {
            id: "banding".into(),
            statement: "Uniform sampling bands at the spatial frequencies k N/(beta - 1); uniform jitter spreads that error into noise".into(),
            published: "eq. 25, Figs. 10-11".into(),
            ours: format!(
                "share of the error energy at the banding frequencies (which are {:.1}% of the frequencies): uniform {:.4}, uniform jitter {:.4}, stratified {:.4}",
                100.0 * fraction, shares[0].0, shares[1].0, shares[2].0
            ),
            theory: format!("k N/(beta - 1) = {}", bands.iter().take(4).map(|f| format!("{f:.0}")).collect::<Vec<_>>().join(", ")),
            decision: criteria::exactly(
                shares[0].0 > 0.9 && shares[1].0 < 2.0 * fraction && shares[2].0 < 2.0 * fraction,
                "uniform's share above 0.9 (banding); uniform jitter's and stratified's below twice the banding frequencies' own share (noise)",
            ),
            ..Claim::default()
        },
        Claim {
            id: "uniform-jitter-less-noise".into(),
            statement: "Uniform jitter has less error than stratified sampling on the grid-of-bars scanline, approaching uniform sampling".into(),
            published: {
                let f8 = crate::published::table("ramamoorthi2012", "fig8");
                format!("{}: uniform {}% (banding), uniform jitter {}% (none)", f8.source, f8.row("uniform").expect("published")[0], f8.row("uniform jitter").expect("published")[0])
            },
            ours: format!("mean squared error per pixel (+- standard error over the {pixels} pixels): uniform {:.3e}, uniform jitter {:.3e} +- {:.1e}, stratified {:.3e} +- {:.1e}", mse[0].value, mse[1].value, mse[1].se, mse[2].value, mse[2].se),
            theory: "section 4.2: 1/6 against 1/3 per pair of discontinuities".into(),
            decision: criteria::less(mse[1], mse[2]),
            ..Claim::default()
        },
    ]
}
