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


def machine():
    """One line naming the machine a table is measured on (every table's header): the
    processor, its cores, and the instruction set samplab's hot loops run on there: the
    widest the processor has by `samplab::simd::Tier::detected`'s test (AVX-512 with BW,
    DQ, VL and GFNI; else AVX2; else the SSE2 baseline), or the narrower one SAMPLAB_SIMD
    names."""
    import os
    model, flags = "unknown processor", set()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key, _, value = line.partition(":")
                if key.strip() == "model name" and model == "unknown processor":
                    model = value.strip()
                elif key.strip() == "flags" and not flags:
                    flags = set(value.split())
    except OSError:
        pass
    if {"avx512f", "avx512bw", "avx512dq", "avx512vl", "gfni"} <= flags:
        widest = "avx512"
    elif "avx2" in flags:
        widest = "avx2"
    else:
        widest = "baseline"
    names = {"avx512": "AVX-512 (512-bit vectors)", "avx2": "AVX2 (256-bit vectors)", "baseline": "SSE2 (128-bit vectors)"}
    tier = os.environ.get("SAMPLAB_SIMD", widest)
    limited = " (limited by SAMPLAB_SIMD; the processor has %s)" % names[widest] if tier != widest else ""
    return "machine: %s, %d cores, samplab's vector paths: %s%s, %s" % (
        model, os.cpu_count(), names.get(tier, tier), limited, time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()))
