//! The subset of the Mitsuba 3 XML scene format these experiments need: a `perspective`
//! or `thinlens` sensor (a rigid `to_world`, `fov`, `fov_axis`, `near_clip` and `far_clip`:
//! the camera sees only what lies between the planes, as in Mitsuba) with an `hdrfilm`
//! (its size and its `box` or `gaussian` reconstruction filter), `diffuse`, `conductor` (a
//! perfect mirror) and `roughconductor` (Beckmann or GGX microfacets, reflecting fully) BSDFs
//! (also inside `twosided`, by `id` and `ref`), shapes `rectangle`, `disk`, `sphere`, `cube`
//! and `obj` with `to_world` transforms (`translate`, `scale`, `rotate`, `matrix`, `lookat`),
//! `area` emitters with a radiance on every shape but the sphere (inside the shape, or by `id`
//! and `ref` in any order), `<include>` of other files and `<default>` parameters with
//! `$name` substitution. Anything else is refused with its element and line, never skipped
//! silently (a `path` integrator's `max_depth` is path mode's depth unless the render sets
//! one; other integrators and samplers are read past: the testbed has its own). Mitsuba's
//! numbers may be written as `<integer>` where it takes a float.
//!
//! Surfaces are honoured as Mitsuba defines them: a BSDF reflects on the front of its shape
//! only (the side its normal points to; black from behind) unless wrapped in `twosided`, a
//! shape without a BSDF is a one-sided grey diffuse (reflectance 0.5), and an emitter shape
//! is a surface too: it blocks rays from both sides, reflects by its BSDF and emits on its
//! front. A shape's front is Mitsuba's: `flip_normals` turns it over (refused on spheres);
//! a mesh with vertex normals takes the side they point to unless `face_normals` is set
//! ([`crate::obj`]), and a mirroring transform keeps the side of a rectangle's, disk's or
//! cube's normal, which Mitsuba transforms as a normal. The film's filter is where the camera rays go unless the render says (`box`: the
//! pixel area; `gaussian`, Mitsuba's default: its footprint, [`crate::filter`]).

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};

use glam::DVec3;
use roxmltree::Node;

use crate::bvh::{Bvh, Object};
use crate::camera::Camera;
use crate::error::{Error, Result};
use crate::filter::Footprint;
use crate::geometry::Shape;
use crate::light::{DiskMap, Light, LightShape};
use crate::scene::{Material, Scene};

mod plugins;

/// Where the files a scene names (OBJ meshes) may be.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
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
    check_nesting(&doc, file)?;
    let mut reader = Reader { file, doc: &doc, dir, paths, state: State::default(), includes: 0 };
    reader.scene(doc.root_element())
}

/// Refuse a document nested deeper than [`MAX_NESTING`].
fn check_nesting(doc: &roxmltree::Document, file: &str) -> Result<()> {
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
    Ok(())
}

/// The deepest nesting of elements a scene may have (Mitsuba's own scenes nest a few
/// levels: scene, shape, bsdf, twosided's bsdf, texture, its transform).
const MAX_NESTING: usize = 64;

/// The deepest chain of `<include>`s (a file including itself is refused by it).
const MAX_INCLUDES: usize = 16;

/// What every file of a scene shares: the parameters and the named BSDFs and emitters.
#[derive(Default)]
struct State {
    defaults: HashMap<String, String>,
    bsdfs: HashMap<String, Material>,
    /// Named area emitters' radiance.
    emitters: HashMap<String, DVec3>,
}

struct Reader<'a, 'input> {
    file: &'a str,
    doc: &'a roxmltree::Document<'input>,
    dir: &'a Path,
    paths: Paths,
    state: State,
    /// How many `<include>`s deep this file is.
    includes: usize,
}

/// Where an element is, for an error raised once the whole scene is read.
#[derive(Clone)]
struct Place {
    file: String,
    line: usize,
}

impl Place {
    fn fail(&self, message: String) -> Error {
        Error::Scene { file: self.file.clone(), line: self.line, message }
    }
}

/// A shape as read, its references resolved once the whole scene is read (Mitsuba lets a
/// `ref` name an element defined later).
struct Part {
    /// Its surfaces, or why it cannot be one.
    surfaces: Result<Vec<Shape>>,
    /// Its outline as a light, or why it cannot emit.
    lights: Result<Vec<LightShape>>,
    /// Its BSDF, given inside it (None: a `ref` or the default).
    bsdf: Option<Material>,
    /// Its emitter's radiance, given inside it.
    emitter: Option<DVec3>,
    /// Its `ref`s, each to a BSDF or an emitter.
    refs: Vec<(String, Place)>,
}

struct Built {
    camera: Option<Camera>,
    resolution: (usize, usize),
    footprint: Option<Footprint>,
    parts: Vec<Part>,
    max_depth: Option<usize>,
}

fn grey(v: f64) -> Material {
    Material::diffuse(DVec3::splat(v))
}

/// Mitsuba's BSDF for a shape that names none: a one-sided grey diffuse.
fn default_bsdf() -> Material {
    Material { front_only: true, ..grey(0.5) }
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
                .state
                .defaults
                .get(key)
                .cloned()
                .ok_or_else(|| self.fail(node, format!("'${key}' has no <default name=\"{key}\">"))),
            None => Ok(raw.to_string()),
        }
    }

    fn place(&self, node: Node) -> Place {
        Place { file: self.file.into(), line: self.doc.text_pos_at(node.range().start).row as usize }
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
        let refuse = |why: &'static str| Error::PathOutsideScene {
            file: self.file.into(),
            line: self.doc.text_pos_at(node.range().start).row as usize,
            name: samplab::error::excerpt(name),
            why,
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
        // Mitsuba's film where a sensor names none: 768 x 576 pixels, a Gaussian filter
        let mut built = Built {
            camera: None,
            resolution: (768, 576),
            footprint: Some(Footprint::MITSUBA),
            parts: vec![],
            max_depth: None,
        };
        self.elements(root, &mut built)?;
        let camera = built.camera.ok_or_else(|| self.fail(root, "the scene has no <sensor>"))?;
        let (mut materials, mut objects, mut lights) = (vec![default_bsdf()], vec![], vec![]);
        for part in built.parts {
            let (mut bsdf, mut emitter) = (part.bsdf, part.emitter);
            for (id, place) in part.refs {
                if let Some(m) = self.state.bsdfs.get(&id) {
                    bsdf = Some(*m);
                } else if let Some(e) = self.state.emitters.get(&id) {
                    emitter = Some(*e);
                } else {
                    return Err(place.fail(format!("no <bsdf id=\"{id}\"> or <emitter id=\"{id}\"> in the scene")));
                }
            }
            let material = match bsdf {
                Some(m) => {
                    materials.push(m);
                    materials.len() as u32 - 1
                }
                None => 0,
            };
            match emitter {
                Some(radiance) => lights.extend(part.lights?.into_iter().map(|shape| Light {
                    shape,
                    radiance,
                    falloff: None,
                    disk_map: DiskMap::Concentric,
                    surface: Some(material),
                })),
                None => objects.extend(part.surfaces?.into_iter().map(|shape| Object { shape, material })),
            }
        }
        Ok(Scene {
            camera,
            materials,
            bvh: Bvh::new(objects),
            planes: vec![],
            lights,
            resolution: built.resolution,
            max_depth: built.max_depth,
            footprint: built.footprint,
        })
    }

    /// The top-level elements of a scene (or of a file it includes).
    fn elements(&mut self, root: Node, built: &mut Built) -> Result<()> {
        if root.tag_name().name() != "scene" {
            return Err(self.fail(root, format!("the root element is <{}>, not <scene>", root.tag_name().name())));
        }
        for node in root.children().filter(Node::is_element) {
            match node.tag_name().name() {
                "default" => {
                    let (name, value) = (self.attr(node, "name")?, self.attr(node, "value")?);
                    self.state.defaults.entry(name).or_insert(value);
                }
                "integrator" => self.integrator(node, built)?,
                // the render's strategies and sample count stand in for Mitsuba's sampler:
                // choosing them is what samplab is for
                "sampler" => {}
                "sensor" => self.sensor(node, built)?,
                "bsdf" => {
                    let id = self.attr(node, "id")?;
                    let m = self.bsdf(node)?;
                    self.state.bsdfs.insert(id, m);
                }
                "emitter" if node.attribute("id").is_some() => {
                    let id = self.attr(node, "id")?;
                    let radiance = self.emitter(node)?;
                    self.state.emitters.insert(id, radiance);
                }
                "shape" => {
                    let part = self.shape(node)?;
                    built.parts.push(part);
                }
                "include" => self.include(node, built)?,
                _ => return Err(self.unsupported(node, "not supported by samplab's Mitsuba subset")),
            }
        }
        Ok(())
    }

    /// An `<include filename>`: its file's elements read as if written here; the files it
    /// names are found from the main scene's folder, as Mitsuba's resolver does.
    fn include(&mut self, node: Node, built: &mut Built) -> Result<()> {
        if self.includes >= MAX_INCLUDES {
            return Err(self.fail(node, format!("<include> nested more than {MAX_INCLUDES} deep")));
        }
        let name = self.attr(node, "filename")?;
        let (file, text) = crate::obj::read_scene_file(&self.file_path(node, &name)?)?;
        let doc = roxmltree::Document::parse(&text).map_err(|e| {
            let message = format!("malformed XML: {e}");
            Error::Scene { file: file.clone(), line: e.pos().row as usize, message }
        })?;
        check_nesting(&doc, &file)?;
        let mut inner = Reader {
            file: &file,
            doc: &doc,
            dir: self.dir,
            paths: self.paths,
            state: std::mem::take(&mut self.state),
            includes: self.includes + 1,
        };
        let read = inner.elements(doc.root_element(), built);
        self.state = inner.state;
        read
    }
}
