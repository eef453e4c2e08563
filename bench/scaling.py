#!/usr/bin/env python3
"""How samplab's heavy work scales with threads: the table of the "every core used" issue.

Each row is one command of the release binary, run with RAYON_NUM_THREADS = 1, 2 and, where
the machine has them, 4, 8, 16 cores; rounds alternate the thread counts so that a slow
spell of a noisy machine hits every column alike. Prints the median wall time per column,
the speed-up at 2 threads and the serial fraction Amdahl's law gives from the 1- and
2-thread medians, f = 2 T2 / T1 - 1 (T(p) = T1 (f + (1 - f) / p)). Each command's output is
compared across thread counts: a row whose bytes differ is marked.

A run of a row lasts from half a second to minutes, and this machine's second core is
slower in some spells than in others, so a median of K rounds of a short row rests on a
few seconds of the machine's life. With --seconds S a row runs as many rounds as it takes
to spend S seconds (judged from its first round; K at least), and every row prints the
quartiles of its rounds' own speed-ups (T1 / T2 of one round, minutes apart at most): the
spread that a single median hides.

With --ceiling, each round also runs two copies of the one-thread command at once (p copies
for each further column p): what the machine itself gives to p independent processes that
share nothing but its caches, memory bus and host. The ceiling column is p T1 / Tc, Tc the
median time of a copy run beside the others: a row's speed-up can only reach the ceiling,
and a speed-up close to it has no serial part left that threads could remove.

With --profile, each row is also run K times (--rounds) on the top column's p threads under
`perf record` (the cpu-clock at 1 kHz: a thread on a core is sampled once a millisecond, so
a window of w ms holds w samples per busy thread), each run cut into 4 ms windows. A
window's work is its samples, counted as at least one thread's worth (a window with fewer
is a wait, serial too: it lasts as long on one thread) and at most p threads' worth;
Amdahl's law over the windows gives the serial fraction the profile measures,
f = (p T_p / T_1 - 1) / (p - 1), T_p the run's windows and T_1 their work in windows, and
the run of median f is printed. A core the host (or another process: run it on an
otherwise idle machine) takes away shows as a thread off the processor, so this f is an
upper bound on the run's own serial part; unlike the wall-clock one it does not depend on
how fast the second core is in that spell, but it counts a thread as working while rayon's
idle loop spins (briefly) before it sleeps, and it cannot see two threads slowing each
other down through the memory they share. The profile also names the functions a lone
thread was in while the others waited: where the serial part is.

With --timeline, each row is also run K times on the top column's threads while a loop
reads its threads' CPU times (Linux's /proc/PID/task/TID/schedstat) every 2 ms: the same
windowed serial fraction as --profile's, with no perf needed (a machine lent without it),
and a strip of the threads busy in each fiftieth of the run, which shows where the run is
serial (its start, a phase between two parallel ones, its end). The loop itself takes part
of one core, and a thread's clock may move only at the kernel's tick or when it stops, so a
2 ms window can read no work and the next twice its share: the fraction by windows is an
upper bound, and the strip, averaged over longer stretches, is the steadier reading.

With --threads P,Q,.. only those thread counts are run (a long row such as the reproduction
on 1 and 16 threads alone). Where the top column is more than 2 threads, the table also
gives the speed-up there and the serial fraction it implies, f = (p T_p / T_1 - 1) / (p - 1).

Usage: bench/compare scaling [--rounds K] [--seconds S] [--threads P,..] [--ceiling] [--timeline] [--profile]
       [ROW...]
(--help lists the rows)
"""
import argparse
import collections
import hashlib
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# the bench folder's helpers, wherever this file is run or loaded from (the tests load it)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from timing import machine  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAMPLAB = os.environ.get("SAMPLAB_BIN", os.path.join(ROOT, "target", "release", "samplab"))

# (name, label, arguments; OUT is replaced by a fresh path, its content hashed)
ROWS = [
    ("render", "render spheres 512x512, 64 spp",
     ["render", "spheres", "--res", "512x512", "--spp", "64", "-o", "OUT.exr"]),
    ("integrate", "integrate, 3 samplers x 4 counts x 2000 sets x 10 instances",
     ["integrate", "--integrand", "quad", "--sampler", "random", "--sampler", "jitter", "--sampler", "sobol.owen",
      "-n", "16,64,256,1024", "--sets", "2000", "--json"]),
    ("extreme", "exact 2D extreme discrepancy, Owen-Sobol' 10^4",
     ["discrepancy", "extreme", "--sampler", "sobol.owen", "-n", "10000", "--json"]),
    ("spectrum", "spectrum statistics, 64 sets of 65536 points, 1024^2",
     ["spectrum", "--sampler", "random", "-n", "65536", "--sets", "64", "--res", "1024", "-o", "OUT"]),
    ("elimination", "generate elimination 10^5",
     ["generate", "elimination", "-n", "100000", "-o", "OUT.npy"]),
    ("elimination.tiled", "generate elimination.tiled 10^5 (in tiles, other points)",
     ["generate", "elimination.tiled", "-n", "100000", "-o", "OUT.npy"]),
    ("ccvt", "generate ccvt 4096 (capacity 64, up to 50 iterations)",
     ["generate", "ccvt", "-n", "4096", "-o", "OUT.npy"]),
    ("poisson", "generate poisson 10^6 (dart throwing)",
     ["generate", "poisson", "-n", "1000000", "-o", "OUT.npy"]),
    ("poisson.maximal", "generate poisson.maximal 2x10^4 (radius bisected to exactly n)",
     ["generate", "poisson.maximal", "-n", "20000", "-o", "OUT.npy"]),
    ("l2", "L2-star + centered of 10^6 random points",
     ["discrepancy", "l2-star", "centered", "--sampler", "random", "-n", "1000000", "--json"]),
    ("reproduce", "samplab reproduce (fast)", ["reproduce", "--out", "OUT"]),
]


def digest(path):
    """SHA-256 of a file, or of a folder's files (names and bytes) in sorted order; the
    reproduction's HTML pages and timing.json are left out, as they give the time each
    part took."""
    h = hashlib.sha256()
    if os.path.isdir(path):
        for base, dirs, files in sorted(os.walk(path)):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(".html") or f == "timing.json" or f.startswith(".samplab"):
                    continue
                p = os.path.join(base, f)
                h.update(os.path.relpath(p, path).encode())
                with open(p, "rb") as fh:
                    h.update(fh.read())
    elif os.path.exists(path):
        with open(path, "rb") as fh:
            h.update(fh.read())
    return h.hexdigest()


def prepare(args, threads, out):
    """A row's arguments with OUT replaced by the path `out` (the output, if any, removed
    from an earlier run), the path it writes, and the environment for `threads` threads."""
    argv = [a.replace("OUT", out) for a in args]
    target = next((a for a in argv if a.startswith(out)), None)
    if target and os.path.isdir(target):
        shutil.rmtree(target)
    return argv, target, dict(os.environ, RAYON_NUM_THREADS=str(threads))


def launch(args, threads, out):
    """Starts one run writing under the path `out`; returns what `finish` needs."""
    argv, target, env = prepare(args, threads, out)
    done = subprocess.Popen([SAMPLAB] + argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    return done, argv, target


def finish(started):
    """Waits for a run; returns its output's digest."""
    done, argv, target = started
    stdout, stderr = done.communicate()
    if done.returncode != 0:
        sys.exit("samplab %s: exit %d: %s" % (" ".join(argv), done.returncode, stderr.decode()[-400:]))
    return digest(target) if target else hashlib.sha256(stdout).hexdigest()


def run(args, threads, tmp):
    """One run on `threads` threads: (seconds, digest of its output)."""
    start = time.perf_counter()
    d = finish(launch(args, threads, os.path.join(tmp, "out%d" % threads)))
    return time.perf_counter() - start, d


def copies(args, p, tmp):
    """p one-thread runs at once: the seconds until the last is done, and their digests."""
    start = time.perf_counter()
    started = [launch(args, 1, os.path.join(tmp, "copy%d" % i)) for i in range(p)]
    digests = [finish(s) for s in started]
    return time.perf_counter() - start, digests


def thread_counts(text, cores):
    """The columns `--threads` asks for ("1,16"), or by default 1, 2, 4, 8, 16 up to the
    machine's cores; None when the text is not a list of distinct counts that holds 1 (every
    speed-up is against one thread)."""
    if text is None:
        return [p for p in (1, 2, 4, 8, 16) if p <= cores]
    try:
        counts = [int(t) for t in text.split(",")]
    except ValueError:
        return None
    if 1 not in counts or min(counts) < 1 or len(set(counts)) != len(counts):
        return None
    return sorted(counts)


def amdahl(t1, tp, p):
    """Amdahl's serial fraction from the times on 1 and p threads: T_p = T_1 (f + (1 - f) / p)."""
    return (p * tp / t1 - 1.0) / (p - 1.0)


def rounds_for(first, k, seconds):
    """The rounds of a row whose first round took `first` seconds: at least k, and as many
    as spend `seconds`."""
    return max(k, math.ceil(seconds / first))


def quartiles(one, two):
    """The lower and upper quartiles of the rounds' own speed-ups, one[i] / two[i] (each
    round's runs are at most minutes apart); the one speed-up when there is one round."""
    ratios = [a / b for a, b in zip(one, two)]
    if len(ratios) == 1:
        return ratios[0], ratios[0]
    q = statistics.quantiles(ratios, n=4, method="inclusive")
    return q[0], q[2]


# the profile: sampling rate (Hz) and window (seconds)
PROFILE_HZ = 1000
WINDOW = 0.004


def short(symbol):
    """A function's name without its generic arguments and crate path: `poisson::bridson`."""
    depth, plain = 0, []
    for c in symbol:
        depth += c == "<"
        if depth == 0:
            plain.append(c)
        depth -= c == ">" and depth > 0
    parts = [p for p in "".join(plain).split("::") if p and p != "{{closure}}"]
    return "::".join(parts[-2:]) or symbol


def profile(args, p, tmp):
    """One run on p threads under perf: its `windows`."""
    data = os.path.join(tmp, "perf.data")
    argv, _, env = prepare(args, p, os.path.join(tmp, "profiled"))
    rec = subprocess.run(["perf", "record", "-q", "-F", str(PROFILE_HZ), "-e", "cpu-clock", "-o", data, "--",
                          SAMPLAB] + argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if rec.returncode != 0:
        sys.exit("perf record samplab %s: exit %d: %s" % (" ".join(argv), rec.returncode,
                                                          rec.stderr.decode()[-400:]))
    text = subprocess.run(["perf", "script", "-i", data, "-F", "tid,time,ip,sym"], capture_output=True,
                          check=True).stdout.decode(errors="replace")
    return windows(text, p)


def windowed_serial(windows, p):
    """Amdahl's serial fraction of a run on p threads cut into windows (width, threads
    busy): a window's work is its busy threads, counted as at least one (a window with
    fewer is a wait, serial too: it lasts as long on one thread) and at most p."""
    span = sum(width for width, _ in windows)
    work = sum(width * min(max(busy, 1.0), p) for width, busy in windows)
    return amdahl(work, span, p)


def cpu_times(pid):
    """Each thread's CPU time so far, in nanoseconds (the first field of Linux's
    /proc/PID/task/TID/schedstat), by thread id; threads gone meanwhile are left out."""
    base = "/proc/%d/task" % pid
    try:
        tids = os.listdir(base)
    except OSError:
        return {}
    times = {}
    for tid in tids:
        try:
            with open("%s/%s/schedstat" % (base, tid)) as fh:
                times[tid] = int(fh.read().split()[0])
        except (OSError, ValueError, IndexError):
            pass
    return times


def busy_between(samples):
    """The windows between successive samples (time in seconds, CPU nanoseconds by thread):
    (width, threads busy), a thread first seen counted from zero."""
    out = []
    for (t0, c0), (t1, c1) in zip(samples, samples[1:]):
        ns = sum(v - c0.get(tid, 0) for tid, v in c1.items())
        out.append((t1 - t0, ns / 1e9 / (t1 - t0)))
    return out


# the timeline: how often the threads' CPU times are read (seconds), and its parts
PERIOD = 0.002
PARTS = 50
DIGITS = "0123456789abcdefghijklmnopqrstuvwxyz"


def strip(windows, parts):
    """The mean threads busy in each of `parts` equal stretches of the run's windows, as one
    character each (0-9, then a = 10 .. z = 35)."""
    span = sum(width for width, _ in windows)
    work, at = [0.0] * parts, 0.0
    for width, busy in windows:
        # a window's work goes to the stretches it overlaps, by overlap
        a, b = at, at + width
        for k in range(min(int(a / span * parts), parts - 1), min(int(b / span * parts), parts - 1) + 1):
            overlap = min(b, (k + 1) * span / parts) - max(a, k * span / parts)
            work[k] += max(overlap, 0.0) * busy
        at = b
    return "".join(DIGITS[min(int(round(w * parts / span)), len(DIGITS) - 1)] for w in work)


def timeline(args, p, tmp):
    """One run on p threads, its threads' CPU times read every PERIOD seconds (no perf
    needed): (seconds, serial fraction by windows, share of the time with under 1.5 threads
    busy, the timeline strip)."""
    argv, _, env = prepare(args, p, os.path.join(tmp, "sampled"))
    start = time.perf_counter()
    # stderr to a file: a pipe nobody reads while the run goes on could fill and stop it
    log = tempfile.TemporaryFile()
    proc = subprocess.Popen([SAMPLAB] + argv, env=env, stdout=subprocess.DEVNULL, stderr=log)
    samples = [(start, {})]
    while proc.poll() is None:
        times = cpu_times(proc.pid)
        samples.append((time.perf_counter(), times))
        time.sleep(PERIOD)
    seconds = time.perf_counter() - start
    log.seek(0)
    stderr = log.read()
    if proc.returncode != 0:
        sys.exit("samplab %s: exit %d: %s" % (" ".join(argv), proc.returncode, stderr.decode()[-400:]))
    got = [(t, c) for t, c in samples if c] or samples
    windows = busy_between([samples[0]] + got)
    lone = sum(width for width, busy in windows if busy < 1.5) / max(sum(w for w, _ in windows), 1e-9)
    return seconds, windowed_serial(windows, p), lone, strip(windows, PARTS)


def windows(text, p):
    """The windows of a run's samples (`perf script -F tid,time,ip,sym` lines) on p
    threads: (its windows, the windows in which one thread ran, the serial fraction, and
    that lone thread's three commonest functions as (share, name))."""
    per = PROFILE_HZ * WINDOW  # samples of one busy thread in a window
    samples = collections.Counter()
    tids = collections.defaultdict(set)
    where = collections.defaultdict(list)
    for line in text.splitlines():
        fields = line.split(None, 3)
        if len(fields) < 3:
            continue
        tid, at = int(fields[0]), float(fields[1].rstrip(":"))
        w = int(at / WINDOW)
        samples[w] += 1
        tids[w].add(tid)
        where[w].append(short(fields[3]) if len(fields) > 3 else fields[2])
    first, last = min(samples), max(samples)
    span = last - first + 1
    serial = windowed_serial([(1.0, samples[w] / per) for w in range(first, last + 1)], p)
    lone = [w for w in tids if len(tids[w]) == 1]
    alone = collections.Counter(f for w in lone for f in where[w])
    total = sum(alone.values()) or 1
    return span, len(lone), serial, [(c / total, f) for f, c in alone.most_common(3)]


def main():
    parser = argparse.ArgumentParser(
        prog="bench/compare scaling",
        description="samplab's heavy commands on 1, 2, 4, 8, 16 threads (as many as the machine "
                    "has): median wall times, the speed-up at 2 threads, Amdahl's serial fraction "
                    "and whether the output bytes agree.")
    parser.add_argument("rows", nargs="*", metavar="ROW",
                        help="rows to run (default: all): " + ", ".join(r[0] for r in ROWS))
    parser.add_argument("--rounds", type=int, default=3, metavar="K",
                        help="runs per column; the median is reported (default 3)")
    parser.add_argument("--seconds", type=float, default=0.0, metavar="S",
                        help="more rounds for short rows: as many as make S seconds, judged from "
                             "the first round (default 0: K rounds)")
    parser.add_argument("--threads", metavar="P,..",
                        help="the thread counts to run, e.g. 1,16 (default: 1, 2, 4, 8, 16 up to "
                             "the machine's cores)")
    parser.add_argument("--ceiling", action="store_true",
                        help="also run p one-thread copies at once per column p: the machine's "
                             "own limit for p independent processes")
    parser.add_argument("--timeline", action="store_true",
                        help="also run each row K times on the top column's threads, reading "
                             "its threads' CPU times every 2 ms from /proc (Linux, no perf): the "
                             "serial fraction by windows and a strip of the threads busy over "
                             "the run")
    parser.add_argument("--profile", action="store_true",
                        help="also profile K runs per row on the top column's threads with perf (Debian's "
                             "linux-perf): the serial fraction of their busy-thread windows and "
                             "the functions a lone busy thread was in")
    opts = parser.parse_args()
    print(machine(), flush=True)
    if opts.rounds < 1:
        parser.error("--rounds must be at least 1, not %d" % opts.rounds)
    if not opts.seconds >= 0 or math.isinf(opts.seconds):
        parser.error("--seconds must be a finite number of seconds, at least 0, not %s" % opts.seconds)
    unknown = [r for r in opts.rows if r not in [row[0] for row in ROWS]]
    if unknown:
        parser.error("unknown row %r (rows: %s)" % (unknown[0], ", ".join(r[0] for r in ROWS)))
    if opts.profile and shutil.which("perf") is None:
        parser.error("--profile needs perf on the PATH (Debian: apt-get install linux-perf)")
    if opts.profile and (os.cpu_count() or 1) < 2:
        parser.error("--profile needs at least two cores: a serial fraction compares threads")
    rounds, ceiling = opts.rounds, opts.ceiling
    rows = [r for r in ROWS if not opts.rows or r[0] in opts.rows]
    cores = os.cpu_count() or 1
    columns = thread_counts(opts.threads, cores)
    if columns is None:
        parser.error("--threads must be distinct thread counts, 1 among them, separated by commas, not %r"
                     % opts.threads)
    top = columns[-1] if columns[-1] > 2 else None
    print("samplab scaling, %s, %d cores, at least %d rounds%s, medians of wall time (%s)"
          % (time.strftime("%Y-%m-%d"), cores, rounds,
             " or %g seconds a row" % opts.seconds if opts.seconds > 0 else "", SAMPLAB))
    header = "| work | rounds | " + " | ".join("%d thread%s" % (p, "" if p == 1 else "s") for p in columns) + \
             " | speed-up at 2 | rounds' speed-ups (quartiles) | serial fraction | bytes |"
    many = [p for p in columns if p > 1] if ceiling else []
    header += "".join(" ceiling at %d |" % p for p in many)
    if top:
        header += " speed-up at %d | serial fraction at %d |" % (top, top)
    print(header)
    print("|" + "---|" * (len(columns) + 6 + len(many) + (2 if top else 0)))
    with tempfile.TemporaryDirectory() as tmp:
        for name, label, argv in rows:
            times = {p: [] for p in columns}
            beside = {p: [] for p in many}
            digests = set()
            # at least K rounds, and as many more as fit in --seconds (from the first
            # round's time): a short row's median then rests on as many runs as it needs
            wanted, k = rounds, 0
            while k < wanted:
                began = time.perf_counter()
                for p in columns:
                    seconds, d = run(argv, p, tmp)
                    times[p].append(seconds)
                    digests.add(d)
                for p in many:
                    seconds, ds = copies(argv, p, tmp)
                    beside[p].append(seconds)
                    digests.update(ds)
                if k == 0:
                    wanted = rounds_for(time.perf_counter() - began, rounds, opts.seconds)
                k += 1
            med = {p: statistics.median(times[p]) for p in columns}
            if 2 in med:
                low, high = quartiles(times[1], times[2])
                at2 = "%.2fx | %.2f-%.2fx | %.1f%%" % (med[1] / med[2], low, high, 100 * amdahl(med[1], med[2], 2))
            else:
                at2 = "- | - | -"
            cells = " | ".join("%.2f s" % med[p] for p in columns)
            tops = "".join(" %.2fx |" % (p * med[1] / statistics.median(beside[p])) for p in many)
            if top:
                tops += " %.2fx | %.1f%% |" % (med[1] / med[top], 100 * amdahl(med[1], med[top], top))
            print("| %s | %d | %s | %s | %s |%s"
                  % (label, k, cells, at2, "same" if len(digests) == 1 else "DIFFER", tops),
                  flush=True)
        if opts.timeline:
            p = columns[-1]
            print("\nTimeline: %d runs per row on %d threads, the threads' CPU times read every %g ms; "
                  "the run of median serial fraction; the strip gives the threads busy in each fiftieth "
                  "of the run (0-9, then a = 10, g = 16)" % (rounds, p, PERIOD * 1000))
            print("| work | seconds | serial fraction | under 1.5 threads busy | threads busy over the run |")
            print("|---|---|---|---|---|")
            for name, label, argv in rows:
                runs = sorted((timeline(argv, p, tmp) for _ in range(rounds)), key=lambda r: r[1])
                seconds, serial, lone, line = runs[len(runs) // 2]
                print("| %s | %.2f s | %.1f%% | %.0f%% | `%s` |" % (label, seconds, 100 * serial, 100 * lone, line),
                      flush=True)
        if opts.profile:
            p = columns[-1]
            print("\nProfile: %d runs per row on %d threads, perf's cpu-clock at %d Hz, %d ms windows; "
                  "the run of median serial fraction" % (rounds, p, PROFILE_HZ, WINDOW * 1000))
            print("| work | windows | with one thread busy | serial fraction | the lone busy thread's functions |")
            print("|---|---|---|---|---|")
            for name, label, argv in rows:
                runs = sorted((profile(argv, p, tmp) for _ in range(rounds)), key=lambda r: r[2])
                span, lone, serial, alone = runs[len(runs) // 2]
                funcs = ", ".join("%s %.0f%%" % (f, 100 * share) for share, f in alone)
                print("| %s | %d | %d | %.1f%% | %s |" % (label, span, lone, 100 * serial, funcs), flush=True)


if __name__ == "__main__":
    main()
