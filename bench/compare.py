#!/usr/bin/env python3
"""Side-by-side throughput of samplab and its peers (scipy.stats.qmc, Mitsuba 3), one core.

Runs both in this one invocation on the same machine and prints medians and ratios.
Usage: bench/compare [--quick] [SECTION...]
  installs the peers (bench/requirements.txt: scipy, Mitsuba 3) into bench/.venv, builds
  samplab, and runs the sections named (all by default): samplers, discrepancy, spectrum,
  render. `bench/compare python` runs bench/python.py instead: the Python package against
  the Rust core, scipy.stats.qmc and QMCPy. --quick: PoissonDisk at n = 10^4 instead of 10^5 (minutes less).
"""
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.stats import qmc

from timing import median_time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "throughput")
DISCREPANCY = os.path.join(ROOT, "target", "release", "examples", "discrepancy_timing")
SAMPLAB = os.path.join(ROOT, "target", "release", "samplab")
QUICK = "--quick" in sys.argv
SECTIONS = [a for a in sys.argv[1:] if not a.startswith("--")]


def want(section):
    return not SECTIONS or section in SECTIONS


def samplab(spec, n):
    out = subprocess.run([EXAMPLE, "%s:%d" % (spec, n)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
    return json.loads(out.strip().splitlines()[-1])["seconds"]


def packing_radius(n):
    return math.sqrt(2.0 / (math.sqrt(3.0) * n))


rows = []


def compare(what, n, peer_name, peer_fn, spec, peer_runs=5):
    peer = median_time(peer_fn, min_runs=peer_runs, min_seconds=0.0 if peer_runs == 1 else 1.0)
    ours = samplab(spec, n)
    rows.append((what, n, peer_name, peer, spec, ours))
    print("%-34s n=%-8d %-40s %9.4f s %8.2f M/s | samplab %-28s %9.4f s %8.2f M/s | ratio %7.1fx"
          % (what, n, peer_name, peer, n / peer / 1e6, spec, ours, n / ours / 1e6, peer / ours), flush=True)


if want("samplers"):
    N = 1 << 20  # a power of two: scipy warns otherwise
    rng = np.random.default_rng(1)
    compare("Sobol, cheap scramble (LMS+shift)", N, "scipy Sobol(scramble=True)",
            lambda: qmc.Sobol(d=2, scramble=True, seed=rng).random(N), "sobol.xor")
    compare("Sobol, Owen vs scipy's cheap scramble", N, "scipy Sobol(scramble=True)",
            lambda: qmc.Sobol(d=2, scramble=True, seed=rng).random(N), "sobol.owen")
    compare("Halton, scrambled", N, "scipy Halton(scramble=True)",
            lambda: qmc.Halton(d=2, scramble=True, seed=rng).random(N), "halton.xor")
    compare("Latin hypercube / N-rooks", N, "scipy LatinHypercube",
            lambda: qmc.LatinHypercube(d=2, seed=rng).random(N), "nrooks")
    n_poisson = 10_000 if QUICK else 100_000
    radius = 0.72 * packing_radius(n_poisson)
    got = {}


    def scipy_poisson():
        got["n"] = len(qmc.PoissonDisk(d=2, radius=radius, seed=rng).random(n_poisson))


    compare("Poisson disk, same radius %.5f" % radius, n_poisson, "scipy PoissonDisk.random",
            scipy_poisson, "poisson.fast:radius=%r,edge=plain" % radius, peer_runs=1)
    print("(scipy PoissonDisk returned %d points; samplab returns exactly n)" % got["n"])
    for spec in ["poisson.fast", "poisson"]:
        t = samplab(spec, 1_000_000)
        print("samplab %s, n = 10^6 (auto radius): %.3f s" % (spec, t))


if want("discrepancy"):
    # discrepancies: scipy on the same points (samplab's random set, read back from its CLI)
    print()


    def samplab_disc(metric, n, d=2, sampler="random", threads=1):
        out = subprocess.run([DISCREPANCY, "%s:%d:%d:%s" % (metric, n, d, sampler)], check=True, capture_output=True, text=True,
                             env=dict(os.environ, RAYON_NUM_THREADS=str(threads))).stdout
        row = json.loads(out.strip().splitlines()[-1])
        return row["seconds"], row["value"]


    def points(n, d=2):
        out = subprocess.run([SAMPLAB, "generate", "random", "-n", str(n), "-d", str(d), "--seed", "1", "--format", "json"],
                             check=True, capture_output=True, text=True).stdout
        return np.array(json.loads(out)["sets"][0])


    for metric, method, squared, n in [("l2-star", "L2-star", False, 1 << 14), ("centered", "CD", True, 1 << 14), ("wraparound", "WD", True, 1 << 14)]:
        x = points(n)
        box = {}

        def run():
            box["v"] = qmc.discrepancy(x, method=method, workers=1)

        peer = median_time(run, min_runs=3, min_seconds=1.0)
        # the value on identical points (set 0 of seed 1) through the CLI; the timing from the example's own set
        out = subprocess.run([SAMPLAB, "discrepancy", metric, "--sampler", "random", "-n", str(n), "--seed", "1", "--json"],
                             check=True, capture_output=True, text=True).stdout
        ours_value = json.loads(out)["metrics"][0]["values"][0]
        ours_time, _ = samplab_disc(metric, n)
        theirs = math.sqrt(box["v"]) if squared else box["v"]
        print("%-10s n=%-6d scipy %9.4f s | samplab %9.5f s | ratio %8.1fx | values %.12g vs %.12g (rel. diff %.1e)"
              % (metric, n, peer, ours_time, peer / ours_time, theirs, ours_value, abs(theirs - ours_value) / theirs), flush=True)
    for metric, n, d in [("star", 1000, 2), ("star", 100000, 2), ("star", 1000000, 2), ("l2-star", 1000000, 2)]:
        t, v = samplab_disc(metric, n, d)
        print("samplab %-8s n=%-8d d=%d: %.3f s (value %.6g)" % (metric, n, d, t, v), flush=True)
    # exact 2D extreme discrepancy (branch and bound): the time depends on the set; nets and
    # lattices, whose boxes all come near the maximum, are the slowest
    for n, sampler in [(10000, "random"), (10000, "jitter"), (10000, "sobol.owen"), (10000, "halton"), (4096, "hammersley")]:
        t1, v = samplab_disc("extreme", n, 2, sampler)
        t2, _ = samplab_disc("extreme", n, 2, sampler, threads=2)
        print("samplab extreme  n=%-8d d=2 %-10s: %.3f s on one thread, %.3f s on two (value %.6g)" % (n, sampler, t1, t2, v), flush=True)
    # exact d-D star discrepancy (Dobkin-Eppstein-Mitchell): low-discrepancy sets prune less than random ones
    for n, d in [(2000, 3), (400, 5), (1000, 5)]:
        for sampler in ["random", "sobol", "halton"]:
            t1, v = samplab_disc("star", n, d, sampler)
            t2, _ = samplab_disc("star", n, d, sampler, threads=2)
            print("samplab star     n=%-8d d=%d %-7s: %.3f s on one thread, %.3f s on two (value %.6g)" % (n, d, sampler, t1, t2, v), flush=True)

if want("spectrum"):
    # spectra: direct DFT against the non-uniform FFT at tolerance 1e-9 (one core)
    print()
    out = subprocess.run([os.path.join(ROOT, "target", "release", "examples", "spectrum_timing")], check=True, capture_output=True, text=True,
                         env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
    for line in out.strip().splitlines():
        r = json.loads(line)
        print("spectrum n=%-6d sets=%-3d R=%-4d direct %8.3f s | fast %7.3f s | ratio %6.1fx | max periodogram error %.1e"
              % (r["n"], r["sets"], r["res"], r["direct_seconds"], r["fast_seconds"], r["ratio"], r["max_periodogram_error"]), flush=True)
    # against FINUFFT (pip finufft, one thread, eps 1e-9): the same work per set, a 2D type-1
    # transform of n random points to R x R frequencies and the periodogram's and mean's
    # running sums, plan made once per grid cell; medians of 3
    import finufft

    def finufft_statistics(n, m, res):
        rng = np.random.default_rng(1)
        sets = [rng.random((n, 2)) for _ in range(m)]
        ones = np.ones(n, dtype=np.complex128)

        def run():
            plan = finufft.Plan(1, (res, res), 1, eps=1e-9, isign=-1, nthreads=1)
            power, mean = np.zeros((res, res)), np.zeros((res, res), complex)
            for p in sets:
                plan.setpts(2 * np.pi * p[:, 0], 2 * np.pi * p[:, 1])
                f = plan.execute(ones) / n
                power += f.real ** 2 + f.imag ** 2
                mean += f
        return median_time(run, min_runs=3, min_seconds=0.0)

    cells = [(n, 2, res) for n in (256, 4096, 65536, 1_000_000) for res in (128, 512, 2048)] + [(100_000, 2, 256), (4096, 20, 512)]
    out = subprocess.run([os.path.join(ROOT, "target", "release", "examples", "spectrum_timing")] + ["%d:%d:%d" % c for c in cells],
                         check=True, capture_output=True, text=True, env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
    for line in out.strip().splitlines():
        r = json.loads(line)
        theirs = finufft_statistics(r["n"], r["sets"], r["res"])
        print("spectrum n=%-7d sets=%-3d R=%-4d FINUFFT %8.4f s | samplab %8.4f s | ratio %5.2fx"
              % (r["n"], r["sets"], r["res"], theirs, r["fast_seconds"], theirs / r["fast_seconds"]), flush=True)
    # FINUFFT's own error against the direct DFT on a small cell (samplab's is printed above)
    x = np.random.default_rng(2).random((4096, 2))
    k = np.arange(-64, 64)
    ex, ey = np.exp(-2j * np.pi * np.outer(k, x[:, 0])), np.exp(-2j * np.pi * np.outer(k, x[:, 1]))
    direct = (ex @ ey.T) / len(x)
    fast = finufft.nufft2d1(2 * np.pi * x[:, 0], 2 * np.pi * x[:, 1], np.ones(len(x), complex), (128, 128), eps=1e-9, isign=-1, nthreads=1) / len(x)
    print("FINUFFT eps 1e-9, n=4096, R=128: max |S| error against the direct DFT %.1e (relative to DC)" % np.abs(fast - direct).max(), flush=True)


if want("render"):
    # renderer: samples per CPU-second, one thread, 256x256, pixel area, one camera ray and one
    # shadow ray per sample (direct lighting, one light sample per estimate, the pixel's 64 light
    # samples one Owen-scrambled Sobol' pattern): the same Mitsuba 3 scene file rendered by
    # samplab and by Mitsuba 3 (llvm_ad_rgb, `direct` integrator with one emitter sample and no
    # BSDF sample, box filter, one Dr.Jit thread); then the built-in scenes, among them the
    # 1-million-triangle mesh.
    SCENE_XML = os.path.join(ROOT, "crates", "samplab-render", "tests", "scenes", "sphere-box.xml")


    def samplab_render(scene, spp):
        times = []
        for _ in range(3):
            out = subprocess.run([SAMPLAB, "render", scene, "--sampler", "sobol.owen", "-n", "1", "--spp", str(spp), "--pixel", "area",
                                  "--pattern", "pixel", "--mode", "direct", "--res", "256x256",
                                  "-o", os.path.join(tempfile.gettempdir(), "samplab-bench.exr"), "--json"],
                                 check=True, capture_output=True, text=True, env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
            times.append(json.loads(out)["seconds"])
        return statistics.median(times)


    def mitsuba_render(spp, variant):
        import drjit as dr
        import mitsuba as mi
        mi.set_variant(variant)
        dr.set_thread_count(1)
        scene = mi.load_file(SCENE_XML, res=256, height=256)
        integrator = mi.load_dict({"type": "direct", "emitter_samples": 1, "bsdf_samples": 0})
        times = []
        for run in range(4):  # the first run compiles the kernels: dropped
            start = time.process_time()
            image = mi.render(scene, integrator=integrator, spp=spp, seed=run)
            dr.eval(image)
            dr.sync_thread()
            times.append(time.process_time() - start)
        return statistics.median(times[1:])


    print()
    spp = 64
    samples = 256 * 256 * spp
    ours = samples / samplab_render(SCENE_XML, spp)
    # Mitsuba's vectorized LLVM variant (the target), and its scalar one: how much of the gap is SIMD
    for variant in ["llvm_ad_rgb", "scalar_rgb"]:
        theirs = samples / mitsuba_render(spp, variant)
        print("render sphere-box.xml 256x256 x %d spp, one thread: samplab %.2f M samples per CPU-second | Mitsuba 3 %s %.2f M | ratio %.2fx"
              % (spp, ours / 1e6, variant, theirs / 1e6, ours / theirs), flush=True)
    for scene, spp in [("sphere-box", 64), ("sphere-box-mesh", 16)]:
        t = samplab_render(scene, spp)
        print("render %-16s 256x256 x %-3d spp, one thread: %.3f s (median of 3) = %.2f M samples per CPU-second"
              % (scene, spp, t, 256 * 256 * spp / t / 1e6), flush=True)
