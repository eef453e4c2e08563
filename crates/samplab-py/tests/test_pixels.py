"""Pixel samplers from Python: the CLI's bytes, the shape and the errors."""

import numpy as np
import pytest

import samplab

from conftest import load_npy


@pytest.mark.parametrize(
    "spec, res, spp, dims, frames",
    [("zsobol", (7, 5), 8, 6, 2), ("sobol.padded:randomize=owen", (4, 4), 3, 3, 1), ("openqmc.pmjbn", (3, 2), 4, 5, 1)],
)
def test_pixels_equal_the_cli_bytes(cli, tmp_path, spec, res, spp, dims, frames):
    out = tmp_path / "p.npy"
    cli("pixels", spec, "--res", f"{res[0]}x{res[1]}", "--spp", spp, "--dims", dims, "--frames", frames,
        "--seed", 5, "-o", out)
    a = samplab.pixels(spec, res, spp=spp, dims=dims, frames=frames, seed=5)
    assert a.shape == (frames, res[1], res[0], spp, dims)
    assert a.tobytes() == load_npy(out).tobytes()


def test_every_pixel_sampler_is_listed_and_draws_in_the_unit_interval():
    names = [e["name"] for e in samplab.pixel_samplers()]
    assert {"zsobol", "sobol", "sobol.padded", "pmj02", "dither", "openqmc.sobolbn"} <= set(names)
    for name in names:
        a = samplab.pixels(name, (3, 2), spp=4, dims=4)
        assert ((0 <= a) & (a < 1)).all(), name
    assert any("mapping:" in d for d in samplab.pixel_samplers()[0]["details"])


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: samplab.pixels("zsobol", (4, 4), spp=3), "spp a power of two: try 2 and 4"),
        (lambda: samplab.pixels("zsobl", (4, 4), spp=4), "did you mean zsobol"),
        (lambda: samplab.pixels("zsobol", (0, 4), spp=4), "a film side is 1 to"),
        (lambda: samplab.pixels("zsobol", (4, 4), spp=4.0), "spp = 4.0: must be a whole number"),
        (lambda: samplab.pixels("zsobol", 4, spp=4), "res must be (width, height)"),
        (lambda: samplab.pixels("sobol", (4, 4), spp=4, dims=2000), "2000D is not supported"),
        (lambda: samplab.pixels("sobol", (4, 4), spp=2**40), "spp = 1099511627776: out of range"),
    ],
)
def test_bad_arguments_raise_samplab_error(call, message):
    with pytest.raises(samplab.Error, match=None) as e:
        call()
    assert message in str(e.value)


def test_the_blue_noise_mask_equals_the_cli_and_is_blue(cli, tmp_path):
    out = tmp_path / "m.npy"
    cli("mask", "--size", 32, "--channels", 2, "--seed", 3, "-o", out)
    m = samplab.blue_noise_mask(32, channels=2, seed=3)
    assert m.shape == (32, 32, 2)
    assert m.tobytes() == load_npy(out).tobytes()
    # every channel ranks every pixel once
    for c in range(2):
        assert sorted((m[:, :, c] * 1024 - 0.5).round().astype(int).ravel()) == list(range(1024))
    # blue: the lowest frequencies nearly empty (numpy's FFT, independent of samplab's test)
    p = np.abs(np.fft.fft2(m[:, :, 0] - m[:, :, 0].mean())) ** 2 / m[:, :, 0].size
    f = np.hypot(*np.meshgrid(np.fft.fftfreq(32), np.fft.fftfreq(32)))
    low = p[(f > 0) & (f <= 0.15)].mean() * 12
    assert low < 0.02, low
    with pytest.raises(samplab.Error, match="size = 3: a mask side is 4 to 256"):
        samplab.blue_noise_mask(3)


def _wrapped_gaussian_blur(image, sigma):
    """A Gaussian blur of sigma pixels (truncated at 3 sigma, normalized) that wraps around,
    by numpy's FFT: the independent reference for samplab's direct convolution."""
    if sigma == 0:
        return image
    r = int(np.ceil(3 * sigma))
    g = np.exp(-np.arange(-r, r + 1) ** 2 / (2 * sigma * sigma))
    g /= g.sum()
    h, w = image.shape
    kernel = np.zeros((h, w))
    for i, a in enumerate(g):
        for j, b in enumerate(g):
            kernel[(i - r) % h, (j - r) % w] += a * b
    return np.real(np.fft.ifft2(np.fft.fft2(image) * np.fft.fft2(kernel)))


def test_image_metrics_equal_numpy_references():
    rng = np.random.default_rng(3)
    image = rng.random((48, 64, 3))
    reference = np.full((48, 64, 3), 0.5)
    m = samplab.image_metrics(image, reference, sigma=(0, 1, 2))
    error = (image - reference) @ np.array([0.2126, 0.7152, 0.0722])
    assert m["rmse"] == pytest.approx(np.sqrt(np.mean(error**2)), rel=1e-12)
    for b in m["blurred"]:
        want = np.sqrt(np.mean(_wrapped_gaussian_blur(error, b["sigma"]) ** 2))
        assert b["rmse"] == pytest.approx(want, rel=1e-9)
    # low-frequency energy: the periodogram's mean below 1/16 cycle per pixel over the variance
    power = np.abs(np.fft.fft2(error - error.mean())) ** 2 / error.size
    fy, fx = np.meshgrid(np.fft.fftfreq(48), np.fft.fftfreq(64), indexing="ij")
    f = np.hypot(fx, fy)
    low = power[(f > 0) & (f < 1 / 16)].mean() / error.var(ddof=1)
    assert m["low_frequency"] == pytest.approx(low, rel=1e-9)
    # frames: a static error does not flicker
    stack = samplab.image_metrics(np.stack([error, error, error]))
    assert stack["flicker"] == 0 and len(stack["frames"]) == 3
    with pytest.raises(samplab.Error, match="expected"):
        samplab.image_metrics(np.zeros(5))


def test_image_metrics_fit_the_convergence_of_a_series():
    rng = np.random.default_rng(5)
    base = rng.random((32, 32)) - 0.5
    spp = [4, 16, 64]
    stack = np.stack([base * n**-0.5 for n in spp])
    c = samplab.image_metrics(stack, spp=spp)["convergence"]
    assert c["rmse"][0] == pytest.approx(-0.5, abs=1e-9)
    assert all(q == pytest.approx(-0.5, abs=1e-9) for q in c["per_pixel"])
    with pytest.raises(samplab.Error, match="increasing"):
        samplab.image_metrics(stack, spp=[4, 4, 16])
