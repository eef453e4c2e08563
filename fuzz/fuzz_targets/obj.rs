//! Wavefront OBJ meshes.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(triangles) = samplab_render::obj::parse(&String::from_utf8_lossy(data), "fuzz.obj") {
        assert!(triangles.iter().flatten().all(|v| v.is_finite()));
    }
});
