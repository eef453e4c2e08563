#!/usr/bin/env python3
"""samplab's Python package against the Rust core and against its Python peers, in one
process on the same arrays: scipy.stats.qmc and QMCPy. One thread (RAYON_NUM_THREADS=1),
medians of repeated runs. Run by `bench/compare python` (which installs the package and the
peers into bench/.venv).
"""
import json
import math
import os
import subprocess
import timeit

os.environ.setdefault("RAYON_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import qmcpy  # noqa: E402
from scipy.integrate import qmc_quad  # noqa: E402
from scipy.stats import qmc  # noqa: E402

import samplab  # noqa: E402
from samplab.qmc import Engine  # noqa: E402
from timing import median_time  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "throughput")


def rust_seconds(spec, n):
    out = subprocess.run([EXAMPLE, "%s:%d" % (spec, n)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
    return json.loads(out.strip().splitlines()[-1])["seconds"]


def row(what, peer, peer_s, ours_s):
    print("%-44s %-34s %10.5f s | samplab %10.5f s | ratio %7.1fx" % (what, peer, peer_s, ours_s, peer_s / ours_s), flush=True)


N = 1 << 20
print("== the package against the Rust core (same work, one thread)")
for spec in ("sobol.owen", "halton.xor", "jitter"):
    n = N if spec != "jitter" else 1024**2
    py = median_time(lambda: samplab.generate(spec, n=n, d=2, seed=1))
    rs = rust_seconds(spec, n)
    print("%-44s python %10.5f s | rust example %10.5f s | python / rust %5.2f" % ("generate %s n=%d" % (spec, n), py, rs, py / rs))

calls = 20000
for what, fn in [
    ("generate('random', n=1, d=1)", lambda: samplab.generate("random", n=1, d=1, seed=1)),
    ("discrepancy('star', 1 point)", lambda: samplab.discrepancy("star", [[0.5, 0.5]])),
]:
    per = min(timeit.repeat(fn, number=calls, repeat=5)) / calls
    print("%-44s per call %7.2f us" % (what, per * 1e6))

print("== against scipy.stats.qmc and QMCPy (same n, d = 2)")
rng = np.random.default_rng(1)
ours = median_time(lambda: samplab.generate("sobol.owen", n=N, seed=1))
row("Sobol' n=2^20 (Owen vs scipy LMS+shift)", "scipy Sobol(scramble=True)", median_time(lambda: qmc.Sobol(2, seed=rng).random(N)), ours)
row("Sobol' n=2^20 (Owen vs QMCPy NUS)", "qmcpy DigitalNetB2(randomize=NUS)", median_time(lambda: qmcpy.DigitalNetB2(2, seed=7, randomize="NUS").gen_samples(N), min_runs=1), ours)
row("Sobol' n=2^20 (Owen vs QMCPy LMS DS)", "qmcpy DigitalNetB2()", median_time(lambda: qmcpy.DigitalNetB2(2, seed=7).gen_samples(N)), ours)
ours = median_time(lambda: samplab.generate("halton.xor", n=N, seed=1))
row("Halton n=2^20, scrambled", "scipy Halton(scramble=True)", median_time(lambda: qmc.Halton(2, seed=rng).random(N)), ours)
row("Halton n=2^20, scrambled", "qmcpy Halton()", median_time(lambda: qmcpy.Halton(2, seed=7).gen_samples(N), min_runs=3), ours)
row("Latin hypercube n=2^20", "scipy LatinHypercube", median_time(lambda: qmc.LatinHypercube(2, seed=rng).random(N)), median_time(lambda: samplab.generate("nrooks", n=N, seed=1)))


def engine_draws(make, n, draws=8):
    """An engine made, then `draws` draws of n points: small draws show a per-call cost."""
    def run():
        engine = make()
        for _ in range(draws):
            engine.random(n)
    return median_time(run)


row("Halton engine, 8 draws of 64 points, 8D", "scipy Halton(scramble=True)",
    engine_draws(lambda: qmc.Halton(8, seed=rng), 64), engine_draws(lambda: Engine("halton.owen", d=8, seed=1), 64))
n_pd = 10_000
radius = 0.72 * math.sqrt(2.0 / (math.sqrt(3.0) * n_pd))
peer = median_time(lambda: qmc.PoissonDisk(2, radius=radius, seed=rng).random(n_pd), min_runs=3)
row("Poisson disk n=10^4 (Bridson)", "scipy PoissonDisk", peer, median_time(lambda: samplab.generate("poisson.fast", n=n_pd, seed=1)))
x = samplab.generate("sobol.owen", n=1 << 12, d=2, seed=3)
for method, metric in (("L2-star", "l2-star"), ("CD", "centered"), ("WD", "wraparound")):
    row("%s discrepancy n=2^12" % method, "scipy qmc.discrepancy", median_time(lambda: qmc.discrepancy(x, method=method)), median_time(lambda: samplab.discrepancy(metric, x)))


def f(x):
    return np.prod(x**2, axis=0)


peer = median_time(lambda: qmc_quad(f, [0] * 3, [1] * 3, n_estimates=8, n_points=1 << 14, qrng=qmc.Sobol(3, seed=rng)), min_runs=5)
ours = median_time(lambda: qmc_quad(f, [0] * 3, [1] * 3, n_estimates=8, n_points=1 << 14, qrng=Engine("sobol.owen", d=3, seed=1)), min_runs=5)
row("qmc_quad 8 x 2^14 points, 3D", "scipy Sobol engine", peer, ours)
