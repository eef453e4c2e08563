#!/usr/bin/env python3
"""Writes crates/samplab/tests/fixtures/qmcpy_integrals.json: the integrals QMCPy 2.4
defines for the families samplab shares with it, for `crates/samplab/tests/integrands_d.rs`
to compare with samplab's exact values.

- Keister: QMCPy's closed form `Keister.get_exact_value(d)`, d = 1 .. 32.
- Genz oscillatory and corner peak: QMCPy's `Genz` fixes the coefficients (kind_coeff 1,
  2, 3) and defines no exact value, so the value is QMCPy's own CubQMCNetG estimate at
  abs_tol 1e-10 (its guaranteed bound), in d = 2 and 3, with the coefficients used.
- Ishigami (a = 7, b = 0.1): QMCPy's CubQMCNetG estimate at abs_tol 1e-8.

Run with QMCPy 2.4 installed (`pip install qmcpy==2.4`): python3 scripts/qmcpy_integrals.py
"""
import json
import os
import warnings

import numpy as np
import qmcpy

warnings.simplefilter("ignore")
out = {"qmcpy": qmcpy.__version__, "keister": {}, "genz": [], "ishigami": {}}
keister = qmcpy.Keister(qmcpy.DigitalNetB2(1, seed=7))
for d in range(1, 33):
    out["keister"][str(d)] = float(keister.get_exact_value(d))

for kind in ("OSCILLATORY", "CORNER PEAK"):
    for coeff in (1, 2, 3):
        for d in (2, 3):
            g = qmcpy.Genz(qmcpy.DigitalNetB2(d, seed=7), kind_func=kind, kind_coeff=coeff)
            value, data = qmcpy.CubQMCNetG(g, abs_tol=1e-10, rel_tol=0, n_limit=2**30).integrate()
            out["genz"].append({
                "family": "genz.oscillatory" if kind == "OSCILLATORY" else "genz.corner-peak",
                "kind_coeff": coeff,
                "d": d,
                "a": [float(c) for c in np.ravel(g.c)],
                "value": float(value),
                "bound": float(data.comb_bound_diff) / 2,
            })

ish = qmcpy.Ishigami(qmcpy.DigitalNetB2(3, seed=7), a=7, b=0.1)
value, data = qmcpy.CubQMCNetG(ish, abs_tol=1e-8, rel_tol=0, n_limit=2**30).integrate()
out["ishigami"] = {"a": 7.0, "b": 0.1, "value": float(value), "bound": float(data.comb_bound_diff) / 2}

here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "crates", "samplab", "tests", "fixtures")
with open(os.path.join(here, "qmcpy_integrals.json"), "w") as f:
    json.dump(out, f, indent=1)
    f.write("\n")
