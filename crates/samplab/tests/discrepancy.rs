//! Discrepancy: every fast algorithm against its brute-force reference on thousands of
//! random sets (ties and boundary points included), the L2 closed forms against exact
//! integrals and scipy, known values, and the paper's claims.

use samplab::discrepancy::{self, Limits, Metric, extreme, l2, star};
use samplab::progress::Progress;
use samplab::seed::{Rng, Seed, below, uniform};
use samplab::{PointSet, sampler};

/// No progress reports, never stopped.
const SILENT: Progress = Progress::SILENT;

/// A random set whose coordinates are drawn from a coarse lattice (ties) mixed with
/// uniform values, 0 and 1.
fn nasty(rng: &mut Rng, n: usize, d: usize) -> Vec<f64> {
    let levels = 1 + below(rng, 8);
    (0..n * d)
        .map(|_| match below(rng, 6) {
            0 => 0.0,
            1 => 1.0,
            2 | 3 => below(rng, levels + 1) as f64 / levels as f64,
            _ => uniform(rng),
        })
        .collect()
}

fn assert_close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() <= 1e-12, "{what}: {a} vs {b}");
}

#[test]
fn star_fast_equals_naive_1d_2d() {
    let mut rng = Seed(1).rng();
    for trial in 0..3000 {
        let n = 1 + below(&mut rng, 64) as usize;
        let x = nasty(&mut rng, n, 1);
        assert_close(star::star_1d(&x), star::star_naive(&x, 1), &format!("1D trial {trial}"));
        let p = nasty(&mut rng, n, 2);
        let naive = star::star_naive(&p, 2);
        assert_close(star::star_2d(&p, SILENT).unwrap(), naive, &format!("2D kinetic, trial {trial}: {p:?}"));
        assert_close(star::star_2d_sweep(&p), naive, &format!("2D sweep, trial {trial}"));
    }
}

#[test]
fn star_kinetic_equals_sweep_on_larger_sets() {
    let mut rng = Seed(2).rng();
    for n in [100usize, 500, 2000] {
        for _ in 0..5 {
            let p: Vec<f64> = (0..2 * n).map(|_| uniform(&mut rng)).collect();
            assert_close(star::star_2d(&p, SILENT).unwrap(), star::star_2d_sweep(&p), &format!("n = {n}"));
            let q = nasty(&mut rng, n, 2);
            assert_close(star::star_2d(&q, SILENT).unwrap(), star::star_2d_sweep(&q), &format!("ties, n = {n}"));
        }
    }
}

/// Brute force 1D extreme discrepancy over intervals with ends at critical values.
fn extreme_1d_naive(x: &[f64]) -> f64 {
    let mut c: Vec<f64> = x.to_vec();
    c.extend([0.0, 1.0]);
    c.sort_by(f64::total_cmp);
    c.dedup();
    let n = x.len() as f64;
    let mut worst: f64 = 0.0;
    for (i, &lo) in c.iter().enumerate() {
        for &hi in &c[i..] {
            let open = x.iter().filter(|&&t| lo < t && t < hi).count() as f64;
            let closed = x.iter().filter(|&&t| lo <= t && t <= hi).count() as f64;
            worst = worst.max(hi - lo - open / n).max(closed / n - (hi - lo));
        }
    }
    worst
}

#[test]
fn extreme_fast_equals_naive_1d_2d() {
    let mut rng = Seed(3).rng();
    for trial in 0..2000 {
        let n = 1 + below(&mut rng, if trial < 1800 { 24 } else { 64 }) as usize;
        let x = nasty(&mut rng, n, 1);
        assert_close(extreme::extreme_1d(&x), extreme_1d_naive(&x), &format!("1D trial {trial}: {x:?}"));
        let p = nasty(&mut rng, n, 2);
        let naive = extreme::extreme_2d_naive(&p);
        assert_close(extreme::extreme_2d(&p, SILENT).unwrap(), naive, &format!("2D trial {trial}: {p:?}"));
        assert_close(extreme::extreme_2d_sweep(&p), naive, &format!("2D sweep, trial {trial}: {p:?}"));
    }
}

#[test]
fn extreme_branch_and_bound_equals_the_sweep_on_larger_sets() {
    // the sweep (O(n^3), every pair) is the oracle; the sets range from easy to prune
    // (random) to the hardest (nets and lattices, whose boxes all come near the maximum),
    // and grids whose every side and edge is a tie
    for (spec, n) in [
        ("random", 700),
        ("jitter", 400),
        ("sobol.owen", 512),
        ("hammersley", 256),
        ("lattice", 256),
        ("lattice.fibonacci", 233),
        ("grid", 400),
        ("nrooks", 300),
    ] {
        let p = sampler::build(spec).unwrap().generate(n, 2, Seed(5)).unwrap();
        let x = p.as_slice();
        assert_close(extreme::extreme_2d(x, SILENT).unwrap(), extreme::extreme_2d_sweep(x), &format!("{spec} n = {n}"));
    }
    let mut rng = Seed(6).rng();
    for n in [200, 600] {
        let q = nasty(&mut rng, n, 2);
        assert_close(
            extreme::extreme_2d(&q, SILENT).unwrap(),
            extreme::extreme_2d_sweep(&q),
            &format!("ties, n = {n}"),
        );
    }
}

#[test]
fn star_exact_equals_naive_in_3d_4d_and_5d() {
    let mut rng = Seed(7).rng();
    for trial in 0..1500 {
        let (d, cap) = if trial < 1200 {
            (3, 24)
        } else if trial < 1400 {
            (4, 10)
        } else {
            (5, 6)
        };
        let n = 1 + below(&mut rng, cap) as usize;
        let p = nasty(&mut rng, n, d);
        let naive = star::star_naive(&p, d);
        assert_close(star::star_exact(&p, d, SILENT).unwrap(), naive, &format!("{d}D trial {trial}: {p:?}"));
        assert_close(star::star_dem(&p, d, SILENT).unwrap(), naive, &format!("{d}D DEM, trial {trial}: {p:?}"));
    }
}

#[test]
fn star_dem_equals_the_recursive_sweep_on_larger_sets() {
    // many slabs per axis, so the cuts, the knapsack and the parallel first two axes all
    // work; on 1, 3 and 8 threads (other schedules, other pruning), the same bits
    let pools: Vec<rayon::ThreadPool> =
        [1, 3, 8].map(|t| rayon::ThreadPoolBuilder::new().num_threads(t).build().unwrap()).into();
    let dem = |x: &[f64], d: usize| {
        let values: Vec<u64> =
            pools.iter().map(|pool| pool.install(|| star::star_dem(x, d, SILENT).unwrap()).to_bits()).collect();
        assert!(values.iter().all(|&v| v == values[0]), "star_dem on 1, 3 and 8 threads: {values:?}");
        f64::from_bits(values[0])
    };
    for (spec, n, d) in [("random", 300, 3), ("sobol", 256, 3), ("halton", 200, 3), ("random", 60, 4), ("sobol", 64, 4)]
    {
        let p = sampler::build(spec).unwrap().generate(n, d, Seed(3)).unwrap();
        let x = p.as_slice();
        assert_close(dem(x, d), star::star_exact(x, d, SILENT).unwrap(), &format!("{spec} n = {n}, {d}D"));
        // ties: the coordinates rounded to a coarse grid
        let q: Vec<f64> = x.iter().map(|v| (v * 8.0).round() / 8.0).collect();
        assert_close(dem(&q, d), star::star_exact(&q, d, SILENT).unwrap(), &format!("{spec} n = {n}, {d}D, ties"));
    }
}

#[test]
fn centred_grids_have_the_closed_form_star_discrepancy() {
    // the cell centres of a k^d grid: D* = 1 - (1 - 1/(2k))^d (the closed box through the
    // last centres holds every point)
    for (k, d) in [(5usize, 1usize), (4, 2), (7, 2), (2, 3), (3, 3), (4, 3), (2, 4)] {
        let g = sampler::build("regular").unwrap().generate(k.pow(d as u32), d, Seed(0)).unwrap();
        let want = 1.0 - (1.0 - 0.5 / k as f64).powi(d as i32);
        let got = discrepancy::compute(&Metric::parse("star").unwrap(), &g, Limits::default()).unwrap();
        assert!((got - want).abs() < 1e-12, "k={k} d={d}: {got} vs {want}");
    }
}

#[test]
fn every_l2_sweep_equals_its_pair_by_pair_sum() {
    // the O(n log n) 2D sweep against every pair's kernel, on sets with ties and points on
    // the boundary, for each L2 discrepancy
    let mut rng = Seed(5).rng();
    for (name, form) in [
        ("star", l2::STAR),
        ("extreme", l2::EXTREME),
        ("centered", l2::CENTERED),
        ("wrap", l2::WRAPAROUND),
        ("mixture", l2::MIXTURE),
        ("diaphony", l2::DIAPHONY),
    ] {
        for trial in 0..600 {
            let n = 1 + below(&mut rng, 64) as usize;
            let p = nasty(&mut rng, n, 2);
            assert_close(
                form.squared(&p, 2, SILENT).unwrap(),
                form.squared_quadratic(&p, 2, SILENT).unwrap(),
                &format!("{name} trial {trial}"),
            );
        }
        // and a large Sobol' set, where the squared discrepancy (L2-extreme: 7e-9) is the
        // difference of terms a million times larger (floating-point sums in the sweep were
        // 1e-7 off here; its sums are compensated; relative 1e-11, but the diaphony is
        let p = sampler::build("sobol.owen").unwrap().generate(1 << 13, 2, Seed(3)).unwrap();
        // 1e-5; the diaphony's kernel dips below zero (1 - pi^2 / 6) and its separable terms
        // reach 4 pi^2, so its sweep is held to 1e-12 absolute, 1e-13 of its largest pair term)
        let (fast, slow) =
            (form.squared(p.as_slice(), 2, SILENT).unwrap(), form.squared_quadratic(p.as_slice(), 2, SILENT).unwrap());
        let tolerance = if name == "diaphony" { 1e-12 } else { 1e-11 * slow.abs() };
        assert!((fast - slow).abs() <= tolerance, "{name} 2^13 Sobol': {fast} vs {slow}");
    }
}

/// The exact integral of (count(x < q)/N - q1 q2)^2 over the unit square, cell by cell of
/// the critical grid (the count is constant on each cell).
fn l2_star_sq_by_integration(p: &[f64]) -> f64 {
    let n = (p.len() / 2) as f64;
    let grid = |k: usize| {
        let mut v: Vec<f64> = p.iter().skip(k).step_by(2).copied().chain([0.0, 1.0]).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    let (gx, gy) = (grid(0), grid(1));
    let mut total = 0.0;
    for wx in gx.windows(2) {
        for wy in gy.windows(2) {
            let c = p.chunks_exact(2).filter(|q| q[0] <= wx[0] && q[1] <= wy[0]).count() as f64 / n;
            // integral of (c - x y)^2 = c^2 A - 2c (X2 Y2) + X3 Y3, with Xk = (b^k - a^k)/k
            let m = |w: &[f64], k: i32| (w[1].powi(k) - w[0].powi(k)) / k as f64;
            total += c * c * m(wx, 1) * m(wy, 1) - 2.0 * c * m(wx, 2) * m(wy, 2) + m(wx, 3) * m(wy, 3);
        }
    }
    total
}

#[test]
fn warnock_equals_the_defining_integral() {
    let mut rng = Seed(6).rng();
    for _ in 0..300 {
        let n = 1 + below(&mut rng, 20) as usize;
        let p = nasty(&mut rng, n, 2);
        let exact = l2_star_sq_by_integration(&p);
        assert!((l2::STAR.squared_quadratic(&p, 2, SILENT).unwrap() - exact).abs() < 1e-13);
        assert!((l2::STAR.squared(&p, 2, SILENT).unwrap() - exact).abs() < 1e-13);
    }
}

#[test]
fn l2_extreme_of_one_point_in_1d_by_integration() {
    // mean over intervals u < v of (1[u <= x < v] - (v - u))^2: midpoint rule on a fine grid
    for x in [0.1, 0.5, 0.93] {
        let k = 2000;
        let h = 1.0 / k as f64;
        let mut s = 0.0;
        for i in 0..k {
            for j in i + 1..k {
                let (u, v) = ((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                let ind = if u <= x && x < v { 1.0 } else { 0.0 };
                s += (ind - (v - u)).powi(2);
            }
        }
        let integral = s * h * h;
        assert!(
            (l2::EXTREME.squared(&[x], 1, SILENT).unwrap() - integral).abs() < 2e-3,
            "x = {x}: {} vs {integral}",
            l2::EXTREME.squared(&[x], 1, SILENT).unwrap()
        );
    }
}

#[test]
fn equal_scipy_on_stored_fixtures() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/scipy_discrepancy.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for case in v["cases"].as_array().unwrap() {
        let d = case["dims"].as_u64().unwrap() as usize;
        let pts: Vec<f64> = case["points"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()))
            .collect();
        let rel = |ours: f64, theirs: f64, what: &str| {
            assert!((ours - theirs).abs() <= 1e-10 * theirs.abs(), "{what} d={d}: ours {ours}, scipy {theirs}");
        };
        let s = &case["scipy"];
        // scipy returns CD, WD, MD squared and L2-star unsquared
        for (form, key) in [(l2::CENTERED, "CD"), (l2::WRAPAROUND, "WD"), (l2::MIXTURE, "MD")] {
            // the 2D sweep (d = 2) and the pair-by-pair sum both
            rel(form.squared(&pts, d, SILENT).unwrap(), s[key].as_f64().unwrap(), key);
            rel(form.squared_quadratic(&pts, d, SILENT).unwrap(), s[key].as_f64().unwrap(), key);
        }
        let set = PointSet::new(d, pts.clone()).unwrap();
        rel(
            discrepancy::compute(&Metric::parse("l2-star").unwrap(), &set, Limits::default()).unwrap(),
            s["L2-star"].as_f64().unwrap(),
            "L2-star",
        );
    }
}

#[test]
fn regular_grid_known_values() {
    let grid = sampler::build("regular").unwrap().generate(16, 2, Seed(0)).unwrap();
    let m = |name: &str| discrepancy::compute(&Metric::parse(name).unwrap(), &grid, Limits::default()).unwrap();
    assert_close(m("star"), 0.234375, "D*");
    assert_close(m("extreme"), 0.4375, "extreme");
    // L2-star of the 4x4 grid by hand: 0.0597... (Shirley's S = 0.0600 rounded)
    let s = m("l2-star");
    assert!((s - 0.059_73).abs() < 5e-5, "{s}");
    assert_close(s, l2_star_sq_by_integration(grid.as_slice()).sqrt(), "L2-star by integration");
}

#[test]
fn wraparound_is_shift_invariant_and_star_is_not() {
    let p = sampler::build("jitter").unwrap().generate(64, 2, Seed(1)).unwrap();
    let shifted = PointSet::new(2, p.iter().flat_map(|q| [(q[0] + 0.3) % 1.0, (q[1] + 0.71) % 1.0]).collect()).unwrap();
    let m = |metric: &str, s: &PointSet| {
        discrepancy::compute(&Metric::parse(metric).unwrap(), s, Limits::default()).unwrap()
    };
    assert!((m("wraparound", &p) - m("wraparound", &shifted)).abs() < 1e-13);
    assert!((m("star", &p) - m("star", &shifted)).abs() > 1e-6);
}

#[test]
fn projected_discrepancy() {
    let p = sampler::build("random").unwrap().generate(20_000, 2, Seed(2)).unwrap();
    let m = |angle: f64, extreme: bool, s: &PointSet| {
        let kind = if extreme { "extreme" } else { "star" };
        let metric = Metric::parse(&format!("projected:angle={angle},kind={kind}")).unwrap();
        discrepancy::compute(&metric, s, Limits::default()).unwrap()
    };
    // angle 0 and 90: the 1D discrepancies of x and y
    assert_close(m(0.0, false, &p), star::star_1d(&p.column(0)), "x");
    assert!((m(90.0, false, &p) - star::star_1d(&p.column(1))).abs() < 1e-12);
    // the projected CDF is right: uniform points pass a 1% Kolmogorov-Smirnov test at any angle
    for angle in [17.0, 30.0, 45.0, 123.0, -60.0] {
        let ks = m(angle, false, &p);
        assert!(ks < 1.63 / (20_000f64).sqrt(), "angle {angle}: {ks}");
    }
    // a 16 x 16 grid seen at 0 degrees: 16 columns of 16 points; a zero-width interval on a
    // column holds 1/16 of the points
    let grid = sampler::build("regular").unwrap().generate(256, 2, Seed(0)).unwrap();
    assert_close(m(0.0, true, &grid), 1.0 / 16.0, "grid at 0 degrees");
}

/// Shirley 1991 section 4: the generalized discrepancy (over rectangles of the warped
/// domain, expected counts from the density) of a tent-warped set equals the extreme
/// discrepancy of the original set. Checked by brute force in the warped domain.
#[test]
fn generalized_discrepancy_of_warped_set_equals_original() {
    let tent = samplab::warp::lookup("tent").unwrap();
    let cdf = samplab::warp::tent_cdf;
    for seed in 0..5 {
        let u = sampler::build("jitter").unwrap().generate(16, 2, Seed(seed)).unwrap();
        let w = samplab::warp::apply(tent, &u).unwrap();
        // brute force: rectangles with sides at the warped coordinates or the support's edges
        let side = |k: usize| {
            let mut v: Vec<f64> = w.column(k).into_iter().chain([-1.0, 1.0]).collect();
            v.sort_by(f64::total_cmp);
            v
        };
        let (xs, ys) = (side(0), side(1));
        let n = 16.0;
        let mut worst: f64 = 0.0;
        let mut anchored: f64 = 0.0;
        for (i, &x0) in xs.iter().enumerate() {
            for &x1 in &xs[i..] {
                for (j, &y0) in ys.iter().enumerate() {
                    for &y1 in &ys[j..] {
                        let mass = (cdf(x1) - cdf(x0)) * (cdf(y1) - cdf(y0));
                        let open =
                            w.iter().filter(|p| x0 < p[0] && p[0] < x1 && y0 < p[1] && p[1] < y1).count() as f64 / n;
                        let closed = w.iter().filter(|p| x0 <= p[0] && p[0] <= x1 && y0 <= p[1] && p[1] <= y1).count()
                            as f64
                            / n;
                        let here = (mass - open).max(closed - mass);
                        worst = worst.max(here);
                        if x0 == -1.0 && y0 == -1.0 {
                            anchored = anchored.max(here);
                        }
                    }
                }
            }
        }
        let limits = Limits::default();
        let ext = discrepancy::compute(&Metric::parse("extreme").unwrap(), &u, limits).unwrap();
        let st = discrepancy::compute(&Metric::parse("star").unwrap(), &u, limits).unwrap();
        assert!((worst - ext).abs() < 1e-12, "extreme: {worst} vs {ext}");
        assert!((anchored - st).abs() < 1e-12, "star: {anchored} vs {st}");
        let g = discrepancy::generalized(&w, &[&cdf, &cdf], false, limits).unwrap();
        assert!((g - ext).abs() < 1e-12);
    }
}

#[test]
fn bad_input_errors() {
    let outside = PointSet::new(2, vec![0.5, 1.5]).unwrap();
    let e = discrepancy::compute(&Metric::parse("star").unwrap(), &outside, Limits::default()).unwrap_err().to_string();
    assert!(e.contains("point 0 coordinate 1 is 1.5"), "{e}");
    // the first coordinate outside is named, whatever the threads scanning a large set
    let mut xs = vec![0.5; 3 * 300_000];
    for (at, x) in [(3 * 299_000 + 1, -0.25), (3 * 123_456 + 2, 1.5), (3 * 200_000, 2.0)] {
        xs[at] = x;
    }
    let set = PointSet::new(3, xs).unwrap();
    for threads in [1, 2, 16] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        let e = pool.install(|| discrepancy::compute(&Metric::parse("l2-star").unwrap(), &set, Limits::default()));
        let e = e.unwrap_err().to_string();
        assert!(e.contains("point 123456 coordinate 2 is 1.5 (outside [0, 1])"), "{threads} threads: {e}");
    }
    // refused before any work, as a work-limit error (the CLI names its flag)
    let big = sampler::build("random").unwrap().generate(200_000, 3, Seed(0)).unwrap();
    let e = discrepancy::compute(&Metric::parse("star").unwrap(), &big, Limits::default()).unwrap_err();
    assert!(matches!(e, samplab::Error::WorkLimit { limit: 2e10, .. }), "{e}");
    let five = sampler::build("random").unwrap().generate(400, 5, Seed(0)).unwrap();
    let e = discrepancy::compute(&Metric::parse("star").unwrap(), &five, Limits { max_work: 1e5, ..Limits::default() })
        .unwrap_err();
    assert!(e.to_string().contains("over the work limit 1.0e5") && e.to_string().contains("5D"), "{e}");
    // a whole-number parameter past 2^53 stays exact (it used to be stored as an f64 and
    // run as 2^53)
    assert_eq!(
        Metric::parse("star-bound:seed=9007199254740993").unwrap().spec(),
        "star-bound:iterations=20000,seed=9007199254740993"
    );
    let e = Metric::parse("stra").unwrap_err().to_string();
    assert!(e.contains("star"), "{e}");
    let e = Metric::parse("projected:angle=400").unwrap_err().to_string();
    assert!(e.contains("'angle'"), "{e}");
}

#[test]
fn threshold_accepting_is_a_lower_bound_and_usually_finds_the_maximum() {
    use samplab::discrepancy::bound::star_lower_bound;
    let mut rng = Seed(8).rng();
    let (mut exact_hits, mut trials) = (0, 0);
    for d in [2usize, 3, 4] {
        for t in 0..40 {
            let n = 5 + below(&mut rng, 20) as usize;
            let p: Vec<f64> = (0..n * d).map(|_| uniform(&mut rng)).collect();
            let exact = star::star_exact(&p, d, SILENT).unwrap();
            let lb = star_lower_bound(&p, d, 4000, Seed(t));
            assert!(lb <= exact + 1e-12, "{d}D: bound {lb} above exact {exact}");
            assert!(lb >= 0.8 * exact, "{d}D: bound {lb} far below exact {exact}");
            exact_hits += usize::from((lb - exact).abs() < 1e-12);
            trials += 1;
        }
    }
    assert!(exact_hits * 10 >= trials * 7, "the search found the exact value in only {exact_hits} of {trials}");
    // high dimension, where no exact algorithm runs: deterministic for a seed, and above the
    // trivial bound max_i (1 - prod x_i ...) given by any single critical box
    let set = sampler::build("sobol.owen").unwrap().generate(256, 10, Seed(1)).unwrap();
    let m = |s: u64| {
        let metric = Metric::parse(&format!("star-bound:iterations=3000,seed={s}")).unwrap();
        discrepancy::compute(&metric, &set, Limits::default()).unwrap()
    };
    assert_eq!(m(1).to_bits(), m(1).to_bits());
    assert!(m(1) > 0.0 && m(1) < 1.0);
}

/// Past the double range of a product of d factors, the L2 forms are summed from
/// logarithms: the values agree with the plain products where both apply, match closed
/// forms of one-point sets at thousands of dimensions, and a value beyond the double range
/// is an error, never 0.
#[test]
fn l2_forms_in_thousands_of_dimensions() {
    let forms = [
        ("l2-star", l2::STAR),
        ("l2-extreme", l2::EXTREME),
        ("centered", l2::CENTERED),
        ("wraparound", l2::WRAPAROUND),
        ("mixture", l2::MIXTURE),
        ("diaphony", l2::DIAPHONY),
    ];
    // the scaled sums against the plain ones, at 60 dimensions
    let set = sampler::build("random").unwrap().generate(40, 60, Seed(3)).unwrap();
    for (name, form) in forms {
        let plain = form.squared(set.as_slice(), 60, SILENT).unwrap();
        let (bracket, log) = form.squared_scaled(set.as_slice(), 60, SILENT).unwrap();
        let scaled = bracket * log.exp();
        assert!((plain - scaled).abs() <= 1e-9 * plain.abs(), "{name}: {plain} vs {scaled}");
    }
    let value = |name: &str, point: &[f64]| {
        let set = PointSet::new(point.len(), point.to_vec()).unwrap();
        discrepancy::compute(&Metric::parse(name).unwrap(), &set, Limits::default())
    };
    // one point at the origin: wrap-around D^2 = 1.5^d - (4/3)^d
    let d = 1800;
    let exact = (0.5 * d as f64 * 1.5f64.ln() + 0.5 * (1.0 - (8.0f64 / 9.0).powi(d)).ln()).exp();
    let wd = value("wraparound", &vec![0.0; d as usize]).unwrap();
    assert!((wd - exact).abs() < 1e-12 * exact, "{wd} vs {exact}");
    assert!(wd > 1e158);
    // one point at the centre: centered D^2 = (13/12)^d - 2 + 1
    let d = 4000;
    let exact = (0.5 * d as f64 * (13.0f64 / 12.0).ln()).exp();
    let cd = value("centered", &vec![0.5; d]).unwrap();
    assert!((cd - exact).abs() < 1e-12 * exact, "{cd} vs {exact}");
    // one point at the origin: L2-star D^2 = 3^-d - 2^(1-d) + 1, whose root is 1
    let star = value("l2-star", &vec![0.0; 3000]).unwrap();
    assert!((star - 1.0).abs() < 1e-12, "{star}");
    // one point at (1, ..., 1): L2-star D^2 = 3^-d, below the double range at d = 1500
    let err = value("l2-star", &vec![1.0; 1500]).unwrap_err().to_string();
    assert!(err.contains("10^-357.8") && err.contains("outside the double-precision range"), "{err}");
}

/// The long exact computations stop soon after their stop flag is raised, with
/// `Interrupted` (no value). Whole, the extreme discrepancy of these Hammersley points took
/// more than 30 s on two threads; the others are 5 x 10^11 to 2 x 10^13 steps.
#[test]
fn long_exact_computations_stop_when_told() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, Mutex};
    use std::time::Duration;
    // the work is measured in CPU seconds of the pool that runs it (the clocks of its own
    // threads), not in wall time: a loaded machine stretches the one, not the other
    let clocks: Arc<Mutex<Vec<libc::clockid_t>>> = Arc::default();
    let pool = {
        let clocks = Arc::clone(&clocks);
        rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .start_handler(move |_| {
                let mut id: libc::clockid_t = 0;
                // SAFETY: the clock of the calling thread, written to a local.
                assert_eq!(unsafe { libc::pthread_getcpuclockid(libc::pthread_self(), &raw mut id) }, 0);
                clocks.lock().unwrap().push(id);
            })
            .build()
            .unwrap()
    };
    let cpu = || -> f64 {
        clocks
            .lock()
            .unwrap()
            .iter()
            .map(|&id| {
                let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
                // SAFETY: a clock of a thread of the pool, which lives as long as the pool.
                assert_eq!(unsafe { libc::clock_gettime(id, &raw mut t) }, 0);
                t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
            })
            .sum()
    };
    let set = |spec: &str, n: usize, d: usize| sampler::build(spec).unwrap().generate(n, d, Seed(3)).unwrap();
    for (metric, points) in [
        // the Hammersley set is the branch and bound's worst case (22 s at 4096 points)
        ("extreme", set("hammersley", 8192, 2)),
        ("star", set("random", 2000, 6)),
        // the 2D sweep: 13.5 s to the end for 3 x 10^6 points on two threads (release,
        // 2026-12-01); stopped in its setup (the sort and the trees) or in the sweep
        ("star", set("random", 4_000_000, 2)),
        ("l2-star", set("random", 400_000, 3)),
        ("centered", set("random", 100_000, 80)),
    ] {
        for wait in [0, 300, 800] {
            let stop = AtomicBool::new(false);
            let limits = Limits { max_work: f64::INFINITY, ..Limits::default() }.stopped_by(Progress::until(&stop));
            let at_stop = Mutex::new(0.0);
            let got = std::thread::scope(|scope| {
                scope.spawn(|| {
                    std::thread::sleep(Duration::from_millis(wait));
                    *at_stop.lock().unwrap() = cpu();
                    stop.store(true, Ordering::Relaxed);
                });
                pool.install(|| discrepancy::compute(&Metric::parse(metric).unwrap(), &points, limits))
            });
            assert_eq!(got, Err(samplab::Error::Interrupted), "{metric}");
            let after = cpu() - *at_stop.lock().unwrap();
            assert!(after < STOPPED_WITHIN, "{metric}, stopped at {wait} ms: {after:.2} CPU seconds after the stop");
        }
    }
}

/// The CPU seconds (of two threads, in the test profile) that a computation may take after
/// its stop flag is raised. The longest stretch between two looks at the flag is a stage of
/// the 2D sweep's setup for 4 x 10^6 points: at most 0.45 CPU s with stops every 100 ms
/// from 0 to 1.5 s (2-core Xeon, 2026-12-07), where it was 2.1 (3.5 on CI's machine) before
/// the binary search per point gave way to ranks from the sort by y.
const STOPPED_WITHIN: f64 = 3.0;
