"""Discrepancies, warps, spectra and integration: against scipy, brute force and the CLI."""

import itertools
import json

import numpy as np
import pytest
from scipy.stats import qmc

import samplab


def brute_star(x):
    """Star discrepancy by every critical box (corners at point coordinates or 1), open and
    closed: O(n^(d+1)), for small sets."""
    n, d = x.shape
    axes = [np.unique(np.append(x[:, k], 1.0)) for k in range(d)]
    worst = 0.0
    for corner in itertools.product(*axes):
        corner = np.array(corner)
        vol = np.prod(corner)
        open_count = np.all(x < corner, axis=1).sum() / n
        closed_count = np.all(x <= corner, axis=1).sum() / n
        worst = max(worst, vol - open_count, closed_count - vol)
    return worst


@pytest.mark.parametrize("d", [1, 2, 3])
def test_star_equals_brute_force(d):
    rng = np.random.default_rng(d)
    for _ in range(5):
        x = rng.random((int(rng.integers(3, 12)), d))
        assert samplab.discrepancy("star", x) == pytest.approx(brute_star(x), abs=1e-12)


@pytest.mark.parametrize("method,ours,squared", [("L2-star", "l2-star", False), ("CD", "centered", True), ("WD", "wraparound", True), ("MD", "mixture", True)])
def test_l2_family_equals_scipy(method, ours, squared):
    x = samplab.generate("sobol.owen", n=128, d=3, seed=2)
    theirs = qmc.discrepancy(x, method=method)
    value = samplab.discrepancy(ours, x)
    assert (value**2 if squared else value) == pytest.approx(theirs, rel=1e-10)


def test_stacks_and_flags():
    stack = samplab.generate("jitter", n=16, sets=4, seed=1)
    values = samplab.discrepancy("star", stack)
    assert values.shape == (4,)
    assert values[2] == samplab.discrepancy("star", stack[2])
    flags = samplab.discrepancy_flags("wd")
    assert flags == {"metric": "wraparound", "squared": False, "l2_closed_form": True, "toroidal_shift_invariant": True, "lower_bound": False}
    assert samplab.discrepancy_flags("star-bound:seed=9007199254740993")["metric"].endswith("seed=9007199254740993")


def test_discrepancy_equals_the_cli(cli):
    out = json.loads(cli("discrepancy", "star", "l2-star", "extreme", "--sampler", "nrooks", "-n", 32, "--sets", 3, "--seed", 4, "--json"))
    stack = samplab.generate("nrooks", n=32, sets=3, seed=4)
    for row in out["metrics"]:
        assert samplab.discrepancy(row["metric"], stack).tolist() == row["values"]


def test_every_metric_and_warp_runs():
    x = samplab.generate("jitter", n=64, seed=1)
    for m in samplab.metrics():
        value = samplab.discrepancy(m["name"], x)
        # discrepancies, distances and the relative radius lie in [0, 1]; a pair correlation
        # is a density ratio (1 for white noise), the effective Nyquist frequency a multiple
        # of a grid's (above 1 for a hexagonal lattice), the oscillation 10 x an RMS; the
        # t-value of 2^6 points lies in 0..=6
        unbounded = ("pcf", "rdf", "nyquist", "oscillation")
        upper = 6 if m["name"] == "t-value" else np.inf if m["name"] in unbounded else 1
        assert 0 <= value <= upper, m["name"]
    for w in samplab.warps():
        y = samplab.warp(w["name"], x)
        assert y.ndim == 2 and y.shape[0] <= 64 and np.isfinite(y).all(), w["name"]
    disk = samplab.warp("disk.concentric", x)
    assert (np.hypot(disk[:, 0], disk[:, 1]) <= 1).all()


@pytest.mark.parametrize(
    "call,message",
    [
        (lambda: samplab.discrepancy("star", [[0.5, 1.5]]), "point 0 coordinate 1 is 1.5"),
        (lambda: samplab.discrepancy("star", [[0.5, np.nan]]), r"^points\[0, 1\] is nan \(not finite\)$"),
        (lambda: samplab.discrepancy("star", [[[0.5, 0.5]], [[np.inf, 0.5]]]), r"^points\[1, 0, 0\] is inf "),
        (lambda: samplab.discrepancy("star", [0.5, 0.2]), "shape"),
        (lambda: samplab.discrepancy("star", [["a", "b"]]), "dtype"),
        (lambda: samplab.discrepancy("stra", [[0.5, 0.5]]), "did you mean star"),
        (lambda: samplab.discrepancy("star", np.random.default_rng(0).random((400, 5)), max_work=1e5), "max_work"),
        (lambda: samplab.warp("disk.concentric", np.zeros((3, 3))), "takes 2D points, not 3D"),
    ],
)
def test_bad_arrays_raise(call, message):
    with pytest.raises(samplab.Error, match=message):
        call()


def test_strided_input_is_copied_not_misread():
    x = samplab.generate("random", n=50, d=4, seed=3)
    view = x[:, ::2]  # not C-contiguous
    assert samplab.discrepancy("l2-star", view) == samplab.discrepancy("l2-star", np.ascontiguousarray(view))


def test_spectrum_equals_the_cli(cli, tmp_path):
    cli("spectrum", "--sampler", "jitter.gaussian:sigma=0.25", "-n", 64, "--sets", 6, "--res", 16, "--seed", 8, "-o", tmp_path / "s")
    theirs = json.loads((tmp_path / "s" / "spectrum.json").read_text())["statistics"]
    stack = samplab.generate("jitter.gaussian:sigma=0.25", n=64, sets=6, seed=8)
    ours = samplab.spectrum(stack, res=16)
    for name in ("periodogram", "expected", "variance"):
        assert ours[name].shape == (16, 16)
        assert ours[name].ravel().tolist() == theirs[name]["grid"]
        assert ours[f"{name}_radial"].tolist() == theirs[name]["radial"]
    direct = samplab.spectrum(stack, res=16, direct=True)
    np.testing.assert_allclose(direct["periodogram"], ours["periodogram"], atol=1e-8)


def test_integration_study_equals_the_cli(cli):
    theirs = json.loads(cli("integrate", "--sampler", "random", "--sampler", "jitter", "--integrand", "quad", "-n", "16,64", "--sets", 5, "--instances", 3, "--seed", 2, "--json"))
    ours = samplab.integrate(["random", "jitter"], "quad", [16, 64], sets=5, instances=3, seed=2)
    assert ours == theirs


def test_integrands_evaluate_with_exact_integrals():
    """Failure probability negligible: the worst error over the families and seeds 0-19 was
    0.07 of the tolerance (2026-12-06). Fixed seed. Least work: 2^14 points, milliseconds a
    family (fewer not measured)."""
    for fam in samplab.integrands():
        dims = fam["details"][0].split(": ")[1]
        # a d-dimensional family at its default d
        d = int(dims) if dims.isdigit() else next(p["default"] for p in fam["params"] if p["name"] == "d")
        x = samplab.generate("sobol.owen", n=2**14, d=d, seed=1)
        values, exact = samplab.integrand(fam["name"], x, instance=1, seed=5)
        assert values.shape == (2**14,)
        # a 2^14-point scrambled Sobol' estimate of a bounded integrand is close (1% of
        # the larger integrals: Genz's peaks reach 100)
        assert values.mean() == pytest.approx(exact, abs=0.02, rel=0.01), fam["name"]


def test_blue_noise_samplers_and_spacing_metrics_from_python():
    """Failure probability below 1e-20: white noise's PCF at r = 2 has a standard deviation
    of 0.015 over seeds 0-199 (2026-12-06), a tenth of the criterion; its relative radius
    and Nyquist share are a tenth of theirs too. Fixed seeds. Least work: 2048 points, a few
    milliseconds."""
    # the registries reach Python as they are: blue-noise sets are far better spread than
    # white noise by the relative radius, and a white-noise PCF at 2 d_max is near 1
    noise = samplab.generate("random", n=2048, seed=3)
    assert samplab.discrepancy("relative-radius", noise) < 0.1
    assert abs(samplab.discrepancy("pcf:r=2", noise) - 1) < 0.15
    for spec in ["elimination", "lloyd:iterations=20", "sot:iterations=50"]:
        x = samplab.generate(spec, n=512, seed=1)
        assert x.shape == (512, 2) and ((0 <= x) & (x < 1)).all(), spec
        assert samplab.discrepancy("relative-radius", x) > 0.3, spec
    d = samplab.discrepancy("min-distance", samplab.generate("regular", n=256))
    assert abs(d - 1 / 16) < 1e-15
    # a grid's zero region ends at sqrt(n) exactly; white noise has none
    assert samplab.discrepancy("nyquist", samplab.generate("regular", n=256)) == pytest.approx(1, abs=1e-12)
    assert samplab.discrepancy("nyquist", noise) < 0.1
    step = samplab.generate("step:iterations=100", n=512, seed=2)
    assert samplab.discrepancy("nyquist", step) > 0.4


def test_predict_equals_the_cli_and_white_noise_is_var_over_n(cli):
    args = ["--integrand", "disk:r=0.3,cx=0.45,cy=0.5", "--sampler", "random", "--sampler", "sobol.owen"]
    theirs = json.loads(cli("predict", *args, "-n", "64,256", "--res", 32, "--sets", 8, "--measure", 50, "--seed", 3, "--json"))
    ours = samplab.predict("disk:r=0.3,cx=0.45,cy=0.5", ["random", "sobol.owen"], [64, 256], res=32, sets=8, measure=50, seed=3)
    assert ours == theirs
    p = np.pi * 0.09
    random = [r for r in ours["rows"] if r["sampler"] == "random"]
    for row in random:
        assert abs(row["predicted"]["variance"] - p * (1 - p) / row["n"]) < 1e-15
    with pytest.raises(samplab.Error, match="measure = 1|--measure 1|measure 1"):
        samplab.predict("disk", "random", 64, measure=1)
    with pytest.raises(samplab.Error, match="n = .*: must be a whole number"):
        samplab.predict("disk", "random", 64.0)


def test_predict_takes_callables_and_arrays_with_their_errors():
    """Failure probability about 7e-5, from the prediction within 4 standard errors of the
    measured variance (400 sets: Student's t with 399 degrees of freedom); the rest is exact.
    Fixed seed. Least work: 4 standard errors at any count; 400 sets let a bias of a fifth of
    the variance's spread show."""
    # a step in x: Var(f) = 1/4, so white noise predicts 1 / (4 n); the callable's spectrum is
    # an FFT of sampled values (within its stated error), the array's a closed form (exact)
    def step(x):
        return (x[:, 0] < 0.5).astype(float)

    grid = np.zeros((4, 4))
    grid[:, :2] = 1.0
    out = samplab.predict([step, grid], "random", [64, 256], res=16, sets=8)
    by = {(r["integrand"], r["n"]): r["predicted"]["variance"] for r in out["rows"]}
    info = {i["spec"]: i for i in out["integrands"]}
    assert info["array 4x4"]["spectrum"] == "closed form"
    assert info["step"]["spectrum"].startswith("FFT")
    for n in (64, 256):
        assert abs(by[("array 4x4", n)] - 0.25 / n) < 1e-15
        assert abs(by[("step", n)] - 0.25 / n) <= info["step"]["error"] / n + 1e-15
    # measured with its integral, shifted: the prediction is exact in expectation
    row = samplab.predict(lambda x: x[:, 0] ** 2, "jitter", 64, res=32, sets=8, measure=400, shift=True, exact=1 / 3)["rows"][0]
    assert abs(row["predicted"]["variance"] - row["measured"]["variance"]) <= 4 * row["measured"]["se"]

    def broken(x):
        raise ZeroDivisionError("inside the user's function")

    with pytest.raises(ZeroDivisionError, match="inside the user's function"):
        samplab.predict(broken, "random", 64, res=16, sets=8)
    with pytest.raises(samplab.Error, match="one per row"):
        samplab.predict(lambda x: x, "random", 64, res=16, sets=8)
    with pytest.raises(samplab.Error, match="NaN at"):
        samplab.predict(lambda x: np.full(len(x), np.nan), "random", 64, res=16, sets=8)
    with pytest.raises(samplab.Error, match="pass exact="):
        samplab.predict(step, "random", 64, res=16, sets=8, measure=10)
    with pytest.raises(samplab.Error, match=r"^d = 3: a callable integrand is 1D or 2D here$"):
        samplab.predict(step, "random", 64, d=3)
    with pytest.raises(samplab.Error, match="cell"):
        samplab.predict(np.array([[1.0, np.inf]]), "random", 64, res=16, sets=8)
    with pytest.raises(samplab.Error, match="expected a spec string"):
        samplab.predict(3, "random", 64)


def test_t_values_equal_the_cli(cli):
    """The Python face prints the same table as ``samplab t-values --json``, from the
    matrices for a net and counted on the points for any other set, and refuses bad input
    with samplab.Error."""
    for spec, projection, dims in [("cascaded.owen", "pairs", 4), ("pmj02", "all", 2), ("net.owen", "quadruples", 5)]:
        ours = samplab.t_values(spec, dims=dims, m=8, projection=projection, seed=7)
        theirs = json.loads(cli("t-values", spec, "-d", dims, "--m", 8, "--projection", projection, "--seed", 7, "--json"))
        assert ours == theirs
    assert samplab.t_values("cascaded", dims=3, m=6)["from_matrices"]
    assert all(max(p["t"]) == 0 for p in samplab.t_values("cascaded", dims=6, m=10)["projections"])
    for bad in [dict(projection="triples"), dict(m=0), dict(base=3), dict(dims=1.5)]:
        with pytest.raises(samplab.Error):
            samplab.t_values("net", **bad)


def test_conform_equals_the_cli(cli, tmp_path):
    """The Python face gives ``samplab conform --json``'s checks: samplab's own sets pass,
    the XOR scramble claimed as Owen's fails the reference check alone, a float32 film of
    pixels is compared in single precision, and bad input is refused with samplab.Error."""
    mine = samplab.generate("net.owen", n=128, d=3, sets=3, seed=7)
    path = tmp_path / "mine.npy"
    np.save(path, mine)
    ours = samplab.conform(mine, "net.owen", seed=7)
    assert ours == json.loads(cli("conform", path, "--as", "net.owen", "--seed", 7, "--json"))
    assert [c["name"] for c in ours] == ["range", "reference", "uniform", "independent", "nets", "distinct"]
    assert all(c["passed"] for c in ours)
    xor = samplab.conform(mine, "net.xor", seed=7)
    assert [c["name"] for c in xor if not c["passed"]] == ["reference"]
    # 32-bit fixed point, as a renderer's integers: samplab's values cut to 32 bits
    words = np.floor(mine * 2.0**32).astype(np.uint32)
    fixed = samplab.conform(words, "net.owen", seed=7)
    assert all(c["passed"] for c in fixed) and "32-bit fixed point" in fixed[1]["detail"], fixed
    np.save(tmp_path / "words.npy", words)
    assert json.loads(cli("conform", tmp_path / "words.npy", "--as", "net.owen", "--seed", 7, "--json")) == fixed
    off = np.nextafter(mine, 1.0)  # one ulp up everywhere
    assert not samplab.conform(off, "net.owen", seed=7)[1]["passed"]
    assert samplab.conform(off, "net.owen", seed=7, ulps=1)[1]["passed"]
    # the shape pixels() returns, two frames: the film from the shape
    frames = samplab.pixels("zsobol", res=(4, 2), spp=8, dims=2, frames=2, seed=5)
    assert all(c["passed"] for c in samplab.conform(frames, "zsobol", seed=5))
    with pytest.raises(samplab.Error, match="gives its film"):
        samplab.conform(frames, "zsobol", res=(4, 2))
    film = frames[0]  # (height, width, spp, dims)
    singles = film.reshape(8, 8, 2).astype(np.float32)
    checks = samplab.conform(singles, "zsobol", seed=5, res=(4, 2))
    assert all(c["passed"] for c in checks), checks
    assert "single precision" in checks[1]["detail"]
    for bad in [dict(as_="nosuch"), dict(as_="zsobol", res=(3, 2)), dict(as_="net", res=(1, 2, 3)), dict(as_="net", frame=-1)]:
        with pytest.raises(samplab.Error):
            samplab.conform(mine, **bad)
