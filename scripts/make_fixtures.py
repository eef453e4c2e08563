#!/usr/bin/env python3
"""Reference values from independent implementations, for samplab's tests.

Writes crates/samplab/tests/fixtures/scipy_sobol.json: the first 1024 unscrambled Sobol'
points in 16 dimensions from scipy.stats.qmc.Sobol (Joe-Kuo directions), and the first
64 unscrambled Halton points in 8 dimensions from scipy.stats.qmc.Halton.

Writes crates/samplab/tests/fixtures/scipy_discrepancy.json: random point sets (numpy,
fixed seed; some with ties and coordinates 0 and 1) with scipy.stats.qmc.discrepancy
for methods CD, WD, MD and L2-star, as scipy returns them (CD, WD and MD squared,
L2-star unsquared).

Writes the QMC constructions fixtures too, and normal_quantile.json: the standard normal
quantile from mpmath at 1706 points (see the end of the file).

Usage: apt-get install libgsl-dev && pip install scipy==1.17.1 qmcpy==2.4 mpmath==1.4.1 && python3 scripts/make_fixtures.py
"""
import json
import os

import scipy
from scipy.stats import qmc

here = os.path.join(os.path.dirname(__file__), "..", "crates", "samplab", "tests", "fixtures")
sobol = qmc.Sobol(d=16, scramble=False).random(1024)
halton = qmc.Halton(d=8, scramble=False).random(64)
with open(os.path.join(here, "scipy_sobol.json"), "w") as f:
    json.dump({
        "source": "scipy.stats.qmc %s, scramble=False" % scipy.__version__,
        "sobol_16d_first_1024": sobol.tolist(),
        "halton_8d_first_64": halton.tolist(),
    }, f)
    f.write("\n")

rng = __import__("numpy").random.default_rng(20261121)
cases = []
for d, n in [(1, 7), (2, 16), (2, 100), (2, 257), (3, 50), (5, 64), (8, 33)]:
    x = rng.random((n, d))
    if n > 20:
        x[3] = x[5]          # a duplicated point
        x[7, 0] = 0.0        # coordinates on the boundary
        x[8, -1] = 1.0
    values = {m: float(qmc.discrepancy(x, method=m)) for m in ["CD", "WD", "MD", "L2-star"]}
    cases.append({"dims": d, "points": x.tolist(), "scipy": values})
with open(os.path.join(here, "scipy_discrepancy.json"), "w") as f:
    json.dump({"source": "scipy.stats.qmc.discrepancy %s (CD, WD, MD squared; L2-star unsquared)" % scipy.__version__, "cases": cases}, f)
    f.write("\n")

# --- QMC constructions (needs qmcpy==2.4, and GSL: apt-get install libgsl-dev) ---
# crates/samplab/tests/fixtures/qmc_constructions.json: unrandomized points of QMCPy's
# Faure and of its digital nets (base 2 and base 3) from the random generating matrices
# written beside it in the LDData "dnet" format (net_b2.txt, net_b3.txt), and GSL's
# Niederreiter base-2 sequence (Bratley, Fox & Niederreiter's construction, 30 bits), and
# QMCPy's lattice in radical-inverse order from the random vector in lattice_vector.txt.
import subprocess
import tempfile

import numpy as np
import qmcpy

rng = np.random.default_rng(20261124)


def write_dnet(path, base, mats, rows, note):
    """mats: (d, m, rows) digits, row 0 the most significant digit of each column's integer."""
    d, m, _ = mats.shape
    weights = base ** np.arange(rows - 1, -1, -1, dtype=object)
    with open(path, "w") as f:
        f.write("# %s\n%d # base\n%d # dimensions\n%d # points\n%d # digits per column\n" % (note, base, d, base ** m, rows))
        for j in range(d):
            f.write(" ".join(str(int(sum(int(x) * w for x, w in zip(mats[j, k], weights)))) for k in range(m)) + "\n")


out = {"source": "qmcpy %s (randomize=False); GNU GSL gsl_qrng_niederreiter_2" % qmcpy.__version__}
out["faure"] = {str(d): qmcpy.Faure(d, randomize=False)(n, warn=False).tolist() for d, n in [(3, 243), (5, 125), (11, 121)]}
b2 = rng.integers(0, 2, size=(4, 10, 30))
write_dnet(os.path.join(here, "net_b2.txt"), 2, b2, 30, "random base-2 matrices for samplab's tests (scripts/make_fixtures.py)")
ints = (b2 * (2 ** np.arange(29, -1, -1))).sum(axis=2).astype(np.uint64)
out["net_b2"] = qmcpy.DigitalNetB2(4, randomize=False, generating_matrices=ints, msb=True, t=30)(1024, warn=False).tolist()
b3 = rng.integers(0, 3, size=(3, 6, 12)).astype(np.uint64)
write_dnet(os.path.join(here, "net_b3.txt"), 3, b3, 12, "random base-3 matrices for samplab's tests (scripts/make_fixtures.py)")
out["net_b3"] = qmcpy.DigitalNetAnyBases(3, randomize="False", bases_generating_matrices=(3, b3))(729, warn=False).tolist()
with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, "n.c"), "w") as f:
        f.write("#include <stdio.h>\n#include <gsl/gsl_qrng.h>\nint main(void){gsl_qrng*q=gsl_qrng_alloc(gsl_qrng_niederreiter_2,12);double v[12];"
                "for(int i=0;i<256;i++){gsl_qrng_get(q,v);for(int j=0;j<12;j++)printf(\"%.17g \",v[j]);printf(\"\\n\");}return 0;}\n")
    subprocess.run(["gcc", os.path.join(tmp, "n.c"), "-o", os.path.join(tmp, "n"), "-lgsl", "-lgslcblas", "-lm"], check=True)
    text = subprocess.run([os.path.join(tmp, "n")], check=True, capture_output=True, text=True).stdout
out["niederreiter_gsl_12d_first_256"] = [[float(x) for x in line.split()] for line in text.splitlines()]
z = np.concatenate([[1], 2 * rng.integers(0, 512, size=4) + 1]).astype(np.uint64)
with open(os.path.join(here, "lattice_vector.txt"), "w") as f:
    f.write("# a random generating vector for samplab's tests (scripts/make_fixtures.py)\n5 # dimensions\n1024 # points\n")
    f.write("".join("%d\n" % x for x in z))
out["lattice_radical_inverse"] = qmcpy.Lattice(5, randomize=False, generating_vector=z, m_max=10, order="RADICAL INVERSE")(1024, warn=False).tolist()
with open(os.path.join(here, "qmc_constructions.json"), "w") as f:
    json.dump(out, f)
    f.write("\n")

# The standard normal quantile at points over (0, 1) and deep into both tails, from mpmath's
# erfinv at enough digits that 2p - 1 keeps p's every digit; each exact value rounded to 25
# significant digits (more than a double holds, so a test can count ulps).
import random

import mpmath

pick = random.Random(20261128)
ps = [pick.random() for _ in range(1000)]
ps += [10.0 ** -pick.uniform(1, 307) for _ in range(500)]
ps += [1.0 - 10.0 ** -pick.uniform(1, 16) for _ in range(200)]
ps += [0.075, 0.925, 0.5, 0.975, 1e-300, 2.2250738585072014e-308]  # AS 241's region edges, the extremes
rows = []
for p in ps:
    with mpmath.workdps(60 + int(-mpmath.log10(p))):
        rows.append([p, mpmath.nstr(mpmath.sqrt(2) * mpmath.erfinv(2 * mpmath.mpf(p) - 1), 25)])
with open(os.path.join(here, "normal_quantile.json"), "w") as f:
    json.dump({"source": "mpmath %s: sqrt(2) erfinv(2p - 1), 25 significant digits" % mpmath.__version__,
               "p_and_quantile": rows}, f)
    f.write("\n")
