//! The exact discrepancies at the sizes the discrepancy and speed issues target: 2D star at
//! n = 10^3..10^6, d-D star (3D n = 2000, 5D n = 400 and 1000) on random, Sobol' (and
//! Halton) points, 2D L2-star at 10^3..10^6 and 2^14, centered and wrap-around at 2^14, 2D
//! extreme at 10^3 and 10^4 (and the Hammersley set at 4096, the hard case).
//! `cargo bench -p samplab --bench discrepancy` (all threads; `RAYON_NUM_THREADS=1` for one core);
//! side by side with scipy, on one core: `bench/compare discrepancy`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use samplab::discrepancy::{self, Limits, Metric};
use samplab::{PointSet, Seed, sampler};

fn set(spec: &str, n: usize, d: usize) -> PointSet {
    sampler::build(spec).unwrap().generate(n, d, Seed(1)).unwrap()
}

fn bench(c: &mut Criterion, group: &str, metric: &str, cases: &[(&str, usize, usize)]) {
    let metric = Metric::parse(metric).unwrap();
    let limits = Limits { max_work: f64::INFINITY, ..Limits::default() };
    let mut g = c.benchmark_group(group);
    g.sample_size(10);
    for &(spec, n, d) in cases {
        let points = set(spec, n, d);
        g.bench_with_input(BenchmarkId::new(format!("{spec}-{d}D"), n), &points, |b, p| {
            b.iter(|| discrepancy::compute(&metric, p, limits).unwrap())
        });
    }
    g.finish();
}

fn discrepancies(c: &mut Criterion) {
    let sizes = [1_000usize, 10_000, 100_000, 1_000_000];
    let star_2d: Vec<(&str, usize, usize)> = sizes.iter().map(|&n| ("random", n, 2)).collect();
    bench(c, "star-2d", "star", &star_2d);
    bench(
        c,
        "star-dd",
        "star",
        &[
            ("random", 2000, 3),
            ("sobol.owen", 2000, 3),
            ("random", 400, 5),
            ("sobol.owen", 400, 5),
            ("random", 1000, 5),
            ("sobol.owen", 1000, 5),
            ("halton", 1000, 5),
        ],
    );
    bench(c, "l2-star-2d", "l2-star", &[star_2d.as_slice(), &[("random", 1 << 14, 2)]].concat());
    bench(c, "centered", "centered", &[("random", 1 << 14, 2)]);
    bench(c, "wraparound", "wraparound", &[("random", 1 << 14, 2)]);
    bench(
        c,
        "extreme-2d",
        "extreme",
        &[
            ("random", 1000, 2),
            ("random", 10_000, 2),
            ("sobol.owen", 10_000, 2),
            ("halton", 10_000, 2),
            ("hammersley", 4096, 2),
        ],
    );
}

criterion_group!(benches, discrepancies);
criterion_main!(benches);
