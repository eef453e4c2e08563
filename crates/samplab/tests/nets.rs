//! Digital nets in base b (Faure, Niederreiter, nets from generating-matrix files): their
//! (t, m, s)-net property counted on every elementary interval, their points against
//! independent implementations (QMCPy, GNU GSL; `scripts/make_fixtures.py`), and their
//! randomizations (unbiased, batch == random access).
//!
//! One test samples (the randomizations' unbiasedness); its doc comment gives its failure
//! probability and least work. The others check properties that hold for every draw.

use samplab::discrepancy::tvalue::of_matrices;
use samplab::progress::Progress;
use samplab::sampler;
use samplab::sampler::qmc::net::Matrices;
use samplab::{PointSet, Seed};

fn set(spec: &str, n: usize, d: usize, seed: u64) -> PointSet {
    sampler::build(spec).unwrap().generate(n, d, Seed(seed)).unwrap()
}

fn fixture(name: &str) -> String {
    format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory for the files a test writes, removed when the test ends.
struct Scratch(std::path::PathBuf);

impl Scratch {
    fn new(tag: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("samplab-{tag}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    /// Each `(body, line, why)`: a direction file of a comment line then `body` is refused,
    /// as `net:directions=FILE{params}`, with its line number and the reason.
    fn assert_refused(&self, params: &str, cases: &[(&str, usize, &str)]) {
        for (body, line, why) in cases {
            let path = self.write("bad.txt", &format!("# a comment\n{body}"));
            let e = sampler::build(&format!("net:directions={path}{params}")).unwrap_err().to_string();
            assert!(e.contains(&format!("bad.txt:{line}: {why}")), "{body:?}: {e}");
        }
    }

    /// Writes `text` to the file `name` in it, and gives the file's path.
    fn write(&self, name: &str, text: &str) -> String {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

fn json() -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(fixture("qmc_constructions.json")).unwrap()).unwrap()
}

fn rows(v: &serde_json::Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(|r| r.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()).collect()
}

fn sorted(mut points: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    points.sort_by(|a, b| {
        a.iter().zip(b).map(|(x, y)| x.total_cmp(y)).find(|o| o.is_ne()).unwrap_or(std::cmp::Ordering::Equal)
    });
    points
}

fn points(p: &PointSet) -> Vec<Vec<f64>> {
    p.iter().map(<[f64]>::to_vec).collect()
}

fn assert_close(ours: &[Vec<f64>], theirs: &[Vec<f64>], tol: f64, what: &str) {
    assert_eq!(ours.len(), theirs.len(), "{what}");
    for (i, (a, b)) in ours.iter().zip(theirs).enumerate() {
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= tol, "{what}: point {i}: {a:?} against {b:?}");
        }
    }
}

/// Every elementary interval of volume b^(t-m) (every split of m - t digits among the
/// dimensions) holds exactly b^t of the b^m points: the (t, m, s)-net property.
fn assert_net(p: &PointSet, base: usize, m: u32, t: u32, what: &str) {
    let s = p.dims();
    assert_eq!(p.len(), base.pow(m), "{what}");
    let k = (m - t) as usize;
    let mut split = vec![0usize; s];
    split[s - 1] = k;
    loop {
        let mut count = vec![0usize; base.pow(k as u32)];
        for x in p.iter() {
            let cell = x.iter().zip(&split).fold(0, |acc, (&c, &kj)| {
                let cells = base.pow(kj as u32);
                // a hair over the point: unscrambled coordinates are rounded rationals
                acc * cells + ((c * cells as f64 + 1e-9) as usize).min(cells - 1)
            });
            count[cell] += 1;
        }
        assert!(count.iter().all(|&c| c == base.pow(t)), "{what}: m = {m}, split {split:?} is not stratified");
        // next composition of k into s parts
        let Some(j) = (0..s - 1).rev().find(|&j| split[j + 1..].iter().sum::<usize>() > 0) else { break };
        let rest: usize = split[j + 1..].iter().sum();
        split[j] += 1;
        split[j + 1..].iter_mut().for_each(|x| *x = 0);
        split[s - 1] = rest - 1;
    }
}

const VARIANTS: [&str; 4] = ["", ".xor", ".lms", ".owen"];

#[test]
fn faure_is_a_zero_net_in_its_base_scrambled_or_not() {
    for (d, base, ms) in [(3usize, 3usize, 1..=7u32), (5, 5, 1..=5), (2, 2, 1..=11)] {
        for v in VARIANTS {
            let spec = format!("faure{v}");
            for m in ms.clone() {
                assert_net(&set(&spec, base.pow(m), d, 7), base, m, 0, &spec);
            }
        }
    }
    // a (0, s)-sequence: the second block of 5^4 points is a net too
    let all = set("faure", 2 * 625, 5, 1);
    let block = PointSet::new(5, all.as_slice()[625 * 5..].to_vec()).unwrap();
    assert_net(&block, 5, 4, 0, "faure, points 625..1250");
}

#[test]
fn niederreiter_t_is_the_sum_of_the_degrees_minus_one() {
    // base 2: x, x+1, x^2+x+1, x^3+x+1, x^3+x^2+1 have degrees 1, 1, 2, 3, 3: t = 0, 0, 1, 3, 5
    for (d, t) in [(2usize, 0u32), (3, 1), (4, 3), (5, 5)] {
        for v in VARIANTS {
            let spec = format!("niederreiter{v}");
            for m in t.max(1)..=12 {
                assert_net(&set(&spec, 1 << m, d, 3), 2, m, t, &format!("{spec} d = {d}"));
            }
        }
    }
    // base 3: x, x+1, x+2 and then x^2+1, x^2+x+2 (degree 2): t = 2 in 5 dimensions
    for v in VARIANTS {
        let spec = format!("niederreiter{v}:base=3");
        for m in 2..=7 {
            assert_net(&set(&spec, 3usize.pow(m), 5, 3), 3, m, 2, &spec);
        }
    }
}

#[test]
fn nets_from_the_default_matrices_are_sobol() {
    for m in [4, 10] {
        let n = 1 << m;
        assert_eq!(sorted(points(&set("net", n, 6, 1))), sorted(points(&set("sobol", n, 6, 1))), "m = {m}");
    }
    for v in VARIANTS {
        let spec = format!("net{v}");
        for m in 1..=11 {
            assert_net(&set(&spec, 1 << m, 2, 5), 2, m, 0, &spec);
        }
    }
}

#[test]
fn points_equal_qmcpy_and_gsl() {
    let f = json();
    for (d, n) in [(3usize, 243usize), (5, 125), (11, 121)] {
        let theirs = rows(&f["faure"][d.to_string()]);
        assert_close(&points(&set("faure", n, d, 1)), &theirs, 1e-15, &format!("faure d = {d}"));
    }
    let b2 = format!("net:matrices={}", fixture("net_b2.txt"));
    assert_close(&sorted(points(&set(&b2, 1024, 4, 1))), &sorted(rows(&f["net_b2"])), 1e-15, "base-2 matrices");
    let b3 = format!("net:matrices={}", fixture("net_b3.txt"));
    assert_close(&sorted(points(&set(&b3, 729, 3, 1))), &sorted(rows(&f["net_b3"])), 1e-15, "base-3 matrices");
    // the embedded lattice in radical-inverse order, from the same vector file
    let lattice = format!("lattice:vector={}", fixture("lattice_vector.txt"));
    assert_close(&points(&set(&lattice, 1024, 5, 1)), &rows(&f["lattice_radical_inverse"]), 0.0, "lattice");
    // GSL keeps 30 bits and walks in Gray-code order: the same 2^8 points, truncated
    let ours: Vec<Vec<f64>> = points(&set("niederreiter", 256, 12, 1))
        .into_iter()
        .map(|p| p.into_iter().map(|x| (x * 2f64.powi(30)).floor() / 2f64.powi(30)).collect())
        .collect();
    assert_close(&sorted(ours), &sorted(rows(&f["niederreiter_gsl_12d_first_256"])), 0.0, "Niederreiter");
}

/// Failure probability about 7e-5 per randomization (a mean of 400 independent estimates,
/// 4 of its standard errors: Student's t with 399 degrees of freedom, two-sided), 1.5e-3 for
/// the test's 20; random access against the batch is exact. Fixed seeds. Least work: the
/// criterion is 4 standard errors at any count, so 400 sets of 81 points buy power (a bias
/// of a fifth of one estimate's spread is seen), not a lower failure probability.
#[test]
fn random_access_equals_the_batch_and_randomizations_are_unbiased() {
    let b3 = format!("net:matrices={}", fixture("net_b3.txt"));
    let families = ["faure", "niederreiter", "niederreiter:base=5", "net", b3.as_str()];
    for family in families {
        let (name, params) = family.split_once(':').map_or((family, String::new()), |(a, b)| (a, format!(":{b}")));
        for v in [".xor", ".lms", ".owen", ".shift", ""] {
            let spec = format!("{name}{v}{params}");
            let s = sampler::build(&spec).unwrap();
            let (n, d) = (81, 3);
            let batch = s.generate(n, d, Seed(11)).unwrap();
            let planned = s.plan(1, d).unwrap();

            let access = planned.access(Seed(11)).unwrap();
            for i in [0, 1, 2, 40, 80] {
                for j in 0..d {
                    assert_eq!(access.sample(i as u64, j).unwrap(), batch.point(i)[j], "{spec}: point {i}");
                }
            }
            if v.is_empty() {
                continue;
            }
            // the integral of x y z is 1/8: 400 randomized sets of 81 points, within 4 standard errors
            let sets = s.plan(n, d).unwrap().generate_sets(Seed(2), 400, &Progress::SILENT).unwrap();
            let est: Vec<f64> =
                sets.iter().map(|p| p.iter().map(|q| q[0] * q[1] * q[2]).sum::<f64>() / n as f64).collect();
            let sum = samplab::stats::Summary::of(&est);
            assert!((sum.mean - 0.125).abs() < 4.0 * sum.sd / 20.0, "{spec}: {} +- {}", sum.mean, sum.sd / 20.0);
            assert!(sum.sd > 0.0, "{spec}: not random");
        }
    }
}

#[test]
fn bad_matrix_files_are_refused_with_their_line() {
    let dir = std::env::temp_dir().join(format!("samplab-nets-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (text, expected) in [
        ("2\n2\n4\n", "ends before the digits per column"),
        ("4 # base\n1\n4\n2\n1 2\n", "not a prime"),
        ("2\n2\n4\n2\n2 1\n1\n", ":6: 1 columns where the first dimension has 2"),
        ("2\n1\n4\n2\n2 x\n", ":5: 'x' is not a whole number"),
        ("2\n1\n4\n2\n2 4\n", ":5: column 4 has more than 2 digits"),
        ("2\n2\n4\n2\n2 1\n", "1 dimensions where the header announces 2"),
        ("2\n1\n4\n2\n2 1\n3 1\n", ":6: more than the 1 dimensions"),
    ] {
        let path = dir.join("m.txt");
        std::fs::write(&path, text).unwrap();
        let e = sampler::build(&format!("net:matrices={}", path.display())).unwrap_err().to_string();
        assert!(e.contains(expected) && e.contains("m.txt"), "{text:?}: {e}");
    }
    let e = sampler::build("net:matrices=/nonexistent/m.txt").unwrap_err().to_string();
    assert!(e.contains("/nonexistent/m.txt"), "{e}");
    // a file with 2 columns makes 4 points, no more
    std::fs::write(dir.join("m.txt"), "2\n1\n4\n2\n2 1\n").unwrap();
    let s = sampler::build(&format!("net:matrices={}", dir.join("m.txt").display())).unwrap();
    assert_eq!(points(&s.generate(4, 1, Seed(1)).unwrap()), vec![vec![0.0], vec![0.5], vec![0.25], vec![0.75]]);
    assert!(s.plan(5, 1).unwrap_err().to_string().contains("at most 4 points"));
    assert!(s.plan(4, 2).is_err());
    assert!(s.plan(1, 1).unwrap().access(Seed(1)).unwrap().sample(4, 0).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A Joe & Kuo direction-number file (`net:directions=FILE`): the published table (the
/// first 1024 dimensions of new-joe-kuo-6.21201) gives scipy's first 2^10 Sobol' points
/// bit for bit;
/// a table of other valid initial numbers keeps Sobol's t-value bound, the sum of the
/// polynomials' degrees less one (Joe & Kuo 2008, section 2), counted on every elementary
/// interval; and a malformed line is refused with its line.
#[test]
fn joe_kuo_direction_files_give_their_sobol_nets() {
    let data = concat!(env!("CARGO_MANIFEST_DIR"), "/data/new-joe-kuo-6.1024.txt");
    let text = std::fs::read_to_string(fixture("scipy_sobol.json")).unwrap();
    let scipy: serde_json::Value = serde_json::from_str(&text).unwrap();
    // scipy draws the first 2^10 points in Gray-code order, a net in natural order: the same set
    let ours = sorted(points(&set(&format!("net:directions={data}"), 1024, 16, 0)));
    assert!(ours == sorted(rows(&scipy["sobol_16d_first_1024"])), "the published table against scipy");
    let dir = Scratch::new("joe-kuo");
    let write = |name: &str, text: &str| dir.write(name, text);
    // x + 1 and x^2 + x + 1 with initial numbers other than Joe & Kuo's: t = 0 + 0 + 1
    let other = write("other.txt", "d s a m_i\n2 1 0 1\n3 2 1 1 1\n");
    for v in VARIANTS {
        let spec = format!("net{v}:directions={other}");
        for m in 1..=10 {
            assert_net(&set(&spec, 1 << m, 3, 5), 2, m, 1, &spec);
        }
        // and not t = 0: the bound is met
        assert!(std::panic::catch_unwind(|| assert_net(&set(&spec, 1 << 6, 3, 5), 2, 6, 0, &spec)).is_err(), "{spec}");
    }
    // the comment is line 1
    dir.assert_refused(
        "",
        &[
            ("2 1 0 2\n", 2, "m_1 = 2 must be odd and below 2^1"),
            ("2 1 0 1\n3 2 1 1 5\n", 3, "m_2 = 5 must be odd and below 2^2"),
            ("2 1 0 1\n4 2 1 1 3\n", 3, "dimension 4 where 3 comes next"),
            ("2 2 2 1 3\n", 2, "a = 2 has more than s - 1 = 1 bits"),
            ("2 1 0 1 1\n", 2, "degree 1 needs 1 initial numbers m_1 .. m_1, got 2"),
            ("2 1 0 x\n", 2, "'x' is not a whole number"),
        ],
    );
    // the OneTwo table's numbering: van der Corput's dimension written out, then from 1
    let written_out = write("written-out.txt", "d s a m_i\n0 0 0 # van der Corput\n1 1 0 1\n2 2 1 1 1\n");
    assert_eq!(
        points(&set(&format!("net:directions={written_out}"), 256, 3, 0)),
        points(&set(&format!("net:directions={other}"), 256, 3, 0))
    );
    // the Cascaded Sobol' table's: from 1 with van der Corput's left out
    let left_out = write("left-out.txt", "d s a m_i\n1 1 0 1\n2 2 1 1 1\n");
    assert_eq!(
        points(&set(&format!("net:directions={left_out}"), 256, 3, 0)),
        points(&set(&format!("net:directions={other}"), 256, 3, 0))
    );
    let late = write("late.txt", "2 1 0 1\n0 0 0\n");
    let e = sampler::build(&format!("net:directions={late}")).unwrap_err().to_string();
    assert!(e.contains("late.txt:2: expected d s a m_1 .. m_s, got 3 numbers"), "{e}");
    let e = sampler::build(&format!("net:directions={other},matrices={other}")).unwrap_err().to_string();
    assert!(e.contains("matrices or directions, not both"), "{e}");
}

/// Gray-code order (Antonov & Saleev 1979): the default matrices in Gray-code order are
/// `sobol`'s points bit for bit (which are scipy's, `structure.rs`), point i + 1 is point i
/// with the one column of i's lowest zero bit added, random access equals the batch under
/// every randomization and the set is the natural order's; a base-3 file is refused.
#[test]
fn gray_code_order_is_sobols_and_steps_by_one_column() {
    for m in [4, 10] {
        assert_eq!(points(&set("net:order=gray", 1 << m, 6, 1)), points(&set("sobol", 1 << m, 6, 1)), "m = {m}");
    }
    let gray = set("net:order=gray", 1 << 10, 4, 1);
    let fixed = |i: usize, d: usize| (gray.point(i)[d] * 4_294_967_296.0) as u32;
    for i in 0..(1usize << 10) - 1 {
        for d in 0..4 {
            let column = samplab::construct::sobol::direction_numbers(d)[i.trailing_ones() as usize];
            assert_eq!(fixed(i, d) ^ fixed(i + 1, d), column, "point {i}, dimension {d}");
        }
    }
    assert_ne!(points(&set("net", 16, 2, 1)), points(&set("net:order=gray", 16, 2, 1)), "natural order is not Gray's");
    for v in VARIANTS {
        let plan = sampler::build(&format!("net{v}:order=gray")).unwrap().plan(256, 4).unwrap();
        let batch = plan.generate(Seed(3)).unwrap();
        let access = plan.access(Seed(3)).unwrap();
        for i in 0..256 {
            for d in 0..4 {
                assert_eq!(access.sample(i as u64, d).unwrap(), batch.point(i)[d], "net{v}: point {i}, dimension {d}");
            }
        }
        assert_eq!(sorted(points(&batch)), sorted(points(&set(&format!("net{v}"), 256, 4, 3))), "net{v}");
    }
    let e = sampler::build(&format!("net:order=gray,matrices={}", fixture("net_b3.txt"))).unwrap_err().to_string();
    assert!(e.contains("Gray-code order is for base-2 matrices"), "{e}");
}

/// The t-value metric against every elementary interval of base 2 enumerated box by box
/// (each box [a_j 2^-d_j, (a_j + 1) 2^-d_j) compared exactly in floating point, its points
/// counted), and against the constructions' known t: Faure's sets are (0, m, s)-nets in
/// base b >= s, Sobol's first two dimensions and the Larcher-Pillichshammer set are
/// (0, m, 2)-nets, scrambled or not; a set with one point moved is not, and uniform random
/// points are far from it.
#[test]
fn the_t_value_metric_is_the_least_t_of_every_elementary_interval() {
    use samplab::discrepancy::{Limits, Metric, compute};
    let t_value = |p: &PointSet, spec: &str| compute(&Metric::parse(spec).unwrap(), p, Limits::default()).unwrap();
    // the least t such that every box of volume 2^(t-m) holds 2^t points
    let naive = |p: &PointSet, m: u32| -> f64 {
        let s = p.dims();
        let holds = |t: u32| {
            let k = m - t;
            let mut splits: Vec<Vec<u32>> = vec![vec![]];
            for _ in 0..s {
                splits = splits.into_iter().flat_map(|v| (0..=k).map(move |d| [v.clone(), vec![d]].concat())).collect();
            }
            splits.into_iter().filter(|v| v.iter().sum::<u32>() == k).all(|d| {
                (0..1u64 << k).all(|code| {
                    // the box's corner a_j: consecutive bits of `code`, d_j of them per axis
                    let mut shift = 0;
                    let corner: Vec<u64> = d
                        .iter()
                        .map(|&dj| {
                            let a = (code >> shift) & ((1 << dj) - 1);
                            shift += dj;
                            a
                        })
                        .collect();
                    let inside = p
                        .iter()
                        .filter(|x| {
                            (0..s).all(|j| {
                                let side = (1u64 << d[j]) as f64;
                                x[j] >= corner[j] as f64 / side && x[j] < (corner[j] + 1) as f64 / side
                            })
                        })
                        .count();
                    inside == 1 << t
                })
            })
        };
        (0..=m).find(|&t| holds(t)).unwrap() as f64
    };
    for (spec, d, m) in
        [("sobol", 3, 6u32), ("sobol.owen", 4, 5), ("lp", 2, 6), ("jitter", 2, 4), ("random", 2, 4), ("random", 3, 5)]
    {
        let p = set(spec, 1 << m, d, 7);
        assert_eq!(t_value(&p, "t-value"), naive(&p, m), "{spec} {d}D");
    }
    for m in 1..=10 {
        for spec in ["sobol", "sobol.owen", "lp", "larcher-pillichshammer.xor", "hammersley"] {
            assert_eq!(t_value(&set(spec, 1 << m, 2, 3), "t-value"), 0.0, "{spec}, m = {m}");
        }
    }
    for spec in ["faure", "faure.owen"] {
        assert_eq!(t_value(&set(spec, 3usize.pow(5), 3, 1), "t-value:base=3"), 0.0, "{spec}");
    }
    // SZ (Ahmed et al. 2025): a (0, 4)-sequence in base 4, as every randomization that keeps
    // nets leaves it; its binary pairs are not all (0, m, 2)-nets (the price of base 4)
    for spec in ["sz", "sz.owen", "sz.xor", "sz.lms"] {
        for k in 1..=5 {
            let p = set(spec, 4usize.pow(k), 4, 5);
            assert_eq!(t_value(&p, "t-value:base=4"), 0.0, "{spec}, 4^{k} points");
        }
    }
    assert!(t_value(&set("sz", 4096, 4, 1), "t-value:projection=pairs") > 0.0);
    assert!(t_value(&set("sobol", 4096, 4, 1), "t-value:base=4") > 0.0);
    // one point moved onto another: no longer a (0, m, 2)-net
    let mut moved = set("sobol", 256, 2, 1).as_slice().to_vec();
    moved[0] = moved[2];
    moved[1] = moved[3];
    assert!(t_value(&PointSet::new(2, moved).unwrap(), "t-value") > 0.0);
    assert!(t_value(&set("random", 1024, 2, 1), "t-value") >= 5.0);
    // the pairs of a 6D Sobol' set are no worse than the whole set
    let sobol6 = set("sobol", 1024, 6, 1);
    assert!(t_value(&sobol6, "t-value:projection=pairs") <= t_value(&sobol6, "t-value"));
    let e = compute(&Metric::parse("t-value").unwrap(), &set("random", 100, 2, 1), Limits::default()).unwrap_err();
    assert!(e.to_string().contains("100 points are not a power of the base 2"), "{e}");
    // consecutive pairs and quadruples: the worst of the counts from the matrices
    let plan = sampler::build("net.owen").unwrap().plan(1 << 10, 9).unwrap();
    let points = plan.generate(Seed(2)).unwrap();
    let worst = |width: usize| {
        (0..=9 - width)
            .map(|j| {
                of_matrices(
                    plan.generating_matrices().unwrap(),
                    &(j..j + width).collect::<Vec<_>>(),
                    10,
                    &Limits::default(),
                )
                .unwrap()
            })
            .max()
            .unwrap() as f64
    };
    assert_eq!(t_value(&points, "t-value:projection=consecutive"), worst(2));
    assert_eq!(t_value(&points, "t-value:projection=quadruples"), worst(4));
    assert!(worst(4) > worst(2));
    let e =
        compute(&Metric::parse("t-value:projection=quadruples").unwrap(), &set("sobol", 64, 3, 1), Limits::default())
            .unwrap_err();
    assert!(e.to_string().contains("quadruples takes sets of 4 or more dimensions, not 3D"), "{e}");
}

/// The least t of the 2D digital net in base b that the first m columns of two generating
/// matrices make (`c[k][r]`: the digit in row r of column k), by samplab's rank count
/// ([`of_matrices`], checked against the box count in
/// `t_from_the_matrices_is_the_box_count_of_every_net`).
fn pair_t(c1: &[Vec<u8>], c2: &[Vec<u8>], m: usize, base: u8) -> usize {
    let rows = c1[0].len();
    let digits = [c1, c2].iter().flat_map(|c| c[..m].iter().flatten().copied()).collect();
    let matrices = Matrices::new(base.into(), 2, m, rows, digits).unwrap();
    of_matrices(&matrices, &[0, 1], m, &samplab::discrepancy::Limits::default()).unwrap()
}

/// A binary generating matrix as digits: `[k][r]`, from its columns as 32-bit words (row 0
/// the most significant bit).
fn binary_digits(columns: &[u32; 32]) -> Vec<Vec<u8>> {
    columns.iter().map(|&v| (0..32).map(|r| (v >> (31 - r) & 1) as u8).collect()).collect()
}

/// Sobol's construction over GF(3) from a direction file (`net:directions=FILE,base=3`, the
/// format of Ostromoukhov et al. 2024): the polynomials x and x + 2 with m_1 = 1 give the
/// identity and the Pascal matrix mod 3 (binomials counted here), so the points are Faure's
/// first two dimensions in base 3; an m_1 changed changes them. Degrees 1 and 2 with any
/// valid initial numbers make a pair with t at most the degrees less one, 0 + 1 (Sobol's
/// bound, as in base 2), met; a malformed line is refused with its line.
#[test]
fn base_three_direction_files_are_sobols_construction_over_gf3() {
    use samplab::construct::sobol3::matrices;
    let c = matrices("d s a m_i\n1 1 3 1\n2 1 5 1\n", 12).unwrap();
    let binomial = |n: usize, k: usize| (0..k).fold(1u64, |b, i| b * (n - i) as u64 / (i + 1) as u64);
    for (k, (identity, pascal)) in c[0].iter().zip(&c[1]).enumerate() {
        for r in 0..12 {
            assert_eq!(identity[r], u8::from(k == r), "identity ({r}, {k})");
            let binomial = if r <= k { (binomial(k, r) % 3) as u8 } else { 0 };
            assert_eq!(pascal[r], binomial, "Pascal ({r}, {k})");
        }
    }
    let dir = Scratch::new("gf3");
    let write = |name: &str, text: &str| dir.write(name, text);
    let faure_file = write("faure.txt", "# x, x + 2\nd s a m_i\n1 1 3 1\n2 1 5 1\n");
    let faure: Vec<Vec<f64>> = points(&set("faure", 243, 3, 0)).into_iter().map(|p| p[..2].to_vec()).collect();
    assert_close(&points(&set(&format!("net:directions={faure_file},base=3"), 243, 2, 0)), &faure, 1e-15, "Faure");
    let changed = write("changed.txt", "1 1 3 1\n2 1 5 2\n");
    assert!(points(&set(&format!("net:directions={changed},base=3"), 243, 2, 0)) != faure, "m_1 changed");
    // x^2 + 1 (irreducible over GF(3)) beside x + 1
    let degrees = write("degrees.txt", "2 1 4 1\n4 2 10 1 5\n");
    for v in VARIANTS {
        let spec = format!("net{v}:directions={degrees},base=3");
        for m in 1..=6 {
            assert_net(&set(&spec, 3usize.pow(m), 2, 5), 3, m, 1, &spec);
        }
        assert!(std::panic::catch_unwind(|| assert_net(&set(&spec, 729, 2, 5), 3, 6, 0, &spec)).is_err(), "{spec}");
    }
    // the comment is line 1
    dir.assert_refused(
        ",base=3",
        &[
            ("1 1 3 3\n", 2, "m_1 = 3 must be below 3^1 with its last base-3 digit not 0"),
            ("1 1 3 1\n4 2 10 1 3\n", 3, "m_2 = 3 must be below 3^2 with its last base-3 digit not 0"),
            ("1 2 5 1 1\n", 2, "a = 5 is not a monic polynomial of degree 2"),
            ("1 1 27 1\n", 2, "a = 27 is not a monic polynomial of degree 1"),
            ("1 1 3 1 1\n", 2, "degree 1 needs 1 initial numbers m_1 .. m_1, got 2"),
            ("1 0 1\n", 2, "expected i s a m_1 .. m_s, got 3 numbers"),
            ("1 1 3 y\n", 2, "'y' is not a whole number"),
            ("", 1, "no dimensions"),
        ],
    );
    let e = sampler::build("net:base=3").unwrap_err().to_string();
    assert!(e.contains("base 3 is not realizable without a directions file"), "{e}");
}

/// The xi-sequence (Ahmed et al. 2023): samplab's unscrambled points are the authors' code's
/// (`xi.h`, the fixture `xi.txt` it printed: 284 indices up to 2^32 - 1) bit for bit, and the two
/// dimensions are a (0, 2)-sequence, by ranks for every prefix of 2^m points to m = 32; one
/// bit flipped in a column breaks it, and so does a vector a without xi (b = a shifted).
#[test]
fn xi_is_the_authors_sequence_and_a_zero_two_sequence() {
    use samplab::construct::xi::{XI, xi_matrices};
    let text = std::fs::read_to_string(fixture("xi.txt")).unwrap();
    let plan = sampler::build("xi").unwrap().plan(1 << 20, 2).unwrap();
    let access = plan.access(Seed(0)).unwrap();
    let mut checked = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split_whitespace().collect();
        let i: u64 = f[0].parse().unwrap();
        for d in 0..2 {
            let theirs = u32::from_str_radix(f[1 + d], 16).unwrap();
            assert_eq!(access.sample(i, d).unwrap() * 4_294_967_296.0, f64::from(theirs), "point {i}, dimension {d}");
        }
        checked += 1;
    }
    assert_eq!(checked, 284);
    let worst = |c: &[[u32; 32]; 2]| {
        (1..=32).map(|m| pair_t(&binary_digits(&c[0]), &binary_digits(&c[1]), m, 2)).max().unwrap()
    };
    assert_eq!(worst(&XI), 0);
    assert_eq!(worst(&xi_matrices([0xC000_0000, 0x8000_0000])), 0, "another vector a");
    let mut flipped = XI;
    flipped[1][7] ^= 1 << 28;
    assert!(worst(&flipped) > 0, "one bit flipped");
    let mut shifted = XI;
    for c in &mut shifted {
        for k in 0..16 {
            c[2 * k + 1] = c[2 * k] >> 1;
        }
    }
    assert!(worst(&shifted) > 0, "b = a shifted");
}

/// Cascaded Sobol' (Paulin et al. 2021): samplab's points are the cascade as the paper
/// describes it, computed here a point at a time (each dimension's 1D Sobol' net drawn at
/// the previous coordinate's first m digits read as an index), of Joe & Kuo's generators and
/// of a file's in the authors' numbering. Every pair of consecutive dimensions is a
/// (0, m, 2)-net at 2^m points, by ranks (31 pairs, m up to 16) and by the box-counting
/// metric on the points, scrambled or not; pairs two apart are not all; a generator whose
/// top-left block is singular breaks its pair; a count that is not a power of 2 is refused.
#[test]
fn cascaded_sobol_is_the_papers_cascade_and_its_consecutive_pairs_are_zero_nets() {
    use samplab::construct::cascaded::matrices;
    use samplab::construct::sobol::direction_numbers;
    use samplab::discrepancy::{Limits, Metric, compute};
    let cascade = |generators: &dyn Fn(usize) -> [u32; 32], i: u32, dims: usize, m: u32| {
        let mut index = i;
        (0..dims)
            .map(|d| {
                let c = generators(d);
                let x = (0..32).filter(|&k| index >> k & 1 == 1).fold(0u32, |x, k| x ^ c[k]);
                index = x.checked_shr(32 - m).unwrap_or(0);
                f64::from(x) / 4_294_967_296.0
            })
            .collect::<Vec<f64>>()
    };
    for m in [0, 1, 3, 8, 12] {
        let p = set("cascaded", 1 << m, 8, 0);
        for i in 0..1u32 << m {
            assert_eq!(p.point(i as usize), cascade(&direction_numbers, i, 8, m), "m = {m}, point {i}");
        }
    }
    let dir = std::env::temp_dir().join(format!("samplab-cascaded-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("table.dat");
    // the authors' numbering: from 1, van der Corput's dimension left out; a generator twice
    std::fs::write(&path, "d s a   m_i\n1 1 0\t 1\n2 1 0\t 1\n3 2 1\t 1 3\n").unwrap();
    let table = samplab::construct::joe_kuo::directions(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let p = set(&format!("cascaded:directions={}", path.display()), 1 << 10, 4, 0);
    for i in 0..1u32 << 10 {
        assert_eq!(p.point(i as usize), cascade(&|d| table[d], i, 4, 10), "the file's, point {i}");
    }
    std::fs::remove_dir_all(&dir).ok();
    let worst = |g: &[Vec<[u32; 32]>], j: usize, k: usize| {
        (1..=16).map(|m| pair_t(&binary_digits(&g[m][j]), &binary_digits(&g[m][k]), m, 2)).max().unwrap()
    };
    let of = |generators: &[[u32; 32]]| (0..=16).map(|m| matrices(generators.to_vec(), m)).collect::<Vec<_>>();
    let joe_kuo: Vec<[u32; 32]> = (0..32).map(direction_numbers).collect();
    let g = of(&joe_kuo);
    for j in 0..31 {
        assert_eq!(worst(&g, j, j + 1), 0, "dimensions {j}-{}", j + 1);
    }
    assert!((0..30).any(|j| worst(&g, j, j + 2) > 0), "pairs two apart");
    let mut singular = joe_kuo.clone();
    singular[5][2] ^= 1 << 29; // column 2 loses its diagonal digit
    assert!(worst(&of(&singular), 4, 5) > 0, "a singular generator");
    let metric = Metric::parse("t-value").unwrap();
    for v in ["", ".xor", ".lms", ".owen"] {
        let points = set(&format!("cascaded{v}"), 1 << 10, 6, 3);
        for j in 0..5 {
            let pair: Vec<f64> = points.iter().flat_map(|x| [x[j], x[j + 1]]).collect();
            let t = compute(&metric, &PointSet::new(2, pair).unwrap(), Limits::default()).unwrap();
            assert_eq!(t, 0.0, "cascaded{v}, dimensions {j}-{}", j + 1);
        }
    }
    let e = sampler::build("cascaded").unwrap().plan(100, 2).unwrap_err().to_string();
    assert!(e.contains("n = 2^m (the matrices depend on m): try 64 and 128"), "{e}");
}

/// The t of a digital net from its generating matrices (rank counts over GF(b)) is the t
/// its points have, counted on every elementary interval: every family with matrices, at
/// every m up to 12 in base 2 (5 in base 3, 4 in base 5), on every projection of 4
/// dimensions (xi: its 2), scrambled too. Faure's nets have t = 0 (Faure 1982) and
/// Niederreiter's in base 2 at most the sum of the degrees less one (Niederreiter 1988,
/// reached: 0, 0, 1, 3 in 1 to 4 dimensions); a flipped digit changes the count, too many
/// columns or an axis past the dimensions is an error, and so is more work than allowed.
#[test]
fn t_from_the_matrices_is_the_box_count_of_every_net() {
    use samplab::discrepancy::{Limits, Metric, compute};
    // Sobol's construction over GF(3): x, x + 1, x + 2 and x^2 + 1
    let gf3 = std::env::temp_dir().join(format!("samplab-t-gf3-{}.txt", std::process::id()));
    std::fs::write(&gf3, "1 1 3 1\n2 1 4 1\n3 1 5 2\n4 2 10 1 4\n").unwrap();
    let gf3_params = format!(":directions={},base=3", gf3.display());
    let families = [
        ("net", "", 2, 12),
        ("niederreiter", "", 2, 12),
        ("sz", "", 2, 12),
        ("cascaded", "", 2, 12),
        ("xi", "", 2, 12),
        ("faure", "", 5, 4),
        ("niederreiter", ":base=3", 3, 5),
        ("net", gf3_params.as_str(), 3, 5),
    ];
    for (family, params, b, most) in families {
        let b: usize = b;
        for v in ["", ".owen"] {
            let spec = format!("{family}{v}{params}");
            let sampler = sampler::build(&spec).unwrap();
            let dims = if spec.starts_with("xi") { 2 } else { 4 };
            let metric = Metric::parse(&format!("t-value:base={b}")).unwrap();
            for m in 1..=most {
                let plan = sampler.plan(b.pow(m as u32), dims).unwrap();
                let matrices = plan.generating_matrices().unwrap();
                let points = plan.generate(Seed(5)).unwrap();
                // every projection: the subsets of the axes
                for mask in 1..1usize << dims {
                    let axes: Vec<usize> = (0..dims).filter(|a| mask >> a & 1 == 1).collect();
                    let xs: Vec<f64> =
                        points.iter().flat_map(|p| axes.iter().map(|&a| p[a]).collect::<Vec<f64>>()).collect();
                    let boxes = compute(&metric, &PointSet::new(axes.len(), xs).unwrap(), Limits::default()).unwrap();
                    let ranks = of_matrices(matrices, &axes, m, &Limits::default()).unwrap();
                    assert_eq!(ranks as f64, boxes, "{spec}, m = {m}, axes {axes:?}");
                }
            }
        }
    }
    let t = |spec: &str, dims: usize, m: usize| {
        let b = if spec == "faure" { 5usize } else { 2 };
        let plan = sampler::build(spec).unwrap().plan(b.pow(m as u32), dims).unwrap();
        of_matrices(plan.generating_matrices().unwrap(), &(0..dims).collect::<Vec<_>>(), m, &Limits::default()).unwrap()
    };
    assert!((1..=8).all(|m| t("faure", 5, m) == 0));
    for (dims, sum) in [(1, 0), (2, 0), (3, 1), (4, 3)] {
        let worst = (1..=20).map(|m| t("niederreiter", dims, m)).max().unwrap();
        assert_eq!(worst, sum, "niederreiter in {dims} dimensions");
    }
    let mut digits = vec![0u8; 2 * 8 * 8];
    for d in 0..2 {
        for k in 0..8 {
            // van der Corput and its reverse: the Hammersley net, t = 0
            let r = if d == 0 { k } else { 7 - k };
            digits[(d * 8 + k) * 8 + r] = 1;
        }
    }
    let hammersley = Matrices::new(2, 2, 8, 8, digits.clone()).unwrap();
    assert_eq!(of_matrices(&hammersley, &[0, 1], 8, &Limits::default()).unwrap(), 0);
    // the reverse loses its last column's digit: the second coordinates' first digit is
    // always 0, so no interval of the upper half holds a point, t = m
    digits[(8 + 7) * 8] = 0;
    let broken = Matrices::new(2, 2, 8, 8, digits).unwrap();
    assert_eq!(of_matrices(&broken, &[0, 1], 8, &Limits::default()).unwrap(), 8);
    let e = of_matrices(&hammersley, &[0, 1], 9, &Limits::default()).unwrap_err().to_string();
    assert!(e.contains("generating matrices: got 8, expected 9 columns"), "{e}");
    let e = of_matrices(&hammersley, &[0, 2], 8, &Limits::default()).unwrap_err().to_string();
    assert!(e.contains("axis 2 takes matrices of more than 2 dimensions, not 2D"), "{e}");
    let small = Limits::new(Some(100.0)).unwrap();
    assert!(matches!(of_matrices(&hammersley, &[0, 1], 8, &small), Err(samplab::Error::WorkLimit { .. })));
    std::fs::remove_file(&gf3).ok();
}
