//! Wavefront OBJ triangle meshes: `v` positions and `f` faces (any of the `i`, `i/t`,
//! `i/t/n`, `i//n` forms, negative indices counting back), polygons split into fans.
//! Texture coordinates, normals, groups and materials are read past.

use std::path::Path;

use glam::DVec3;

use samplab::error::excerpt;

use crate::error::{Error, Result};

/// The triangles of an OBJ file, as vertex triples.
///
/// # Errors
/// The file cannot be read, a number does not parse or is not finite, an index is zero or
/// out of range, a face has fewer than three vertices, or a keyword is unknown; the error
/// names the file and line.
pub fn load(path: &Path) -> Result<Vec<[DVec3; 3]>> {
    let (file, text) = read_scene_file(path)?;
    parse(&text, &file)
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
pub fn parse(text: &str, file: &str) -> Result<Vec<[DVec3; 3]>> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut triangles = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let fail = |message: String| Error::Scene { file: file.into(), line: k + 1, message };
        let line = raw.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else { continue };
        match keyword {
            "v" => {
                let mut xyz = [0.0; 3];
                for (i, c) in xyz.iter_mut().enumerate() {
                    let w = words.next().ok_or_else(|| fail(format!("vertex needs 3 coordinates, found {i}")))?;
                    *c = w
                        .parse::<f64>()
                        .ok()
                        .filter(|x| x.is_finite())
                        .ok_or_else(|| fail(format!("bad coordinate {}", excerpt(w))))?;
                }
                vertices.push(DVec3::from(xyz));
            }
            "f" => {
                let corners = words
                    .map(|w| {
                        let first = w.split('/').next().unwrap_or("");
                        let i: i64 = first.parse().map_err(|_| fail(format!("bad vertex index {}", excerpt(w))))?;
                        let n = vertices.len() as i64;
                        let at = if i > 0 { i - 1 } else { n + i };
                        if i == 0 || !(0..n).contains(&at) {
                            return Err(fail(format!("vertex index {i} out of range (1..={n} defined so far)")));
                        }
                        Ok(vertices[at as usize])
                    })
                    .collect::<Result<Vec<DVec3>>>()?;
                if corners.len() < 3 {
                    return Err(fail(format!("a face needs at least 3 vertices, found {}", corners.len())));
                }
                for i in 1..corners.len() - 1 {
                    triangles.push([corners[0], corners[i], corners[i + 1]]);
                }
            }
            "vt" | "vn" | "vp" | "o" | "g" | "s" | "usemtl" | "mtllib" | "l" | "p" => {}
            other => return Err(fail(format!("unknown OBJ keyword {}", excerpt(other)))),
        }
    }
    Ok(triangles)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_in_every_index_form_make_fans() {
        let text = "# a quad and a triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                    f 1/1/1 2/1/1 3//1 4\nf -1 -2 -3\n";
        let t = parse(text, "q.obj").unwrap();
        assert_eq!(t.len(), 3);
        assert_eq!(t[1], [DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), DVec3::new(0.0, 1.0, 0.0)]);
        assert_eq!(t[2][0], DVec3::new(0.0, 1.0, 0.0));
    }

    #[test]
    fn errors_name_the_line() {
        for (text, want) in [
            ("v 0 0 0\nv 1 nan 0\n", "q.obj:2: bad coordinate 'nan'"),
            ("v 0 0 0\nf 1 2 3\n", "q.obj:2: vertex index 2 out of range"),
            ("v 0 0\n", "q.obj:1: vertex needs 3 coordinates"),
            ("v 0 0 0\nv 0 0 1\nf 1 2\n", "q.obj:3: a face needs at least 3"),
            ("curv 1 2\n", "q.obj:1: unknown OBJ keyword 'curv'"),
        ] {
            let e = parse(text, "q.obj").unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}");
        }
    }
}
