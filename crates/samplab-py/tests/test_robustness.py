"""Bad input never crashes the interpreter: thousands of random calls with odd specs,
counts, shapes and values raise only samplab.Error (never a Rust panic, which pyo3 would
surface as pyo3_runtime.PanicException, nor a segfault, which would kill pytest)."""

import numpy as np
import pytest

import samplab

SPECS = [s["name"] for s in samplab.samplers()] + [
    "", ":", "jitter:", "jitter:sigma", "jitter.gaussian:sigma=1e308", "jitter.gaussian:sigma=nan",
    "poisson:radius=1e-9", "poisson:radius=1", "force-matrix:grid=1", "force-matrix:grid=16777216",
    "jitter.uniform:offsets=1048576", "sobol:x=1", "halton,xor", "ñ", "jitter.box:delta=-0",
]
METRICS = [m["name"] for m in samplab.metrics()] + ["projected:angle=nan", "star-bound:iterations=0", "star-bound:seed=-1", "l2"]


def _calls(rng):
    spec = SPECS[rng.integers(len(SPECS))]
    n = int(rng.choice([0, 1, 2, 3, 15, 16, 17, 64, 2**32 + 1]))
    d = int(rng.choice([0, 1, 2, 3, 5, 65, 1025]))
    shape = tuple(int(x) for x in rng.integers(0, 4, size=rng.integers(1, 4)))
    values = rng.choice([0.5, 0.0, 1.0, -0.1, 1.5, np.nan, np.inf])
    arr = np.full(shape, values)
    # the largest fine grid is valid, and force-matrix scans all its cells for every point
    # at every step (4096 points took 70 s): it is called with few points
    most = 64 if spec == "force-matrix:grid=16777216" else 4096
    return [
        lambda: samplab.generate(spec, n=min(n, most), d=min(d, 70), seed=int(rng.integers(2**63))),
        lambda: samplab.discrepancy(METRICS[rng.integers(len(METRICS))], arr),
        lambda: samplab.warp(samplab.warps()[rng.integers(7)]["name"], arr),
        lambda: samplab.spectrum(arr, res=int(rng.choice([0, 1, 3, 8]))),
        lambda: samplab.sequence_points(spec, start=int(rng.choice([0, 2**32 - 1, 2**53, 2**64 - 1])), n=min(n, 8), d=min(d, 4)),
        lambda: samplab.integrand(samplab.integrands()[rng.integers(13) % len(samplab.integrands())]["name"], arr),
    ]


def test_random_bad_calls_raise_only_samplab_errors():
    rng = np.random.default_rng(2026)
    errors = 0
    for _ in range(400):
        for call in _calls(rng):
            try:
                call()
            except samplab.Error:
                errors += 1
            except BaseException as e:  # a panic or any other exception is a bug
                pytest.fail(f"{type(e).__module__}.{type(e).__name__}: {e}")
    assert errors > 1000  # most of these calls are bad input


def test_failures_are_typed_and_pickle(tmp_path):
    import pickle

    # an unknown name is a LookupError with the name and the nearest known ones
    with pytest.raises(LookupError) as unknown:
        samplab.generate("jittr", n=16)
    e = unknown.value
    assert isinstance(e, samplab.UnknownNameError) and isinstance(e, samplab.Error)
    assert (e.kind, e.name) == ("sampler", "jittr") and "jitter" in e.suggestions
    # a refusal for memory is a MemoryError with the bytes asked and available
    with pytest.raises(MemoryError) as memory:
        samplab.generate("random", n=2**31, d=1000)
    m = memory.value
    assert isinstance(m, samplab.MemoryLimitError) and m.need > m.available > 0
    # a file that cannot be read is an OSError naming it
    missing = tmp_path / "missing.txt"
    with pytest.raises(OSError) as io:
        samplab.load(str(missing))
    assert isinstance(io.value, samplab.FileError) and io.value.path == str(missing)
    with pytest.raises(OSError, match="missing.exr"):
        samplab.read_exr(str(tmp_path / "missing.exr"))
    # every kind, and the plain one, survives pickling (Dask sends errors between processes),
    # by the standard reducers and by tblib's, which Dask's workers install
    from tblib import pickling_support

    plain = samplab.Error("something: wrong")
    for tblib in (False, True):
        if tblib:
            pickling_support.install(e, m, io.value, plain)
        for original in (e, m, io.value, plain):
            copy = pickle.loads(pickle.dumps(original))
            assert type(copy) is type(original) and str(copy) == str(original)
            assert copy.__dict__ == original.__dict__
    # and a bad value stays a ValueError
    with pytest.raises(ValueError):
        samplab.generate("jitter", n=15)
