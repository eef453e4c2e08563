//! The Mitsuba 3 XML subset: a scene file read into the testbed, and refusals that name
//! the element and line.

use std::path::Path;

use glam::DVec3;
use samplab_render::light::LightShape;
use samplab_render::mitsuba::{load, parse};
use samplab_render::scene::{Finish, Texture};
use samplab_render::{Mode, Options, render};

#[test]
fn a_mitsuba_scene_loads_with_its_transforms_materials_and_light() {
    let scene = load(Path::new("tests/scenes/sphere-box.xml")).unwrap();
    assert_eq!(scene.resolution, (64, 48), "$res substituted from <default>");
    assert!((scene.camera.eye - DVec3::new(0.4, 2.2, 3.4)).length() < 1e-12);
    assert_eq!(scene.shapes(), 1 + 1 + 12, "ground, sphere, 6 quads as 12 triangles");
    let [light] = scene.lights[..] else { panic!("one light") };
    let LightShape::Disk { centre, u, v } = light.shape else { panic!("a disk light") };
    assert!((centre - DVec3::new(0.3, 2.4, 0.5)).length() < 1e-12);
    assert!((u.length() - 0.5).abs() < 1e-12 && (v.length() - 0.5).abs() < 1e-12);
    assert!((light.normal().unwrap() - DVec3::NEG_Y).length() < 1e-12, "rotated to face down");
    // it renders, and the lit ground is as bright as the disk's closed form says
    let o = Options { mode: Mode::Direct, ..Options::new("sobol.owen", 64, 64, 48).unwrap() };
    let img = render(&scene, &o, &samplab::progress::Progress::SILENT).unwrap().image;
    assert!(img.rgb.iter().all(|c| c.is_finite()) && img.rgb.iter().any(|&c| c > 0.1));
}

#[test]
fn unsupported_or_malformed_scenes_name_the_element_and_line() {
    let wrap = |body: &str| format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
    let sensor = "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/></sensor>";
    for (body, want) in [
        (format!("{sensor}\n<emitter type=\"envmap\"/>"), "s.xml:3: <emitter type=\"envmap\">"),
        (format!("{sensor}\n<bsdf type=\"plastic\" id=\"m\"/>"), "s.xml:3: <bsdf type=\"plastic\">: only diffuse"),
        (
            format!("{sensor}\n<bsdf type=\"conductor\" id=\"m\"><string name=\"material\" value=\"Au\"/></bsdf>"),
            "s.xml:3: <string>: not supported in a conductor",
        ),
        (
            format!("{sensor}\n<bsdf type=\"roughconductor\" id=\"m\"><float name=\"alpha\" value=\"1.5\"/></bsdf>"),
            "s.xml:3: alpha 1.5 is outside",
        ),
        (format!("{sensor}\n<shape type=\"rectangle\"><ref id=\"nope\"/></shape>"), "s.xml:3: no <bsdf id=\"nope\">"),
        (
            format!("{sensor}\n<shape type=\"sphere\"><float name=\"radius\" value=\"x1\"/></shape>"),
            "s.xml:3: value=\"x1\"",
        ),
        (format!("{sensor}\n<shape type=\"ply\"/>"), "s.xml:3: <shape type=\"ply\">"),
        (
            format!(
                "{sensor}\n<shape type=\"sphere\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>"
            ),
            "s.xml:3: <shape type=\"sphere\">: area emitters",
        ),
        ("<shape type=\"cube\"/>".to_string(), "s.xml:1: the scene has no <sensor>"),
        (
            format!("{sensor}\n<shape type=\"cube\">\n<transform name=\"to_world\"><skew/></transform></shape>"),
            "s.xml:4: <skew>",
        ),
        (format!("{sensor}\n<shape type=\"cube\"></shap>"), "s.xml:3: malformed XML"),
    ] {
        let e = parse(&wrap(&body), "s.xml", Path::new(".")).map(|_| ()).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\n  wanted: {want}");
    }
}

#[test]
fn conductors_are_mirrors_and_rough_ones_glossy() {
    let xml = r#"<scene version="3.0.0">
<sensor type="perspective"><float name="fov" value="40"/></sensor>
<bsdf type="conductor" id="m"><rgb name="specular_reflectance" value="0.8"/></bsdf>
<bsdf type="roughconductor" id="g"><float name="alpha" value="0.2"/><string name="distribution" value="beckmann"/></bsdf>
<shape type="rectangle"><ref id="m"/></shape>
<shape type="rectangle"><ref id="g"/></shape>
</scene>"#;
    let scene = parse(xml, "s.xml", Path::new(".")).unwrap();
    let finishes: Vec<Finish> = scene.materials.iter().map(|m| m.finish).collect();
    assert!(finishes.contains(&Finish::Mirror), "{finishes:?}");
    // Beckmann alpha 0.2 is Phong exponent 2 / 0.04 - 2 = 48
    assert!(finishes.iter().any(|f| matches!(f, Finish::Glossy { exponent } if (exponent - 48.0).abs() < 1e-9)));
    assert!(scene.materials.iter().any(|m| m.albedo == Texture::Constant(DVec3::splat(0.8))));
    assert!(scene.glossy());
}
