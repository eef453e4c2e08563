//! The spec grammar: samplers (planned and filled at 16 points), metrics, integrands, warps,
//! scene lights.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Ok(s) = samplab::sampler::build(&text) {
        let _ = s.plan(16, 2).and_then(|p| p.generate(samplab::Seed(1)));
    }
    let _ = samplab::discrepancy::Metric::parse(&text);
    let _ = samplab::integrand::Family::parse(&text);
    let _ = samplab::warp::lookup(&text);
    let _ = samplab_render::scenes::LightKind::parse(&text);
});
