//! Shirley 1991, "Discrepancy as a quality measure for sample distributions": Tables 1-4
//! (pixel luminance errors on the checker, checker-45, ball and all images), Tables 5, 6
//! and 7 (star, RMS and Stroud discrepancies of 100 sets of 16 points per strategy) and
//! the projected discrepancy of section 3.1 and the conclusion's open question.

use samplab::discrepancy::{self, Limits, Metric};
use samplab::sampler;
use samplab::stats::Summary;
use samplab::{PointSet, Seed};

use crate::plot::{DotChart, LineChart, Series};
use samplab_render::light::DiskMap;
use samplab_render::{Footprint, Mode, Pattern};

use super::shadows::{self, Setup};
use crate::published::{self, PublishedTable};
use crate::{Cell, Claim, Ctx, Error, Experiment, Figure, Output, Paper, Table, Verdict};

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
                parameters: "128 x 96 pixels (the paper's), 16 samples per pixel from each strategy over the pixel area (and, for the ball and all, the same strategy over each light, the lens and the gloss, dealt to the pixel samples in random orders); reference 256 (fast) or 1024 (full) Owen-scrambled Sobol' samples per pixel",
                run: pixel_errors,
            },
            Experiment {
                id: "tables-5-7",
                title: "Discrepancies of the sampling strategies",
                source: "Tables 5, 6 and 7",
                parameters: "100 sets of 16 points per strategy at both scales (the paper's own); Poisson disks by dart throwing with distances measured inside the square",
                run: tables,
            },
            Experiment {
                id: "projected",
                title: "Projected discrepancy against direction",
                source: "Section 3.1 and the conclusion's open question",
                parameters: "100 sets of 16 points; directions every 2 degrees (fast) or 0.5 degrees (full); extreme 1D discrepancy of the projections against their exact distribution",
                run: projected,
            },
        ],
        pending: vec![],
    }
}

/// Shirley's strategies: his name and our spec.
const STRATEGIES: [(&str, &str); 7] = [
    ("separate", "nrooks"),
    ("half-jittered", "jitter.half"),
    ("jittered", "jitter"),
    ("poisson (d = 0.2)", "poisson:radius=0.2,edge=plain"),
    ("regular", "regular"),
    ("poisson (d = 0.1)", "poisson:radius=0.1,edge=plain"),
    ("random", "random"),
];

const SETS: usize = 100;

/// Lattice for the restricted Stroud discrepancy: corners at multiples of 1/20.
const LATTICE: usize = 20;
const N: usize = 16;

fn sets_of(spec: &str, seed: Seed) -> Result<Vec<PointSet>, Error> {
    let s = sampler::build(spec)?;
    Ok(sampler::generate_sets(s.as_ref(), N, 2, seed, SETS)?)
}

fn metric_values(sets: &[PointSet], m: &Metric) -> Result<Vec<f64>, Error> {
    use rayon::prelude::*;
    Ok(sets.par_iter().map(|s| discrepancy::compute(m, s, Limits::default())).collect::<Result<_, _>>()?)
}

/// Stroud's discrepancy restricted to boxes with corners on the lattice {0, 1/k, ..., 1}
/// (half-open boxes): our hypothesis for how the published T values were evaluated.
fn lattice_extreme(set: &PointSet, k: usize) -> f64 {
    let n = set.len() as f64;
    let mut worst: f64 = 0.0;
    for c in 0..=k {
        for a in c..=k {
            for d in 0..=k {
                for b in d..=k {
                    let (x0, x1, y0, y1) =
                        (c as f64 / k as f64, a as f64 / k as f64, d as f64 / k as f64, b as f64 / k as f64);
                    let inside =
                        set.iter().filter(|p| x0 <= p[0] && p[0] < x1 && y0 <= p[1] && p[1] < y1).count() as f64;
                    worst = worst.max((inside / n - (x1 - x0) * (y1 - y0)).abs());
                }
            }
        }
    }
    worst
}

/// z-score of our mean against a published (mean, sd) of 100 sets, with half a unit of
/// the published last digit as rounding error.
fn z_score(ours: &Summary, published: &[f64], half_unit: f64) -> f64 {
    let se =
        (ours.standard_error().powi(2) + (published[1] / (SETS as f64).sqrt()).powi(2) + half_unit * half_unit).sqrt();
    (ours.mean - published[0]) / se
}

struct Measured {
    name: &'static str,
    d: Summary,
    s: Summary,
    t: Summary,
    t_lattice: Summary,
}

fn comparison_table(
    id: &str,
    caption: String,
    rows: &[(&str, Summary)],
    published: &PublishedTable,
    half_unit: f64,
    digits: usize,
) -> (Table, Vec<(String, f64)>) {
    let mut zs = Vec::new();
    let table_rows = rows
        .iter()
        .map(|(name, s)| {
            let p = published.row(name).expect("every strategy is published");
            let z = z_score(s, p, half_unit);
            zs.push((name.to_string(), z));
            vec![
                Cell::from(*name),
                Cell::num(s.mean, digits),
                Cell::num(s.sd, digits),
                Cell::num(s.max, digits),
                Cell::num(p[0], digits),
                Cell::num(p[1], digits),
                Cell::num(p[2], digits),
                Cell::num(z, 2),
            ]
        })
        .collect();
    let columns = [
        "strategy",
        "mean (ours)",
        "SD (ours)",
        "max (ours)",
        "mean (published)",
        "SD (published)",
        "max (published)",
        "z",
    ]
    .map(String::from)
    .to_vec();
    (Table { id: id.into(), caption, columns, rows: table_rows }, zs)
}

fn within_claim(id: &str, table: &str, zs: &[(String, f64)], known: Option<(&str, &str)>) -> Claim {
    let off: Vec<&(String, f64)> = zs.iter().filter(|(_, z)| z.abs() > 3.0).collect();
    let ours = format!(
        "{} of {} within 3 standard errors{}",
        zs.len() - off.len(),
        zs.len(),
        if off.is_empty() {
            String::new()
        } else {
            format!(
                "; outside: {}",
                off.iter().map(|(n, z)| format!("{n} (z = {z:.1})")).collect::<Vec<_>>().join(", ")
            )
        }
    );
    let verdict = match (off.as_slice(), known) {
        ([], _) => Verdict::Reproduced,
        ([(name, _)], Some((k, why))) if name == k => Verdict::DiffersBecause(why.into()),
        _ => Verdict::NotReproduced,
    };
    Claim {
        id: id.into(),
        statement: format!("Our means of {table} agree with the published ones for every strategy"),
        published: format!("{table} (100 sets of 16 points)"),
        ours,
        theory: String::new(),
        verdict,
    }
}

fn lowest<'a>(rows: impl Iterator<Item = (&'a str, f64)>) -> (&'a str, f64) {
    rows.fold(("", f64::INFINITY), |best, (n, v)| if v < best.1 { (n, v) } else { best })
}

fn tables(ctx: &Ctx) -> Result<Output, Error> {
    ctx.progress.set_length(STRATEGIES.len() as u64);
    let mut measured = Vec::new();
    let mut regular_set = None;
    for (i, (name, spec)) in STRATEGIES.iter().enumerate() {
        let sets = sets_of(spec, ctx.seed.derive(i as u64))?;
        let d = Summary::of(&metric_values(&sets, &Metric::Star)?);
        let s = Summary::of(&metric_values(&sets, &Metric::L2Star)?);
        let t = Summary::of(&metric_values(&sets, &Metric::Extreme)?);
        let t_lattice = Summary::of(&sets.iter().map(|s| lattice_extreme(s, LATTICE)).collect::<Vec<_>>());
        if *name == "regular" {
            regular_set = Some(sets[0].clone());
        }
        measured.push(Measured { name, d, s, t, t_lattice });
        ctx.progress.inc(1);
    }
    let (p5, p6, p7) = (
        published::table("shirley1991", "table5"),
        published::table("shirley1991", "table6"),
        published::table("shirley1991", "table7"),
    );
    let rows = |f: fn(&Measured) -> Summary| measured.iter().map(|m| (m.name, f(m))).collect::<Vec<_>>();
    let (t5, z5) = comparison_table(
        "shirley1991-table5",
        format!(
            "Star discrepancy D of 100 sets of 16 points. Published: {}. z: difference over its standard error (both sample means, and half a unit of the published last digit).",
            p5.source
        ),
        &rows(|m| m.d),
        &p5,
        5e-4,
        4,
    );
    let (t6, z6) = comparison_table(
        "shirley1991-table6",
        format!("RMS (L2-star) discrepancy S. Published: {}.", p6.source),
        &rows(|m| m.s),
        &p6,
        5e-5,
        5,
    );
    let t7 = Table {
        id: "shirley1991-table7".into(),
        caption: format!(
            "Stroud's (extreme) discrepancy T, exact, and restricted to half-open boxes with corners on the 0.05 lattice. Published: {}.",
            p7.source
        ),
        columns: [
            "strategy",
            "exact mean",
            "exact SD",
            "exact max",
            "0.05-lattice mean",
            "0.05-lattice SD",
            "published mean",
            "published SD",
            "published max",
            "z (lattice vs published)",
        ]
        .map(String::from)
        .to_vec(),
        rows: measured
            .iter()
            .map(|m| {
                let p = p7.row(m.name).expect("published");
                vec![
                    Cell::from(m.name),
                    Cell::num(m.t.mean, 4),
                    Cell::num(m.t.sd, 4),
                    Cell::num(m.t.max, 4),
                    Cell::num(m.t_lattice.mean, 4),
                    Cell::num(m.t_lattice.sd, 4),
                    Cell::num(p[0], 4),
                    Cell::num(p[1], 4),
                    Cell::num(p[2], 3),
                    Cell::num(z_score(&m.t_lattice, p, 5e-5), 2),
                ]
            })
            .collect(),
    };
    let z7: Vec<(String, f64)> = measured
        .iter()
        .map(|m| (m.name.to_string(), z_score(&m.t_lattice, p7.row(m.name).expect("published"), 5e-5)))
        .collect();

    let mut claims = Vec::new();
    let (best_d, best_d_v) = lowest(measured.iter().map(|m| (m.name, m.d.mean)));
    claims.push(Claim {
        id: "separate-lowest-d".into(),
        statement: "Separate (N-rooks) sampling has the lowest mean star discrepancy of the strategies".into(),
        published: format!(
            "separate {}, next half-jittered {} (Table 5)",
            p5.row("separate").expect("published")[0],
            p5.row("half-jittered").expect("published")[0]
        ),
        ours: format!("lowest: {best_d} {best_d_v:.4}"),
        theory: String::new(),
        verdict: if best_d == "separate" { Verdict::Reproduced } else { Verdict::NotReproduced },
    });
    let sep = measured.iter().find(|m| m.name == "separate").expect("listed");
    let half = measured.iter().find(|m| m.name == "half-jittered").expect("listed");
    let gap = half.s.mean - sep.s.mean;
    let gap_se = (half.s.standard_error().powi(2) + sep.s.standard_error().powi(2)).sqrt();
    claims.push(Claim {
        id: "half-jittered-lowest-s".into(),
        statement: "Half-jittered sampling has a slightly lower mean RMS discrepancy S than separate sampling".into(),
        published: format!("half-jittered {} < separate {} (Table 6)", p6.row("half-jittered").expect("published")[0], p6.row("separate").expect("published")[0]),
        ours: format!("half-jittered {:.5}, separate {:.5} (difference {:+.5} +- {:.5})", half.s.mean, sep.s.mean, gap, gap_se),
        theory: String::new(),
        verdict: if gap < 0.0 {
            Verdict::Reproduced
        } else if gap < 2.0 * gap_se {
            Verdict::DiffersBecause(format!("the difference ({gap:+.5}) is within two standard errors ({gap_se:.5}) of zero: 100 sets cannot order the two, as the published 0.0004 gap already suggests"))
        } else {
            Verdict::NotReproduced
        },
    });
    claims.push(within_claim("table5-means", "Table 5", &z5, None));
    claims.push(within_claim(
        "table6-means",
        "Table 6",
        &z6,
        Some(("regular", "the regular 4x4 grid's S is 0.0597 exactly (Warnock's closed form, checked against the exact integral in our tests); the published 0.0600 is 0.5% high, likely a numerical estimate of the integral")),
    ));
    let regular = regular_set.expect("regular is listed");
    let exact_d = discrepancy::compute(&Metric::Star, &regular, Limits::default())?;
    claims.push(Claim {
        id: "regular-d".into(),
        statement: "The regular grid's star discrepancy".into(),
        published: format!("{} (Table 5)", p5.row("regular").expect("published")[0]),
        ours: format!("{exact_d:.6}"),
        theory: format!("1 - (7/8)^2 = {:.6}", 1.0 - 0.875f64 * 0.875),
        verdict: if (exact_d - p5.row("regular").expect("published")[0]).abs() < 5e-4 {
            Verdict::Reproduced
        } else {
            Verdict::NotReproduced
        },
    });
    let exact_t = discrepancy::compute(&Metric::Extreme, &regular, Limits::default())?;
    let lattice_t = lattice_extreme(&regular, LATTICE);
    claims.push(Claim {
        id: "regular-t".into(),
        statement: "The regular grid's Stroud discrepancy".into(),
        published: format!("{} (Table 7)", p7.row("regular").expect("published")[0]),
        ours: format!("exact {exact_t:.4}; over boxes with corners on the 0.05 lattice {lattice_t:.4}"),
        theory: "1 - (3/4)^2 = 0.4375 (the closed box [1/8, 7/8]^2 holds all 16 points)".into(),
        verdict: Verdict::DiffersBecause(format!(
            "the published value is below the exact supremum; 0.360 = 1 - 0.8^2 is the box [0.1, 0.9]^2, the best box with corners on a 0.05 lattice (ours there: {lattice_t:.3})"
        )),
    });
    let below = measured.iter().filter(|m| m.t.mean > p7.row(m.name).expect("published")[0]).count();
    let lattice_ok = z7.iter().filter(|(_, z)| z.abs() <= 3.0).count();
    claims.push(Claim {
        id: "table7-lattice".into(),
        statement: "Table 7's T values are reproduced by Stroud's discrepancy over boxes with corners on a 0.05 lattice (our explanation of why they are below the exact values)".into(),
        published: "Table 7".into(),
        ours: format!("every published mean below our exact mean: {below} of 7; lattice means within 3 standard errors of the published: {lattice_ok} of 7"),
        theory: String::new(),
        verdict: if lattice_ok == 7 { Verdict::Reproduced } else { Verdict::NotReproduced },
    });

    let chart = |title: &str, y: &str, f: fn(&Measured) -> Summary, p: &PublishedTable| DotChart {
        title: title.into(),
        y_label: y.into(),
        categories: measured.iter().map(|m| m.name.replace("poisson ", "p")).collect(),
        series: vec![
            (
                "ours (mean +- SD)".into(),
                "jitter".into(),
                measured.iter().map(|m| Some((f(m).mean, f(m).sd))).collect(),
            ),
            (
                "published (mean +- SD)".into(),
                "random".into(),
                measured.iter().map(|m| p.row(m.name).map(|r| (r[0], r[1]))).collect(),
            ),
        ],
    };
    let mut t_chart = chart("Table 7: Stroud's discrepancy T", "T", |m| m.t, &p7);
    t_chart.series[0].0 = "ours, exact (mean +- SD)".into();
    t_chart.series.push((
        "ours, boxes on the 0.05 lattice".into(),
        "regular".into(),
        measured.iter().map(|m| Some((m.t_lattice.mean, m.t_lattice.sd))).collect(),
    ));
    let figures = vec![
        Figure::render(
            "shirley1991-table5",
            "Star discrepancy D per strategy, ours and published (100 sets of 16 points)",
            &chart("Table 5: star discrepancy D", "D (fraction of points)", |m| m.d, &p5),
            (900, 520),
        )?,
        Figure::render(
            "shirley1991-table6",
            "RMS discrepancy S per strategy, ours and published",
            &chart("Table 6: RMS discrepancy S", "S", |m| m.s, &p6),
            (900, 520),
        )?,
        Figure::render(
            "shirley1991-table7",
            "Stroud's discrepancy T per strategy: exact (ours), restricted to boxes with corners on the 0.05 lattice (ours), and published",
            &t_chart,
            (900, 520),
        )?,
    ];
    Ok(Output {
        tables: vec![t5, t6, t7],
        figures,
        claims,
        notes: vec![
            "Exact algorithms: D by a sweep over x with a kinetic segment tree, T by a slab sweep, S by Warnock's closed form (see samplab's discrepancy module); all are checked against brute force over critical boxes.".into(),
            "Poisson disks: dart throwing with the minimum distance measured inside the unit square (no wrap-around), as a 1991 implementation would.".into(),
        ],
    })
}

fn projected(ctx: &Ctx) -> Result<Output, Error> {
    let step = ctx.pick(2.0, 0.5);
    let angles: Vec<f64> = (0..).map(|i| i as f64 * step).take_while(|&a| a < 180.0).collect();
    let mut strategies: Vec<(&str, &str)> = STRATEGIES.to_vec();
    strategies.extend([("sobol (Owen)", "sobol.owen"), ("pmj02", "pmj02")]);
    ctx.progress.set_length(strategies.len() as u64);
    let mut curves = Vec::new();
    for (i, (name, spec)) in strategies.iter().enumerate() {
        let sets = sets_of(spec, ctx.seed.derive(i as u64))?;
        let mut curve = Vec::with_capacity(angles.len());
        for &angle in &angles {
            let v = metric_values(&sets, &Metric::Projected { angle, extreme: true })?;
            curve.push((angle, Summary::of(&v).mean));
        }
        curves.push((*name, *spec, curve));
        ctx.progress.inc(1);
    }
    let at = |c: &[(f64, f64)], a: f64| c.iter().find(|p| (p.0 - a).abs() < 1e-9).map_or(f64::NAN, |p| p.1);
    let table = Table {
        id: "shirley1991-projected".into(),
        caption: "Mean extreme 1D discrepancy of the projections of 16 points, over 100 sets, by direction (degrees from the x axis)".into(),
        columns: ["strategy", "0 deg (x)", "45 deg", "90 deg (y)", "mean over directions", "worst direction", "its value"].map(String::from).to_vec(),
        rows: curves
            .iter()
            .map(|(name, _, c)| {
                let mean = c.iter().map(|p| p.1).sum::<f64>() / c.len() as f64;
                let worst = c.iter().copied().fold((0.0, f64::NEG_INFINITY), |w, p| if p.1 > w.1 { p } else { w });
                vec![Cell::from(*name), Cell::num(at(c, 0.0), 4), Cell::num(at(c, 45.0), 4), Cell::num(at(c, 90.0), 4), Cell::num(mean, 4), Cell::num(worst.0, 1), Cell::num(worst.1, 4)]
            })
            .collect(),
    };
    let axis = |c: &[(f64, f64)]| (at(c, 0.0) + at(c, 90.0)) / 2.0;
    let shirleys = &curves[..STRATEGIES.len()];
    let (best, best_v) = lowest(shirleys.iter().map(|(n, _, c)| (*n, axis(c))));
    let claims = vec![Claim {
        id: "separate-best-on-axes".into(),
        statement: "N-rooks (separate) sampling has the lowest discrepancy of the x and y projections of the strategies, which is why it does well with horizontal and vertical edges".into(),
        published: "section 3.1 (no number)".into(),
        ours: format!("lowest mean of the 0 and 90 degree projections: {best} {best_v:.4}"),
        theory: "N-rooks puts one point in each of the 16 slabs of each axis".into(),
        verdict: if best == "separate" { Verdict::Reproduced } else { Verdict::NotReproduced },
    }];
    let series = curves
        .iter()
        .filter(|(n, _, _)| ["separate", "jittered", "regular", "random", "sobol (Owen)", "pmj02"].contains(n))
        .map(|(n, spec, c)| Series { colour_key: Some(spec.to_string()), ..Series::line(*n, c.clone()) })
        .collect::<Vec<_>>();
    let line = LineChart {
        title: "Projected discrepancy against direction (16 points)".into(),
        x_label: "direction (degrees from the x axis)".into(),
        y_label: "mean extreme 1D discrepancy".into(),
        series: series.clone(),
        log_y: false,
        log_x: false,
        polar: false,
    };
    let polar = LineChart {
        title: "Projected discrepancy, polar (radius = discrepancy)".into(),
        x_label: String::new(),
        y_label: "discrepancy".into(),
        series,
        log_y: false,
        log_x: false,
        polar: true,
    };
    Ok(Output {
        tables: vec![table],
        figures: vec![
            Figure::render("shirley1991-projected", "Mean projected (extreme) discrepancy against direction, 100 sets of 16 points", &line, (900, 520))?,
            Figure::render("shirley1991-projected-polar", "The same in polar form: distance from the centre is the discrepancy in that direction", &polar, (760, 760))?,
        ],
        claims,
        notes: vec!["The conclusion asks whether some distributions have low projected discrepancy in many directions: the table's 'mean over directions' column answers it for these strategies, including two modern ones (Owen-scrambled Sobol' and pmj02) that the paper did not have.".into()],
    })
}

/// Tables 1-4: mean, SD and max of the absolute luminance error per pixel.
fn pixel_errors(ctx: &Ctx) -> Result<Output, Error> {
    let scenes = [("checker", "table1"), ("checker-45", "table2"), ("ball", "table3"), ("all", "table4")];
    ctx.progress.set_length((scenes.len() * (1 + STRATEGIES.len())) as u64);
    let mut out = Output::default();
    for (scene_name, table_id) in scenes {
        let scene = shadows::scene(scene_name, None)?;
        let setup = Setup {
            mode: Mode::Direct,
            footprint: Footprint::Area,
            pattern: Pattern::PerPixel,
            ..Setup::visibility(&scene, (128, 96), DiskMap::Concentric)
        };
        let reference = setup.reference(4, ctx.pick(256, 1024), ctx.seed.derive_str("reference"))?;
        ctx.progress.inc(1);
        let published = published::table("shirley1991", table_id);
        let mut rows = Vec::new();
        let mut means = Vec::new();
        for (name, spec) in STRATEGIES {
            // one strategy for every dimension the scene has: pixel, light, lens and gloss
            let e =
                Setup { pixel: spec, lens: spec, gloss: spec, ..setup }.errors(&reference, spec, 1, N, 1, ctx.seed)?;
            ctx.progress.inc(1);
            means.push((name, e.mean_abs));
            let mut row =
                vec![Cell::from(name), Cell::num(e.mean_abs, 4), Cell::num(e.sd_abs, 4), Cell::num(e.max_abs, 3)];
            row.extend(published.row(name).expect("every strategy is in the table").iter().map(|&v| Cell::num(v, 4)));
            rows.push(row);
        }
        means.sort_by(|a, b| a.1.total_cmp(&b.1));
        let order: Vec<&str> = means.iter().map(|m| m.0).collect();
        // the paper: separate best on three images, and on "all" behind regular and
        // half-jittered only; read from the published table, checked against ours
        let mean_of = |name: &str| published.row(name).expect("every strategy is in the table")[0];
        let ahead_published: Vec<&str> =
            STRATEGIES.iter().map(|s| s.0).filter(|&name| mean_of(name) < mean_of("separate")).collect();
        let ahead_ours = &order[..order.iter().position(|&name| name == "separate").expect("listed")];
        out.claims.push(Claim {
            id: format!("{scene_name}-separate-rank"),
            statement: if ahead_published.is_empty() {
                format!("{scene_name}: separate (N-rooks) sampling has the lowest average absolute error")
            } else {
                format!("{scene_name}: separate (N-rooks) sampling is outperformed only by {}", ahead_published.join(" and "))
            },
            published: format!("{}: ranking by ave|E| {}", published.source, {
                let mut p: Vec<&str> = STRATEGIES.iter().map(|s| s.0).collect();
                p.sort_by(|a, b| mean_of(a).total_cmp(&mean_of(b)));
                p.join(" < ")
            }),
            ours: format!("ranking by mean |E|: {}", order.join(" < ")),
            theory: String::new(),
            verdict: if ahead_ours.iter().all(|name| ahead_published.contains(name)) {
                Verdict::Reproduced
            } else {
                Verdict::DiffersBecause(format!("{} rank ahead of separate here; our scenes are re-creations (the paper's camera, light and ball positions are not given), and one image per strategy makes close ranks noisy", ahead_ours.join(" and ")))
            },
        });
        out.tables.push(Table {
            id: format!("shirley1991-{table_id}"),
            caption: format!("{scene_name}: absolute luminance error per pixel, ours beside {}", published.source),
            columns: [
                "strategy",
                "ave|E|",
                "SD|E|",
                "max|E|",
                "published ave|E|",
                "published SD|E|",
                "published max|E|",
            ]
            .map(String::from)
            .to_vec(),
            rows,
        });
    }
    out.notes.push("The checkerboards are self-luminous (black 0, white 1) so the error is the antialiasing error alone; the ball is lit by two square lights (direct lighting); \"all\" adds a perfect mirror, a glossy mirror (Phong exponent 60) and a thin lens focused on the ball, every dimension sampled by the strategy (the lens and gloss samples dealt to the pixel samples in random orders).".into());
    Ok(out)
}
