//! Tables 1-4 (image errors of the test scenes), Figures 1-6, and the thesis that
//! discrepancy predicts image error.

use samplab::discrepancy::Metric;
use samplab::stats::Summary;
use samplab_render::light::DiskMap;
use samplab_render::{Footprint, Mode, Pattern};

use super::super::shadows::{self, Setup};
use super::{N, STRATEGIES, metric_values, sets_of};
use crate::criteria::{self, Decision, Estimate, Verdict};
use crate::published::{self, PublishedTable};
use crate::{Cell, Claim, Ctx, Error, Output, Table};

/// Tables 1-4: mean, SD and max of the absolute luminance error per pixel, each over
/// several seeds; Figures 1-6; and the thesis that discrepancy predicts the error.
pub(super) fn pixel_errors(ctx: &Ctx) -> Result<Output, Error> {
    let scenes = [("checker", "table1", 1), ("checker-45", "table2", 2), ("ball", "table3", 3), ("all", "table4", 4)];
    let seeds = ctx.pick(4, 8);
    ctx.set_length((scenes.len() * (1 + STRATEGIES.len()) + 1) as u64);
    let mut out = Output::default();
    // per scene, per strategy: ave|E| over the seeds
    let mut errors: Vec<Vec<Summary>> = Vec::new();
    for scene in scenes {
        errors.push(one_scene(ctx, scene, seeds, &mut out)?);
    }
    out.claims.push(thesis(ctx, &errors)?);
    ctx.advance(1)?;
    out.notes.push("The checkerboards are self-luminous (black 0, white 1) so the error is the antialiasing error alone; the ball is lit by two square lights (direct lighting); \"all\" adds a perfect mirror, a glossy mirror (Phong exponent 60) and a thin lens focused on the ball, every dimension sampled by the strategy (the lens and gloss samples dealt to the pixel samples in random orders). Errors are of the displayed images (every channel clamped to [0, 1]), as the paper's luminance errors of 8-bit images are; even so ave|E| and max|E| are not comparable with the published ones in value (the scenes are re-creations whose size and geometry the paper does not give: the -values claims), only in ranking.".into());
    Ok(out)
}

/// One scene of Tables 1-4: its reference, every strategy's errors over the seeds (ave|E|
/// returned, per strategy), its table, figures and claims.
fn one_scene(
    ctx: &Ctx,
    (scene_name, table_id, figure): (&str, &str, usize),
    seeds: u64,
    out: &mut Output,
) -> Result<Vec<Summary>, Error> {
    let scene = shadows::scene(scene_name, None)?;
    let setup = Setup {
        mode: Mode::Direct,
        footprint: Footprint::Area,
        pattern: Pattern::PerPixel,
        displayed: true,
        ..Setup::visibility(ctx.stop, &scene, (128, 96), DiskMap::Concentric)
    };
    let reference = setup.reference(4, ctx.pick(256, 1024), ctx.seed.derive_str("reference"))?;
    out.figures.push(shadows::picture(
        &format!("shirley1991-fig{figure}"),
        &format!("Figure {figure}: test scene {scene_name} (our re-creation; reference render)"),
        &reference,
    )?);
    ctx.advance(1)?;
    let published = published::table("shirley1991", table_id);
    let mut rows = Vec::new();
    let mut per = Vec::new();
    for (name, spec) in STRATEGIES {
        // one strategy for every dimension the scene has: pixel, light, lens and gloss
        let with = Setup { pixel: spec, lens: spec, gloss: spec, ..setup };
        let e = with.errors_each(&reference, spec, 1, N, seeds, ctx.seed)?;
        let field = |f: fn(&samplab_render::Errors) -> f64| Summary::of(&e.iter().map(f).collect::<Vec<_>>());
        let ave = field(|e| e.mean_abs);
        let mut row = vec![
            Cell::from(name),
            Cell::num(ave.mean, 5),
            Cell::num(ave.standard_error(), 5),
            Cell::num(field(|e| e.sd_abs).mean, 4),
            Cell::num(field(|e| e.max_abs).mean, 3),
        ];
        row.extend(published.row(name).expect("every strategy is in the table").iter().map(|&v| Cell::num(v, 4)));
        rows.push(row);
        per.push(ave);
        if scene_name == "checker-45" && (name == "regular" || name == "separate") {
            let (fig, which) = if name == "regular" { (5, "regular") } else { (6, "separate") };
            out.figures.push(shadows::picture(
                &format!("shirley1991-fig{fig}"),
                &format!("Figure {fig}: checker-45 with 16 {which} samples per pixel (seed 0 of the table)"),
                &with.render(spec, 1, N, ctx.seed.derive(0))?,
            )?);
        }
        ctx.advance(1)?;
    }
    out.claims.extend(ranking_claims(scene_name, &published, &per, seeds));
    out.claims.push(values_claim(scene_name, &published, &per));
    out.tables.push(errors_table(scene_name, table_id, seeds, &published, rows));
    Ok(per)
}

fn mean_of(published: &PublishedTable, name: &str) -> f64 {
    published.row(name).expect("every strategy is in the table")[0]
}

/// The paper: separate best on three images, and on "all" behind regular and half-jittered
/// only (read from the published table); and the whole ranking.
fn ranking_claims(scene_name: &str, published: &PublishedTable, per: &[Summary], seeds: u64) -> Vec<Claim> {
    let mut claims = Vec::new();
    let mean_of = |name: &str| mean_of(published, name);
    let index = |name: &str| STRATEGIES.iter().position(|s| s.0 == name).expect("listed");
    let sep = Estimate::mean_of(&per[index("separate")]);
    // the paper: separate best on three images, and on "all" behind regular and
    // half-jittered only; read from the published table
    let ahead: Vec<&str> = STRATEGIES.iter().map(|s| s.0).filter(|&n| mean_of(n) < mean_of("separate")).collect();
    let behind: Vec<Decision> = STRATEGIES
        .iter()
        .filter(|s| s.0 != "separate" && !ahead.contains(&s.0))
        .map(|s| criteria::less(sep, Estimate::mean_of(&per[index(s.0)])))
        .collect();
    let mut order: Vec<(&str, f64)> = STRATEGIES.iter().map(|s| s.0).zip(per.iter().map(|p| p.mean)).collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut published_order: Vec<&str> = STRATEGIES.iter().map(|s| s.0).collect();
    published_order.sort_by(|a, b| mean_of(a).total_cmp(&mean_of(b)));
    let ours_order = order.iter().map(|o| o.0).collect::<Vec<_>>().join(" < ");
    claims.push(Claim {
        id: format!("{scene_name}-separate-rank"),
        statement: if ahead.is_empty() {
            format!("{scene_name}: separate (N-rooks) sampling has the lowest average absolute error")
        } else {
            format!("{scene_name}: separate (N-rooks) sampling is outperformed only by {}", ahead.join(" and "))
        },
        published: format!("{}: ranking by ave|E| {}", published.source, published_order.join(" < ")),
        ours: format!("ranking by mean ave|E| over {seeds} seeds: {ours_order}"),
        decision: criteria::all(&behind),
        explanation: (scene_name == "ball").then(|| "on our ball the regular grid and half-jittered sampling beat separate sampling, each by many standard errors (the table): the ball's error comes from its round silhouette and the soft shadows of two square lights, edges at every angle, where N-rooks' one point per row and column gives no advantage and the grid's even spacing does; the paper's ball (geometry and lights not published) may have had more axis-aligned edges. The same ordering shows in Table 4's all scene, which contains the ball".to_string()),
        ..Claim::default()
    });
    let ours_means: Vec<f64> = per.iter().map(|p| p.mean).collect();
    let theirs: Vec<f64> = STRATEGIES.iter().map(|s| mean_of(s.0)).collect();
    let places = published_order.iter().zip(&order).filter(|(p, o)| **p != o.0).count();
    claims.push(Claim {
        id: format!("{scene_name}-order"),
        statement: format!(
            "{scene_name}: our ranking of the seven strategies by ave|E| goes with the published one beyond chance (a rank correlation, not the same order)"
        ),
        published: published_order.join(" < "),
        ours: format!("{ours_order} ({places} of 7 places differ)"),
        decision: criteria::rank_agreement(&ours_means, &theirs, 0.05),
        ..Claim::default()
    });
    claims
}

/// The values themselves: the published ave|E| is a mean over the paper's pixels with no
/// stated error; ours are means over seeds with their standard errors.
fn values_claim(scene_name: &str, published: &PublishedTable, per: &[Summary]) -> Claim {
    let mean_of = |name: &str| mean_of(published, name);
    let values: Vec<Decision> = STRATEGIES
        .iter()
        .zip(per)
        .map(|(s, p)| criteria::agrees(Estimate::mean_of(p), Estimate::exact(mean_of(s.0)), 0.5 * 10f64.powi(-4)))
        .collect();
    let ratios: Vec<f64> = STRATEGIES.iter().zip(per).map(|(s, p)| p.mean / mean_of(s.0)).collect();
    let (lo, hi) = ratios.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| (a.min(r), b.max(r)));
    Claim {
        id: format!("{scene_name}-values"),
        statement: format!("{scene_name}: our ave|E| per strategy equals the published one"),
        published: format!("{} (ave|E| column)", published.source),
        ours: format!("ours / published from {lo:.2} to {hi:.2} over the seven strategies"),
        decision: criteria::all(&values),
        explanation: Some(format!(
            "the scene is our re-creation: the paper publishes neither its geometry, nor its image size, nor its luminance scale, and the mean error per pixel scales with the share of pixels an edge crosses, so the values differ (ours / published {lo:.2}-{hi:.2} here) and only the rankings are compared (the -order and -separate-rank claims); max|E| depends on the sharpest edge and the image size likewise and is not compared"
        )),
        ..Claim::default()
    }
}

/// A scene's table, ours beside the published.
fn errors_table(
    scene_name: &str,
    table_id: &str,
    seeds: u64,
    published: &PublishedTable,
    rows: Vec<Vec<Cell>>,
) -> Table {
    Table {
        id: format!("shirley1991-{table_id}"),
        caption: format!(
            "{scene_name}: absolute luminance error per pixel of the displayed image (mean over {seeds} seeds, and the standard error of ave|E|), ours beside {}",
            published.source
        ),
        columns: [
            "strategy",
            "ave|E|",
            "SE of ave|E|",
            "SD|E|",
            "max|E|",
            "published ave|E|",
            "published SD|E|",
            "published max|E|",
        ]
        .map(String::from)
        .to_vec(),
        rows,
    }
}

/// Each strategy's error relative to the scene's mean error, averaged over the scenes.
fn error_score(per_scene: &[Vec<f64>]) -> Vec<f64> {
    let k = per_scene[0].len();
    let mut score = vec![0.0; k];
    for scene in per_scene {
        let mean = scene.iter().sum::<f64>() / k as f64;
        score.iter_mut().zip(scene).for_each(|(s, e)| *s += e / mean / per_scene.len() as f64);
    }
    score
}

/// The paper's thesis (sections 3.1 and 5): across the strategies, the discrepancies D, S
/// and T rank the strategies as their image errors do. Kendall's tau of each discrepancy's
/// mean against the error score (ave|E| over the scene's mean, averaged over Tables 1-4).
fn thesis(ctx: &Ctx, errors: &[Vec<Summary>]) -> Result<Claim, Error> {
    let metrics = [
        ("D", Metric::parse("star")?, "table5"),
        ("S", Metric::parse("l2-star")?, "table6"),
        ("T", Metric::parse("extreme")?, "table7"),
    ];
    let ours_score = error_score(&errors.iter().map(|s| s.iter().map(|x| x.mean).collect()).collect::<Vec<_>>());
    let tables = ["table1", "table2", "table3", "table4"];
    let published_score = error_score(
        &tables
            .iter()
            .map(|t| {
                let p = published::table("shirley1991", t);
                STRATEGIES.iter().map(|s| p.row(s.0).expect("published")[0]).collect()
            })
            .collect::<Vec<_>>(),
    );
    let mut decisions = Vec::new();
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    for (label, metric, table) in metrics {
        let mut means = Vec::new();
        for (i, (_, spec)) in STRATEGIES.iter().enumerate() {
            let sets = sets_of(spec, ctx.seed.derive_str("thesis").derive(i as u64))?;
            means.push(Summary::of(&metric_values(&sets, &metric)?).mean);
        }
        let d = criteria::rank_agreement(&means, &ours_score, 0.05);
        ours.push(format!("{label}: tau {:.2}", criteria::kendall_tau(&means, &ours_score)));
        let p = published::table("shirley1991", table);
        let published_means: Vec<f64> = STRATEGIES.iter().map(|s| p.row(s.0).expect("published")[0]).collect();
        let pd = criteria::rank_agreement(&published_means, &published_score, 0.05);
        theirs.push(format!(
            "{label}: tau {:.2} ({})",
            criteria::kendall_tau(&published_means, &published_score),
            if pd.verdict == Verdict::Reproduced { "significant" } else { "not significant" }
        ));
        decisions.push(d);
    }
    Ok(Claim {
        id: "discrepancy-predicts-error".into(),
        statement: "Across the seven strategies, lower discrepancy (each of D, S and T) goes with lower image error (the ordering is 'reasonably consistent with empirical behavior')".into(),
        published: format!("sections 3.1 and 5 (no statistic); the published Tables 1-7 themselves give {}", theirs.join(", ")),
        ours: format!("{} (error score: ave|E| over the scene's mean, averaged over Tables 1-4)", ours.join(", ")),
        decision: criteria::all(&decisions),
        explanation: Some("our exact T orders the seven strategies exactly as the published T does (Table 7), so the difference is in the errors: on our re-created ball and all scenes the regular grid has the lowest error (Tables 3 and 4), while T ranks it last; D and S, which rank regular fifth of seven, keep their agreement".into()),
        ..Claim::default()
    })
}
