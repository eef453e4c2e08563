//! Sections 5.3 and 6 at one pixel: what a Gaussian light does to the visibility spectrum of
//! a linear light (Fig. 12) and to the sampling comb of a square light (Figs. 14 and 15).
//!
//! A light with intensity L(y) sampled uniformly is the pattern weighted by L (the paper's
//! P(y) L(y), section 5.3): the estimate is (1/N) sum_i V(y_i) L(y_i), L normalized to unit
//! integral, against the exact integral of V L. The Gaussian is the renderer's
//! (`samplab_render::scenes::GAUSSIAN_SIGMA` half-widths), so these one-pixel experiments
//! and the rendered ones of Figs. 13-20 use the same light.

use std::f64::consts::TAU;
use std::sync::LazyLock;

use samplab::numeric::quadrature::gauss_legendre;
use samplab::sampler;
use samplab::stats::Summary;
use samplab_render::scenes::GAUSSIAN_SIGMA;

use crate::criteria::{self, Estimate};
use crate::plot::{HeatMap, LineChart, Series};
use crate::{Cell, Claim, Ctx, Error, Figure, Output, Table};

/// The Gaussian's standard deviation on the unit interval (the light's half-width is 1/2).
const SIGMA: f64 = 0.5 * GAUSSIAN_SIGMA;

/// The integral of the unnormalized Gaussian over [0, 1].
static GAUSSIAN_MASS: LazyLock<f64> = LazyLock::new(|| integral(0.0, 1.0));

/// Where the one-pixel spectra put their discontinuity (any position off the strata's
/// boundaries shows the same shapes).
const EDGE: f64 = 0.37;

fn gaussian(y: f64) -> f64 {
    (-(y - 0.5).powi(2) / (2.0 * SIGMA * SIGMA)).exp()
}

/// The integral of the unnormalized Gaussian over [a, b] (4 panels of 16-point
/// Gauss-Legendre: exact to rounding for this smooth integrand).
fn integral(a: f64, b: f64) -> f64 {
    gauss_legendre(gaussian, a, b, 4)
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Light {
    Constant,
    Gaussian,
}

impl Light {
    const BOTH: [(&'static str, Light); 2] = [("constant", Light::Constant), ("Gaussian", Light::Gaussian)];

    /// Intensity at y in [0, 1], unit integral.
    fn weight(self, y: f64) -> f64 {
        match self {
            Light::Constant => 1.0,
            Light::Gaussian => gaussian(y) / *GAUSSIAN_MASS,
        }
    }

    /// The integral of the intensity over [y0, 1].
    fn tail(self, y0: f64) -> f64 {
        match self {
            Light::Constant => 1.0 - y0,
            Light::Gaussian => integral(y0, 1.0) / *GAUSSIAN_MASS,
        }
    }

    /// |integral over [0, 1] of V(y) L(y) exp(-2 pi i w y)| for V = H(y - `edge`) (or V = 1
    /// without an edge), by a 2^14-point midpoint rule.
    fn spectrum(self, edge: Option<f64>, w: f64) -> f64 {
        const M: usize = 1 << 14;
        let (mut re, mut im) = (0.0, 0.0);
        for i in 0..M {
            let y = (i as f64 + 0.5) / M as f64;
            if edge.is_some_and(|e| y < e) {
                continue;
            }
            let (s, c) = (-TAU * w * y).sin_cos();
            re += self.weight(y) * c;
            im += self.weight(y) * s;
        }
        re.hypot(im) / M as f64
    }
}

/// N^2 (1D) or N (2D) x the mean squared error of `spec` over `trials` visibility functions
/// V = H(x - x0), x0 uniform, the pattern weighted by `light` along every axis.
fn edge_mse(ctx: &Ctx, spec: &str, n: usize, dims: usize, light: Light, trials: usize) -> Result<Estimate, Error> {
    let s = sampler::build(spec)?;
    let key = ctx.seed.derive_str(spec).derive(dims as u64).derive(light as u64);
    let sets = sampler::generate_sets(&s, n, dims, key, trials)?;
    let mut edges = key.derive_str("edges").rng();
    let scale = if dims == 1 { (n * n) as f64 } else { n as f64 };
    let errors: Vec<f64> = sets
        .iter()
        .map(|set| {
            let x0 = samplab::seed::uniform(&mut edges);
            let estimate = set
                .iter()
                .filter(|p| p[0] >= x0)
                .map(|p| p.iter().map(|&c| light.weight(c)).product::<f64>())
                .sum::<f64>()
                / n as f64;
            scale * (estimate - light.tail(x0)).powi(2)
        })
        .collect();
    Ok(Estimate::mean_of(&Summary::of(&errors)))
}

/// Fig. 12: a single discontinuity on a linear light, constant against Gaussian intensity.
pub(super) fn gaussian_light(ctx: &Ctx) -> Result<Output, Error> {
    let (n, trials) = (16usize, ctx.pick(20_000, 200_000));
    let strategies = [("uniform", "regular"), ("uniform jitter", "jitter.uniform"), ("stratified", "jitter")];
    ctx.set_length(7);
    let mut series = Vec::new();
    for (name, light) in Light::BOTH {
        let points = (1..=64).map(|w| (w as f64, light.spectrum(Some(EDGE), w as f64))).collect();
        series.push(Series { markers: true, ..Series::line(format!("visibility x {name} light"), points) });
    }
    ctx.advance(1)?;
    let mut rows = Vec::new();
    let mut mse = Vec::new();
    for (light_name, light) in Light::BOTH {
        let mut row = vec![Cell::from(light_name)];
        let mut each = Vec::new();
        for (_, spec) in strategies {
            let e = edge_mse(ctx, spec, n, 1, light, trials)?;
            ctx.advance(1)?;
            row.push(Cell::num(e.value, 4));
            each.push(e);
        }
        row.push(Cell::num(each[1].value / each[0].value, 3));
        rows.push(row);
        mse.push(each);
    }
    let (constant, gauss) = (&mse[0], &mse[1]);
    let chart = LineChart {
        title: format!("Fig. 12: spectrum of one discontinuity (at y = {EDGE}) on a linear light"),
        x_label: "light frequency (cycles over the light)".into(),
        y_label: "|spectrum of V L|".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    };
    let claims = fig12_claims(constant, gauss, n, trials);
    Ok(Output {
        tables: vec![Table {
            id: "ramamoorthi2012-fig12".into(),
            caption: format!(
                "N^2 x mean squared error of one discontinuity (uniform in [0, 1]) on a linear light, N = {n}, {trials} edges per strategy; Gaussian sigma = {SIGMA} of the light's length"
            ),
            columns: ["light", "uniform", "uniform jitter", "stratified", "uniform jitter / uniform"]
                .map(String::from)
                .to_vec(),
            rows,
        }],
        figures: vec![Figure::render(
            "ramamoorthi2012-fig12",
            "Fig. 12: the visibility spectrum of one discontinuity oscillates with a 1/frequency decay under a constant light; the Gaussian light smooths it",
            &chart,
            (860, 500),
        )?],
        claims,
        notes: vec![],
    })
}

/// Figs. 14 and 15: a square light with an edge parallel to its sample columns; the
/// spectra of the visibility, of the uniform-jitter comb and of the comb under a Gaussian.
pub(super) fn square_light(ctx: &Ctx) -> Result<Output, Error> {
    let (n, side, res, trials) = (25usize, 5usize, 64usize, ctx.pick(20_000, 200_000));
    ctx.set_length(5);
    let figures = fig15(ctx, side, res)?;
    ctx.advance(1)?;
    let mut rows = Vec::new();
    let mut ratios = Vec::new();
    for (light_name, light) in Light::BOTH {
        let strat = edge_mse(ctx, "jitter", n, 2, light, trials)?;
        let uj = edge_mse(ctx, "jitter.uniform", n, 2, light, trials)?;
        ctx.advance(2)?;
        let ratio = uj.ratio(strat);
        rows.push(vec![
            Cell::from(light_name),
            Cell::num(strat.value, 5),
            Cell::num(uj.value, 5),
            Cell::num(ratio.value, 3),
            if light == Light::Constant { Cell::num((n as f64).sqrt(), 0) } else { Cell::Empty },
        ]);
        ratios.push((strat, uj, ratio));
    }
    let (constant, gauss) = (ratios[0], ratios[1]);
    let claims = fig14_claims(constant, gauss, side);
    Ok(Output {
        tables: vec![Table {
            id: "ramamoorthi2012-fig15".into(),
            caption: format!("N x mean squared error of a vertical edge (uniform position) on a square light, N = {n} (5 x 5), {trials} edges per strategy"),
            columns: ["light", "stratified", "uniform jitter", "uniform jitter / stratified", "theory (constant)"].map(String::from).to_vec(),
            rows,
        }],
        figures,
        claims,
        notes: vec!["The spectra are of one pixel's light (2D), not the pixel-light spectra of section 5; each map is the product of its two axes' spectra (the edge, the comb and the Gaussian are all separable), floored at 1e-6 for the log colour scale.".into()],
    })
}

/// Fig. 12's claims: uniform jitter against stratified under the constant light, against
/// uniform under the Gaussian one.
fn fig12_claims(constant: &[Estimate], gauss: &[Estimate], n: usize, trials: usize) -> Vec<Claim> {
    let ratio = gauss[1].ratio(gauss[0]);
    vec![
        Claim {
            id: "fig12-constant-uniform-jitter-as-stratified".into(),
            statement: "Constant linear light, one discontinuity: uniform jitter has the same RMS error as stratified sampling".into(),
            published: "Fig. 12(a) caption".into(),
            ours: format!(
                "N^2 x MSE: uniform jitter {:.4}, stratified {:.4} (N = {n}, {trials} edges each)",
                constant[1].value, constant[2].value
            ),
            theory: "1/6 for both (Fig. 4)".into(),
            decision: criteria::agrees(constant[1], constant[2], 0.0),
            ..Claim::default()
        },
        Claim {
            id: "fig12-gaussian-uniform-jitter-as-uniform".into(),
            statement: "Gaussian linear light, one discontinuity: the smoother spectrum lets uniform jitter perform essentially as well as uniform sampling (read as: within 25% in mean squared error)".into(),
            published: "Fig. 12(b) caption".into(),
            ours: format!(
                "uniform jitter / uniform MSE = {:.3} with the Gaussian light ({:.3} with the constant one)",
                ratio.value,
                constant[1].value / constant[0].value
            ),
            theory: "2 for a constant light (1/6 against 1/12, Fig. 4)".into(),
            decision: criteria::in_range(ratio, 0.0, 1.25),
            ..Claim::default()
        },
    ]
}

/// Fig. 15's maps, each separable: |F(u)| |G(v)|, u across (index k % res), v up.
fn fig15(ctx: &Ctx, side: usize, res: usize) -> Result<Vec<Figure>, Error> {
    let half = (res / 2) as f64;
    let freq = |k: usize| k as f64 - half;
    let map = |fu: &dyn Fn(f64) -> f64, fv: &dyn Fn(f64) -> f64| -> Vec<f64> {
        let (us, vs): (Vec<f64>, Vec<f64>) = (0..res).map(|k| (fu(freq(k)), fv(freq(k)))).unzip();
        (0..res * res).map(|i| (vs[i / res] * us[i % res]).max(1e-6)).collect()
    };
    // one realization of the uniform-jitter comb: sample columns at (j + g) / side
    let shift = samplab::seed::uniform(&mut ctx.seed.derive_str("comb").rng());
    let comb = |light: Light, w: f64| {
        let (mut re, mut im, mut mass) = (0.0, 0.0, 0.0);
        for j in 0..side {
            let x = (j as f64 + shift) / side as f64;
            let (s, c) = (-TAU * w * x).sin_cos();
            re += light.weight(x) * c;
            im += light.weight(x) * s;
            mass += light.weight(x);
        }
        re.hypot(im) / mass
    };
    let maps = [
        (
            "visibility",
            "(a) visibility of an edge at x = 0.37 on a constant square light",
            map(&|u| Light::Constant.spectrum(Some(EDGE), u), &|v| Light::Constant.spectrum(None, v)),
        ),
        (
            "comb",
            "(b) uniform jitter, 5 x 5: a comb at multiples of 5",
            map(&|u| comb(Light::Constant, u), &|v| comb(Light::Constant, v)),
        ),
        (
            "gaussian-comb",
            "(c) the same comb under the Gaussian light: each tooth spread",
            map(&|u| comb(Light::Gaussian, u), &|v| comb(Light::Gaussian, v)),
        ),
    ];
    let mut figures = Vec::new();
    for (key, title, values) in maps {
        let mut h = HeatMap::centred(format!("Fig. 15{title}"), "|spectrum|".into(), values, res);
        h.x_label = "light frequency u (across the edge)".into();
        h.y_label = "light frequency v".into();
        figures.push(Figure::render(
            &format!("ramamoorthi2012-fig15-{key}"),
            &format!("Fig. 15{title}"),
            &h,
            (700, 600),
        )?);
    }
    Ok(figures)
}

/// Figs. 14 and 15's claims: (stratified, uniform jitter, their ratio) under the constant
/// and the Gaussian light.
fn fig14_claims(
    constant: (Estimate, Estimate, Estimate),
    gauss: (Estimate, Estimate, Estimate),
    side: usize,
) -> Vec<Claim> {
    vec![
        Claim {
            id: "fig14-square-aligned-edge".into(),
            statement: "Square light, an edge parallel to the sample columns: uniform jitter has higher error than stratified sampling, every light scanline giving the same result".into(),
            published: "Fig. 14 and section 6".into(),
            ours: format!("N x MSE: stratified {:.5}, uniform jitter {:.5}", constant.0.value, constant.1.value),
            theory: String::new(),
            decision: criteria::less(constant.0, constant.1),
            ..Claim::default()
        },
        Claim {
            id: "aligned-edge-ratio".into(),
            statement: "For an edge parallel to the columns of an n x n pattern, uniform jitter's variance is sqrt(N) = n times stratified sampling's: its n samples in the edge's column cross the edge together, stratified's independently".into(),
            ours: format!("uniform jitter / stratified MSE = {:.3}", constant.2.value),
            theory: format!("{}", side),
            decision: criteria::agrees(constant.2, Estimate::exact(side as f64), 0.0),
            addition: Some("samplab's derivation from Fig. 14's configuration: per column, n Bernoulli(t) strata against one, t(1 - t)/(n N) against t(1 - t)/N".into()),
            ..Claim::default()
        },
        Claim {
            id: "fig15-gaussian-spreads-comb".into(),
            statement: "A Gaussian light spreads the comb's energy away from its teeth, so uniform jitter's disadvantage on the aligned edge shrinks".into(),
            published: "Fig. 15(c) and section 6".into(),
            ours: format!("uniform jitter / stratified MSE: constant {:.3}, Gaussian {:.3}", constant.2.value, gauss.2.value),
            theory: String::new(),
            decision: criteria::less(gauss.2, constant.2),
            ..Claim::default()
        },
    ]
}
