//! Tests of [`super`].

use super::*;

#[test]
fn every_builtin_builds_with_every_light_it_accepts() {
    for b in BUILTINS.iter().filter(|b| b.about.name != "sphere-box-mesh") {
        let kinds: Vec<Option<LightKind>> =
            if b.default_light.is_some() { LightKind::ALL.iter().map(|(_, k)| Some(*k)).collect() } else { vec![None] };
        for k in kinds {
            let s = builtin(b.about.name, k).unwrap();
            assert!(s.camera.fov > 0.0);
        }
    }
    assert!(builtin("checker", Some(LightKind::Disk)).is_err());
    assert!(builtin("nope", None).is_err());
}

#[test]
fn cuboid_normals_point_outward() {
    let corner = DVec3::ZERO;
    for face in cuboid(corner, DVec3::X, DVec3::Y, DVec3::Z) {
        let Shape::Parallelogram { corner, u, v } = face else { unreachable!() };
        let centre = corner + 0.5 * (u + v);
        assert!(u.cross(v).dot(centre - DVec3::splat(0.5)) > 0.0, "{face:?}");
    }
}
