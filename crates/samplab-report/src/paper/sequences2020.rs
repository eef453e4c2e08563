//! The 2020-2025 sequences beside the Sobol' sequence they set out to improve. First the SZ
//! sequence (Ahmed, Pharr, Ostromoukhov & Huang 2025) as OpenQMC's `SobolSampler` draws it
//! since its pull request #108: the protocol of that thread (the RMSE of Sobol' against SZ
//! on each pair of dimensions of 2D integrands, 1024 realizations, 4096 samples), and the
//! structure OpenQMC's README states (a (0, 4)-sequence in base 4, Sobol's first two
//! dimensions), counted on elementary intervals. Then the pairs of dimensions of Cascaded
//! Sobol' (Paulin et al. 2021) and the xi-sequence (Ahmed et al. 2023) beside Sobol's and
//! Niederreiter's, and what Samplin' Safari calls xi. (OneTwo and the quad-optimized
//! sequences are their authors' tables, which samplab does not ship: the coverage says so.)
//! Criteria are fixed in this file before any run.

use rayon::prelude::*;
use samplab::discrepancy::{self, Limits, Metric};
use samplab::pixel::{Film, prepare};
use samplab::points::PointSet;
use samplab::seed::below;

use crate::criteria::{self, Decision, Estimate};
use crate::plot::{LineChart, Series};
use crate::published::table;
use crate::{Cell, Claim, Ctx, Error, Experiment, Figure, Output, Paper, Table};

/// The page.
pub fn paper() -> Paper {
    Paper {
        key: "sequences2020",
        title: "The 2020-2025 sequences",
        experiments: vec![
            Experiment {
                id: "pairs",
                title: "SZ against Sobol' on every pair of dimensions (OpenQMC pull request #108)",
                source: "Ahmed et al. 2025 (SZ sequences); OpenQMC pull request #108 (its protocol and published ratios)",
                parameters: "openqmc.sobol (OpenQMC 0.2's SobolSampler, the classic Sobol' matrices) against openqmc.sz (its SobolSampler since pull request #108, the SZ matrices), pixel (0, 0), frame 0; 1024 realizations (a seed each, the same for both samplers), 4096 samples each; the quarter disk, quarter Gaussian and bilinear integrands of OpenQMC's shapes on each of the 6 pairs of dimensions 0-3; RMSE of the running estimate over the realizations; the ratio Sobol' / SZ's geometric mean over n = 16, 64, 256, 1024, 4096 (4^k) and over n = 8, 32, 128, 512, 2048 (2 * 4^k); standard errors by a paired bootstrap of the realizations (200 resamples); f64 arithmetic throughout (OpenQMC's script sums in f32); the same at both scales",
                run: pairs,
            },
            Experiment {
                id: "t-values",
                title: "The t-value of each 2D projection and of the whole set",
                source: "Ahmed et al. 2025; OpenQMC's README at pull request #108 (the structure it states)",
                parameters: "sobol, sz, niederreiter (base 2) and faure (base 5, 5^5 points) in 4 dimensions; 4096 points (4^6); t of each pair of dimensions and of the whole set in base 2 and base 4, counted on elementary intervals (samplab's t-value metric); the base-4 claim also at every prefix of 4^k points, k = 1..6",
                run: t_values,
            },
            Experiment {
                id: "projections",
                title: "The pairs of dimensions of Cascaded Sobol' and xi",
                source: "Paulin et al. 2021 (Cascaded Sobol', here of Joe & Kuo's generators); Ahmed et al. 2023 (xi) and Samplin' Safari's name for it",
                parameters: "sobol and cascaded (base 2, 4096 points) and niederreiter:base=3 (base 3, 3^7 = 2187 points) in 16 dimensions, xi in 2; the largest t over the pairs (2k, 2k + 1), over the pairs (2k + 1, 2k + 2), and over every pair, counted on elementary intervals; the claim at every prefix of 2^m points, m = 1..12",
                run: projections,
            },
        ],
    }
}

/// The two samplers compared, Sobol' first (the ratio's numerator).
const SAMPLERS: [&str; 2] = ["openqmc.sobol", "openqmc.sz"];
/// Realizations and samples of the protocol.
const REALIZATIONS: usize = 1024;
const SAMPLES: u32 = 4096;
/// Every pair of dimensions 0-3.
const PAIRS: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
/// The counts of the two geometric means: 4^k and 2 * 4^k, the last five of each up to
/// 4096.
const AT_POWERS_OF_4: [u32; 5] = [16, 64, 256, 1024, 4096];
const AT_TWICE: [u32; 5] = [8, 32, 128, 512, 2048];
/// Bootstrap resamples for the standard errors.
const RESAMPLES: usize = 200;

/// erf(1), to double precision (checked by quadrature in the tests).
const ERF_1: f64 = 0.842_700_792_949_714_9;

/// OpenQMC's 2D shapes (its `src/shapes.h`): name, the function, the exact integral.
type Shape = (&'static str, fn(f64, f64) -> f64, f64);
const SHAPES: [Shape; 3] = [
    ("quarter disk", |x, y| if x * x + y * y < 2.0 / std::f64::consts::PI { 1.0 } else { 0.0 }, 0.5),
    ("quarter Gaussian", |x, y| (-(x * x + y * y)).exp(), std::f64::consts::FRAC_PI_4 * ERF_1 * ERF_1),
    ("bilinear", |x, y| x * y, 0.25),
];

/// The series: shape-major, then pair.
const SERIES: usize = SHAPES.len() * PAIRS.len();
/// The checkpoints: every count of either mean, ascending.
const CHECKPOINTS: [u32; 10] = [8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096];

/// One realization's squared errors: `[series][checkpoint]`.
type Squared = [[f64; CHECKPOINTS.len()]; SERIES];

/// The squared errors of every realization of `name`.
fn realizations(ctx: &Ctx, name: &str) -> Result<Vec<Squared>, Error> {
    let film = Film { width: 1, height: 1, spp: SAMPLES, dims: 4 };
    (0..REALIZATIONS)
        .into_par_iter()
        .map(|r| {
            let p = prepare(name, film, ctx.seed.derive(r as u64))?;
            let mut sums = [0.0; SERIES];
            let mut out = [[0.0; CHECKPOINTS.len()]; SERIES];
            let mut next = 0;
            for i in 0..SAMPLES {
                let x = p.sample4([0, 0], 0, i, 0);
                for (s, (_, f, _)) in SHAPES.iter().enumerate() {
                    for (q, &(a, b)) in PAIRS.iter().enumerate() {
                        sums[s * PAIRS.len() + q] += f(x[a], x[b]);
                    }
                }
                if i + 1 == CHECKPOINTS[next] {
                    for (k, sum) in sums.iter().enumerate() {
                        let exact = SHAPES[k / PAIRS.len()].2;
                        out[k][next] = (sum / f64::from(i + 1) - exact).powi(2);
                    }
                    next = (next + 1).min(CHECKPOINTS.len() - 1);
                }
            }
            ctx.advance(1)?;
            Ok(out)
        })
        .collect()
}

/// log(RMSE of Sobol' / RMSE of SZ) per series and checkpoint, over the realizations
/// `picks` (indices, with repeats in a bootstrap resample).
fn log_ratios(sobol: &[Squared], sz: &[Squared], picks: &[usize]) -> Squared {
    let mut out = [[0.0; CHECKPOINTS.len()]; SERIES];
    for (k, row) in out.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            let mse = |set: &[Squared]| picks.iter().map(|&r| set[r][k][c]).sum::<f64>();
            *v = 0.5 * (mse(sobol) / mse(sz)).ln();
        }
    }
    out
}

/// The geometric mean over `counts` of a series' ratios, from its log ratios.
fn geometric_mean(logs: &[f64; CHECKPOINTS.len()], counts: &[u32]) -> f64 {
    let sum: f64 = counts.iter().map(|n| logs[CHECKPOINTS.iter().position(|c| c == n).expect("a checkpoint")]).sum();
    (sum / counts.len() as f64).exp()
}

/// Per series: the two geometric means, each with its bootstrap standard error.
fn means(ctx: &Ctx, sobol: &[Squared], sz: &[Squared]) -> Vec<[Estimate; 2]> {
    let all: Vec<usize> = (0..REALIZATIONS).collect();
    let point = log_ratios(sobol, sz, &all);
    let mut rng = ctx.seed.derive_str("bootstrap").rng();
    let resamples: Vec<Squared> = (0..RESAMPLES)
        .map(|_| {
            let picks: Vec<usize> = (0..REALIZATIONS).map(|_| below(&mut rng, REALIZATIONS as u64) as usize).collect();
            log_ratios(sobol, sz, &picks)
        })
        .collect();
    (0..SERIES)
        .map(|k| {
            [&AT_POWERS_OF_4[..], &AT_TWICE[..]].map(|counts| {
                let value = geometric_mean(&point[k], counts);
                let draws: Vec<f64> = resamples.iter().map(|b| geometric_mean(&b[k], counts)).collect();
                Estimate::bootstrapped(value, &draws)
            })
        })
        .collect()
}

/// The published ratio of a (shape, pair) at 4^k and 2 * 4^k, where the thread gives one.
fn published(shape: &str, pair: (usize, usize)) -> Option<[f64; 2]> {
    let key = format!("{shape} {}{}", pair.0, pair.1);
    table("sequences2020", "pr108").row(&key).map(|v| [v[0], v[1]])
}

/// "Sobol' / SZ is the published ratio": within [`criteria::Z`] standard errors of ours,
/// allowing half a unit of the two printed decimals.
pub(crate) fn ratio_agrees(ours: Estimate, published: f64) -> Decision {
    criteria::agrees(ours, Estimate::exact(published), 0.005)
}

fn pairs(ctx: &Ctx) -> Result<Output, Error> {
    ctx.set_length((SAMPLERS.len() * REALIZATIONS) as u64);
    let sobol = realizations(ctx, SAMPLERS[0])?;
    let sz = realizations(ctx, SAMPLERS[1])?;
    let means = means(ctx, &sobol, &sz);
    let mut rows = Vec::new();
    let mut claims = Vec::new();
    for (s, (shape, _, _)) in SHAPES.iter().enumerate() {
        for (q, &pair) in PAIRS.iter().enumerate() {
            let m = means[s * PAIRS.len() + q];
            let theirs = published(shape, pair);
            let mut row = vec![Cell::Text((*shape).into()), Cell::Text(format!("({}, {})", pair.0, pair.1))];
            for (i, e) in m.iter().enumerate() {
                row.push(Cell::Text(format!("{:.3} ± {:.3}", e.value, e.se)));
                row.push(theirs.map_or(Cell::Text("-".into()), |p| Cell::num(p[i], 2)));
            }
            rows.push(row);
            let Some(theirs) = theirs else { continue };
            for (i, (label, id)) in [("4^k", "powers-of-4"), ("2 * 4^k", "twice")].into_iter().enumerate() {
                claims.push(Claim {
                    id: format!("pr108-{}-{}{}-{id}", shape.replace(' ', "-").to_lowercase(), pair.0, pair.1),
                    statement: format!(
                        "{shape} on dimensions ({}, {}): RMSE of Sobol' / SZ, geometric mean at n = {label}, is {:.2}",
                        pair.0, pair.1, theirs[i]
                    ),
                    published: format!("OpenQMC pull request #108 (wantonsushi, 2026-08-04): {:.2}", theirs[i]),
                    ours: format!("{:.3} ± {:.3} (bootstrap standard error)", m[i].value, m[i].se),
                    decision: ratio_agrees(m[i], theirs[i]),
                    ..Claim::default()
                });
            }
        }
    }
    let mut columns = vec!["shape".to_string(), "pair".to_string()];
    for label in ["4^k", "2 * 4^k"] {
        columns.push(format!("Sobol' / SZ at {label}"));
        columns.push(format!("published at {label}"));
    }
    Ok(Output {
        tables: vec![Table {
            id: "sequences2020-pairs".into(),
            caption: "RMSE of OpenQMC's Sobol' sampler over its SZ sampler (above 1: SZ the better), geometric means over n = 16..4096 (4^k) and 8..2048 (2 * 4^k), 1024 realizations, ± a bootstrap standard error; published: OpenQMC pull request #108, where the thread gives the pair (the pairs (1, 2) and (1, 3) of its table, and (0, 1) and (2, 3), were not in the text available to samplab: '-')".into(),
            columns,
            rows,
        }],
        figures: vec![figure(&sobol, &sz)?],
        claims,
        notes: vec![
            "SZ's dimensions 0 and 1 are Sobol's, bit for bit (the fixture test), so the pair (0, 1) is the same set for both samplers and its ratio is 1 exactly; a pair with dimension 2 or 3 is where the two differ.".into(),
        ],
    })
}

/// The ratio Sobol' / SZ against n for each pair, on the quarter Gaussian (whose published
/// ratios move the most between the two kinds of count).
fn figure(sobol: &[Squared], sz: &[Squared]) -> Result<Figure, Error> {
    let all: Vec<usize> = (0..REALIZATIONS).collect();
    let logs = log_ratios(sobol, sz, &all);
    let s = 1; // the quarter Gaussian
    let series = PAIRS
        .iter()
        .enumerate()
        .map(|(q, &(a, b))| {
            let points =
                CHECKPOINTS.iter().zip(&logs[s * PAIRS.len() + q]).map(|(&n, l)| (f64::from(n), l.exp())).collect();
            let mut series = Series::line(format!("({a}, {b})"), points);
            series.markers = true;
            series.colour_key = Some(["random", "jitter", "halton", "sobol", "pmj02", "lattice"][q].into());
            series
        })
        .collect();
    let chart = LineChart {
        title: "Quarter Gaussian: RMSE of Sobol' / RMSE of SZ".into(),
        x_label: "samples n".into(),
        y_label: "RMSE ratio (above 1: SZ better)".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    };
    Figure::render(
        "sequences2020-pairs-ratio",
        "The ratio of OpenQMC's Sobol' to SZ RMSE on the quarter Gaussian, per pair of dimensions, at n = 8, 16, ..., 4096 (1024 realizations)",
        &chart,
        (900, 600),
    )
}

/// The t of a point set's dimensions `dims` in `base`, counted on elementary intervals.
fn t_of(points: &PointSet, dims: &[usize], base: u32) -> Result<f64, Error> {
    let d = points.dims();
    let picked: Vec<f64> = points.as_slice().chunks_exact(d).flat_map(|p| dims.iter().map(|&j| p[j])).collect();
    let projection = PointSet::new(dims.len(), picked)?;
    Ok(discrepancy::compute(&Metric::parse(&format!("t-value:base={base}"))?, &projection, Limits::default())?)
}

/// The t-value table's samplers: spec, points, and the base of the whole set's second t.
const T_SAMPLERS: [(&str, usize, u32); 4] =
    [("sobol", 4096, 4), ("sz", 4096, 4), ("niederreiter", 4096, 4), ("faure", 3125, 5)];

fn t_values(ctx: &Ctx) -> Result<Output, Error> {
    ctx.set_length(T_SAMPLERS.len() as u64 + 1);
    let mut rows = Vec::new();
    for (spec, n, second) in T_SAMPLERS {
        let points = samplab::sampler::build(spec)?.generate(n, 4, ctx.seed.derive_str(spec))?;
        let base = if spec == "faure" { 5 } else { 2 };
        let mut row = vec![Cell::Text(spec.into()), Cell::Text(n.to_string())];
        for &(a, b) in &PAIRS {
            row.push(Cell::num(t_of(&points, &[a, b], base)?, 0));
        }
        row.push(Cell::num(t_of(&points, &[0, 1, 2, 3], base)?, 0));
        row.push(Cell::Text(format!("{} (base {second})", t_of(&points, &[0, 1, 2, 3], second)?)));
        rows.push(row);
        ctx.advance(1)?;
    }
    let claims = structure_claims(ctx)?;
    ctx.advance(1)?;
    let mut columns = vec!["sampler".to_string(), "n".to_string()];
    columns.extend(PAIRS.iter().map(|(a, b)| format!("t ({a}, {b})")));
    columns.extend(["t, all 4".to_string(), "t, all 4, in the second base".to_string()]);
    Ok(Output {
        tables: vec![Table {
            id: "sequences2020-t-values".into(),
            caption: "The least t for which each 2D projection, and the whole 4D set, is a (t, m, s)-net: every elementary interval of volume b^(t-m) holds b^t points, counted interval by interval (base 2; faure in its own base 5); the last column in base 4 (faure: 5). t = 0 is the best a set can do".into(),
            columns,
            rows,
        }],
        claims,
        ..Output::default()
    })
}

/// The projections table's samplers: spec, base, points, dimensions.
const P_SAMPLERS: [(&str, u32, usize, usize); 4] =
    [("sobol", 2, 4096, 16), ("cascaded", 2, 4096, 16), ("niederreiter:base=3", 3, 2187, 16), ("xi", 2, 4096, 2)];

/// The largest t over the pairs of dimensions `pairs` of `points`, in `base`.
fn worst_t(points: &PointSet, pairs: impl Iterator<Item = (usize, usize)>, base: u32) -> Result<f64, Error> {
    pairs.map(|(a, b)| t_of(points, &[a, b], base)).try_fold(0.0f64, |w, t| t.map(|t| w.max(t)))
}

/// The largest t over the pairs `pairs` of `spec` at every prefix of b^m points, m = 1..=`most`.
fn worst_t_of_prefixes(
    ctx: &Ctx,
    spec: &str,
    base: u32,
    most: u32,
    dims: usize,
    pairs: &[(usize, usize)],
) -> Result<f64, Error> {
    let sampler = samplab::sampler::build(spec)?;
    let mut worst = 0.0f64;
    for m in 1..=most {
        let points = sampler.generate(base.pow(m) as usize, dims, ctx.seed.derive_str(spec))?;
        worst = worst.max(worst_t(&points, pairs.iter().copied(), base)?);
    }
    Ok(worst)
}

fn projections(ctx: &Ctx) -> Result<Output, Error> {
    ctx.set_length(P_SAMPLERS.len() as u64 + 1);
    let mut rows = Vec::new();
    for (spec, base, n, dims) in P_SAMPLERS {
        let points = samplab::sampler::build(spec)?.generate(n, dims, ctx.seed.derive_str(spec))?;
        let even = worst_t(&points, (0..dims - 1).step_by(2).map(|j| (j, j + 1)), base)?;
        let mut row = vec![Cell::Text(spec.into()), Cell::Text(base.to_string()), Cell::Text(n.to_string())];
        row.push(Cell::num(even, 0));
        if dims > 2 {
            let odd = worst_t(&points, (1..dims - 1).step_by(2).map(|j| (j, j + 1)), base)?;
            let all = worst_t(&points, (0..dims).flat_map(|a| (a + 1..dims).map(move |b| (a, b))), base)?;
            row.extend([Cell::num(odd, 0), Cell::num(all, 0)]);
        } else {
            row.extend([Cell::Text("-".into()), Cell::num(even, 0)]);
        }
        rows.push(row);
        ctx.advance(1)?;
    }
    let claims = projection_claims(ctx)?;
    ctx.advance(1)?;
    let columns = ["sampler", "base", "n", "t, pairs (2k, 2k+1)", "t, pairs (2k+1, 2k+2)", "t, every pair"];
    Ok(Output {
        tables: vec![Table {
            id: "sequences2020-projections".into(),
            caption: "The largest t over pairs of dimensions of the first 16 (xi: its 2), each pair's t the least for which every elementary interval of volume b^(t-m) holds b^t points, counted interval by interval in the sampler's base. t = 0 is the best a pair can do".into(),
            columns: columns.iter().map(|c| c.to_string()).collect(),
            rows,
        }],
        claims,
        ..Output::default()
    })
}

/// The xi statement of Samplin' Safari, checked on the points.
fn projection_claims(ctx: &Ctx) -> Result<Vec<Claim>, Error> {
    let xi = worst_t_of_prefixes(ctx, "xi", 2, 12, 2, &[(0, 1)])?;
    Ok(vec![Claim {
        id: "xi-0-2-sequence".into(),
        statement: "xi: the two dimensions are a (0, 2)-sequence".into(),
        published: "Samplin' Safari's name for the xi-sequence of Ahmed et al. 2023 (include/sampler/XiSequence.h): \"Xi (0,m,2)-sequence\"".into(),
        ours: format!("the largest t at every prefix of 2^m points, m = 1..12: {xi}"),
        decision: criteria::exactly(xi == 0.0, &format!("t = 0 at every prefix (largest {xi})")),
        derived: true,
        ..Claim::default()
    }])
}

/// OpenQMC's statements on its SZ matrices, checked on `sz`'s points.
fn structure_claims(ctx: &Ctx) -> Result<Vec<Claim>, Error> {
    let sz = samplab::sampler::build("sz")?;
    let readme = "OpenQMC's README at pull request #108: \"every pair of the four dimensions forms a (0, 2)-sequence in base 4, and the four together a (0, 4)-sequence\"";
    // every prefix of 4^k points of the whole, and every pair at 4^6
    let mut worst_whole = 0.0f64;
    for k in 1..=6 {
        let p = sz.generate(4usize.pow(k), 4, ctx.seed)?;
        worst_whole = worst_whole.max(t_of(&p, &[0, 1, 2, 3], 4)?);
    }
    let p = sz.generate(4096, 4, ctx.seed)?;
    let worst_pair = PAIRS.iter().map(|&(a, b)| t_of(&p, &[a, b], 4)).try_fold(0.0f64, |w, t| t.map(|t| w.max(t)))?;
    // `net` is Sobol' (Joe & Kuo's matrices) in natural order, as `sz` is; `sobol` is in
    // Gray-code order
    let sobol = samplab::sampler::build("net")?.generate(4096, 4, ctx.seed)?;
    let same01 = sobol.as_slice().chunks_exact(4).zip(p.as_slice().chunks_exact(4)).all(|(a, b)| a[..2] == b[..2]);
    Ok(vec![
        Claim {
            id: "sz-0-4-sequence".into(),
            statement: "sz: every prefix of 4^k points is a (0, k, 4)-net in base 4 (a (0, 4)-sequence)".into(),
            published: readme.into(),
            ours: format!("the largest t over k = 1..6: {worst_whole}"),
            decision: criteria::exactly(
                worst_whole == 0.0,
                &format!("t = 0 in base 4 for every k = 1..6 (largest {worst_whole})"),
            ),
            derived: true,
            ..Claim::default()
        },
        Claim {
            id: "sz-pairs-0-2".into(),
            statement: "sz: every pair of its four dimensions is a (0, 2)-sequence in base 4".into(),
            published: readme.into(),
            ours: format!("the largest t of the 6 pairs at 4^6 points: {worst_pair}"),
            decision: criteria::exactly(
                worst_pair == 0.0,
                &format!("t = 0 in base 4 for every pair (largest {worst_pair})"),
            ),
            derived: true,
            ..Claim::default()
        },
        Claim {
            id: "sz-first-two-sobol".into(),
            statement: "sz: dimensions 0 and 1 are Sobol's".into(),
            published: "OpenQMC's README at pull request #108: \"Dimensions 0 and 1 are the same as Sobol\"".into(),
            ours: format!(
                "the 4096 points' first two coordinates equal those of net (Sobol' in natural order): {same01}"
            ),
            decision: criteria::exactly(same01, "every coordinate of dimensions 0 and 1 equal, bit for bit"),
            derived: true,
            ..Claim::default()
        },
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Verdict;

    #[test]
    fn erf_1_is_the_integral() {
        // erf(1) = 2 / sqrt(pi) * int_0^1 exp(-t^2) dt, by Simpson's rule on 2000 panels
        let n = 2000;
        let h = 1.0 / n as f64;
        let f = |t: f64| (-t * t).exp();
        let simpson =
            (0..n).map(|i| i as f64 * h).map(|a| h / 6.0 * (f(a) + 4.0 * f(a + h / 2.0) + f(a + h))).sum::<f64>();
        assert!((2.0 / std::f64::consts::PI.sqrt() * simpson - ERF_1).abs() < 1e-14);
    }

    #[test]
    fn the_ratio_criterion_can_fail() {
        let ours = Estimate { value: 1.10, se: 0.02 };
        assert_eq!(ratio_agrees(ours, 1.13).verdict, Verdict::Reproduced);
        assert_eq!(ratio_agrees(ours, 1.46).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn every_published_ratio_names_a_shape_and_pair_of_the_page() {
        let t = table("sequences2020", "pr108");
        assert!(!t.rows.is_empty());
        for (key, values) in &t.rows {
            let found = SHAPES.iter().any(|(s, _, _)| PAIRS.iter().any(|(a, b)| *key == format!("{s} {a}{b}")));
            assert!(found && values.len() == 2, "{key}");
        }
    }

    #[test]
    fn the_geometric_mean_is_over_its_counts() {
        let mut logs = [0.0; CHECKPOINTS.len()];
        logs[1] = 2.0f64.ln(); // n = 16: ratio 2, the others 1
        assert!((geometric_mean(&logs, &AT_POWERS_OF_4) - 2.0f64.powf(0.2)).abs() < 1e-12);
        assert!((geometric_mean(&logs, &AT_TWICE) - 1.0).abs() < 1e-12);
    }
}
