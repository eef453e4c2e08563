//! Spectral statistics: the direct DFT against single-frequency sums, and Subr & Kautz's
//! central claims with tolerances derived from the number of realizations.

use samplab::construct::spectrum_theory as theory;
use samplab::spectrum::{self, Method};
use samplab::{PointSet, Seed, sampler};

fn sets(spec: &str, n: usize, m: usize, seed: u64) -> Vec<PointSet> {
    sampler::generate_sets(&sampler::build(spec).unwrap(), n, 2, Seed(seed), m).unwrap()
}

#[test]
fn direct_dft_equals_the_defining_sum() {
    let p = &sets("random", 37, 1, 1)[0];
    let res = 10;
    let s = spectrum::direct_dft(p, res).unwrap();
    for (idx, c) in s.iter().enumerate() {
        let (wx, wy) = ((idx / res) as f64 - 5.0, (idx % res) as f64 - 5.0);
        let (mut re, mut im) = (0.0, 0.0);
        for q in p.iter() {
            let a = -std::f64::consts::TAU * (wx * q[0] + wy * q[1]);
            re += a.cos();
            im += a.sin();
        }
        assert!((c[0] - re / 37.0).abs() < 1e-13 && (c[1] - im / 37.0).abs() < 1e-13);
    }
}

#[test]
fn regular_and_uniform_jitter_share_a_periodogram_but_not_an_expected_spectrum() {
    let (n, m, res) = (256, 100, 64);
    let regular = spectrum::statistics(&sets("regular", n, m, 2), res, Method::default()).unwrap();
    let uniform = spectrum::statistics(&sets("jitter.uniform", n, m, 3), res, Method::Direct).unwrap();
    // a shift multiplies every S(w) by a phase: identical periodograms, set by set (the
    // regular grid's through the fast path at 1e-9, hence the tolerance)
    for (a, b) in regular.periodogram.iter().zip(&uniform.periodogram) {
        assert!((a - b).abs() < 3e-9);
    }
    // away from DC, |<S>| of uniform jitter is Monte Carlo noise: at the grid's alias
    // peaks (|S| = 1, uniform phase) its mean over m sets has modulus ~ 1/sqrt(m)
    let dc = (res / 2) * res + res / 2;
    let peak = (res / 2 + 16) * res + res / 2; // w = (16, 0), the first alias of a 16 x 16 grid
    assert!((regular.expected[peak] - 1.0).abs() < 1e-9, "regular grid's alias peak {}", regular.expected[peak]);
    assert!(uniform.expected[peak] < 4.0 / (m as f64).sqrt(), "uniform jitter at the peak: {}", uniform.expected[peak]);
    let worst = uniform.expected.iter().enumerate().filter(|(i, _)| *i != dc).map(|(_, v)| *v).fold(0.0, f64::max);
    assert!(worst < 5.0 / (m as f64).sqrt(), "uniform jitter's largest |<S>| off DC: {worst}");
    assert!((uniform.expected[dc] - 1.0).abs() < 1e-12);
}

/// Gaussian jitter of sigma = 0.1 cells on a 16 x 16 grid (absolute s = 0.1/16): the
/// second-order forms hold to x = 2 pi^2 s^2 w^2 relative, under 5% for |w| < 8. Below
/// the grid frequency the expected spectrum vanishes and the variance is (1 - phi^2)/N;
/// at the first alias peak |<S>| = phi(16).
///
/// Failure probability: below 6e-7 for each of the two sampled comparisons, 5 standard
/// errors of a single value (two-sided normal tail) where the annulus average's own error is
/// smaller still; fixed seed. Least work: not re-sized; 400 sets of 256 points put a single
/// value's relative error at 5%, so the criterion allows 25%, generous for an annulus
/// average, as the comment below says.
#[test]
fn gaussian_jitter_matches_eqs_8_and_9_at_low_frequencies() {
    let (n, m, res) = (256, 400, 64);
    let s_abs = 0.1 / 16.0;
    let st = spectrum::statistics(&sets("jitter.gaussian:sigma=0.1", n, m, 4), res, Method::default()).unwrap();
    let half = (res / 2) as f64;
    // variance, averaged over the annulus 2 <= |w| < 8: each value is a chi-square estimate
    // with 2(m-1) degrees of freedom, relative sd 1/sqrt(m-1); averaging over the annulus
    // reduces it further, so 5 single-value standard errors is generous
    let (mut measured, mut exact, mut eq9, mut count) = (0.0, 0.0, 0.0, 0.0);
    for (idx, v) in st.variance.iter().enumerate() {
        let w = ((idx / res) as f64 - half).hypot((idx % res) as f64 - half);
        if (2.0..8.0).contains(&w) {
            measured += v;
            exact += theory::gaussian_variance(w, s_abs, n);
            eq9 += theory::gaussian_variance_eq9(w, s_abs, n);
            count += 1.0;
        }
    }
    let (measured, exact, eq9) = (measured / count, exact / count, eq9 / count);
    let tol = 5.0 / ((m - 1) as f64).sqrt();
    assert!((measured / exact - 1.0).abs() < tol, "V measured {measured}, exact {exact}");
    assert!((measured / eq9 - 1.0).abs() < tol + 0.05, "V measured {measured}, eq. 9 {eq9}");
    // expected spectrum at the alias peak w = (16, 0): phi(16), noise sqrt(V/m)
    let peak = (res / 2 + 16) * res + res / 2;
    let phi = theory::gaussian_ratio(16.0, s_abs);
    let noise = (st.variance[peak] / m as f64).sqrt();
    assert!((st.expected[peak] - phi).abs() < 5.0 * noise + 1e-3, "|<S>| {} vs {phi}", st.expected[peak]);
    // at w = 16, x = 2 pi^2 s^2 w^2 = 0.197: eq. 8's second-order factor is off by about
    // x^2 / 2 = 0.02 there, outside the low-frequency range where it holds to 5%
    let x = 2.0 * std::f64::consts::PI.powi(2) * s_abs * s_abs * 256.0;
    let gap = (theory::gaussian_ratio_eq8(16.0, s_abs) - phi).abs();
    assert!(gap <= x * x / 2.0 && gap > x * x / 4.0, "gap {gap}, x {x}");
}

#[test]
fn bad_input() {
    let one = sets("random", 16, 1, 5);
    assert!(spectrum::statistics(&one, 16, Method::Direct).unwrap_err().to_string().contains("at least 2 sets"));
    let two = sets("random", 16, 2, 5);
    assert!(spectrum::statistics(&two, 15, Method::Direct).unwrap_err().to_string().contains("even"));
    assert!(
        spectrum::statistics(&two, 1 << 14, Method::Direct).unwrap_err().to_string().contains("lower the resolution")
    );
}

#[test]
fn fast_path_equals_the_direct_dft_within_its_tolerance() {
    use samplab::spectrum::nufft::Nufft;
    let cases = [
        ("random", 1, 1000, 64),
        ("random", 1, 17, 200),
        ("random", 2, 300, 32),
        ("random", 2, 1000, 64),
        ("random", 2, 64, 50),
        ("regular", 2, 256, 64),
        ("sobol", 2, 1024, 64),
        ("regular", 1, 64, 128),
    ];
    for (spec, dims, n, res) in cases {
        let p = sampler::build(spec).unwrap().generate(n, dims, Seed(n as u64)).unwrap();
        let direct = spectrum::direct_dft(&p, res).unwrap();
        for tol in [1e-3, 1e-6, 1e-9, 1e-12] {
            let fast = Nufft::new(res, dims, tol).unwrap().transform(&p).unwrap();
            let err = fast.iter().zip(&direct).map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1])).fold(0.0, f64::max);
            // |S| <= 1 (DC = 1): the error is relative to DC
            assert!(err <= tol, "{spec} {dims}D n={n} R={res} tol={tol}: max error {err}");
        }
    }
}

#[test]
fn a_plan_reused_across_sets_and_threads_gives_each_set_a_fresh_plans_bits() {
    use rayon::prelude::*;
    use samplab::spectrum::nufft::Nufft;
    for dims in [1, 2] {
        let sets: Vec<PointSet> = (0..12)
            .map(|k| sampler::build("random").unwrap().generate(50 + 40 * k, dims, Seed(k as u64)).unwrap())
            .collect();
        let fresh: Vec<Vec<[f64; 2]>> =
            sets.iter().map(|p| Nufft::new(32, dims, 1e-9).unwrap().transform(p).unwrap()).collect();
        let plan = Nufft::new(32, dims, 1e-9).unwrap();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            // every set twice, in an order that hands each buffer sets of other sizes
            let again: Vec<Vec<[f64; 2]>> = pool
                .install(|| (0..24).into_par_iter().map(|k| plan.transform(&sets[(7 * k) % 12]).unwrap()).collect());
            for (k, s) in again.iter().enumerate() {
                assert!(s == &fresh[(7 * k) % 12], "{dims}D, {threads} threads, call {k}");
            }
        }
    }
}

/// Ramamoorthi et al. 2012 section 5: uniform sampling bands at k N / (beta - 1); uniform
/// jitter and stratified sampling turn that error into noise spread over all frequencies.
///
/// Failure probability: the mean-error check is 4 standard errors of a mean over 512 pixels,
/// 6.3e-5 each (normal tail; the pixels' errors are not independent along a band, so this is
/// a guide), 3.2e-4 over the 5 blockers; the banding shares have margins measured, not
/// computed. Fixed seeds. Least work: 512 pixels of 16 samples, 5 blockers.
#[test]
fn pixel_light_banding_frequencies() {
    use samplab::spectrum::pixel_light::{self, Blocker, Pattern, Scene};
    let (n, beta, pixels) = (16, 3.0, 512);
    for blocker_seed in 1..6 {
        let scene = Scene { beta, blocker: Blocker::random(6, 0.05, beta, Seed(blocker_seed)) };
        let bands = pixel_light::banding_frequencies(n, beta, (pixels / 2) as f64);
        assert_eq!(bands[0], 8.0);
        // the share of the error energy (w >= 1) at the banding frequencies: the edges project
        // into the light over limited ranges of x, so the banding is a windowed periodic
        // signal, but nearly all of uniform sampling's error is there; noise puts about the
        // banding frequencies' own share of the spectrum there (32 of 256 here)
        let share = |pattern| {
            let a = pixel_light::analyse(&scene, pattern, pixels, n, 32, Seed(2)).unwrap();
            a.banding_share(&bands)
        };
        let (uniform, jitter, stratified) =
            (share(Pattern::Uniform), share(Pattern::UniformJitter), share(Pattern::Stratified));
        assert_eq!(uniform.1, 32.0 / 256.0);
        assert!(uniform.0 > 0.9, "blocker {blocker_seed}: uniform {uniform:?}");
        assert!(
            jitter.0 < 2.0 * jitter.1 && stratified.0 < 2.0 * stratified.1,
            "blocker {blocker_seed}: uniform jitter {jitter:?}, stratified {stratified:?}"
        );
        // the exact integral is right: the mean error of stratified sampling is near zero
        let a = pixel_light::analyse(&scene, Pattern::Stratified, pixels, n, 32, Seed(3)).unwrap();
        let mean = a.error.iter().sum::<f64>() / pixels as f64;
        let sd = (a.error.iter().map(|e| e * e).sum::<f64>() / pixels as f64).sqrt();
        assert!(mean.abs() < 4.0 * sd / (pixels as f64).sqrt(), "mean error {mean}, sd {sd}");
    }
}

#[test]
fn the_statistics_are_the_same_bits_on_one_three_and_more_threads_than_a_leafs_sets() {
    // up to BLOCK threads a node's two children go one after the other, on more side by
    // side: 70 sets are five leaves, three levels of merges
    use samplab::spectrum::tree::BLOCK;
    let given = sets("random", 300, 70, 5);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        pool.install(|| spectrum::statistics(&given, 32, Method::Fast { tol: 1e-9 }).unwrap())
    };
    let one = on(1);
    for threads in [3, BLOCK + 4] {
        let other = on(threads);
        assert!(other.periodogram == one.periodogram, "periodogram on {threads} threads");
        assert!(other.expected == one.expected, "expected on {threads} threads");
        assert!(other.variance == one.variance, "variance on {threads} threads");
    }
}

#[test]
fn the_merge_tree_gives_the_same_bits_however_the_sets_are_split_and_matches_two_pass_statistics() {
    use samplab::progress::Progress;
    use samplab::spectrum::tree::{self, Partial};
    use samplab::spectrum::{Sets, Spectra};
    let (n, m, res) = (64, 83, 16); // 6 blocks: a tree whose right edge has lone nodes
    let jitter = sampler::build("jitter").unwrap();
    let plan = jitter.plan(n, 2).unwrap();
    let given = sets("jitter", n, m, 11);
    let whole = spectrum::statistics(&given, res, Method::Direct).unwrap();
    let generated = Sets::Generated { plan: &plan, seed: Seed(11), m };
    let spectra = Spectra::new(res, 2, Method::Direct).unwrap();
    let root = tree::root_level(m);
    assert_eq!(root, 3);
    for level in 0..=root {
        // every node of a level computed on its own (as chunks on workers), through bytes
        let parts: Vec<Partial> = (0..tree::nodes_at(m, level))
            .map(|i| {
                let p = spectra.node(&generated, level, i, &Progress::SILENT).unwrap();
                Partial::from_bytes(&p.to_bytes()).unwrap()
            })
            .collect();
        let merged = tree::merge_up(parts).unwrap().finish(res, 2, n).unwrap();
        assert_eq!(merged.periodogram, whole.periodogram, "level {level}");
        assert_eq!(merged.expected, whole.expected, "level {level}");
        assert_eq!(merged.variance, whole.variance, "level {level}");
    }
    // against the textbook two-pass mean and variance of the direct spectra
    let all: Vec<Vec<[f64; 2]>> = given.iter().map(|s| spectrum::direct_dft(s, res).unwrap()).collect();
    for c in 0..res * res {
        let mean = [0, 1].map(|p| all.iter().map(|s| s[c][p]).sum::<f64>() / m as f64);
        let var =
            all.iter().map(|s| (s[c][0] - mean[0]).powi(2) + (s[c][1] - mean[1]).powi(2)).sum::<f64>() / (m - 1) as f64;
        let power = all.iter().map(|s| s[c][0] * s[c][0] + s[c][1] * s[c][1]).sum::<f64>() / m as f64;
        assert!((whole.variance[c] - var).abs() <= 1e-13 * var.max(1e-3), "{c}");
        assert!((whole.expected[c] - mean[0].hypot(mean[1])).abs() <= 1e-14);
        assert!((whole.periodogram[c] - power).abs() <= 1e-13 * power.max(1e-3));
    }
    // bytes that are not a partial are refused
    let bytes = spectra.node(&generated, 0, 0, &Progress::SILENT).unwrap().to_bytes();
    assert!(Partial::from_bytes(&bytes[..bytes.len() - 8]).is_err());
    assert!(Partial::from_bytes(&bytes[..10]).is_err());
    assert!(spectra.node(&generated, 0, 6, &Progress::SILENT).is_err(), "past the last block");
}
