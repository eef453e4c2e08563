//! The d-dimensional families' exact integrals against independent computations: tensor
//! Gauss-Legendre rules split at every kink and jump (Genz), a radial quadrature (Keister),
//! and the point symmetry of the cube (the half-space).

use samplab::Seed;
use samplab::integrand::{Family, Integrand, genz_instance};
use samplab::numeric::quadrature::gauss_legendre;
use samplab::numeric::{normal_cdf, normal_quantile};

/// The integral over [0,1] of `f` split at `breaks` (each piece 8 panels of 16 points).
fn pieces(f: impl Fn(f64) -> f64, breaks: &[f64]) -> f64 {
    let mut cuts: Vec<f64> = std::iter::once(0.0).chain(breaks.iter().copied()).chain([1.0]).collect();
    cuts.sort_by(f64::total_cmp);
    cuts.windows(2).map(|w| gauss_legendre(&f, w[0], w[1], 8)).sum()
}

/// The integral over [0,1]^d (d <= 3) of `f`, every axis split at `breaks`.
fn tensor(f: &dyn Fn(&[f64]) -> f64, d: usize, breaks: &[f64]) -> f64 {
    match d {
        1 => pieces(|x| f(&[x]), breaks),
        2 => pieces(|x| pieces(|y| f(&[x, y]), breaks), breaks),
        3 => pieces(|x| pieces(|y| pieces(|z| f(&[x, y, z]), breaks), breaks), breaks),
        _ => unreachable!(),
    }
}

#[test]
fn genz_families_integrate_to_their_exact_values() {
    for name in ["oscillatory", "product-peak", "corner-peak", "gaussian", "continuous", "discontinuous"] {
        for d in [1usize, 2, 3] {
            if d == 3 && name != "corner-peak" && name != "continuous" {
                continue; // the 3D tensor rule is slow; two families cover d = 3
            }
            let spec = format!("genz.{name}:d={d}");
            for k in 0..3 {
                let f = genz_instance(&spec, Seed(7), k).unwrap();
                // the same instance as the registry's
                let registered = Family::parse(&spec).unwrap().instance(Seed(7), k).unwrap();
                assert_eq!((registered.dims(), registered.exact()), (d, f.exact()));
                // the continuous family kinks and the discontinuous one jumps at the u_i
                let breaks = f.coefficients().1.to_vec();
                let quadrature = tensor(&|x| f.eval(x), d, &breaks);
                let exact = f.exact();
                assert!(
                    (quadrature - exact).abs() <= 1e-9 * exact.abs().max(1.0),
                    "genz.{name} d={d} instance {k}: exact {exact}, quadrature {quadrature}"
                );
            }
        }
    }
}

#[test]
fn keister_matches_a_radial_quadrature() {
    for d in [1usize, 2, 3, 5, 8, 16, 32] {
        let f = Family::parse(&format!("keister:d={d}")).unwrap().instance(Seed(1), 0).unwrap();
        // the surface of S^(d-1) times the integral over r in [0, 14] of r^(d-1) cos r exp(-r^2)
        let half = d as f64 / 2.0;
        let surface = 2.0 * std::f64::consts::PI.powf(half) / libm_gamma(half);
        let radial = gauss_legendre(|r| r.powi(d as i32 - 1) * r.cos() * (-r * r).exp(), 0.0, 14.0, 64);
        let expected = surface * radial;
        assert!(
            (f.exact() - expected).abs() <= 1e-10 * expected.abs().max(1.0),
            "keister d={d}: {} against {expected}",
            f.exact()
        );
    }
}

/// Gamma(x) for x a multiple of 1/2, by its recurrence from Gamma(1/2) and Gamma(1).
fn libm_gamma(x: f64) -> f64 {
    let (mut g, mut t) = if (x * 2.0) as usize % 2 == 1 { (std::f64::consts::PI.sqrt(), 0.5) } else { (1.0, 1.0) };
    while t < x - 1e-9 {
        g *= t;
        t += 1.0;
    }
    g
}

#[test]
fn keister_in_one_dimension_is_the_gaussian_weighted_cosine() {
    // d = 1 in the cube's own coordinate, against sqrt(pi) exp(-1/4) (the integral of
    // cos(t) exp(-t^2) over the line)
    let f = Family::parse("keister:d=1").unwrap().instance(Seed(1), 0).unwrap();
    // Phi^-1 is steep at both ends: panels shrink geometrically towards them
    let ends: Vec<f64> = (1..=14).flat_map(|k| [10f64.powi(-k), 1.0 - 10f64.powi(-k)]).collect();
    let cube = pieces(|x| f.eval(&[x]), &ends);
    let exact = std::f64::consts::PI.sqrt() * (-0.25f64).exp();
    assert!((f.exact() - exact).abs() < 1e-14);
    assert!((cube - exact).abs() < 1e-9, "{cube} against {exact}");
}

#[test]
fn ishigami_and_gaussian_d_integrate_to_their_exact_values() {
    let f = Family::parse("ishigami").unwrap().instance(Seed(2), 0).unwrap();
    assert!((tensor(&|x| f.eval(x), 3, &[0.5]) - 3.5).abs() < 1e-9);
    assert_eq!(f.exact(), 3.5);
    let family = Family::parse("gaussian.d:d=2,sigma=0.2").unwrap();
    for k in 0..3 {
        let f = family.instance(Seed(3), k).unwrap();
        assert!((tensor(&|x| f.eval(x), 2, &[]) - f.exact()).abs() < 1e-10);
    }
}

#[test]
fn the_half_space_is_point_symmetric_about_the_centre() {
    // f(x) + f(1 - x) = 1 off the boundary, so the integral is 1/2 whatever the normal
    for d in [2usize, 5, 40] {
        let family = Family::parse(&format!("heaviside.d:d={d}")).unwrap();
        for k in 0..5 {
            let f = family.instance(Seed(4), k).unwrap();
            let mut rng = Seed(k).rng();
            for _ in 0..1000 {
                let x: Vec<f64> = (0..d).map(|_| samplab::seed::uniform(&mut rng)).collect();
                let mirror: Vec<f64> = x.iter().map(|v| 1.0 - v).collect();
                assert_eq!(f.eval(&x) + f.eval(&mirror), 1.0);
            }
            assert_eq!(f.exact(), 0.5);
        }
    }
}

#[test]
fn the_normal_quantile_inverts_the_distribution_function() {
    assert!((normal_quantile(0.975) - 1.959_963_984_540_054).abs() < 1e-14);
    assert!(normal_quantile(0.5).abs() < 1e-16);
    for &p in &[1e-300, 1e-100, 1e-10, 0.001, 0.1, 0.3, 0.7, 0.9, 0.999, 1.0 - 1e-10] {
        let x = normal_quantile(p);
        let back = normal_cdf(x);
        // 8 ulp in x (the test below) moves Phi by a relative 8 eps x phi(x) / Phi(x), which
        // is below 8 eps (1 + x^2) in either tail
        let tol = 8.0 * f64::EPSILON * (1.0 + x * x) * p.min(1.0 - p);
        assert!((back - p).abs() <= tol + 1e-300, "p = {p}: Phi(Phi^-1(p)) = {back}");
    }
}

/// Within 8 ulp of mpmath's quantile at 1706 points, the tails down to the least normal
/// double included (scripts/make_fixtures.py). The previous method, Halley steps on Phi from
/// a rational start, failed it: over 2000 ulp off near p = 1/2, where Phi(x) - p cancels, and
/// -1.9e-18 at p = 1/2 itself.
#[test]
fn the_normal_quantile_is_within_8_ulp_of_mpmath() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/normal_quantile.json")).unwrap();
    let fixture: serde_json::Value = serde_json::from_str(&text).unwrap();
    let rows = fixture["p_and_quantile"].as_array().unwrap();
    assert_eq!(rows.len(), 1706);
    let mut worst = (0, 0.0);
    for row in rows {
        let p = row[0].as_f64().unwrap();
        let exact: f64 = row[1].as_str().unwrap().parse().unwrap();
        let x = normal_quantile(p);
        // doubles of one sign are ordered as their bits are
        assert_eq!(x.is_sign_negative(), exact.is_sign_negative(), "p = {p}: {x} against {exact}");
        let ulps = (x.to_bits() as i64 - exact.to_bits() as i64).abs();
        if ulps > worst.0 {
            worst = (ulps, p);
        }
    }
    assert!(worst.0 <= 8, "{} ulp at p = {}", worst.0, worst.1);
}

#[test]
fn blinn_phong_matches_the_hemisphere_integral_and_the_mapped_square() {
    use std::f64::consts::PI;
    for e in [0.0, 1.0, 7.5, 32.0, 400.0] {
        let f = Family::parse(&format!("blinn-phong:e={e}")).unwrap().instance(Seed(0), 0).unwrap();
        // the BRDF times cos theta over the hemisphere, the half vector built as a vector:
        // theta in [0, pi/2] by Gauss-Legendre (the integrand does not depend on phi)
        let lobe = |theta: f64| {
            let w = [theta.sin(), 0.0, theta.cos()];
            let h = [w[0], w[1], w[2] + 1.0];
            let cos_h = h[2] / (h[0] * h[0] + h[1] * h[1] + h[2] * h[2]).sqrt();
            (e + 2.0) / (2.0 * PI) * cos_h.powf(e) * theta.cos() * theta.sin() * 2.0 * PI
        };
        let hemisphere = pieces(|x| lobe(x * PI / 2.0) * PI / 2.0, &[0.25, 0.5, 0.75]);
        assert!((hemisphere - f.exact()).abs() < 1e-12 * f.exact(), "e {e}: {hemisphere} vs {}", f.exact());
        // the integrand on the square (through the concentric map) by a 1500^2 midpoint rule
        let k = 1500;
        let mut sum = 0.0;
        for j in 0..k {
            for i in 0..k {
                sum += f.eval(&[(i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64]);
            }
        }
        let square = sum / (k * k) as f64;
        assert!((square - f.exact()).abs() < 1e-5 * f.exact(), "e {e}: {square} vs {}", f.exact());
    }
    // Lambert: reflectance 1
    let lambert = Family::parse("blinn-phong:e=0").unwrap().instance(Seed(0), 0).unwrap();
    assert!((lambert.exact() - 1.0).abs() < 1e-15);
}

/// QMCPy 2.4's values (scripts/qmcpy_integrals.py wrote the fixture).
fn qmcpy() -> serde_json::Value {
    serde_json::from_str(include_str!("fixtures/qmcpy_integrals.json")).unwrap()
}

#[test]
fn keister_equals_qmcpys_closed_form_in_1_to_32_dimensions() {
    let fixture = qmcpy();
    for (d, value) in fixture["keister"].as_object().unwrap() {
        let want = value.as_f64().unwrap();
        let ours = Family::parse(&format!("keister:d={d}")).unwrap().instance(Seed(0), 0).unwrap().exact();
        assert!((ours - want).abs() <= 1e-12 * want.abs(), "d {d}: {ours} vs QMCPy's {want}");
    }
}

#[test]
fn genz_and_ishigami_agree_with_qmcpys_guaranteed_estimates() {
    let fixture = qmcpy();
    for case in fixture["genz"].as_array().unwrap() {
        let a: Vec<f64> = case["a"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect();
        // QMCPy's oscillatory is cos(sum c_i t_i) (no shift); its corner peak has no shift
        let f = samplab::integrand::Genz::new(case["family"].as_str().unwrap(), a.clone(), vec![0.0; a.len()]).unwrap();
        let (want, bound) = (case["value"].as_f64().unwrap(), case["bound"].as_f64().unwrap());
        assert!((f.exact() - want).abs() <= bound + 1e-14, "{case}: ours {}", f.exact());
    }
    let ishigami = &fixture["ishigami"];
    let ours = Family::parse("ishigami:a=7,b=0.1").unwrap().instance(Seed(0), 0).unwrap().exact();
    let (want, bound) = (ishigami["value"].as_f64().unwrap(), ishigami["bound"].as_f64().unwrap());
    assert!((ours - want).abs() <= bound, "ours {ours}, QMCPy {want} +- {bound}");
}

#[test]
fn the_corner_peak_matches_the_corner_sum_where_that_sum_is_well_conditioned() {
    // the sum over the 2^d corners of (-1)^|v| / (1 + a.v), over d! prod a: exact in exact
    // arithmetic, and accurate in floating point when the a_i are of order 1
    for a in [vec![0.7], vec![1.3, 0.4], vec![0.9, 2.0, 0.5], vec![0.5, 0.6, 0.7, 0.8, 0.9]] {
        let d = a.len();
        let factorial: f64 = (1..=d).map(|k| k as f64).product();
        let corners: f64 = (0u64..1 << d)
            .map(|v| {
                let dot: f64 = a.iter().enumerate().filter(|(i, _)| v >> i & 1 == 1).map(|(_, a)| a).sum();
                if v.count_ones() % 2 == 0 { 1.0 / (1.0 + dot) } else { -1.0 / (1.0 + dot) }
            })
            .sum();
        let want = corners / (factorial * a.iter().product::<f64>());
        let f = samplab::integrand::Genz::new("genz.corner-peak", a.clone(), vec![0.0; d]).unwrap();
        assert!((f.exact() - want).abs() < 1e-13 * want, "{a:?}: {} vs {want}", f.exact());
    }
}
