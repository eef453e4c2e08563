use samplab_render::{
    Mode, Options,
    light::DiskMap,
    render,
    scenes::{LightKind, builtin},
};
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene_name = &args[1];
    let (w, h) = (128, 96);
    for kind in [LightKind::Square, LightKind::Disk, LightKind::Gaussian, LightKind::Linear] {
        let scene = builtin(scene_name, Some(kind)).unwrap();
        let mut refo = Options::new("sobol.owen", 4096, w, h).unwrap();
        refo.mode = Mode::Visibility;
        let t = std::time::Instant::now();
        let reference = render(&scene, &refo, &samplab::progress::Progress::SILENT).unwrap();
        eprintln!("{kind:?} ref {:.2}s", t.elapsed().as_secs_f64());
        for (spec, n, map) in [
            ("jitter", 16, DiskMap::Concentric),
            ("jitter.uniform", 16, DiskMap::Concentric),
            ("jitter", 25, DiskMap::Reject),
            ("jitter.uniform", 25, DiskMap::Reject),
            ("halton.shift", 16, DiskMap::Concentric),
            ("random", 16, DiskMap::Concentric),
        ] {
            if kind == LightKind::Linear && n == 25 {
                continue;
            }
            let mut mse = 0.0;
            for s in 0..4 {
                let mut o = Options::new(spec, n, w, h).unwrap();
                o.disk_map = Some(map);
                o.seed = samplab::seed::Seed(s);
                let img = render(&scene, &o, &samplab::progress::Progress::SILENT).unwrap();
                mse += img.image.errors(&reference.image, false).unwrap().mse / 4.0;
            }
            println!("{scene_name} {kind:?} {spec} n={n} {map:?}: mse {mse:.3e}");
        }
    }
}
