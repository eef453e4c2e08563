//! Closed forms from the papers, for overlays and tests.

/// Sbert et al. 2006 eq. 10: the constant k of the systematic-sampling variance law
/// Var = k B u^3 (isotropic rotation assumed).
pub const K_SYSTEMATIC: f64 = 0.0724;

/// Variance of the mean of n independent uniform samples of an indicator of area p:
/// p (1 - p) / n (Sbert et al. 2006 eq. 12 with A_T = 1).
pub fn random_indicator_variance(p: f64, n: usize) -> f64 {
    p * (1.0 - p) / n as f64
}

/// Systematic (uniform-jitter) sampling of a region with boundary length `b` on a square
/// grid of n cells over the unit square (spacing u = n^-1/2): k B u^3 (Sbert et al. eq. 10-11).
pub fn systematic_variance(b: f64, n: usize) -> f64 {
    K_SYSTEMATIC * b * (n as f64).powf(-1.5)
}

/// Relative efficiency of systematic against independent sampling, Var_indep / Var_sys
/// = sqrt(N) sqrt(p) (1 - p) / (k k'), with B = k' sqrt(A) (Sbert et al. eq. 15).
pub fn systematic_efficiency(p: f64, n: usize, k_prime: f64) -> f64 {
    (n as f64).sqrt() * p.sqrt() * (1.0 - p) / (K_SYSTEMATIC * k_prime)
}

/// The range of p where systematic sampling beats independent sampling, from the
/// small-p and near-1 approximations (Sbert et al. eqs. 17 and 19):
/// (k k')^2 / N <= p <= 1 - k k' / sqrt(N). For a square (k' = 4): 0.0838/N and 0.2896/sqrt(N) (eq. 20).
pub fn systematic_break_even(n: usize, k_prime: f64) -> (f64, f64) {
    let kk = K_SYSTEMATIC * k_prime;
    (kk * kk / n as f64, 1.0 - kk / (n as f64).sqrt())
}

/// Exact efficiency of systematic against independent sampling for a region of area `p`
/// narrower than the grid spacing n^-1/2 (a disk of diameter below it, say): the region
/// then holds at most one grid point, and holds one with probability N p, so the estimate
/// (points inside)/N has variance p (1 - N p)/N, and the efficiency p (1 - p)/N over that is
/// (1 - p)/(1 - N p) >= 1. Below eq. 17's lower bound (k k')^2/N, where eq. 16 predicts an
/// efficiency under 1 (Sbert et al. 2006), every disk is that narrow.
pub fn systematic_efficiency_small(p: f64, n: usize) -> f64 {
    (1.0 - p) / (1.0 - n as f64 * p)
}

/// The covariogram of a disk of radius `r` (Sbert et al. 2006 eq. 6 for its indicator): the
/// area of the lens where the disk and its copy moved by `d` overlap,
/// 2 r^2 acos(d / 2r) - (d / 2) sqrt(4 r^2 - d^2), zero from d = 2r on.
pub fn disk_covariogram(r: f64, d: f64) -> f64 {
    if d >= 2.0 * r {
        return 0.0;
    }
    2.0 * r * r * (d / (2.0 * r)).acos() - 0.5 * d * (4.0 * r * r - d * d).sqrt()
}

/// The exact variance of systematic sampling's estimate of a disk's area, Sbert et al. 2006
/// eq. 5: V sum over the lattice vectors tau k of g(tau k), less the integral of g (the
/// squared area), with g the disk's covariogram (eq. 6, [`disk_covariogram`]). The lattice
/// is the square grid of `n` points over the unit square (n a perfect square, spacing
/// n^-1/2, cell volume V = 1/n) under one uniform random offset; the disk (radius `r`)
/// must lie inside the square, where the torus's grid and the plane's agree. Unlike the
/// law k B u^3 (eq. 10), an average over positions and sizes, this holds for one disk, so
/// it follows the variance's oscillation with the radius (the Zitterbewegung).
pub fn systematic_variance_disk(r: f64, n: usize) -> f64 {
    let side = (n as f64).sqrt().round();
    let spacing = 1.0 / side;
    let reach = (2.0 * r / spacing).ceil() as i64;
    let mut sum = crate::numeric::Sum::default();
    for i in -reach..=reach {
        for j in -reach..=reach {
            sum.add(disk_covariogram(r, spacing * ((i * i + j * j) as f64).sqrt()));
        }
    }
    let area = std::f64::consts::PI * r * r;
    sum.value() / n as f64 - area * area
}

/// The expected estimate of Gaussian jitter (`jitter.gaussian:sigma`, toroidal wrap) on `f`
/// with `n` points (n a perfect square m^2), Subr & Kautz 2013 eq. 4 with eq. 8's expected
/// spectrum: every point's density is a Gaussian of deviation sigma cells about its cell's
/// centre, wrapped, so the average density has Fourier coefficients (-1)^(j1 + j2)
/// exp(-2 pi^2 sigma^2 |j|^2) at the grid's frequencies m j and none elsewhere, and the
/// expected estimate is the sum over j of those times Re F(m j). Its bias is this less the
/// integral. The sum stops where the Gaussian factor falls below 1e-17. None when `f` has
/// no closed-form Fourier coefficients, n is not a square, or sigma is not positive.
pub fn gaussian_jitter_expectation(f: &dyn crate::integrand::Integrand, n: usize, sigma: f64) -> Option<f64> {
    gaussian_jitter_harmonics(f, n, sigma, |j, sign, weight, [re, _]| if j == [0, 0] { re } else { sign * weight * re })
}

/// Subr & Kautz 2013 eq. 7's bound on Gaussian jitter's bias on `f` (n and sigma as in
/// [`gaussian_jitter_expectation`]): the phases of eq. 4 ignored, the sum over the grid's
/// harmonics m j != 0 of `|<S>| |F(m j)|`, with `|<S>| = exp(-2 pi^2 sigma^2 |j|^2)`. It bounds
/// |bias| from above (the triangle inequality), the "conservative approximation" of their
/// section 2.4.
pub fn gaussian_jitter_bias_bound(f: &dyn crate::integrand::Integrand, n: usize, sigma: f64) -> Option<f64> {
    gaussian_jitter_harmonics(
        f,
        n,
        sigma,
        |j, _, weight, [re, im]| if j == [0, 0] { 0.0 } else { weight * re.hypot(im) },
    )
}

/// The sum over Gaussian jitter's harmonics j (frequencies m j, m = sqrt(n)) of
/// `term(j, (-1)^(j1 + j2), exp(-2 pi^2 sigma^2 |j|^2), F(m j))`, as far as the Gaussian
/// factor exceeds 1e-17; None when `f` has no closed-form Fourier coefficients, n is not a
/// square, or sigma is not positive.
fn gaussian_jitter_harmonics(
    f: &dyn crate::integrand::Integrand,
    n: usize,
    sigma: f64,
    term: impl Fn([i64; 2], f64, f64, [f64; 2]) -> f64,
) -> Option<f64> {
    let m = (n as f64).sqrt().round() as i64;
    if m * m != n as i64 || sigma.is_nan() || sigma <= 0.0 || f.dims() != 2 {
        return None;
    }
    let falloff = |j2: i64| (-2.0 * std::f64::consts::PI.powi(2) * sigma * sigma * j2 as f64).exp();
    let reach = (17.0 * 10f64.ln() / (2.0 * std::f64::consts::PI.powi(2) * sigma * sigma)).sqrt().ceil() as i64;
    let mut sum = crate::numeric::Sum::default();
    for a in -reach..=reach {
        for b in -reach..=reach {
            let weight = falloff(a * a + b * b);
            if weight < 1e-17 {
                continue;
            }
            let sign = if (a + b).rem_euclid(2) == 0 { 1.0 } else { -1.0 };
            sum.add(term([a, b], sign, weight, f.fourier([m * a, m * b])?));
        }
    }
    Some(sum.value())
}

/// Ramamoorthi et al. 2012: the expected N^2 x squared error of 1D visibility with
/// `discontinuities` discontinuities in distinct strata, over uniform random positions,
/// for a sampler family (`regular` = their "uniform", `jitter` = "stratified",
/// `jitter.uniform` = "uniform jitter"; eqs. 11-12, section 4.2, Fig. 7). None for other
/// samplers.
pub fn visibility_normalized_mse(sampler: &str, discontinuities: usize) -> Option<f64> {
    let k = discontinuities as f64;
    match sampler {
        "regular" => Some(k / 12.0),
        "jitter" => Some(k / 6.0),
        // pairs of discontinuities behave as for uniform sampling; an odd one costs 1/12 more
        "jitter.uniform" => Some(if discontinuities.is_multiple_of(2) { k / 12.0 } else { (k + 1.0) / 12.0 }),
        _ => None,
    }
}

/// Ramamoorthi et al. Figs. 4 and 6: the worst-case N x |error| for one discontinuity
/// (uniform 1/2, stratified 1) and for a box (uniform and uniform jitter 1, stratified 2).
pub fn visibility_worst_case(sampler: &str, discontinuities: usize) -> Option<f64> {
    match (sampler, discontinuities) {
        ("regular", 1) => Some(0.5),
        ("jitter" | "jitter.uniform", 1) => Some(1.0),
        ("regular" | "jitter.uniform", 2) => Some(1.0),
        ("jitter", 2) => Some(2.0),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_region_efficiency_by_brute_force_over_offsets() {
        // a disk of radius 0.03 (diameter 0.06) on the 4 x 4 grid (spacing 0.25): every
        // offset of the grid on a 500 x 500 lattice over one cell, points in the disk counted
        let (r, n, side) = (0.03f64, 16usize, 500usize);
        let (cx, cy, h) = (0.41, 0.67, 0.25);
        let (mut sum, mut sum2) = (0.0, 0.0);
        for i in 0..side * side {
            let (ox, oy) = (((i % side) as f64 + 0.5) / side as f64 * h, ((i / side) as f64 + 0.5) / side as f64 * h);
            let inside = (0..n)
                .filter(|k| {
                    let (x, y) = (ox + (k % 4) as f64 * h, oy + (k / 4) as f64 * h);
                    (x - cx).hypot(y - cy) < r
                })
                .count() as f64
                / n as f64;
            sum += inside;
            sum2 += inside * inside;
        }
        let mean = sum / (side * side) as f64;
        let variance = sum2 / (side * side) as f64 - mean * mean;
        let p = std::f64::consts::PI * r * r;
        let efficiency = random_indicator_variance(p, n) / variance;
        assert!((mean - p).abs() < 0.01 * p, "{mean} against {p}");
        assert!((efficiency / systematic_efficiency_small(p, n) - 1.0).abs() < 0.01, "{efficiency}");
        // eq. 16's small-p efficiency says the opposite there
        assert!(systematic_efficiency(p, n, 2.0 * std::f64::consts::PI.sqrt()) < 1.0);
        assert!(systematic_efficiency_small(p, n) > 1.0);
    }

    /// The exact variance over offsets of (points of the sqrt(n) x sqrt(n) grid in the disk) / n,
    /// by brute force: the offsets on a `side` x `side` midpoint lattice over one cell.
    fn variance_over_offsets(r: f64, (cx, cy): (f64, f64), n: usize, side: usize) -> f64 {
        let k = (n as f64).sqrt() as usize;
        let h = 1.0 / k as f64;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for i in 0..side * side {
            let (ox, oy) = (((i % side) as f64 + 0.5) / side as f64 * h, ((i / side) as f64 + 0.5) / side as f64 * h);
            let inside = (0..n)
                .filter(|p| (ox + (p % k) as f64 * h - cx).hypot(oy + (p / k) as f64 * h - cy) < r)
                .count() as f64
                / n as f64;
            sum += inside;
            sum2 += inside * inside;
        }
        let m = (side * side) as f64;
        sum2 / m - (sum / m).powi(2)
    }

    #[test]
    fn eq5_is_the_variance_over_offsets_by_brute_force() {
        // disks wider than the grid's spacing (where the small-region form no longer holds),
        // off centre, and one narrower (where it does)
        for (r, centre, n) in [(0.3, (0.5, 0.5), 16), (0.21, (0.45, 0.52), 64), (0.137, (0.6, 0.35), 100)] {
            let exact = systematic_variance_disk(r, n);
            let brute = variance_over_offsets(r, centre, n, 600);
            assert!((exact / brute - 1.0).abs() < 0.01, "r = {r}, N = {n}: eq. 5 {exact}, over offsets {brute}");
        }
        let (r, n) = (0.04, 36);
        let p = std::f64::consts::PI * r * r;
        let small = random_indicator_variance(p, n) / systematic_efficiency_small(p, n);
        assert!((systematic_variance_disk(r, n) / small - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_disk_covariogram_integrates_to_the_squared_area() {
        // eq. 6: g(0) is the area, g vanishes from 2r, and its integral over the plane is the
        // area squared (radial midpoint rule, 20000 rings)
        let r = 0.3;
        let area = std::f64::consts::PI * r * r;
        assert!((disk_covariogram(r, 0.0) - area).abs() < 1e-15);
        assert_eq!(disk_covariogram(r, 2.0 * r), 0.0);
        let rings = 20000;
        let dr = 2.0 * r / rings as f64;
        let integral: f64 = (0..rings)
            .map(|i| {
                let d = (i as f64 + 0.5) * dr;
                2.0 * std::f64::consts::PI * d * disk_covariogram(r, d) * dr
            })
            .sum();
        assert!((integral / (area * area) - 1.0).abs() < 1e-7, "{integral} against {}", area * area);
    }

    /// Failure probability: about 6e-7 (5 standard errors of a mean of 200,000 independent
    /// estimates, nearly normal), fixed seed. Least work: at N = 16 and sigma 0.1 the bias of
    /// each quad is 100-1000 standard errors, so far fewer estimates would decide; 200,000
    /// keep the comparison at a relative precision of about 1% where the bias is smallest.
    #[test]
    fn gaussian_jitter_expectation_is_the_samplers_mean() {
        use crate::integrand::Family;
        use crate::{Seed, sampler};
        let family = Family::parse("quad").unwrap();
        for (instance, sigma) in [(0, 0.1), (1, 0.25), (2, 0.1)] {
            let f = family.instance(Seed(21), instance).unwrap();
            let n = 16;
            let s = sampler::build(&format!("jitter.gaussian:sigma={sigma}")).unwrap();
            let estimates: Vec<f64> = sampler::generate_sets(&s, n, 2, Seed(5).derive(instance), 200_000)
                .unwrap()
                .iter()
                .map(|set| set.iter().map(|p| f.eval(p)).sum::<f64>() / n as f64)
                .collect();
            let stats = crate::stats::Summary::of(&estimates);
            let exact = gaussian_jitter_expectation(f.as_ref(), n, sigma).unwrap();
            let z = (stats.mean - exact) / stats.standard_error();
            assert!(z.abs() < 5.0, "quad {instance}, sigma {sigma}: mean {} against {exact} (z = {z:.2})", stats.mean);
            // and the bias is real: the expectation is not the integral
            assert!((exact - f.exact()).abs() > 20.0 * stats.standard_error(), "quad {instance}: no bias to test");
            // eq. 7's amplitudes-only sum bounds it
            assert!(gaussian_jitter_bias_bound(f.as_ref(), n, sigma).unwrap() >= (exact - f.exact()).abs());
        }
        // the uniform-jitter limit: a wide Gaussian leaves no bias; a regular grid (sigma
        // 0) and a non-square count have no such sum
        let f = family.instance(Seed(21), 0).unwrap();
        assert!((gaussian_jitter_expectation(f.as_ref(), 16, 2.0).unwrap() - f.exact()).abs() < 1e-12);
        assert!(gaussian_jitter_expectation(f.as_ref(), 16, 0.0).is_none());
        assert!(gaussian_jitter_expectation(f.as_ref(), 15, 0.1).is_none());
    }

    #[test]
    fn eq7_is_the_bias_itself_for_one_real_harmonic() {
        use crate::integrand::Family;
        // (1 + cos(2 pi 16 x)) / 2 at N = 256: all its energy on the grid's first harmonics,
        // real (zero phase), so ignoring the phases loses nothing: the bound is |bias|, which
        // is exp(-2 pi^2 sigma^2) / 2 (the two harmonics each carry 1/4, sign -1)
        let f = Family::parse("cosine:u=16,v=0,phase=0").unwrap().instance(crate::Seed(1), 0).unwrap();
        for sigma in [0.1, 0.25, 0.5] {
            let bias = gaussian_jitter_expectation(f.as_ref(), 256, sigma).unwrap() - f.exact();
            let want = -(-2.0 * std::f64::consts::PI.powi(2) * sigma * sigma).exp() / 2.0;
            assert!((bias - want).abs() < 1e-14, "sigma {sigma}: {bias} against {want}");
            assert!((gaussian_jitter_bias_bound(f.as_ref(), 256, sigma).unwrap() - want.abs()).abs() < 1e-14);
        }
    }

    #[test]
    fn sbert_eq_20_for_a_square() {
        // k' = 4: the published 0.0838/N and 1 - 0.2896/sqrt(N)
        let (lo, hi) = systematic_break_even(1, 4.0);
        assert!((lo - 0.0838).abs() < 1e-4, "{lo}");
        assert!((1.0 - hi - 0.2896).abs() < 1e-4, "{hi}");
        // N = 20: 0.0042 <= p <= 0.9352
        let (lo, hi) = systematic_break_even(20, 4.0);
        assert!((lo - 0.0042).abs() < 1e-4 && (hi - 0.9352).abs() < 1e-4);
    }

    #[test]
    fn efficiency_is_largest_at_one_third() {
        let e = |p| systematic_efficiency(p, 100, 4.0);
        assert!(e(1.0 / 3.0) > e(0.3) && e(1.0 / 3.0) > e(0.36));
    }
}
