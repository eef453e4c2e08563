//! Points per second in 2D for the samplers that the foundation issue targets, n = 10^3..10^6;
//! the maximal Poisson disk at 10^4; random access against the batch.
//! `cargo bench -p samplab --bench samplers`; side-by-side ratios against peers: `bench/compare`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use samplab::{Seed, sampler};

const SPECS: &[&str] = &[
    "random",
    "jitter",
    "nrooks",
    "halton.xor",
    "halton.owen",
    "sobol.xor",
    "sobol.owen",
    "pmj02",
    "poisson",
    "poisson.fast",
];

fn samplers(c: &mut Criterion) {
    for spec in SPECS {
        let s = sampler::build(spec).unwrap();
        let mut group = c.benchmark_group(*spec);
        group.sample_size(10);
        for n in [1_000usize, 10_000, 100_000, 1_000_000] {
            // the grid family needs perfect squares
            let n = if spec.starts_with("jitter") { ((n as f64).sqrt().round() as usize).pow(2) } else { n };
            group.throughput(Throughput::Elements(n as u64));
            group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, &n| {
                b.iter(|| s.generate(n, 2, Seed(1)).unwrap())
            });
        }
        group.finish();
    }
}

/// The maximal Poisson disk with exactly n points (a search over whole maximal sets: seconds
/// at 10^4, so that size only).
fn maximal(c: &mut Criterion) {
    let s = sampler::build("poisson.maximal").unwrap();
    let mut group = c.benchmark_group("poisson.maximal");
    group.sample_size(10);
    group.bench_with_input(BenchmarkId::from_parameter(10_000), &10_000, |b, &n| {
        b.iter(|| s.generate(n, 2, Seed(1)).unwrap())
    });
    group.finish();
}

/// Random access against the batch, per coordinate, at dimension 1000: one access prepared
/// (tables built once), then single coordinates of scattered points.
fn random_access(c: &mut Criterion) {
    const DIMS: usize = 1000;
    const POINTS: usize = 64;
    for spec in ["halton", "halton.xor", "halton.owen", "sobol.owen"] {
        let s = sampler::build(spec).unwrap();
        let mut group = c.benchmark_group(format!("{spec} d={DIMS} per coordinate"));
        group.sample_size(10);
        // the batch at a size where its per-fill tables are amortized
        const BATCH: usize = 1024;
        group.throughput(Throughput::Elements((BATCH * DIMS) as u64));
        group.bench_function("batch", |b| b.iter(|| s.generate(BATCH, DIMS, Seed(1)).unwrap()));
        group.throughput(Throughput::Elements((POINTS * DIMS) as u64));
        let planned = s.plan(1, DIMS).unwrap();

        let access = planned.access(Seed(1)).unwrap();
        group.bench_function("random access", |b| {
            b.iter(|| {
                let mut sum = 0.0;
                for i in 0..POINTS as u64 {
                    for d in 0..DIMS {
                        sum += access.sample(i * 7919, d).unwrap();
                    }
                }
                sum
            })
        });
        group.finish();
    }
}

criterion_group!(benches, samplers, maximal, random_access);
criterion_main!(benches);
