"""samplab for Python: sampling patterns for Monte Carlo integration in rendering.

Generate point sets with every strategy of Shirley 1991, Subr & Kautz 2013, Sbert et al.
2006 and Ramamoorthi et al. 2012 and the modern low-discrepancy sequences; warp them;
measure their discrepancies and spectra; run integration studies; reproduce the papers.
Everything runs in the Rust core (the GIL is released), with the CLI's seeds: the same
arguments give the same bytes as ``samplab generate`` and friends. Ctrl-C stops a long
call: ``KeyboardInterrupt`` is raised, and nothing is returned or written.

The registries (``samplers()``, ``metrics()``, ``warps()``, ``integrands()``, ``formats()``,
``scenes()``) list every name, alias, parameter (default, range) and reference.
``samplab.qmc.Engine`` is a ``scipy.stats.qmc.QMCEngine`` for every sampler.
"""

from __future__ import annotations

import json
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

import numpy as np

from . import _samplab
from ._samplab import Error, __version__


class UnknownNameError(Error, LookupError):
    """An unknown sampler, integrand, metric, warp or other registered name: ``kind``,
    ``name`` and the nearest known ``suggestions``."""


class MemoryLimitError(Error, MemoryError):
    """A computation refused before it started for the memory it needs: ``need`` and
    ``available``, in bytes."""


class FileError(Error, OSError):
    """A file that cannot be read or written (``path``; the message has the reason)."""

    def __new__(cls, *args: Any, **kwargs: Any) -> "FileError":
        # OSError's layout is the one instances have: unpicklers that call cls.__new__
        # (tblib's, which Dask installs) must reach OSError's, not ValueError's
        return OSError.__new__(cls, *args)


class WorkLimitError(Error):
    """An exact computation refused before it started: its estimated ``work`` (steps) is
    over the ``limit``."""


__all__ = [
    "Error",
    "FileError",
    "MemoryLimitError",
    "UnknownNameError",
    "WorkLimitError",
    "Study",
    "StudyResult",
    "__version__",
    "DEFAULT_SEED",
    "samplers",
    "metrics",
    "warps",
    "integrands",
    "cubature",
    "reference",
    "predict",
    "formats",
    "scenes",
    "generate",
    "pixel_samplers",
    "pixels",
    "blue_noise_mask",
    "image_metrics",
    "is_sequence",
    "sequence_points",
    "warp",
    "save",
    "load",
    "discrepancy",
    "discrepancy_flags",
    "spectrum",
    "integrate",
    "integrand",
    "reproduce",
    "render",
    "image_errors",
    "read_exr",
]

#: The seed the CLI uses when none is given.
DEFAULT_SEED: int = _samplab.default_seed()


def _seed(seed: Optional[int]) -> int:
    if seed is None:
        return DEFAULT_SEED
    if isinstance(seed, (bool, float)) or not isinstance(seed, (int, np.integer)):
        raise Error(f"seed must be a whole number in [0, 2^64), got {seed!r}")
    if not 0 <= int(seed) < 2**64:
        raise Error(f"seed {seed} is out of range [0, 2^64)")
    return int(seed)


def _count(name: str, value: Any) -> int:
    if isinstance(value, (bool, float)) or not isinstance(value, (int, np.integer)):
        raise Error(f"{name} = {value!r}: must be a whole number")
    if not 0 <= value < 2**64:
        raise Error(f"{name} = {value}: out of range [0, 2^64)")
    return int(value)


def _counts(name: str, value: Any) -> List[int]:
    """One count or a sequence of counts, each checked by ``_count`` (a float such as 64.0
    is refused as one count, not iterated)."""
    iterable = hasattr(value, "__iter__") and not isinstance(value, (str, bytes))
    values = list(value) if iterable else [value]
    return [_count(name, v) for v in values]


def _points(points: Any, what: str = "points", *, stack: bool) -> np.ndarray:
    """A C-contiguous float64 array of shape (n, d), or (sets, n, d) when ``stack``
    (an (n, d) array is then one set)."""
    try:
        a = np.asarray(points)
    except Exception as e:  # noqa: BLE001 - any conversion failure is bad input
        raise Error(f"{what}: not an array of numbers ({e})") from None
    if a.dtype.kind not in "fiu":
        raise Error(f"{what}: expected numbers, got dtype {a.dtype}")
    a = np.ascontiguousarray(a, dtype=np.float64)
    if stack and a.ndim == 2:
        a = a[np.newaxis]
    want = 3 if stack else 2
    if a.ndim != want:
        shape = "(sets, n, d) or (n, d)" if stack else "(n, d)"
        raise Error(f"{what}: expected shape {shape}, got {a.shape}")
    if 0 in a.shape:
        raise Error(f"{what}: empty (shape {a.shape}); give at least one set of one point")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        index = np.unravel_index(bad[0], a.shape)
        raise Error(f"{what}{list(index)} is {a[index]} (not finite)")
    return a


def _registry(kind: str) -> List[Dict[str, Any]]:
    return _samplab.registry(kind)


def samplers() -> List[Dict[str, Any]]:
    """Every sampler: name, aliases, summary, params (name, kind, default, range, doc),
    references, and details (counts it can make, dimensions)."""
    return _registry("samplers")


def metrics() -> List[Dict[str, Any]]:
    """Every discrepancy metric, with its flags in ``details`` (L2, shift invariance,
    lower bound)."""
    return _registry("metrics")


def warps() -> List[Dict[str, Any]]:
    """Every warp (square to disk, tent, Gaussian, hemispheres), with its dimensions."""
    return _registry("warps")


def integrands() -> List[Dict[str, Any]]:
    """Every integrand family with an exact integral (the papers' test cases)."""
    return _registry("integrands")


def formats() -> List[Dict[str, Any]]:
    """Every point-file format of the CLI."""
    return _registry("formats")


def scenes() -> List[Dict[str, Any]]:
    """Every built-in scene of the renderer."""
    return _registry("scenes")


def generate(spec: str, n: int, d: int = 2, seed: Optional[int] = None, sets: Optional[int] = None) -> np.ndarray:
    """Points of the sampler ``spec`` (e.g. ``"jitter"``, ``"sobol.owen"``,
    ``"GJittered:0.25"``) in [0, 1)^d, float64.

    Returns an (n, d) array, or (sets, n, d) when ``sets`` is given. Set k is seeded by a
    hash of ``seed`` and k, as ``samplab generate`` does: the bytes equal the CLI's for the
    same arguments. A count the sampler cannot make (a grid asked for 15 points) raises
    ``samplab.Error`` naming the nearest counts that work.
    """
    m = 1 if sets is None else _count("sets", sets)
    out = _samplab.generate(spec, _count("n", n), _count("d", d), _seed(seed), m)
    return out[0] if sets is None else out


def pixel_samplers() -> List[Dict[str, Any]]:
    """Every pixel sampler family (``"zsobol"``, ``"sobol.padded"``, ``"pmj02.bn"``,
    ``"dither"``, ``"openqmc.sobolbn"``, ...): name, aliases, summary, params, references,
    and details (sample counts, dimensions, and how the family becomes a pixel sampler)."""
    return _registry("pixels")


def pixels(
    spec: str, res: Sequence[int], spp: int, dims: int = 2, frames: int = 1, seed: Optional[int] = None
) -> np.ndarray:
    """Every value the pixel sampler ``spec`` gives a film of ``res = (width, height)``
    pixels: a float64 array of shape (frames, height, width, spp, dims), whose entry
    [f, y, x, i, d] is dimension d of sample i of pixel (x, y) in frame f. A pure function
    of (seed, pixel, frame, index, dimension): the bytes equal ``samplab pixels`` with the
    same arguments. A sample count the family does not take (ZSobol asked for 3 spp)
    raises ``samplab.Error`` naming the nearest that work.
    """
    try:
        if isinstance(res, (str, bytes)):
            raise TypeError
        width, height = res
    except (TypeError, ValueError):
        raise Error(f"res must be (width, height), got {res!r}") from None
    keys = {"width": width, "height": height, "spp": spp, "dims": dims, "frames": frames}
    for name, value in keys.items():
        if _count(name, value) >= 2**32:
            raise Error(f"{name} = {value}: out of range [0, 2^32)")
    film = (int(width), int(height), int(spp), int(dims))
    return _samplab.pixels(spec, film, int(frames), _seed(seed))


def blue_noise_mask(size: int = 64, channels: int = 1, seed: Optional[int] = None) -> np.ndarray:
    """A tileable blue-noise mask by void-and-cluster (Ulichney 1993): a float64 array of
    shape (size, size, channels), each channel an independent ranking of the pixels as
    (rank + 1/2) / size^2; the masks of the ``dither`` and ``pmj02.bn`` pixel samplers, and
    the bytes of ``samplab mask -o FILE.npy``. ``size`` is 4 to 256, ``channels`` 1 to 4."""
    return _samplab.blue_noise_mask(_count("size", size), _count("channels", channels), _seed(seed))


def image_metrics(
    image: Any, reference: Any = None, sigma: Sequence[float] = (0, 1, 2, 4), spp: Optional[Sequence[float]] = None
) -> dict:
    """How an image's error is spread over the screen, as ``samplab image-metrics --json``
    reports it: RMSE, the RMSE after Gaussian blurs of ``sigma`` pixels beside white noise's
    of the same standard deviation, the low-frequency energy (power below 1/16 cycle per
    pixel over the variance: 1 for white noise), and the radial power spectrum.

    ``image`` is (height, width) values, (height, width, 3) linear RGB (taken as Rec. 709
    luminance), or a stack of frames of either; ``reference`` (same shape, or one frame for
    every frame) is subtracted first (without it, ``image`` is the error). One frame gives
    one dict; several give ``{"frames": [dict, ...], "flicker": f}``, f the RMS of the
    frame-to-frame change of the error over its RMS (independent frames: sqrt(2), static: 0);
    with ``spp`` (one count per image, increasing) the images are a convergence series and
    ``"convergence"`` replaces the flicker: slopes of ln(error) against ln(spp) for the RMSE
    (with its 95% interval), each blurred RMSE, and the per-pixel quartiles.
    """

    def luminance(a: np.ndarray, name: str) -> np.ndarray:
        a = np.asarray(a, dtype=np.float64)
        if a.ndim >= 3 and a.shape[-1] == 3:
            a = a @ np.array([0.2126, 0.7152, 0.0722])
        if a.ndim not in (2, 3):
            raise Error(f"{name}: expected (height, width), (height, width, 3) or a stack of frames, got shape {a.shape}")
        return a

    error = luminance(image, "image")
    if reference is not None:
        ref = luminance(reference, "reference")
        if ref.shape != error.shape and ref.shape != error.shape[-2:]:
            raise Error(f"reference: shape {ref.shape} does not match the image's {error.shape}")
        error = error - ref
    single = error.ndim == 2
    frames = np.ascontiguousarray(error[None] if single else error)
    counts = None if spp is None else [float(n) for n in spp]
    result = json.loads(_samplab.image_metrics(frames, [float(s) for s in sigma], counts))
    return result["frames"][0] if single and spp is None else result


def is_sequence(spec: str) -> bool:
    """Whether ``spec`` is a progressive sequence (Sobol', Halton): extensible, with random
    access."""
    return _samplab.is_sequence(spec)


def sequence_points(spec: str, start: int, n: int, d: int = 2, seed: Optional[int] = None) -> np.ndarray:
    """Points ``start .. start + n`` of the sequence ``spec``, randomized as
    ``generate(spec, ..., seed=seed)``: ``start = 0`` gives the same points."""
    return _samplab.sequence_points(spec, _count("start", start), _count("n", n), _count("d", d), _seed(seed))


def warp(name: str, points: Any) -> np.ndarray:
    """Warp an (n, d) array of points in [0, 1)^d (``"disk.concentric"``, ``"tent"``,
    ``"hemisphere.cosine"``, ...); rejection warps drop points."""
    return _samplab.warp(name, _points(points, stack=False))


def save(path: str, points: Any, format: Optional[str] = None, header: Optional[Sequence[str]] = None) -> None:
    """Write an (n, d) set or a (sets, n, d) stack to ``path`` in ``format`` (``"text"``,
    ``"csv"``, ``"npy"``, ``"json"``; by default from the extension), atomically, as
    ``samplab generate -o`` does. ``header`` lines go into text comments or JSON metadata."""
    _samplab.save(str(path), _points(points, stack=True), format, None if header is None else list(header))


def load(path: str, format: Optional[str] = None) -> List[np.ndarray]:
    """Every set of a point file as a list of (n, d) float64 arrays (the formats of
    ``formats()``; by default from the extension). Malformed or non-finite data raises
    ``samplab.Error`` naming the file and line."""
    return _samplab.load(str(path), format)


def discrepancy(metric: str, points: Any, max_work: Optional[float] = None) -> Union[float, np.ndarray]:
    """The discrepancy ``metric`` (``"star"``, ``"extreme"``, ``"l2-star"``, ``"centered"``,
    ``"wraparound"``, ``"mixture"``, ``"projected:angle=30"``, ...) of an (n, d) set, or of
    each set of a (sets, n, d) stack. Values are never squared (scipy squares CD, WD and
    MD). Points must lie in [0, 1]^d; exact algorithms whose cost would exceed ``max_work``
    steps are refused before any work.
    """
    a = _points(points, stack=True)
    v = np.asarray(_samplab.discrepancy(metric, a, None if max_work is None else float(max_work)))
    return float(v[0]) if np.ndim(points) == 2 else v


def discrepancy_flags(metric: str) -> Dict[str, Any]:
    """The canonical spec of ``metric`` and its flags: squared, l2_closed_form,
    toroidal_shift_invariant, lower_bound (as ``samplab discrepancy --json``)."""
    return json.loads(_samplab.metric_flags(metric))


def spectrum(points: Any, res: int = 128, direct: bool = False, tolerance: float = 1e-9) -> Dict[str, np.ndarray]:
    """Periodogram, amplitude of the expected spectrum and variance of the spectrum of a
    (sets, n, d) stack (at least two sets), each an R^d array with DC at index R/2, and
    their radial averages (``*_radial``) and anisotropies in dB (``*_anisotropy_db``). The fast path
    (a non-uniform FFT) holds ``tolerance`` relative to DC; ``direct=True`` is the exact DFT.
    """
    return _samplab.spectrum(_points(points, stack=True), _count("res", res), bool(direct), float(tolerance))


def reference(f: Any, d: int) -> float:
    """The integral of your function ``f`` over [0, 1]^d for reference, where you do not know
    it: ``cubature`` to a relative 1e-9 (at most 2^22 points x 16 randomizations), or an
    error saying how far it got (then give ``exact=`` yourself)."""
    return float(_samplab.reference(f, _count("d", d)))


def _by_columns(f: Any, columns: bool) -> Any:
    """``f`` called with x of shape (n, d), where ``columns`` says it takes (d, n)."""
    if not columns:
        return f
    if not callable(f):
        raise Error("columns=True: only a callable integrand takes points")

    def by_rows(x: Any) -> Any:
        return f(x.T)

    by_rows.__name__ = getattr(f, "__name__", "f")
    return by_rows


def integrate(
    samplers: Union[str, Sequence[str]],
    integrand: Any,
    n: Union[int, Sequence[int]],
    sets: int = 50,
    instances: int = 10,
    seed: Optional[int] = None,
    *,
    d: Optional[int] = None,
    exact: Optional[float] = None,
    columns: bool = False,
) -> Dict[str, List[Dict[str, Any]]]:
    """Bias, variance and convergence of samplers on an integrand family, as ``samplab
    integrate --json``: ``{"rows": [...], "fits": [...]}`` (a row per sampler and count:
    relative mean, relative variance, RMSE, N^2 MSE and the closed form where one applies;
    a fit per sampler: the convergence exponent and its 95% interval).

    ``integrand`` is a family spec (``"quad"``, ``"keister:d=3"``) or your own vectorized
    function ``f(x)``, x of shape (n, d), returning n values: give its dimension ``d`` and
    its integral ``exact`` if you know it (otherwise ``samplab.reference`` computes it to a
    relative 1e-9); it is one function, so ``instances`` does not apply. ``columns=True``: x of shape (d, n), scipy's
    convention."""
    names = [samplers] if isinstance(samplers, str) else list(samplers)
    integrand = _by_columns(integrand, columns)
    if callable(integrand):
        if d is None:
            raise Error("a callable integrand needs d= (its dimension)")
        given = (_count("d", d), float(reference(integrand, d) if exact is None else exact))
        return json.loads(
            _samplab.integrate_given(names, integrand, _counts("n", n), _count("sets", sets), _seed(seed), given)
        )
    return json.loads(
        _samplab.integrate(
            names,
            integrand,
            _counts("n", n),
            _count("sets", sets),
            _count("instances", instances),
            _seed(seed),
        )
    )


def cubature(
    integrand: Any,
    d: Optional[int] = None,
    *,
    abs_tol: Optional[float] = None,
    rel_tol: Optional[float] = None,
    rule: Optional[str] = None,
    sampler: Optional[str] = None,
    level: Optional[float] = None,
    replications: Optional[int] = None,
    min_n: Optional[int] = None,
    max_n: Optional[int] = None,
    seed: Optional[int] = None,
    exact: Optional[float] = None,
    columns: bool = False,
) -> Dict[str, Any]:
    """The integral of ``integrand`` over [0, 1]^d to a tolerance, as ``samplab cubature
    --json``: ``{"estimate", "bound", "kind", "converged", "n", "evaluations", "steps",
    "seconds", "integrand", "exact"}``.

    ``integrand`` is a family spec (``"keister:d=8"``) or a vectorized callable ``f(x)``, x of
    shape (n, d), returning n values (give ``d``, and ``exact`` when the integral is known);
    ``columns=True`` passes x of shape (d, n) instead, as ``scipy.integrate.qmc_quad`` does.
    The points per randomization are doubled from ``min_n`` (256; 1024 for the guaranteed
    rules) until the bound is at most ``max(abs_tol, rel_tol |estimate|)`` (1e-3, 0) or
    ``max_n`` (2^20) is reached (``converged`` says which); a sequence's earlier points are
    kept. ``rule`` picks the bound: ``"replicated"`` (the default; probabilistic, Student's
    t interval at ``level`` (0.99) over ``replications`` (16) randomizations of
    ``sampler``, ``sobol.owen`` by default), ``"net"`` or ``"lattice"`` (guaranteed for
    integrands in the cone of Hickernell & Jimenez Rugama 2016, on one randomized digital
    net, ``net.lms``, or shifted lattice sequence with the baker's transform). Unset
    keywords take the library's defaults."""
    if callable(integrand) and d is None:
        raise Error("d: give the dimension of a callable integrand")
    integrand = _by_columns(integrand, columns)
    given: Dict[str, Any] = {}
    for name, value in (("abs_tol", abs_tol), ("rel_tol", rel_tol), ("level", level)):
        if value is not None:
            given[name] = float(value)
    for name, value in (("replications", replications), ("min_n", min_n), ("max_n", max_n)):
        if value is not None:
            given[name] = _count(name, value)
    for name, text in (("rule", rule), ("sampler", sampler)):
        if text is not None:
            given[name] = str(text)
    if seed is not None:
        given["seed"] = _seed(seed)
    dims = 0 if d is None else _count("d", d)
    return json.loads(_samplab.cubature(integrand, dims, None if exact is None else float(exact), json.dumps(given)))


def predict(
    integrand: Any,
    samplers: Union[None, str, Sequence[str]] = None,
    n: Union[int, Sequence[int]] = (16, 64, 256, 1024),
    res: int = 128,
    sets: int = 16,
    measure: Optional[int] = None,
    shift: bool = False,
    seed: Optional[int] = None,
    d: int = 2,
    exact: Union[None, float, Sequence[float]] = None,
    cache: bool = True,
) -> Dict[str, Any]:
    """The variance of each sampler on one or more integrands predicted from spectra, as
    ``samplab predict --json``: ``{"integrands", "rows", "ranking", "rates", "skipped"}``
    (a row per integrand, sampler and count: the predicted variance of the estimator over a
    random toroidal shift of each set and its standard error, the radial form of the same,
    where the sampler's spectrum comes from, and the measured mean squared error over
    ``measure`` realizations when given, shifted when ``shift``; the ranking per integrand
    by predicted variance at the largest count with the fitted exponents; per sampler the
    small-frequency exponent of its spectrum with the best- and worst-case convergence
    exponents it implies).

    ``integrand`` is a spec (``"disk:r=0.3"``), a 2D float array (values on a grid over the
    unit square, row 0 at y = 0, box lookups: an image), a vectorized callable ``f(x)``
    taking an (m, d) array and returning m values (``d`` 1 or 2; its spectrum is the FFT of
    its values at the midpoints of a fine grid, the error of that estimate stated), or a
    list of these. ``exact``: the integral of each callable, in order, needed to measure.
    ``samplers=None`` ranks every registered sampler of the integrands' dimension.
    ``cache``: read and keep measured sampler spectra in the user's cache (``$SAMPLAB_CACHE``,
    else ``$XDG_CACHE_HOME/samplab``, else ``~/.cache/samplab``)."""
    names = [] if samplers is None else [samplers] if isinstance(samplers, str) else list(samplers)
    given = list(integrand) if isinstance(integrand, (list, tuple)) else [integrand]
    given = [np.ascontiguousarray(g, dtype=np.float64) if isinstance(g, np.ndarray) else g for g in given]
    integrals = [] if exact is None else [exact] if isinstance(exact, (int, float)) else list(exact)
    measured = None if measure is None else (_count("measure", measure), bool(shift))
    return json.loads(
        _samplab.predict(
            names,
            given,
            _counts("n", n),
            _count("res", res),
            _count("sets", sets),
            measured,
            _seed(seed),
            _count("d", d),
            [float(v) for v in integrals],
            bool(cache),
        )
    )


def integrand(spec: str, points: Any, instance: int = 0, seed: Optional[int] = None) -> "tuple[np.ndarray, float]":
    """Instance ``instance`` of the integrand family ``spec`` (as a study with ``seed``
    draws it): its values at the rows of an (n, d) array, and its exact integral."""
    values, exact = _samplab.integrand_eval(spec, _count("instance", instance), _seed(seed), _points(points, stack=False))
    return values, exact


def reproduce(
    out: str = "report",
    full: bool = False,
    only: Optional[Sequence[str]] = None,
    seed: Optional[int] = None,
    force: bool = False,
    progress: Optional[Callable[[str, str, int, int], Any]] = None,
) -> List[Dict[str, str]]:
    """Reproduce the papers into the folder ``out`` (replaced only when the run completes),
    as ``samplab reproduce``; returns each claim's paper, id and verdict. An existing ``out``
    that holds files samplab did not write is refused unless ``force`` (as ``--force``).

    Nothing is drawn on the terminal: ``progress(paper, experiment, done, total)``, when
    given, is called as each experiment starts (``done`` 0), learns its length, advances (at
    most once per percent) and finishes (``done == total``), from any thread: experiments run
    side by side, so the calls of several interleave. An exception it raises stops the run
    and is raised here."""
    if progress is not None and not callable(progress):
        raise Error(f"progress: {progress!r} is not callable")
    keys = None if only is None else [only] if isinstance(only, str) else list(only)
    return json.loads(_samplab.reproduce(str(out), bool(full), keys, None if seed is None else _seed(seed), bool(force), progress))


def render(scene: str, light: Optional[str] = None, reference_samples: Optional[int] = None, allow_paths_outside_scene: bool = False, **settings: Any) -> Dict[str, Any]:
    """Render ``scene`` (a built-in scene, see ``scenes()``, or a Mitsuba 3 XML file),
    lit by ``light`` (``"square"``, ``"disk"``, ``"linear"``, ``"gaussian"``) if given.

    Keywords are the CLI's flags, with the CLI's defaults: ``sampler`` (light strategy,
    ``"jitter"``), ``n`` (16), ``spp`` (1), ``mode`` (``"visibility"``, ``"direct"``,
    ``"obscurance"``, ``"path"``), ``max_depth`` (path mode's most segments, 5), ``pixel``
    (``"center"``, ``"area"``), ``pixel_sampler``,
    ``lens_sampler``, ``time_sampler``, ``gloss_sampler`` (``"sobol.owen"``), ``pattern``
    (``"estimate"``, ``"pixel"``), ``disk_map``, ``range``, ``interleave`` ((w, h)), ``res``
    ((width, height)), ``seed``. With ``reference_samples``, the converged reference the
    CLI renders for these settings instead. A Mitsuba scene may name meshes only inside its
    own folder unless ``allow_paths_outside_scene`` (for scenes you trust).

    Returns ``{"rgb": (h, w, 3) float32, "visibility": (h, w) float32, "camera_rays",
    "shadow_rays"}``: the same numbers ``samplab render -o x.exr`` writes.
    """
    if "seed" in settings:
        settings["seed"] = _seed(settings["seed"])
    samples = None if reference_samples is None else _count("reference_samples", reference_samples)
    return _samplab.render(scene, light, settings, samples, bool(allow_paths_outside_scene))


def _image(a: Any, what: str, ndim: int) -> np.ndarray:
    arr = np.ascontiguousarray(np.asarray(a), dtype=np.float32)
    if arr.ndim != ndim:
        raise Error(f"{what}: expected {ndim} dimensions, got shape {arr.shape}")
    return arr


def image_errors(image: Any, reference: Any, penumbra: bool = False) -> Dict[str, float]:
    """Errors of ``image`` against ``reference`` on luminance (as ``samplab render --json``):
    pixels, mse, rmse, relative, mean_abs, sd_abs, max_abs, bias. Each argument is a
    ``render()`` result or an (h, w, 3) array; ``penumbra`` restricts the comparison to the
    reference's 0 < V < 1 (it needs the reference's visibility)."""
    def parts(x: Any, what: str):
        if isinstance(x, dict):
            v = x.get("visibility")
            return _image(x["rgb"], what, 3), None if v is None else _image(v, what + " visibility", 2)
        return _image(x, what, 3), None

    rgb, _ = parts(image, "image")
    ref_rgb, ref_vis = parts(reference, "reference")
    return json.loads(_samplab.image_errors(rgb, ref_rgb, ref_vis, bool(penumbra)))


def read_exr(path: str) -> Dict[str, Any]:
    """An OpenEXR image as ``samplab render`` writes it: ``{"rgb": (h, w, 3), "visibility":
    (h, w) or None}``, float32."""
    return _samplab.read_exr(str(path))


from .study import Study, StudyResult  # noqa: E402  (study.py imports this package's names)
