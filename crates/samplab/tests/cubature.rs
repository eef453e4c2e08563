//! Cubature to a tolerance: Student's t quantiles against published tables, the bound
//! met within the tolerance on Keister (QMCPy's example) over 50 seeds, the 99% interval's
//! coverage over 200 seeds, and the refusals.

use samplab::Seed;
use samplab::cubature::{Settings, cubature};
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

#[test]
fn keister_to_1e_3_misses_as_rarely_as_its_level_says_over_50_seeds() {
    // QMCPy's documented example (Keister at abs_tol 1e-3) in 1, 2 and 3 dimensions: the
    // bound is probabilistic (99%), so a miss is allowed as often as the level allows; a
    // guaranteed criterion would miss never (not implemented: issue 41)
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

#[test]
fn the_99_percent_interval_covers_in_97_to_100_percent_of_200_seeds() {
    // a fixed count (no stopping), so that the interval is the plain replicated one
    let f = Family::parse("genz.product-peak:d=4").unwrap().instance(Seed(1), 0).unwrap();
    let mut covered = 0;
    for s in 0..200 {
        let settings = Settings { abs_tol: 1e-15, min_n: 64, max_n: 64, seed: Seed(s), ..Settings::default() };
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
    // each step doubles n; every step's points are counted for every randomization
    assert!(c.steps.windows(2).all(|w| w[1].n == 2 * w[0].n));
    assert_eq!(c.evaluations, c.steps.iter().map(|s| s.n * 16).sum::<usize>());
    assert!(c.steps[..c.steps.len() - 1].iter().all(|s| s.bound > 1e-4));
}

#[test]
fn a_deterministic_sampler_and_bad_settings_are_refused() {
    let f = keister(2);
    let run = |settings: Settings| cubature(f.as_ref(), &settings, &Progress::SILENT).unwrap_err().to_string();
    assert!(run(Settings { sampler: "sobol".into(), ..Settings::default() }).contains("deterministic"));
    assert!(run(Settings { abs_tol: 0.0, rel_tol: 0.0, ..Settings::default() }).contains("tolerances"));
    assert!(run(Settings { replications: 1, ..Settings::default() }).contains("replications = 1"));
    assert!(run(Settings { level: 1.0, ..Settings::default() }).contains("level = 1"));
    assert!(run(Settings { sampler: "sobl.owen".into(), ..Settings::default() }).contains("unknown sampler"));
}
