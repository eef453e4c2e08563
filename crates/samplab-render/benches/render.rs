//! The renderer on the benchmark set-up at a bench-sized image: sphere-box, pixel
//! area, direct lighting, one Owen-scrambled Sobol' light sample per estimate from one
//! pattern per pixel (one camera ray and one shadow ray per sample); the spheres scene in
//! visibility mode (the papers' estimator, with its unoccluded quadrature); and the
//! 1-million-triangle mesh. `cargo bench -p samplab-render` (all threads;
//! `RAYON_NUM_THREADS=1` for one core); side by side with Mitsuba 3: `bench/compare render`.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use samplab_render::scenes::{LightKind, builtin};
use samplab_render::{Footprint, Mode, Options, Pattern, render};

fn options(light: &str, n: usize, spp: usize, mode: Mode) -> Options {
    let mut o = Options::new(light, n, 128, 128).unwrap();
    o.spp = spp;
    o.mode = mode;
    if mode == Mode::Direct {
        o.footprint = Footprint::Area;
        o.strategies_mut().expect("strategies").pattern = Pattern::PerPixel;
    }
    o
}

fn renders(c: &mut Criterion) {
    let mut g = c.benchmark_group("render-128x128");
    g.sample_size(10);
    let cases = [
        (
            "sphere-box direct 1 x 64 spp",
            builtin("sphere-box", None).unwrap(),
            options("sobol.owen", 1, 64, Mode::Direct),
        ),
        (
            "spheres disk visibility 16 x 4 spp",
            builtin("spheres", Some(LightKind::Disk)).unwrap(),
            options("jitter", 16, 4, Mode::Visibility),
        ),
        (
            "sphere-box-mesh direct 1 x 16 spp",
            builtin("sphere-box-mesh", None).unwrap(),
            options("sobol.owen", 1, 16, Mode::Direct),
        ),
    ];
    for (name, scene, o) in &cases {
        g.throughput(Throughput::Elements((o.width * o.height * o.spp * o.n) as u64));
        g.bench_function(*name, |b| b.iter(|| render(scene, o, &samplab::progress::Progress::SILENT).unwrap()));
    }
    g.finish();
}

criterion_group!(benches, renders);
criterion_main!(benches);
