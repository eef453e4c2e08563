#!/usr/bin/env python3
"""The blue-noise samplers against UTK's, one thread each (RAYON_NUM_THREADS and
OMP_NUM_THREADS = 1), both through their command lines writing a text file, same n and the
same iteration counts; medians of 3 runs (one when a run takes over 10 s). Beside each time,
the relative radius of the set made (samplab's `relative-radius` metric on both files).

Run by `bench/compare blue [--utk DIR] [WORDS]`, DIR holding UTK's executables (built from
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
SAMPLAB = os.path.join(os.path.dirname(__file__), "..", "target", "release", "samplab")
ARGS = sys.argv[1:]
UTK = ARGS[ARGS.index("--utk") + 1] if "--utk" in ARGS else None
# rows whose family contains one of the remaining words (all by default)
ONLY = [w for k, w in enumerate(ARGS) if w not in ("blue", "--utk") and (k == 0 or ARGS[k - 1] != "--utk")]

# (family, samplab spec, UTK executable and its arguments besides -n, -d, -s, -o)
CASES = [
    # UTK's Lloyd executable makes 3D points only (its add_arguments(app, 3)): no 2D peer
    ("Lloyd, 50 steps, torus", "lloyd:iterations=50", None),
    ("sliced OT, 200 x 32 directions", "sot:iterations=200,directions=32", ["SOT", "-i", "200", "-p", "32"]),
    ("dart throwing", "poisson", ["DartThrowing"]),
    ("Bridson", "poisson.fast", ["Bridson"]),
    ("sample elimination", "elimination", None),
    ("Gaussian blue noise, 100 steps", "gbn", None),
    ("CCVT, capacity 64", "ccvt", None),
]


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def timed(cmd):
    first = median_time(lambda: run(cmd), 1)
    return first if first > 10 else median_time(lambda: run(cmd), 3)


def relative_radius(path):
    out = subprocess.run([SAMPLAB, "discrepancy", "relative-radius", path], check=True, capture_output=True, text=True)
    return float(out.stdout.split()[-1])


def utk_points(path, out):
    """UTK's .dat (one point per line, '#' between sets) as a plain text file samplab reads."""
    with open(path) as f, open(out, "w") as g:
        g.writelines(line for line in f if line.strip() and not line.startswith("#"))


tmp = tempfile.mkdtemp()
print("family                              n     samplab s   rho  | UTK s        rho     ratio")
for family, spec, utk in CASES:
    if ONLY and not any(w in family for w in ONLY):
        continue
    for n in (1024, 4096, 16384):
        ours = os.path.join(tmp, "ours.txt")
        t = timed([SAMPLAB, "generate", spec, "-n", str(n), "--seed", "1", "-o", ours])
        line = "%-34s %6d %9.3f  %5.3f  |" % (family, n, t, relative_radius(ours))
        if UTK is None or utk is None:
            print(line, "(no UTK build given)" if utk else "(UTK has none)", flush=True)
            continue
        dat, txt = os.path.join(tmp, "utk.dat"), os.path.join(tmp, "utk.txt")
        cmd = [os.path.join(UTK, utk[0]), "-n", str(n), "-d", "2", "-s", "1", "-o", dat, "--silent"] + utk[1:]
        try:
            u = timed(cmd)
        except subprocess.CalledProcessError as e:
            print(line, "UTK failed: exit %d" % e.returncode, flush=True)
            continue
        utk_points(dat, txt)
        print(line, "%9.3f  %5.3f  %7.1fx" % (u, relative_radius(txt), u / t), flush=True)
