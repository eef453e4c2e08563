"""The Python guide's examples page (docs/guide/python.md): five figures a notebook would make with samplab.

    python crates/samplab-py/examples/gallery.py OUT_DIR

writes OUT_DIR/{pattern,discrepancy,periodogram,convergence,shadows}.png (matplotlib).
The test suite runs it, so the examples cannot rot.
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import samplab  # noqa: E402


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)

    # 1. a pattern: 256 jittered points, warped to the disk
    pts = samplab.generate("jitter", n=256, seed=1)
    disk = samplab.warp("disk.concentric", pts)
    fig, axes = plt.subplots(1, 2, figsize=(8, 4))
    axes[0].scatter(*pts.T, s=4)
    axes[0].set_title("jitter, 256 points")
    axes[1].scatter(*disk.T, s=4)
    axes[1].set_title("warped: disk.concentric")
    for a in axes:
        a.set_aspect("equal")
    fig.savefig(out / "pattern.png", dpi=100)

    # 2. the star discrepancy of four samplers against n (20 sets each)
    fig, ax = plt.subplots(figsize=(6, 4))
    ns = [16, 64, 256, 1024]
    for spec in ["random", "jitter", "nrooks", "sobol.owen"]:
        d = [samplab.discrepancy("star", samplab.generate(spec, n=n, sets=20, seed=2)).mean() for n in ns]
        ax.loglog(ns, d, marker="o", label=spec)
    ax.set_xlabel("n")
    ax.set_ylabel("mean star discrepancy")
    ax.legend()
    fig.savefig(out / "discrepancy.png", dpi=100)

    # 3. a periodogram over 20 realizations (Subr & Kautz's Fig. 2)
    spec = samplab.spectrum(samplab.generate("jitter", n=256, sets=20, seed=3), res=128)
    fig, axes = plt.subplots(1, 2, figsize=(9, 4))
    axes[0].imshow(np.log10(spec["periodogram"] + 1e-6), cmap="viridis")
    axes[0].set_title("periodogram (log10), jitter")
    axes[1].plot(np.arange(1, len(spec["periodogram_radial"]) + 1), spec["periodogram_radial"])
    axes[1].set_xlabel("radial frequency")
    axes[1].set_title("radial average")
    fig.savefig(out / "periodogram.png", dpi=100)

    # 4. a convergence plot on Subr & Kautz's test case I
    study = samplab.integrate(["random", "jitter", "sobol.owen"], "quad", [16, 64, 256, 1024], sets=20, instances=5, seed=4)
    fig, ax = plt.subplots(figsize=(6, 4))
    for fit in study["fits"]:
        rows = [r for r in study["rows"] if r["sampler"] == fit["sampler"]]
        ax.loglog([r["n"] for r in rows], [r["relative_variance"] for r in rows], marker="o",
                  label="%s (slope %.2f)" % (fit["sampler"], fit["exponent"]))
    ax.set_xlabel("N")
    ax.set_ylabel("relative variance")
    ax.legend()
    fig.savefig(out / "convergence.png", dpi=100)

    # 5. a soft shadow: jittered and uniformly jittered light samples, and their errors
    settings = dict(light="disk", n=16, res=(96, 64), seed=5)
    reference = samplab.render("spheres", reference_samples=1024, **settings)
    fig, axes = plt.subplots(1, 3, figsize=(12, 3))
    axes[0].imshow(np.clip(reference["rgb"], 0, 1))
    axes[0].set_title("reference")
    for ax, sampler in zip(axes[1:], ["jitter", "jitter.uniform"]):
        img = samplab.render("spheres", sampler=sampler, **settings)
        e = samplab.image_errors(img, reference, penumbra=True)
        ax.imshow(np.clip(img["rgb"], 0, 1))
        ax.set_title("%s: penumbra RMSE %.3f" % (sampler, e["rmse"]))
    fig.savefig(out / "shadows.png", dpi=100)
    plt.close("all")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "gallery"))
