//! Points per second in 2D for the samplers that the foundation issue targets, n = 10^3..10^6.
//! `cargo bench -p samplab --bench samplers`; side-by-side ratios against peers: `bench/compare`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use samplab::{Seed, sampler};

const SPECS: &[&str] =
    &["random", "jitter", "nrooks", "halton.xor", "halton.owen", "sobol.xor", "sobol.owen", "pmj02", "poisson.fast"];

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

criterion_group!(benches, samplers);
criterion_main!(benches);
