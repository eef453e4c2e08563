"""The adversarial probe's Python cases: allocations past the memory available raise
samplab.Error instead of aborting the interpreter, and bad study arguments raise
samplab.Error naming them instead of bare MemoryError / OverflowError / AttributeError /
FileExistsError, or being accepted."""

import os
import subprocess
import sys

import numpy as np
import pytest

import samplab
from samplab import Study


def test_allocations_past_an_address_space_limit_raise_samplab_errors():
    # under `ulimit -v 2000000`, as the CLI's probe: each call must raise samplab.Error
    code = """
import resource, samplab
resource.setrlimit(resource.RLIMIT_AS, (2_000_000 * 1024, resource.RLIM_INFINITY))
for call in [
    lambda: samplab.discrepancy("oscillation", samplab.generate("random", n=100000)),
    lambda: samplab.sequence_points("sobol", 0, 2**40),
    lambda: samplab.render("spheres", n=2**32),
    lambda: samplab.integrate(["random"], "quad", [16], sets=2, instances=10**12),
]:
    try:
        call()
    except samplab.Error as e:
        print("refused:", str(e).splitlines()[0])
    else:
        print("accepted")
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert len(lines) == 4 and all(line.startswith("refused: ") for line in lines), out.stdout


def test_study_arguments_are_checked_with_samplab_errors(tmp_path):
    with pytest.raises(samplab.Error, match="sets"):
        Study.spectrum("jitter", 16, sets=10**15, res=8)
    with pytest.raises(samplab.Error, match="out of range"):
        Study.integrate(["random"], "quad", [-1])
    with pytest.raises(samplab.Error, match="whole number"):
        Study.integrate(["random"], "quad", [16.7])
    # a lone float count is refused as a count, not iterated (it raised TypeError)
    for call in (lambda: samplab.integrate("random", "quad", 64.0), lambda: Study.integrate("random", "quad", 64.0)):
        with pytest.raises(samplab.Error, match="= 64.0: must be a whole number"):
            call()
    with pytest.raises(samplab.Error, match="a study needs at least 1 count n, got 0"):
        Study.integrate(["random"], "quad", [])
    with pytest.raises(samplab.Error, match="a study needs at least 1 sampler, got 0"):
        Study.integrate([], "quad", [16])
    study = Study.integrate(["random"], "quad", [16], sets=2, instances=1)
    with pytest.raises(samplab.Error, match="neither a Dask client nor a concurrent.futures.Executor"):
        study.run("nope")
    file = tmp_path / "file"
    file.write_text("mine")
    with pytest.raises(samplab.Error, match="must be a folder"):
        study.run(checkpoint=str(file))
    assert file.read_text() == "mine"
    # a chunk linked to /dev/zero is refused, not read until memory runs out
    folder = tmp_path / "checkpoint"
    study.run(checkpoint=str(folder))
    chunk = next(p for p in folder.iterdir() if p.name.endswith(".chunk"))
    chunk.unlink()
    os.symlink("/dev/zero", chunk)
    with pytest.raises(samplab.Error, match="not a regular file"):
        study.run(checkpoint=str(folder))


def test_empty_stacks_are_refused():
    for empty in [np.empty((0, 4, 2)), np.empty((2, 0, 2)), np.empty((0, 2))]:
        with pytest.raises(samplab.Error, match="empty"):
            samplab.discrepancy("star", empty)


# Round 3 (issue 89)


def test_work_limits_raise_work_limit_error():
    with pytest.raises(samplab.WorkLimitError, match="raise it with max_work") as caught:
        samplab.discrepancy("star", samplab.generate("random", n=4000, d=6), max_work=10)
    assert caught.value.limit == 10 and caught.value.work > 1e10


@pytest.mark.parametrize(
    "call",
    [
        lambda: samplab.discrepancy("star", samplab.generate("random", n=16), max_work="x"),
        lambda: samplab.spectrum(samplab.generate("random", n=16), res=8, tolerance="x"),
        lambda: samplab.cubature("keister:d=2", abs_tol="x"),
        lambda: samplab.image_metrics(np.zeros((8, 8)), sigma="x"),
        lambda: samplab.image_metrics(np.zeros((8, 8)), sigma=[1, "x"]),
        lambda: samplab.generate("jit\udc80", n=4),
        lambda: samplab.integrate(["random", "jit\udc80"], "quad", [16]),
        lambda: samplab.image_metrics(np.zeros((0, 0))),
        lambda: samplab.image_metrics(np.zeros((8, 0, 3))),
        lambda: samplab.image_metrics(np.zeros((8, 8), complex)),
        lambda: samplab.cubature(lambda x: x.sum(axis=1), d=2, exact=float("nan")),
        lambda: samplab.cubature(lambda x: x.sum(axis=1), d=2, exact=float("inf")),
        lambda: samplab.integrate("random", lambda x: x[:, 0], [16], d=1, exact=float("nan")),
    ],
)
def test_bad_arguments_raise_samplab_errors(call):
    with pytest.raises(samplab.Error):
        call()


@pytest.mark.parametrize(
    "inner",
    [
        "samplab.cubature(lambda y: y.sum(axis=1), d=1, abs_tol=1e-2)['estimate'] * 0",
        "samplab.generate('sobol.owen', n=1 << 17).sum() * 0",
        "samplab.discrepancy('l2-star', samplab.generate('random', n=1 << 17)) * 0",
    ],
)
def test_a_callable_that_calls_samplab_finishes(inner):
    """Failure probability negligible: the estimate's 99% bound meets 1e-2 and the check
    allows 5e-2, on an integrand Owen-scrambled Sobol' integrates almost exactly. Least work:
    one small cubature, the call that hung."""
    # re-entrant: samplab inside an integrand samplab evaluates (it hung the interpreter)
    code = f"""
import samplab
f = lambda x: x.sum(axis=1) + {inner}
print(samplab.cubature(f, d=2, abs_tol=1e-2, max_n=1 << 12)["estimate"])
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert abs(float(out.stdout) - 1.0) < 0.05, out.stdout


def test_a_render_past_the_memory_available_raises():
    code = """
import resource, samplab
resource.setrlimit(resource.RLIMIT_AS, (8_000_000 * 1024, resource.RLIM_INFINITY))
try:
    samplab.render("spheres", n=10**8)
except samplab.MemoryLimitError as e:
    print("refused:", e)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.startswith("refused: "), out.stdout
