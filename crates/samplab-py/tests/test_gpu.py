"""samplab.gpu without a GPU: its kernels' source compiles under NVRTC (what CuPy's RawModule
runs), every kernel it names is in that source, and what it cannot do is refused by name."""

import glob
import re
import subprocess
import sys
from pathlib import Path

import pytest

import samplab
import samplab.gpu
from samplab import _samplab

ROOT = Path(__file__).resolve().parents[3]


def _device():
    try:
        import cupy

        return cupy.cuda.runtime.getDeviceCount() > 0
    except Exception:
        return False


@pytest.mark.skipif(_device(), reason="a CUDA device is here: bench/gpu.py checks it")
def test_without_cupy_or_a_device_the_error_names_what_is_missing():
    with pytest.raises(samplab.Error, match="samplab.gpu needs (CuPy and )?a CUDA device"):
        samplab.gpu.generate("sobol.owen", 16, 2)
    with pytest.raises(samplab.Error, match="samplab.gpu needs (CuPy and )?a CUDA device"):
        samplab.gpu.pixels("zsobol", (8, 8), 4)


def test_what_has_no_kernel_or_cannot_be_made_is_refused_by_name():
    with pytest.raises(samplab.Error, match=r"no GPU kernel for 'halton.owen'; these have one: sobol, "):
        samplab.gpu.generate("halton.owen", 16)
    with pytest.raises(samplab.Error, match=r"no GPU kernel for 'pmj02'"):
        samplab.gpu.pixels("pmj02", (8, 8), 4)
    with pytest.raises(samplab.Error, match=r"spp = 3: zsobol needs a power of two"):
        samplab.gpu.pixels("zsobol", (8, 8), 3)
    with pytest.raises(samplab.Error, match=r"dims = 1001: halton has at most 1000 dimensions"):
        samplab.gpu.pixels("halton", (8, 8), 4, dims=1001)
    with pytest.raises(samplab.Error, match=r"d = 1025"):
        samplab.gpu.generate("sobol", 16, 1025)


def test_every_kernel_named_is_in_the_source():
    source = _samplab.cuda_source()
    kernels = set(re.findall(r'extern "C" __global__ void (\w+)\(', source))
    kernels |= set(re.findall(r"^SAMPLAB_FILL\((\w+),", source, flags=re.M))
    named = {kernel for kernel, _ in samplab.gpu.PIXEL_SAMPLERS.values()} | {"sobol_points"}
    assert named <= kernels, named - kernels
    # one text: no include but the C library's (which NVRTC skips)
    assert re.findall(r"^#include (.*)$", source, flags=re.M) == ["<stdint.h>", "<stdint.h>"]


@pytest.mark.skipif(
    not [p for p in glob.glob(f"{sys.prefix}/lib/python*/site-packages/nvidia/cu13/lib/libnvrtc.so.*") if "builtins" not in p],
    reason="NVRTC is not installed here (crates/samplab-c/requirements-cuda.txt)",
)
def test_the_kernels_source_compiles_under_nvrtc(tmp_path):
    source = tmp_path / "samplab_gpu.cu"
    source.write_text(_samplab.cuda_source())
    run = subprocess.run([sys.executable, str(ROOT / "scripts/nvrtc-compile"), str(source)], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
