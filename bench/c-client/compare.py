#!/usr/bin/env python3
"""The RMSE of each pixel sampler in a renderer that links samplab's C library
(bench/c-client/pathtracer.c), against a reference of `independent` samples, and its ratio
to `independent`'s at the same spp. The reference's own noise is taken out: two references
of independent seeds give its mean squared error (half their mean squared difference),
which is subtracted from each measured one. RMSE is the root of the mean over pixels and
seeds. Run by bench/c-client/run (standard library only)."""
import argparse
import math
import struct
import subprocess
import tempfile

SAMPLERS = ["independent", "stratified", "sobol", "zsobol", "halton", "pmj02", "openqmc.sobol"]


def render(renderer, spec, size, spp, seed, out):
    info = subprocess.run(
        [renderer, spec, str(size), str(spp), "24", str(seed), out], check=True, capture_output=True, text=True
    ).stdout.strip()
    with open(out, "rb") as f:
        return struct.unpack(f"{size * size}f", f.read()), info


def mse(a, b):
    return sum((x - y) ** 2 for x, y in zip(a, b)) / len(a)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--renderer", required=True)
    p.add_argument("--size", type=int, default=32)
    p.add_argument("--seeds", type=int, default=4)
    p.add_argument("--spp", default="4,16,64,256")
    p.add_argument("--reference-spp", type=int, default=16384)
    a = p.parse_args()
    spps = [int(s) for s in a.spp.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/img.f32"
        ref1, _ = render(a.renderer, "independent", a.size, a.reference_spp, 1_000_001, out)
        ref2, _ = render(a.renderer, "independent", a.size, a.reference_spp, 1_000_002, out)
        ref = [(x + y) / 2 for x, y in zip(ref1, ref2)]
        # the averaged reference's own MSE: a quarter of the two references' mean squared difference
        noise = mse(ref1, ref2) / 4
        print(f"{a.size}x{a.size} pixels, reference {2 * a.reference_spp} spp (its MSE {noise:.3g}, taken out), "
              f"{a.seeds} seeds, 24 dimensions then padding")
        print("| sampler | " + " | ".join(f"{s} spp RMSE (ratio)" for s in spps) + " |")
        print("|---|" + "---|" * len(spps))
        base = {}
        for spec in SAMPLERS:
            cells = []
            for spp in spps:
                errors = [mse(render(a.renderer, spec, a.size, spp, seed, out)[0], ref) for seed in range(a.seeds)]
                rmse = math.sqrt(max(sum(errors) / len(errors) - noise, 0.0))
                base.setdefault(spp, rmse)
                cells.append(f"{rmse:.4f} ({rmse / base[spp]:.2f})")
            print(f"| {spec} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
