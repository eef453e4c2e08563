//! The elements of a Mitsuba scene the reader turns into samplab's: emitters, the
//! integrator, the sensor and its film and filter, transforms, BSDFs and shapes.

use super::{Built, Part, Reader, default_bsdf};
use crate::camera::Camera;
use crate::error::Result;
use crate::filter::Footprint;
use crate::geometry::Shape;
use crate::light::LightShape;
use crate::obj::Normals;
use crate::scene::{Distribution, Finish, Material, Texture};
use crate::scenes::cuboid;
use glam::{DAffine3, DMat3, DMat4, DVec3};
use roxmltree::Node;

impl Reader<'_, '_> {
    /// An area emitter's radiance.
    pub(super) fn emitter(&self, node: Node) -> Result<DVec3> {
        if self.attr(node, "type")? != "area" {
            return Err(self.unsupported(node, "only area emitters on shapes are supported"));
        }
        let mut radiance = None;
        for c in node.children().filter(Node::is_element) {
            match c.attribute("name") {
                Some("radiance") => radiance = Some(self.colour(c)?),
                _ => return Err(self.unsupported(c, "not supported in an area emitter")),
            }
        }
        radiance.ok_or_else(|| self.fail(node, "an area emitter needs a radiance"))
    }

    /// A `path` integrator's `max_depth` (a path's most segments; -1, Mitsuba's unlimited,
    /// is refused: samplab's paths end at a depth); its roulette depth (`rr_depth`) changes
    /// no expectation and is read past. Any other integrator is read past (the render's
    /// `--mode` chooses the estimator); a property samplab would not honour is refused.
    pub(super) fn integrator(&self, node: Node, built: &mut Built) -> Result<()> {
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
                // Russian roulette changes a path's noise, not its expectation
                ("integer", "rr_depth") => {}
                ("boolean", "hide_emitters") if self.attr(c, "value")? == "false" => {}
                _ => return Err(self.unsupported(c, "not supported in a path integrator")),
            }
        }
        Ok(())
    }

    pub(super) fn sensor(&self, node: Node, built: &mut Built) -> Result<()> {
        let kind = self.attr(node, "type")?;
        if kind != "perspective" && kind != "thinlens" {
            return Err(self.unsupported(node, "only perspective and thinlens sensors are supported"));
        }
        let (mut fov, mut axis, mut to_world) = (None, "x".to_string(), DMat4::IDENTITY);
        // Mitsuba's default clipping planes
        let mut camera = Camera {
            eye: DVec3::ZERO,
            target: DVec3::Z,
            up: DVec3::Y,
            fov: 0.0,
            aperture: 0.0,
            focus: 1.0,
            clip: [1e-2, 1e4],
        };
        for c in node.children().filter(Node::is_element) {
            match (c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                // Mitsuba reads an <integer> where it takes a float
                ("float" | "integer", "fov") => fov = Some(self.number(c, "value")?),
                ("string", "fov_axis") => axis = self.attr(c, "value")?,
                ("float" | "integer", "aperture_radius") => camera.aperture = self.number(c, "value")?,
                ("float" | "integer", "focus_distance") => camera.focus = self.number(c, "value")?,
                ("float" | "integer", "near_clip") => camera.clip[0] = self.number(c, "value")?,
                ("float" | "integer", "far_clip") => camera.clip[1] = self.number(c, "value")?,
                ("transform", "to_world") => to_world = self.transform(c)?,
                ("film", _) => self.film(c, built)?,
                // as a top-level sampler
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
        let [near, far] = camera.clip;
        if near <= 0.0 || far <= near {
            return Err(self.fail(node, format!("near_clip {near} and far_clip {far}: Mitsuba needs 0 < near < far")));
        }
        // Mitsuba refuses a camera transform that scales (and so one that shears or is
        // singular), with the same tolerance on its columns' products; a mirror it would
        // render mirrored, which samplab's right-handed frame cannot
        let linear = DMat3::from_mat4(to_world);
        let off =
            (linear.transpose() * linear - DMat3::IDENTITY).to_cols_array().iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // (a diagonal product overflows to infinity, never NaN, so `max` misses nothing)
        if off > 1e-3 {
            return Err(self.fail(
                node,
                format!(
                    "the sensor's to_world scales, shears or is singular (its columns' products are {off:.1e} off \
                     orthonormal); a camera's transform rotates and translates only"
                ),
            ));
        }
        if linear.determinant() < 0.0 {
            return Err(self.fail(node, "the sensor's to_world mirrors the camera's frame (determinant -1)"));
        }
        camera.eye = to_world.transform_point3(DVec3::ZERO);
        camera.target = camera.eye + to_world.transform_vector3(DVec3::Z);
        camera.up = to_world.transform_vector3(DVec3::Y);
        built.camera = Some(camera);
        Ok(())
    }

    /// An `hdrfilm`: its size and reconstruction filter (Mitsuba's default: a Gaussian);
    /// its pixel and component formats only encode the output and are read past.
    pub(super) fn film(&self, node: Node, built: &mut Built) -> Result<()> {
        if self.attr(node, "type")? != "hdrfilm" {
            return Err(self.unsupported(node, "only hdrfilm is supported"));
        }
        for f in node.children().filter(Node::is_element) {
            match (f.tag_name().name(), f.attribute("name").unwrap_or("")) {
                ("integer", "width") => built.resolution.0 = self.count(f)?,
                ("integer", "height") => built.resolution.1 = self.count(f)?,
                // how Mitsuba stores its image file; samplab writes its own formats
                ("string", "pixel_format" | "component_format") => {}
                ("rfilter", _) => built.footprint = Some(self.rfilter(f)?),
                _ => return Err(self.unsupported(f, "not supported in a film")),
            }
        }
        Ok(())
    }

    /// A reconstruction filter: `box` (the pixel area) or `gaussian` (with its `stddev`).
    pub(super) fn rfilter(&self, node: Node) -> Result<Footprint> {
        let kind = self.attr(node, "type")?;
        let mut stddev = 0.5;
        for c in node.children().filter(Node::is_element) {
            match (kind.as_str(), c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                ("gaussian", "float" | "integer", "stddev") => stddev = self.number(c, "value")?,
                _ => return Err(self.unsupported(c, &format!("not supported in a {kind} filter"))),
            }
        }
        match kind.as_str() {
            "box" => Ok(Footprint::Area),
            "gaussian" if stddev > 0.0 && stddev <= 100.0 => Ok(Footprint::Gaussian { stddev }),
            "gaussian" => Err(self.fail(node, format!("stddev {stddev} is outside (0, 100] pixels"))),
            _ => Err(self.unsupported(node, "filters: box, gaussian")),
        }
    }

    pub(super) fn count(&self, node: Node) -> Result<usize> {
        let v = self.attr(node, "value")?;
        v.parse::<usize>()
            .ok()
            .filter(|&n| n > 0)
            .ok_or_else(|| self.fail(node, format!("'{v}' is not a positive integer")))
    }

    pub(super) fn transform(&self, node: Node) -> Result<DMat4> {
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

    pub(super) fn bsdf(&self, node: Node) -> Result<Material> {
        match self.attr(node, "type")?.as_str() {
            "twosided" => {
                let mut inner = node.children().filter(Node::is_element);
                let front = inner.next().ok_or_else(|| self.fail(node, "<twosided> needs a BSDF"))?;
                if let Some(back) = inner.next() {
                    return Err(self.unsupported(back, "a second BSDF for the back side is not supported"));
                }
                Ok(Material { front_only: false, ..self.bsdf(front)? })
            }
            "diffuse" => {
                let mut m = default_bsdf();
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
                Ok(Material { finish, front_only: true, ..Material::diffuse(reflectance) })
            }
            _ => Err(self.unsupported(node, "only diffuse, conductor and roughconductor BSDFs are supported")),
        }
    }

    pub(super) fn colour(&self, node: Node) -> Result<DVec3> {
        match node.tag_name().name() {
            "rgb" | "spectrum" | "float" => self.vector(node, "value"),
            _ => Err(self.unsupported(node, "a colour must be <rgb>, <float> or a constant <spectrum>")),
        }
    }

    /// A shape, its references left to resolve ([`Part`]).
    pub(super) fn shape(&self, node: Node) -> Result<Part> {
        let kind = self.attr(node, "type")?;
        let (mut to_world, mut bsdf, mut emitter, mut refs) = (DMat4::IDENTITY, None, None, vec![]);
        let (mut centre, mut radius, mut filename, mut flip) = (DVec3::ZERO, 1.0, None, false);
        let mut normals = Normals::Vertex;
        for c in node.children().filter(Node::is_element) {
            match (c.tag_name().name(), c.attribute("name").unwrap_or("")) {
                ("transform", "to_world") => to_world = self.transform(c)?,
                ("ref", _) => refs.push((self.attr(c, "id")?, self.place(c))),
                ("bsdf", _) => bsdf = Some(self.bsdf(c)?),
                ("emitter", _) => emitter = Some(self.emitter(c)?),
                ("point", "center") => centre = self.xyz(c, 0.0)?,
                ("float", "radius") => radius = self.number(c, "value")?,
                ("string", "filename") => filename = Some(self.attr(c, "filename").or_else(|_| self.attr(c, "value"))?),
                ("boolean", "flip_normals") => flip = self.attr(c, "value")? == "true",
                ("boolean", "face_normals") if self.attr(c, "value")? == "true" => normals = Normals::Face,
                ("boolean", "face_normals") => normals = Normals::Vertex,
                _ => return Err(self.unsupported(c, &format!("not supported in <shape type=\"{kind}\">"))),
            }
        }
        let affine = DAffine3::from_mat4(to_world);
        let point = |p: DVec3| affine.transform_point3(p);
        let vector = |v: DVec3| affine.transform_vector3(v);
        // Mitsuba transforms a rectangle's or disk's normal, and a mesh's vertex normals, as
        // normals: under a mirroring transform they keep their side while the winding of the
        // transformed corners (samplab's front) turns over
        let mirror = DMat3::from_mat4(to_world).determinant() < 0.0;
        let (mut u, mut v) = (vector(DVec3::X), vector(DVec3::Y));
        if flip != mirror {
            std::mem::swap(&mut u, &mut v);
        }
        let no_light = |what: &str| Err(self.unsupported(node, &format!("area emitters on {what} are not supported")));
        let (surfaces, lights) = match kind.as_str() {
            "rectangle" => {
                let (corner, u, v) = (point(DVec3::new(-1.0, -1.0, 0.0)), 2.0 * u, 2.0 * v);
                (Ok(vec![Shape::Parallelogram { corner, u, v }]), Ok(vec![LightShape::Parallelogram { corner, u, v }]))
            }
            "disk" => {
                let r = u.length();
                let surface = if (v.length() - r).abs() > 1e-9 * r || u.dot(v).abs() > 1e-9 * r * r {
                    Err(self.fail(node, "<shape type=\"disk\">: non-uniform scales make an ellipse, unsupported"))
                } else {
                    Ok(vec![Shape::Disk { centre: point(DVec3::ZERO), normal: u.cross(v).normalize(), radius: r }])
                };
                (surface, Ok(vec![LightShape::Disk { centre: point(DVec3::ZERO), u, v }]))
            }
            "sphere" => {
                let m3 = DMat3::from_mat4(to_world);
                let scale = m3.x_axis.length();
                if (m3.y_axis.length() - scale).abs() > 1e-9 * scale
                    || (m3.z_axis.length() - scale).abs() > 1e-9 * scale
                {
                    return Err(
                        self.fail(node, "<shape type=\"sphere\">: non-uniform scales make an ellipsoid, unsupported")
                    );
                }
                if flip {
                    return Err(self.fail(
                        node,
                        "<shape type=\"sphere\">: flip_normals (a sphere seen from inside) is not supported",
                    ));
                }
                let sphere = Shape::Sphere { centre: point(centre), radius: radius * scale, velocity: DVec3::ZERO };
                (Ok(vec![sphere]), no_light("spheres"))
            }
            "cube" => {
                let mut faces = cuboid(
                    point(DVec3::splat(-1.0)),
                    2.0 * vector(DVec3::X),
                    2.0 * vector(DVec3::Y),
                    2.0 * vector(DVec3::Z),
                );
                // Mitsuba's cube is a mesh with outward vertex normals
                if flip != (mirror && normals == Normals::Vertex) {
                    for face in &mut faces {
                        if let Shape::Parallelogram { u, v, .. } = face {
                            std::mem::swap(u, v);
                        }
                    }
                }
                let lights = faces.iter().map(|f| match *f {
                    Shape::Parallelogram { corner, u, v } => LightShape::Parallelogram { corner, u, v },
                    _ => unreachable!("a cuboid's faces are parallelograms"),
                });
                let lights = lights.collect();
                (Ok(faces.to_vec()), Ok(lights))
            }
            "obj" => {
                let name =
                    filename.ok_or_else(|| self.fail(node, "<shape type=\"obj\"> needs <string name=\"filename\">"))?;
                let triangles = crate::obj::load(&self.file_path(node, &name)?, normals)?;
                let corners = triangles.into_iter().map(|t| {
                    let [a, mut b, mut c] = t.corners.map(point);
                    if flip != (mirror && t.by_normals) {
                        std::mem::swap(&mut b, &mut c);
                    }
                    (a, b - a, c - a)
                });
                let corners: Vec<_> = corners.collect();
                (
                    Ok(corners.iter().map(|&(p, e1, e2)| Shape::Triangle { p, e1, e2 }).collect()),
                    Ok(corners.iter().map(|&(p, e1, e2)| LightShape::Triangle { p, e1, e2 }).collect()),
                )
            }
            _ => return Err(self.unsupported(node, "shapes: rectangle, disk, sphere, cube, obj")),
        };
        Ok(Part { surfaces, lights, bsdf, emitter, refs })
    }
}
