//! Mitsuba 3 XML scenes (meshes resolved against the render crate's test scenes, and only
//! inside that folder, as the CLI does by default).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../crates/samplab-render/tests/scenes"));
    let _ = samplab_render::mitsuba::parse(&String::from_utf8_lossy(data), "fuzz.xml", dir, Default::default());
});
