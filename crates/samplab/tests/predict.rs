//! The predicted variance (`samplab::predict`) against measurement and against an
//! independent brute-force computation of the same quantity.

use samplab::integrand::{Family, Integrand};
use samplab::numeric::quadrature::gauss_legendre;
use samplab::predict::{self, IntegrandSpectrum, Predicted};
use samplab::progress::Progress;
use samplab::{Seed, sampler};

const SILENT: &Progress = &Progress::SILENT;

fn instance(spec: &str) -> Box<dyn Integrand> {
    Family::parse(spec).unwrap().instance(Seed(11), 0).unwrap()
}

fn predicted(spec: &str, f: &IntegrandSpectrum, n: usize, sets: usize) -> Predicted {
    let s = sampler::build(spec).unwrap();
    let spectrum = predict::sampler_spectrum(&s, n, f.dims, f.res, sets, Seed(5), SILENT).unwrap();
    predict::predict(f, &spectrum).unwrap()
}

/// A trigonometric polynomial: 1 + sum of a_j cos(2 pi k_j.x + phi_j), written here with
/// its own coefficients.
struct Trig(Vec<([i64; 2], f64, f64)>);

impl Integrand for Trig {
    fn dims(&self) -> usize {
        2
    }
    fn eval(&self, x: &[f64]) -> f64 {
        1.0 + self
            .0
            .iter()
            .map(|&(k, a, phi)| a * (std::f64::consts::TAU * (k[0] as f64 * x[0] + k[1] as f64 * x[1]) + phi).cos())
            .sum::<f64>()
    }
    fn exact(&self) -> f64 {
        1.0
    }
    fn fourier(&self, k: [i64; 2]) -> Option<[f64; 2]> {
        if k == [0, 0] {
            return Some([1.0, 0.0]);
        }
        let mut c = [0.0, 0.0];
        for &(q, a, phi) in &self.0 {
            if q == k {
                c[0] += a / 2.0 * phi.cos();
                c[1] += a / 2.0 * phi.sin();
            } else if q == [-k[0], -k[1]] {
                c[0] += a / 2.0 * phi.cos();
                c[1] -= a / 2.0 * phi.sin();
            }
        }
        Some(c)
    }
    fn exact_square(&self) -> Option<f64> {
        Some(1.0 + self.0.iter().map(|(_, a, _)| a * a / 2.0).sum::<f64>())
    }
}

fn trig() -> Trig {
    Trig(vec![([3, 1], 0.5, 0.3), ([0, 7], 0.25, 1.1), ([5, -4], 0.4, 2.0), ([1, 0], 0.2, 0.7)])
}

/// The variance over toroidal shifts u of (1/n) sum f(x_j + u), by the equispaced rule on
/// a g x g grid of shifts: exact for a trigonometric polynomial of degree below g / 2 in
/// each axis (the squared error has degree below g).
fn brute_force(f: &dyn Integrand, points: &[f64], g: usize) -> f64 {
    let n = points.len() / 2;
    let mut total = 0.0;
    for a in 0..g {
        for b in 0..g {
            let u = [a as f64 / g as f64, b as f64 / g as f64];
            let estimate: f64 =
                points.chunks_exact(2).map(|p| f.eval(&[(p[0] + u[0]).fract(), (p[1] + u[1]).fract()])).sum::<f64>()
                    / n as f64;
            total += (estimate - f.exact()).powi(2);
        }
    }
    total / (g * g) as f64
}

/// Failure probability: the brute-force half is exact (to 1e-10), so only the measured half
/// can fail by chance: 0.27% for each of its 34 comparisons whose variance is not zero, at 3
/// standard errors, 8.8% for the test were they independent (they are 34 fixed seeds' draws,
/// so the verdict is the same on every run; the largest |z| at 2026-12-06 was 2.1). Least
/// work: 4000 shifted realizations put the measured variance's standard error at about 1.1%
/// of it (sobol.shift at n = 16), so a prediction 5% off is 4.5 standard errors away; the
/// criterion scales with that error, so fewer realizations would keep the failure
/// probability and lose that power.
#[test]
fn shifted_sets_on_trigonometric_integrands_are_predicted_exactly() {
    let cosine = instance("cosine:u=3,v=5");
    let poly = trig();
    let integrands: [&dyn Integrand; 2] = [cosine.as_ref(), &poly];
    for f in integrands {
        let spectrum = predict::integrand_spectrum(f, 32).unwrap();
        assert_eq!(spectrum.source, "closed form");
        // jitter.box at delta = 1/2 cell is jitter with its spectrum measured from the same
        // realizations the brute force takes (jitter's own is the closed-form expectation)
        for sampler_spec in ["sobol.shift", "halton.shift", "lattice.shift", "jitter", "jitter.box:delta=0.5"] {
            let s = sampler::build(sampler_spec).unwrap();
            for n in [16, 64, 256, 1024] {
                let p = predicted(sampler_spec, &spectrum, n, 8);
                // measured over 4000 shifted realizations
                let m = predict::measure(&s, f, n, 4000, Seed(9), true, SILENT).unwrap();
                // 3 standard errors, or the formula's rounding (a few ulps of Var(f) / n)
                // where the set integrates the integrand exactly (a lattice that does not
                // alias its frequencies) and both are 0 but for rounding
                let rounding = 1e-15 * spectrum.variance / n as f64;
                let se = m.se.hypot(p.se);
                assert!(
                    (p.variance - m.variance).abs() <= 3.0 * se + rounding,
                    "{sampler_spec} n={n}: predicted {:.4e} +- {:.1e}, measured {:.4e} +- {:.1e}",
                    p.variance,
                    p.se,
                    m.variance,
                    m.se
                );
                if sampler_spec == "jitter" {
                    continue;
                }
                // the same sum by brute force over the shifts, for the same 8 realizations
                let sets = sampler::generate_sets(&s, n, 2, Seed(5), 8).unwrap();
                let brute: f64 = sets.iter().map(|set| brute_force(f, set.as_slice(), 16)).sum::<f64>() / 8.0;
                // to 1e-10, or to the formula's rounding
                assert!(
                    (p.variance - brute).abs() <= 1e-10 * brute + rounding,
                    "{sampler_spec} n={n}: predicted {:.15e}, brute force {brute:.15e}",
                    p.variance
                );
            }
        }
    }
}

/// The integral of g over the square by tensor Gauss-Legendre quadrature.
fn quadrature_2d(g: impl Fn(f64, f64) -> f64) -> f64 {
    gauss_legendre(|y| gauss_legendre(|x| g(x, y), 0.0, 1.0, 32), 0.0, 1.0, 32)
}

/// How a test computes Var(f) on its own.
type VarianceOf = dyn Fn(&dyn Integrand) -> f64;

#[test]
fn white_noise_predicts_the_variance_of_f_over_n() {
    // Var(f) computed apart from the code under test: p(1 - p) for an indicator,
    // quadrature for smooth integrands
    let indicator = |f: &dyn Integrand| f.exact() * (1.0 - f.exact());
    let by_quadrature = |f: &dyn Integrand| {
        let mean = f.exact();
        quadrature_2d(|x, y| (f.eval(&[x, y]) - mean).powi(2))
    };
    let cases: [(&str, &VarianceOf); 8] = [
        ("quad", &indicator),
        ("disk", &indicator),
        ("halfplane", &indicator),
        ("smooth", &by_quadrature),
        ("cosine:u=4,v=2", &by_quadrature),
        ("step", &indicator),
        ("box", &indicator),
        ("steps:k=5", &|f: &dyn Integrand| f.exact() * (1.0 - f.exact())),
    ];
    for (spec, variance) in cases {
        let f = instance(spec);
        let spectrum = predict::integrand_spectrum(f.as_ref(), 16).unwrap();
        assert_eq!(spectrum.source, "closed form", "{spec}");
        let want = variance(f.as_ref());
        for n in [16, 100, 1000] {
            let p = predicted("random", &spectrum, n, 8);
            assert!(
                (p.variance - want / n as f64).abs() <= 1e-12 * want / n as f64,
                "{spec} n={n}: {} vs {}",
                p.variance,
                want / n as f64
            );
            assert_eq!(p.se, 0.0);
        }
    }
}

/// An integrand seen only through its values: the prediction must take the numeric path.
struct Opaque<'a>(&'a dyn Integrand);

impl Integrand for Opaque<'_> {
    fn dims(&self) -> usize {
        self.0.dims()
    }
    fn eval(&self, x: &[f64]) -> f64 {
        self.0.eval(x)
    }
    fn exact(&self) -> f64 {
        self.0.exact()
    }
}

#[test]
fn closed_forms_agree_with_the_fft_of_sampled_values() {
    for spec in ["quad", "disk", "halfplane", "smooth", "cosine:u=4,v=2", "box", "steps:k=3"] {
        let f = instance(spec);
        let closed = predict::integrand_spectrum(f.as_ref(), 16).unwrap();
        let numeric = predict::integrand_spectrum(&Opaque(f.as_ref()), 16).unwrap();
        assert!(numeric.source.starts_with("FFT"), "{spec}");
        // every coefficient's power within 1e-3 of the variance, and the variance within 1e-3
        let worst = closed.power.iter().zip(&numeric.power).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst <= 1e-3 * closed.variance, "{spec}: worst power difference {worst:e}");
        assert!((closed.variance - numeric.variance).abs() <= 1e-3 * closed.variance, "{spec}");
    }
}

/// Failure probability: 0.27% for each of the 2 comparisons at 3 standard errors of the
/// measured spectrum's prediction (256 sets), 0.54% in all; a fixed seed. Least work: the
/// criterion scales with the measured prediction's standard error, so the sets buy power,
/// not a lower failure probability; 256 sets take 1.1 s (2026-12-06).
#[test]
fn the_closed_form_jitter_spectrum_predicts_what_measured_jitter_spectra_do() {
    // jitter.box at delta = 1/2 cell is jitter by another name, so its spectrum is measured
    let f = instance("disk:r=0.3,cx=0.45,cy=0.5");
    let spectrum = predict::integrand_spectrum(f.as_ref(), 64).unwrap();
    for n in [64, 256] {
        let closed = predicted("jitter", &spectrum, n, 8);
        let measured = predicted("jitter.box:delta=0.5", &spectrum, n, 256);
        assert!(
            (closed.variance - measured.variance).abs() <= 3.0 * measured.se,
            "n={n}: closed {:.4e}, measured {:.4e} +- {:.1e}",
            closed.variance,
            measured.variance,
            measured.se
        );
    }
}

/// Failure probability: the exponent is a closed form's (no sampling); the measured
/// variances over 4000 realizations have a standard error of about sqrt(2 / 4000) = 2.2% of
/// themselves for errors near Gaussian (a sum over many cells), so 20% is about 9 standard
/// errors: below 1e-15 per comparison. Least work: issue 40's fixed criterion; 1000
/// realizations would keep a failure probability of about 1e-5 (4.4 standard errors) for a
/// quarter of the test's 0.4 s (2026-12-06): not worth a looser test.
#[test]
fn jittered_sampling_of_a_disk_converges_as_n_to_the_minus_three_halves() {
    // criterion fixed before the first run (issue 40): the predicted exponent within 0.05
    // of -1.5, the predicted variance within 20% of the measured one at n = 256 and 1024
    let f = instance("disk:r=0.3,cx=0.45,cy=0.5");
    let spectrum = predict::integrand_spectrum(f.as_ref(), 1024).unwrap();
    let ns = [256, 1024, 4096, 16384];
    let points: Vec<(f64, f64)> =
        ns.iter().map(|&n| (n as f64, predicted("jitter", &spectrum, n, 8).variance)).collect();
    let (slope, _) = samplab::experiment::loglog_fit(&points).unwrap();
    assert!((slope + 1.5).abs() <= 0.05, "predicted exponent {slope}");
    let jitter = sampler::build("jitter").unwrap();
    for (n, (_, p)) in ns.iter().zip(&points).take(2) {
        let m = predict::measure(&jitter, f.as_ref(), *n, 4000, Seed(3), false, SILENT).unwrap();
        assert!(
            (p / m.variance - 1.0).abs() <= 0.2,
            "n={n}: predicted {p:.4e}, measured {:.4e} +- {:.1e}",
            m.variance,
            m.se
        );
    }
}

#[test]
fn bad_grids_and_mismatched_spectra_are_refused() {
    let f = instance("disk");
    assert_eq!(
        predict::integrand_spectrum(f.as_ref(), 7).unwrap_err().to_string(),
        "res = 7: the spectrum grid is an even 4 to 4096 frequencies per axis"
    );
    let a = predict::integrand_spectrum(f.as_ref(), 16).unwrap();
    let random = sampler::build("random").unwrap();
    let s = predict::sampler_spectrum(&random, 64, 2, 32, 8, Seed(1), SILENT).unwrap();
    assert!(predict::predict(&a, &s).is_err());
    let e = predict::sampler_spectrum(&random, 64, 2, 16, 4, Seed(1), SILENT).unwrap_err().to_string();
    assert!(e.starts_with("sets = 4"), "{e}");
}

fn spectra(spec: &str, ns: &[usize], res: usize, sets: usize) -> Vec<predict::SamplerSpectrum> {
    let s = sampler::build(spec).unwrap();
    ns.iter().map(|&n| predict::sampler_spectrum(&s, n, 2, res, sets, Seed(7), SILENT).unwrap()).collect()
}

#[test]
fn the_small_frequency_exponents_are_those_of_the_closed_forms() {
    // white noise: P = 1, beta = 0 exactly, both exponents -1
    let random = spectra("random", &[64, 1024], 128, 8);
    let fit = predict::small_frequency(&random.iter().collect::<Vec<_>>()).unwrap();
    assert_eq!(fit.exponent, Some(0.0));
    assert_eq!((fit.best, fit.worst), (Some(-1.0), -1.0));
    // jitter: 1 - sinc^2 sinc^2 = (pi^2 / 3) |k|^2 / n + O(|k|^4 / n^2): beta = 2, best -2,
    // worst -1.5 (criterion: within 0.1). The fitted c is pi^2 / 3 less the quartic term's
    // share of the fit region (0.88 pi^2 / 3 measured), so it is bounded, not matched.
    let jitter = spectra("jitter", &[256, 1024, 4096], 128, 8);
    let fit = predict::small_frequency(&jitter.iter().collect::<Vec<_>>()).unwrap();
    let beta = fit.exponent.unwrap();
    assert!((beta - 2.0).abs() <= 0.1, "beta {beta}");
    let c = fit.constant.unwrap() / (std::f64::consts::PI.powi(2) / 3.0);
    assert!((0.75..=1.0).contains(&c), "c / (pi^2 / 3) = {c}");
    assert!((fit.best.unwrap() + 2.0).abs() <= 0.05 && fit.worst == -1.5, "{fit:?}");
    // a rank-1 lattice: P vanishes below its shortest dual vector, a zero region
    let lattice = spectra("lattice.shift", &[256, 1024], 128, 8);
    let fit = predict::small_frequency(&lattice.iter().collect::<Vec<_>>()).unwrap();
    assert_eq!((fit.exponent, fit.best, fit.worst), (None, None, -1.5));
}

/// Failure probability: small but not computed. The measured slope's own standard error,
/// from variances known to about 2.2% each (4000 shifted realizations, errors near
/// Gaussian) over a factor 16 in n, is about 0.011, so the criterion of 0.1 is about 9 of
/// them; the predicted exponent comes from a fit to 8-set spectra, whose error is not in that
/// figure. Least work: the test takes 0.4 s (2026-12-06).
#[test]
fn the_best_case_exponent_is_what_jitter_shows_on_a_band_limited_integrand() {
    // criterion fixed before the run: the measured slope (shifted sets) on the plane wave
    // cos(2 pi (x + y)) at n = 256..4096 within 0.1 of the predicted best case
    let ns = [256, 1024, 4096];
    let jitter = spectra("jitter", &ns, 64, 8);
    let best = predict::small_frequency(&jitter.iter().collect::<Vec<_>>()).unwrap().best.unwrap();
    let f = instance("cosine:u=1,v=1");
    let s = sampler::build("jitter").unwrap();
    let points: Vec<(f64, f64)> = ns
        .iter()
        .map(|&n| (n as f64, predict::measure(&s, f.as_ref(), n, 4000, Seed(2), true, SILENT).unwrap().variance))
        .collect();
    let (slope, _) = samplab::experiment::loglog_fit(&points).unwrap();
    assert!((slope - best).abs() <= 0.1, "measured {slope}, predicted best {best}");
}

/// Failure probability: 0.27% for each of the 2 comparisons of the radial form with the
/// torus sum at 3 standard errors (64 Poisson-disk sets); the comparisons with measured
/// variances (2000 shifted realizations, standard error about 3.2%) allow 20%, about 6
/// standard errors: about 1e-9 for errors near Gaussian. Fixed seeds. Least work: 3.9 s
/// (2026-12-06), most of it making Poisson-disk sets; not re-sized yet.
#[test]
fn the_radial_form_is_the_torus_sum_for_isotropic_spectra() {
    let f = instance("disk:r=0.3,cx=0.45,cy=0.5");
    let spectrum = predict::integrand_spectrum(f.as_ref(), 64).unwrap();
    // white noise is constant on rings: the two forms agree to rounding
    for s in spectra("random", &[64, 1024], 64, 8) {
        let (a, b) = (predict::predict(&spectrum, &s).unwrap(), predict::predict_radial(&spectrum, &s).unwrap());
        assert!((a.variance - b.variance).abs() <= 1e-12 * a.variance, "{a:?} {b:?}");
    }
    // Poisson disk (isotropic in expectation): the radial form within 3 standard errors
    // of the torus sum, and within 20% of the measured variance of shifted sets
    let poisson = sampler::build("poisson.fast").unwrap();
    for n in [256, 1024] {
        let s = predict::sampler_spectrum(&poisson, n, 2, 64, 64, Seed(4), SILENT).unwrap();
        let (a, b) = (predict::predict(&spectrum, &s).unwrap(), predict::predict_radial(&spectrum, &s).unwrap());
        assert!((a.variance - b.variance).abs() <= 3.0 * a.se.hypot(b.se), "n={n}: {a:?} {b:?}");
        let m = predict::measure(&poisson, f.as_ref(), n, 2000, Seed(8), true, SILENT).unwrap();
        assert!((b.variance / m.variance - 1.0).abs() <= 0.2, "n={n}: radial {b:?}, measured {m:?}");
    }
}

#[test]
fn a_grid_integrand_has_the_fourier_coefficients_of_its_cells() {
    use samplab::integrand::Grid;
    let (w, h) = (3, 2);
    let values = vec![0.5, -1.0, 2.0, 0.25, 3.0, -0.75];
    let g = Grid::new(w, h, values.clone()).unwrap();
    // box lookups, the first row at y = 0
    assert_eq!(g.eval(&[0.1, 0.1]), 0.5);
    assert_eq!(g.eval(&[0.9, 0.9]), -0.75);
    assert_eq!(g.eval(&[0.5, 0.99]), 3.0);
    assert!((g.exact() - values.iter().sum::<f64>() / 6.0).abs() < 1e-15);
    // each cell's integral of exp(-2 pi i k x), per axis: (e(b) - e(a)) / (-2 pi i k)
    let axis = |k: i64, a: f64, b: f64| -> (f64, f64) {
        if k == 0 {
            return (b - a, 0.0);
        }
        let t = std::f64::consts::TAU * k as f64;
        // (cos tb - i sin tb - cos ta + i sin ta) / (-i t) = ((sin ta - sin tb) + i (cos tb - cos ta)) / t ... times i / i
        ((t * b).sin() / t - (t * a).sin() / t, ((t * b).cos() - (t * a).cos()) / t)
    };
    for k in [[0, 0], [1, 0], [0, 1], [2, -1], [-3, 5], [7, 4]] {
        let mut sum = (0.0, 0.0);
        for j in 0..h {
            for i in 0..w {
                let x = axis(k[0], i as f64 / w as f64, (i + 1) as f64 / w as f64);
                let y = axis(k[1], j as f64 / h as f64, (j + 1) as f64 / h as f64);
                let v = values[j * w + i];
                sum.0 += v * (x.0 * y.0 - x.1 * y.1);
                sum.1 += v * (x.0 * y.1 + x.1 * y.0);
            }
        }
        let [re, im] = g.fourier(k).unwrap();
        assert!((re - sum.0).abs() < 1e-12 && (im - sum.1).abs() < 1e-12, "k={k:?}: {re} {im} against {sum:?}");
    }
    assert!(Grid::new(2, 2, vec![1.0, f64::NAN, 0.0, 0.0]).unwrap_err().to_string().contains("cell (1, 0)"));
    assert!(Grid::new(0, 2, vec![]).is_err());
    assert!(Grid::new(2, 2, vec![1.0]).is_err());
}

#[test]
fn kept_spectra_are_read_back_bit_for_bit() {
    let dir = std::env::temp_dir().join(format!("samplab-predict-cache-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let cache = predict::Cache::new(&dir);
    let f = instance("disk:r=0.3,cx=0.45,cy=0.5");
    let samplers = vec![sampler::build("sobol.owen").unwrap(), sampler::build("jitter").unwrap()];
    let integrands = [(f.as_ref(), "disk".to_string())];
    let run = |cache: Option<&predict::Cache>| {
        let study = predict::Study {
            samplers: &samplers,
            integrands: &integrands,
            ns: &[16, 64],
            res: 16,
            sets: 8,
            measure: None,
            seed: Seed(1),
            cache,
        };
        serde_json::to_string(&study.run(SILENT).unwrap()).unwrap()
    };
    let fresh = run(None);
    assert_eq!(run(Some(&cache)), fresh);
    // sobol.owen's two spectra are kept (jitter's is a closed form), and read back
    let files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    assert_eq!(files.len(), 2, "{files:?}");
    assert_eq!(run(Some(&cache)), fresh);
    // a damaged file is measured again, not believed
    std::fs::write(&files[0], b"samplab spectrum cache 1\nsomething else").unwrap();
    let bytes = std::fs::read(&files[1]).unwrap();
    std::fs::write(&files[1], &bytes[..bytes.len() - 8]).unwrap();
    assert_eq!(run(Some(&cache)), fresh);
    let _ = std::fs::remove_dir_all(&dir);
}
