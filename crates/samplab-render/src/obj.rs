//! Wavefront OBJ triangle meshes: `v` positions, `vn` normals and `f` faces (any of the
//! `i`, `i/t`, `i/t/n`, `i//n` forms, negative indices counting back), polygons split into
//! fans. Texture coordinates, groups and materials are read past: samplab's materials come
//! from the scene, and it has no textures on meshes.
//!
//! Mitsuba 3 shades a mesh with vertex normals by them (unless the shape says
//! `face_normals`): a diffuse BSDF's front, and an area emitter's, is the side its
//! interpolated normal points to. samplab shades by face normals, so it reads a face's
//! vertex normals for that side only: normals parallel to the face (flat shading, as
//! exporters write for boxes) decide which side is the front; normals that bend away from
//! it (smooth shading) are refused, since samplab would render them differently.

use std::path::Path;

use glam::DVec3;

use samplab::error::excerpt;

use crate::error::{Error, Result};

/// The most a vertex normal of a flat face may lean from the face's normal, in radians:
/// the rounding of exporters that write 4 decimals, and a change of at most 1e-3 in any
/// cosine Mitsuba's shading frame would give.
pub const FLAT: f64 = 1e-3;

/// Whether a mesh's vertex normals are read (Mitsuba's default) or ignored (its shapes'
/// `face_normals`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Normals {
    /// A face's vertex normals say which side is its front.
    Vertex,
    /// Only the winding does.
    Face,
}

/// A triangle of an OBJ file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    /// Its corners, wound counter-clockwise seen from its front.
    pub corners: [DVec3; 3],
    /// Whether its vertex normals chose the front. Mitsuba transforms them as normals, so
    /// under a mirroring transform such a front lies on the other side of the winding.
    pub by_normals: bool,
}

/// The triangles of an OBJ file.
///
/// # Errors
/// The file cannot be read, a number does not parse or is not finite, an index is zero or
/// out of range, a face has fewer than three vertices, a vertex normal is zero or bends
/// away from its face, or a keyword is unknown; the error names the file and line.
pub fn load(path: &Path, normals: Normals) -> Result<Vec<Triangle>> {
    let (file, text) = read_scene_file(path)?;
    parse(&text, &file, normals)
}

/// A scene file's name (for errors) and text.
///
/// # Errors
/// The file cannot be read, is not a regular file (a device or a FIFO, whose reading may
/// never end), or is larger than the memory available.
pub(crate) fn read_scene_file(path: &Path) -> Result<(String, String)> {
    let file = path.display().to_string();
    let fail = |message: String| Error::Scene { file: file.clone(), line: 0, message };
    let meta = std::fs::metadata(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    if !meta.is_file() {
        return Err(fail("not a regular file".into()));
    }
    samplab::memory::check(|| format!("reading {file}"), u128::from(meta.len()))?;
    let text = std::fs::read_to_string(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    Ok((file, text))
}

/// Parse OBJ text; `file` names it in errors.
///
/// # Errors
/// As [`load`].
pub fn parse(text: &str, file: &str, normals: Normals) -> Result<Vec<Triangle>> {
    let (mut vertices, mut vertex_normals) = (Vec::new(), Vec::new());
    let mut triangles = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let fail = |message: String| Error::Scene { file: file.into(), line: k + 1, message };
        let line = raw.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else { continue };
        match keyword {
            "v" => vertices.push(xyz(&mut words, "vertex").map_err(&fail)?),
            "vn" => vertex_normals.push(xyz(&mut words, "vertex normal").map_err(&fail)?),
            "f" => {
                let mut corners = Vec::new();
                let mut shading = Vec::new();
                for w in words {
                    let mut fields = w.split('/');
                    corners.push(element(fields.next().unwrap_or(""), &vertices, "vertex", w).map_err(&fail)?);
                    match fields.nth(1) {
                        Some(n) if normals == Normals::Vertex && !n.is_empty() => {
                            shading.push(element(n, &vertex_normals, "vertex normal", w).map_err(&fail)?);
                        }
                        _ => {}
                    }
                }
                if corners.len() < 3 {
                    return Err(fail(format!("a face needs at least 3 vertices, found {}", corners.len())));
                }
                if !shading.is_empty() && shading.len() != corners.len() {
                    return Err(fail("a face gives vertex normals at some corners only".into()));
                }
                for i in 1..corners.len() - 1 {
                    let mut corners = [corners[0], corners[i], corners[i + 1]];
                    let by_normals = !shading.is_empty();
                    if by_normals {
                        let face = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
                        let side = front(face, [shading[0], shading[i], shading[i + 1]]).map_err(&fail)?;
                        if side < 0.0 {
                            corners.swap(1, 2);
                        }
                    }
                    triangles.push(Triangle { corners, by_normals });
                }
            }
            "vt" | "vp" | "o" | "g" | "s" | "usemtl" | "mtllib" | "l" | "p" => {}
            other => return Err(fail(format!("unknown OBJ keyword {}", excerpt(other)))),
        }
    }
    Ok(triangles)
}

/// The three coordinates of a `v` or `vn` line (`what`) that follow in `words`.
fn xyz<'a>(words: &mut impl Iterator<Item = &'a str>, what: &str) -> std::result::Result<DVec3, String> {
    let mut xyz = [0.0; 3];
    for (i, c) in xyz.iter_mut().enumerate() {
        let w = words.next().ok_or_else(|| format!("{what} needs 3 coordinates, found {i}"))?;
        *c = w.parse::<f64>().ok().filter(|x| x.is_finite()).ok_or_else(|| format!("bad coordinate {}", excerpt(w)))?;
    }
    Ok(DVec3::from(xyz))
}

/// The element a face corner's (1-based, or negative counting back) index `word` names.
fn element(word: &str, list: &[DVec3], what: &str, corner: &str) -> std::result::Result<DVec3, String> {
    let i: i64 = word.parse().map_err(|_| format!("bad {what} index {}", excerpt(corner)))?;
    let n = list.len() as i64;
    let at = if i > 0 { i - 1 } else { n + i };
    if i == 0 || !(0..n).contains(&at) {
        return Err(format!("{what} index {i} out of range (1..={n} defined so far)"));
    }
    Ok(list[at as usize])
}

/// Which side of a triangle with (unnormalized) normal `face` its corners' vertex normals
/// point to: 1 or -1, or 0 for a degenerate triangle, which nothing sees.
///
/// # Errors
/// A vertex normal is zero, or leans more than [`FLAT`] from the face's normal line.
fn front(face: DVec3, normals: [DVec3; 3]) -> std::result::Result<f64, String> {
    let Some(face) = face.try_normalize() else { return Ok(0.0) };
    let mut side = 0.0;
    for n in normals {
        let n = n.try_normalize().ok_or("a vertex normal is zero")?;
        let lean = n.angle_between(face).min(n.angle_between(-face));
        if lean > FLAT || (side != 0.0 && side * n.dot(face) < 0.0) {
            let how = if lean > FLAT { format!("by {:.2} degrees", lean.to_degrees()) } else { "to both sides".into() };
            return Err(format!(
                "vertex normals that bend away from their face ({how}): samplab shades by face normals \
                 only (give the shape <boolean name=\"face_normals\" value=\"true\"/> to render it flat, \
                 as Mitsuba then does)"
            ));
        }
        side = n.dot(face).signum();
    }
    Ok(side)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_in_every_index_form_make_fans() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                    f 1/1/1 2/1/1 3//1 4\nf -1 -2 -3\n";
        let t = parse(text, "q.obj", Normals::Face).unwrap();
        assert_eq!(t.len(), 3);
        assert_eq!(t[1].corners, [DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)]);
        assert_eq!(t[2].corners[0], DVec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn errors_name_the_line() {
        for (text, want) in [
            ("v 0 0 0\nv 1 nan 0\n", "q.obj:2: bad coordinate 'nan'"),
            ("v 0 0 0\nf 1 2 3\n", "q.obj:2: vertex index 2 out of range"),
            ("v 0 0\n", "q.obj:1: vertex needs 3 coordinates"),
            ("v 0 0 0\nv 0 0 1\nf 1 2\n", "q.obj:3: a face needs at least 3"),
            ("curv 1 2\n", "q.obj:1: unknown OBJ keyword 'curv'"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//1\n", "q.obj:5: vertex normal index 2 out of range"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3//1\n", "q.obj:5: a face gives vertex normals at some"),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n", "q.obj:5: a vertex normal is zero"),
            ("vn 1 x 0\n", "q.obj:1: bad coordinate 'x'"),
        ] {
            let e = parse(text, "q.obj", Normals::Vertex).unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}");
        }
    }

    /// A triangle in the plane z = 0 wound about +z, its corners given the vertex normals
    /// `normals` (one `vn` line each).
    fn shaded(normals: [&str; 3]) -> String {
        let vn: String = normals.iter().map(|n| format!("vn {n}\n")).collect();
        format!("v 0 0 0\nv 1 0 0\nv 0 1 0\n{vn}f 1//1 2//2 3//3\n")
    }

    #[test]
    fn flat_vertex_normals_choose_the_front_and_smooth_ones_are_refused() {
        let front = |text: &str, normals| {
            let [t] = parse(text, "q.obj", normals).unwrap()[..] else { panic!("one triangle") };
            let [a, b, c] = t.corners;
            ((b - a).cross(c - a).z.signum(), t.by_normals)
        };
        assert_eq!(front(&shaded(["0 0 1"; 3]), Normals::Vertex), (1.0, true));
        assert_eq!(front(&shaded(["0 0 -2"; 3]), Normals::Vertex), (-1.0, true), "rewound toward the normals");
        assert_eq!(front(&shaded(["0 0 -1"; 3]), Normals::Face), (1.0, false), "face_normals: the winding");
        // within FLAT of the face's normal line, as exporters round; beyond it refused
        let lean = |angle: f64| format!("{} 0 {}", angle.sin(), angle.cos());
        assert_eq!(front(&shaded([&lean(0.9 * FLAT), "0 0 1", "0 0 1"]), Normals::Vertex), (1.0, true));
        for text in [shaded([&lean(1.1 * FLAT), "0 0 1", "0 0 1"]), shaded(["0 0 1", "0 0 -1", "0 0 1"])] {
            let e = parse(&text, "q.obj", Normals::Vertex).unwrap_err().to_string();
            assert!(e.starts_with("q.obj:7: vertex normals that bend away from their face"), "{e}");
            assert_eq!(front(&text, Normals::Face), (1.0, false), "face_normals reads past them");
        }
    }
}
