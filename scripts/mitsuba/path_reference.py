#!/usr/bin/env python3
"""Mitsuba 3's `path` integrator on samplab's built-in scene glossy-box
(crates/samplab-render/scenes/glossy-box.xml): the per-pixel mean of R independent renders
and its standard error, written as the fixture that crates/samplab-render/tests/path.rs
compares samplab's path mode with.

    python3 -m venv /tmp/mi && /tmp/mi/bin/pip install mitsuba==3.9.1 drjit==1.5.0 numpy
    /tmp/mi/bin/python scripts/mitsuba/path_reference.py > crates/samplab-render/tests/fixtures/glossy-box-mitsuba.json

The scalar_rgb variant (no LLVM needed), a box filter, max_depth 5 and Russian roulette
pushed past it (rr_depth 100), as samplab's path mode traces.
"""
import json
import sys
from pathlib import Path

import mitsuba as mi
import numpy as np

WIDTH, HEIGHT, DEPTH = 24, 18, 5
RENDERS, SPP = 16, 4096

mi.set_variant("scalar_rgb")
xml = Path(__file__).resolve().parents[2] / "crates/samplab-render/scenes/glossy-box.xml"
scene = mi.load_file(str(xml), res=WIDTH, height=HEIGHT)
integrator = mi.load_dict({"type": "path", "max_depth": DEPTH, "rr_depth": 100, "hide_emitters": False})
images = []
for r in range(RENDERS):
    image = np.array(mi.render(scene, integrator=integrator, spp=SPP, seed=r), dtype=np.float64)
    images.append(image[:, :, :3])
    print(f"render {r + 1}/{RENDERS}", file=sys.stderr)
stack = np.stack(images)
mean = stack.mean(axis=0)
se = stack.std(axis=0, ddof=1) / np.sqrt(RENDERS)
json.dump(
    {
        "source": "Mitsuba 3 (pip mitsuba==%s), variant scalar_rgb, integrator path" % mi.__version__,
        "script": "scripts/mitsuba/path_reference.py",
        "scene": "glossy-box",
        "width": WIDTH,
        "height": HEIGHT,
        "max_depth": DEPTH,
        "renders": RENDERS,
        "spp": SPP,
        "mean": [round(float(v), 7) for v in mean.reshape(-1)],
        "se": [round(float(v), 7) for v in se.reshape(-1)],
    },
    sys.stdout,
)
print()
