#!/usr/bin/env python3
"""Mitsuba 3's images of small scenes that each turn on one scene element samplab reads: the
sensor's clipping planes, a mesh's vertex normals and `face_normals`, `flip_normals`, and a
mirroring `to_world` on rectangles, cubes and meshes. Writes the scenes (XML and OBJ) to
crates/samplab-render/tests/scenes/elements/ and prints the image means (per channel, over
independent renders, with their standard errors), the fixture that
crates/samplab-render/tests/as_mitsuba.rs compares samplab with.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 drjit==1.5.0 numpy
    /tmp/mi/bin/python scripts/mitsuba/elements_reference.py > crates/samplab-render/tests/fixtures/elements-mitsuba.json

Two families, each at 16 x 16 pixels with a box filter, Mitsuba's scalar_rgb variant:
- clip-*: a camera at the origin looking down +z at two emitting rectangles that face it, a
  small red one 2 away and a large green one 4 away, seen directly (max_depth 1), through
  a pinhole or a thin lens focused at 3, with near and far clipping planes between them;
- ground-*: a one-sided diffuse ground lit by a rectangle light 2 above it, seen from above
  (max_depth 2, direct light): whether the ground (or, last, the light) faces the right way
  is the element under test.
"""
import json
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

RES, RENDERS, SPP = 16, 8, 256
OUT = Path(__file__).resolve().parents[2] / "crates/samplab-render/tests/scenes/elements"

mi.set_variant("scalar_rgb")

FILM = (
    f'<film type="hdrfilm"><integer name="width" value="{RES}"/>'
    f'<integer name="height" value="{RES}"/><rfilter type="box"/></film>'
)

# a 2 x 2 quad in the plane y = 0, wound so that its normal points down (as listed) or up
# (reversed); `vn` gives every corner the same vertex normal
QUAD = ["-1 0 -1", "1 0 -1", "1 0 1", "-1 0 1"]


def obj(name, wound, vn=None):
    corners = QUAD if wound == "down" else QUAD[::-1]
    lines = [f"v {c}" for c in corners]
    if vn is None:
        lines.append("f 1 2 3 4")
    else:
        lines.append("vn 0 %d 0" % (1 if vn == "up" else -1))
        lines.append("f 1//1 2//1 3//1 4//1")
    (OUT / name).write_text("# written by scripts/mitsuba/elements_reference.py\n" + "\n".join(lines) + "\n")


def clip_scene(sensor, near=None, far=None):
    clip = "".join(
        f'<float name="{n}" value="{v}"/>' for n, v in (("near_clip", near), ("far_clip", far)) if v is not None
    )
    lens = '<float name="aperture_radius" value="0.2"/><float name="focus_distance" value="3"/>' if sensor == "thinlens" else ""
    emitter = lambda x, s, z, rgb: (  # noqa: E731
        f'<shape type="rectangle"><transform name="to_world"><scale value="{s}"/>'
        f'<rotate y="1" angle="180"/><translate x="{x}" z="{z}"/></transform>'
        f'<emitter type="area"><rgb name="radiance" value="{rgb}"/></emitter></shape>'
    )
    return f"""<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="1"/></integrator>
    <sensor type="{sensor}">
        <float name="fov" value="50"/>{lens}{clip}
        <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>
        {FILM}
    </sensor>
    {emitter(0.3, 0.5, 2, "1, 0, 0")}
    {emitter(0, 4, 4, "0, 1, 0")}
</scene>
"""


def ground_scene(ground, light=None):
    light = light or (
        '<shape type="rectangle"><transform name="to_world"><scale value="0.5"/>'
        '<rotate x="1" angle="90"/><translate y="2"/></transform>'
        '<emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>'
    )
    return f"""<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="2"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="60"/>
        <transform name="to_world"><lookat origin="0, 3, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        {FILM}
    </sensor>
    <bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.5"/></bsdf>
    {ground}
    {light}
</scene>
"""


def shape(kind, body, transform="", extra=""):
    file = f'<string name="filename" value="{body}"/>' if kind == "obj" else ""
    t = f'<transform name="to_world">{transform}</transform>' if transform else ""
    return f'<shape type="{kind}">{file}{t}{extra}<ref id="grey"/></shape>'


FACE_NORMALS = '<boolean name="face_normals" value="true"/>'
FLIP = '<boolean name="flip_normals" value="true"/>'
# a rectangle's +z turned to +y, and a cube flattened to a slab whose top is y = 0
UP = '<rotate x="1" angle="-90"/>'
SLAB = '<scale x="1" y="0.1" z="1"/><translate y="-0.1"/>'
MIRROR = '<scale x="-1" y="1" z="1"/>'

SCENES = {
    "clip-default.xml": clip_scene("perspective"),
    "clip-near.xml": clip_scene("perspective", near=3),
    "clip-far.xml": clip_scene("perspective", far=3),
    "clip-between.xml": clip_scene("perspective", near=2.5, far=3.5),
    "clip-lens-near.xml": clip_scene("thinlens", near=3),
    "clip-lens-far.xml": clip_scene("thinlens", far=3),
    "ground-obj-up.xml": ground_scene(shape("obj", "quad-up.obj")),
    "ground-obj-vn-up-wound-down.xml": ground_scene(shape("obj", "quad-down-vn-up.obj")),
    "ground-obj-vn-up-wound-down-face-normals.xml": ground_scene(
        shape("obj", "quad-down-vn-up.obj", extra=FACE_NORMALS)
    ),
    "ground-obj-flip.xml": ground_scene(shape("obj", "quad-up.obj", extra=FLIP)),
    "ground-obj-vn-mirror.xml": ground_scene(shape("obj", "quad-up-vn-up.obj", MIRROR)),
    "ground-obj-vn-mirror-face-normals.xml": ground_scene(shape("obj", "quad-up-vn-up.obj", MIRROR, FACE_NORMALS)),
    "ground-rect-mirror.xml": ground_scene(shape("rectangle", None, MIRROR + UP)),
    "ground-rect-flip.xml": ground_scene(shape("rectangle", None, UP, FLIP)),
    "ground-cube-mirror.xml": ground_scene(shape("cube", None, MIRROR + SLAB)),
    "ground-cube-mirror-flip.xml": ground_scene(shape("cube", None, MIRROR + SLAB, FLIP)),
    "ground-light-obj-vn-down.xml": ground_scene(
        shape("rectangle", None, UP),
        light='<shape type="obj"><string name="filename" value="quad-up-vn-down.obj"/>'
        '<transform name="to_world"><scale value="0.5"/><translate y="2"/></transform>'
        '<emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>',
    ),
}


def image_means(path):
    scene = mi.load_file(str(path))
    means = []
    for r in range(RENDERS):
        image = np.array(mi.render(scene, spp=SPP, seed=r), dtype=np.float64)
        means.append(image[:, :, :3].reshape(-1, 3).mean(axis=0))
    means = np.array(means)
    return means.mean(axis=0), means.std(axis=0, ddof=1) / np.sqrt(RENDERS)


OUT.mkdir(parents=True, exist_ok=True)
obj("quad-up.obj", "up")
obj("quad-down-vn-up.obj", "down", "up")
obj("quad-up-vn-up.obj", "up", "up")
obj("quad-up-vn-down.obj", "up", "down")
images = []
for name, text in SCENES.items():
    (OUT / name).write_text(f"<!-- written by scripts/mitsuba/elements_reference.py -->\n{text}")
    mean, se = image_means(OUT / name)
    print(f"{name}: {mean} +- {se}", file=sys.stderr)
    images.append({"scene": name, "mean": [round(float(v), 8) for v in mean], "se": [round(float(v), 8) for v in se]})
json.dump(
    {
        "source": "Mitsuba 3 (pip mitsuba==%s), variant scalar_rgb, integrator path" % mi.__version__,
        "script": "scripts/mitsuba/elements_reference.py",
        "width": RES,
        "height": RES,
        "renders": RENDERS,
        "spp": SPP,
        "images": images,
    },
    sys.stdout,
    indent=1,
)
print()
