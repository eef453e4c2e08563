#!/usr/bin/env python3
"""Error-bounded cubature against QMCPy (issue 41): the time and the function evaluations
to reach abs_tol on Keister at d = 3, 8, 32 with the same numpy integrand (x on [0,1]^d
mapped by the normal quantile), samplab's guaranteed rules (`rule="net"` on net.lms,
`rule="lattice"` on a shifted lattice with the baker's transform) against QMCPy's
CubQMCNetG (DigitalNetB2, LMS + digital shift) and CubQMCLatticeG (Lattice, baker's
transform), both starting at 2^10 points and stopping at the same n_limit. One thread
(RAYON_NUM_THREADS=1), one run each. Run by `bench/compare cubature` (which installs the
package and QMCPy into bench/.venv). Ratios > 1: samplab is faster. "f alone" is the numpy
integrand's own time on the points samplab evaluated, a floor for both sides; "beyond f"
is the ratio of the times each side spends beyond it.

Usage: bench/compare cubature [--tol 1e-4] [--limit 22]
"""
import argparse
import math
import os
import time

os.environ.setdefault("RAYON_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import qmcpy  # noqa: E402
from scipy.special import ndtri  # noqa: E402

import samplab  # noqa: E402


def keister(x):
    """Keister's integrand on [0,1]^d: pi^(d/2) cos |t| with t ~ N(0, I/2)."""
    d = x.shape[1]
    t = ndtri(x) / math.sqrt(2.0)
    return math.pi ** (d / 2) * np.cos(np.sqrt((t * t).sum(axis=1)))


def exact(d):
    return samplab.cubature(f"keister:d={d}", abs_tol=1.0, max_n=256)["exact"]


def qmcpy_run(stopping, sequence, d, tol, limit):
    f = qmcpy.CustomFun(qmcpy.Uniform(sequence(d)), g=keister)
    start = time.perf_counter()
    solution, data = stopping(f, abs_tol=tol, rel_tol=0, n_init=1024, n_limit=limit).integrate()
    return time.perf_counter() - start, float(solution), int(data.n_total)


def ours(rule, d, tol, limit):
    start = time.perf_counter()
    c = samplab.cubature(keister, d, abs_tol=tol, rule=rule, max_n=limit, seed=7)
    return time.perf_counter() - start, c["estimate"], c["evaluations"], c["converged"]


def floor(d, n):
    """The integrand's own time on n points, in the 2^16-point chunks samplab calls it with:
    what neither side can go below."""
    x = np.random.default_rng(1).random((n, d))
    start = time.perf_counter()
    for i in range(0, n, 1 << 16):
        keister(x[i : i + (1 << 16)])
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--tol", type=float, default=1e-4)
    parser.add_argument("--limit", type=int, default=22, help="log2 of the most points")
    args, _ = parser.parse_known_args()
    limit = 1 << args.limit
    peers = {
        "net": (qmcpy.CubQMCNetG, lambda d: qmcpy.DigitalNetB2(d, seed=7)),
        "lattice": (qmcpy.CubQMCLatticeG, lambda d: qmcpy.Lattice(d, seed=7)),
    }
    print(f"Keister to abs_tol {args.tol:g}, at most 2^{args.limit} points, one thread, one run")
    print(f"{'d':>3} {'rule':<8} {'samplab s':>10} {'evals':>9} {'error':>9} {'qmcpy s':>9} {'evals':>9} {'error':>9} {'ratio':>7} {'f alone s':>10} {'beyond f':>9}")
    for d in (3, 8, 32):
        truth = exact(d)
        for rule, (stopping, sequence) in peers.items():
            t_ours, est, n_ours, converged = ours(rule, d, args.tol, limit)
            t_peer, sol, n_peer = qmcpy_run(stopping, sequence, d, args.tol, limit)
            flag = "" if converged else " (limit)"
            alone = floor(d, n_ours)
            # the time each side spends beyond evaluating f, and its ratio
            beyond = (t_peer - alone) / max(t_ours - alone, 1e-3)
            print(
                f"{d:>3} {rule:<8} {t_ours:>10.3f} {n_ours:>9} {abs(est - truth):>9.2e} {t_peer:>9.3f} {n_peer:>9} "
                f"{abs(sol - truth):>9.2e} {t_peer / t_ours:>7.1f} {alone:>10.3f} {beyond:>9.1f}{flag}"
            )


if __name__ == "__main__":
    main()
