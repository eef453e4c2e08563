//! Spatial statistics against brute force over every pair, closed forms (packing radii, a
//! grid's PCF peak, white noise's PCF of 1) and the diaphony's Fourier definition.

use samplab::discrepancy::{self, Limits, Metric};
use samplab::progress::Progress;
use samplab::sampler::blue_noise::lloyd::{self, Cells};
use samplab::seed::{Rng, Seed, below, uniform};
use samplab::{PointSet, sampler, spatial};

/// Coordinates from a coarse lattice (ties, coincident points) mixed with uniform values,
/// 0 and 1.
fn nasty(rng: &mut Rng, n: usize, d: usize) -> PointSet {
    let levels = 1 + below(rng, 8);
    let data = (0..n * d)
        .map(|_| match below(rng, 6) {
            0 => 0.0,
            1 => 1.0,
            2 | 3 => below(rng, levels + 1) as f64 / levels as f64,
            _ => uniform(rng),
        })
        .collect();
    PointSet::new(d, data).unwrap()
}

/// The distance, on the torus as the difference less its nearest integer.
fn distance(a: &[f64], b: &[f64], torus: bool) -> f64 {
    let gaps = a.iter().zip(b).map(|(x, y)| if torus { (x - y) - (x - y).round() } else { x - y });
    gaps.map(|t| t * t).sum::<f64>().sqrt()
}

/// Every pair's distance, i < j.
fn all_distances(p: &PointSet, torus: bool) -> Vec<f64> {
    let mut out = Vec::new();
    for i in 0..p.len() {
        for j in i + 1..p.len() {
            out.push(distance(p.point(i), p.point(j), torus));
        }
    }
    out
}

fn random_set(n: usize, d: usize, seed: u64) -> PointSet {
    sampler::build("random").unwrap().generate(n, d, Seed(seed)).unwrap()
}

#[test]
fn min_distance_equals_brute_force() {
    let mut rng = Seed(3).rng();
    for trial in 0..800 {
        let d = 1 + below(&mut rng, 5) as usize;
        let n = 2 + below(&mut rng, 300) as usize;
        let p = if trial % 2 == 0 { nasty(&mut rng, n, d) } else { random_set(n, d, trial) };
        for torus in [true, false] {
            let want = all_distances(&p, torus).into_iter().fold(f64::INFINITY, f64::min);
            assert_eq!(spatial::min_distance(&p, torus), want, "trial {trial}, {n} points in {d}D, torus {torus}");
        }
    }
    // clustered: every point but two on a coarse grid, those two very close (rings grow)
    let mut data: Vec<f64> =
        (0..100).flat_map(|i| [(i % 10) as f64 / 10.0 + 0.05, (i / 10) as f64 / 10.0 + 0.05]).collect();
    data.extend([0.5, 0.5, 0.5 + 1e-9, 0.5]);
    let p = PointSet::new(2, data).unwrap();
    assert!((spatial::min_distance(&p, true) - 1e-9).abs() < 1e-15);
    assert_eq!(spatial::min_distance(&random_set(1, 2, 0), true), f64::INFINITY);
}

#[test]
fn packing_radii_are_the_known_packings() {
    // 2D hexagonal: sqrt(1 / (2 sqrt 3 n)); 3D face-centred cubic: (1 / (4 sqrt 2 n))^(1/3);
    // 1D: 1 / (2n)
    for n in [1usize, 7, 1000] {
        let n_f = n as f64;
        let close = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-14;
        assert!(close(spatial::packing_radius(n, 1).unwrap(), 0.5 / n_f));
        assert!(close(spatial::packing_radius(n, 2).unwrap(), (1.0 / (2.0 * 3f64.sqrt() * n_f)).sqrt()));
        assert!(close(spatial::packing_radius(n, 3).unwrap(), (1.0 / (4.0 * 2f64.sqrt() * n_f)).cbrt()));
    }
    assert!(spatial::packing_radius(10, 9).is_err());
    // a hexagonal arrangement that tiles the torus (k columns, 2m rows, spacing ratio close
    // to sqrt 3 / 2) is within a few percent of the packing; white noise far from it
    let hex = sampler::build("hexagonal").unwrap().generate(32 * 2 * 18, 2, Seed(1)).unwrap();
    let rho = spatial::relative_radius(&hex).unwrap();
    assert!((0.97..=1.0).contains(&rho), "hexagonal: {rho}");
    let rho = spatial::relative_radius(&random_set(1152, 2, 1)).unwrap();
    assert!(rho < 0.1, "white noise: {rho}");
}

/// The Gaussian-kernel PCF over every ordered pair, by its definition.
fn pcf_brute(p: &PointSet, r: f64, sigma: f64) -> f64 {
    let n = p.len() as f64;
    let surface = p.dims() as f64 * spatial::unit_ball_volume(p.dims());
    let sum: f64 = all_distances(p, true).iter().map(|&d| (-((r - d) / sigma).powi(2)).exp()).sum();
    2.0 * sum / (std::f64::consts::PI.sqrt() * sigma) / (n * (n - 1.0) * surface * r.powi(p.dims() as i32 - 1))
}

#[test]
fn pcf_and_rdf_equal_their_definitions() {
    let mut rng = Seed(4).rng();
    for trial in 0..60 {
        let d = 1 + below(&mut rng, 3) as usize;
        let n = 2 + below(&mut rng, 400) as usize;
        let p = match trial % 3 {
            0 => nasty(&mut rng, n, d),
            1 => random_set(n, d, trial),
            // piles of equal points (each pile once, with its count, in the fast sum)
            _ => {
                let few = random_set(1 + n / 10, d, trial);
                let picks = (0..n).flat_map(|_| few.point(below(&mut rng, few.len() as u64) as usize).to_vec());
                PointSet::new(d, picks.collect()).unwrap()
            }
        };
        let sigma = 0.002 + 0.05 * uniform(&mut rng);
        // evenly spaced radii (the kernel by a recurrence) and uneven ones
        let even: Vec<f64> = (1..=40).map(|i| i as f64 * 0.0125).collect();
        let uneven: Vec<f64> = (1..=20).map(|i| 0.5 * (i as f64 / 20.0).powi(2)).collect();
        for radii in [even, uneven] {
            let fast = spatial::pcf(&p, &radii, sigma).unwrap();
            for (&r, &g) in radii.iter().zip(&fast) {
                let want = pcf_brute(&p, r, sigma);
                assert!((g - want).abs() <= 1e-12 * want.max(1.0), "trial {trial}: r = {r}: {g} vs {want}");
            }
        }
        let edges: Vec<f64> = (0..=25).map(|i| i as f64 * 0.02).collect();
        let fast = spatial::rdf(&p, &edges).unwrap();
        let distances = all_distances(&p, true);
        let ball = spatial::unit_ball_volume(d);
        for (b, w) in edges.windows(2).enumerate() {
            let count = distances.iter().filter(|&&x| w[0] <= x && x < w[1]).count() as f64;
            let want = 2.0 * count / (n as f64 * (n as f64 - 1.0) * ball * (w[1].powi(d as i32) - w[0].powi(d as i32)));
            assert!((fast[b] - want).abs() <= 1e-12 * want.max(1.0), "trial {trial}: shell {b}");
        }
    }
    let p = random_set(10, 2, 0);
    assert!(spatial::pcf(&p, &[0.6], 0.01).is_err());
    assert!(spatial::pcf(&p, &[0.2, 0.1], 0.01).is_err());
    assert!(spatial::pcf(&p, &[0.1], 0.0).is_err());
}

/// Failure probability: 6.3e-5 for each of the 20 radii at 4 standard errors (two-sided
/// normal tail; each mean is over 40 independent sets), 1.3e-3 for the test; the grid half
/// is a closed form to 1e-12. Fixed seeds. Least work: the criterion scales with the
/// standard error, so the 40 sets of 2000 points (2.6 s with the grid, 2026-12-06) buy
/// power against a biased estimator, not a lower failure probability.
#[test]
fn white_noise_has_pcf_one_and_a_grid_peaks_at_its_spacing() {
    // white noise: the estimator is unbiased for r > 3 sigma (exactly in 2D); the mean of
    // 40 sets of 2000 points within 4 standard errors of 1
    let radii: Vec<f64> = (1..=20).map(|i| 0.02 * i as f64).collect();
    let sets: Vec<Vec<f64>> = (0..40).map(|s| spatial::pcf(&random_set(2000, 2, s), &radii, 0.005).unwrap()).collect();
    for (b, &r) in radii.iter().enumerate() {
        let v: Vec<f64> = sets.iter().map(|g| g[b]).collect();
        let s = samplab::stats::Summary::of(&v);
        assert!((s.mean - 1.0).abs() <= 4.0 * s.standard_error(), "r = {r}: {} +- {}", s.mean, s.standard_error());
    }
    // a k x k grid: each point has 4 neighbours at h = 1/k and the next shell is at sqrt(2) h,
    // so with sigma = h / 20 g(h) = 4 / ((n - 1) sqrt(pi) sigma 2 pi h) (to e^-68)
    let k = 32usize;
    let grid = sampler::build("regular").unwrap().generate(k * k, 2, Seed(0)).unwrap();
    let (h, n) = (1.0 / k as f64, (k * k) as f64);
    let sigma = h / 20.0;
    let g = spatial::pcf(&grid, &[h, 1.2 * h], sigma).unwrap();
    let want = 4.0 / ((n - 1.0) * std::f64::consts::PI.sqrt() * sigma * 2.0 * std::f64::consts::PI * h);
    assert!((g[0] / want - 1.0).abs() < 1e-12, "{} vs {want}", g[0]);
    assert!(g[1] < 1e-6 * g[0], "between the shells: {}", g[1]);
}

#[test]
fn spacing_metrics_go_through_the_registry() {
    let grid = sampler::build("regular").unwrap().generate(256, 2, Seed(0)).unwrap();
    let m = |spec: &str| discrepancy::compute(&Metric::parse(spec).unwrap(), &grid, Limits::default()).unwrap();
    assert!((m("min-distance") - 1.0 / 16.0).abs() < 1e-15);
    let r_max = spatial::packing_radius(256, 2).unwrap();
    assert!((m("relative-radius") - 1.0 / 32.0 / r_max).abs() < 1e-12);
    // a grid's highest PCF value is near its spacing h = 1/16, the closed form of the 4
    // neighbours there for the default sigma = d_max / 8 (the peak of exp(-(r - h)^2 / sigma^2)
    // / r lies a little below h and a little higher); its RDF's highest shell holds them too
    let (h, sigma) = (1.0 / 16.0, 2.0 * r_max / 8.0);
    let peak = 4.0 / (255.0 * std::f64::consts::PI.sqrt() * sigma * 2.0 * std::f64::consts::PI * h);
    assert!((1.0..1.02).contains(&(m("pcf") / peak)), "{} vs {peak}", m("pcf"));
    // the RDF in the default shell (width d_max / 10) around h holds those 4 neighbours alone
    let (lo, hi) = (h - 0.1 * r_max, h + 0.1 * r_max);
    let shell = 4.0 / (255.0 * std::f64::consts::PI * (hi * hi - lo * lo));
    let spec = format!("rdf:r={}", h / (2.0 * r_max));
    let at_h = discrepancy::compute(&Metric::parse(&spec).unwrap(), &grid, Limits::default()).unwrap();
    assert!((at_h / shell - 1.0).abs() < 1e-12, "{at_h} vs {shell}");
    assert!(m("rdf") > 2.0, "{}", m("rdf"));
    // the grid's periodogram is zero inside |k| < 16 = sqrt(n) and n on the reciprocal lattice
    assert!((m("nyquist") - 1.0).abs() < 1e-12 && (m("effective-nyquist") - 1.0).abs() < 1e-12);
    let noise = random_set(4096, 2, 2);
    let g = discrepancy::compute(&Metric::parse("pcf:r=2").unwrap(), &noise, Limits::default()).unwrap();
    assert!((g - 1.0).abs() < 0.1, "white noise at 2 d_max: {g}");
}

#[test]
fn diaphony_is_its_fourier_sum_and_a_lattice_s_p2() {
    // the Fourier definition, truncated at |h_k| <= H: the tail sum_(|h| > H) 1/h^2 < 2/H
    // per axis bounds the gap
    let mut rng = Seed(6).rng();
    let form = |p: &PointSet| discrepancy::l2::DIAPHONY.squared(p.as_slice(), p.dims(), Progress::SILENT).unwrap();
    for trial in 0..5 {
        let n = 1 + below(&mut rng, 12) as usize;
        let p = nasty(&mut rng, n, 2);
        let h_max = 300i64;
        let mut sum = 0.0;
        for h1 in -h_max..=h_max {
            for h2 in -h_max..=h_max {
                if (h1, h2) == (0, 0) {
                    continue;
                }
                let (mut re, mut im) = (0.0, 0.0);
                for q in p.iter() {
                    let a = 2.0 * std::f64::consts::PI * (h1 as f64 * q[0] + h2 as f64 * q[1]);
                    re += a.cos();
                    im += a.sin();
                }
                let n = p.len() as f64;
                sum += (re * re + im * im) / (n * n) / ((h1.abs().max(1) * h2.abs().max(1)) as f64).powi(2);
            }
        }
        let bound = 2.0 * (2.0 / h_max as f64) * (1.0 + std::f64::consts::PI.powi(2) / 3.0);
        assert!((form(&p) - sum).abs() <= bound, "trial {trial}: {} vs {sum}", form(&p));
    }
    // a rank-1 lattice's diaphony^2 is its worst-case error P_2 (a sum over n, not n^2)
    for (n, z) in [(89usize, vec![1u64, 55]), (101, vec![1, 40, 85]), (64, vec![1, 19])] {
        let points: Vec<f64> =
            (0..n as u64).flat_map(|i| z.iter().map(move |&zj| (i * zj % n as u64) as f64 / n as f64)).collect();
        let p = PointSet::new(z.len(), points).unwrap();
        let p2 = samplab::sampler::qmc::lattice::p2(&z, n);
        assert!((form(&p) - p2).abs() <= 1e-12 * p2, "n = {n}: {} vs {p2}", form(&p));
    }
}

/// The place in `alive` of the heaviest point of `alive` for which `within` holds (ties:
/// the lower index), every weight summed over every pair with the other points of `alive`.
fn heaviest(
    points: &[f64],
    dims: usize,
    alive: &[usize],
    (r_min, r_max): (f64, f64),
    torus: bool,
    within: impl Fn(usize) -> bool,
) -> usize {
    let point = |i: usize| &points[i * dims..(i + 1) * dims];
    let weight = |i: usize| -> u64 {
        alive
            .iter()
            .filter(|&&j| j != i)
            .map(|&j| distance(point(i), point(j), torus))
            .filter(|&d| d < 2.0 * r_max)
            .map(|d| samplab::sampler::blue_noise::elimination::pair_weight(d, r_min, 2.0 * r_max))
            .sum()
    };
    let (k, _) = alive.iter().enumerate().filter(|&(_, &i)| within(i)).fold((0, None), |best, (k, &i)| {
        let w = weight(i);
        if best.1.is_none_or(|b| w > b) { (k, Some(w)) } else { best }
    });
    k
}

/// Yuksel's r_min and r_max for m candidates and `target` survivors.
fn radii(m: usize, dims: usize, target: usize) -> (f64, f64) {
    let r_max = spatial::packing_radius(target, dims).unwrap();
    (r_max * (1.0 - (target as f64 / m as f64).powf(1.5)) * 0.65, r_max)
}

/// Sample elimination by its definition: every step recomputes every remaining point's
/// weight over all pairs and removes the largest (ties: the lower index).
fn eliminate_naive(points: &[f64], dims: usize, target: usize) -> Vec<usize> {
    let m = points.len() / dims;
    let mut alive: Vec<usize> = (0..m).collect();
    let mut gone = Vec::new();
    while alive.len() > target {
        let k = heaviest(points, dims, &alive, radii(m, dims, target), true, |_| true);
        gone.push(alive.remove(k));
    }
    gone
}

/// The tiled elimination by its definition (the `elimination` module's docs): `tiles` per
/// axis, each with its quota of the survivors (equal shares capped by its candidates, one
/// more to the tiles with room, most candidates first); in round r, the colours (the
/// parities of a tile's coordinates, as a number c) in the order c = r, r + 1, ... mod 2^d,
/// and the tiles of each colour one after the other in index order, each
/// removing its heaviest point (every weight recomputed over all remaining points) until
/// it is down to its share of the round.
fn eliminate_tiled_naive(points: &[f64], dims: usize, target: usize, torus: bool, tiles: usize) -> Vec<usize> {
    use samplab::sampler::blue_noise::elimination::ROUNDS;
    let m = points.len() / dims;
    let tile = |i: usize| {
        (0..dims).rev().fold(0, |t, a| t * tiles + ((points[i * dims + a] * tiles as f64) as usize).min(tiles - 1))
    };
    let count = tiles.pow(dims as u32);
    let colour = |t: usize| (0..dims).map(|a| (t / tiles.pow(a as u32) % 2) << a).sum::<usize>();
    let counts: Vec<usize> = (0..count).map(|t| (0..m).filter(|&i| tile(i) == t).count()).collect();
    let mut level = 0;
    while counts.iter().map(|&c| c.min(level + 1)).sum::<usize>() <= target {
        level += 1;
    }
    let mut quota: Vec<usize> = counts.iter().map(|&c| c.min(level)).collect();
    let mut room: Vec<usize> = (0..count).filter(|&t| counts[t] > level).collect();
    room.sort_by_key(|&t| (std::cmp::Reverse(counts[t]), t));
    let spare = target - quota.iter().sum::<usize>();
    for &t in &room[..spare] {
        quota[t] += 1;
    }
    let mut alive: Vec<usize> = (0..m).collect();
    let mut gone = Vec::new();
    for round in 1..=ROUNDS {
        for turn in 0..1 << dims {
            let hue = (round + turn) % (1 << dims);
            for t in (0..count).filter(|&t| colour(t) == hue) {
                let share = quota[t] + (counts[t] - quota[t]) * (ROUNDS - round) / ROUNDS;
                while alive.iter().filter(|&&i| tile(i) == t).count() > share {
                    let k = heaviest(points, dims, &alive, radii(m, dims, target), torus, |i| tile(i) == t);
                    gone.push(alive.remove(k));
                }
            }
        }
    }
    gone
}

#[test]
fn sample_elimination_removes_the_heaviest_point_each_step() {
    // weights in fixed point: the same sums whatever their order, so the orders agree
    // exactly, ties (clamped pairs, isolated points) included
    let mut rng = Seed(8).rng();
    for trial in 0..30 {
        let dims = 1 + trial % 3;
        let target = 4 + below(&mut rng, 40) as usize;
        let m = target * (2 + below(&mut rng, 5) as usize);
        let points: Vec<f64> = (0..m * dims).map(|_| uniform(&mut rng)).collect();
        let (kept, gone) = samplab::sampler::blue_noise::elimination::eliminate(&points, dims, target, true).unwrap();
        assert_eq!(gone, eliminate_naive(&points, dims, target), "trial {trial}: {m} to {target} in {dims}D");
        assert_eq!(kept.len(), target);
    }
}

/// Sample elimination by one heap with stale entries skipped (an independent serial
/// reference for sets too large for [`eliminate_naive`]): the removals in order.
fn eliminate_by_heap(points: &[f64], dims: usize, target: usize, torus: bool) -> Vec<usize> {
    use std::cmp::Reverse;
    let m = points.len() / dims;
    let (r_min, r_max) = radii(m, dims, target);
    let point = |i: usize| &points[i * dims..(i + 1) * dims];
    // every pair once, listed on both sides, each list in increasing j
    let mut near: Vec<Vec<(usize, u64)>> = vec![Vec::new(); m];
    for i in 0..m {
        for j in i + 1..m {
            let d = distance(point(i), point(j), torus);
            if d < 2.0 * r_max {
                let w = samplab::sampler::blue_noise::elimination::pair_weight(d, r_min, 2.0 * r_max);
                near[i].push((j, w));
                near[j].push((i, w));
            }
        }
    }
    let mut weight: Vec<u64> = near.iter().map(|list| list.iter().map(|&(_, w)| w).sum()).collect();
    let mut heap: std::collections::BinaryHeap<(u64, Reverse<usize>)> =
        (0..m).map(|i| (weight[i], Reverse(i))).collect();
    let mut alive = vec![true; m];
    let mut gone = Vec::new();
    while gone.len() < m - target {
        let (w, Reverse(i)) = heap.pop().unwrap();
        if alive[i] && w == weight[i] {
            alive[i] = false;
            gone.push(i);
            for &(j, wj) in &near[i] {
                if alive[j] {
                    weight[j] -= wj;
                    heap.push((weight[j], Reverse(j)));
                }
            }
        }
    }
    gone
}

#[test]
fn sample_elimination_of_many_points_follows_one_heap() {
    // over 2 x 8192 candidates, each batch's threshold comes from a sample of the live
    // points (and the last batch may remove more than needed): the order must still be
    // one heap's
    for (dims, m, target, torus) in [(2, 21_000, 18_000, true), (2, 20_000, 2500, false), (3, 18_000, 9000, true)] {
        let mut rng = Seed(m as u64).rng();
        let points: Vec<f64> = (0..m * dims).map(|_| uniform(&mut rng)).collect();
        let (kept, gone) = samplab::sampler::blue_noise::elimination::eliminate(&points, dims, target, torus).unwrap();
        assert!(gone == eliminate_by_heap(&points, dims, target, torus), "{m} to {target} in {dims}D");
        let mut all: Vec<usize> = kept.iter().chain(&gone).copied().collect();
        all.sort_unstable();
        assert!(all.iter().copied().eq(0..m) && kept.len() == target, "{m} to {target} in {dims}D");
    }
}

#[test]
fn tiled_elimination_follows_its_definition() {
    // the same removals in the same order as the definition run one tile at a time: tiles
    // of one colour share no pair, so running them side by side changes nothing
    let mut rng = Seed(9).rng();
    for trial in 0..12 {
        let dims = 1 + trial % 3;
        let tiles = if dims == 3 { 2 } else { 2 + 2 * (trial % 2) };
        let torus = trial % 4 < 2;
        let target = 40 + below(&mut rng, 40) as usize;
        let m = target * (2 + below(&mut rng, 4) as usize);
        let points: Vec<f64> = (0..m * dims).map(|_| uniform(&mut rng)).collect();
        // every tile at least d_max wide: the library keeps this many tiles
        assert!(1.0 / tiles as f64 >= 2.0 * spatial::packing_radius(target, dims).unwrap());
        let (kept, gone) =
            samplab::sampler::blue_noise::elimination::eliminate_in_tiles(&points, dims, target, torus, tiles).unwrap();
        let naive = eliminate_tiled_naive(&points, dims, target, torus, tiles);
        assert_eq!(gone, naive, "trial {trial}: {m} to {target} in {dims}D, {tiles} tiles per axis");
        assert_eq!(kept.len(), target);
    }
}

#[test]
fn parallel_constructions_are_the_same_on_any_thread_count() {
    for (name, n) in
        [("elimination", 20_000), ("elimination.tiled", 20_000), ("ccvt:iterations=5", 2000), ("poisson.maximal", 1000)]
    {
        let set = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| sampler::build(name).unwrap().generate(n, 2, Seed(4)).unwrap())
        };
        let one = set(1);
        for threads in [2, 3, 8] {
            assert!(one.as_slice() == set(threads).as_slice(), "{name} on {threads} threads");
        }
    }
}

#[test]
fn eliminated_sets_and_their_prefixes_are_blue_noise() {
    // every prefix of n / 2^k points is a stage's survivors: spread far beyond white noise
    // (whose relative radius at these n is about 0.02-0.1) and above 0.5
    // (the tiled variant in 4 tiles per axis at 4096 points)
    let n = 4096;
    for name in ["elimination", "elimination.tiled"] {
        let set = sampler::build(name).unwrap().generate(n, 2, Seed(5)).unwrap();
        for k in [4096usize, 1024, 256, 64] {
            let prefix = PointSet::new(2, set.as_slice()[..2 * k].to_vec()).unwrap();
            let rho = spatial::relative_radius(&prefix).unwrap();
            assert!(rho > 0.5, "{name}, first {k}: relative radius {rho}");
        }
        // its low frequencies: the PCF below half the packing distance is near 0 (no close
        // pairs)
        let d_max = 2.0 * spatial::packing_radius(n, 2).unwrap();
        let g = spatial::pcf(&set, &[0.4 * d_max], 0.05 * d_max).unwrap();
        assert!(g[0] < 0.05, "{name}: PCF at 0.4 d_max: {}", g[0]);
    }
}

/// Voronoi centroids and the quantization energy sum_i integral_(cell i) |x - p_i|^2 by
/// quadrature: the midpoints of a g x g grid, each given to its nearest point by brute force.
fn voronoi_by_quadrature(points: &[f64], torus: bool, g: usize) -> (Vec<f64>, f64) {
    let n = points.len() / 2;
    let (mut sum, mut count, mut energy) = (vec![0.0; 2 * n], vec![0.0; n], 0.0);
    for a in 0..g {
        for b in 0..g {
            let x = [(a as f64 + 0.5) / g as f64, (b as f64 + 0.5) / g as f64];
            let offset = |i: usize, k: usize| {
                let t = x[k] - points[2 * i + k];
                if torus { t - t.round() } else { t }
            };
            let d2 = |i: usize| offset(i, 0).powi(2) + offset(i, 1).powi(2);
            let best = (0..n).min_by(|&i, &j| d2(i).total_cmp(&d2(j))).unwrap();
            sum[2 * best] += offset(best, 0);
            sum[2 * best + 1] += offset(best, 1);
            count[best] += 1.0;
            energy += d2(best);
        }
    }
    let centroids = (0..2 * n).map(|k| points[k] + sum[k] / count[k / 2]).collect();
    (centroids, energy / (g * g) as f64)
}

#[test]
fn lloyd_moves_points_to_their_cells_centroids_and_lowers_the_energy() {
    for torus in [true, false] {
        for (n, seed) in [(1usize, 1u64), (2, 2), (5, 3), (40, 4)] {
            let p = random_set(n, 2, seed);
            let ours = lloyd::centroids(p.as_slice(), torus, Cells::Delaunay).unwrap();
            let (want, _) = voronoi_by_quadrature(p.as_slice(), torus, 600);
            for (k, (a, b)) in ours.iter().zip(&want).enumerate() {
                let gap = if torus { (a - b) - (a - b).round() } else { a - b };
                assert!(gap.abs() < 2e-3, "torus {torus}, n = {n}, coordinate {k}: {a} vs {b}");
            }
        }
        // each step lowers the energy (Lloyd's descent), here by far more than the quadrature's error
        let mut points = random_set(32, 2, 9).as_slice().to_vec();
        let mut last = voronoi_by_quadrature(&points, torus, 300).1;
        for step in 0..6 {
            points = lloyd::centroids(&points, torus, Cells::Delaunay).unwrap();
            let e = voronoi_by_quadrature(&points, torus, 300).1;
            assert!(e < last, "torus {torus}, step {step}: energy {e} after {last}");
            last = e;
        }
    }
    // relaxed sets are well spread: relative radius above dart throwing's usual 0.7
    let set = sampler::build("lloyd").unwrap().generate(1024, 2, Seed(3)).unwrap();
    let rho = spatial::relative_radius(&set).unwrap();
    assert!(rho > 0.7, "lloyd: relative radius {rho}");
}

#[test]
fn clipped_cells_are_the_triangulation_s() {
    // each cell clipped on its own gives the triangulation's centroids to rounding, on the
    // torus and in the square, for random sets (irregular cells, some needing wider rings)
    // and relaxed ones, and for sets too small to clip (the fallback); whatever the threads
    for torus in [true, false] {
        for (n, seed) in [(3usize, 1u64), (17, 2), (300, 3), (5000, 4)] {
            let mut points = random_set(n, 2, seed).as_slice().to_vec();
            for step in 0..3 {
                let want = lloyd::centroids(&points, torus, Cells::Delaunay).unwrap();
                for threads in [1, 3] {
                    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                    let got = pool.install(|| lloyd::centroids(&points, torus, Cells::Clipped)).unwrap();
                    for (k, (a, b)) in got.iter().zip(&want).enumerate() {
                        let gap = if torus { (a - b) - (a - b).round() } else { a - b };
                        assert!(gap.abs() < 1e-12, "torus {torus}, n = {n}, step {step}, coordinate {k}: {a} vs {b}");
                    }
                }
                points = want;
            }
        }
    }
    // coincident points: an error either way
    let twice = [0.25, 0.5, 0.25, 0.5, 0.75, 0.75];
    assert!(lloyd::centroids(&twice, true, Cells::Clipped).is_err());
}

#[test]
fn projected_cube_quantiles_invert_their_cdf() {
    use samplab::sampler::blue_noise::sot::Projected;
    // 2D: the trapezoid's quantile in closed form (a <= b the two widths)
    let trapezoid = |a: f64, b: f64, u: f64| {
        let q = |v: f64| {
            if v <= a / (2.0 * b) {
                (2.0 * a * b * v).sqrt()
            } else if v <= 1.0 - a / (2.0 * b) {
                v * b + a / 2.0
            } else {
                a + b - (2.0 * a * b * (1.0 - v)).sqrt()
            }
        };
        q(u)
    };
    let mut rng = Seed(12).rng();
    for _ in 0..200 {
        let theta = [uniform(&mut rng) * 2.0 - 1.0, uniform(&mut rng) * 2.0 - 1.0];
        let (a, b) = (theta[0].abs().min(theta[1].abs()), theta[0].abs().max(theta[1].abs()));
        if a < 1e-3 * b {
            continue;
        }
        let shift: f64 = theta.iter().filter(|&&t| t < 0.0).sum();
        let p = Projected::new(&theta);
        for k in 1..100 {
            let u = k as f64 / 100.0;
            let (ours, want) = (p.quantile(u), shift + trapezoid(a, b, u));
            assert!((ours - want).abs() < 1e-12, "{theta:?} at {u}: {ours} vs {want}");
        }
    }
    // 3D to 5D: quantiles of 200000 draws of theta . U, within their sampling error
    for dims in 3..=5 {
        let theta: Vec<f64> = (0..dims).map(|k| if k % 2 == 0 { 0.3 + 0.1 * k as f64 } else { -0.5 }).collect();
        let mut draws: Vec<f64> =
            (0..200_000).map(|_| theta.iter().map(|t| t * uniform(&mut rng)).sum::<f64>()).collect();
        draws.sort_by(f64::total_cmp);
        let p = Projected::new(&theta);
        for k in 1..20 {
            let u = k as f64 / 20.0;
            let (ours, empirical) = (p.quantile(u), draws[(u * draws.len() as f64) as usize]);
            assert!((ours - empirical).abs() < 5e-3, "{dims}D at {u}: {ours} vs {empirical}");
        }
    }
}

#[test]
fn sliced_transport_lowers_the_sliced_distance() {
    use samplab::sampler::blue_noise::sot::sliced_distance2;
    // the distance SOT descends, measured along 64 directions it did not use, against the
    // a uniform random set of the same size (what it starts from)
    for dims in [2usize, 3] {
        let start = random_set(256, dims, 0).as_slice().to_vec();
        let start_sw = sliced_distance2(&start, dims, 64, Seed(77));
        let set = sampler::build("sot:iterations=100").unwrap().generate(256, dims, Seed(0)).unwrap();
        let end_sw = sliced_distance2(set.as_slice(), dims, 64, Seed(77));
        assert!(end_sw < start_sw / 10.0, "{dims}D: sliced distance^2 {end_sw} from {start_sw}");
    }
}

#[test]
fn gaussian_blue_noise_descends_its_energy() {
    use samplab::sampler::blue_noise::gbn;
    // one step against every pair's pull by brute force (the same 5 sigma reach)
    let (n, dims) = (300usize, 2usize);
    let start = random_set(n, dims, 21).as_slice().to_vec();
    let sigma = 0.5 / (n as f64).sqrt();
    let mut ours = start.clone();
    gbn::descend(&mut ours, dims, sigma, 0.5);
    for i in 0..n {
        let mut push = [0.0; 2];
        for j in (0..n).filter(|&j| j != i) {
            let offset: Vec<f64> = (0..dims)
                .map(|k| {
                    (start[i * dims + k] - start[j * dims + k]) - (start[i * dims + k] - start[j * dims + k]).round()
                })
                .collect();
            let d2: f64 = offset.iter().map(|t| t * t).sum();
            if d2 < (5.0 * sigma).powi(2) {
                for k in 0..dims {
                    push[k] += 0.5 * offset[k] * (-d2 / (2.0 * sigma * sigma)).exp();
                }
            }
        }
        for k in 0..dims {
            let want = start[i * dims + k] + push[k];
            let want = want - want.floor();
            let gap = (ours[i * dims + k] - want) - (ours[i * dims + k] - want).round();
            assert!(gap.abs() < 1e-14, "point {i}: {} vs {want}", ours[i * dims + k]);
        }
    }
    // the energy falls at every step, and the result is well spread
    for dims in [2usize, 3] {
        let mut points = random_set(512, dims, 5).as_slice().to_vec();
        let sigma = 0.5 * 512f64.powf(-1.0 / dims as f64);
        let mut last = gbn::energy(&points, dims, sigma);
        for step in 0..30 {
            gbn::descend(&mut points, dims, sigma, 0.5);
            let e = gbn::energy(&points, dims, sigma);
            assert!(e < last, "{dims}D step {step}: energy {e} after {last}");
            last = e;
        }
    }
    let set = sampler::build("gbn").unwrap().generate(1024, 2, Seed(2)).unwrap();
    let rho = spatial::relative_radius(&set).unwrap();
    assert!(rho > 0.7, "gbn: relative radius {rho}");
}

/// One CCVT iteration by its definition (the `ccvt` module's docs), one pair after
/// another: every pair of sites closer than 2 n^(-1/d) on the torus, in increasing order
/// (i, j), swaps the point of i gaining most by moving to j with the point of j gaining most
/// by moving to i while the two gains sum above zero (each swapped point taking the other's
/// place in its new site's list); then each site moves by the mean of its points' torus
/// offsets, summed in list order.
fn ccvt_iteration_naive(dims: usize, sites: &mut [f64], points: &[f64], members: &mut [Vec<usize>]) {
    let n = members.len();
    let site = |sites: &[f64], s: usize| sites[s * dims..(s + 1) * dims].to_vec();
    let point = |k: usize| &points[k * dims..(k + 1) * dims];
    let d2 = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| (x - y) - (x - y).round()).map(|t| t * t).sum::<f64>();
    let reach = 2.0 * (n as f64).powf(-1.0 / dims as f64);
    for i in 0..n {
        for j in i + 1..n {
            let (si, sj) = (site(sites, i), site(sites, j));
            if d2(&si, &sj) >= reach * reach {
                continue;
            }
            // (gain, slot) of each point of a moving to b, largest gain first
            let gains = |a: &[usize], from: &[f64], to: &[f64]| {
                let mut g: Vec<(f64, usize)> =
                    a.iter().enumerate().map(|(slot, &k)| (d2(point(k), from) - d2(point(k), to), slot)).collect();
                g.sort_by(|x, y| y.0.total_cmp(&x.0));
                g
            };
            let (from_i, from_j) = (gains(&members[i], &si, &sj), gains(&members[j], &sj, &si));
            for (&(gi, a), &(gj, b)) in from_i.iter().zip(&from_j) {
                if gi + gj <= 0.0 {
                    break;
                }
                let (ki, kj) = (members[i][a], members[j][b]);
                (members[i][a], members[j][b]) = (kj, ki);
            }
        }
    }
    for (s, list) in members.iter().enumerate() {
        let mut mean = vec![0.0; dims];
        for &k in list {
            for (axis, m) in mean.iter_mut().enumerate() {
                let gap = point(k)[axis] - sites[s * dims + axis];
                *m += gap - gap.round();
            }
        }
        for (axis, m) in mean.into_iter().enumerate() {
            let x = sites[s * dims + axis] + m / list.len() as f64;
            sites[s * dims + axis] = x - x.floor();
        }
    }
}

#[test]
fn ccvt_iterations_follow_the_definition_one_pair_after_another() {
    // the library swaps the pairs of many sites side by side: the sites must be those of
    // one pair after another, to the bit, on any number of threads (16 threads on a few
    // cores preempt the one that starts the first tasks: a version that scanned the
    // tasks' counts while the first tasks ran started some tasks twice)
    use samplab::sampler::blue_noise::ccvt::State;
    let mut rng = Seed(12).rng();
    for (dims, n, capacity) in [(2, 2000, 16), (3, 120, 8), (1, 50, 4)] {
        let sites: Vec<f64> = (0..n * dims).map(|_| uniform(&mut rng)).collect();
        let points: Vec<f64> = (0..n * capacity * dims).map(|_| uniform(&mut rng)).collect();
        let mut naive = sites.clone();
        let mut members: Vec<Vec<usize>> = (0..n).map(|s| (s * capacity..(s + 1) * capacity).collect()).collect();
        let mut states: Vec<_> = [1, 2, 16]
            .map(|threads| {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                (threads, pool, State::from_points(dims, sites.clone(), points.clone()))
            })
            .into_iter()
            .collect();
        for round in 0..10 {
            ccvt_iteration_naive(dims, &mut naive, &points, &mut members);
            for (threads, pool, state) in &mut states {
                pool.install(|| state.iterate());
                assert!(state.sites == naive, "{dims}D, {n} sites, {threads} threads: round {round}");
            }
        }
    }
}

#[test]
fn ccvt_keeps_capacities_and_lowers_its_energy() {
    use samplab::sampler::blue_noise::ccvt::State;
    for dims in [2usize, 3] {
        let mut state = State::new(64, dims, 32, Seed(4)).unwrap();
        let mut last = state.energy();
        for round in 0..15 {
            let swaps = state.iterate();
            let e = state.energy();
            assert!(state.counts().iter().all(|&c| c == 32), "{dims}D round {round}: capacities {:?}", state.counts());
            assert!(e < last || (swaps == 0 && e <= last), "{dims}D round {round}: energy {e} after {last}");
            last = e;
        }
    }
    let set = sampler::build("ccvt:capacity=128").unwrap().generate(512, 2, Seed(2)).unwrap();
    let rho = spatial::relative_radius(&set).unwrap();
    let noise = spatial::relative_radius(&random_set(512, 2, 2)).unwrap();
    assert!(rho > 0.5 && rho > 5.0 * noise, "ccvt: relative radius {rho} (white noise {noise})");
}

#[test]
fn step_and_single_peak_sets_have_the_spectra_they_target() {
    use samplab::spectrum::{Method, periodogram};
    // Heck et al.'s claims, measured on 2 sets of 1024 points: a step at nu = 0.564 sqrt(n)
    // gives an effective Nyquist frequency near nu and a flat spectrum past it (oscillation
    // under 0.7, white noise's floor being ~0.45 here, Lloyd's above 2); the peak moves the
    // zero region's edge out; both keep the low frequencies (|k| < nu sqrt(n) / 2) under a
    // tenth of white noise's power
    let metric = |spec: &str, set: &PointSet| {
        discrepancy::compute(&Metric::parse(spec).unwrap(), set, Limits::default()).unwrap()
    };
    let mut nyquist = Vec::new();
    for (spec, nu) in [("step", 0.564), ("single-peak", 0.8)] {
        let sampler = sampler::build(spec).unwrap();
        let (mut nu_eff, mut osc, mut low) = (0.0, 0.0, 0.0);
        for s in 0..2 {
            let set = sampler.generate(1024, 2, Seed(40 + s)).unwrap();
            nu_eff += metric("nyquist", &set) / 2.0;
            osc += metric("oscillation", &set) / 2.0;
            let res = 64;
            let p = periodogram(&set, res, Method::default()).unwrap();
            let (mut sum, mut count) = (0.0, 0);
            for (idx, v) in p.iter().enumerate() {
                let (i, j) = ((idx / res) as f64 - 32.0, (idx % res) as f64 - 32.0);
                let r = i.hypot(j);
                if r > 0.0 && r < nu * 32.0 / 2.0 {
                    sum += 1024.0 * v;
                    count += 1;
                }
            }
            low += sum / count as f64 / 2.0;
        }
        assert!((nu_eff - nu).abs() < 0.06, "{spec}: effective Nyquist {nu_eff} for a target at {nu}");
        assert!(low < 0.1, "{spec}: low-frequency power {low} of white noise's");
        if spec == "step" {
            assert!(osc < 0.7, "step: oscillation {osc}");
        }
        nyquist.push(nu_eff);
    }
    assert!(nyquist[1] > nyquist[0] + 0.1);
}

/// Failure probability: not computed in closed form (a correlated chain with the Euler
/// step's bias): the share's error was 4-12% at 10^5 to 4 x 10^5 steps against a criterion
/// of 20%, while a temperature halved or doubled moves the share by a factor of 19 or 4.4
/// (the comment below; 2026-11-30). Fixed seed. Least work: 10^5 steps, the fewest measured.
#[test]
fn kdm_langevin_steps_sample_the_gibbs_distribution() {
    use samplab::sampler::blue_noise::gbn;
    // two points on a circle: their gap d follows Langevin dynamics for E(d) = exp(-d^2 /
    // (2 sigma^2)) at temperature T, whose stationary density is exp(-E(d) / T); the share of
    // time spent at |d| < sigma against that density's, by quadrature (within 20%: this
    // chain's share is 8% above the density's after 10^5 steps, 4% after 2 x 10^5 and 12%
    // after 4 x 10^5, its statistical error and Euler's step bias, while halving or doubling
    // the temperature moves the density's share by a factor of 19 or 4.4; measured
    // 2026-11-30)
    let (sigma, t, step) = (0.1, 0.25, 0.1);
    let mut rng = Seed(9).rng();
    let mut points = vec![0.1, 0.6];
    let (mut near, total) = (0usize, 100_000usize);
    for _ in 0..total {
        gbn::langevin(&mut points, 1, sigma, step, t, &mut rng);
        let d = (points[0] - points[1]) - (points[0] - points[1]).round();
        near += usize::from(d.abs() < sigma);
    }
    let weight = |d: f64| (-(-d * d / (2.0 * sigma * sigma)).exp() / t).exp();
    let integral = |a: f64, b: f64| {
        let m = 20_000;
        (0..m).map(|i| weight(a + (i as f64 + 0.5) * (b - a) / m as f64)).sum::<f64>() * (b - a) / m as f64
    };
    let want = integral(-sigma, sigma) / integral(-0.5, 0.5);
    let got = near as f64 / total as f64;
    assert!((got / want - 1.0).abs() < 0.2, "share at |d| < sigma: {got} vs Gibbs {want}");
    // the model's limits: cold, the energy's minimum (regular: large relative radius, high
    // oscillation); hot, white noise; in between both fall as the temperature rises
    let kdm = |t: f64| {
        let set = sampler::build(&format!("kdm:temperature={t}")).unwrap().generate(1024, 2, Seed(4)).unwrap();
        let oscillation =
            discrepancy::compute(&Metric::parse("oscillation").unwrap(), &set, Limits::default()).unwrap();
        (spatial::relative_radius(&set).unwrap(), oscillation)
    };
    let runs: Vec<(f64, f64)> = [0.0, 0.02, 0.1, 100.0].into_iter().map(kdm).collect();
    assert!(
        runs.windows(2).all(|w| w[1].0 < w[0].0 && w[1].1 < w[0].1),
        "(relative radius, oscillation) by temperature: {runs:?}"
    );
    assert!(runs[0].0 > 0.7 && runs[3].0 < 0.3, "{runs:?}");
}

#[test]
fn pair_weights_are_the_rounded_definition() {
    // (1 - max(d, 2 r_min) / d_max)^8 in units of 2^-40, rounded half away from zero
    let mut rng = Seed(10).rng();
    let (r_min, d_max) = (0.013, 0.07);
    let mut ds: Vec<f64> = (0..100_000).map(|_| uniform(&mut rng) * d_max).collect();
    ds.extend([0.0, 2.0 * r_min, d_max, d_max * (1.0 - 1e-9)]);
    for d in ds {
        let exact = ((1.0 - d.max(2.0 * r_min) / d_max).powi(8) * (1u64 << 40) as f64).round() as u64;
        assert_eq!(samplab::sampler::blue_noise::elimination::pair_weight(d, r_min, d_max), exact, "d = {d}");
    }
}
