#!/usr/bin/env python3
"""The blue-noise samplers against UTK's, one thread each (RAYON_NUM_THREADS and
OMP_NUM_THREADS = 1), both through their command lines writing a text file, same n and the
same iteration counts; medians of 3 runs (one when a run takes over 10 s). Beside each time,
the quality of the set made, measured by samplab on both files: the relative radius, or for
the spectral targets (step, single-peak) the effective Nyquist frequency and oscillation.

Run by `bench/compare blue [--utk DIR] [--limit SECONDS] [WORDS]`, DIR holding UTK's executables (built from
its public source; UTK is on no package registry), WORDS picking rows by family. Without
--utk only samplab's rows are printed.
"""
import os
import subprocess
import sys
import tempfile

from timing import median_time

os.environ["RAYON_NUM_THREADS"] = "1"
os.environ["OMP_NUM_THREADS"] = "1"
SAMPLAB = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "target", "release", "samplab"))
ARGS = sys.argv[1:]
UTK = os.path.abspath(ARGS[ARGS.index("--utk") + 1]) if "--utk" in ARGS else None
# rows whose family contains one of the remaining words (all by default)
ONLY = [w for k, w in enumerate(ARGS) if w not in ("blue", "--utk", "--limit") and (k == 0 or ARGS[k - 1] not in ("--utk", "--limit"))]

RHO = ["relative-radius"]
SPECTRAL = ["nyquist", "oscillation"]
# (family, samplab spec, UTK executable and its arguments besides -n, -d, -s, -o, metrics)
CASES = [
    # UTK's Lloyd executable makes 3D points only (its add_arguments(app, 3)): no 2D peer
    ("Lloyd, 50 steps, torus", "lloyd:iterations=50", None, RHO),
    ("sliced OT, 200 x 32 directions", "sot:iterations=200,directions=32", ["SOT", "-i", "200", "-p", "32"], RHO),
    ("dart throwing", "poisson", ["DartThrowing"], RHO),
    ("Bridson", "poisson.fast", ["Bridson"], RHO),
    ("sample elimination", "elimination", None, RHO),
    ("Gaussian blue noise, 100 steps", "gbn", None, RHO),
    ("CCVT, capacity 64", "ccvt", None, RHO),
    # UTK wraps Fattal's own code, which needs its image and multigrid libraries: not built here
    ("kernel density model, 100 steps", "kdm", None, RHO + SPECTRAL),
    # UTK's Step: the same target (its critical frequency 0.606 / d_hex is nu = 0.564 sqrt(n)),
    # its own annealed descent (iterations until its temperature falls from 1 to 1e-3)
    ("step blue noise", "step", ["Step"], SPECTRAL),
    # UTK's SinglePeak at its defaults (a peak at 36.5 cycles whatever n): not samplab's target
    ("single-peak blue noise", "single-peak", ["SinglePeak"], SPECTRAL),
]


# a UTK run longer than this (--limit SECONDS) is stopped and reported as such
LIMIT = float(ARGS[ARGS.index("--limit") + 1]) if "--limit" in ARGS else 600


def run(cmd, limit=None):
    # in the scratch folder: UTK's Step and SinglePeak write force.dat where they run
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=limit, cwd=tmp)


def timed(cmd, limit=None):
    first = median_time(lambda: run(cmd, limit), 1)
    return first if first > 10 else median_time(lambda: run(cmd, limit), 3)


def quality(path, metrics):
    """Each metric's value on the file, as 'value' (one metric) or 'name value ...'."""
    out = subprocess.run([SAMPLAB, "discrepancy", *metrics, path], check=True, capture_output=True, text=True)
    rows = out.stdout.strip().splitlines()[-len(metrics):]
    values = ["%.3f" % float(row.split()[-1]) for row in rows]
    return values[0] if len(metrics) == 1 else " ".join("%s %s" % (m[:3], v) for m, v in zip(metrics, values))


def utk_points(path, out):
    """UTK's .dat (one point per line, '#' between sets) as a plain text file samplab reads."""
    with open(path) as f, open(out, "w") as g:
        g.writelines(line for line in f if line.strip() and not line.startswith("#"))


tmp = tempfile.mkdtemp()
print("family                              n     samplab s   quality  | UTK s        quality     ratio")
for family, spec, utk, metrics in CASES:
    if ONLY and not any(w in family for w in ONLY):
        continue
    for n in (1024, 4096, 16384):
        ours = os.path.join(tmp, "ours.txt")
        t = timed([SAMPLAB, "generate", spec, "-n", str(n), "--seed", "1", "-o", ours])
        line = "%-34s %6d %9.3f  %s  |" % (family, n, t, quality(ours, metrics))
        if UTK is None or utk is None:
            print(line, "(no UTK build given)" if utk else "(UTK has none)", flush=True)
            continue
        dat, txt = os.path.join(tmp, "utk.dat"), os.path.join(tmp, "utk.txt")
        cmd = [os.path.join(UTK, utk[0]), "-n", str(n), "-d", "2", "-s", "1", "-o", dat, "--silent"] + utk[1:]
        try:
            u = timed(cmd, LIMIT)
        except subprocess.CalledProcessError as e:
            print(line, "UTK failed: exit %d" % e.returncode, flush=True)
            continue
        except subprocess.TimeoutExpired:
            print(line, "UTK > %g s (stopped)" % LIMIT, flush=True)
            continue
        utk_points(dat, txt)
        print(line, "%9.3f  %s  %7.1fx" % (u, quality(txt, metrics), u / t), flush=True)
