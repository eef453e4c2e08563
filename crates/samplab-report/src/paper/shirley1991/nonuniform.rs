//! Section 4: non-uniform densities (the tent warp, the disk maps, the generalized
//! discrepancy).

use samplab::discrepancy::{self, Limits, Metric};
use samplab::sampler;
use samplab::stats::Summary;
use samplab::{PointSet, warp};

use super::{N, STRATEGIES, sets_of};
use crate::criteria;
use crate::plot::Strata;
use crate::{Cell, Claim, Ctx, Error, Figure, Output, Table};

/// Section 4: the tent filter's warp (eqs. 1-2, Figure 8), the two ways to map a
/// stratified square to a disk (Figure 7), and the generalized discrepancy.
pub(super) fn nonuniform(ctx: &Ctx) -> Result<Output, Error> {
    ctx.set_length(3);
    let mut out = Output::default();
    out.claims.push(tent_claim());
    ctx.advance(1)?;
    out.figures.extend(figures(ctx)?);
    ctx.advance(1)?;
    let (table, claim) = generalized(ctx)?;
    out.tables.push(table);
    out.claims.push(claim);
    ctx.advance(1)?;
    Ok(out)
}

/// Eq. 2: the tent density's per-axis distribution function F(x) = 1/2 + x - x|x|/2.
fn tent_cdf(x: f64) -> f64 {
    0.5 + x - 0.5 * x * x.abs()
}

/// samplab's tent warp against the transformation printed in section 4, and F.
fn tent_claim() -> Claim {
    // the inverse printed in section 4
    let printed = |u: f64| if u < 0.5 { -1.0 + (2.0 * u).sqrt() } else { 1.0 - (2.0 * (1.0 - u)).sqrt() };
    let us: Vec<f64> = (0..=1000).map(|i| i as f64 / 1000.0).collect();
    let worst = us
        .iter()
        .map(|&u| (warp::tent_inverse_cdf(u) - printed(u)).abs().max((tent_cdf(warp::tent_inverse_cdf(u)) - u).abs()))
        .fold(0.0, f64::max);
    Claim {
        id: "tent-warp-inverts-eq2".into(),
        statement: "Points with the tent density (1-|x|)(1-|y|) come from canonical ones through the inverse of F(x) = 1/2 + x - x|x|/2 per axis (eq. 2), which is x = -1 + sqrt(2u) below 1/2 and 1 - sqrt(2(1-u)) above".into(),
        published: "eqs. 1-2 and the transformation of section 4".into(),
        ours: format!("largest deviation of samplab's tent warp from the printed transformation, and of F(warp(u)) from u, over 1001 u in [0, 1]: {worst:.1e}"),
        theory: "F(F^-1(u)) = u".into(),
        decision: criteria::within(worst, 0.0, 1e-12),
        derived: true,
        ..Claim::default()
    }
}

/// Figures 7 and 8: one set of 16 jittered points with its strata, warped.
fn figures(ctx: &Ctx) -> Result<Vec<Figure>, Error> {
    let jitter = sampler::build("jitter")?;
    let mut figures = Vec::new();
    let set = sampler::generate_sets(&jitter, N, 2, ctx.seed.derive_str("figures"), 1)?.remove(0);
    for (id, caption, name) in [
        (
            "shirley1991-fig7-polar",
            "Figure 7 (top): 16 jittered points and their strata through the polar map, which stretches the strata",
            "disk.polar",
        ),
        (
            "shirley1991-fig7-concentric",
            "Figure 7 (bottom): the same through the area-preserving concentric map, which keeps the strata compact",
            "disk.concentric",
        ),
        (
            "shirley1991-fig8",
            "Figure 8: the same 16 jittered points and their strata through the tent-filter transformation (section 4)",
            "tent",
        ),
    ] {
        let w = warp::lookup(name)?;
        figures.push(Figure::render(
            id,
            caption,
            &Strata { set: &set, warp: w, cells: 4, title: caption.split(':').next().unwrap_or(id).to_string() },
            (620, 620),
        )?);
    }
    Ok(figures)
}

/// The generalized discrepancy of the warped sets, by brute force over every critical
/// rectangle anchored at (-1, -1), against the star discrepancy of the original sets.
fn generalized(ctx: &Ctx) -> Result<(Table, Claim), Error> {
    let mut rows = Vec::new();
    let mut largest: f64 = 0.0;
    for (i, (name, spec)) in STRATEGIES.iter().enumerate() {
        let sets = sets_of(spec, ctx.seed.derive_str("generalized").derive(i as u64))?;
        let tent = warp::lookup("tent")?;
        let mut gap: f64 = 0.0;
        let mut values = Vec::new();
        for s in &sets {
            let star = discrepancy::compute(&Metric::parse("star")?, s, Limits::default())?;
            let general = tent_star_brute_force(&warp::apply(tent, s)?, &tent_cdf);
            gap = gap.max((star - general).abs());
            values.push(general);
        }
        largest = largest.max(gap);
        rows.push(vec![Cell::from(*name), Cell::num(Summary::of(&values).mean, 4), Cell::num(gap, 2)]);
    }
    let table = Table {
        id: "shirley1991-generalized".into(),
        caption: "Generalized star discrepancy of tent-warped sets (100 sets of 16 points per strategy; rectangles anchored at (-1, -1), the tent's mass in closed form), and the largest difference from the star discrepancy of the unwarped sets".into(),
        columns: ["strategy", "mean generalized D", "largest |generalized D - D|"].map(String::from).to_vec(),
        rows,
    };
    let claim = Claim {
        id: "generalized-equals-star".into(),
        statement: "With a separable density and the per-axis transformation, the conventional discrepancy of the original set equals the generalized discrepancy of the transformed set".into(),
        published: "section 4".into(),
        ours: format!("largest difference over 700 sets: {largest:.1e}"),
        theory: "rectangles map to rectangles and keep their points; their mass is the original area".into(),
        decision: criteria::within(largest, 0.0, 1e-12),
        derived: true,
        ..Claim::default()
    };
    Ok((table, claim))
}

/// sup over rectangles [-1, a) x [-1, b) of |n/N - mass| under the tent density (mass
/// F(a) F(b)), by brute force: a and b at every point's coordinates and at 1, counting the
/// closed and open boxes (Shirley 1991, section 4's generalized discrepancy).
fn tent_star_brute_force(set: &PointSet, f: &dyn Fn(f64) -> f64) -> f64 {
    let n = set.len() as f64;
    let mut xs: Vec<f64> = set.iter().map(|p| p[0]).chain([1.0]).collect();
    let mut ys: Vec<f64> = set.iter().map(|p| p[1]).chain([1.0]).collect();
    xs.sort_by(f64::total_cmp);
    ys.sort_by(f64::total_cmp);
    let mut worst: f64 = 0.0;
    for &a in &xs {
        for &b in &ys {
            let mass = f(a) * f(b);
            let open = set.iter().filter(|p| p[0] < a && p[1] < b).count() as f64;
            let closed = set.iter().filter(|p| p[0] <= a && p[1] <= b).count() as f64;
            worst = worst.max((open / n - mass).abs()).max((closed / n - mass).abs());
        }
    }
    worst
}
