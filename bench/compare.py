#!/usr/bin/env python3
"""Side-by-side throughput of samplab and its peers (scipy.stats.qmc, Mitsuba 3), one core.

Runs both in this one invocation on the same machine and prints medians and ratios.
Usage: bench/compare [--quick] [SECTION...]
  installs the peers (bench/requirements.txt: scipy, Mitsuba 3) into bench/.venv, builds
  samplab, and runs the sections named (all by default): samplers, discrepancy, spectrum,
  render. `bench/compare python` runs bench/python.py instead: the Python package against
  the Rust core, scipy.stats.qmc and QMCPy. --quick: PoissonDisk at n = 10^4 instead of 10^5 (minutes less).
  `bench/compare goals` (only when named) prints the speed issue's goal table: each row timed
  here and by its criterion benchmark in the same run, beside its anchor (about 25 minutes).
  `bench/compare x86` (only when named) prints the x86 issue's table: spectra against FINUFFT
  on one and two threads, in-process and through the CLI, and dart throwing at 10^6 (about
  two minutes). Every run prints the machine first: processor, cores, vector width.
"""
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.stats import qmc

from timing import machine, median_time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "target", "release", "examples", "throughput")
DISCREPANCY = os.path.join(ROOT, "target", "release", "examples", "discrepancy_timing")
SAMPLAB = os.path.join(ROOT, "target", "release", "samplab")
QUICK = "--quick" in sys.argv
SECTIONS = [a for a in sys.argv[1:] if not a.startswith("--")]


print(machine(), flush=True)


def want(section):
    return not SECTIONS or section in SECTIONS


def samplab(spec, n):
    out = subprocess.run([EXAMPLE, "%s:%d" % (spec, n)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, RAYON_NUM_THREADS="1")).stdout
    return json.loads(out.strip().splitlines()[-1])["seconds"]


def packing_radius(n):
    return math.sqrt(2.0 / (math.sqrt(3.0) * n))


def samplab_disc(metric, n, d=2, sampler="random", threads=1):
    """(median seconds, value) of a metric on the example's set (seed 1)."""
    out = subprocess.run([DISCREPANCY, "%s:%d:%d:%s" % (metric, n, d, sampler)], check=True, capture_output=True, text=True,
                         env=dict(os.environ, RAYON_NUM_THREADS=str(threads))).stdout
    row = json.loads(out.strip().splitlines()[-1])
    return row["seconds"], row["value"]


def l2_extended(metric, x):
    """The L2 discrepancy of the 2D set x by its closed form summed pair by pair in numpy's
    extended precision (x86 long double, 64-bit mantissa): a reference for both libraries'
    double-precision values (Warnock's formula; Hickernell 1998, eq. 5.1c and 5.1d)."""
    X = x.astype(np.longdouble)
    n, half = len(X), np.longdouble(0.5)
    if metric == "l2-star":
        base, f, g = np.longdouble(1) / 9, lambda u: (1 - u * u) / 2, lambda u, v: 1 - np.maximum(u, v)
    elif metric == "centered":
        base = (np.longdouble(13) / 12) ** 2
        f = lambda u: 1 + half * abs(u - half) - half * (u - half) ** 2
        g = lambda u, v: 1 + half * abs(u - half) + half * abs(v - half) - half * abs(u - v)
    else:
        base, f = -(np.longdouble(4) / 3) ** 2, lambda u: 0 * u
        g = lambda u, v: np.longdouble(1.5) - abs(u - v) * (1 - abs(u - v))
    pairs = np.longdouble(0)
    for start in range(0, n, 256):
        a = X[start:start + 256]
        pairs += np.sum(g(a[:, None, 0], X[None, :, 0]) * g(a[:, None, 1], X[None, :, 1]), dtype=np.longdouble)
    return float(np.sqrt(base - 2 * np.sum(f(X[:, 0]) * f(X[:, 1]), dtype=np.longdouble) / n + pairs / (n * n)))


def l2_against_scipy(metric, n):
    """scipy's qmc.discrepancy and samplab on the same random 2D set (set 0 of seed 1, read
    back from the CLI), one core: (scipy seconds, samplab seconds, scipy value, samplab value,
    extended-precision value), the values as samplab reports them (scipy gives CD and WD
    squared)."""
    method, squared = {"l2-star": ("L2-star", False), "centered": ("CD", True), "wraparound": ("WD", True)}[metric]
    out = subprocess.run([SAMPLAB, "generate", "random", "-n", str(n), "-d", "2", "--seed", "1", "--format", "json"],
                         check=True, capture_output=True, text=True).stdout
    x = np.array(json.loads(out)["sets"][0])
    box = {}

    def run():
        box["v"] = qmc.discrepancy(x, method=method, workers=1)

    peer = median_time(run, min_runs=3, min_seconds=1.0)
    # the value on identical points through the CLI; the timing from the example's own set
    out = subprocess.run([SAMPLAB, "discrepancy", metric, "--sampler", "random", "-n", str(n), "--seed", "1", "--json"],
                         check=True, capture_output=True, text=True).stdout
    ours_value = json.loads(out)["metrics"][0]["values"][0]
    ours_time, _ = samplab_disc(metric, n)
    return peer, ours_time, math.sqrt(box["v"]) if squared else box["v"], ours_value, l2_extended(metric, x)


# spectrum cells (n, sets, R): the grid n = 256..10^6 x R = 128..2048, then two more
SPECTRUM_CELLS = [(n, 2, res) for n in (256, 4096, 65536, 1_000_000) for res in (128, 512, 2048)] + [(100_000, 2, 256), (4096, 20, 512)]


def spectrum_against_finufft(cells, threads=1):
    """[(n, sets, R, FINUFFT seconds, samplab seconds)], `threads` threads each. FINUFFT (pip,
    eps 1e-9) does the same work per set: a 2D type-1 transform of n random points to R x R
    frequencies and the periodogram's and mean's running sums, plan made once per cell;
    medians of 3."""
    import finufft

    def finufft_statistics(n, m, res):
        rng = np.random.default_rng(1)
        sets = [rng.random((n, 2)) for _ in range(m)]
        ones = np.ones(n, dtype=np.complex128)

        def run():
            plan = finufft.Plan(1, (res, res), 1, eps=1e-9, isign=-1, nthreads=threads)
            power, mean = np.zeros((res, res)), np.zeros((res, res), complex)
            for p in sets:
                plan.setpts(2 * np.pi * p[:, 0], 2 * np.pi * p[:, 1])
                f = plan.execute(ones) / n
                power += f.real ** 2 + f.imag ** 2
                mean += f
        return median_time(run, min_runs=3, min_seconds=0.0)

    out = subprocess.run([os.path.join(ROOT, "target", "release", "examples", "spectrum_timing")] + ["%d:%d:%d" % c for c in cells],
                         check=True, capture_output=True, text=True, env=dict(os.environ, RAYON_NUM_THREADS=str(threads))).stdout
    rows = []
    for line in out.strip().splitlines():
        r = json.loads(line)
        rows.append((r["n"], r["sets"], r["res"], finufft_statistics(r["n"], r["sets"], r["res"]), r["fast_seconds"]))
    return rows


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
    for metric, n in [("l2-star", 1 << 14), ("centered", 1 << 14), ("wraparound", 1 << 14)]:
        peer, ours_time, theirs, ours_value, exact = l2_against_scipy(metric, n)
        print("%-10s n=%-6d scipy %9.4f s | samplab %9.5f s | ratio %8.1fx | relative error against extended precision: scipy %.1e, samplab %.1e"
              % (metric, n, peer, ours_time, peer / ours_time, abs(theirs / exact - 1), abs(ours_value / exact - 1)), flush=True)
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
    for n, m, res, theirs, ours in spectrum_against_finufft(SPECTRUM_CELLS):
        print("spectrum n=%-7d sets=%-3d R=%-4d FINUFFT %8.4f s | samplab %8.4f s | ratio %5.2fx"
              % (n, m, res, theirs, ours, theirs / ours), flush=True)
    import finufft
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


def criterion(bench, pattern):
    """Run a criterion benchmark of the samplab crate (its filter `pattern`, all threads) and
    return {benchmark id: median seconds} read from criterion's estimates."""
    print("(criterion: cargo bench --bench %s -- '%s')" % (bench, pattern), flush=True)
    start = time.time()
    subprocess.run(["cargo", "bench", "--quiet", "-p", "samplab", "--bench", bench, "--", pattern], check=True, cwd=ROOT,
                   stdout=subprocess.DEVNULL)
    found = {}
    base = os.path.join(ROOT, "target", "criterion")
    for path, _, files in os.walk(base):
        fresh = "estimates.json" in files and os.path.getmtime(os.path.join(path, "estimates.json")) >= start
        if fresh and os.path.basename(path) == "new":
            with open(os.path.join(path, "estimates.json")) as f:
                found[os.path.relpath(os.path.dirname(path), base)] = json.load(f)["median"]["point_estimate"] / 1e9
    return found


if "x86" in SECTIONS:
    # the x86 issue's acceptance (issue 98) on the machine the header names, in one run
    # (about two minutes): spectra against FINUFFT in-process (one and two threads) and
    # through the CLI net of its start, dart throwing at 10^6 on two threads
    def cli_seconds(args, threads=2, runs=5):
        env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
        return median_time(lambda: subprocess.run([SAMPLAB] + args, check=True, capture_output=True, env=env),
                           min_runs=runs)

    start = cli_seconds(["--version"], runs=9)
    print("\n| work | peer | samplab | ratio (peer / samplab) |\n|---|---|---|---|")
    for threads in [1, 2]:
        for n, m, res, theirs, ours in spectrum_against_finufft([(100_000, 2, 256), (1_000_000, 2, 1024)], threads):
            print("| spectrum statistics, %d sets of %d points, %d^2, %d thread%s, in-process | FINUFFT %.4f s | %.4f s | %.2fx |"
                  % (m, n, res, threads, "" if threads == 1 else "s", theirs, ours, theirs / ours), flush=True)
    out = tempfile.mkdtemp()
    for threads in [1, 2]:
        cli = cli_seconds(["spectrum", "--sampler", "random", "-n", "100000", "--sets", "2", "--res", "256",
                           "--seed", "1", "-o", os.path.join(out, "spectrum"), "--force"], threads) - start
        theirs = spectrum_against_finufft([(100_000, 2, 256)], threads)[0][3]
        print("| `samplab spectrum --sampler random -n 100000 --sets 2 --res 256`, %d thread%s, net of the CLI's start (%.3f s; the CLI also writes 3 CSV files and 3 PNG images) | FINUFFT %.4f s | %.4f s | %.2fx |"
              % (threads, "" if threads == 1 else "s", start, theirs, cli, theirs / cli), flush=True)
    dart = cli_seconds(["generate", "poisson", "-n", "1000000", "-o", os.path.join(out, "poisson.npy")])
    print("| `samplab generate poisson -n 1000000`, two threads (the goal: under 1 s) | | %.3f s (%.3f s net of the start) | |"
          % (dart, dart - start), flush=True)
    shutil.rmtree(out)

if "goals" in SECTIONS:
    # the speed issue's goal table in one run: each operation timed by this script (one thread
    # unless said) and by its criterion benchmark (all threads; medians of 10 samples), beside
    # the anchor measured now where there is one
    print("\nspeed goals, %s, %d cores" % (time.strftime("%Y-%m-%d"), os.cpu_count()))
    table = []

    def row(operation, anchor, ours, crit, goal, met):
        table.append((operation, anchor, ours, crit, goal, "yes" if met else "NO"))
        print("| %s | %s | %s | %s | %s | %s |" % table[-1], flush=True)

    crit = {}
    crit.update(criterion("spectrum", "spectrum/"))
    crit.update(criterion("discrepancy", "^(extreme-2d/.*/(10000|4096)|l2-star-2d/random-2D/(16384|1000000)|centered/.*|wraparound/.*|star-dd/.*-5D/1000)$"))
    crit.update(criterion("samplers", "^(poisson/1000000|poisson.maximal/10000)$"))
    print("| operation | anchor | samplab (bench/compare) | samplab (criterion) | goal | met |")
    print("|---|---|---|---|---|---|")
    cells = spectrum_against_finufft(SPECTRUM_CELLS)
    for n, m, res, theirs, ours in cells[-2:]:
        row("spectrum statistics, %d sets of %d points, %d^2" % (m, n, res), "FINUFFT %.4f s" % theirs,
            "%.4f s (%.2fx FINUFFT)" % (ours, theirs / ours), "%.4f s" % crit["spectrum/%dx%d/%d" % (m, n, res)],
            "at least FINUFFT's speed", theirs >= ours)
    worst = min(cells[:-2], key=lambda c: c[3] / c[4])
    row("spectrum statistics, grid n = 256..10^6 x R = 128..2048 (2 sets)", "FINUFFT",
        "least ratio %.2fx (n = %d, R = %d); ratios %s" % (worst[3] / worst[4], worst[0], worst[2],
                                                          " ".join("%.2f" % (c[3] / c[4]) for c in cells[:-2])),
        "%.4f s at 2 x 65536 x 128^2" % crit["spectrum/2x65536/128"], "at least FINUFFT's speed at every cell",
        worst[3] >= worst[4])
    for sampler, n in [("random", 10_000), ("sobol.owen", 10_000), ("halton", 10_000), ("hammersley", 4096)]:
        one = samplab_disc("extreme", n, 2, sampler)[0] if n == 10_000 else None
        two = samplab_disc("extreme", n, 2, sampler, threads=2)[0]
        key = "extreme-2d/%s-2D/%d" % (sampler, n)
        row("exact 2D extreme discrepancy, %s, n = %d" % (sampler, n), "none computes it exactly",
            ("%.2f s one thread, " % one if one else "") + "%.2f s two" % two,
            "%.2f s" % crit[key] if key in crit else "-", "n = 10^4 under 10 s", n == 10_000 and two < 10)
    for metric in ["l2-star", "centered", "wraparound"]:
        peer, ours, theirs_value, ours_value, exact = l2_against_scipy(metric, 1 << 14)
        big, _ = samplab_disc(metric, 1_000_000)
        key = "%s/random-2D/16384" % ("l2-star-2d" if metric == "l2-star" else metric)
        row("%s, n = 2^14 and 10^6, 2D" % metric,
            "scipy %.4f s (relative error %.1e; samplab's %.1e, against extended precision)"
            % (peer, abs(theirs_value / exact - 1), abs(ours_value / exact - 1)),
            "%.2f ms (%.0fx scipy); 10^6: %.3f s" % (ours * 1e3, peer / ours, big), "%.2f ms" % (crit[key] * 1e3),
            ">= 100x scipy at 2^14, 10^6 under 1 s", peer / ours >= 100 and big < 1)
    t = samplab("poisson", 1_000_000)
    row("Poisson disk (dart throwing), 10^6 points, auto radius", "UTK Bridson 41.8 s (issue)", "%.3f s" % t,
        "%.3f s" % crit["poisson/1000000"], "under 1 s, exactly n", t < 1)
    for n in [10_000, 100_000]:
        start = time.perf_counter()
        subprocess.run([SAMPLAB, "generate", "poisson.maximal", "-n", str(n), "-o", os.path.join(tempfile.gettempdir(), "maximal.npy")],
                       check=True, capture_output=True)
        key = "poisson.maximal/%d" % n
        row("maximal Poisson disk, exactly n = %d" % n, "-", "%.1f s (CLI, writing included)" % (time.perf_counter() - start),
            "%.1f s" % crit[key] if key in crit else "-", "under 1 s at 10^6", False)
    for sampler in ["random", "sobol.owen", "halton"]:
        one = samplab_disc("star", 1000, 5, sampler)[0]
        two = samplab_disc("star", 1000, 5, sampler, threads=2)[0]
        key = "star-dd/%s-5D/1000" % sampler
        row("exact 5D star discrepancy, %s, n = 1000" % sampler, "-", "%.1f s one thread, %.1f s two" % (one, two),
            "%.1f s" % crit[key] if key in crit else "-", "under 10 s", two < 10)
