#!/usr/bin/env python3
"""Reference values from independent implementations, for samplab's tests.

Writes crates/samplab/tests/fixtures/scipy_sobol.json: the first 1024 unscrambled Sobol'
points in 16 dimensions from scipy.stats.qmc.Sobol (Joe-Kuo directions), and the first
64 unscrambled Halton points in 8 dimensions from scipy.stats.qmc.Halton.

Writes crates/samplab/tests/fixtures/scipy_discrepancy.json: random point sets (numpy,
fixed seed; some with ties and coordinates 0 and 1) with scipy.stats.qmc.discrepancy
for methods CD, WD, MD and L2-star, as scipy returns them (CD, WD and MD squared,
L2-star unsquared).

Usage: pip install scipy && python3 scripts/make_fixtures.py
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
