"""Generation: against scipy's unscrambled sequences, the CLI's bytes, and the registry."""

import copy
import hashlib
import json
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scipy.stats import qmc

import samplab
from conftest import load_npy

# a saved set (two sets of 16 jittered 2D points), as the Rust tests read it
SAVED = Path(__file__).resolve().parents[2] / "samplab" / "tests" / "fixtures" / "saved16.txt"


@pytest.mark.parametrize("d", [1, 2, 5])
def test_unscrambled_sobol_equals_scipy(d):
    ours = samplab.generate("sobol", n=256, d=d, seed=1)
    theirs = qmc.Sobol(d, scramble=False).random(256)
    assert np.array_equal(ours, theirs)


@pytest.mark.parametrize("d", [1, 2, 7])
def test_unscrambled_halton_equals_scipy(d):
    ours = samplab.generate("halton", n=300, d=d, seed=1)
    theirs = qmc.Halton(d, scramble=False).random(300)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "spec,n,d,sets",
    [
        ("jitter", 64, 2, 3),
        ("sobol.owen", 100, 3, 2),
        ("poisson.fast", 50, 2, 1),
        ("GJittered:0.25", 16, 2, 1),
        ("nrooks", 33, 4, 5),
        ("sobol+shift", 64, 3, 2),
        ("kronecker+shift+micro-jitter:0.2", 50, 2, 2),
        (f"file:path={SAVED}+shift", 16, 2, 3),
    ],
)
def test_bytes_equal_the_cli(cli, tmp_path, spec, n, d, sets):
    out = tmp_path / "p.npy"
    cli("generate", spec, "-n", n, "-d", d, "--seed", 99, "--sets", sets, "-o", out)
    theirs = load_npy(out)
    ours = samplab.generate(spec, n=n, d=d, seed=99, sets=sets if sets > 1 else None)
    assert ours.dtype == np.float64 and ours.flags.c_contiguous
    assert ours.tobytes() == theirs.tobytes()


def test_default_seed_is_the_clis(cli, tmp_path):
    out = tmp_path / "p.npy"
    cli("generate", "random", "-n", 8, "-o", out)
    assert samplab.generate("random", n=8).tobytes() == load_npy(out).tobytes()


def _count_for(name, d):
    # a count every entry can make in d dimensions (as the Rust conformance test)
    if name.startswith(("jitter", "regular", "micro-jitter")):
        return 4**d
    if name.startswith("lattice.fibonacci"):
        return 55
    return {"poisson.maximal": 40, "lhs.oa": 49, "hexagonal": 56}.get(name, 64)


def test_every_registered_sampler_generates():
    for entry in samplab.samplers():
        name = entry["name"]
        # a saved set needs its file, and makes its own count
        args = f":path={SAVED}" if name == "file" else ""
        d = 2
        n = 16 if name == "file" else _count_for(name, d)
        p = samplab.generate(name + args, n=n, d=d, seed=3)
        assert p.shape == (n, d), name
        assert ((p >= 0) & (p < 1)).all(), name
        for alias in entry["aliases"]:
            assert samplab.generate(alias + args, n=n, d=d, seed=3).tobytes() == p.tobytes(), alias


def test_registry_entries_are_complete():
    kinds = {
        "samplers": samplab.samplers(),
        "metrics": samplab.metrics(),
        "warps": samplab.warps(),
        "integrands": samplab.integrands(),
        "formats": samplab.formats(),
        "scenes": samplab.scenes(),
    }
    for kind, entries in kinds.items():
        assert entries, kind
        for e in entries:
            assert set(e) >= {"name", "aliases", "summary", "params", "references", "details"}, (kind, e)
            for p in e["params"]:
                assert p["kind"] in ("real", "int", "choice", "path", "reals") and "default" in p and p["doc"], (kind, e["name"], p)
    sigma = next(p for e in kinds["samplers"] if e["name"] == "jitter.gaussian" for p in e["params"] if p["name"] == "sigma")
    assert (sigma["default"], sigma["min"], sigma["max"]) == (0.25, 0.0, 8.0)
    seed = next(p for e in kinds["metrics"] if e["name"] == "star-bound" for p in e["params"] if p["name"] == "seed")
    assert seed["kind"] == "int" and seed["max"] == 2**64 - 1


def test_sequences_have_random_access():
    for spec in ("sobol.owen", "halton.xor"):
        assert samplab.is_sequence(spec)
        whole = samplab.generate(spec, n=200, d=3, seed=5)
        tail = samplab.sequence_points(spec, start=120, n=80, d=3, seed=5)
        assert tail.tobytes() == whole[120:].tobytes()
    assert not samplab.is_sequence("jitter")
    with pytest.raises(samplab.Error, match="cannot be extended"):
        samplab.sequence_points("jitter", 0, 4)


def test_a_sampler_object_makes_the_functions_bytes_and_pickles():
    s = samplab.Sampler("sobol.owen", d=4)
    assert s.d == 4 and s.is_sequence and s.spec.startswith("sobol.owen")
    assert repr(s) == "samplab.Sampler('sobol.owen', d=4)"
    whole = samplab.generate("sobol.owen", n=64, d=4, seed=7, sets=3)
    assert s.generate(64, seed=7, sets=3).tobytes() == whole.tobytes()
    assert s.points(16, 48, seed=7).tobytes() == whole[0, 16:].tobytes()
    # pickled (as Dask sends it), copied, and the native half on its own
    for again in (pickle.loads(pickle.dumps(s)), copy.deepcopy(s)):
        assert isinstance(again, samplab.Sampler) and (again.spec, again.d) == (s.spec, s.d)
        assert again.generate(64, seed=7, sets=3).tobytes() == whole.tobytes()
    native = pickle.loads(pickle.dumps(s._native))
    assert native.generate(64, 4, 7, 3).tobytes() == whole.tobytes()


def test_a_sequence_served_per_pixel_is_the_point_set_under_each_pixels_seed():
    # one randomization word in both doors: pixel (x, y) of frame f holds the set that
    # generate makes under pixel_seed(seed, x, y, f), as `samplab pixels sobol.owen` does
    for spec in ("sobol.owen", "halton.xor", "lattice.shift"):
        s = samplab.Sampler(spec, d=3)
        film = s.pixels((3, 2), 8, frames=2, seed=5)
        assert film.shape == (2, 2, 3, 8, 3)
        assert film.tobytes() == samplab.pixels(spec, (3, 2), 8, dims=3, frames=2, seed=5).tobytes()
        for f, y, x in ((0, 0, 0), (1, 1, 2)):
            here = s.generate(8, seed=samplab.pixel_seed(5, x, y, f))
            assert film[f, y, x].tobytes() == here.tobytes(), (spec, f, y, x)
        assert film[0, 0, 0].tobytes() != film[0, 0, 1].tobytes()
    # "sobol" is a pixel sampler's name too: the Sampler serves the point set, unscrambled,
    # the same in every pixel
    plain = samplab.Sampler("sobol", d=2).pixels((2, 2), 4)
    assert (plain == plain[0, 0, 0]).all()
    assert not (samplab.pixels("sobol", (2, 2), 4) == plain).all()
    with pytest.raises(samplab.Error, match="sequence with random access"):
        samplab.Sampler("jitter").pixels((2, 2), 4)


def test_a_sampler_unpickled_in_another_process_makes_the_same_bytes():
    s = samplab.Sampler("halton.owen", d=3)
    program = (
        "import pickle, sys, hashlib; import samplab; "
        "t = pickle.loads(sys.stdin.buffer.read()); "
        "print(hashlib.sha256(t.generate(100, seed=4).tobytes()).hexdigest())"
    )
    out = subprocess.run([sys.executable, "-c", program], input=pickle.dumps(s), capture_output=True, check=True)
    assert out.stdout.decode().strip() == hashlib.sha256(s.generate(100, seed=4).tobytes()).hexdigest()


@pytest.mark.parametrize(
    "call,error,message",
    [
        (lambda: samplab.Sampler("sobl"), samplab.UnknownNameError, "did you mean sobol"),
        (lambda: samplab.Sampler("sobol", d=2000), samplab.Error, "1..=1024"),
        (lambda: samplab.Sampler("pmj02", d=3), samplab.Error, "3D is not supported"),
        (lambda: samplab.Sampler("random", d=-1), samplab.Error, "d"),
        (lambda: samplab.Sampler("sobol\ud800"), samplab.Error, "not valid text"),
        (lambda: samplab.Sampler("jitter").points(0, 4), samplab.Error, "cannot be extended"),
        (lambda: samplab.Sampler("jitter").generate(15), samplab.Error, "9 and 16"),
    ],
)
def test_a_sampler_refuses_bad_input_when_built(call, error, message):
    with pytest.raises(error, match=message):
        call()


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda: samplab.generate("jitter", n=15), "9 and 16"),
        (lambda: samplab.generate("sobl", n=4), "did you mean sobol"),
        (lambda: samplab.generate("jitter.gaussian:sigma=-1", n=16), "'sigma'"),
        (lambda: samplab.generate("pmj02", n=16, d=3), "3D is not supported"),
        (lambda: samplab.generate("random", n=0), "n must be"),
        (lambda: samplab.generate("random", n=2**40), "n must be"),
        (lambda: samplab.generate("random", n=4, seed=-1), "seed"),
        (lambda: samplab.generate("random", n=4.5), "whole number"),
        (lambda: samplab.generate("random", n=4, sets=0), "sets"),
        (lambda: samplab.sequence_points("sobol", start=2**32, n=1), "2\\^32 - 1"),
    ],
)
def test_bad_input_raises_samplab_error(call, message):
    with pytest.raises(samplab.Error, match=message):
        call()
    assert issubclass(samplab.Error, ValueError)


def test_every_format_round_trips_and_matches_the_cli(cli, tmp_path):
    stack = samplab.generate("sobol.owen", n=20, d=3, sets=2, seed=4)
    for fmt in samplab.formats():
        name = fmt["name"]
        ext = {"text": "txt"}.get(name, name)
        path = tmp_path / f"p.{ext}"
        samplab.save(path, stack)
        back = samplab.load(path)
        assert len(back) == 2 and all(b.tobytes() == s.tobytes() for b, s in zip(back, stack)), name
        # the CLI reads what Python wrote: its discrepancy of the file equals ours
        out = json.loads(cli("discrepancy", "l2-star", path, "--json"))
        assert out["metrics"][0]["values"] == samplab.discrepancy("l2-star", stack).tolist(), name


def test_numpy_files_of_float32_or_big_endian_read_as_their_float64_values(cli, tmp_path):
    stack = samplab.generate("sobol.owen", n=20, d=3, sets=2, seed=4)
    for dtype in ("<f4", ">f4", ">f8"):
        path = tmp_path / f"p_{'be' if dtype[0] == '>' else 'le'}{dtype[2]}.npy"
        saved = stack.astype(dtype)
        np.save(path, saved)  # numpy writes the file
        widened = saved.astype("<f8")
        back = samplab.load(path)
        assert all(b.tobytes() == w.tobytes() for b, w in zip(back, widened)), dtype
        out = json.loads(cli("discrepancy", "l2-star", path, "--json"))
        assert out["metrics"][0]["values"] == samplab.discrepancy("l2-star", widened).tolist(), dtype


def test_bad_files_raise(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("0.1 0.2\n0.3\n")
    with pytest.raises(samplab.Error, match="bad.txt:2"):
        samplab.load(bad)
    with pytest.raises(samplab.Error, match="unknown format"):
        samplab.load(bad, format="xls")
