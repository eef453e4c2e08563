#!/usr/bin/env python3
"""The QMC constructions against QMCPy and scipy.stats.qmc: each at 2^20 points (p^2 =
251^2 for the orthogonal-array LHS: scipy's took 10 s there in 8D, and more than 5 minutes
and 16 GB at 509^2) in 2, 8 and 32 dimensions, one thread, in one process
on the same arrays, medians of repeated runs; and the fast CBC construction of a generating
vector for n = 2^16, s = 32. Run by `bench/compare qmc` (which installs the package and the
peers into bench/.venv). Ratios > 1: samplab is faster. QMCPy's Owen (NUS) scramblings take
about a minute per 2^20 x 2 points, so those rows use 2^16 points, for both sides; a peer
run longer than 10 s is timed once.
"""
import os
import sys

os.environ.setdefault("RAYON_NUM_THREADS", "1")

import qmcpy  # noqa: E402
from scipy.stats import qmc  # noqa: E402

import samplab  # noqa: E402
from timing import median_time  # noqa: E402

N = 1 << 20
SLOW = 1 << 16  # the count of the rows whose peer is QMCPy's NUS


def ours(spec, n, d):
    return median_time(lambda: samplab.generate(spec, n=n, d=d, seed=1), 5)


CASES = [
    # (construction, samplab spec, [(peer name, peer call(n, d)[, most dimensions])])
    ("Sobol' matrices, LMS + digital shift", "net.lms", [
        ("qmcpy DigitalNetB2 (LMS DS)", lambda n, d: qmcpy.DigitalNetB2(d, seed=7).gen_samples(n)),
        ("scipy Sobol (LMS + shift)", lambda n, d: qmc.Sobol(d, seed=7).random(n)),
    ]),
    ("Sobol' matrices, Owen [2^16]", "net.owen", [
        ("qmcpy DigitalNetB2 (NUS)", lambda n, d: qmcpy.DigitalNetB2(d, seed=7, randomize="NUS").gen_samples(n)),
    ]),
    ("Faure, unrandomized", "faure", [
        ("qmcpy Faure (False)", lambda n, d: qmcpy.Faure(d, randomize="FALSE").gen_samples(n, warn=False)),
    ]),
    ("Faure, LMS + digital shift", "faure.lms", [
        ("qmcpy Faure (LMS DS)", lambda n, d: qmcpy.Faure(d, seed=7, randomize="LMS DS").gen_samples(n, warn=False)),
    ]),
    ("Halton, random digit permutations", "halton.xor", [
        ("scipy Halton (permutations)", lambda n, d: qmc.Halton(d, seed=7).random(n)),
        # at 2^20 x 32 QMCPy's Halton was killed for memory on a 24 GB machine
        ("qmcpy Halton (PERM)", lambda n, d: qmcpy.Halton(d, seed=7, randomize="PERM").gen_samples(n, warn=False), 8),
    ]),
    ("Halton, Owen [2^16]", "halton.owen", [
        # 77 s at 2^16 x 8; about five minutes at 32D
        ("qmcpy Halton (NUS)", lambda n, d: qmcpy.Halton(d, seed=7, randomize="NUS").gen_samples(n, warn=False), 8),
    ]),
    ("lattice sequence, random shift", "lattice.shift", [
        ("qmcpy Lattice (SHIFT)", lambda n, d: qmcpy.Lattice(d, seed=7).gen_samples(n)),
    ]),
    ("Kronecker, random shift", "kronecker.shift", [
        ("qmcpy Kronecker", lambda n, d: qmcpy.Kronecker(d, seed=7).gen_samples(n)),
    ]),
    ("Niederreiter, Owen", "niederreiter.owen", []),
    ("Latin hypercube, centered", "lhs.centered", [
        ("scipy LatinHypercube(scramble=False)", lambda n, d: qmc.LatinHypercube(d, scramble=False, seed=7).random(n)),
    ]),
    ("Latin hypercube, OA [251^2]", "lhs.oa", [
        ("scipy LatinHypercube(strength=2)", lambda n, d: qmc.LatinHypercube(d, strength=2, seed=7).random(n)),
    ]),
]

ONLY = sys.argv[1:]  # construction names containing one of these words (all by default)
print("construction                            d   samplab s  | peer                                   peer s      ratio")
for what, spec, peers in CASES:
    if ONLY and not any(w in what for w in ONLY):
        continue
    for d in (2, 8, 32):
        n = 251 ** 2 if spec == "lhs.oa" else SLOW if "[2^16]" in what else N
        try:
            t = ours(spec, n, d)
        except samplab.Error as e:
            print("%-38s %3d  %s" % (what, d, e), flush=True)
            continue
        if not peers:
            print("%-38s %3d %10.4f  | (no peer has it)" % (what, d, t), flush=True)
        for name, call, *most in peers:
            if most and d > most[0]:
                print("%-38s %3d %10.4f  | %-38s skipped above %dD" % (what, d, t, name, most[0]), flush=True)
                continue
            try:
                first = median_time(lambda: call(n, d), 1)
                p = first if first > 10 else median_time(lambda: call(n, d), 3)
            except Exception as e:  # a peer that cannot: say so and go on
                print("%-38s %3d %10.4f  | %-38s %s" % (what, d, t, name, str(e).splitlines()[0][:40]), flush=True)
                continue
            print("%-38s %3d %10.4f  | %-38s %9.4f %8.1fx" % (what, d, t, name, p, p / t), flush=True)

t = median_time(lambda: samplab.generate("lattice.cbc", n=1 << 16, d=32, seed=1), 1)
print("fast CBC construction, n = 2^16, s = 32 (first call, construction and points): %.3f s" % t)
