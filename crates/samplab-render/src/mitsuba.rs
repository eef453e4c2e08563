//! The subset of the Mitsuba 3 XML scene format these experiments need: a `perspective`
//! or `thinlens` sensor (`lookat` or matrix `to_world`, `fov`, `fov_axis`, film size),
//! `diffuse`, `conductor` (a perfect mirror) and `roughconductor` (Beckmann or GGX microfacets,
//! reflecting fully) BSDFs (also inside `twosided`, by `id` and `ref`), shapes `rectangle`, `disk`,
//! `sphere`, `cube` and `obj` with `to_world` transforms (`translate`, `scale`, `rotate`,
//! `matrix`, `lookat`), `area` emitters with a radiance on rectangles and disks, and
//! `<default>` parameters with `$name` substitution. Anything else is refused with its
//! element and line, never skipped silently (a `path` integrator's `max_depth` is path mode's
//! depth unless the render sets one; other integrators and samplers are read past: the
//! testbed has its own). Mitsuba's numbers may be written as `<integer>` where it takes a
//! float.
//!
//! Two differences from Mitsuba remain, so that a file meant to render the same in both
//! wraps open surfaces in `twosided` and gives each emitter shape a black BSDF: samplab's
//! surfaces reflect on both sides, and its lights reflect nothing and block nothing
//! (Mitsuba gives an emitter shape a grey diffuse BSDF unless told otherwise).

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

use glam::{DAffine3, DMat3, DMat4, DVec3};
use roxmltree::Node;

use crate::bvh::{Bvh, Object};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::geometry::Shape;
use crate::light::{DiskMap, Light, LightShape};
use crate::scene::{Distribution, Finish, Material, Scene, Texture};
use crate::scenes::cuboid;

/// Where the files a scene names (OBJ meshes) may be.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Paths {
    /// In the scene's folder or below it: a path with `..`, an absolute path, or a link
    /// leading out of the folder is refused, so a scene received from someone else cannot
    /// make samplab read (and quote) the user's other files.
    #[default]
    InsideScene,
    /// Anywhere (the CLI's `--allow-paths-outside-scene`, for the user's own scenes).
    Anywhere,
}

/// Load a Mitsuba 3 XML scene; the files it names must be where `paths` allows.
///
/// # Errors
/// The file cannot be read or parsed, or uses an element this subset does not support, or
/// names a file outside its folder (under [`Paths::InsideScene`]); the message names the
/// file, line and element.
pub fn load(path: &Path, paths: Paths) -> Result<Scene> {
    let (file, text) = crate::obj::read_scene_file(path)?;
    parse(&text, &file, path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new(".")), paths)
}

/// Parse Mitsuba XML text; `file` names it in errors, OBJ files are found relative to `dir`,
/// where `paths` allows.
///
/// # Errors
/// As [`load`].
pub fn parse(text: &str, file: &str, dir: &Path, paths: Paths) -> Result<Scene> {
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let pos = e.pos();
        Error::Scene { file: file.into(), line: pos.row as usize, message: format!("malformed XML: {e}") }
    })?;
    // the reader descends recursively: a scene nested deeper than any real one is refused
    // (each node's depth from its parent's: nodes come in document order, parents first)
    let mut depth = vec![0usize; doc.descendants().count()];
    for node in doc.descendants() {
        let d = node.parent().map_or(0, |p| depth[p.id().get() as usize]) + usize::from(node.is_element());
        depth[node.id().get() as usize] = d;
        if d > MAX_NESTING {
            let line = doc.text_pos_at(node.range().start).row as usize;
            let message = format!("elements nested more than {MAX_NESTING} deep");
            return Err(Error::Scene { file: file.into(), line, message });
        }
    }
    let mut reader = Reader { file, doc: &doc, dir, paths, defaults: HashMap::new(), bsdfs: HashMap::new() };
    reader.scene(doc.root_element())
}

/// The deepest nesting of elements a scene may have (Mitsuba's own scenes nest a few
/// levels: scene, shape, bsdf, twosided's bsdf, texture, its transform).
const MAX_NESTING: usize = 64;

struct Reader<'a, 'input> {
    file: &'a str,
    doc: &'a roxmltree::Document<'input>,
    dir: &'a Path,
    paths: Paths,
    defaults: HashMap<String, String>,
    bsdfs: HashMap<String, Material>,
}

struct Built {
    camera: Option<Camera>,
    resolution: (usize, usize),
    materials: Vec<Material>,
    objects: Vec<Object>,
    lights: Vec<Light>,
    max_depth: Option<usize>,
}

fn grey(v: f64) -> Material {
    Material::diffuse(DVec3::splat(v))
}

impl Reader<'_, '_> {
    fn fail(&self, node: Node, message: impl Into<String>) -> Error {
        let line = self.doc.text_pos_at(node.range().start).row as usize;
        Error::Scene { file: self.file.into(), line, message: message.into() }
    }

    fn unsupported(&self, node: Node, what: &str) -> Error {
        let kind = node.attribute("type").map(|t| format!(" type=\"{t}\"")).unwrap_or_default();
        self.fail(node, format!("<{}{kind}>: {what}", node.tag_name().name()))
    }

    /// An attribute with `$name` defaults substituted.
    fn attr(&self, node: Node, name: &str) -> Result<String> {
        let raw = node
            .attribute(name)
            .ok_or_else(|| self.fail(node, format!("<{}> needs a '{name}' attribute", node.tag_name().name())))?;
        match raw.strip_prefix('$') {
            Some(key) => self
                .defaults
                .get(key)
                .cloned()
                .ok_or_else(|| self.fail(node, format!("'${key}' has no <default name=\"{key}\">"))),
            None => Ok(raw.to_string()),
        }
    }

    fn numbers(&self, node: Node, name: &str) -> Result<Vec<f64>> {
        let text = self.attr(node, name)?;
        text.split(|c: char| c == ',' || c.is_whitespace())
            .filter(|w| !w.is_empty())
            .map(|w| {
                w.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| self.fail(node, format!("{name}=\"{text}\": '{w}' is not a finite number")))
            })
            .collect()
    }

    fn number(&self, node: Node, name: &str) -> Result<f64> {
        match self.numbers(node, name)?[..] {
            [x] => Ok(x),
            _ => Err(self.fail(node, format!("{name} must be one number"))),
        }
    }

    fn vector(&self, node: Node, name: &str) -> Result<DVec3> {
        match self.numbers(node, name)?[..] {
            [x] => Ok(DVec3::splat(x)),
            [x, y, z] => Ok(DVec3::new(x, y, z)),
            _ => Err(self.fail(node, format!("{name} must be 1 or 3 numbers"))),
        }
    }

    /// `x`, `y`, `z` attributes (missing ones `missing`) or a `value` triple.
    fn xyz(&self, node: Node, missing: f64) -> Result<DVec3> {
        if node.attribute("value").is_some() {
            return self.vector(node, "value");
        }
        let mut v = DVec3::splat(missing);
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            if node.attribute(axis).is_some() {
                v[i] = self.number(node, axis)?;
            }
        }
        Ok(v)
    }

    /// The file a `filename` names, where [`Paths`] allows it.
    fn file_path(&self, node: Node, name: &str) -> Result<PathBuf> {
        let path = self.dir.join(name);
        if self.paths == Paths::Anywhere {
            return Ok(path);
        }
        let refuse = |why: &str| {
            let name = samplab::error::excerpt(name);
            self.fail(node, format!("filename {name} {why}; allow it with --allow-paths-outside-scene"))
        };
        if Path::new(name).components().any(|c| !matches!(c, Component::Normal(_) | Component::CurDir)) {
            return Err(refuse("leads outside the scene's folder"));
        }
        let real = |p: &Path| std::fs::canonicalize(p);
        match (real(self.dir), real(&path)) {
            (Ok(dir), Ok(file)) if file.starts_with(&dir) => Ok(file),
            (Ok(_), Ok(_)) => Err(refuse("is a link leading outside the scene's folder")),
            (_, Err(e)) | (Err(e), _) => {
                Err(self.fail(node, format!("filename {}: cannot read: {e}", samplab::error::excerpt(name))))
            }
        }
    }

    fn scene(&mut self, root: Node) -> Result<Scene> {
        if root.tag_name().name() != "scene" {
            return Err(self.fail(root, format!("the root element is <{}>, not <scene>", root.tag_name().name())));
        }
        let mut built = Built {
            camera: None,
            resolution: (256, 256),
            materials: vec![grey(0.5)],
            objects: vec![],
            lights: vec![],
            max_depth: None,
        };
        for node in root.children().filter(Node::is_element) {
            match node.tag_name().name() {
                "default" => {
                    let (name, value) = (self.attr(node, "name")?, self.attr(node, "value")?);
                    self.defaults.entry(name).or_insert(value);
                }
                "integrator" => self.integrator(node, &mut built)?,
                "sampler" => {}
                "sensor" => self.sensor(node, &mut built)?,
                "bsdf" => {
                    let id = self.attr(node, "id")?;
                    let m = self.bsdf(node)?;
                    self.bsdfs.insert(id, m);
                }
                "shape" => self.shape(node, &mut built)?,
                _ => return Err(self.unsupported(node, "not supported by samplab's Mitsuba subset")),
            }
        }
        let camera = built.camera.ok_or_else(|| self.fail(root, "the scene has no <sensor>"))?;
        Ok(Scene {
            camera,
            materials: built.materials,
            bvh: Bvh::new(built.objects),
            planes: vec![],
            lights: built.lights,
            resolution: built.resolution,
            max_depth: built.max_depth,
        })
    }

    /// A `path` integrator's `max_depth` (a path's most segments; -1, Mitsuba's unlimited,
    /// is refused: samplab's paths end at a depth); its roulette depth (`rr_depth`) changes
    /// no expectation and is read past. Any other integrator is read past (the render's
    /// `--mode` chooses the estimator); a property samplab would not honour is refused.
    fn integrator(&self, node: Node, built: &mut Built) -> Result<()> {
        if self.attr(node, "type")? != "path" {
            return Ok(());
        }
        for c in node.children().filter(Node::is_element) {
            match (c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                ("integer", "max_depth") => {
                    let v = self.attr(c, "value")?;
                    let depth =
                        v.parse::<usize>().ok().filter(|d| crate::path::check_depth(*d).is_ok()).ok_or_else(|| {
                            self.fail(
                                c,
                                format!(
                                    "max_depth {v}: samplab's paths have 1 to {} segments (no unlimited depth)",
                                    crate::path::MAX_DEPTH
                                ),
                            )
                        })?;
                    built.max_depth = Some(depth);
                }
                ("integer", "rr_depth") => {}
                ("boolean", "hide_emitters") if self.attr(c, "value")? == "false" => {}
                _ => return Err(self.unsupported(c, "not supported in a path integrator")),
            }
        }
        Ok(())
    }

    fn sensor(&self, node: Node, built: &mut Built) -> Result<()> {
        let kind = self.attr(node, "type")?;
        if kind != "perspective" && kind != "thinlens" {
            return Err(self.unsupported(node, "only perspective and thinlens sensors are supported"));
        }
        let (mut fov, mut axis, mut to_world) = (None, "x".to_string(), DMat4::IDENTITY);
        let mut camera =
            Camera { eye: DVec3::ZERO, target: DVec3::Z, up: DVec3::Y, fov: 0.0, aperture: 0.0, focus: 1.0 };
        for c in node.children().filter(Node::is_element) {
            match (c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                // Mitsuba reads an <integer> where it takes a float
                ("float" | "integer", "fov") => fov = Some(self.number(c, "value")?),
                ("string", "fov_axis") => axis = self.attr(c, "value")?,
                ("float" | "integer", "aperture_radius") => camera.aperture = self.number(c, "value")?,
                ("float" | "integer", "focus_distance") => camera.focus = self.number(c, "value")?,
                ("float" | "integer", "near_clip" | "far_clip") => {}
                ("transform", "to_world") => to_world = self.transform(c)?,
                ("film", _) => {
                    for f in c.children().filter(Node::is_element) {
                        match (f.tag_name().name(), f.attribute("name").unwrap_or("")) {
                            ("integer", "width") => built.resolution.0 = self.count(f)?,
                            ("integer", "height") => built.resolution.1 = self.count(f)?,
                            _ => {}
                        }
                    }
                }
                ("sampler", _) => {}
                _ => return Err(self.unsupported(c, "not supported in a sensor")),
            }
        }
        let fov = fov.ok_or_else(|| self.fail(node, "the sensor needs <float name=\"fov\">"))?;
        if !(0.0..180.0).contains(&fov) || fov == 0.0 {
            return Err(self.fail(node, format!("fov {fov} is out of range (0, 180) degrees")));
        }
        let (w, h) = (built.resolution.0 as f64, built.resolution.1 as f64);
        let to_x = |f: f64| 2.0 * ((0.5 * f.to_radians()).tan() * w / h).atan().to_degrees();
        camera.fov = match axis.as_str() {
            "x" => fov,
            "y" => to_x(fov),
            "smaller" if h < w => to_x(fov),
            "larger" if h > w => to_x(fov),
            "smaller" | "larger" => fov,
            other => {
                return Err(self.fail(node, format!("fov_axis '{other}' is not supported (x, y, smaller, larger)")));
            }
        };
        // a singular matrix maps the camera's frame to a plane, a line or a point
        let det = DMat3::from_mat4(to_world).determinant();
        if !det.is_finite() || det.abs() < 1e-12 {
            return Err(
                self.fail(node, format!("the sensor's to_world is singular (determinant {det:e}): no camera frame"))
            );
        }
        camera.eye = to_world.transform_point3(DVec3::ZERO);
        camera.target = camera.eye + to_world.transform_vector3(DVec3::Z);
        camera.up = to_world.transform_vector3(DVec3::Y);
        built.camera = Some(camera);
        Ok(())
    }

    fn count(&self, node: Node) -> Result<usize> {
        let v = self.attr(node, "value")?;
        v.parse::<usize>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| self.fail(node, format!("'{v}' is not a positive integer")))
    }

    fn transform(&self, node: Node) -> Result<DMat4> {
        let mut m = DMat4::IDENTITY;
        for op in node.children().filter(Node::is_element) {
            let step = match op.tag_name().name() {
                "translate" => DMat4::from_translation(self.xyz(op, 0.0)?),
                "scale" => DMat4::from_scale(self.xyz(op, 1.0)?),
                "rotate" => {
                    let axis = self.xyz(op, 0.0)?;
                    if axis.length_squared() == 0.0 {
                        return Err(self.fail(op, "<rotate> needs a non-zero axis"));
                    }
                    DMat4::from_axis_angle(axis.normalize(), self.number(op, "angle")?.to_radians())
                }
                "matrix" => {
                    let v = self.numbers(op, "value")?;
                    if v.len() != 16 {
                        return Err(self.fail(op, format!("<matrix> needs 16 numbers, found {}", v.len())));
                    }
                    DMat4::from_cols_slice(&v).transpose() // Mitsuba writes rows
                }
                "lookat" => {
                    let (origin, target) = (self.vector(op, "origin")?, self.vector(op, "target")?);
                    let up = if op.attribute("up").is_some() { self.vector(op, "up")? } else { DVec3::Y };
                    let dir = (target - origin).normalize();
                    let left = up.cross(dir);
                    if !dir.is_finite() || left.length_squared() == 0.0 {
                        return Err(self.fail(op, "<lookat> with origin = target or up parallel to the view"));
                    }
                    let left = left.normalize();
                    let up = dir.cross(left);
                    DMat4::from_cols(left.extend(0.0), up.extend(0.0), dir.extend(0.0), origin.extend(1.0))
                }
                _ => return Err(self.unsupported(op, "not a supported transform")),
            };
            m = step * m;
        }
        Ok(m)
    }

    fn bsdf(&self, node: Node) -> Result<Material> {
        match self.attr(node, "type")?.as_str() {
            "twosided" => {
                let inner =
                    node.children().find(Node::is_element).ok_or_else(|| self.fail(node, "<twosided> needs a BSDF"))?;
                self.bsdf(inner)
            }
            "diffuse" => {
                let mut m = grey(0.5);
                for c in node.children().filter(Node::is_element) {
                    if c.attribute("name") != Some("reflectance") {
                        return Err(self.unsupported(c, "not supported in a diffuse BSDF"));
                    }
                    m.albedo = Texture::Constant(self.colour(c)?);
                }
                Ok(m)
            }
            // a perfect mirror (Mitsuba's default material "none"), and a rough one: Walter et
            // al. 2007's microfacet model, Beckmann (Mitsuba's default) or GGX
            kind @ ("conductor" | "roughconductor") => {
                let (mut reflectance, mut alpha, mut distribution) = (DVec3::ONE, 0.1, Distribution::Beckmann);
                for c in node.children().filter(Node::is_element) {
                    match (kind, c.attribute("name").unwrap_or("")) {
                        (_, "specular_reflectance") => reflectance = self.colour(c)?,
                        ("roughconductor", "alpha") => alpha = self.number(c, "value")?,
                        ("roughconductor", "distribution") => {
                            distribution = match c.attribute("value") {
                                Some("beckmann") => Distribution::Beckmann,
                                Some("ggx") => Distribution::Ggx,
                                _ => return Err(self.unsupported(c, "distributions: beckmann, ggx")),
                            }
                        }
                        _ => return Err(self.unsupported(c, &format!("not supported in a {kind} BSDF"))),
                    }
                }
                let finish = if kind == "conductor" {
                    Finish::Mirror
                } else if alpha > 0.0 && alpha < 1.0 {
                    Finish::Rough { alpha, distribution }
                } else {
                    return Err(self.fail(node, format!("alpha {alpha} is outside (0, 1)")));
                };
                Ok(Material { finish, ..Material::diffuse(reflectance) })
            }
            _ => Err(self.unsupported(node, "only diffuse, conductor and roughconductor BSDFs are supported")),
        }
    }

    fn colour(&self, node: Node) -> Result<DVec3> {
        match node.tag_name().name() {
            "rgb" | "spectrum" | "float" => self.vector(node, "value"),
            _ => Err(self.unsupported(node, "a colour must be <rgb>, <float> or a constant <spectrum>")),
        }
    }

    fn shape(&self, node: Node, built: &mut Built) -> Result<()> {
        let kind = self.attr(node, "type")?;
        let (mut to_world, mut material, mut emitter) = (DMat4::IDENTITY, 0u32, None);
        let (mut centre, mut radius, mut filename, mut flip) = (DVec3::ZERO, 1.0, None, false);
        for c in node.children().filter(Node::is_element) {
            match (c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                ("transform", "to_world") => to_world = self.transform(c)?,
                ("ref", _) => {
                    let id = self.attr(c, "id")?;
                    let m = self
                        .bsdfs
                        .get(&id)
                        .ok_or_else(|| self.fail(c, format!("no <bsdf id=\"{id}\"> before this")))?;
                    built.materials.push(*m);
                    material = built.materials.len() as u32 - 1;
                }
                ("bsdf", _) => {
                    built.materials.push(self.bsdf(c)?);
                    material = built.materials.len() as u32 - 1;
                }
                ("emitter", _) => {
                    if self.attr(c, "type")? != "area" {
                        return Err(self.unsupported(c, "only area emitters on shapes are supported"));
                    }
                    let radiance = c
                        .children()
                        .find(|r| r.is_element() && r.attribute("name") == Some("radiance"))
                        .ok_or_else(|| self.fail(c, "an area emitter needs a radiance"))?;
                    emitter = Some(self.colour(radiance)?);
                }
                ("point", "center") => centre = self.xyz(c, 0.0)?,
                ("float", "radius") => radius = self.number(c, "value")?,
                ("string", "filename") => filename = Some(self.attr(c, "filename").or_else(|_| self.attr(c, "value"))?),
                ("boolean", "flip_normals") => flip = self.attr(c, "value")? == "true",
                ("boolean", "face_normals") => {}
                _ => return Err(self.unsupported(c, &format!("not supported in <shape type=\"{kind}\">"))),
            }
        }
        let affine = DAffine3::from_mat4(to_world);
        let point = |p: DVec3| affine.transform_point3(p);
        let vector = |v: DVec3| affine.transform_vector3(v);
        let (mut u, mut v) = (vector(DVec3::X), vector(DVec3::Y));
        if flip {
            std::mem::swap(&mut u, &mut v);
        }
        let mut push = |shape| built.objects.push(Object { shape, material });
        match (kind.as_str(), emitter) {
            ("rectangle", None) => {
                push(Shape::Parallelogram { corner: point(DVec3::new(-1.0, -1.0, 0.0)), u: 2.0 * u, v: 2.0 * v })
            }
            ("rectangle", Some(radiance)) => built.lights.push(Light {
                shape: LightShape::Parallelogram { corner: point(DVec3::new(-1.0, -1.0, 0.0)), u: 2.0 * u, v: 2.0 * v },
                radiance,
                falloff: None,
                disk_map: DiskMap::Concentric,
            }),
            ("disk", Some(radiance)) => built.lights.push(Light {
                shape: LightShape::Disk { centre: point(DVec3::ZERO), u, v },
                radiance,
                falloff: None,
                disk_map: DiskMap::Concentric,
            }),
            ("disk", None) => {
                let r = u.length();
                if (v.length() - r).abs() > 1e-9 * r || u.dot(v).abs() > 1e-9 * r * r {
                    return Err(
                        self.fail(node, "<shape type=\"disk\">: non-uniform scales make an ellipse, unsupported")
                    );
                }
                push(Shape::Disk { centre: point(DVec3::ZERO), normal: u.cross(v).normalize(), radius: r });
            }
            ("sphere", None) => {
                let m3 = DMat3::from_mat4(to_world);
                let scale = m3.x_axis.length();
                if (m3.y_axis.length() - scale).abs() > 1e-9 * scale
                    || (m3.z_axis.length() - scale).abs() > 1e-9 * scale
                {
                    return Err(
                        self.fail(node, "<shape type=\"sphere\">: non-uniform scales make an ellipsoid, unsupported")
                    );
                }
                push(Shape::Sphere { centre: point(centre), radius: radius * scale, velocity: DVec3::ZERO });
            }
            ("cube", None) => {
                for face in cuboid(
                    point(DVec3::splat(-1.0)),
                    2.0 * vector(DVec3::X),
                    2.0 * vector(DVec3::Y),
                    2.0 * vector(DVec3::Z),
                ) {
                    push(face);
                }
            }
            ("obj", None) => {
                let name =
                    filename.ok_or_else(|| self.fail(node, "<shape type=\"obj\"> needs <string name=\"filename\">"))?;
                for [a, b, c] in crate::obj::load(&self.file_path(node, &name)?)? {
                    let (a, b, c) = (point(a), point(b), point(c));
                    push(Shape::Triangle { p: a, e1: b - a, e2: c - a });
                }
            }
            ("sphere" | "cube" | "obj", Some(_)) => {
                return Err(self.unsupported(node, "area emitters are supported on rectangles and disks only"));
            }
            _ => return Err(self.unsupported(node, "shapes: rectangle, disk, sphere, cube, obj")),
        }
        Ok(())
    }
}
