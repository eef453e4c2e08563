//! Built-in scenes: one for each paper's set-up. The y axis points up; the ground is the
//! plane y = 0; every light faces down. Lights are power-normalised: each kind (square,
//! disk inscribed in the square, segment across it, Gaussian square) gives the same
//! unoccluded irradiance straight below, so images of different lights are comparable.

use std::f64::consts::PI;

use glam::DVec3;

use crate::bvh::{Bvh, Object};
use crate::camera::Camera;
use samplab::registry::{About, Entry, Registry};

use crate::error::{Error, Result};
use crate::geometry::{Plane, Shape};
use crate::light::{DiskMap, Light, LightShape};
use crate::mitsuba::Paths;
use crate::scene::{Finish, Material, Scene, Texture};

/// The kinds of light a built-in scene can be lit by (`--light`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum LightKind {
    /// A square.
    Square,
    /// The disk inscribed in the square.
    Disk,
    /// A segment across the square, along x.
    Linear,
    /// The square with a Gaussian falloff (sigma = 0.5 of the half-width).
    Gaussian,
}

impl LightKind {
    /// Every kind, with its command-line name.
    pub const ALL: [(&'static str, LightKind); 4] = [
        ("square", LightKind::Square),
        ("disk", LightKind::Disk),
        ("linear", LightKind::Linear),
        ("gaussian", LightKind::Gaussian),
    ];

    /// The kind's name.
    pub fn name(self) -> &'static str {
        Self::ALL.iter().find(|(_, k)| *k == self).map_or("", |(n, _)| n)
    }

    /// The kind called `name`.
    ///
    /// # Errors
    /// An unknown name, with the closest known ones.
    pub fn parse(name: &str) -> Result<LightKind> {
        Self::ALL.iter().find(|(n, _)| n.eq_ignore_ascii_case(name)).map(|(_, k)| *k).ok_or_else(|| {
            Error::Samplab(samplab::Error::UnknownName {
                kind: "light",
                name: name.into(),
                suggestions: samplab::error::closest_names(name, Self::ALL.iter().map(|(n, _)| *n)),
            })
        })
    }
}

/// Gaussian falloff of `LightKind::Gaussian`, in half-widths.
pub const GAUSSIAN_SIGMA: f64 = 0.5;
/// Unoccluded irradiance straight below every built-in light, at the ground.
const IRRADIANCE: f64 = 2.5;

/// A light of `kind` centred at `centre`, `size` across, facing down.
pub fn overhead_light(kind: LightKind, centre: DVec3, size: f64) -> Light {
    let (u, v) = (DVec3::X * size, DVec3::Z * size); // x cross z = -y: facing down
    let shape = match kind {
        LightKind::Square | LightKind::Gaussian => LightShape::Parallelogram { corner: centre - 0.5 * (u + v), u, v },
        LightKind::Disk => LightShape::Disk { centre, u: 0.5 * u, v: 0.5 * v },
        LightKind::Linear => LightShape::Segment { a: centre - 0.5 * u, b: centre + 0.5 * u },
    };
    let falloff = (kind == LightKind::Gaussian).then_some(GAUSSIAN_SIGMA);
    let mut light = Light { shape, radiance: DVec3::ONE, falloff, disk_map: DiskMap::Concentric, surface: None };
    // small-light irradiance at height h: L * A * mean falloff / h^2 (cos = 1)
    let h = centre.y;
    light.radiance = DVec3::splat(IRRADIANCE * h * h / (light.area() * light.mean_weight()));
    light
}

/// A built-in scene: its name, what it is for, and its default light.
#[derive(Debug)]
pub struct Builtin {
    /// Name on the command line and what it shows (which paper uses it).
    pub about: About,
    /// The light it has unless `--light` says otherwise (None: its lights are fixed).
    pub default_light: Option<LightKind>,
    build: fn(LightKind) -> Scene,
}

impl Entry for Builtin {
    fn about(&self) -> &About {
        &self.about
    }
    fn details(&self) -> Vec<String> {
        vec![match self.default_light {
            Some(kind) => format!("light: {kind:?} (replaceable)").to_lowercase(),
            None => "lights: fixed".into(),
        }]
    }
}

/// Every built-in scene (a Mitsuba 3 XML file is the other kind of scene).
pub static SCENES: Registry<Builtin> =
    Registry::new("scene", "SCENES  (built in; or a Mitsuba 3 .xml file)", &[&[BUILTINS]]);

static BUILTINS: &[Builtin] = &[
    Builtin {
        about: About::new("spheres", "two spheres above a ground plane (Ramamoorthi et al. 2012, Fig. 13)"),
        default_light: Some(LightKind::Square),
        build: spheres,
    },
    Builtin {
        about: About::new("sphere-box", "a sphere and a box on a plane (Ramamoorthi et al. 2012, Figs. 16 and 18)"),
        default_light: Some(LightKind::Disk),
        build: sphere_box,
    },
    Builtin {
        about: About::new("grids", "three grids of bars above a plane (Ramamoorthi et al. 2012, Figs. 8, 17, 19, 20)"),
        default_light: Some(LightKind::Linear),
        build: |kind| grids(kind, [20.0, 80.0, 140.0]),
    },
    Builtin {
        about: About::new("grids-aligned", "the three grids with bars at 0, 90 and 45 degrees to the light's edges"),
        default_light: Some(LightKind::Linear),
        build: |kind| grids(kind, [0.0, 90.0, 45.0]),
    },
    Builtin {
        about: About::new(
            "fibers",
            "400 thin random fibres above a plane: many shadow edges per stratum (in place of Ramamoorthi et al. 2012's tentacles, Fig. 21, whose geometry is not published)",
        ),
        default_light: Some(LightKind::Disk),
        build: fibers,
    },
    Builtin {
        about: About::new("occluder", "a disc light above a square occluder (Subr & Kautz 2013, Fig. 8)"),
        default_light: Some(LightKind::Disk),
        build: occluder,
    },
    Builtin {
        about: About::new("checker", "an infinite black-and-white checkerboard to the horizon (Shirley 1991, Table 1)"),
        default_light: None,
        build: |_| checker(0.0),
    },
    Builtin {
        about: About::new("checker-45", "the checkerboard rotated 45 degrees (Shirley 1991, Table 2)"),
        default_light: None,
        build: |_| checker(45.0),
    },
    Builtin {
        about: About::new("ball", "a ball lit by two square lights (Shirley 1991, Table 3)"),
        default_light: Some(LightKind::Square),
        build: ball,
    },
    Builtin {
        about: About::new("all", "a ball, a mirror and a glossy mirror, thin lens, two lights (Shirley 1991, Table 4)"),
        default_light: None,
        build: |_| all(),
    },
    Builtin {
        about: About::new(
            "defocus",
            "spheres at five depths and small bright beads, thin lens (Subr & Kautz 2013, Fig. 7)",
        ),
        default_light: Some(LightKind::Disk),
        build: defocus,
    },
    Builtin {
        about: About::new("motion", "a sphere moving across the frame during the shutter (Subr & Kautz 2013, Fig. 9)"),
        default_light: Some(LightKind::Disk),
        build: motion,
    },
    Builtin {
        about: About::new(
            "glossy-box",
            "a box with coloured walls, a GGX rough-mirror sphere and a diffuse one, for path tracing (scenes/glossy-box.xml, which Mitsuba 3 reads too)",
        ),
        default_light: None,
        build: |_| glossy_box(),
    },
    Builtin {
        about: About::new(
            "sphere-box-mesh",
            "the sphere-and-box scene with the sphere as a 1-million-triangle mesh (BVH benchmark)",
        ),
        default_light: Some(LightKind::Disk),
        build: sphere_box_mesh,
    },
];

/// The built-in scene `name`, lit by `light` (or its default).
///
/// # Errors
/// An unknown name (with the known ones), or a light asked of a scene whose lights are fixed.
pub fn builtin(name: &str, light: Option<LightKind>) -> Result<Scene> {
    let entry = SCENES.lookup(name)?;
    let kind = match (entry.default_light, light) {
        (Some(default), chosen) => chosen.unwrap_or(default),
        (None, None) => LightKind::Square,
        (None, Some(_)) => {
            let reason = format!("scene '{}' has no area light to replace", entry.about.name);
            return Err(crate::error::setting("light", light.map_or("", |k| k.name()), reason));
        }
    };
    Ok((entry.build)(kind))
}

const GREY: DVec3 = DVec3::splat(0.7);

fn sphere(centre: DVec3, radius: f64) -> Shape {
    Shape::Sphere { centre, radius, velocity: DVec3::ZERO }
}

/// The six faces of a box with edges `a`, `b`, `c` from `corner` (a right-handed triple),
/// normals outward.
pub(crate) fn cuboid(corner: DVec3, a: DVec3, b: DVec3, c: DVec3) -> [Shape; 6] {
    let quad = |corner, u, v| Shape::Parallelogram { corner, u, v };
    [
        quad(corner, b, a),
        quad(corner + c, a, b),
        quad(corner, a, c),
        quad(corner + b, c, a),
        quad(corner, c, b),
        quad(corner + a, b, c),
    ]
}

fn scene(camera: Camera, shapes: Vec<(Shape, u32)>, materials: Vec<Material>, lights: Vec<Light>) -> Scene {
    let objects = shapes.into_iter().map(|(shape, material)| Object { shape, material }).collect();
    Scene {
        camera,
        materials,
        bvh: Bvh::new(objects),
        planes: vec![(Plane { point: DVec3::ZERO, normal: DVec3::Y }, 0)],
        lights,
        resolution: (256, 192),
        max_depth: None,
        footprint: None,
    }
}

fn look(eye: [f64; 3], target: [f64; 3], fov: f64) -> Camera {
    Camera {
        eye: eye.into(),
        target: target.into(),
        up: DVec3::Y,
        fov,
        aperture: 0.0,
        focus: 1.0,
        clip: [0.0, f64::INFINITY],
    }
}

fn spheres(kind: LightKind) -> Scene {
    let shapes = vec![(sphere(DVec3::new(-0.55, 0.75, 0.1), 0.42), 1), (sphere(DVec3::new(0.6, 0.45, -0.25), 0.38), 1)];
    let light = overhead_light(kind, DVec3::new(0.0, 2.4, 0.0), 1.0);
    scene(
        look([0.0, 2.6, 3.6], [0.0, 0.3, 0.0], 50.0),
        shapes,
        vec![Material::diffuse(GREY), Material::diffuse(GREY)],
        vec![light],
    )
}

fn sphere_box_shapes() -> Vec<(Shape, u32)> {
    let (s, c) = (30f64.to_radians().sin(), 30f64.to_radians().cos());
    let (a, b) = (DVec3::new(0.7 * c, 0.0, 0.7 * s), DVec3::new(0.0, 0.7, 0.0));
    let depth = a.cross(b).normalize() * 0.7;
    let mut shapes: Vec<(Shape, u32)> =
        cuboid(DVec3::new(0.15, 0.0, -0.1), a, b, depth).into_iter().map(|f| (f, 2)).collect();
    shapes.push((sphere(DVec3::new(-0.55, 0.5, 0.1), 0.5), 1));
    shapes
}

fn sphere_box_lit(kind: LightKind, shapes: Vec<(Shape, u32)>) -> Scene {
    let light = overhead_light(kind, DVec3::new(0.3, 2.4, 0.5), 1.0);
    let materials = vec![
        Material::diffuse(GREY),
        Material::diffuse(DVec3::new(0.75, 0.6, 0.5)),
        Material::diffuse(DVec3::new(0.5, 0.6, 0.75)),
    ];
    scene(look([0.4, 2.2, 3.4], [0.0, 0.35, 0.0], 50.0), shapes, materials, vec![light])
}

fn sphere_box(kind: LightKind) -> Scene {
    sphere_box_lit(kind, sphere_box_shapes())
}

/// The sphere-and-box scene with the sphere tessellated into 2 x 708 x 706 triangles
/// (999,696), a benchmark for the BVH.
fn sphere_box_mesh(kind: LightKind) -> Scene {
    let mut shapes: Vec<(Shape, u32)> =
        sphere_box_shapes().into_iter().filter(|(s, _)| !matches!(s, Shape::Sphere { .. })).collect();
    let (centre, radius) = (DVec3::new(-0.55, 0.5, 0.1), 0.5);
    let (slices, stacks) = (708usize, 707usize);
    let vertex = |i: usize, j: usize| {
        let (theta, phi) = (PI * j as f64 / stacks as f64, 2.0 * PI * i as f64 / slices as f64);
        centre + radius * DVec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
    };
    for j in 0..stacks {
        for i in 0..slices {
            let (p00, p10, p01, p11) = (vertex(i, j), vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1));
            for (p, q, r) in [(p00, p10, p11), (p00, p11, p01)] {
                if (q - p).cross(r - p).length_squared() > 0.0 {
                    shapes.push((Shape::Triangle { p, e1: q - p, e2: r - p }, 1));
                }
            }
        }
    }
    sphere_box_lit(kind, shapes)
}

/// Three grids of thin bars at three heights, the bars of each at its angle (degrees) to the
/// light's edges. Ramamoorthi et al. 2012 show three grids casting overlapping soft shadows
/// without publishing the geometry; bars parallel to a square light's sample rows favour
/// stratified sampling (their section 6), so `grids` turns every grid off the light's axes
/// and `grids-aligned` keeps two on them.
fn grids(kind: LightKind, angles: [f64; 3]) -> Scene {
    let mut shapes = Vec::new();
    for (k, (height, angle)) in [0.45, 0.8, 1.15].into_iter().zip(angles).enumerate() {
        let (s, c) = angle.to_radians().sin_cos();
        let (along, across) = (DVec3::new(c, 0.0, s), DVec3::new(-s, 0.0, c));
        for bar in 0..9 {
            let offset = -0.8 + 0.2 * bar as f64 + 0.05 * k as f64;
            let corner = DVec3::new(0.0, height, 0.0) - 1.0 * along + (offset - 0.03) * across;
            for face in cuboid(corner, 2.0 * along, DVec3::Y * 0.03, 0.06 * across) {
                shapes.push((face, 1));
            }
        }
    }
    under_bar_light(kind, shapes)
}

/// `shapes`, grey, under the light and seen by the camera of the scenes of thin bars
/// (`grids`, `fibers`).
fn under_bar_light(kind: LightKind, shapes: Vec<(Shape, u32)>) -> Scene {
    let light = overhead_light(kind, DVec3::new(0.0, 2.2, 0.0), 1.0);
    scene(
        look([0.0, 3.2, 2.2], [0.0, 0.0, 0.0], 55.0),
        shapes,
        vec![Material::diffuse(GREY), Material::diffuse(GREY)],
        vec![light],
    )
}

/// 400 fibres (square section 0.01, lengths 0.4-1.2) at random heights 0.3-1.3, positions
/// and directions (one fixed seed), under the grids' light: from a shading point below
/// them the light is crossed by many thin shadows, several within one light stratum.
fn fibers(kind: LightKind) -> Scene {
    let mut rng = samplab::Seed(21).rng();
    let mut u = || samplab::seed::uniform(&mut rng);
    let mut shapes = Vec::new();
    for _ in 0..400 {
        let (height, x, z, length) = (0.3 + u(), 2.0 * u() - 1.0, 2.0 * u() - 1.0, 0.4 + 0.8 * u());
        let (s, c) = (PI * u()).sin_cos();
        let (along, across) = (DVec3::new(c, 0.0, s), DVec3::new(-s, 0.0, c));
        let corner = DVec3::new(x, height, z) - 0.5 * length * along - 0.005 * across;
        for face in cuboid(corner, length * along, DVec3::Y * 0.01, 0.01 * across) {
            shapes.push((face, 1));
        }
    }
    under_bar_light(kind, shapes)
}

fn occluder(kind: LightKind) -> Scene {
    let square = Shape::Parallelogram {
        corner: DVec3::new(-0.3, 0.6, -0.3),
        u: DVec3::new(0.0, 0.0, 0.6),
        v: DVec3::new(0.6, 0.0, 0.0),
    };
    let light = overhead_light(kind, DVec3::new(0.0, 1.6, 0.0), 0.8);
    scene(
        look([0.0, 2.4, 1.6], [0.0, 0.0, 0.0], 60.0),
        vec![(square, 1)],
        vec![Material::diffuse(GREY), Material::diffuse(GREY)],
        vec![light],
    )
}

fn checker(angle: f64) -> Scene {
    let board = Material {
        emission: Texture::Checker { even: DVec3::ONE, odd: DVec3::ZERO, size: 1.0, angle },
        ..Material::diffuse(DVec3::ZERO)
    };
    let mut s = scene(look([0.0, 1.0, 0.0], [0.0, 0.6, -4.0], 60.0), vec![], vec![board], vec![]);
    s.resolution = (128, 96);
    s
}

fn ball(_: LightKind) -> Scene {
    let lights = vec![
        overhead_light(LightKind::Square, DVec3::new(-1.2, 2.0, 0.6), 0.6),
        overhead_light(LightKind::Square, DVec3::new(1.3, 1.7, -0.4), 0.6),
    ];
    let mut s = scene(
        look([0.0, 1.3, 3.0], [0.0, 0.4, 0.0], 45.0),
        vec![(sphere(DVec3::new(0.0, 0.5, 0.0), 0.5), 1)],
        vec![Material::diffuse(GREY), Material::diffuse(DVec3::new(0.8, 0.5, 0.4))],
        lights,
    );
    s.resolution = (128, 96);
    s
}

/// Shirley's "all": the ball scene's lights and ball, with a perfect mirror behind on the
/// left, a glossy one on the right turned toward the ball, and a lens focused on the ball.
fn all() -> Scene {
    let mut s = ball(LightKind::Square);
    let upright =
        |corner: DVec3, across: DVec3| Shape::Parallelogram { corner, u: across, v: DVec3::new(0.0, 1.4, 0.0) };
    let mirror = Material { finish: Finish::Mirror, ..Material::diffuse(DVec3::splat(0.9)) };
    let glossy =
        Material { finish: Finish::Glossy { exponent: 60.0 }, ..Material::diffuse(DVec3::new(0.8, 0.75, 0.6)) };
    s.materials.extend([mirror, glossy]);
    let ball = s.bvh.objects()[0];
    let objects = vec![
        ball,
        Object { shape: upright(DVec3::new(-1.9, 0.0, -0.9), DVec3::new(1.7, 0.0, -0.5)), material: 2 },
        Object { shape: upright(DVec3::new(0.3, 0.0, -1.4), DVec3::new(1.5, 0.0, 0.7)), material: 3 },
    ];
    s.bvh = Bvh::new(objects);
    s.camera.aperture = 0.05;
    s.camera.focus = (DVec3::new(0.0, 0.5, 0.0) - s.camera.eye).length();
    s
}

/// The Mitsuba 3 file of the built-in scene `glossy-box`.
pub const GLOSSY_BOX_XML: &str = include_str!("../scenes/glossy-box.xml");

/// `glossy-box`, read from its Mitsuba 3 file (which names no other file).
fn glossy_box() -> Scene {
    let scene = crate::mitsuba::parse(GLOSSY_BOX_XML, "glossy-box.xml", std::path::Path::new("."), Paths::InsideScene);
    scene.expect("the built-in glossy-box.xml parses (tested)")
}

fn defocus(kind: LightKind) -> Scene {
    let mut shapes = Vec::new();
    for k in 0..5 {
        let z = 1.0 - 1.0 * k as f64;
        shapes.push((sphere(DVec3::new(-1.0 + 0.5 * k as f64, 0.3, z), 0.3), 1));
        // beads well in front of the focus plane (1 to 2.6 from the eye, focus about 4):
        // bokeh discs tens of pixels wide
        shapes.push((sphere(DVec3::new(-0.45 + 0.225 * k as f64, 0.95, 2.0 - 0.4 * k as f64), 0.04), 2));
    }
    // beads dim enough that their bokeh is not clipped white, and a wide aperture, so that
    // the lens strategy's structure shows inside each disc
    let bead = Material { emission: Texture::Constant(DVec3::splat(12.0)), ..Material::diffuse(DVec3::ZERO) };
    let mut camera = look([0.0, 0.9, 3.0], [0.0, 0.3, -1.0], 45.0);
    camera.aperture = 0.3;
    camera.focus = (camera.target - camera.eye).length();
    let light = overhead_light(kind, DVec3::new(0.0, 2.5, 0.0), 1.0);
    scene(
        camera,
        shapes,
        vec![Material::diffuse(GREY), Material::diffuse(DVec3::new(0.8, 0.3, 0.3)), bead],
        vec![light],
    )
}

fn motion(kind: LightKind) -> Scene {
    let moving =
        Shape::Sphere { centre: DVec3::new(-0.6, 0.4, 0.0), radius: 0.35, velocity: DVec3::new(1.2, 0.0, 0.0) };
    let still = sphere(DVec3::new(0.5, 0.3, -0.8), 0.3);
    let light = overhead_light(kind, DVec3::new(0.0, 2.2, 0.3), 0.8);
    scene(
        look([0.0, 1.4, 2.8], [0.0, 0.3, 0.0], 45.0),
        vec![(moving, 1), (still, 1)],
        vec![Material::diffuse(GREY), Material::diffuse(GREY)],
        vec![light],
    )
}

#[cfg(test)]
mod tests;
