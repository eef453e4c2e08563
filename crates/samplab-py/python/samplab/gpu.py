"""samplab's samplers on a CUDA device, as CuPy arrays.

The kernels are compiled at first use, by NVRTC through CuPy's ``RawModule``, from the same
header-only C++ that renderers include (``crates/samplab-c/include/samplab/samplers.hpp``).
On the CPU its values equal the library's bit for bit (``crates/samplab-c/tests/header.rs``
checks a million keys per family). ``bench/gpu.py`` checks the device's bytes on a lent GPU.
DLPack hands the arrays to PyTorch or JAX without a copy (``torch.from_dlpack(x)``).

>>> import samplab.gpu                                                    # doctest: +SKIP
>>> x = samplab.gpu.generate("sobol.owen", 1 << 20, 8, seed=7)            # doctest: +SKIP
>>> u = samplab.gpu.pixels("zsobol", (1920, 1080), 64, dims=4, seed=7)    # doctest: +SKIP

Needs CuPy (``pip install "samplab[gpu]"``) and a CUDA device. Without them, each function
raises ``samplab.Error`` naming what is missing. Until the device bytes have been checked
on a GPU (``bench/gpu.py``), treat these arrays as unverified there.
"""

from __future__ import annotations

import functools
from typing import Any, Optional, Sequence

from . import Error, _count, _samplab, _seed

#: The point sets with a kernel: spec -> the kernel's randomization word.
POINT_SETS = {"sobol": 0, "sobol.xor": 1, "sobol.owen": 2, "sobol.shift": 3}

#: The pixel samplers with a kernel: spec -> (kernel, most dimensions; None: any).
PIXEL_SAMPLERS = {
    "independent": ("independent", None),
    "stratified": ("stratified", None),
    "sobol": ("sobol", 1024),
    "sobol.padded": ("sobol_padded", None),
    "zsobol": ("zsobol", None),
    "zsobol:curve=hilbert": ("zsobol_hilbert", None),
    "lattice": ("lattice", 1024),
    "halton": ("halton", 1000),
    "sobol.owen": ("sobol_owen_per_pixel", 1024),
}

_MASK64 = (1 << 64) - 1


def _mix64(x: int) -> int:
    x = ((x ^ (x >> 30)) * 0xBF58476D1CE4E5B9) & _MASK64
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & _MASK64
    return x ^ (x >> 31)


def _set_seed(seed: int, k: int) -> int:
    """The seed of set k (samplab's Seed::derive), as ``samplab generate`` seeds its sets."""
    return _mix64((_mix64(seed ^ 0x9E3779B97F4A7C15) + k) & _MASK64)


def _cupy() -> Any:
    """CuPy, with a device to run on; samplab.Error naming what is missing otherwise."""
    try:
        import cupy
    except ImportError:
        raise Error('samplab.gpu needs CuPy and a CUDA device: CuPy is not installed (pip install "samplab[gpu]")') from None
    try:
        devices = cupy.cuda.runtime.getDeviceCount()
    except Exception as e:  # CuPy's CUDARuntimeError, or a missing driver library
        raise Error(f"samplab.gpu needs a CUDA device: CuPy finds none ({e})") from None
    if devices < 1:
        raise Error("samplab.gpu needs a CUDA device: CuPy finds none")
    return cupy


@functools.lru_cache(maxsize=None)
def _module() -> Any:
    return _cupy().RawModule(code=_samplab.cuda_source(), options=("-std=c++17",))


def _launch(kernel: Any, total: int, args: tuple) -> None:
    block = 256
    kernel(((total + block - 1) // block,), (block,), args)


def generate(spec: str, n: int, d: int = 2, seed: Optional[int] = None, sets: Optional[int] = None) -> Any:
    """Points of a Sobol' point set on the device, as ``samplab.generate`` makes them.

    ``spec`` is one of ``POINT_SETS``. Returns a ``cupy.ndarray`` of float64 of shape (n, d),
    or (sets, n, d) when ``sets`` is given. Set k is seeded as ``samplab generate`` seeds it.
    At most 2^32 points and 1024 dimensions."""
    if spec not in POINT_SETS:
        raise Error(f"samplab.gpu.generate: no GPU kernel for {spec!r}; these have one: {', '.join(POINT_SETS)}")
    n, d, s = _count("n", n), _count("d", d), _seed(seed)
    m = 1 if sets is None else _count("sets", sets)
    if not 1 <= n <= 1 << 32 or not 1 <= d <= 1024:
        raise Error(f"samplab.gpu.generate: n = {n}, d = {d}: 1 to 2^32 points in 1 to 1024 dimensions")
    cp = _cupy()
    import numpy as np

    out = cp.empty((m, n, d), dtype=cp.float64)
    kernel = _module().get_function("sobol_points")
    for k in range(m):
        args = (np.uint64(_set_seed(s, k)), np.uint32(0), np.uint32(n), np.uint32(d), np.uint32(POINT_SETS[spec]), out[k])
        _launch(kernel, n * d, args)
    return out[0] if sets is None else out


def pixels(spec: str, res: Sequence[int], spp: int, dims: int = 2, frames: int = 1, seed: Optional[int] = None) -> Any:
    """Every value a pixel sampler gives a film, on the device, as ``samplab.pixels``.

    ``spec`` is one of ``PIXEL_SAMPLERS``. Returns a ``cupy.ndarray`` of float64 of shape
    (frames, height, width, spp, dims); entry [f, y, x, i, d] is dimension d of sample i of
    pixel (x, y) in frame f."""
    if spec not in PIXEL_SAMPLERS:
        raise Error(f"samplab.gpu.pixels: no GPU kernel for {spec!r}; these have one: {', '.join(PIXEL_SAMPLERS)}")
    name, most = PIXEL_SAMPLERS[spec]
    width, height = (_count("res", r) for r in res)
    spp, dims, frames, s = _count("spp", spp), _count("dims", dims), _count("frames", frames), _seed(seed)
    if min(width, height, spp, dims, frames) < 1:
        raise Error(f"samplab.gpu.pixels: res {width}x{height}, spp {spp}, dims {dims}, frames {frames}: each at least 1")
    if most is not None and dims > most:
        raise Error(f"samplab.gpu.pixels: dims = {dims}: {spec} has at most {most} dimensions")
    if spec.startswith("zsobol") and spp & (spp - 1):
        raise Error(f"samplab.gpu.pixels: spp = {spp}: {spec} needs a power of two")
    cp = _cupy()
    import numpy as np

    out = cp.empty((frames, height, width, spp, dims), dtype=cp.float64)
    plane = cp.empty((height, width, spp), dtype=cp.float64)
    kernel = _module().get_function(name)
    for f in range(frames):
        for d in range(dims):
            args = (np.uint64(s), np.uint32(width), np.uint32(height), np.uint32(spp), np.uint32(f), np.uint32(d), plane)
            _launch(kernel, width * height * spp, args)
            out[f, :, :, :, d] = plane
    return out
