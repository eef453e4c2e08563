//! Mitsuba 3's two Cornell boxes rendered by path mode as Mitsuba renders them: the scene's
//! depth, filter, one-sided BSDFs and an emitter that is a surface (it reflects by its
//! BSDF and blocks rays from behind), against Mitsuba's own images
//! (scripts/mitsuba/cornell_reference.py, tests/fixtures/cornell-mitsuba.json).
//!
//! The criterion, fixed before the first comparison: each channel's image mean within 3
//! standard errors of Mitsuba's, z = (a - b) / sqrt(se_a^2 + se_b^2), the standard errors
//! over independent renders (a chance failure of about 0.27% per channel, so about 3% for
//! the 12 values of a passing run). samplab's renders are independent randomizations (seeds)
//! of its default path sampler, Owen-scrambled Sobol': their mean is unbiased and their
//! spread an honest standard error, a tenth of independent sampling's at this cost (8 x 256
//! spp), so the same criterion sees each element left out (20 SE and more at 2026-12-06;
//! the box filter for the Gaussian, about 6). Each test shows that it fails then.

use std::path::Path;

use samplab_render::mitsuba::{Paths, load};
use samplab_render::{Footprint, Scene, Settings, render};

const RENDERS: usize = 8;
const SPP: usize = 256;

/// Mitsuba's image means of `scene` at `depth` (mean, se per channel).
fn mitsuba(scene: &str, depth: usize) -> ([f64; 3], [f64; 3]) {
    let text = std::fs::read_to_string("tests/fixtures/cornell-mitsuba.json").unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!((v["width"].as_u64(), v["height"].as_u64()), (Some(32), Some(32)));
    let image = v["images"]
        .as_array()
        .unwrap()
        .iter()
        .find(|i| i["scene"] == scene && i["max_depth"].as_u64() == Some(depth as u64))
        .unwrap();
    let three = |k: &str| std::array::from_fn(|c| image[k][c].as_f64().unwrap());
    (three("mean"), three("se"))
}

fn scene(name: &str) -> Scene {
    load(&Path::new("tests/scenes").join(name), Paths::InsideScene).unwrap()
}

/// samplab's image means of `scene` at `depth` over [`RENDERS`] independent renders at
/// 32 x 32 (mean, se per channel), with the footprint `pixel` (None: the scene's).
fn samplab(scene: &Scene, depth: usize, pixel: Option<&str>) -> ([f64; 3], [f64; 3]) {
    let means: Vec<[f64; 3]> = (0..RENDERS)
        .map(|r| {
            let settings = Settings {
                mode: "path".into(),
                max_depth: Some(depth),
                spp: SPP,
                res: Some((32, 32)),
                pixel: pixel.map(str::to_string),
                seed: 100 + r as u64,
                ..Settings::default()
            };
            let o = settings.options(scene).unwrap();
            let rgb = render(scene, &o, &samplab::progress::Progress::SILENT).unwrap().image.rgb;
            std::array::from_fn(|c| rgb.iter().skip(c).step_by(3).map(|&v| v as f64).sum::<f64>() / 1024.0)
        })
        .collect();
    let n = RENDERS as f64;
    let mean: [f64; 3] = std::array::from_fn(|c| means.iter().map(|m| m[c]).sum::<f64>() / n);
    let se =
        std::array::from_fn(|c| (means.iter().map(|m| (m[c] - mean[c]).powi(2)).sum::<f64>() / (n - 1.0) / n).sqrt());
    (mean, se)
}

/// Whether samplab's means agree with Mitsuba's by the criterion; a description.
fn agrees(ours: ([f64; 3], [f64; 3]), theirs: ([f64; 3], [f64; 3])) -> (bool, String) {
    let z: [f64; 3] =
        std::array::from_fn(|c| (ours.0[c] - theirs.0[c]) / (ours.1[c] * ours.1[c] + theirs.1[c] * theirs.1[c]).sqrt());
    let text = (0..3)
        .map(|c| format!("{:.5} vs {:.5} ({:+.2} SE)", ours.0[c], theirs.0[c], z[c]))
        .collect::<Vec<_>>()
        .join(", ");
    (z.iter().all(|z| z.abs() <= 3.0), text)
}

#[test]
fn mitsubas_cornell_box_renders_as_mitsuba_renders_it() {
    let box_ = scene("cornell-box.xml");
    assert_eq!(box_.max_depth, Some(8), "the scene's integrator");
    assert_eq!(box_.footprint, Some(Footprint::MITSUBA), "its film's Gaussian filter");
    for depth in [5, 8] {
        let (ok, text) = agrees(samplab(&box_, depth, None), mitsuba("cornell-box.xml", depth));
        assert!(ok, "depth {depth}: {text}");
    }
    let reference = mitsuba("cornell-box.xml", 8);
    // the criterion can fail: one segment fewer
    let (ok, text) = agrees(samplab(&box_, 7, None), reference);
    assert!(!ok, "depth 7 passed: {text}");
    // the film's Gaussian filter read as a box (the pixel area)
    let (ok, text) = agrees(samplab(&box_, 8, Some("area")), reference);
    assert!(!ok, "a box filter passed: {text}");
    // the light's own BSDF left out (black)
    let mut unlit = box_.clone();
    let light = unlit.lights[0].surface.unwrap() as usize;
    unlit.materials[light].albedo = samplab_render::scene::Texture::Constant(glam::DVec3::ZERO);
    let (ok, text) = agrees(samplab(&unlit, 8, None), reference);
    assert!(!ok, "a black light passed: {text}");
    // the light not a surface: it neither reflects nor blocks from behind
    let mut ghost = box_.clone();
    ghost.lights[0].surface = None;
    let (ok, text) = agrees(samplab(&ghost, 8, None), reference);
    assert!(!ok, "a light that blocks nothing passed: {text}");
}

#[test]
fn mitsubas_own_cbox_rgb_renders_as_mitsuba_renders_it() {
    let cbox = scene("cbox/cbox-rgb.xml");
    assert_eq!(cbox.footprint, Some(Footprint::Area), "its film's box filter");
    assert_eq!(cbox.lights.len(), 2, "the luminaire's two triangles");
    for depth in [5, 8] {
        let (ok, text) = agrees(samplab(&cbox, depth, None), mitsuba("cbox/cbox-rgb.xml", depth));
        assert!(ok, "depth {depth}: {text}");
    }
    // the criterion can fail: the luminaire, 5 mm below the ceiling, blocking nothing
    let mut ghost = cbox.clone();
    for light in &mut ghost.lights {
        light.surface = None;
    }
    let (ok, text) = agrees(samplab(&ghost, 8, None), mitsuba("cbox/cbox-rgb.xml", 8));
    assert!(!ok, "a light that blocks nothing passed: {text}");
}
