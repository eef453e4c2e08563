#!/usr/bin/env python3
"""Write the Joe-Kuo (2008) Sobol' direction numbers, new-joe-kuo-6.21201, first 1024
dimensions, in the authors' own text format (d s a m_1 .. m_s), from the copy that
scipy ships (scipy/stats/_sobol_direction_numbers.npz stores the primitive polynomials
with their leading and trailing terms, and the initial m_i).

Usage: python3 scripts/export_joe_kuo.py > crates/samplab/data/new-joe-kuo-6.1024.txt
The build script (crates/samplab/build.rs) turns this file into 32-bit direction numbers.
"""
import os
import sys

import numpy as np
import scipy.stats

DIMS = 1024

path = os.path.join(os.path.dirname(scipy.stats.__file__), "_sobol_direction_numbers.npz")
data = np.load(path)
poly, vinit = data["poly"], data["vinit"]
out = sys.stdout
out.write("# Joe & Kuo (2008) new-joe-kuo-6.21201, dimensions 2..%d; exported from scipy %s\n" % (DIMS, scipy.__version__))
out.write("d s a m_i\n")
for j in range(1, DIMS):
    p = int(poly[j])
    s = p.bit_length() - 1
    a = (p >> 1) & ((1 << (s - 1)) - 1)
    m = [int(v) for v in vinit[j][:s]]
    assert all(v % 2 == 1 and v < (1 << (i + 1)) for i, v in enumerate(m)), (j, m)
    out.write("%d %d %d %s\n" % (j + 1, s, a, " ".join(map(str, m))))
