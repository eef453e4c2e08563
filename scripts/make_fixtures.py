#!/usr/bin/env python3
"""Reference values from independent implementations, for samplab's tests.

Writes crates/samplab/tests/fixtures/scipy_sobol.json: the first 1024 unscrambled Sobol'
points in 16 dimensions from scipy.stats.qmc.Sobol (Joe-Kuo directions), and the first
64 unscrambled Halton points in 8 dimensions from scipy.stats.qmc.Halton.

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
