"""samplab.cubature: a user's callable and a family integrated to a tolerance, the same
numbers as the CLI, errors from the callable and from bad settings."""

import json
import os
import subprocess

import numpy as np
import pytest

import samplab


def test_a_callable_reaches_the_tolerance_and_the_exact_value():
    # exp(-|x|^2) over [0, 1]^3: (sqrt(pi)/2 erf(1))^3
    from math import erf, pi, sqrt

    exact = (sqrt(pi) / 2 * erf(1.0)) ** 3
    r = samplab.cubature(lambda x: np.exp(-(x * x).sum(axis=1)), 3, abs_tol=1e-5, seed=3)
    assert r["converged"] and r["bound"] <= 1e-5
    assert abs(r["estimate"] - exact) <= 1e-5
    assert r["exact"] is None and r["integrand"] == "<lambda>"
    assert r["evaluations"] == sum(s["n"] for s in r["steps"]) * 16


def test_a_family_gives_the_cli_numbers():
    cli = os.environ.get("SAMPLAB_CLI")
    if not cli:
        pytest.skip("SAMPLAB_CLI not set")
    args = ["--integrand", "keister:d=3", "--abs-tol", "1e-3", "--seed", "5", "--json"]
    out = json.loads(subprocess.run([cli, "cubature", *args], capture_output=True, text=True, check=True).stdout)
    r = samplab.cubature("keister:d=3", abs_tol=1e-3, seed=5)
    for key in ("estimate", "bound", "n", "evaluations", "exact", "integrand", "steps", "kind"):
        assert r[key] == out[key], key


def test_errors_name_what_is_wrong():
    with pytest.raises(samplab.Error, match="give the dimension"):
        samplab.cubature(lambda x: x[:, 0])
    with pytest.raises(samplab.Error, match="replications = 1"):
        samplab.cubature("keister:d=2", replications=1)
    with pytest.raises(samplab.Error, match="min_n must be a whole number|min_n = 2.5"):
        samplab.cubature("keister:d=2", min_n=2.5)
    with pytest.raises(samplab.Error, match="deterministic"):
        samplab.cubature("keister:d=2", sampler="halton")

    def broken(x):
        raise ValueError("my bug")

    with pytest.raises(ValueError, match="my bug"):
        samplab.cubature(broken, 2)


def test_samplers_compared_on_your_function():
    """samplab.integrate on a callable: the same rows as the family it computes, and its
    integral from samplab.cubature."""
    spec = "keister:d=2"  # no random coefficients: every instance is this function
    x0 = np.array([[0.5, 0.5]])
    _, exact = samplab._samplab.integrand_eval(spec, 0, samplab.DEFAULT_SEED, x0)

    def f(x):
        return samplab._samplab.integrand_eval(spec, 0, samplab.DEFAULT_SEED, np.ascontiguousarray(x))[0]

    mine = samplab.integrate(["random", "sobol.owen"], f, [64, 256, 1024], sets=20, d=2, exact=exact)
    family = samplab.integrate(["random", "sobol.owen"], spec, [64, 256, 1024], sets=20, instances=1)
    for a, b in zip(mine["rows"], family["rows"]):
        assert a["integrand"] == "f"
        for key in ("relative_mean", "relative_variance", "rmse"):
            assert a[key] == b[key], key
    # sobol.owen converges faster than random on this smooth function
    fits = {fit["sampler"]: fit["exponent"] for fit in mine["fits"]}
    assert fits["sobol.owen"] < fits["random"]
    reference = samplab.cubature(f, 2, abs_tol=1e-6)
    assert abs(reference["estimate"] - exact) <= 1e-6
    with pytest.raises(samplab.Error, match="exact="):
        samplab.integrate("random", f, 64, d=2)
