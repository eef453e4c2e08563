//! Figure 6's exponents at larger N: on an integrand with edges, jitter of any fixed width
//! (Gaussian or uniform in the cell) leaves O(sqrt N) points near the edges, each with O(1)
//! variance, so the relative variance falls as N^-1.5; the -2 of smooth integrands is out of
//! reach. This experiment backs the explanation beside the not-reproduced exponents.

use samplab::experiment;

use super::super::study;
use super::{sampler_spec_matches, variance_chart};
use crate::criteria;
use crate::plot::Series;
use crate::{Cell, Claim, Ctx, Error, Figure, Output, Table};

/// Jitter and Gaussian jitter on test case I at large N.
pub(super) fn asymptotics(ctx: &Ctx) -> Result<Output, Error> {
    let ns: Vec<usize> = ctx.pick(vec![1024, 2304, 4096, 9216], vec![1024, 2304, 4096, 9216, 16384, 36864]);
    let strategies = [
        ("Jittered", "jitter"),
        ("GJittered:0.1", "jitter.gaussian:sigma=0.1"),
        ("GJittered:0.25", "jitter.gaussian:sigma=0.25"),
    ];
    let specs: Vec<&str> = strategies.iter().map(|s| s.1).collect();
    ctx.set_length((strategies.len() * ns.len() * 10) as u64);
    let rows = study(ctx, &specs, "quad", &ns, 50, 10, ctx.seed.derive_str("asymptotics"))?;
    let fits = experiment::fits(&rows);
    let fit_of = |spec: &str| fits.iter().find(|f| sampler_spec_matches(spec, &f.sampler)).expect("a fit per strategy");
    let mut series: Vec<Series> = strategies
        .iter()
        .map(|(name, spec)| Series {
            markers: true,
            colour_key: Some(spec.to_string()),
            ..Series::line(
                *name,
                rows.iter()
                    .filter(|r| sampler_spec_matches(spec, &r.sampler))
                    .map(|r| (r.n as f64, r.relative_variance))
                    .collect(),
            )
        })
        .collect();
    // the two bounds, through jitter's first point
    let (n0, v0) = series[0].points[0];
    let n1 = *ns.last().expect("counts") as f64;
    for (slope, key) in [(-1.5, "bound-edges"), (-2.0, "bound-smooth")] {
        series.push(Series {
            dashed: true,
            colour_key: Some(key.into()),
            ..Series::line(format!("N^{slope}"), vec![(n0, v0), (n1, v0 * (n1 / n0).powf(slope))])
        });
    }
    let rows_t: Vec<Vec<Cell>> = strategies
        .iter()
        .map(|(name, spec)| {
            let f = fit_of(spec);
            vec![Cell::from(*name), Cell::num(f.exponent, 3), Cell::Text(format!("[{:.3}, {:.3}]", f.ci.0, f.ci.1))]
        })
        .collect();
    let decisions: Vec<criteria::Decision> = specs.iter().map(|s| criteria::covers(fit_of(s).ci, -1.5)).collect();
    let ours = strategies
        .iter()
        .map(|(name, spec)| format!("{name} {:.3}", fit_of(spec).exponent))
        .collect::<Vec<_>>()
        .join(", ");
    let chart = variance_chart("Test case I at large N: relative variance against N".into(), series);
    Ok(Output {
        tables: vec![Table {
            id: "subr2013-asymptotics".into(),
            caption: format!("Convergence exponents on test case I over N = {ns:?} (10 instances x 50 realizations), with 95% intervals"),
            columns: ["strategy", "exponent", "95% interval"].map(String::from).to_vec(),
            rows: rows_t,
        }],
        figures: vec![Figure::render(
            "subr2013-asymptotics",
            "Figure 6's strategies at larger N on test case I, with the asymptotic slopes -1.5 (integrands with edges) and -2 (smooth) drawn through jitter's first point",
            &chart,
            (900, 560),
        )?],
        claims: vec![Claim {
            id: "edges-exponent".into(),
            statement: "On an integrand with edges, jitter and Gaussian jitter (sigma 0.1, 0.25) converge as N^-1.5 at large N".into(),
            ours: format!("exponents over N = {}..{}: {ours}", ns[0], n1),
            theory: "-1.5: about B sigma sqrt(N) points lie within the jitter's reach of an edge, each with O(1) variance".into(),
            decision: criteria::all(&decisions),
            addition: Some("samplab's analysis backing the explanation of Figure 6's Gaussian-jitter exponents; the bound is the classical one for jittered sampling of indicator functions (Mitchell 1996)".into()),
            ..Claim::default()
        }],
        notes: vec![],
    })
}
