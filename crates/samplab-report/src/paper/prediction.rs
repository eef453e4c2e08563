//! Predicted against measured: the variance [`samplab::predict`] gives from the spectra,
//! beside the variance measured, for the samplers on the papers' integrands at four
//! counts, with criteria fixed in this file before any run.

use samplab::integrand::{Family, Integrand};
use samplab::predict::{self, IntegrandSpectrum, Predicted, SmallFrequency};
use samplab::progress::Progress;
use samplab::sampler::Sampler;

use crate::criteria::{self, Decision};
use crate::plot::{LineChart, Series};
use crate::{Cell, Claim, Ctx, Error, Experiment, Figure, Output, Paper, Table};

/// The page.
pub fn paper() -> Paper {
    Paper {
        key: "prediction",
        title: "Predicted against measured",
        experiments: vec![Experiment {
            id: "variance",
            title: "Variance from the spectra, and measured",
            source: "Pilleboue et al. 2015 (variance of a shifted estimator from the spectra); the integrands of Subr & Kautz 2013 (case I, the quad) and Sbert et al. 2006 (the disk, the half-plane)",
            parameters: "integrands quad, disk, halfplane and the plane wave cosine:u=3,v=5 (instance 0 of each family for the experiment's seed); counts 16, 64, 256, 1024; 128 frequencies per axis; the spectra of random and jitter in closed form, each other sampler's from the first 16 of its sets, the variance measured over 256 sets, each moved by a uniform toroidal shift, and again unshifted; its small-frequency exponent fitted to its radial spectra at the four counts over |k| / sqrt n <= 0.25; 15 samplers (fast) or every registered 2D sampler (full)",
            run: variance,
        }],
    }
}

/// The samplers at the fast scale: one of each kind, cheap to make.
const FAST: [&str; 15] = [
    "random",
    "jitter",
    "jitter.half",
    "nrooks",
    "poisson.fast",
    "regular",
    "cmj",
    "pmj02",
    "halton.owen",
    "halton.shift",
    "sobol.owen",
    "sobol.shift",
    "lattice.shift",
    "kronecker.shift",
    "hammersley.shift",
];

const COUNTS: [usize; 4] = [16, 64, 256, 1024];
const RES: usize = 128;
const SPECTRUM_SETS: usize = 16;
/// Sets per measured variance (the optimizing samplers of the full scale make them slowly).
const MEASURED_SETS: usize = 256;
/// The plane wave: periodic, its two frequencies inside the window.
const PERIODIC: &str = "cosine:u=3,v=5";
const INTEGRANDS: [&str; 4] = ["quad", "disk", "halfplane", PERIODIC];

/// One (integrand, sampler, n).
struct Row {
    integrand: usize,
    sampler: String,
    n: usize,
    predicted: Predicted,
    shifted: Predicted,
    unshifted: Predicted,
}

impl Row {
    /// |predicted - measured (shifted)| in combined standard errors.
    fn z(&self) -> f64 {
        let se = self.predicted.se.hypot(self.shifted.se);
        let gap = (self.predicted.variance - self.shifted.variance).abs();
        // an estimate that is exact (a lattice on a plane wave it does not alias) is 0 on
        // both sides, but for rounding
        if gap <= 1e-15 * self.shifted.variance.max(self.predicted.variance) + 1e-28 { 0.0 } else { gap / se }
    }
}

fn variance(ctx: &Ctx) -> Result<Output, Error> {
    let samplers: Vec<Sampler> = match ctx.scale {
        crate::Scale::Fast => FAST.iter().map(|s| samplab::sampler::build(s)).collect::<Result<_, _>>()?,
        crate::Scale::Full => predict::every_sampler(2),
    };
    let integrands: Vec<(String, Box<dyn Integrand>)> = INTEGRANDS
        .iter()
        .map(|spec| {
            let family = Family::parse(spec)?;
            Ok((family.spec(), family.instance(ctx.seed, 0)?))
        })
        .collect::<Result<_, samplab::Error>>()?;
    let spectra: Vec<IntegrandSpectrum> =
        integrands.iter().map(|(_, f)| predict::integrand_spectrum(f.as_ref(), RES)).collect::<Result<_, _>>()?;
    ctx.set_length((samplers.len() * COUNTS.len()) as u64);
    let (mut rows, mut skipped, mut rates) = (Vec::new(), Vec::new(), Vec::new());
    for (k, s) in samplers.iter().enumerate() {
        if let Some(e) = COUNTS.iter().find_map(|&n| s.plan(n, 2).err()) {
            skipped.push(format!("{}: {e}", s.spec()));
            ctx.advance(COUNTS.len() as u64)?;
            continue;
        }
        let mut spectra_of_s = Vec::new();
        for n in COUNTS {
            let seed = ctx.seed.derive(k as u64).derive(n as u64);
            let stop = Progress::until(ctx.stop);
            let sets = s.plan(n, 2)?.generate_sets(seed, MEASURED_SETS, &stop)?;
            let spectrum = match predict::closed_form(s.spec(), n, 2, RES) {
                Some(closed) => closed,
                None => predict::spectrum_of_sets(s.spec(), &sets[..SPECTRUM_SETS], RES, &stop)?,
            };
            for (i, (_, f)) in integrands.iter().enumerate() {
                rows.push(Row {
                    integrand: i,
                    sampler: s.spec().to_string(),
                    n,
                    predicted: predict::predict(&spectra[i], &spectrum)?,
                    shifted: predict::measure_sets(f.as_ref(), &sets, seed, true, &stop)?,
                    unshifted: predict::measure_sets(f.as_ref(), &sets, seed, false, &stop)?,
                });
            }
            spectra_of_s.push(spectrum);
            ctx.advance(1)?;
        }
        rates.push((s.spec().to_string(), predict::small_frequency(&spectra_of_s.iter().collect::<Vec<_>>())));
    }
    let names: Vec<&str> = integrands.iter().map(|(name, _)| name.as_str()).collect();
    let mut claims = vec![exact_claim(&rows, INTEGRANDS.len() - 1, &names)];
    claims.extend(approximate_claims(&rows, &names));
    claims.push(jitter_disk_claim(&rows));
    let mut notes = vec![
        "Predicted: (1/n) [Var(f) + sum over the 128 x 128 window of |F(k)|^2 (P(k) - 1)], the variance of the estimator over a uniform toroidal shift; exact for shifted sets when P = 1 outside the window. The spectra of random and jitter are closed forms; the others are the mean periodogram of 16 sets, with a standard error from 8 batches.".to_string(),
    ];
    if !skipped.is_empty() {
        notes.push(format!("Left out (a count they cannot make): {}.", skipped.join("; ")));
    }
    Ok(Output {
        tables: vec![table(&rows, &names), exponents(&rows, &names), rate_table(&rows, &rates)],
        figures: vec![scatter(&rows, &names)?],
        claims,
        notes,
    })
}

/// "For shifted sets on a periodic integrand whose frequencies the window holds, the
/// prediction is exact": at most 5% of rows beyond 3 standard errors, none beyond 5.
fn exact_claim(rows: &[Row], periodic: usize, names: &[&str]) -> Claim {
    let z: Vec<f64> = rows.iter().filter(|r| r.integrand == periodic).map(Row::z).collect();
    Claim {
        id: "exact-periodic".into(),
        statement: format!("for shifted sets of every sampler on the plane wave {}, the predicted variance is the measured one", names[periodic]),
        published: "Pilleboue et al. 2015: the variance of a homogenized (randomly shifted) estimator is the integrand's power spectrum weighted by the sampler's".into(),
        ours: format!("{} rows; {} beyond 3 standard errors, worst {:.2}", z.len(), z.iter().filter(|&&z| z > 3.0).count(), z.iter().copied().fold(0.0, f64::max)),
        decision: agreement(&z, 0.05),
        addition: Some("samplab's test of its own prediction".into()),
        ..Claim::default()
    }
}

/// "The prediction holds for shifted sets on the discontinuous integrands too": at most
/// 10% of rows beyond 3 standard errors, none beyond 5 (the window leaves out frequencies,
/// so this is the approximation's test).
fn approximate_claims(rows: &[Row], names: &[&str]) -> Vec<Claim> {
    (0..names.len() - 1)
        .map(|i| {
            let z: Vec<f64> = rows.iter().filter(|r| r.integrand == i).map(Row::z).collect();
            Claim {
                id: format!("window-{}", names[i].split(':').next().unwrap_or(names[i])),
                statement: format!("for shifted sets on {}, the windowed prediction is the measured variance", names[i]),
                published: "Pilleboue et al. 2015 (the sum over every frequency; samplab sums a window of 128 per axis)".into(),
                ours: format!(
                    "{} rows; {} beyond 3 standard errors, worst {:.2}",
                    z.len(),
                    z.iter().filter(|&&z| z > 3.0).count(),
                    z.iter().copied().fold(0.0, f64::max)
                ),
                decision: agreement(&z, 0.1),
                addition: Some("samplab's test of its own approximation".into()),
                ..Claim::default()
            }
        })
        .map(|c| {
            let explanation = (c.decision.verdict != crate::Verdict::Reproduced).then(|| WINDOW.to_string());
            Claim { explanation, ..c }
        })
        .collect()
}

/// Why the windowed prediction misses on straight edges, with the evidence.
const WINDOW: &str = "The rows beyond 3 standard errors (the table prediction-variance) are at n = 256 and 1024, where the sets' spectra differ from 1 beyond the 128-frequency window, which the prediction counts as 1; a straight edge keeps |F(k)|^2 falling only as |k|^-2 along its normal, so the terms left out are large. Two kinds of set. Lattice-like sets (lattices, Kronecker, shifted Sobol', a regular grid): their periodogram is n at the points of their dual lattice and near 0 between, and the first dual points lie outside the window at these counts. Owen-scrambled nets (halton.owen, sobol.owen), which are not lattices: their one-dimensional projections are stratified into n intervals, so their periodogram stays well below 1 along the axes out to |k| of about n, past the window, and the prediction overestimates. Widening the window moves the prediction to the measurement: `samplab predict --integrand halfplane:angle=30,x=0.4,y=0.5 --sampler lattice.shift -n 1024 --sets 8 --measure 2000 --shift` gives predicted / measured 2.30 at --res 128, 1.53 at 256 and 1.14 at 512 (sobol.shift 1.35, 1.15, 1.06; 2026-11-27); with --sampler sobol.owen 1.15, 1.05, 1.01 and halton.owen 1.16 at 128, 1.06 at 512 (2026-12-06).";

/// Reproduced when at most `share` of the rows are beyond 3 standard errors and none
/// beyond 5.
fn agreement(z: &[f64], share: f64) -> Decision {
    let beyond = z.iter().filter(|&&z| z > 3.0).count();
    let worst = z.iter().copied().fold(0.0, f64::max);
    criteria::exactly(
        !z.is_empty() && beyond as f64 <= share * z.len() as f64 && worst <= 5.0,
        &format!(
            "{beyond} of {} rows beyond 3 standard errors (at most {:.0}%), worst {worst:.2} (at most 5)",
            z.len(),
            100.0 * share
        ),
    )
}

/// "Within 20% for jittered sampling on the disk at n >= 64", unshifted (as `integrate`
/// uses it): the example of an approximation.
fn jitter_disk_claim(rows: &[Row]) -> Claim {
    let ratios: Vec<(usize, f64)> = rows
        .iter()
        .filter(|r| r.integrand == 1 && r.sampler == "jitter" && r.n >= 64)
        .map(|r| (r.n, r.predicted.variance / r.unshifted.variance))
        .collect();
    let ok = !ratios.is_empty() && ratios.iter().all(|(_, q)| (q - 1.0).abs() <= 0.2);
    let list = ratios.iter().map(|(n, q)| format!("{q:.3} at n = {n}")).collect::<Vec<_>>().join(", ");
    Claim {
        id: "jitter-disk".into(),
        statement: "jittered sampling of the disk, used unshifted: the predicted variance within 20% of the measured one at n >= 64".into(),
        published: "Pilleboue et al. 2015 (the shifted estimator); the unshifted one is samplab's question".into(),
        ours: format!("predicted / measured: {list}"),
        decision: criteria::exactly(ok, &format!("every ratio within [0.8, 1.2]: {list}")),
        addition: Some("issue 40's criterion".into()),
        ..Claim::default()
    }
}

fn table(rows: &[Row], names: &[&str]) -> Table {
    Table {
        id: "prediction-variance".into(),
        caption: "Predicted and measured variance per integrand, sampler and n: the measured one over shifted sets (where the prediction is exact up to the window) and over the same sets unshifted".into(),
        columns: ["integrand", "sampler", "n", "predicted", "+- SE", "measured, shifted", "+- SE", "z", "measured, unshifted"]
            .map(String::from)
            .to_vec(),
        rows: rows
            .iter()
            .map(|r| {
                vec![
                    Cell::Text(names[r.integrand].into()),
                    Cell::Text(r.sampler.clone()),
                    Cell::num(r.n as f64, 0),
                    Cell::Text(format!("{:.4e}", r.predicted.variance)),
                    Cell::Text(format!("{:.1e}", r.predicted.se)),
                    Cell::Text(format!("{:.4e}", r.shifted.variance)),
                    Cell::Text(format!("{:.1e}", r.shifted.se)),
                    Cell::num(r.z(), 2),
                    Cell::Text(format!("{:.4e}", r.unshifted.variance)),
                ]
            })
            .collect(),
    }
}

/// The exponents: slopes of log variance against log n, predicted and measured (shifted).
fn exponents(rows: &[Row], names: &[&str]) -> Table {
    let mut samplers: Vec<&str> = rows.iter().map(|r| r.sampler.as_str()).collect();
    samplers.dedup();
    let slope = |i: usize, s: &str, value: &dyn Fn(&Row) -> f64| {
        let points: Vec<(f64, f64)> =
            rows.iter().filter(|r| r.integrand == i && r.sampler == s).map(|r| (r.n as f64, value(r))).collect();
        samplab::experiment::loglog_fit(&points).map_or(Cell::Text("-".into()), |(e, _)| Cell::num(e, 3))
    };
    let mut columns = vec!["sampler".to_string()];
    for name in &names[..names.len() - 1] {
        columns.push(format!("{name}: predicted"));
        columns.push(format!("{name}: measured"));
    }
    Table {
        id: "prediction-exponents".into(),
        caption: "Convergence exponents: the slope of log variance against log n over 16-1024, predicted and measured (shifted sets), on the discontinuous integrands".into(),
        columns,
        rows: samplers
            .iter()
            .map(|s| {
                let mut row = vec![Cell::Text(s.to_string())];
                for i in 0..names.len() - 1 {
                    row.push(slope(i, s, &|r| r.predicted.variance));
                    row.push(slope(i, s, &|r| r.shifted.variance));
                }
                row
            })
            .collect(),
    }
}

/// A measured variance below this is rounding (the integrands are of order 1).
const ROUNDING: f64 = 1e-24;

/// Each sampler's small-frequency exponent, the best- and worst-case exponents it implies,
/// and the slopes measured (shifted sets) on the plane wave (band-limited: the best case)
/// and the disk (a jump along a curve: the worst case) between the two largest counts.
fn rate_table(rows: &[Row], rates: &[(String, Option<SmallFrequency>)]) -> Table {
    let (periodic, disk) = (INTEGRANDS.len() - 1, 1);
    let [.., below, top] = COUNTS;
    let measured = |i: usize, s: &str| {
        let at =
            |n: usize| rows.iter().find(|r| r.integrand == i && r.sampler == s && r.n == n).map(|r| r.shifted.variance);
        match (at(below), at(top)) {
            // a set that integrates the plane wave exactly leaves only rounding
            (Some(a), Some(b)) if a.max(b) < ROUNDING => Cell::Text("exact".into()),
            (Some(a), Some(b)) if a > 0.0 && b > 0.0 => Cell::num((b / a).ln() / (top as f64 / below as f64).ln(), 3),
            _ => Cell::Text("-".into()),
        }
    };
    let optional = |v: Option<f64>, none: &str| v.map_or(Cell::Text(none.into()), |v| Cell::num(v, 3));
    Table {
        id: "prediction-rates".into(),
        caption: format!(
            "Convergence rates from the spectrum (Pilleboue et al. 2015's analysis): beta and c of P(k) ~ c (|k| / sqrt n)^beta fitted over |k| / sqrt n <= {} at every count, the variance exponents they imply, -1 - beta/2 on a band-limited integrand (best) and -1 - min(beta, 1)/2 with a jump along a smooth curve (worst; 'zero': P vanishes there, a zero region, best faster than any power; 'exact': the measured variances are rounding), beside the slopes measured on shifted sets between n = {below} and {top} on {} (band-limited) and the disk",
            predict::SMALL_FREQUENCY_REACH,
            INTEGRANDS[periodic]
        ),
        columns: [
            "sampler",
            "beta",
            "c",
            "best, predicted",
            "plane wave, measured",
            "worst, predicted",
            "disk, measured",
        ]
        .map(String::from)
        .to_vec(),
        rows: rates
            .iter()
            .map(|(s, fit)| {
                let (beta, c, best, worst) = match fit {
                    Some(f) => (
                        optional(f.exponent, "zero"),
                        optional(f.constant, "-"),
                        optional(f.best, "-inf"),
                        Cell::num(f.worst, 3),
                    ),
                    None => {
                        (Cell::Text("-".into()), Cell::Text("-".into()), Cell::Text("-".into()), Cell::Text("-".into()))
                    }
                };
                vec![Cell::Text(s.clone()), beta, c, best, measured(periodic, s), worst, measured(disk, s)]
            })
            .collect(),
    }
}

fn scatter(rows: &[Row], names: &[&str]) -> Result<Figure, Error> {
    let mut series: Vec<Series> = names
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let mut points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.integrand == i && r.predicted.variance > 0.0 && r.shifted.variance > 0.0)
                .map(|r| (r.predicted.variance, r.shifted.variance))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            // one colour per integrand (series named by integrand share the hash's colours)
            let key = ["random", "jitter", "sobol", "poisson"][i % 4].to_string();
            Series { markers: true, colour_key: Some(key), ..Series::line(name.to_string(), points) }
        })
        .collect();
    let all: Vec<f64> = series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
    let (lo, hi) = all.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    if lo < hi {
        series.push(Series { dashed: true, ..Series::line("measured = predicted", vec![(lo, lo), (hi, hi)]) });
    }
    let chart = LineChart {
        title: "Measured (shifted sets) against predicted variance".into(),
        x_label: "predicted variance".into(),
        y_label: "measured variance".into(),
        series,
        log_y: true,
        log_x: true,
        polar: false,
    };
    Figure::render(
        "prediction-scatter",
        "Every (sampler, n) per integrand, measured against predicted variance on log axes; points of one integrand joined in order of predicted variance; the dashed line is equality",
        &chart,
        (900, 650),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Verdict;

    fn row(integrand: usize, n: usize, predicted: f64, measured: f64, se: f64) -> Row {
        let p = Predicted { variance: predicted, se: 0.0 };
        let m = Predicted { variance: measured, se };
        Row { integrand, sampler: "jitter".into(), n, predicted: p, shifted: m, unshifted: m }
    }

    #[test]
    fn the_criteria_can_fail() {
        assert_eq!(agreement(&[0.5, 1.0, 2.9], 0.05).verdict, Verdict::Reproduced);
        assert_eq!(agreement(&[0.5, 3.5], 0.05).verdict, Verdict::NotReproduced);
        assert_eq!(agreement(&[0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 5.5], 0.1).verdict, Verdict::NotReproduced);
        let good = [row(1, 64, 1.0, 1.1, 0.01), row(1, 256, 1.0, 0.9, 0.01)];
        assert_eq!(jitter_disk_claim(&good).decision.verdict, Verdict::Reproduced);
        let bad = [row(1, 64, 1.0, 1.3, 0.01)];
        assert_eq!(jitter_disk_claim(&bad).decision.verdict, Verdict::NotReproduced);
        assert_eq!(row(0, 16, 1.0, 1.0 + 1e-17, 0.0).z(), 0.0);
        assert!((row(0, 16, 1.0, 1.3, 0.1).z() - 3.0).abs() < 1e-12);
    }
}
