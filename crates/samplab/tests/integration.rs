//! Integrands and the estimator harness: exact integrals against brute-force quadrature
//! of the same instance, and the papers' closed forms with statistical tolerances derived
//! from the number of trials (fixed seeds).

use samplab::experiment::{self, Row, Study};
use samplab::integrand::{Dims, Family, INTEGRANDS};
use samplab::progress::Progress;
use samplab::{Sampler, Seed, sampler};

/// Midpoint rule on a k^d grid.
fn midpoint(f: &dyn samplab::integrand::Integrand, k: usize) -> f64 {
    let h = 1.0 / k as f64;
    if f.dims() == 1 {
        return (0..k).map(|i| f.eval(&[(i as f64 + 0.5) * h])).sum::<f64>() * h;
    }
    let mut s = 0.0;
    for i in 0..k {
        for j in 0..k {
            s += f.eval(&[(i as f64 + 0.5) * h, (j as f64 + 0.5) * h]);
        }
    }
    s * h * h
}

#[test]
fn exact_integrals_equal_brute_force_quadrature() {
    for e in INTEGRANDS.iter() {
        // the d-dimensional families have their own rules, split at their kinks and jumps
        // (tests/integrands_d.rs): a midpoint rule across a jump errs by more than 1e-4
        if !matches!(e.dims, Dims::Fixed(1 | 2)) {
            continue;
        }
        let family = Family::parse(e.about.name).unwrap();
        for k in 0..4 {
            let f = family.instance(Seed(11), k).unwrap();
            let (grid, tol) = if f.dims() == 1 { (2_000_000, 2e-6) } else { (2000, 1e-4) };
            let q = midpoint(f.as_ref(), grid);
            assert!(
                (f.exact() - q).abs() < tol,
                "{} instance {k}: exact {} vs quadrature {q}",
                e.about.name,
                f.exact()
            );
        }
    }
    // fixed parameters too
    for spec in [
        "zoneplate:a=1000",
        "cosine:u=16,v=0,phase=0",
        "cosine:u=0,v=0,phase=1",
        "disk:r=0.45,cx=0.5,cy=0.5",
        "gaussian:sigma=0.05",
        "steps:k=20",
        "halfplane:angle=30,x=0.2,y=0.9",
    ] {
        let f = Family::parse(spec).unwrap().instance(Seed(3), 0).unwrap();
        let (grid, tol) = if f.dims() == 1 { (2_000_000, 2e-6) } else { (3000, 1e-4) };
        assert!((f.exact() - midpoint(f.as_ref(), grid)).abs() < tol, "{spec}");
    }
}

#[test]
fn delaunay_piecewise_functions_are_continuous_or_constant_where_expected() {
    // test case III is continuous: values on both sides of any point agree closely
    let f = Family::parse("delaunay-linear").unwrap().instance(Seed(5), 0).unwrap();
    for i in 1..200 {
        let x = [i as f64 / 200.0, 0.37];
        let (a, b) = (f.eval(&x), f.eval(&[x[0] + 1e-9, x[1]]));
        assert!((a - b).abs() < 1e-6, "jump at {x:?}");
    }
}

fn study(samplers: &[&str], integrand: &str, ns: &[usize], sets: usize, instances: usize, seed: u64) -> Vec<Row> {
    let s: Vec<Sampler> = samplers.iter().map(|x| sampler::build(x).unwrap()).collect();
    let family = Family::parse(integrand).unwrap();
    experiment::run(
        &Study { samplers: &s, family: (&family).into(), ns, sets, instances, seed: Seed(seed) },
        &Progress::SILENT,
    )
    .unwrap()
}

/// Failure probability: 6.3e-5, a deviation of 4 relative standard errors of a sample
/// variance over 4000 realizations (two-sided normal tail; a random estimator of an
/// indicator at n = 64 is close to normal). Fixed seed. Least work: the criterion scales with
/// the realizations' standard error, so their number buys power, not a lower failure
/// probability; 4000 put 4 standard errors at 9% of the variance.
#[test]
fn random_sampling_of_an_indicator_matches_p_one_minus_p_over_n() {
    // one fixed disk, M = 4000 realizations: the sample variance has relative standard
    // error sqrt(2/(M-1)) = 2.2%; allow 4 of them
    let rows = study(&["random"], "disk:r=0.3,cx=0.5,cy=0.5", &[64], 4000, 1, 1);
    let t = rows[0].theory.as_ref().unwrap();
    assert_eq!(t.statistic, "relative_variance");
    let rel = rows[0].relative_variance / t.value;
    assert!((rel - 1.0).abs() < 4.0 * (2.0f64 / 3999.0).sqrt(), "measured / theory = {rel}");
}

#[test]
fn convergence_exponents_of_jitter_and_random() {
    let ns = [16, 64, 256, 1024, 4096, 16384];
    for integrand in ["disk", "quad"] {
        let rows = study(&["jitter", "random"], integrand, &ns, 60, 10, 2);
        let fits = experiment::fits(&rows);
        let get = |s: &str| fits.iter().find(|f| f.sampler == s).unwrap().exponent;
        assert!((get("jitter") + 1.5).abs() < 0.1, "{integrand}: jitter {}", get("jitter"));
        assert!((get("random") + 1.0).abs() < 0.05, "{integrand}: random {}", get("random"));
    }
}

#[test]
fn systematic_sampling_of_disks_follows_k_b_u_cubed() {
    // averaged over random centres and radii (the law holds on average: Sbert et al.)
    let rows = study(&["jitter.uniform"], "disk", &[4096], 16, 400, 3);
    let t = rows[0].theory.as_ref().unwrap();
    let ratio = rows[0].relative_variance / t.value;
    assert!((ratio - 1.0).abs() < 0.10, "Var / (k B u^3) = {ratio} x 0.0724");
}

/// Failure probability: N^2 MSE over 4000 instances has a standard error under 2% of its
/// mean, so 5% is over 2.5 standard errors: at most 1.2% for each of the 6 comparisons
/// (two-sided normal tail), about 7% for the test were they independent; fixed seeds, so
/// the verdict is the same on every run. Least work: not re-sized yet (the margin is the
/// thinnest of this file's statistical tests).
#[test]
fn ramamoorthi_normalized_variances() {
    // N = 256, 4000 instances: N^2 MSE has a standard error under 2% of its mean
    for (integrand, expect) in
        [("step", [1.0 / 12.0, 1.0 / 6.0, 1.0 / 6.0]), ("box", [1.0 / 6.0, 1.0 / 3.0, 1.0 / 6.0])]
    {
        let rows = study(&["regular", "jitter", "jitter.uniform"], integrand, &[256], 2, 4000, 4);
        for (row, want) in rows.iter().zip(expect) {
            assert!(
                (row.normalized_mse / want - 1.0).abs() < 0.05,
                "{integrand} {}: {} vs {want}",
                row.sampler,
                row.normalized_mse
            );
            assert!((row.theory.as_ref().unwrap().value - want).abs() < 1e-12);
        }
    }
}

/// The standard errors a row states (of the relative mean, the relative variance and N^2
/// MSE) are the spreads the numbers actually have: 100 studies of 50 instances each (of
/// one fixed disk, so that mean / exact is bounded) under independent seeds, whose values
/// scatter with standard deviations that must match the
/// rows' mean stated standard errors.
///
/// Failure probability: under 3e-3 for the three together. Each study's value is a mean
/// over 50 instances (close to normal), so the sample standard deviation of the 100 values
/// has a relative standard error of about sqrt(1 / 198) = 7%; the band [0.75, 1.3] is 3.5 of
/// them below and 4.2 above (the stated errors, averaged over 100 studies, vary far less).
/// Fixed seeds. Least work: 100 studies keep the band narrow enough to catch a missing
/// sqrt(2) or a divisor of instances instead of its root (factors 0.71 and 7).
#[test]
fn the_stated_standard_errors_are_the_spreads_over_seeds() {
    let rows: Vec<Row> =
        (0..100).map(|s| study(&["random"], "disk:r=0.3,cx=0.5,cy=0.5", &[16], 2, 50, 1000 + s).remove(0)).collect();
    // a statistic of a row and its stated standard error
    type Stated = fn(&Row) -> (f64, f64);
    let stats: [(&str, Stated); 3] = [
        ("relative mean", |r| (r.relative_mean, r.relative_mean_se)),
        ("relative variance", |r| (r.relative_variance, r.relative_variance_se)),
        ("N^2 MSE", |r| (r.normalized_mse, r.normalized_mse_se)),
    ];
    for (what, of) in stats {
        let values: Vec<f64> = rows.iter().map(|r| of(r).0).collect();
        let mean = values.iter().sum::<f64>() / values.len() as f64;
        let spread = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (values.len() - 1) as f64).sqrt();
        let stated = rows.iter().map(|r| of(r).1).sum::<f64>() / rows.len() as f64;
        let ratio = spread / stated;
        assert!((0.75..1.3).contains(&ratio), "{what}: spread over seeds / stated standard error = {ratio}");
    }
    // one instance has no spread to state
    let one = study(&["random"], "step", &[16], 2, 1, 7).remove(0);
    assert!(one.relative_mean_se.is_nan() && one.relative_variance_se.is_nan() && one.normalized_mse_se.is_nan());
}

#[test]
fn bad_studies_are_errors() {
    let s: Vec<Sampler> = vec![sampler::build("jitter").unwrap()];
    let family = Family::parse("quad").unwrap();
    let run = |ns: &[usize], sets: usize| {
        experiment::run(
            &Study { samplers: &s, family: (&family).into(), ns, sets, instances: 2, seed: Seed(1) },
            &Progress::SILENT,
        )
    };
    assert!(run(&[15], 10).unwrap_err().to_string().contains("9 and 16"));
    assert!(run(&[16], 1).unwrap_err().to_string().contains("at least 2"));
    assert!(Family::parse("quadd").unwrap_err().to_string().contains("quad"));
    assert!(Family::parse("disk:r=0.9").unwrap_err().to_string().contains("'r'"));
    assert!(Family::parse("disk:r=0.3,cx=0.1").unwrap().instance(Seed(1), 0).is_err());
}

#[test]
fn a_study_computed_unit_by_unit_through_bytes_equals_the_whole_run() {
    let s: Vec<Sampler> = ["random", "jitter"].iter().map(|x| sampler::build(x).unwrap()).collect();
    let family = Family::parse("disk").unwrap();
    let study = Study { samplers: &s, family: (&family).into(), ns: &[16, 64], sets: 20, instances: 3, seed: Seed(4) };
    let whole = experiment::run(&study, &Progress::SILENT).unwrap();
    let prepared = study.prepare().unwrap();
    assert_eq!(prepared.units(), 12);
    // units in reverse order (as workers might finish), each through its bytes
    let mut units: Vec<(usize, experiment::UnitStats)> = (0..12)
        .rev()
        .map(|u| {
            let bytes = prepared.unit(u, &Progress::SILENT).unwrap().to_bytes();
            (u, experiment::UnitStats::from_bytes(&bytes).unwrap())
        })
        .collect();
    units.sort_by_key(|(u, _)| *u);
    let rows = prepared.rows(&units.into_iter().map(|(_, s)| s).collect::<Vec<_>>()).unwrap();
    assert_eq!(serde_json::to_string(&rows).unwrap(), serde_json::to_string(&whole).unwrap());
    assert!(prepared.unit(12, &Progress::SILENT).is_err());
    assert!(prepared.rows(&[]).is_err());
}
