"""The one timing helper of the bench scripts: the median of repeated runs (machines here
are noisy, so every figure the scripts print is a median)."""
import time


def median_time(fn, min_runs=5, min_seconds=0.0, max_runs=50):
    """Median wall time of fn() over at least min_runs runs, repeated until min_seconds have
    passed (at most max_runs runs)."""
    times = []
    start = time.perf_counter()
    while len(times) < min_runs or (time.perf_counter() - start < min_seconds and len(times) < max_runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    times.sort()
    return times[len(times) // 2]
