//! The expression integrand's evaluation rate (issue 41 asks for at least 50 M points/s per
//! thread on a 2D Gaussian), beside the built-in Gaussian it should approach.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use samplab::integrand::{Expr, Family, Integrand};
use samplab::{Seed, sampler};
use std::hint::black_box;

fn expressions(c: &mut Criterion) {
    let n = 1 << 16;
    let points = sampler::build("sobol.owen").unwrap().plan(n, 2).unwrap().generate(Seed(1)).unwrap();
    let mut out = vec![0.0; n];
    let mut group = c.benchmark_group("integrand");
    group.throughput(Throughput::Elements(n as u64));
    let expr = Expr::parse("exp(-x0*x0 - x1*x1)", None).unwrap();
    group.bench_function("expr gaussian 2D", |b| {
        b.iter(|| expr.eval_many(black_box(points.as_slice()), &mut out));
    });
    let builtin = Family::parse("gaussian.d:d=2").unwrap().instance(Seed(1), 0).unwrap();
    group.bench_function("gaussian.d:d=2 (built in)", |b| {
        b.iter(|| builtin.eval_many(black_box(points.as_slice()), &mut out));
    });
    group.finish();
}

criterion_group!(benches, expressions);
criterion_main!(benches);
