//! Cubature to a tolerance: Student's t quantiles against published tables, the bound
//! met within the tolerance on Keister (QMCPy's example) over 50 seeds, the 99% interval's
//! coverage over 200 seeds, and the refusals.

use samplab::Seed;
use samplab::cubature::{Rule, Settings, cubature};
use samplab::integrand::Family;
use samplab::numeric::{student_t_cdf, student_t_quantile};
use samplab::progress::Progress;

#[test]
fn student_t_quantiles_match_the_tables() {
    // two-sided 95% (Fisher & Yates' table, three decimals) and 99% values
    for (df, t975) in [(1.0, 12.706), (2.0, 4.303), (5.0, 2.571), (10.0, 2.228), (30.0, 2.042)] {
        assert!((student_t_quantile(0.975, df) - t975).abs() < 5e-4, "df {df}");
    }
    assert!((student_t_quantile(0.995, 15.0) - 2.946_712_883).abs() < 1e-8);
    assert!((student_t_quantile(0.975, 1.0) - 12.706_204_736).abs() < 1e-7);
    // large df tends to the normal quantile
    assert!((student_t_quantile(0.975, 1e7) - 1.959_964).abs() < 1e-5);
    for t in [-3.0, -0.5, 0.0, 0.7, 4.0] {
        assert!((student_t_cdf(t, 7.0) + student_t_cdf(-t, 7.0) - 1.0).abs() < 1e-14);
    }
}

fn keister(d: usize) -> Box<dyn samplab::integrand::Integrand> {
    Family::parse(&format!("keister:d={d}")).unwrap().instance(Seed(0), 0).unwrap()
}

/// Failure probability: 0.065, the chance that a rule whose 99% level is exact misses more
/// than 3 of 150 independent runs (binomial). Least work: 150 runs, QMCPy's example at its
/// own tolerance in the three dimensions it documents; fewer could not tell a 99% level from
/// a 97% one at all (150 runs reject 97% with probability 0.34, 95% with 0.95). The seeds
/// are fixed, so the verdict is the same on every run.
#[test]
fn keister_to_1e_3_misses_as_rarely_as_its_level_says_over_50_seeds() {
    // QMCPy's documented example (Keister at abs_tol 1e-3) in 1, 2 and 3 dimensions: the
    // bound is probabilistic (99%), so a miss is allowed as often as the level allows (the
    // guaranteed rules below may miss never)
    let mut misses = Vec::new();
    for d in [1usize, 2, 3] {
        let f = keister(d);
        for s in 0..50 {
            let settings = Settings { abs_tol: 1e-3, seed: Seed(s), ..Settings::default() };
            let c = cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap();
            assert!(c.converged && c.bound <= 1e-3);
            if (c.estimate - f.exact()).abs() > 1e-3 {
                misses.push((d, s, c.estimate - f.exact()));
            }
        }
    }
    // at most 3 of 150 (98%): with a true 99% level, more happens with probability 0.07
    eprintln!("Keister at 1e-3: {} misses of 150: {misses:?}", misses.len());
    assert!(misses.len() <= 3, "misses: {misses:?}");
}

/// Failure probability: 0.0043, the chance that an exact 99% interval misses more than 6 of
/// 200 independent replications (binomial). Least work: 200 fixed-size cubatures of 16 x 64
/// points (a second in all), the fewest that keep that failure probability under 1% while
/// rejecting a 97% interval with probability 0.61.
#[test]
fn the_99_percent_interval_covers_in_97_to_100_percent_of_200_seeds() {
    // a fixed count (no stopping), so that the interval is the plain replicated one
    let f = Family::parse("genz.product-peak:d=4").unwrap().instance(Seed(1), 0).unwrap();
    let mut covered = 0;
    for s in 0..200 {
        let settings = Settings { abs_tol: 1e-15, min_n: Some(64), max_n: 64, seed: Seed(s), ..Settings::default() };
        let c = cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap();
        assert!(!c.converged);
        covered += usize::from((c.estimate - f.exact()).abs() <= c.bound);
    }
    eprintln!("the 99% interval covered {covered} of 200");
    assert!((194..=200).contains(&covered), "covered {covered} of 200");
}

#[test]
fn the_doubling_stops_at_the_tolerance_and_counts_its_evaluations() {
    let f = keister(3);
    let c = cubature(f.as_ref(), &Settings { abs_tol: 1e-4, ..Settings::default() }, &Progress::SILENT).unwrap();
    assert!(c.converged && c.bound <= 1e-4);
    // each step doubles n; Owen-scrambled Sobol' is a sequence, so a doubling evaluates
    // only the new points: n per randomization in all
    assert!(c.steps.windows(2).all(|w| w[1].n == 2 * w[0].n));
    assert_eq!(c.evaluations, c.n * 16);
    // the estimate made of kept and new points equals the 16 sets of n points made afresh
    let sobol = samplab::sampler::build("sobol.owen").unwrap();
    let plan = sobol.plan(c.n, 3).unwrap();
    let fresh: f64 = (0..16)
        .map(|k| {
            let points = plan.generate(Seed::DEFAULT.derive(k)).unwrap();
            let mut values = vec![0.0; c.n];
            f.eval_many(points.as_slice(), &mut values);
            values.iter().sum::<f64>() / c.n as f64
        })
        .sum::<f64>()
        / 16.0;
    assert!((c.estimate - fresh).abs() < 1e-12, "{} vs {fresh}", c.estimate);
    assert!(c.steps[..c.steps.len() - 1].iter().all(|s| s.bound > 1e-4));
}

#[test]
fn a_deterministic_sampler_and_bad_settings_are_refused() {
    let f = keister(2);
    let run = |settings: Settings| cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap_err().to_string();
    assert!(run(Settings { sampler: Some("sobol".into()), ..Settings::default() }).contains("deterministic"));
    assert!(run(Settings { abs_tol: 0.0, rel_tol: 0.0, ..Settings::default() }).contains("tolerances"));
    assert!(run(Settings { replications: 1, ..Settings::default() }).contains("replications = 1"));
    assert!(run(Settings { level: 1.0, ..Settings::default() }).contains("level = 1"));
    assert!(run(Settings { sampler: Some("sobl.owen".into()), ..Settings::default() }).contains("unknown sampler"));
}

/// Keister to 1e-3 in 1 .. `dims` dimensions with `rule`, 50 seeds each: the guaranteed
/// bound holds in every run (Keister is smooth, inside the cone), and each run converges.
///
/// Failure probability: zero for a correct rule on an integrand in its cone (the bound is
/// deterministic, not a confidence level); a miss is a defect, or Keister outside the cone.
/// Least work: the 50 seeds in each dimension are issue 97's coverage criterion ("misses at
/// most 1 in 50"; here none), in every dimension from 1 to 8 (the issue names 3 and 8; the
/// others are kept, not trimmed to save time): about 40 s of one core for each rule, spread
/// over the cores (the runs are independent; the suite's other tests end long before).
fn guaranteed_on_keister(rule: Rule, dims: usize) {
    use rayon::prelude::*;
    let runs: Vec<(usize, u64)> = (1..=dims).flat_map(|d| (0..50).map(move |s| (d, s))).collect();
    let worst = runs
        .par_iter()
        .map(|&(d, s)| {
            let f = keister(d);
            let settings = Settings { rule, abs_tol: 1e-3, max_n: 1 << 22, seed: Seed(s), ..Settings::default() };
            let c = cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap();
            let error = (c.estimate - f.exact()).abs();
            assert!(c.converged && c.bound <= 1e-3, "{rule:?} d {d} seed {s}: bound {}", c.bound);
            assert!(error <= 1e-3, "{rule:?} d {d} seed {s}: error {error} over the tolerance");
            assert!(c.kind.starts_with("guaranteed"));
            error / c.bound
        })
        .reduce(|| 0.0, f64::max);
    eprintln!(
        "{rule:?}: Keister 1..{dims}D at 1e-3, 50 seeds: every error within its bound; worst error/bound {worst:.3}"
    );
}

#[test]
#[ignore = "slow tier: 400 cubatures, about a minute"]
fn the_net_rule_meets_1e_3_on_keister_in_1_to_8_dimensions_in_every_one_of_50_seeds() {
    guaranteed_on_keister(Rule::Net, 8);
}

#[test]
#[ignore = "slow tier: 400 cubatures, about a minute"]
fn the_lattice_rule_meets_1e_3_on_keister_in_1_to_8_dimensions_in_every_one_of_50_seeds() {
    guaranteed_on_keister(Rule::Lattice, 8);
}

#[test]
fn a_spike_the_first_points_miss_fools_the_guaranteed_rule() {
    // outside the cone: a 3D Gaussian bump of width 0.02 and integral 1 (to 1e-12), which
    // 1024 points mostly miss; the rule sees a nearly flat function, so its bound is met at
    // once and is wrong (docs/guide/integrate.md shows this)
    let spike = "exp(-((x0-0.7)^2+(x1-0.3)^2+(x2-0.6)^2)/0.02^2) / (0.02*sqrt(pi))^3";
    let f = samplab::integrand::Expr::parse(spike, None).unwrap();
    let settings = Settings { rule: Rule::Net, abs_tol: 1e-2, seed: Seed(3), ..Settings::default() };
    let c = cubature(&f, &settings, &Progress::SILENT).unwrap();
    assert!(c.converged && c.bound <= 1e-2 && c.n == 1024);
    assert!((c.estimate - 1.0).abs() > 0.9, "the spike was found: {}", c.estimate);
    // so the result says what kind of bound it is: one whose cone nobody checked
    assert!(
        c.kind.starts_with("guaranteed only for integrands in the cone") && c.kind.contains("can be false"),
        "{}",
        c.kind
    );
}

#[test]
fn the_guaranteed_rules_refuse_what_they_cannot_use() {
    let f = keister(2);
    let run = |settings: Settings| cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap_err().to_string();
    let net = |sampler: &str| Settings { rule: Rule::Net, sampler: Some(sampler.into()), ..Settings::default() };
    // Owen's scrambling is not linear (no digital net), Sobol' here is in Gray-code order
    for sampler in ["net.owen", "sobol.xor", "lattice.shift", "random"] {
        assert!(run(net(sampler)).contains("needs a randomized sequence"), "{sampler}");
    }
    let lattice = Settings { rule: Rule::Lattice, sampler: Some("net.lms".into()), ..Settings::default() };
    assert!(run(lattice).contains("lattice.shift"));
    assert!(run(Settings { rule: Rule::Net, min_n: Some(1000), ..Settings::default() }).contains("power of two"));
    // a first n the user did not set is named as the rule's default
    let unset = run(Settings { rule: Rule::Net, max_n: 512, ..Settings::default() });
    assert!(unset.contains("1024 (the net rule's default)"), "{unset}");
    for rule in ["replicated", "net", "lattice"] {
        assert_eq!(Rule::parse(rule).unwrap().name(), rule);
    }
}
