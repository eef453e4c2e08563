//! Structural tests for every sampler family (STYLE.md's table): stratification counts,
//! net properties, reference values from independent implementations, minimum distances,
//! and batch == random access.
//!
//! Every test here checks a property that holds for every draw (counts, distances, bits,
//! equality with a reference), so none has a failure probability; a randomized sampler is
//! drawn at fixed seeds only to make the case generic.

use samplab::construct::radical;
use samplab::sampler;
use samplab::{PointSet, Seed};

fn make(spec: &str, n: usize, d: usize, seed: u64) -> PointSet {
    sampler::build(spec).unwrap().generate(n, d, Seed(seed)).unwrap()
}

/// Every elementary interval of area 2^-m of base 2 in 2D holds exactly one point.
fn assert_02_net(points: &[f64], m: u32, what: &str) {
    assert_eq!(points.len(), 2 << m);
    for a in 0..=m {
        let (nx, ny) = (1usize << a, 1usize << (m - a));
        let mut count = vec![0u8; 1 << m];
        for p in points.chunks_exact(2) {
            let cx = (p[0] * nx as f64) as usize;
            let cy = (p[1] * ny as f64) as usize;
            count[cx * ny + cy] += 1;
        }
        assert!(count.iter().all(|&c| c == 1), "{what}: m = {m}, intervals {nx}x{ny} not stratified");
    }
}

#[test]
fn jitter_family_one_point_per_cell() {
    for spec in [
        "regular",
        "jitter",
        "jitter.half",
        "jitter.box:0.3",
        "jitter.uniform",
        "jitter.gaussian:sigma=0.1,edge=resample",
    ] {
        for (d, k) in [(1usize, 50usize), (2, 16), (3, 6)] {
            let n = k.pow(d as u32);
            let p = make(spec, n, d, 3);
            let mut seen = vec![false; n];
            let gaussian = spec.starts_with("jitter.gaussian");
            let mut outside = 0;
            for (i, x) in p.iter().enumerate() {
                let cell = x.iter().fold(0, |acc, &c| acc * k + (c * k as f64) as usize);
                if gaussian {
                    // a normal offset of 0.1 cells leaves the cell with probability ~ 1e-6 per axis
                    outside += usize::from(cell != i);
                    continue;
                }
                assert!(!seen[cell], "{spec} {d}D: two points in cell {cell}");
                seen[cell] = true;
            }
            assert!(outside <= 1, "{spec}: {outside} points left their cell");
        }
    }
}

#[test]
fn half_and_box_jitter_stay_in_their_boxes() {
    let k = 8.0;
    for (spec, delta) in [("jitter.half", 0.25), ("jitter.box:delta=0.1", 0.1)] {
        for x in make(spec, 64, 2, 9).as_slice() {
            let within = (x * k).fract() - 0.5;
            assert!(within.abs() <= delta + 1e-12, "{spec}: offset {within}");
        }
    }
}

#[test]
fn systematic_offsets_are_whole_grids_with_their_own_offsets() {
    // 4 offsets x 9 points in 2D: four 3 x 3 grids, one after the other, each a rigid
    // translate of the cell centres (one offset within the cell for all its points)
    let p = make("jitter.uniform:offsets=4", 36, 2, 5);
    let offset = |x: &[f64]| [(x[0] * 3.0).fract(), (x[1] * 3.0).fract()];
    let mut firsts = Vec::new();
    for block in p.as_slice().chunks_exact(18) {
        let o = offset(&block[..2]);
        let mut cells: Vec<usize> =
            block.chunks_exact(2).map(|x| (x[0] * 3.0) as usize * 3 + (x[1] * 3.0) as usize).collect();
        for x in block.chunks_exact(2) {
            let q = offset(x);
            assert!((q[0] - o[0]).abs() < 1e-12 && (q[1] - o[1]).abs() < 1e-12, "{q:?} vs {o:?}");
        }
        cells.sort_unstable();
        assert_eq!(cells, (0..9).collect::<Vec<_>>(), "one point per cell");
        firsts.push(o);
    }
    assert!(firsts.windows(2).all(|w| w[0] != w[1]), "each grid has its own offset");
    for bad in [35, 32] {
        let e = sampler::build("jitter.uniform:offsets=4").unwrap().generate(bad, 2, Seed(1)).unwrap_err();
        assert!(e.to_string().contains("jitter.uniform:offsets=4"), "{e}");
    }
}

#[test]
fn nrooks_one_per_row_and_column_in_every_pair_of_dimensions() {
    for (n, d) in [(50usize, 3usize), (7, 5), (1000, 2)] {
        let p = make("nrooks", n, d, 5);
        for axis in 0..d {
            let mut seen = vec![false; n];
            for x in p.column(axis) {
                let s = (x * n as f64) as usize;
                assert!(!seen[s], "n={n} d={d} axis {axis}: slab {s} twice");
                seen[s] = true;
            }
        }
    }
}

#[test]
fn digital_nets_for_m_1_to_12() {
    let sets = [
        "hammersley",
        "hammersley.xor",
        "hammersley.owen",
        "lp",
        "larcher-pillichshammer.xor",
        "larcher-pillichshammer.owen",
    ];
    let specs = ["sobol", "sobol.xor", "sobol.owen", "pmj02"];
    for spec in specs.into_iter().chain(sets) {
        for seed in [1u64, 2] {
            if sets.contains(&spec) {
                for m in 1..=12 {
                    assert_02_net(make(spec, 1 << m, 2, seed).as_slice(), m, spec);
                }
                continue;
            }
            // progressive: every prefix of 2^m points, and every later block of 2^m
            let p = make(spec, 1 << 12, 2, seed);
            for m in 1..=12u32 {
                let block = 2usize << m;
                for chunk in p.as_slice().chunks_exact(block) {
                    assert_02_net(chunk, m, spec);
                }
            }
        }
    }
}

#[test]
fn shift_is_a_toroidal_translate_not_a_net() {
    let base = make("sobol", 256, 2, 1);
    let shifted = make("sobol.shift", 256, 2, 1);
    let off: Vec<f64> = (0..2).map(|d| (shifted.point(0)[d] - base.point(0)[d]).rem_euclid(1.0)).collect();
    for (a, b) in base.iter().zip(shifted.iter()) {
        for d in 0..2 {
            let diff = (b[d] - a[d] - off[d]).rem_euclid(1.0);
            assert!(!(1e-12..=1.0 - 1e-12).contains(&diff));
        }
    }
}

#[test]
fn sobol_and_halton_equal_scipy() {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/scipy_sobol.json")).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let sobol = make("sobol", 1024, 16, 0);
    for (i, row) in v["sobol_16d_first_1024"].as_array().unwrap().iter().enumerate() {
        for (d, x) in row.as_array().unwrap().iter().enumerate() {
            assert_eq!(sobol.point(i)[d], x.as_f64().unwrap(), "sobol point {i} dim {d}");
        }
    }
    let halton = make("halton", 64, 8, 0);
    for (i, row) in v["halton_8d_first_64"].as_array().unwrap().iter().enumerate() {
        for (d, x) in row.as_array().unwrap().iter().enumerate() {
            let want = x.as_f64().unwrap();
            assert!(
                (halton.point(i)[d] - want).abs() <= 4.0 * f64::EPSILON,
                "halton point {i} dim {d}: {} vs {want}",
                halton.point(i)[d]
            );
        }
    }
}

#[test]
fn halton_first_points_by_hand() {
    let h = make("halton", 8, 2, 0);
    let base2 = [0.0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875];
    let base3 = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 9.0, 4.0 / 9.0, 7.0 / 9.0, 2.0 / 9.0, 5.0 / 9.0];
    for i in 0..8 {
        assert_eq!(h.point(i)[0], base2[i]);
        assert!((h.point(i)[1] - base3[i]).abs() < 1e-15);
    }
    // radical inverse in base 2 is bit reversal
    for i in 0u64..1000 {
        let rev = (i.reverse_bits() >> 11) as f64 / (1u64 << 53) as f64;
        assert_eq!(radical::radical_inverse(i, 2), rev);
    }
}

#[test]
fn batch_equals_random_access() {
    for family in ["sobol", "halton"] {
        for suffix in ["", ".xor", ".owen", ".shift"] {
            // random access reached from the registry
            let s = sampler::build(&format!("{family}{suffix}")).unwrap();
            // each walk the fill has (one to three dimensions, more), whole blocks and a tail
            for (n, dims) in [(300, 5), (64, 1), (64, 2), (77, 2), (301, 3)] {
                let p = s.generate(n, dims, Seed(42)).unwrap();
                let plan = s.plan(n, dims).unwrap();
                let access = plan.access(Seed(42)).unwrap_or_else(|| panic!("{family}{suffix} has no random access"));
                for i in 0..n {
                    for d in 0..dims {
                        assert_eq!(
                            p.point(i)[d].to_bits(),
                            access.sample(i as u64, d).unwrap().to_bits(),
                            "{} point {i} dim {d}",
                            s.spec()
                        );
                    }
                }
            }
        }
    }
    assert!(sampler::build("jitter").unwrap().plan(4, 2).unwrap().access(Seed(1)).is_none());
}

#[test]
fn random_access_refuses_indices_beyond_the_tables() {
    // the old random access cast the index to u32: point 2^32 + 5 came back as point 5
    let s = sampler::build("sobol.owen").unwrap();
    let planned = s.plan(1, 2).unwrap();

    let access = planned.access(Seed(1)).unwrap();
    let last = access.sample((1 << 32) - 1, 1).unwrap();
    assert!((0.0..1.0).contains(&last));
    let e = access.sample((1 << 32) + 5, 1).unwrap_err().to_string();
    assert!(e.contains("index = 4294967301") && e.contains("2^32 - 1"), "{e}");
    // Halton's digit tables hold 53 bits: beyond, an error (it used to index past them)
    for spec in ["halton", "halton.xor", "halton.owen", "halton.shift"] {
        let h = sampler::build(spec).unwrap();
        let planned = h.plan(1, 2).unwrap();

        let access = planned.access(Seed(1)).unwrap();
        for dim in 0..2 {
            assert!((0.0..1.0).contains(&access.sample((1 << 53) - 1, dim).unwrap()), "{spec}");
            let e = access.sample(u64::MAX, dim).unwrap_err().to_string();
            assert!(e.contains("2^53 - 1"), "{spec}: {e}");
        }
    }
}

#[test]
fn scrambled_halton_keeps_its_strata() {
    // b^k consecutive points of a digit-scrambled radical inverse fill the b^k intervals
    for spec in ["halton.xor", "halton.owen"] {
        let p = make(spec, 243, 2, 7);
        let mut seen = [false; 243];
        for x in p.column(1) {
            let c = (x * 243.0) as usize;
            assert!(!seen[c], "{spec}: base-3 interval {c} twice");
            seen[c] = true;
        }
    }
}

fn min_distance(p: &PointSet, torus: bool) -> f64 {
    let mut best = f64::INFINITY;
    for i in 0..p.len() {
        for j in 0..i {
            let d2: f64 = p
                .point(i)
                .iter()
                .zip(p.point(j))
                .map(|(a, b)| {
                    let d = (a - b).abs();
                    let d = if torus { d.min(1.0 - d) } else { d };
                    d * d
                })
                .sum();
            best = best.min(d2.sqrt());
        }
    }
    best
}

#[test]
fn poisson_sets_respect_the_minimum_distance() {
    for (spec, n, d, torus) in [
        ("poisson:radius=0.1", 16, 2, true),
        ("poisson:radius=0.2,edge=plain", 16, 2, false),
        ("poisson:radius=0.05", 100, 3, true),
        ("poisson.fast:radius=0.03", 500, 2, true),
        ("poisson.fast:radius=0.03,edge=plain", 500, 2, false),
    ] {
        let p = make(spec, n, d, 11);
        let r: f64 = spec.split("radius=").nth(1).unwrap().split(',').next().unwrap().parse().unwrap();
        assert!(min_distance(&p, torus) >= r, "{spec}: {}", min_distance(&p, torus));
    }
}

/// Dart throwing by its definition: uniform candidates in order from the first try's
/// stream, each kept when no kept point lies closer than r on the torus (O(n) per test).
fn dart_throwing_by_definition(n: usize, d: usize, r: f64, seed: Seed) -> Vec<f64> {
    let mut rng = seed.derive(0).rng();
    let mut kept: Vec<f64> = Vec::new();
    while kept.len() < n * d {
        let c: Vec<f64> = (0..d).map(|_| samplab::seed::uniform(&mut rng)).collect();
        let near = kept.chunks_exact(d).any(|q| {
            let d2: f64 = c.iter().zip(q).map(|(a, b)| (a - b).abs().min(1.0 - (a - b).abs()).powi(2)).sum();
            d2 < r * r
        });
        if !near {
            kept.extend(&c);
        }
    }
    kept
}

#[test]
fn dart_throwing_is_its_definition() {
    // the grids, the nearest-first cell order and the candidates drawn ahead (prefetched)
    // change the work, never the set
    for (n, d, r, seed) in [(3000, 2, 0.012, 5), (1000, 2, 0.02, 6), (400, 3, 0.08, 7)] {
        let fast = make(&format!("poisson:radius={r}"), n, d, seed);
        assert_eq!(fast.as_slice(), &dart_throwing_by_definition(n, d, r, Seed(seed))[..], "{n} points in {d}D");
    }
}

#[test]
fn maximal_poisson_is_maximal_and_exact() {
    let n = 300;
    let p = make("poisson.maximal", n, 2, 3);
    assert_eq!(p.len(), n);
    let r_min = min_distance(&p, true);
    let rel = r_min / (2.0 * samplab::spatial::packing_radius(n, 2).unwrap());
    assert!((0.70..0.85).contains(&rel), "relative radius {rel}");
    // no room left: every probe point of a fine lattice lies within r of some point
    let probes = 200;
    for a in 0..probes {
        for b in 0..probes {
            let q = [(a as f64 + 0.5) / probes as f64, (b as f64 + 0.5) / probes as f64];
            let nearest = p
                .iter()
                .map(|x| {
                    let dx = (x[0] - q[0]).abs().min(1.0 - (x[0] - q[0]).abs());
                    let dy = (x[1] - q[1]).abs().min(1.0 - (x[1] - q[1]).abs());
                    (dx * dx + dy * dy).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            assert!(nearest < r_min * (1.0 + 1e-9), "gap at {q:?}: {nearest} >= {r_min}");
        }
    }
}

#[test]
fn cmj_is_multi_jittered() {
    // n = 16: a 4x4 arrangement; every column of width 1/16 and every 4x4 cell holds one point
    let p = make("cmj", 256, 2, 4);
    for axis in 0..2 {
        let mut seen = [false; 256];
        for x in p.column(axis) {
            let s = (x * 256.0) as usize;
            assert!(!seen[s]);
            seen[s] = true;
        }
    }
    let mut cells = [false; 256];
    for x in p.iter() {
        let c = (x[0] * 16.0) as usize * 16 + (x[1] * 16.0) as usize;
        assert!(!cells[c]);
        cells[c] = true;
    }
}

#[test]
fn force_matrix_is_spread_out() {
    // n points chosen from a fine grid: distinct cells, and a minimum distance far above
    // that of random points (expected ~ 0.5/n for n = 64 random points)
    let p = make("force-matrix", 64, 2, 2);
    let d = min_distance(&p, true);
    assert!(d > 0.5 * (2.0 * samplab::spatial::packing_radius(64, 2).unwrap()), "min distance {d}");
    // full grid: the limiting case is the systematic grid
    let full = make("force-matrix:grid=8", 64, 2, 2);
    let mut cells = [false; 64];
    for x in full.iter() {
        let c = (x[0] * 8.0) as usize * 8 + (x[1] * 8.0) as usize;
        assert!(!cells[c]);
        cells[c] = true;
    }
}

/// The force matrix by its definition (the `force_matrix` module's docs), cell by cell: each
/// of the n choices scans every cell of the G^d grid (G = ceil(4 n^(1/d))) in order for the
/// least energy, the chosen cells counting as infinite, exact ties drawn uniformly as they
/// are met (the draw `below(ties) == 0` takes the new one); a free cell's energy is summed
/// afresh, in choice order, over the cells chosen so far whose toroidal offset is at most
/// `reach` cells on every axis, f(r) = exp(-(r / s)^p) with r in cells and s in mean
/// spacings; then one uniform offset per axis moves the whole pattern inside a cell.
fn force_matrix_naive(n: usize, dims: usize, s: f64, p: f64, seed: u64) -> Vec<f64> {
    use samplab::seed::{below, uniform};
    let g = (4.0 * (n as f64).powf(1.0 / dims as f64)).ceil() as usize;
    let cells = g.pow(dims as u32);
    let s_cells = s * (n as f64).powf(-1.0 / dims as f64) * g as f64;
    let reach = ((s_cells * 39.2f64.powf(1.0 / p)).ceil() as usize).min((g - 1) / 2);
    let coords = |c: usize| -> Vec<usize> { (0..dims).map(|a| c / g.pow((dims - 1 - a) as u32) % g).collect() };
    let mut rng = Seed(seed).rng();
    let mut chosen: Vec<usize> = Vec::new();
    for _ in 0..n {
        let energy = |c: usize| -> f64 {
            if chosen.contains(&c) {
                return f64::INFINITY;
            }
            let x = coords(c);
            let mut e = 0.0;
            for &q in &chosen {
                let y = coords(q);
                // the signed toroidal offset per axis, in cells
                let offsets: Vec<i64> = x
                    .iter()
                    .zip(&y)
                    .map(|(&a, &b)| (a as i64 - b as i64).rem_euclid(g as i64))
                    .map(|o| if o > g as i64 / 2 { o - g as i64 } else { o })
                    .collect();
                if offsets.iter().all(|o| o.unsigned_abs() as usize <= reach) {
                    let r2: f64 = offsets.iter().fold(0.0, |r2, &o| r2 + (o * o) as f64);
                    e += (-(r2.sqrt() / s_cells).powf(p)).exp();
                }
            }
            e
        };
        let (mut best, mut ties, mut best_e) = (0, 0, f64::INFINITY);
        for c in 0..cells {
            let e = energy(c);
            if e < best_e {
                (best, ties, best_e) = (c, 1, e);
            } else if e == best_e {
                ties += 1;
                if below(&mut rng, ties) == 0 {
                    best = c;
                }
            }
        }
        chosen.push(best);
    }
    let offset: Vec<f64> = (0..dims).map(|_| uniform(&mut rng)).collect();
    chosen
        .iter()
        .flat_map(|&c| {
            coords(c).into_iter().zip(&offset).map(|(x, o)| ((x as f64 + o) / g as f64).min(1.0 - f64::EPSILON / 2.0))
        })
        .collect()
}

#[test]
fn force_matrix_follows_its_definition_cell_by_cell() {
    // the library keeps each block's least energy and scans only the blocks that can hold
    // the least or a tie, and adds a window of precomputed f(r) per choice: the same cells,
    // draws and bits as the full scan (cases with the window cut at reach, and wider than
    // half the grid)
    for (n, dims, s, p, seed) in
        [(64, 2, 0.5, 2.0, 3), (120, 2, 0.5, 2.0, 4), (40, 3, 1.0, 1.5, 5), (30, 1, 0.5, 2.0, 6), (50, 2, 3.0, 4.0, 7)]
    {
        let spec = format!("force-matrix:s={s},p={p}");
        let set = make(&spec, n, dims, seed);
        let naive = force_matrix_naive(n, dims, s, p, seed);
        assert!(set.as_slice() == naive.as_slice(), "{spec}, n = {n}, {dims}D");
    }
}

#[test]
fn rotated_grid_is_a_rigid_motion_of_the_grid() {
    let p = make("regular.rotated", 64, 2, 8);
    // nearest-neighbour distance of every point is the grid spacing 1/8 (toroidal seams aside,
    // most points keep it)
    let spacing = 1.0 / 8.0;
    let mut exact = 0;
    for i in 0..64 {
        let nn = (0..64)
            .filter(|&j| j != i)
            .map(|j| {
                let dx = (p.point(i)[0] - p.point(j)[0]).abs();
                let dy = (p.point(i)[1] - p.point(j)[1]).abs();
                (dx * dx + dy * dy).sqrt()
            })
            .fold(f64::INFINITY, f64::min);
        exact += usize::from((nn - spacing).abs() < 1e-9);
    }
    assert!(exact >= 32, "{exact} points at exact grid spacing");
}

/// A stage after any spec: `+shift` moves every point of a set by one offset per axis, mod
/// 1 (a translate: the differences to the unshifted set are one number per axis), keeps
/// random access and streaming equal to the batch, and randomizes a saved set per seed.
#[test]
fn a_shift_stage_translates_any_set_and_keeps_random_access() {
    let saved = concat!("file:path=", env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/saved16.txt");
    for (base, n) in [("sobol", 64), ("halton.owen", 50), ("jitter", 64), ("random", 30), (saved, 16)] {
        let plain = sampler::build(base).unwrap();
        let shifted = sampler::build(&format!("{base}+shift")).unwrap();
        assert_eq!(shifted.spec(), format!("{}+shift", plain.spec()));
        let (p, s) = (plain.plan(n, 2).unwrap(), shifted.plan(n, 2).unwrap());
        for seed in [Seed(1), Seed(2)] {
            let (a, b) = (p.generate(seed).unwrap(), s.generate(seed).unwrap());
            for d in 0..2 {
                let offset = (b.point(0)[d] - a.point(0)[d]).rem_euclid(1.0);
                for i in 0..n {
                    let o = (b.point(i)[d] - a.point(i)[d]).rem_euclid(1.0);
                    let gap = (o - offset).abs();
                    assert!(gap.min(1.0 - gap) < 1e-15, "{base}+shift point {i}: offset {o} against {offset}");
                }
            }
            // random access and streaming, where the sampler has them, equal the batch
            if let Some(access) = s.access(seed) {
                for i in [0, 1, n - 1] {
                    assert_eq!(access.sample(i as u64, 1).unwrap(), b.point(i)[1], "{base}+shift");
                }
            }
            if let Some(mut stream) = s.stream(seed) {
                let mut chunk = vec![0.0; 2 * n];
                stream.next(&mut chunk).unwrap();
                assert_eq!(chunk, b.as_slice(), "{base}+shift streamed");
            }
        }
        // a new shift per seed
        assert_ne!(s.generate(Seed(1)).unwrap(), s.generate(Seed(2)).unwrap(), "{base}+shift");
    }
    // stages follow one another; a '+' inside a number is not a stage
    let chained = sampler::build("kronecker+shift+micro-jitter:0.2").unwrap();
    assert_eq!(chained.spec(), "kronecker+shift+micro-jitter:fraction=0.2");
    assert!(sampler::build("jitter.gaussian:sigma=1e+0+shift").is_ok());
    assert!(sampler::build("sobol+shift:x=1").unwrap_err().to_string().contains("'x'"));
}
