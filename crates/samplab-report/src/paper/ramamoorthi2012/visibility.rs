//! Section 4: 1D visibility over a linear light at one pixel (Figs. 3, 4, 6 and 7).

use samplab::experiment::Row;
use samplab::integrand::Family;
use samplab::sampler;
use samplab::theory;

use super::super::study;
use super::STRATEGIES;
use crate::criteria::{self, Estimate};
use crate::plot::{LineChart, Series};
use crate::{Cell, Claim, Ctx, Error, Figure, Output, Table};

pub(super) fn error_vs_position(ctx: &Ctx) -> Result<Output, Error> {
    let n = 8;
    let positions = 400;
    let reps = ctx.pick(400, 4000);
    ctx.set_length(4);
    let mut series = Vec::new();
    let mut worst = Vec::new();
    for (name, spec) in [STRATEGIES[0], STRATEGIES[1], STRATEGIES[3], ("random", "random")] {
        let (curve, max_err) = rms_curve(ctx, spec, n, positions, reps)?;
        worst.push((name, spec, n as f64 * max_err));
        series.push(Series { colour_key: Some(spec.into()), ..Series::line(name, curve) });
        ctx.advance(1)?;
    }
    series.extend(theory_series(n, positions));
    let chart = LineChart {
        title: "N x RMS error against the discontinuity's position (N = 8)".into(),
        x_label: "position y0 of the discontinuity".into(),
        y_label: "N x RMS error".into(),
        series,
        log_y: false,
        log_x: false,
        polar: false,
    };
    let table = Table {
        id: "ramamoorthi2012-worst-case".into(),
        caption:
            "Worst-case N x |error| over all positions and realizations, one discontinuity, N = 8 (theory: Fig. 4)"
                .into(),
        columns: ["strategy", "measured", "theory"].map(String::from).to_vec(),
        rows: worst
            .iter()
            .map(|(name, spec, w)| {
                vec![
                    Cell::from(*name),
                    Cell::num(*w, 4),
                    theory::visibility_worst_case(spec, 1).map_or(Cell::Empty, |t| Cell::num(t, 4)),
                ]
            })
            .collect(),
    };
    let (uniform_worst, halton_worst) = (worst[0].2, worst[2].2);
    Ok(Output {
        tables: vec![table],
        figures: vec![Figure::render(
            "ramamoorthi2012-fig3",
            "N x RMS error against the position of one visibility discontinuity, N = 8 (Fig. 3): uniform, stratified, Halton and random sampling; dashed: theory",
            &chart,
            (900, 520),
        )?],
        claims: worst_claims(uniform_worst, halton_worst, n),
        notes: vec![],
    })
}

/// N x the RMS error of `spec`'s realizations against the position y0 of one step, and the
/// worst absolute error seen.
fn rms_curve(ctx: &Ctx, spec: &str, n: usize, positions: usize, reps: usize) -> Result<(Vec<(f64, f64)>, f64), Error> {
    let s = sampler::build(spec)?;
    // the same realizations for every position: N x RMS error as a function of y0
    let sets = sampler::generate_sets(&s, n, 1, ctx.seed.derive_str(spec), reps)?;
    let mut curve = Vec::with_capacity(positions);
    let mut max_err: f64 = 0.0;
    for i in 0..positions {
        let y0 = (i as f64 + 0.5) / positions as f64;
        let f = Family::parse(&format!("step:y0={y0}"))?.instance(ctx.seed, 0)?;
        let exact = f.exact();
        let sq: f64 = sets
            .iter()
            .map(|p| {
                let e = p.iter().map(|x| f.eval(x)).sum::<f64>() / n as f64 - exact;
                max_err = max_err.max(e.abs());
                e * e
            })
            .sum::<f64>()
            / reps as f64;
        curve.push((y0, n as f64 * sq.sqrt()));
    }
    // the worst case sits just past a sample (a step at y0 = y_k + 0): probe there too
    for k in 0..2 * n {
        let y0 = k as f64 / (2 * n) as f64 + 1e-9;
        let f = Family::parse(&format!("step:y0={y0}"))?.instance(ctx.seed, 0)?;
        for p in &sets {
            let e = p.iter().map(|x| f.eval(x)).sum::<f64>() / n as f64 - f.exact();
            max_err = max_err.max(e.abs());
        }
    }
    Ok((curve, max_err))
}

/// The closed forms of Fig. 3's curves.
fn theory_series(n: usize, positions: usize) -> Vec<Series> {
    let mut series = Vec::new();
    // theory within a stratum at relative position t: uniform |min(t, 1-t)|, stratified sqrt(t (1-t))
    let theory = |f: fn(f64) -> f64| {
        (0..positions)
            .map(|i| (i as f64 + 0.5) / positions as f64)
            .map(|y| (y, f((y * n as f64).fract())))
            .collect::<Vec<_>>()
    };
    series.push(Series {
        dashed: true,
        colour_key: Some("regular".into()),
        ..Series::line("uniform, theory", theory(|t| t.min(1.0 - t)))
    });
    series.push(Series {
        dashed: true,
        colour_key: Some("jitter".into()),
        ..Series::line("stratified, theory", theory(|t| (t * (1.0 - t)).sqrt()))
    });
    // independent points: N x sqrt(y0 (1 - y0) / N)
    series.push(Series {
        dashed: true,
        colour_key: Some("random".into()),
        ..Series::line(
            "random, theory",
            (0..positions)
                .map(|i| (i as f64 + 0.5) / positions as f64)
                .map(|y| (y, (n as f64 * y * (1.0 - y)).sqrt()))
                .collect(),
        )
    });
    series
}

/// The worst cases of uniform (centred) and Halton sampling against their closed forms.
fn worst_claims(uniform_worst: f64, halton_worst: f64, n: usize) -> Vec<Claim> {
    vec![
        Claim {
            id: "uniform-worst-case".into(),
            statement: "Uniform (centred) sampling has worst-case error 1/(2N) for one discontinuity, the lower bound"
                .into(),
            published: "1/(2N) (eq. 8, Figs. 3 and 4)".into(),
            ours: format!(
                "N x worst error = {uniform_worst:.9} over 400 positions and the {} positions just past a sample",
                2 * n
            ),
            theory: "0.5".into(),
            decision: criteria::within(uniform_worst, 0.5, 1e-6),
            derived: true,
            ..Claim::default()
        },
        Claim {
            id: "halton-worst-case".into(),
            statement: "Halton (base 2) has worst-case error 1/N for one discontinuity".into(),
            published: "1/N (Fig. 3)".into(),
            ours: format!("N x worst error = {halton_worst:.9}"),
            theory: "1".into(),
            decision: criteria::within(halton_worst, 1.0, 1e-6),
            derived: true,
            ..Claim::default()
        },
    ]
}

pub(super) fn tables(ctx: &Ctx) -> Result<Output, Error> {
    let trials = ctx.pick(4000, 40000);
    ctx.set_length(2 * 4 * trials as u64);
    let specs: Vec<&str> = STRATEGIES.iter().map(|s| s.1).collect();
    let one = study(ctx, &specs, "step", &[256], 2, trials, ctx.seed.derive(1))?;
    let two = study(ctx, &specs, "box", &[256], 2, trials, ctx.seed.derive(2))?;
    // N^2 x MSE and its standard error over the trials (the visibility functions)
    let measured = |r: &Row| Estimate { value: r.normalized_mse, se: r.normalized_mse_se };
    let mut claims = Vec::new();
    let mut rows = Vec::new();
    for ((name, spec), (r1, r2)) in STRATEGIES.iter().zip(one.iter().zip(&two)) {
        let (t1, t2) = (theory::visibility_normalized_mse(spec, 1), theory::visibility_normalized_mse(spec, 2));
        rows.push(vec![
            Cell::from(*name),
            Cell::num(r1.normalized_mse, 4),
            t1.map_or(Cell::Empty, |t| Cell::num(t, 4)),
            Cell::num(r2.normalized_mse, 4),
            t2.map_or(Cell::Empty, |t| Cell::num(t, 4)),
        ]);
        for (k, r, t) in [(1, r1, t1), (2, r2, t2)] {
            if let Some(t) = t {
                let dev = r.normalized_mse / t - 1.0;
                claims.push(Claim {
                    id: format!("{spec}-{k}"),
                    statement: format!(
                        "{name} sampling: N^2 x expected squared error for {}",
                        if k == 1 { "one discontinuity" } else { "a box (two discontinuities)" }
                    ),
                    published: format!("{} (Fig. {})", fraction(t), if k == 1 { 4 } else { 6 }),
                    ours: format!("{:.4} ({:+.1}%)", r.normalized_mse, 100.0 * dev),
                    theory: format!("{t:.4}"),
                    decision: criteria::agrees(measured(r), Estimate::exact(t), 0.0),
                    ..Claim::default()
                });
            }
        }
    }
    claims.push(endpoints_claim(measured(&one[3])));
    // both strategies integrate the same visibility functions, so their errors correlate
    // positively and the independent ratio's standard error is conservative
    let halving = measured(&two[2]).ratio(measured(&two[1]));
    claims.push(Claim {
        id: "uniform-jitter-halves-box".into(),
        statement: "Uniform jitter halves stratified sampling's variance for two discontinuities".into(),
        published: "1/6 against 1/3 (Fig. 6)".into(),
        ours: format!("ratio {:.3} +- {:.3} (SE)", halving.value, halving.se),
        theory: "0.5".into(),
        decision: criteria::agrees(halving, Estimate::exact(0.5), 0.0),
        ..Claim::default()
    });
    let (worst_table, worst_claims) = box_worst_case(ctx, trials)?;
    claims.extend(worst_claims);
    Ok(Output {
        tables: vec![Table {
            id: "ramamoorthi2012-figs4-6".into(),
            caption: format!("N^2 x mean squared error, N = 256, over {trials} random visibility functions (discontinuities uniform in [0,1]); theory from Figs. 4 and 6"),
            columns: ["strategy", "one discontinuity", "theory", "box", "theory"].map(String::from).to_vec(),
            rows,
        }, worst_table],
        figures: vec![],
        claims,
        notes: vec!["'Uniform' is the paper's name for stratum centres (samplab's regular), 'stratified' for jitter, 'uniform jitter' for one random offset shared by all strata (jitter.uniform). Halton is the unscrambled base-2 radical inverse: for N = 256 its points are the strata's left ends, the worst placement of Fig. 4.".into()],
    })
}

/// Eq. 11 at the stratum's end: with the sample at fraction y1 of each stratum, N^2 x the
/// expected squared error of one discontinuity is (y1^3 + (1 - y1)^3) / 3, which is 1/3 at
/// y1 = 0, Fig. 4's worst placement. The unscrambled base-2 Halton points at N = 256 (a
/// power of 2) are the strata's left ends, so its measured N^2 MSE (`halton`) tests it.
fn endpoints_claim(halton: Estimate) -> Claim {
    let t = 1.0 / 3.0;
    Claim {
        id: "eq11-endpoints".into(),
        statement: "With the sample at a stratum's end, N^2 x the expected squared error of one discontinuity is 1/3, twice stratified sampling's (eq. 11 at y1 = 0; Fig. 4's end-points)".into(),
        published: "(y1^3 + (1 - y1)^3) / 3 (eq. 11); end-points worst (Fig. 4)".into(),
        ours: format!("Halton (base 2) at N = 256, the strata's left ends: {:.4} +- {:.4} (SE)", halton.value, halton.se),
        theory: "1/3".into(),
        decision: criteria::agrees(halton, Estimate::exact(t), 0.0),
        ..Claim::default()
    }
}

/// Fig. 6's worst-case column: the largest N x |error| of a box (two discontinuities) over
/// `trials` realizations of N = 8 samples, with the box's edges placed where the error peaks:
/// just before or just past a sample (the error is piecewise linear in each edge, so its
/// extremes over the edges sit there).
fn box_worst_case(ctx: &Ctx, trials: usize) -> Result<(Table, Vec<Claim>), Error> {
    const N: usize = 8;
    const EPS: f64 = 1e-9;
    let mut rows = Vec::new();
    let mut claims = Vec::new();
    for (name, spec) in &STRATEGIES[..3] {
        let s = sampler::build(spec)?;
        let sets = sampler::generate_sets(&s, N, 1, ctx.seed.derive_str("box-worst").derive_str(spec), trials)?;
        let mut worst: f64 = 0.0;
        for set in &sets {
            let xs = set.as_slice();
            let edges: Vec<f64> =
                xs.iter().flat_map(|&x| [x - EPS, x + EPS]).filter(|e| (0.0..=1.0).contains(e)).collect();
            for &y0 in &edges {
                for &z0 in edges.iter().filter(|&&z| z > y0) {
                    let inside = xs.iter().filter(|&&x| (y0..z0).contains(&x)).count();
                    worst = worst.max((inside as f64 - N as f64 * (z0 - y0)).abs());
                }
            }
        }
        let theory = theory::visibility_worst_case(spec, 2).expect("the three strategies have a closed form");
        // a random strategy approaches its supremum from below: over `trials` realizations the
        // two extreme offsets it needs come within about 1/(N sqrt(trials)) of the strata's ends;
        // the grid's points, and uniform jitter's up to one shared offset that leaves the
        // worst case unchanged, sit at fixed positions: derived, not measured
        let fixed = *spec == "regular" || *spec == "jitter.uniform";
        let tolerance = if fixed { 1e-6 } else { 0.02 };
        rows.push(vec![Cell::from(*name), Cell::num(worst, 6), Cell::Text(fraction_of_n(theory))]);
        claims.push(Claim {
            id: format!("{spec}-box-worst-case"),
            statement: format!("{name} sampling: worst-case error of a box (two discontinuities in different strata)"),
            published: format!("{} (Fig. 6)", fraction_of_n(theory)),
            ours: format!("N x worst |error| = {worst:.6} over {trials} realizations, N = {N}"),
            theory: format!("{theory}"),
            decision: criteria::within(worst, theory, tolerance),
            derived: fixed,
            ..Claim::default()
        });
    }
    let table = Table {
        id: "ramamoorthi2012-fig6-worst-case".into(),
        caption: format!(
            "Fig. 6's worst case: N x the largest |error| of a box over {trials} realizations of N = {N} samples, edges just before or past each sample"
        ),
        columns: ["strategy", "N x worst |error|", "theory (Fig. 6)"].map(String::from).to_vec(),
        rows,
    };
    Ok((table, claims))
}

/// Fig. 7b's reading at 100 discontinuities: stratified's N^2 MSE over uniform's in [1.8,
/// 2.2] ("about twice"), by their standard errors over the instances. Both strategies
/// integrate the same instances, whose errors are positively correlated, so the
/// independent estimates' delta-method error overstates the ratio's: the interval is
/// conservative (more undecided, never a verdict the data do not carry).
fn stratified_twice(stratified: Estimate, uniform: Estimate) -> Claim {
    let ratio = stratified.ratio(uniform);
    Claim {
        id: "stratified-twice-at-100".into(),
        statement: "With many discontinuities (100), stratified sampling still has about twice the variance of uniform sampling".into(),
        published: "about twice (Fig. 7b)".into(),
        ours: format!("stratified / uniform = {:.2} +- {:.2} (SE) at 100 discontinuities", ratio.value, ratio.se),
        theory: "2 while the discontinuities fall in distinct strata".into(),
        decision: criteria::in_range(ratio, 1.8, 2.2),
        explanation: Some(format!(
            "with 100 discontinuities at uniform random positions over 256 strata, about C(100,2)/256 = 19 pairs share a stratum, which the per-discontinuity theory excludes; the schemes then draw closer ({:.2}), as the paper notes for very complex visibility",
            ratio.value
        )),
        ..Claim::default()
    }
}

/// `t / N` written as the paper writes it: 1/N, 2/N.
fn fraction_of_n(t: f64) -> String {
    format!("{t}/N")
}

fn fraction(t: f64) -> String {
    let d = (1.0 / t).round();
    if (1.0 / d - t).abs() < 1e-12 { format!("1/{d}") } else { format!("{t:.4}") }
}

pub(super) fn discontinuities(ctx: &Ctx) -> Result<Output, Error> {
    let trials = 1000;
    let small: Vec<usize> = (1..=7).collect();
    let large: Vec<usize> = vec![1, 2, 5, 10, 20, 30, 50, 70, 100];
    ctx.set_length(((small.len() + large.len()) * 4 * trials) as u64);
    let mut figures = Vec::new();
    let mut claims = Vec::new();
    let mut table_rows = Vec::new();
    for (which, ks) in [("7", &small), ("100", &large)] {
        let mut curves: Vec<Series> = STRATEGIES
            .iter()
            .map(|(name, spec)| Series {
                markers: which == "7",
                colour_key: Some(spec.to_string()),
                ..Series::line(*name, Vec::new())
            })
            .collect();
        let mut rows = Vec::new();
        for &k in ks {
            let specs: Vec<&str> = STRATEGIES.iter().map(|s| s.1).collect();
            rows = study(ctx, &specs, &format!("steps:k={k}"), &[256], 2, trials, ctx.seed.derive(k as u64))?;
            for (c, r) in curves.iter_mut().zip(&rows) {
                c.points.push((k as f64, r.normalized_mse));
            }
            if which == "7" {
                let mut row = vec![Cell::num(k as f64, 0)];
                for r in &rows {
                    row.push(Cell::num(r.normalized_mse, 3));
                }
                for (_, spec) in &STRATEGIES[..3] {
                    row.push(theory::visibility_normalized_mse(spec, k).map_or(Cell::Empty, |t| Cell::num(t, 3)));
                }
                table_rows.push(row);
            }
        }
        figures.push(fig7(which, ks, &curves)?);
        claims.push(fig7_claim(which, &curves, &rows));
    }
    let mut columns: Vec<String> = vec!["discontinuities".into()];
    columns.extend(STRATEGIES.iter().map(|s| s.0.to_string()));
    columns.extend(STRATEGIES[..3].iter().map(|s| format!("{}, theory", s.0)));
    Ok(Output {
        tables: vec![Table {
            id: "ramamoorthi2012-fig7".into(),
            caption: "N^2 x mean squared error against the number of discontinuities, N = 256, 1000 trials (Fig. 7a)"
                .into(),
            columns,
            rows: table_rows,
        }],
        figures,
        claims,
        notes: vec![],
    })
}

/// The discontinuities of section 8's comparisons.
const SECTION8_KS: [usize; 6] = [1, 2, 3, 5, 10, 20];

/// Dart throwing's relative radius for section 8: the paper's 0.75 is past what random
/// sequential addition reaches in 1D (Renyi's parking constant, 0.7476, is its mean density
/// at saturation), so samplab's default 0.7, inside Lagae & Dutre's recommended 0.65-0.85.
const POISSON_RHO: f64 = 0.7;

/// Section 8: Poisson disk sampling (relative radius [`POISSON_RHO`]) against stratified
/// sampling and uniform jitter at N = 256, and Halton with a random offset per estimate
/// against uniform jitter at N = 200 (not a power of 2: at N = 256 the base-2 points are
/// the grid k/256, and a random offset makes them uniform jitter exactly), on 1D visibility
/// with [`SECTION8_KS`] discontinuities.
pub(super) fn section8(ctx: &Ctx) -> Result<Output, Error> {
    let trials = 1000;
    ctx.set_length((SECTION8_KS.len() * trials * 6) as u64);
    let poisson = format!("poisson:radius={}", POISSON_RHO / 256.0);
    let measured = |r: &Row| Estimate { value: r.normalized_mse, se: r.normalized_mse_se };
    let (mut rows, mut worse, mut similar) = (Vec::new(), Vec::new(), Vec::new());
    for &k in &SECTION8_KS {
        let integrand = format!("steps:k={k}");
        let seed = ctx.seed.derive(k as u64);
        let at256 =
            study(ctx, &["jitter", "jitter.uniform", &poisson, "halton.shift"], &integrand, &[256], 2, trials, seed)?;
        let at200 = study(ctx, &["jitter.uniform", "halton.shift"], &integrand, &[200], 2, trials, seed.derive(1))?;
        let (strat, uj, pd) = (measured(&at256[0]), measured(&at256[1]), measured(&at256[2]));
        let ratio = measured(&at200[1]).ratio(measured(&at200[0]));
        worse.push((k, strat, uj, pd));
        similar.push((k, measured(&at256[3]).ratio(uj), ratio));
        rows.push(vec![
            Cell::num(k as f64, 0),
            Cell::num(strat.value, 4),
            Cell::num(uj.value, 4),
            Cell::num(pd.value, 4),
            Cell::num(pd.se, 4),
            Cell::num(similar[similar.len() - 1].1.value, 3),
            Cell::num(ratio.value, 3),
            Cell::num(ratio.se, 3),
        ]);
    }
    Ok(Output {
        tables: vec![Table {
            id: "ramamoorthi2012-section8".into(),
            caption: format!(
                "Section 8 on 1D visibility: N^2 x mean squared error at N = 256 over {trials} trials (stratified, uniform jitter, Poisson disk at relative radius {POISSON_RHO}), and Halton with a random offset over uniform jitter at N = 256 and 200"
            ),
            columns: [
                "discontinuities",
                "stratified",
                "uniform jitter",
                "Poisson disk",
                "its SE",
                "Halton (offset) / uniform jitter, N = 256",
                "the same, N = 200",
                "its SE",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        }],
        figures: vec![],
        claims: vec![poisson_worse_claim(&worse), halton_shift_claim(&similar)],
        notes: vec![format!(
            "Dart throwing in 1D cannot reliably reach the paper's relative radius 0.75: random sequential addition jams at a mean density of 0.7476 (Renyi's parking constant), and `samplab generate {} -n 256 --dims 1 --sets 2000` fails for lack of room; the comparison uses {POISSON_RHO}, inside the 0.65-0.85 that Lagae & Dutre recommend.",
            format!("poisson:radius={}", 0.75 / 256.0)
        )],
    })
}

/// Section 8's "the more uneven spacing ... caused by rho < 1 leads to larger errors than
/// ... both stratified and uniform jitter": at every count of discontinuities, Poisson
/// disk's N^2 MSE above each, by 3 standard errors. `per_k`: (k, stratified, uniform
/// jitter, Poisson disk).
fn poisson_worse_claim(per_k: &[(usize, Estimate, Estimate, Estimate)]) -> Claim {
    let parts: Vec<_> = per_k.iter().flat_map(|&(_, s, u, p)| [criteria::less(s, p), criteria::less(u, p)]).collect();
    Claim {
        id: "poisson-worse".into(),
        statement: "Poisson disk sampling (relative radius below 1) has larger errors than stratified sampling and uniform jitter on visibility (section 8, initial tests)".into(),
        published: "section 8: 'leads to larger errors than the sampling strategies (both stratified and uniform jitter)'".into(),
        ours: per_k
            .iter()
            .map(|(k, s, u, p)| format!("k = {k}: {:.3} / {:.3} / {:.3}", s.value, u.value, p.value))
            .collect::<Vec<_>>()
            .join("; ")
            + &format!(" (N^2 MSE, stratified / uniform jitter / Poisson disk at relative radius {POISSON_RHO}, N = 256)"),
        theory: "section 8: rho < 1 shrinks the band-gap around DC below uniform jitter's (Fig. 11)".into(),
        decision: criteria::all(&parts),
        ..Claim::default()
    }
}

/// Section 8's "one can jitter the offset independently at each pixel ... in which case
/// Halton will perform very similarly to uniform jitter": Halton (offset) over uniform
/// jitter's N^2 MSE within [0.8, 1.25] at every count of discontinuities and at both N =
/// 256 and N = 200, by its interval of 3 standard errors (both integrate the same
/// visibility functions, so the independent ratio's error is conservative). `per_k`: (k,
/// the ratio at 256, at 200).
fn halton_shift_claim(per_k: &[(usize, Estimate, Estimate)]) -> Claim {
    let decision = criteria::all(
        &per_k
            .iter()
            .flat_map(|(_, a, b)| [criteria::in_range(*a, 0.8, 1.25), criteria::in_range(*b, 0.8, 1.25)])
            .collect::<Vec<_>>(),
    );
    let fails_at_200 =
        per_k.iter().any(|(_, _, b)| criteria::in_range(*b, 0.8, 1.25).verdict == crate::Verdict::NotReproduced);
    Claim {
        id: "halton-offset-like-uniform-jitter".into(),
        statement: "Halton with its offset jittered independently per pixel performs very similarly to uniform jitter on visibility (section 8)".into(),
        published: "section 8".into(),
        ours: per_k
            .iter()
            .map(|(k, a, b)| format!("k = {k}: {:.3} +- {:.3} (N = 256), {:.3} +- {:.3} (N = 200)", a.value, a.se, b.value, b.se))
            .collect::<Vec<_>>()
            .join("; ")
            + " (Halton (offset) over uniform jitter, N^2 MSE)",
        theory: "at N = 2^m the base-2 points are the grid k/N, and one random offset makes them uniform jitter exactly".into(),
        decision,
        explanation: fails_at_200.then(|| "the statement holds where the count is a power of the base: at N = 256 the first 256 base-2 points are the grid k/256, and the shared offset makes them uniform jitter exactly (ratio 1 within its error). At N = 200 they are the 128 points of the grid k/128 and 72 of the midpoints between them: where no midpoint was added the gap is twice the others, and a discontinuity there errs as with a grid of half the density, so the error is about twice uniform jitter's at 200 points. The paper does not say which counts its remark was tried at".into()),
        ..Claim::default()
    }
}

/// Fig. 7 up to `which` discontinuities: the measured curves and the closed forms.
fn fig7(which: &str, ks: &[usize], curves: &[Series]) -> Result<Figure, Error> {
    let mut series = curves.to_vec();
    for (name, spec) in &STRATEGIES[..3] {
        let pts =
            ks.iter().filter_map(|&k| theory::visibility_normalized_mse(spec, k).map(|t| (k as f64, t))).collect();
        series.push(Series {
            dashed: true,
            colour_key: Some(spec.to_string()),
            ..Series::line(format!("{name}, theory"), pts)
        });
    }
    let chart = LineChart {
        title: format!("N^2 x variance against the number of discontinuities (up to {which}), N = 256"),
        x_label: "number of discontinuities".into(),
        y_label: "N^2 x mean squared error".into(),
        series,
        log_y: false,
        log_x: false,
        polar: false,
    };
    Figure::render(
        &format!("ramamoorthi2012-fig7-{which}"),
        &format!("Fig. 7: normalized variance, up to {which} discontinuities, 1000 trials; dashed: theory"),
        &chart,
        (900, 560),
    )
}

/// Fig. 7's claims: Halton's zigzag up to 7 discontinuities (from the curves), stratified
/// against uniform at the last count of `rows` (100).
fn fig7_claim(which: &str, curves: &[Series], rows: &[samplab::experiment::Row]) -> Claim {
    if which == "100" {
        stratified_twice(
            Estimate { value: rows[1].normalized_mse, se: rows[1].normalized_mse_se },
            Estimate { value: rows[0].normalized_mse, se: rows[0].normalized_mse_se },
        )
    } else {
        let halton: Vec<f64> = curves[3].points.iter().map(|p| p.1).collect();
        let zigzag =
            (1..halton.len() - 1).filter(|&i| (halton[i] - halton[i - 1]) * (halton[i + 1] - halton[i]) < 0.0).count();
        Claim {
            id: "halton-odd-even".into(),
            statement:
                "Halton's error is non-monotonic between odd and even numbers of discontinuities (larger for odd)"
                    .into(),
            published: "Fig. 7a".into(),
            ours: format!(
                "{zigzag} direction changes over k = 1..7; values {}",
                halton.iter().map(|v| format!("{v:.3}")).collect::<Vec<_>>().join(", ")
            ),
            theory: String::new(),
            decision: criteria::exactly(zigzag >= 4, "at least 4 changes of direction over k = 1..7"),
            ..Claim::default()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Verdict;

    #[test]
    fn stratified_twice_can_fail() {
        let est = |value, se| Estimate { value, se };
        // twice, measured tightly
        assert_eq!(stratified_twice(est(0.4, 0.004), est(0.2, 0.002)).decision.verdict, Verdict::Reproduced);
        // 1.6 +- 0.02: wholly below the band
        assert_eq!(stratified_twice(est(0.32, 0.003), est(0.2, 0.002)).decision.verdict, Verdict::NotReproduced);
        // 1.8 with a wide error: the band's edge inside the interval
        assert_eq!(stratified_twice(est(0.36, 0.03), est(0.2, 0.02)).decision.verdict, Verdict::Undecided);
    }

    #[test]
    fn the_section8_claims_can_fail() {
        let est = |value, se| Estimate { value, se };
        let (s, u) = (est(0.5, 0.02), est(0.3, 0.01));
        assert_eq!(poisson_worse_claim(&[(1, s, u, est(0.8, 0.03))]).decision.verdict, Verdict::Reproduced);
        // Poisson disk between the two
        assert_eq!(poisson_worse_claim(&[(1, s, u, est(0.4, 0.01))]).decision.verdict, Verdict::NotReproduced);
        let one = est(1.0, 0.02);
        assert_eq!(halton_shift_claim(&[(1, one, est(1.02, 0.03))]).decision.verdict, Verdict::Reproduced);
        let failed = halton_shift_claim(&[(1, one, est(1.6, 0.05))]);
        assert_eq!(failed.decision.verdict, Verdict::NotReproduced);
        assert!(failed.explanation.is_some());
    }

    #[test]
    fn the_endpoints_claim_can_fail() {
        let est = |value, se| Estimate { value, se };
        assert_eq!(endpoints_claim(est(0.335, 0.005)).decision.verdict, Verdict::Reproduced);
        // stratified's 1/6 where the end's 1/3 is due
        assert_eq!(endpoints_claim(est(0.167, 0.005)).decision.verdict, Verdict::NotReproduced);
    }
}
