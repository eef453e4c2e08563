//! `conform`: samplab's own values and the pbrt-v4 and OpenQMC values of the fixtures pass
//! every check; each planted defect fails the check named for it.

use samplab::Seed;
use samplab::conform::{Check, Claim, Layout, Precision, conform};
use samplab::pixel::{Film, prepare};
use samplab::points::PointSet;
use samplab::progress::Progress;
use samplab::sampler::{self, generate_sets};

/// The checks of `sets` claimed as `spec` in `layout`, with `seed`, compared as found.
fn check(sets: &[PointSet], spec: &str, layout: Layout, seed: Option<u64>) -> samplab::Result<Vec<Check>> {
    let claim = Claim { spec, layout, seed: seed.map(Seed), precision: Precision::Found, ulps: 0 };
    conform(sets, &claim, &Progress::SILENT)
}

fn failed(checks: &[Check]) -> Vec<&'static str> {
    checks.iter().filter(|c| !c.passed).map(|c| c.name).collect()
}

fn names(checks: &[Check]) -> Vec<&'static str> {
    checks.iter().map(|c| c.name).collect()
}

fn sets(spec: &str, n: usize, d: usize, seed: u64, m: usize) -> Vec<PointSet> {
    generate_sets(&sampler::build(spec).unwrap(), n, d, Seed(seed), m).unwrap()
}

/// A film's pixels, row by row, as sets (as a user would dump them), `change` applied to
/// each pixel's values.
fn film(spec: &str, film: Film, seed: u64, change: impl Fn([u32; 2], u32, u32) -> [u32; 3]) -> Vec<PointSet> {
    let p = prepare(spec, film, Seed(seed)).unwrap();
    (0..film.height)
        .flat_map(|y| (0..film.width).map(move |x| [x, y]))
        .map(|xy| {
            let values = (0..film.spp)
                .flat_map(|i| (0..film.dims).map(move |j| (i, j)))
                .map(|(i, j)| {
                    let [x, y, jj] = change(xy, i, j);
                    p.sample([x, y], 0, i, jj)
                })
                .collect();
            PointSet::new(film.dims as usize, values).unwrap()
        })
        .collect()
}

#[test]
fn samplab_itself_passes_every_check() {
    let ours = sets("net.owen", 64, 3, 7, 32);
    let checks = check(&ours, "net.owen", Layout::Sets, Some(7)).unwrap();
    assert_eq!(names(&checks), ["range", "reference", "uniform", "independent", "unbiased", "nets", "distinct"]);
    assert!(failed(&checks).is_empty(), "{checks:#?}");
    // the same values in single precision, found or asked for, and cut to 32-bit fixed point
    let changed = |f: &dyn Fn(f64) -> f64| -> Vec<PointSet> {
        ours.iter().map(|s| PointSet::new(3, s.as_slice().iter().map(|&x| f(x)).collect()).unwrap()).collect()
    };
    let singles = changed(&|x| f64::from((x as f32).min(0.999_999_94)));
    for precision in [Precision::Found, Precision::Single] {
        let claim = Claim { precision, seed: Some(Seed(7)), ..Claim::sets("net.owen") };
        let checks = conform(&singles, &claim, &Progress::SILENT).unwrap();
        assert!(failed(&checks).is_empty(), "{checks:#?}");
        assert!(checks[1].detail.contains("(single precision)"), "{}", checks[1].detail);
    }
    let fixed = changed(&|x| (x * 4_294_967_296.0).floor() / 4_294_967_296.0);
    let checks = check(&fixed, "net.owen", Layout::Sets, Some(7)).unwrap();
    assert!(failed(&checks).is_empty() && checks[1].detail.contains("(32-bit fixed point)"), "{checks:#?}");
    // one ulp off everywhere: refused bit for bit, passed within 1 ulp
    let off = changed(&|x| f64::from_bits(x.to_bits() + 1));
    assert_eq!(failed(&check(&off, "net.owen", Layout::Sets, Some(7)).unwrap()), ["reference"]);
    let claim = Claim { seed: Some(Seed(7)), ulps: 1, ..Claim::sets("net.owen") };
    let checks = conform(&off, &claim, &Progress::SILENT).unwrap();
    assert!(failed(&checks).is_empty() && checks[1].detail.contains("within 1 ulps"), "{checks:#?}");
    // a film of a pixel family; an unscrambled net's identical realizations are no defect
    let f = Film { width: 4, height: 3, spp: 16, dims: 4 };
    let pixels = film("sobol.padded", f, 3, |[x, y], _, j| [x, y, j]);
    let checks = check(&pixels, "sobol.padded", Layout::film(4, 3, 0), Some(3)).unwrap();
    assert_eq!(names(&checks), ["range", "reference", "uniform", "independent", "distinct"]);
    assert!(failed(&checks).is_empty(), "{checks:#?}");
    let checks = check(&sets("net", 64, 3, 1, 3), "net", Layout::Sets, None).unwrap();
    assert_eq!(names(&checks), ["range", "uniform", "independent", "nets"]);
    assert!(failed(&checks).is_empty(), "{checks:#?}");
}

#[test]
fn each_planted_defect_fails_its_check() {
    // a wrong direction number: Joe & Kuo's dimension 3 (x^2 + x + 1) with m_2 = 1, not 3
    let dir = std::env::temp_dir().join(format!("samplab-conform-{}.txt", std::process::id()));
    std::fs::write(&dir, "2 1 0 1\n3 2 1 1 1\n").unwrap();
    let wrong = sets(&format!("net:directions={}", dir.display()), 256, 3, 0, 1);
    std::fs::remove_file(&dir).ok();
    let checks = check(&wrong, "net", Layout::Sets, Some(0)).unwrap();
    assert!(failed(&checks).contains(&"reference"), "{checks:#?}");
    let detail = &checks.iter().find(|c| c.name == "reference").unwrap().detail;
    assert!(detail.contains("sample 2, dimension 2"), "{detail}");
    // and without the seed, its pair of dimensions 1-2 is a worse net than Joe & Kuo's
    assert_eq!(failed(&check(&wrong, "net", Layout::Sets, None).unwrap()), ["nets"]);
    // a warp left in (x^2): not uniform (and no more a net)
    let squared: Vec<PointSet> = sets("sobol.owen", 1024, 2, 3, 1)
        .iter()
        .map(|s| PointSet::new(2, s.as_slice().iter().map(|x| x * x).collect()).unwrap())
        .collect();
    assert_eq!(failed(&check(&squared, "sobol.owen", Layout::Sets, None).unwrap()), ["uniform", "nets"]);
    // values cut to 8 bits: every dimension still looks uniform, the integrals are biased
    let cut: Vec<PointSet> = sets("sobol.owen", 256, 2, 3, 64)
        .iter()
        .map(|s| PointSet::new(2, s.as_slice().iter().map(|x| (x * 256.0).floor() / 256.0).collect()).unwrap())
        .collect();
    assert_eq!(failed(&check(&cut, "sobol.owen", Layout::Sets, None).unwrap()), ["unbiased"]);
    // an XOR scramble claimed as Owen's: the same nets, other values
    let xor = sets("sobol.xor", 256, 4, 7, 2);
    assert_eq!(failed(&check(&xor, "sobol.owen", Layout::Sets, Some(7)).unwrap()), ["reference"]);
    // a seed shared across pixels: every pixel draws pixel (0, 0)'s values
    let f = Film { width: 4, height: 4, spp: 16, dims: 4 };
    let shared = film("sobol", f, 5, |_, _, j| [0, 0, j]);
    assert_eq!(failed(&check(&shared, "sobol", Layout::film(4, 4, 0), None).unwrap()), ["distinct"]);
    // a seed shared across dimensions: dimension 1 draws dimension 0's values
    let f8 = Film { width: 8, height: 8, spp: 16, dims: 2 };
    let same = film("sobol.padded", f8, 5, |[x, y], _, _| [x, y, 0]);
    let checks = check(&same, "sobol.padded", Layout::film(8, 8, 0), None).unwrap();
    assert!(failed(&checks).contains(&"independent"), "{checks:#?}");
    // a float conversion that rounds 1 - 2^-32 up to 1.0
    let mut rounded = sets("sobol.owen", 64, 2, 1, 1);
    let mut values = rounded[0].as_slice().to_vec();
    // the largest value, in [1 - 2^-6, 1) as the net's last cell: as if it were 1 - 2^-32
    let largest = (0..values.len()).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap();
    values[largest] = f64::from((1.0 - 2f64.powi(-32)) as f32);
    rounded[0] = PointSet::new(2, values).unwrap();
    assert_eq!(failed(&check(&rounded, "sobol.owen", Layout::Sets, None).unwrap()), ["range"]);
    // a dimension off by one in the padding: dimension j drawn as j + 1; without the seed,
    // its pairs (2k, 2k + 1) are no more nets (on a film of 32 pixels at least)
    let off = film("sobol.padded", Film { dims: 6, ..f }, 2, |[x, y], _, j| [x, y, (j + 1) % 6]);
    let checks = check(&off, "sobol.padded", Layout::film(4, 4, 0), Some(2)).unwrap();
    assert_eq!(failed(&checks), ["reference"], "{checks:#?}");
    let detail = &checks.iter().find(|c| c.name == "reference").unwrap().detail;
    assert!(detail.contains("sample 0, dimension 0"), "{detail}");
    let off = film("sobol.padded", Film { dims: 6, ..f8 }, 2, |[x, y], _, j| [x, y, (j + 1) % 6]);
    let checks = check(&off, "sobol.padded", Layout::film(8, 8, 0), None).unwrap();
    assert_eq!(failed(&checks), ["nets"], "{checks:#?}");
    let right = film("sobol.padded", Film { dims: 6, ..f8 }, 2, |[x, y], _, j| [x, y, j]);
    let checks = check(&right, "sobol.padded", Layout::film(8, 8, 0), None).unwrap();
    assert!(names(&checks).contains(&"nets") && failed(&checks).is_empty(), "{checks:#?}");
}

/// The fixtures' values from pbrt-v4's own samplers and OpenQMC's own `SobolSampler`
/// (see tests/pixels.rs), grouped by setting, pass every check.
#[test]
fn pbrt_and_openqmc_pass() {
    use std::collections::BTreeMap;
    /// A setting: spec, film width and height, seed.
    type Setting = (String, u32, u32, u64);
    // each setting's pixels (x, y, frame), each with its values in order
    let mut groups: BTreeMap<Setting, BTreeMap<[u32; 3], Vec<f64>>> = BTreeMap::new();
    for line in include_str!("fixtures/pbrt_pixel_samplers.txt").lines().filter(|l| !l.starts_with('#')) {
        let (f, spec, seed) = super::pixels::pbrt_line(line);
        let num = |k: usize| f[k].parse::<u32>().unwrap();
        let value = f64::from(f32::from_bits(u32::from_str_radix(f[10], 16).unwrap()));
        let key = (spec, num(3), num(4), u64::from(seed));
        groups.entry(key).or_default().entry([num(6), num(7), 0]).or_default().push(value);
    }
    for line in include_str!("fixtures/openqmc_sz.txt").lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<u32> = line.split(' ').take(6).map(|t| t.parse().unwrap()).collect();
        let bits = u32::from_str_radix(line.rsplit(' ').next().unwrap(), 16).unwrap();
        let key = ("openqmc.sz".to_string(), 512, 301, u64::from(f[0]));
        groups.entry(key).or_default().entry([f[1], f[2], f[3]]).or_default().push(f64::from(bits) / 4_294_967_296.0);
    }
    assert_eq!(groups.len(), 25 + 2);
    for ((spec, width, height, seed), pixels) in groups {
        let keys: Vec<[u32; 3]> = pixels.keys().copied().collect();
        let sets: Vec<PointSet> = pixels.into_values().map(|v| PointSet::new(8, v).unwrap()).collect();
        let layout = Layout::Pixels { width, height, keys };
        let checks = check(&sets, &spec, layout, Some(seed)).unwrap();
        assert!(failed(&checks).is_empty(), "{spec} {width}x{height} seed {seed}: {checks:#?}");
        assert!(names(&checks).contains(&"reference"));
    }
}

#[test]
fn bad_requests_are_errors() {
    let two = sets("random", 16, 2, 1, 2);
    let e = check(&two, "nosuch", Layout::Sets, None).unwrap_err().to_string();
    assert!(e.contains("unknown sampler"), "{e}");
    let e = check(&two, "random", Layout::film(3, 1, 0), None).unwrap_err().to_string();
    assert!(e.contains("conform's pixels: got 3, expected one per set, 2"), "{e}");
    let layout = Layout::Pixels { width: 2, height: 2, keys: vec![[0, 0, 0], [2, 0, 0]] };
    let e = check(&two, "sobol", layout, None).unwrap_err().to_string();
    assert!(e.contains("res = 2x2: pixel (2, 0) is off the film"), "{e}");
    let mixed = vec![two[0].clone(), sets("random", 8, 2, 1, 1).remove(0)];
    let e = check(&mixed, "random", Layout::Sets, None).unwrap_err().to_string();
    assert!(e.contains("set 1: got 8 2D points, expected 16 2D points, as set 0"), "{e}");
}
