#!/usr/bin/env python3
"""Mitsuba 3's own images of its two Cornell boxes, as Mitsuba renders them: the image mean
of each channel over R independent renders, with its standard error, written as the fixture
that crates/samplab-render/tests/as_mitsuba.rs compares samplab's path mode with.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 drjit==1.5.0 numpy
    /tmp/mi/bin/python scripts/mitsuba/cornell_reference.py > crates/samplab-render/tests/fixtures/cornell-mitsuba.json

The scenes, each at 32 x 32 pixels and path depths 5 and 8, through each file's own
parameters:
- tests/scenes/cornell-box.xml: `mi.cornell_box()` written as XML (this script first checks
  that Mitsuba renders the file and the dictionary alike), Gaussian filter, the light a white
  diffuse rectangle 1 cm below the ceiling;
- tests/scenes/cbox/cbox-rgb.xml: the Cornell box of Mitsuba's scene repository
  (mitsuba-data, scenes/cbox), OBJ meshes, box filter, its `res` and `max_depth` defaults
  set as Mitsuba's loader sets them.
Everything else is Mitsuba's default: the scalar_rgb variant, Russian roulette from depth
5 (unbiased), emitters visible.
"""
import json
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

RES, RENDERS, SPP = 32, 16, 4096
ROOT = Path(__file__).resolve().parents[2] / "crates/samplab-render/tests/scenes"

mi.set_variant("scalar_rgb")


def check_cornell_xml():
    """The XML file and mi.cornell_box() give the same image (to float rounding)."""
    a = mi.load_file(str(ROOT / "cornell-box.xml"), res=16)
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = 16
    b = mi.load_dict(d)
    ia, ib = (np.array(mi.render(s, spp=16, seed=7), dtype=np.float64) for s in (a, b))
    worst = np.abs(ia - ib).max() / np.abs(ib).max()
    assert worst < 1e-5, f"cornell-box.xml differs from mi.cornell_box(): {worst}"


def image_means(path, depth):
    if path.name == "cornell-box.xml":
        scene = mi.load_file(str(path), res=RES)
        integrator = mi.load_dict({"type": "path", "max_depth": depth})
    else:
        scene = mi.load_file(str(path), res=RES, max_depth=depth)
        integrator = scene.integrator()
    means = []
    for r in range(RENDERS):
        image = np.array(mi.render(scene, integrator=integrator, spp=SPP, seed=r), dtype=np.float64)
        means.append(image[:, :, :3].reshape(-1, 3).mean(axis=0))
        print(f"{path.name} depth {depth}: render {r + 1}/{RENDERS}", file=sys.stderr)
    means = np.array(means)
    return means.mean(axis=0), means.std(axis=0, ddof=1) / np.sqrt(RENDERS)


check_cornell_xml()
scenes = {}
for name in ["cornell-box.xml", "cbox/cbox-rgb.xml"]:
    for depth in [5, 8]:
        mean, se = image_means(ROOT / name, depth)
        scenes[f"{name}@{depth}"] = {
            "scene": name,
            "max_depth": depth,
            "mean": [round(float(v), 8) for v in mean],
            "se": [round(float(v), 8) for v in se],
        }
json.dump(
    {
        "source": "Mitsuba 3 (pip mitsuba==%s), variant scalar_rgb, integrator path" % mi.__version__,
        "script": "scripts/mitsuba/cornell_reference.py",
        "width": RES,
        "height": RES,
        "renders": RENDERS,
        "spp": SPP,
        "images": list(scenes.values()),
    },
    sys.stdout,
    indent=1,
)
print()
