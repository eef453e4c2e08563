"""Rendering: the CLI's bytes, its reference policy, errors, and bad settings."""

import json

import numpy as np
import pytest

import samplab


@pytest.mark.parametrize(
    "scene,args,settings",
    [
        ("spheres", ["--sampler", "jitter", "-n", 4], {"sampler": "jitter", "n": 4}),
        ("sphere-box", ["--mode", "obscurance", "--range", 0.5, "-n", 4], {"mode": "obscurance", "range": 0.5, "n": 4}),
        ("checker", ["--pixel", "area", "--spp", 4, "--interleave", "2x2", "--area-sampler", "jitter"], {"pixel": "area", "spp": 4, "interleave": (2, 2), "area_sampler": "jitter"}),
        ("defocus", ["--spp", 4, "-n", 4], {"spp": 4, "n": 4}),
        # a pixel sampler: every dimension of every estimate from it
        ("defocus", ["--spp", 4, "-n", 4, "--pixel", "area", "--pixel-sampler", "zsobol"], {"spp": 4, "n": 4, "pixel": "area", "pixel_sampler": "zsobol"}),
        ("sphere-box", ["--mode", "obscurance", "-n", 4, "--pixel-sampler", "sobol"], {"mode": "obscurance", "n": 4, "pixel_sampler": "sobol"}),
        # a point-set sequence per pixel
        ("sphere-box", ["--mode", "obscurance", "-n", 4, "--pixel-sampler", "halton.owen"], {"mode": "obscurance", "n": 4, "pixel_sampler": "halton.owen"}),
        # path tracing: the default pixel sampler, and another at depth 3
        ("glossy-box", ["--mode", "path", "--spp", 4, "--pixel", "area"], {"mode": "path", "spp": 4, "pixel": "area"}),
        ("glossy-box", ["--mode", "path", "--spp", 4, "--max-depth", 3, "--pixel-sampler", "zsobol"], {"mode": "path", "spp": 4, "max_depth": 3, "pixel_sampler": "zsobol"}),
    ],
)
def test_render_equals_the_cli(cli, tmp_path, scene, args, settings):
    out = tmp_path / "x.exr"
    cli("render", scene, *args, "--res", "24x16", "--seed", 20, "-o", out)
    theirs = samplab.read_exr(out)
    ours = samplab.render(scene, res=(24, 16), seed=20, **settings)
    assert ours["rgb"].shape == (16, 24, 3) and ours["rgb"].dtype == np.float32
    assert ours["rgb"].tobytes() == theirs["rgb"].tobytes()
    assert ours["visibility"].tobytes() == theirs["visibility"].tobytes()


def test_reference_and_errors_equal_the_cli(cli, tmp_path):
    ref = tmp_path / "ref.exr"
    summary = json.loads(
        cli("render", "spheres", "--light", "disk", "-n", 4, "--res", "20x12", "--seed", 3, "-o", tmp_path / "x.exr",
            "--reference", ref, "--reference-samples", 64, "--penumbra", "--json")
    )
    ours = samplab.render("spheres", light="disk", n=4, res=(20, 12), seed=3)
    reference = samplab.render("spheres", light="disk", n=4, res=(20, 12), seed=3, reference_samples=64)
    assert reference["rgb"].tobytes() == samplab.read_exr(ref)["rgb"].tobytes()
    assert samplab.image_errors(ours, reference, penumbra=True) == summary["errors"]


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda: samplab.render("spheres", mode="foo"), "mode = foo: unknown value"),
        (lambda: samplab.render("spheres", sampler="jiter"), "did you mean jitter"),
        (lambda: samplab.render("spheres", n=15), "9 and 16"),
        (lambda: samplab.render("nosuch"), "unknown scene"),
        (lambda: samplab.render("spheres", colour="red"), "unknown render setting 'colour'"),
        # keywords are read through the library's one table of settings, by its types
        (lambda: samplab.render("spheres", range=float("nan")), "range: NaN is not a finite number"),
        (lambda: samplab.render("spheres", n=4.5), "render settings: invalid type: floating point `4.5`, expected usize"),
        (lambda: samplab.render("spheres", res=(0, 10)), r"res = 0x10: each side must be in 1\.\.="),
        (lambda: samplab.render("glossy-box", mode="path", max_depth=0), "max_depth = 0: the most segments"),
        (lambda: samplab.render("glossy-box", mode="path", pixel_sampler="jitter"), "a set, not a sequence"),
        (lambda: samplab.render("spheres", pixel_sampler="jitter"), "the strategy over the pixel area alone is the area sampler"),
        # a setting the render would not read
        (lambda: samplab.render("spheres", max_depth=3), "max_depth = 3: read in path mode only"),
        (lambda: samplab.render("glossy-box", mode="path", n=4), "n = 4: not read: the pixel sampler sobol"),
        (lambda: samplab.image_errors(np.zeros((2, 2, 3)), np.zeros((3, 2, 3))), "the image: got 2x2, expected 2x3, as the reference"),
    ],
)
def test_bad_settings_raise(call, message):
    with pytest.raises(samplab.Error, match=message):
        call()


def test_every_scene_renders():
    for scene in samplab.scenes():
        out = samplab.render(scene["name"], res=(8, 6), n=1, sampler="random", seed=1)
        assert out["rgb"].shape == (6, 8, 3) and np.isfinite(out["rgb"]).all(), scene["name"]
        assert out["camera_rays"] >= 48, scene["name"]


def test_the_readme_gallery_runs(tmp_path):
    import runpy
    from pathlib import Path

    gallery = runpy.run_path(str(Path(__file__).resolve().parents[1] / "examples" / "gallery.py"))
    gallery["main"](tmp_path)
    for name in ("pattern", "discrepancy", "periodogram", "convergence", "shadows"):
        assert (tmp_path / f"{name}.png").read_bytes()[1:4] == b"PNG", name
