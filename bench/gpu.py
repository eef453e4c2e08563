#!/usr/bin/env python3
"""samplab's header-only samplers on a GPU (issue 94): the device's bytes against the CPU's,
and throughput beside cuRAND and the card's copy bandwidth, in one run.

Prepared for a lent device (H100/H200 with nvcc and CuPy), run from the repository root:

    python3 bench/gpu.py --samplab target/release/samplab --lib bench/.c-prefix/lib/libsamplab_c.so

Needs numpy, CuPy and nvcc on the device, and two things built here (carried to the device):
the CLI (`cargo build --release -p samplab-cli`) for the CPU's bytes, and the C library
(`scripts/install-c bench/.c-prefix`) for the tables of pmj02 and pmj02.bn.

1. Bytes: crates/samplab-c/examples/cuda/fill.cu, compiled by nvcc for this card, fills a
   film per family (every dimension) and an Owen-scrambled Sobol' set; each must equal
   `samplab pixels` / `samplab generate` bit for bit. The first differing key is printed.
2. Throughput, medians of CUDA-event timings: Owen-Sobol' points and each pixel family in
   f64 values written per second; cuRAND's scrambled Sobol' 64 (a digital shift, not Owen)
   on the same count; a device-to-device copy of the same bytes (its f64 values written per
   second, the bandwidth limit).
The fused integration study of the issue (samplab.gpu.integrate) is not built yet.
"""

import argparse
import ctypes
import json
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
MASK64 = (1 << 64) - 1


def mix64(x):
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & MASK64
    return x ^ (x >> 31)


def set_seed(seed, k):
    """samplab's Seed::derive: the seed of set k of `samplab generate --seed SEED`."""
    return mix64((mix64(seed ^ 0x9E3779B97F4A7C15) + k) & MASK64)


def compile_module(cp, nvcc, out):
    cubin = out / "fill.cubin"
    subprocess.run(
        [nvcc, "-std=c++17", "-O3", "-arch=native", "-cubin", "-I", str(ROOT / "crates/samplab-c/include"),
         "-o", str(cubin), str(ROOT / "crates/samplab-c/examples/cuda/fill.cu")],
        check=True,
    )
    return cp.RawModule(path=str(cubin))


def cli_pixels(samplab, spec, w, h, spp, dims, seed, out):
    path = out / "pixels.npy"
    subprocess.run([samplab, "pixels", spec, "--res", f"{w}x{h}", "--spp", str(spp), "--dims", str(dims),
                    "--seed", str(seed), "-o", str(path)], check=True, capture_output=True)
    return np.load(path).reshape(h, w, spp, dims)


def header_tables(lib, spec, w, h, spp, dims, seed):
    """samplab_pixels_header_tables' words for `spec`, through the C library."""
    lib.samplab_pixels_new.restype = ctypes.c_void_p
    lib.samplab_pixels_new.argtypes = [ctypes.c_char_p, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_uint32,
                                       ctypes.c_uint32, ctypes.c_uint64, ctypes.c_char_p, ctypes.c_size_t]
    lib.samplab_pixels_header_tables.restype = ctypes.c_size_t
    lib.samplab_pixels_header_tables.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t]
    lib.samplab_pixels_free.argtypes = [ctypes.c_void_p]
    error = ctypes.create_string_buffer(256)
    s = lib.samplab_pixels_new(spec.encode(), w, h, spp, dims, seed, error, 256)
    if not s:
        sys.exit(f"gpu.py: {spec}: {error.value.decode()}")
    n = lib.samplab_pixels_header_tables(s, None, 0)
    words = np.empty(n, dtype=np.uint32)
    lib.samplab_pixels_header_tables(s, words.ctypes.data, n)
    lib.samplab_pixels_free(s)
    return words


# (samplab spec, kernel, pmj02 mask side or None)
FAMILIES = [
    ("independent", "independent", None),
    ("sobol", "sobol", None),
    ("sobol.padded", "sobol_padded", None),
    ("zsobol", "zsobol", None),
    ("zsobol:curve=hilbert", "zsobol_hilbert", None),
    ("stratified", "stratified", None),
    ("lattice", "lattice", None),
    ("halton", "halton", None),
    ("sobol.owen", "sobol_owen_per_pixel", None),
    ("pmj02", "pmj02", 0),
    ("pmj02.bn", "pmj02", 64),
]


def launch(cp, kernel, total, args):
    block = 256
    kernel(((total + block - 1) // block,), (block,), args)


def family_args(np_, seed, w, h, spp, frame, dim, tables, mask, out):
    head = (np_.uint64(seed), np_.uint32(w), np_.uint32(h), np_.uint32(spp), np_.uint32(frame), np_.uint32(dim))
    return head + ((tables, np_.uint32(mask), out) if mask is not None else (out,))


def check_bytes(cp, mod, samplab, lib, out):
    w, h, spp, dims, seed = 64, 48, 16, 8, 7
    rows = []
    for spec, name, mask in FAMILIES:
        cpu = cli_pixels(samplab, spec, w, h, spp, dims, seed, out)
        tables = cp.asarray(header_tables(lib, spec, w, h, spp, dims, seed)) if mask is not None else None
        device = cp.empty((h, w, spp), dtype=cp.float64)
        first = None
        for d in range(dims):
            launch(cp, mod.get_function(name), w * h * spp, family_args(np, seed, w, h, spp, 0, d, tables, mask, device))
            got = cp.asnumpy(device).view(np.uint64)
            want = np.ascontiguousarray(cpu[..., d]).view(np.uint64)
            if first is None and not np.array_equal(got, want):
                y, x, i = (int(v[0]) for v in np.nonzero(got != want))
                first = f"(x {x}, y {y}, frame 0, index {i}, dim {d})"
        rows.append((spec, first))
        print(f"bytes {spec:14} {'equal' if first is None else 'DIFFER at ' + first}", flush=True)
    # an Owen-scrambled Sobol' set, as `samplab generate sobol.owen` writes set 0
    n, d = 1 << 12, 16
    path = out / "points.npy"
    subprocess.run([samplab, "generate", "sobol.owen", "-n", str(n), "-d", str(d), "--seed", str(seed), "-o", str(path)],
                   check=True, capture_output=True)
    cpu = np.load(path).reshape(n, d)
    device = cp.empty((n, d), dtype=cp.float64)
    launch(cp, mod.get_function("sobol_points"), n * d,
           (np.uint64(set_seed(seed, 0)), np.uint32(0), np.uint32(n), np.uint32(d), np.uint32(2), device))
    same = np.array_equal(cp.asnumpy(device).view(np.uint64), cpu.view(np.uint64))
    print(f"bytes {'sobol.owen set':14} {'equal' if same else 'DIFFER'}", flush=True)
    rows.append(("sobol.owen set", None if same else "differs"))
    return rows


def median_seconds(cp, run, rounds=7):
    run()  # warm up
    times = []
    for _ in range(rounds):
        start, stop = cp.cuda.Event(), cp.cuda.Event()
        start.record()
        run()
        stop.record()
        stop.synchronize()
        times.append(cp.cuda.get_elapsed_time(start, stop) / 1e3)
    return statistics.median(times)


def throughput(cp, mod, lib):
    from cupy.cuda import curand

    results = {}
    n, d = 1 << 24, 8  # 2^27 f64 values, 1 GiB
    values = n * d
    out = cp.empty(values, dtype=cp.float64)
    source = cp.zeros(values, dtype=cp.float64)
    results["copy (device to device)"] = values / median_seconds(cp, lambda: cp.copyto(out, source))
    k = mod.get_function("sobol_points")
    owen = (np.uint64(set_seed(7, 0)), np.uint32(0), np.uint32(n), np.uint32(d), np.uint32(2), out)
    results["samplab sobol.owen points"] = values / median_seconds(cp, lambda: launch(cp, k, values, owen))
    gen = curand.createGenerator(curand.CURAND_RNG_QUASI_SCRAMBLED_SOBOL64)
    curand.setQuasiRandomGeneratorDimensions(gen, d)
    results["cuRAND scrambled Sobol' 64"] = values / median_seconds(
        cp, lambda: curand.generateUniformDouble(gen, out.data.ptr, values))
    curand.destroyGenerator(gen)
    # pixel families: a 1920 x 1080 film at 64 spp, one dimension per launch (2^27 values)
    w, h, spp = 1920, 1080, 64
    film = cp.empty(w * h * spp, dtype=cp.float64)
    for spec, name, mask in FAMILIES:
        tables = cp.asarray(header_tables(lib, spec, w, h, spp, 8, 7)) if mask is not None else None
        f = mod.get_function(name)
        args = family_args(np, 7, w, h, spp, 0, 2, tables, mask, film)
        results[f"samplab {spec} (pixels)"] = w * h * spp / median_seconds(cp, lambda: launch(cp, f, w * h * spp, args))
    return results


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--samplab", default=str(ROOT / "target/release/samplab"), help="the samplab CLI (CPU bytes)")
    p.add_argument("--lib", default=str(ROOT / "bench/.c-prefix/lib/libsamplab_c.so"), help="the C library")
    p.add_argument("--nvcc", default="nvcc")
    a = p.parse_args()
    try:
        import cupy as cp
    except ImportError:
        sys.exit("gpu.py: CuPy is not installed (pip install cupy-cuda12x); it needs a CUDA device")
    lib = ctypes.CDLL(a.lib)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        mod = compile_module(cp, a.nvcc, out)
        device = cp.cuda.runtime.getDeviceProperties(0)["name"].decode()
        print(f"device: {device}", flush=True)
        rows = check_bytes(cp, mod, a.samplab, lib, out)
        results = throughput(cp, mod, lib)
    print(f"\n{'what':40} {'f64 values/s':>14} {'of copy':>8}")
    copy = results["copy (device to device)"]
    for name, rate in results.items():
        print(f"{name:40} {rate:14.4e} {rate / copy:8.2f}")
    print(json.dumps({"device": device, "bytes": {s: f is None for s, f in rows}, "values_per_second": results}))
    sys.exit(0 if all(f is None for _, f in rows) else 1)


if __name__ == "__main__":
    main()
