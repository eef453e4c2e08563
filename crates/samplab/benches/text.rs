//! Numbers as text: `io::text::push_f64` against the standard library's `{:?}` (the same
//! bytes), on 10^5 uniform values in [0, 1), one thread.
//! `cargo bench -p samplab --bench text`.

use std::io::Write as _;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use samplab::io::text::push_f64;
use samplab::{Seed, sampler};

fn text(c: &mut Criterion) {
    let values = sampler::build("random").unwrap().generate(100_000, 1, Seed(1)).unwrap();
    let values = values.as_slice();
    let mut group = c.benchmark_group("f64 as text");
    group.throughput(Throughput::Elements(values.len() as u64));
    let mut out = Vec::with_capacity(30 * values.len());
    group.bench_function("std {:?}", |b| {
        b.iter(|| {
            out.clear();
            values.iter().for_each(|x| write!(out, "{x:?}").unwrap());
            out.len()
        })
    });
    group.bench_function("io::text::push_f64", |b| {
        b.iter(|| {
            out.clear();
            values.iter().for_each(|&x| push_f64(&mut out, x));
            out.len()
        })
    });
    group.finish();
}

criterion_group!(benches, text);
criterion_main!(benches);
