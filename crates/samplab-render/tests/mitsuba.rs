//! The Mitsuba 3 XML subset: a scene file read into the testbed, and refusals that name
//! the element and line.

use std::path::Path;

use glam::DVec3;
use samplab_render::light::LightShape;
use samplab_render::mitsuba::{Paths, load, parse};
use samplab_render::scene::{Distribution, Finish, Texture};
use samplab_render::{Mode, Options, render};

#[test]
fn a_mitsuba_scene_loads_with_its_transforms_materials_and_light() {
    let scene = load(Path::new("tests/scenes/sphere-box.xml"), Paths::InsideScene).unwrap();
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
        (format!("{sensor}\n<shape type=\"rectangle\"><ref id=\"nope\"/></shape>"), "s.xml:3: no <bsdf id=\"nope\"> or <emitter id=\"nope\">"),
        (
            format!("{sensor}\n<shape type=\"sphere\"><float name=\"radius\" value=\"x1\"/></shape>"),
            "s.xml:3: value=\"x1\"",
        ),
        (format!("{sensor}\n<shape type=\"ply\"/>"), "s.xml:3: <shape type=\"ply\">"),
        (
            format!("{sensor}\n<shape type=\"obj\"><shape type=\"obj\"/></shape>"),
            "s.xml:3: <shape type=\"obj\">: not supported in <shape type=\"obj\">",
        ),
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
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<film type=\"hdrfilm\"><integer name=\"crop_width\" value=\"8\"/></film></sensor>".into(),
            "s.xml:3: <integer>: not supported in a film",
        ),
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<film type=\"hdrfilm\"><rfilter type=\"lanczos\"/></film></sensor>".into(),
            "s.xml:3: <rfilter type=\"lanczos\">: filters: box, gaussian",
        ),
        (
            format!("{sensor}\n<bsdf type=\"twosided\" id=\"t\"><bsdf type=\"diffuse\"/>\n<bsdf type=\"diffuse\"/></bsdf>"),
            "s.xml:4: <bsdf type=\"diffuse\">: a second BSDF for the back side",
        ),
        (format!("{sensor}\n<include filename=\"absent.xml\"/>"), "s.xml:3: filename 'absent.xml': cannot read"),
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<float name=\"near_clip\" value=\"0\"/></sensor>".into(),
            "s.xml:2: near_clip 0 and far_clip 10000: Mitsuba needs 0 < near < far",
        ),
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<float name=\"far_clip\" value=\"0.001\"/></sensor>".into(),
            "s.xml:2: near_clip 0.01 and far_clip 0.001",
        ),
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<transform name=\"to_world\"><scale value=\"2\"/></transform></sensor>".into(),
            "s.xml:2: the sensor's to_world scales, shears or is singular",
        ),
        (
            "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n<transform name=\"to_world\"><scale x=\"-1\"/></transform></sensor>".into(),
            "s.xml:2: the sensor's to_world mirrors",
        ),
        (
            format!("{sensor}\n<shape type=\"sphere\"><boolean name=\"flip_normals\" value=\"true\"/></shape>"),
            "s.xml:3: <shape type=\"sphere\">: flip_normals",
        ),
        (
            format!("{sensor}\n<emitter type=\"area\" id=\"e\"><rgb name=\"irradiance\" value=\"1\"/></emitter>"),
            "s.xml:3: <rgb>: not supported in an area emitter",
        ),
    ] {
        let e = parse(&wrap(&body), "s.xml", Path::new("."), Paths::InsideScene).map(|_| ()).unwrap_err().to_string();
        assert!(e.starts_with(want), "{e}\n  wanted: {want}");
    }
}

/// What a ray straight down sees of a rectangle facing up (+z rotated to +y) and one facing
/// down, each wrapped in `twosided` or not: Mitsuba's BSDFs are black from behind.
#[test]
fn a_bsdf_reflects_on_its_front_only_unless_twosided() {
    use samplab_render::geometry::Ray;
    use samplab_render::scene::Seen;
    let seen = |angle: i32, twosided: bool| {
        let bsdf = "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf>";
        let bsdf = if twosided { format!("<bsdf type=\"twosided\">{bsdf}</bsdf>") } else { bsdf.to_string() };
        let xml = format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/></sensor>\
             <shape type=\"rectangle\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"{angle}\"/></transform>\
             {bsdf}</shape></scene>"
        );
        let scene = parse(&xml, "s.xml", Path::new("."), Paths::InsideScene).unwrap();
        let ray = Ray { origin: DVec3::new(0.1, 2.0, 0.2), dir: DVec3::NEG_Y, time: 0.0 };
        let mut hits = vec![];
        scene.trace(&[ray], &mut hits);
        match scene.seen(&ray, hits[0]) {
            Seen::Surface { albedo, normal, .. } => (albedo.x, normal.y),
            other => panic!("{other:?}"),
        }
    };
    assert_eq!(seen(-90, false), (0.8, 1.0), "the front, facing up");
    assert_eq!(seen(90, false), (0.0, 1.0), "the back: black");
    assert_eq!(seen(90, true), (0.8, 1.0), "the back of a twosided BSDF");
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
    let scene = parse(xml, "s.xml", Path::new("."), Paths::InsideScene).unwrap();
    let finishes: Vec<Finish> = scene.materials.iter().map(|m| m.finish).collect();
    assert!(finishes.contains(&Finish::Mirror), "{finishes:?}");
    assert!(finishes.contains(&Finish::Rough { alpha: 0.2, distribution: Distribution::Beckmann }));
    assert!(scene.materials.iter().any(|m| m.albedo == Texture::Constant(DVec3::splat(0.8))));
    assert!(scene.glossy());
}

/// A scene in a fresh folder whose one mesh is `filename`; the folder's path (under cargo's
/// scratch folder for integration tests, emptied here by the next run).
#[cfg(unix)]
fn scene_naming(name: &str, filename: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("confined-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("scene")).unwrap();
    let xml = std::fs::read_to_string("tests/scenes/sphere-box.xml").unwrap();
    assert!(xml.contains("\"cube.obj\""));
    std::fs::write(dir.join("scene/s.xml"), xml.replace("\"cube.obj\"", &format!("\"{filename}\""))).unwrap();
    std::fs::copy("tests/scenes/cube.obj", dir.join("scene/cube.obj")).unwrap();
    // a file outside the scene's folder, holding what must never be read or quoted
    std::fs::write(dir.join("secret.obj"), "password=hunter2!and-more\n").unwrap();
    dir
}

#[cfg(unix)]
#[test]
fn a_scene_cannot_make_samplab_read_a_file_outside_its_folder() {
    use std::os::unix::fs::symlink;
    let secret = |dir: &Path| dir.join("secret.obj").display().to_string();
    let refused = |dir: &Path| {
        let e = load(&dir.join("scene/s.xml"), Paths::InsideScene).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains("outside the scene's folder") && !e.contains("hunter2"), "{e}");
        // allowed: the file is read (and refused as a mesh, quoting at most a token)
        let e = load(&dir.join("scene/s.xml"), Paths::Anywhere).map(|_| ()).unwrap_err().to_string();
        assert!(e.contains("unknown OBJ keyword 'password=hunter2…'"), "{e}");
    };
    // `..`
    refused(&scene_naming("up", "../secret.obj"));
    // an absolute path
    let dir = scene_naming("absolute", "ABS");
    let xml = std::fs::read_to_string(dir.join("scene/s.xml")).unwrap().replace("ABS", &secret(&dir));
    std::fs::write(dir.join("scene/s.xml"), xml).unwrap();
    refused(&dir);
    // a link in the scene's folder leading out
    let dir = scene_naming("link", "mesh.obj");
    symlink(dir.join("secret.obj"), dir.join("scene/mesh.obj")).unwrap();
    refused(&dir);
    // a link inside a folder that is itself a link leading out
    let dir = scene_naming("folder-link", "meshes/mesh.obj");
    std::fs::create_dir(dir.join("elsewhere")).unwrap();
    symlink(dir.join("secret.obj"), dir.join("elsewhere/mesh.obj")).unwrap();
    symlink(dir.join("elsewhere"), dir.join("scene/meshes")).unwrap();
    refused(&dir);
    // a link that stays inside, and a subfolder, are fine
    let dir = scene_naming("inside", "sub/mesh.obj");
    std::fs::create_dir(dir.join("scene/sub")).unwrap();
    symlink(dir.join("scene/cube.obj"), dir.join("scene/sub/mesh.obj")).unwrap();
    assert_eq!(load(&dir.join("scene/s.xml"), Paths::InsideScene).unwrap().shapes(), 14);
    // a FIFO is refused before it is opened (an open would wait for a writer)
    let dir = scene_naming("fifo", "pipe.obj");
    let c = std::ffi::CString::new(dir.join("scene/pipe.obj").to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let e = load(&dir.join("scene/s.xml"), Paths::InsideScene).map(|_| ()).unwrap_err().to_string();
    assert!(e.contains("not a regular file"), "{e}");
}

/// A scene's `path` integrator sets path mode's depth unless the render sets its own (the
/// Mitsuba Cornell box asks for 8, which samplab rendered at its default 5), and a number
/// Mitsuba reads where it takes a float may be written as an integer.
#[test]
fn the_scenes_max_depth_and_integer_numbers_are_read_as_mitsuba_reads_them() {
    use samplab_render::settings::Settings;
    let text = std::fs::read_to_string("tests/scenes/sphere-box.xml").unwrap();
    let with = |integrator: &str| {
        let text = text.replacen("<sensor", &format!("{integrator}\n<sensor"), 1);
        parse(&text, "s.xml", Path::new("tests/scenes"), Paths::InsideScene)
    };
    let deep = with("<integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/><integer name=\"rr_depth\" value=\"3\"/></integrator>").unwrap();
    assert_eq!(deep.max_depth, Some(2));
    let plain = load(Path::new("tests/scenes/sphere-box.xml"), Paths::InsideScene).unwrap();
    assert_eq!(plain.max_depth, None);
    let path = |max_depth| Settings { mode: "path".into(), max_depth, res: Some((8, 6)), ..Settings::default() };
    let depth = |scene, s: Settings| match s.options(scene).unwrap().mode {
        Mode::Path { max_depth } => max_depth,
        other => panic!("{other:?}"),
    };
    assert_eq!(depth(&deep, path(None)), 2, "the scene's depth");
    assert_eq!(depth(&deep, path(Some(7))), 7, "the render's own");
    assert_eq!(depth(&plain, path(None)), samplab_render::settings::MAX_DEPTH as u32);
    // outside path mode the scene's depth is not an error: the render did not set one
    assert!(Settings { res: Some((8, 6)), ..Settings::default() }.options(&deep).is_ok());
    for (integrator, want) in [
        ("<integrator type=\"path\"><integer name=\"max_depth\" value=\"-1\"/></integrator>", "max_depth -1"),
        ("<integrator type=\"path\"><boolean name=\"hide_emitters\" value=\"true\"/></integrator>", "<boolean>"),
    ] {
        let e = with(integrator).unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
    }
    let focus = |kind: &str| {
        let t = text.replacen(
            "<float name=\"fov\"",
            &format!("<{kind} name=\"focus_distance\" value=\"3\"/><float name=\"fov\""),
            1,
        );
        parse(&t, "s.xml", Path::new("tests/scenes"), Paths::InsideScene).unwrap().camera.focus
    };
    assert_eq!(focus("integer"), 3.0);
    assert_eq!(focus("integer"), focus("float"));
}
