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

import functools
import inspect
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

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
    "Sampler",
    "generate",
    "pixel_samplers",
    "pixels",
    "pixel_seed",
    "blue_noise_mask",
    "image_metrics",
    "is_sequence",
    "sequence_points",
    "warp",
    "save",
    "load",
    "discrepancy",
    "t_values",
    "conform",
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
    if type(seed) is int and 0 <= seed < 2**64:  # the common case, checked first (it is cheap)
        return seed
    if isinstance(seed, (bool, float)) or not isinstance(seed, (int, np.integer)):
        raise Error(f"seed must be a whole number in [0, 2^64), got {seed!r}")
    if not 0 <= int(seed) < 2**64:
        raise Error(f"seed {seed} is out of range [0, 2^64)")
    return int(seed)


def _count(name: str, value: Any) -> int:
    if type(value) is int and 0 <= value < 2**64:  # as in _seed
        return value
    if isinstance(value, (bool, float)) or not isinstance(value, (int, np.integer)):
        raise Error(f"{name} = {value!r}: must be a whole number")
    if not 0 <= value < 2**64:
        raise Error(f"{name} = {value}: out of range [0, 2^64)")
    return int(value)


def _real(name: str, value: Any, finite: bool = False) -> float:
    """A real number (a Python or NumPy int or float, not a bool or a string), finite when
    ``finite`` (samplab.Error naming it otherwise, as ``_count``)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise Error(f"{name} = {value!r}: expected a real number, not {type(value).__name__}")
    x = float(value)
    if finite and not np.isfinite(x):
        raise Error(f"{name} = {x}: must be a finite number")
    return x


def _reals(name: str, values: Any, finite: bool = False) -> List[float]:
    """``_real`` of each of a sequence."""
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise Error(f"{name} = {values!r}: expected a sequence of real numbers")
    return [_real(name, v, finite) for v in values]


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
    given = a.ndim
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
        # the index in the caller's shape, as plain integers (numpy's repr of its own
        # integers would read points[np.int64(0), ...])
        index = [int(i) for i in np.unravel_index(bad[0], a.shape)][a.ndim - given :]
        raise Error(f"{what}{index} is {a.flat[bad[0]]} (not finite)")
    return a


def _registry(kind: str) -> List[Dict[str, Any]]:
    return _samplab.registry(kind)


def samplers() -> List[Dict[str, Any]]:
    """Every registered sampler, as ``samplab list samplers`` lists it.

    Returns
    -------
    list of dict
        Per entry: ``name``, ``aliases``, ``summary``, ``params`` (name, kind, default,
        range, doc), ``references`` and ``details`` (the counts it can make, its
        dimensions).

    Examples
    --------
    >>> names = [s["name"] for s in samplab.samplers()]
    >>> "sobol.owen" in names and "jitter" in names
    True
    """
    return _registry("samplers")


def metrics() -> List[Dict[str, Any]]:
    """Every discrepancy and spacing metric.

    Returns
    -------
    list of dict
        Per entry its name, aliases, summary, parameters and references; ``details``
        holds its flags (L2, shift invariance, lower bound).

    Examples
    --------
    >>> "l2-star" in [m["name"] for m in samplab.metrics()]
    True
    """
    return _registry("metrics")


def warps() -> List[Dict[str, Any]]:
    """Every warp (square to disk, tent, Gaussian, hemispheres), with its dimensions.

    Returns
    -------
    list of dict
        Per entry its name, aliases, summary and references.

    Examples
    --------
    >>> "disk.concentric" in [w["name"] for w in samplab.warps()]
    True
    """
    return _registry("warps")


def integrands() -> List[Dict[str, Any]]:
    """Every integrand family with an exact integral (the papers' test cases, Genz's
    families, Keister, Ishigami, ...).

    Returns
    -------
    list of dict
        Per entry its name, aliases, summary, parameters and references.

    Examples
    --------
    >>> "keister" in [f["name"] for f in samplab.integrands()]
    True
    """
    return _registry("integrands")


def formats() -> List[Dict[str, Any]]:
    """Every point-file format of the CLI (text, CSV, .npy, JSON).

    Returns
    -------
    list of dict
        Per format its name, aliases and summary.

    Examples
    --------
    >>> sorted(f["name"] for f in samplab.formats())
    ['csv', 'json', 'npy', 'text']
    """
    return _registry("formats")


def scenes() -> List[Dict[str, Any]]:
    """Every built-in scene of the renderer.

    Returns
    -------
    list of dict
        Per scene its name, aliases and summary.

    Examples
    --------
    >>> "sphere-box" in [s["name"] for s in samplab.scenes()]
    True
    """
    return _registry("scenes")


class Sampler:
    """A sampler built once from its spec, for ``d`` dimensions.

    Building it checks the name, the parameters and the dimensions once; its sets then come
    from the object (the bytes of ``samplab generate`` with the same spec and seed). It
    pickles as its spec and dimensions, so Dask's and multiprocessing's workers rebuild the
    same sampler.

    Parameters
    ----------
    spec : str
        The sampler's spec, e.g. ``"sobol.owen"`` (``samplers()`` lists them).
    d : int, default 2
        Dimensions.

    Raises
    ------
    samplab.Error
        An unknown name (``UnknownNameError``, with suggestions), a bad parameter, or
        dimensions the sampler does not make (naming those it does).

    Examples
    --------
    >>> s = samplab.Sampler("sobol.owen", d=4)
    >>> s.d, s.is_sequence
    (4, True)
    >>> s.generate(8, seed=1).shape
    (8, 4)
    >>> import pickle
    >>> again = pickle.loads(pickle.dumps(s))
    >>> bool((again.generate(8, seed=1) == s.generate(8, seed=1)).all())
    True
    """

    __slots__ = ("_native", "_given", "_d")

    def __init__(self, spec: str, d: int = 2) -> None:
        if not isinstance(spec, str):
            raise TypeError(f"spec must be a str, got {type(spec).__name__}")
        native = _samplab.Sampler(spec)
        d = _count("d", d)
        native.check_dims(d)
        self._native, self._given, self._d = native, spec, d

    @property
    def spec(self) -> str:
        """The canonical spec: the name and every parameter, defaults included."""
        return self._native.spec

    @property
    def d(self) -> int:
        """Dimensions."""
        return self._d

    @property
    def is_sequence(self) -> bool:
        """Whether it is a progressive sequence (Sobol', Halton): extensible, with random
        access (``points``)."""
        return self._native.is_sequence()

    def generate(self, n: int, seed: Optional[int] = None, sets: Optional[int] = None) -> np.ndarray:
        """``n`` points in [0, 1)^d: float64 of shape (n, d), or (sets, n, d) when ``sets``
        is given; set k is seeded by a hash of ``seed`` and k, as ``samplab generate`` does.
        A count the sampler cannot make raises ``samplab.Error`` naming the nearest ones."""
        m = 1 if sets is None else _count("sets", sets)
        out = self._native.generate(_count("n", n), self._d, _seed(seed), m)
        return out[0] if sets is None else out

    def points(self, start: int, n: int, seed: Optional[int] = None) -> np.ndarray:
        """Points ``start .. start + n`` of a sequence, float64 of shape (n, d), randomized as
        ``generate(..., seed=seed)`` (so ``start = 0`` gives its first points)."""
        return self._native.points(_count("start", start), _count("n", n), self._d, _seed(seed))

    def pixels(self, res: Sequence[int], spp: int, frames: int = 1, seed: Optional[int] = None) -> np.ndarray:
        """The sequence served per pixel: float64 of shape (frames, height, width, spp, d),
        entry [f, y, x, i] point i of ``generate(spp, seed=pixel_seed(seed, x, y, f))`` (so
        ``"sobol.owen"`` names one scramble for point sets and pixels). Only a sequence
        (``is_sequence``) serves pixels; ``samplab.pixels`` gives the pixel samplers."""
        return _film_values(self._given, res, spp, self._d, frames, seed, per_pixel=True)

    def __reduce__(self) -> Tuple[Any, Tuple[str, int]]:
        return (Sampler, (self._given, self._d))

    def __repr__(self) -> str:
        return f"samplab.Sampler({self._given!r}, d={self._d})"


def generate(spec: str, n: int, d: int = 2, seed: Optional[int] = None, sets: Optional[int] = None) -> np.ndarray:
    """Points of a sampler in [0, 1)^d.

    Parameters
    ----------
    spec : str
        The sampler's spec, e.g. ``"jitter"``, ``"sobol.owen"``, ``"GJittered:0.25"``
        (``samplers()`` lists them).
    n : int
        Points per set.
    d : int, default 2
        Dimensions.
    seed : int, optional
        The seed (``DEFAULT_SEED`` when omitted). Set k is seeded by a hash of ``seed`` and
        k, as ``samplab generate`` does: the bytes equal the CLI's for the same arguments.
    sets : int, optional
        Independent sets (realizations); one set when omitted.

    Returns
    -------
    numpy.ndarray
        float64 of shape (n, d), or (sets, n, d) when ``sets`` is given.

    Raises
    ------
    samplab.Error
        A count the sampler cannot make (a grid asked for 15 points), naming the nearest
        counts that work; an unknown name (``UnknownNameError``, with suggestions).

    Examples
    --------
    >>> pts = samplab.generate("jitter", n=16, seed=1)
    >>> pts.shape, pts.dtype.name
    ((16, 2), 'float64')
    >>> cells = np.floor(pts * 4).astype(int)          # one point in each of the 4 x 4 cells
    >>> len({(int(a), int(b)) for a, b in cells})
    16
    >>> samplab.generate("sobol.owen", n=1024, d=3, sets=10).shape
    (10, 1024, 3)
    """
    return Sampler(spec, d).generate(n, seed=seed, sets=sets)


def pixel_samplers() -> List[Dict[str, Any]]:
    """Every pixel sampler family (``"zsobol"``, ``"sobol.padded"``,
    ``"pmj02.bn"``, ``"dither"``, ``"openqmc.sobolbn"``, ...).

    Returns
    -------
    list of dict
        Per family its name, aliases, summary, params and references, and ``details``
        (sample counts, dimensions, and how the family becomes a pixel sampler).

    Examples
    --------
    >>> "zsobol" in [p["name"] for p in samplab.pixel_samplers()]
    True
    """
    return _registry("pixels")


def pixels(
    spec: str, res: Sequence[int], spp: int, dims: int = 2, frames: int = 1, seed: Optional[int] = None
) -> np.ndarray:
    """Every value a pixel sampler gives a film.

    A pure function of (seed, pixel, frame, index, dimension): the bytes equal
    ``samplab pixels`` with the same arguments.

    Parameters
    ----------
    spec : str
        The pixel sampler, e.g. ``"zsobol"`` (``pixel_samplers()`` lists them).
    res : (int, int)
        The film's (width, height) in pixels.
    spp : int
        Samples per pixel.
    dims : int, default 2
        Dimensions per sample.
    frames : int, default 1
        Frames.
    seed : int, optional
        The seed (``DEFAULT_SEED`` when omitted).

    Returns
    -------
    numpy.ndarray
        float64 of shape (frames, height, width, spp, dims): entry [f, y, x, i, d] is
        dimension d of sample i of pixel (x, y) in frame f.

    Raises
    ------
    samplab.Error
        A sample count the family does not take (ZSobol asked for 3 spp), naming the
        nearest that work.

    Examples
    --------
    >>> v = samplab.pixels("zsobol", res=(8, 4), spp=4, dims=2)
    >>> v.shape
    (1, 4, 8, 4, 2)
    >>> bool(((v >= 0) & (v < 1)).all())
    True
    """
    return _film_values(spec, res, spp, dims, frames, seed, per_pixel=False)


def pixel_seed(seed: Optional[int], x: int, y: int, frame: int = 0) -> int:
    """The seed of pixel (x, y) in ``frame``: a point-set sequence served per pixel
    (``Sampler.pixels``, ``samplab pixels sobol.owen``) gives that pixel the set
    ``generate(spp, seed=pixel_seed(seed, x, y, frame))``."""
    for name, value in (("x", x), ("y", y), ("frame", frame)):
        if _count(name, value) >= 2**32:
            raise Error(f"{name} = {value}: out of range [0, 2^32)")
    return int(_samplab.pixel_seed(_seed(seed), int(x), int(y), int(frame)))


def _film_values(
    spec: str, res: Sequence[int], spp: int, dims: int, frames: int, seed: Optional[int], per_pixel: bool
) -> np.ndarray:
    """``pixels`` (or, ``per_pixel``, a point-set sequence per pixel), its arguments checked."""
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
    return _samplab.pixels(spec, film, int(frames), _seed(seed), per_pixel)


def blue_noise_mask(size: int = 64, channels: int = 1, seed: Optional[int] = None) -> np.ndarray:
    """A tileable blue-noise mask by void-and-cluster (Ulichney 1993).

    The masks of the ``dither`` and ``pmj02.bn`` pixel samplers, and the bytes of
    ``samplab mask -o FILE.npy``.

    Parameters
    ----------
    size : int, default 64
        Pixels per side, 4 to 256.
    channels : int, default 1
        Independent rankings, 1 to 4.
    seed : int, optional
        The seed (``DEFAULT_SEED`` when omitted).

    Returns
    -------
    numpy.ndarray
        float64 of shape (size, size, channels): each channel a ranking of the pixels as
        (rank + 1/2) / size^2.

    Examples
    --------
    >>> m = samplab.blue_noise_mask(size=8)
    >>> m.shape
    (8, 8, 1)
    >>> bool(np.allclose(np.sort(m.ravel()), (np.arange(64) + 0.5) / 64))   # a permutation of the ranks
    True
    """
    return _samplab.blue_noise_mask(_count("size", size), _count("channels", channels), _seed(seed))


def image_metrics(
    image: Any, reference: Any = None, sigma: Sequence[float] = (0, 1, 2, 4), spp: Optional[Sequence[float]] = None
) -> dict:
    """How an image's error is spread over the screen, as ``samplab image-metrics --json``.

    Parameters
    ----------
    image : array_like
        (height, width) values, (height, width, 3) linear RGB (taken as Rec. 709
        luminance), or a stack of frames of either.
    reference : array_like, optional
        Subtracted first (same shape, or one frame for every frame); without it, ``image``
        is the error.
    sigma : sequence of float, default (0, 1, 2, 4)
        Widths in pixels of the Gaussian blurs.
    spp : sequence of float, optional
        One sample count per image, increasing: the images are then a convergence series.

    Returns
    -------
    dict
        For one frame: the RMSE, the RMSE after each blur beside white noise's of the same
        standard deviation, the low-frequency energy (power below 1/16 cycle per pixel over
        the variance: 1 for white noise) and the radial power spectrum. For several:
        ``{"frames": [dict, ...], "flicker": f}``, f the RMS of the frame-to-frame change of
        the error over its RMS (independent frames: sqrt(2), static: 0). With ``spp``,
        ``"convergence"`` replaces the flicker: slopes of ln(error) against ln(spp) for the
        RMSE (with its 95% interval), each blurred RMSE, and the per-pixel quartiles.

    Examples
    --------
    >>> err = np.random.default_rng(1).normal(size=(64, 64))
    >>> m = samplab.image_metrics(err)
    >>> bool(abs(m["rmse"] - np.sqrt((err ** 2).mean())) < 1e-12)
    True
    """

    def luminance(a: np.ndarray, name: str) -> np.ndarray:
        a = np.asarray(a)
        if a.dtype.kind not in "fiu":
            raise Error(f"{name}: expected real numbers, got dtype {a.dtype}")
        a = np.asarray(a, dtype=np.float64)
        if 0 in a.shape:
            raise Error(f"{name}: an empty image, shape {a.shape}")
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
    counts = None if spp is None else _reals("spp", spp, finite=True)
    result = _samplab.image_metrics(frames, _reals("sigma", sigma, finite=True), counts)
    return result["frames"][0] if single and spp is None else result


def is_sequence(spec: str) -> bool:
    """Whether a sampler is a progressive sequence (Sobol', Halton): extensible, with
    random access.

    Parameters
    ----------
    spec : str
        The sampler's spec.

    Returns
    -------
    bool

    Examples
    --------
    >>> samplab.is_sequence("sobol.owen"), samplab.is_sequence("jitter")
    (True, False)
    """
    return _samplab.Sampler(spec).is_sequence()


def sequence_points(spec: str, start: int, n: int, d: int = 2, seed: Optional[int] = None) -> np.ndarray:
    """Points ``start .. start + n`` of a sequence, randomized as
    ``generate(spec, ..., seed=seed)``.

    Parameters
    ----------
    spec : str
        A sequence's spec (``is_sequence(spec)``).
    start : int
        The index of the first point.
    n : int
        How many points.
    d : int, default 2
        Dimensions.
    seed : int, optional
        The seed (``DEFAULT_SEED`` when omitted).

    Returns
    -------
    numpy.ndarray
        float64 of shape (n, d).

    Examples
    --------
    >>> whole = samplab.generate("sobol.owen", n=64, seed=3)
    >>> bool((samplab.sequence_points("sobol.owen", 16, 48, seed=3) == whole[16:]).all())
    True
    """
    return Sampler(spec, d).points(start, n, seed=seed)


def warp(name: str, points: Any) -> np.ndarray:
    """Warp points of [0, 1)^d to another domain.

    Parameters
    ----------
    name : str
        The warp: ``"disk.concentric"``, ``"tent"``, ``"hemisphere.cosine"``, ...
        (``warps()`` lists them).
    points : array_like
        An (n, d) array in [0, 1)^d.

    Returns
    -------
    numpy.ndarray
        The warped points; rejection warps drop points.

    Examples
    --------
    >>> disk = samplab.warp("disk.concentric", samplab.generate("jitter", n=64))
    >>> bool((np.hypot(disk[:, 0], disk[:, 1]) <= 1).all())
    True
    """
    return _samplab.warp(name, _points(points, stack=False))


def save(path: str, points: Any, format: Optional[str] = None, header: Optional[Sequence[str]] = None) -> None:
    """Write point sets to a file, atomically, as ``samplab generate -o`` does.

    Parameters
    ----------
    path : str or path-like
        The file.
    points : array_like
        An (n, d) set or a (sets, n, d) stack.
    format : str, optional
        ``"text"``, ``"csv"``, ``"npy"`` or ``"json"``; by default from the extension.
    header : sequence of str, optional
        Lines for text comments or JSON metadata.

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = os.path.join(folder.name, "pts.npy")
    >>> samplab.save(path, samplab.generate("random", n=8, sets=2))
    >>> [s.shape for s in samplab.load(path)]
    [(8, 2), (8, 2)]
    >>> folder.cleanup()
    """
    _samplab.save(str(path), _points(points, stack=True), format, None if header is None else list(header))


def load(path: str, format: Optional[str] = None) -> List[np.ndarray]:
    """Every set of a point file.

    Parameters
    ----------
    path : str or path-like
        The file, in one of the formats of ``formats()``.
    format : str, optional
        The format; by default from the extension.

    Returns
    -------
    list of numpy.ndarray
        One (n, d) float64 array per set.

    Raises
    ------
    samplab.FileError
        A file that cannot be read.
    samplab.Error
        Malformed or non-finite data, naming the file and line.

    Examples
    --------
    >>> import os, tempfile
    >>> folder = tempfile.TemporaryDirectory()
    >>> path = os.path.join(folder.name, "pts.txt")
    >>> with open(path, "w") as f:
    ...     _ = f.write("0.25 0.5\\n0.75 nan\\n")
    >>> samplab.load(path)
    Traceback (most recent call last):
    ...
    samplab.Error: ...pts.txt:2: coordinate 2 is not finite: 'nan'
    >>> folder.cleanup()
    """
    return _samplab.load(str(path), format)


def discrepancy(metric: str, points: Any, max_work: Optional[float] = None) -> Union[float, np.ndarray]:
    """A discrepancy of a point set, or of each set of a stack.

    Parameters
    ----------
    metric : str
        ``"star"``, ``"extreme"``, ``"l2-star"``, ``"centered"``, ``"wraparound"``,
        ``"mixture"``, ``"projected:angle=30"``, ... (``metrics()`` lists them). Values are
        never squared (scipy squares CD, WD and MD).
    points : array_like
        An (n, d) set or a (sets, n, d) stack, in [0, 1]^d.
    max_work : float, optional
        Exact algorithms whose cost would exceed this many steps are refused before any
        work (``WorkLimitError``).

    Returns
    -------
    float or numpy.ndarray
        One value for a set, one per set for a stack.

    Examples
    --------
    One point at the centre of the square: the anchored box [0, 1/2]^2 holds all of it and
    a quarter of the area, so the star discrepancy is 3/4.

    >>> samplab.discrepancy("star", np.array([[0.5, 0.5]]))
    0.75
    >>> samplab.discrepancy("l2-star", samplab.generate("jitter", n=16, sets=4)).shape
    (4,)
    """
    a = _points(points, stack=True)
    v = np.asarray(_samplab.discrepancy(metric, a, None if max_work is None else _real("max_work", max_work)))
    return float(v[0]) if np.ndim(points) == 2 else v


def t_values(
    spec: str,
    dims: int = 2,
    m: int = 12,
    projection: str = "consecutive",
    base: Optional[int] = None,
    seed: int = DEFAULT_SEED,
    max_work: Optional[float] = None,
) -> Dict[str, Any]:
    """The t of every projection of a sampler's nets at b^1 .. b^m points, as
    ``samplab t-values --json``.

    A digital net's (``net``, ``faure``, ``niederreiter``, ``sz``, ``cascaded``, ``xi`` and
    their ``.xor``, ``.lms``, ``.owen``) comes from its
    generating matrices, by ranks over GF(b): the t of its points under each such scramble.
    Any other sampler's is counted on the points of one set (``seed``) in ``base`` (2 when
    not given).

    Parameters
    ----------
    spec : str
        The sampler.
    dims : int, default 2
        Dimensions.
    m : int, default 12
        The largest m.
    projection : str, default "consecutive"
        ``"consecutive"`` (the pairs (j, j + 1)), ``"pairs"`` (every 2D projection),
        ``"quadruples"`` (j .. j + 3) or ``"all"`` (the whole set).
    base : int, optional
        The base of a sampler without generating matrices.
    seed : int, default DEFAULT_SEED
        The seed of the set counted (samplers without generating matrices).
    max_work : float, optional
        Refuse more work than this many steps (``WorkLimitError``).

    Returns
    -------
    dict
        ``source``, ``base``, ``from_matrices`` and ``projections``: each ``{"axes": [...],
        "t": [t at m = 1, 2, ...]}``.

    Examples
    --------
    >>> table = samplab.t_values("net", dims=4, m=10)
    >>> [max(p["t"]) for p in table["projections"]]
    [0, 1, 2]
    """
    return _samplab.t_values(
        spec,
        _count("dims", dims),
        _count("m", m),
        projection,
        None if base is None else _count("base", base),
        _seed(seed),
        None if max_work is None else _real("max_work", max_work),
    )


def conform(
    points: Any,
    as_: str,
    *,
    seed: Optional[int] = None,
    res: Optional[Tuple[int, int]] = None,
    frame: int = 0,
    single: bool = False,
    ulps: int = 0,
) -> List[Dict[str, Any]]:
    """Referee your own sampler: samples from your implementation checked against
    samplab's entry ``as_``, as ``samplab conform --json``.

    Checks: ``range`` (every value in [0, 1)), ``reference`` (with ``seed``: every value
    equals samplab's bit for bit, or within ``ulps``; in single precision for a float32
    array or with ``single``, in 32-bit fixed point where every value is a multiple of
    2^-32), ``uniform`` (each dimension by Kolmogorov-Smirnov, p >= 0.001 / d),
    ``independent`` (consecutive dimensions' correlation, |r| sqrt N <= 5), ``unbiased`` (30
    sets or more: the means of x_j and x_j x_(j+1) within 5 standard errors), ``nets``
    (each pair (j, j + 1) of every prefix of b^m points no worse a net than samplab's
    matrices make, or without matrices a (0, m, 2)-net where 64 of samplab's own sets all
    are) and ``distinct`` (sets or pixels that differ where samplab's
    do); a statistical check runs where samplab's own sets pass it.

    Parameters
    ----------
    points : array_like
        Shape (n, d) or (sets, n, d): realizations (set k made with sub-seed k of ``seed``,
        as ``generate(..., sets=...)`` makes them), or with ``res`` a film's pixels row by
        row, each set one pixel's samples; or (frames, height, width, spp, d), the shape
        ``pixels`` returns, a film whose shape gives ``res``. A uint32 array is 32-bit fixed
        point (u / 2^32), as the CLI reads a uint32 ``.npy``.
    as_ : str
        What they should be: a sampler spec (with ``res``, a pixel family).
    seed : int, optional
        The seed they were made with: adds the ``reference`` check.
    res : (int, int), optional
        The film's (width, height) when the sets are pixels.
    frame : int, default 0
        The frame the pixels were drawn at.
    single : bool, default False
        Compare in single precision (values that are singles are found without it).
    ulps : int, default 0
        How many units in the last place a value may differ from samplab's.

    Returns
    -------
    list of dict
        One per check: ``name``, ``passed``, ``number`` (the number behind it) and
        ``detail`` (in words, with the first failing key).

    Examples
    --------
    >>> mine = samplab.generate("net.xor", n=256, d=3, sets=2, seed=7)
    >>> checks = samplab.conform(mine, "net.owen", seed=7)
    >>> [c["name"] for c in checks], [c["name"] for c in checks if not c["passed"]]
    (['range', 'reference', 'uniform', 'independent', 'nets', 'distinct'], ['reference'])
    """
    if np.asarray(points).dtype == np.uint32:
        points = np.asarray(points, dtype=np.float64) / 2.0**32
    frames = 1
    if np.ndim(points) == 5:
        if res is not None:
            raise Error("res: the array's shape (frames, height, width, spp, d) gives its film")
        shape = np.shape(points)
        frames, res = shape[0], (shape[2], shape[1])
        points = np.reshape(points, (shape[0] * shape[1] * shape[2], shape[3], shape[4]))
    a = _points(points, stack=True)

    def word(name: str, value: Any) -> int:
        v = _count(name, value)
        if v >= 2**32:
            raise Error(f"{name} = {v}: out of range [0, 2^32)")
        return v

    if res is not None:
        if np.ndim(res) != 1 or len(res) != 2:
            raise Error(f"res = {res!r}: expected (width, height)")
        res = (word("width", res[0]), word("height", res[1]))
    return _samplab.conform(
        a, as_, None if seed is None else _seed(seed), res, word("frame", frame), bool(single), _count("ulps", ulps),
        word("frames", frames),
    )


def discrepancy_flags(metric: str) -> Dict[str, Any]:
    """The canonical spec of a metric and its flags, as ``samplab discrepancy --json``.

    Parameters
    ----------
    metric : str
        The metric's spec.

    Returns
    -------
    dict
        ``metric`` (canonical spec), ``squared``, ``l2_closed_form``,
        ``toroidal_shift_invariant``, ``lower_bound``.

    Examples
    --------
    >>> samplab.discrepancy_flags("wraparound")["toroidal_shift_invariant"]
    True
    """
    return _samplab.metric_flags(metric)


def spectrum(points: Any, res: int = 128, direct: bool = False, tolerance: float = 1e-9) -> Dict[str, np.ndarray]:
    """Periodogram, amplitude of the expected spectrum and variance of the spectrum of
    a stack of point sets (Subr & Kautz 2013).

    Parameters
    ----------
    points : array_like
        A (sets, n, d) stack, at least two sets, d 1 or 2.
    res : int, default 128
        Frequencies per axis R (even; DC at index R/2).
    direct : bool, default False
        The exact DFT instead of the fast path.
    tolerance : float, default 1e-9
        The fast path's (a non-uniform FFT) error bound, relative to DC.

    Returns
    -------
    dict of numpy.ndarray
        ``periodogram``, ``expected`` and ``variance``, each an R^d array; their radial
        averages (``*_radial``) and anisotropies in dB (``*_anisotropy_db``).
        S(w) = (1/n) sum exp(-2 pi i w.x), so DC is 1 and white noise's periodogram 1/n.

    Examples
    --------
    >>> spec = samplab.spectrum(samplab.generate("random", n=256, sets=20), res=32)
    >>> spec["periodogram"].shape
    (32, 32)
    >>> round(float(spec["periodogram"][16, 16]), 9)   # DC
    1.0
    >>> bool(0.5 < 256 * spec["periodogram_radial"].mean() < 1.5)   # white noise: 1/n
    True
    """
    return _samplab.spectrum(_points(points, stack=True), _count("res", res), bool(direct), _real("tolerance", tolerance))


def reference(f: Any, d: int) -> float:
    """The integral of your function over [0, 1]^d, for reference, where you do not know it.

    Computed by ``cubature`` to a relative 1e-9 (at most 2^22 points x 16
    randomizations).

    Parameters
    ----------
    f : callable
        Vectorized: ``f(x)`` with x of shape (m, d) returns m values.
    d : int
        Dimensions.

    Returns
    -------
    float

    Raises
    ------
    samplab.Error
        When it cannot reach the accuracy, saying how far it got (then give ``exact=``
        yourself).

    Examples
    --------
    >>> round(samplab.reference(lambda x: x[:, 0] * x[:, 1], d=2), 9)
    0.25
    """
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
    """Bias, variance and convergence of samplers on an integrand, as ``samplab
    integrate --json``.

    Parameters
    ----------
    samplers : str or sequence of str
        Sampler specs.
    integrand : str or callable
        A family spec (``"quad"``, ``"keister:d=3"``) or your own vectorized function
        ``f(x)``, x of shape (m, d), returning m values (it is one function, so
        ``instances`` does not apply).
    n : int or sequence of int
        The counts.
    sets : int, default 50
        Realizations per instance and count.
    instances : int, default 10
        Instances of a family.
    seed : int, optional
        The seed (``DEFAULT_SEED`` when omitted).
    d : int, optional
        A callable's dimension (required for one).
    exact : float, optional
        A callable's integral; ``reference`` computes it to a relative 1e-9 otherwise.
    columns : bool, default False
        The callable takes x of shape (d, m), scipy's convention.

    Returns
    -------
    dict
        ``{"rows": [...], "fits": [...]}``: a row per sampler and count (relative mean,
        relative variance, RMSE, N^2 MSE, and the closed form where one applies); a fit per
        sampler (the convergence exponent and its 95% interval).

    Examples
    --------
    >>> r = samplab.integrate(["random", "jitter"], "quad", [16, 64, 256], sets=20, instances=4)
    >>> len(r["rows"]), [f["sampler"] for f in r["fits"]]
    (6, ['random', 'jitter'])
    >>> r = samplab.integrate("sobol.owen", lambda x: x.sum(axis=1), [64, 256], sets=8, d=3, exact=1.5)
    >>> r["rows"][0]["integrand"]
    '<lambda>'
    """
    names = [samplers] if isinstance(samplers, str) else list(samplers)
    integrand = _by_columns(integrand, columns)
    if callable(integrand):
        if d is None:
            raise Error("a callable integrand needs d= (its dimension)")
        given = (_count("d", d), _real("exact", reference(integrand, d) if exact is None else exact, finite=True))
        return _samplab.integrate_given(names, integrand, _counts("n", n), _count("sets", sets), _seed(seed), given)
    return _samplab.integrate(
        names,
        integrand,
        _counts("n", n),
        _count("sets", sets),
        _count("instances", instances),
        _seed(seed),
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
    """The integral of an integrand over [0, 1]^d to a tolerance, as ``samplab cubature --json``.

    The points per randomization are doubled from ``min_n`` until the bound is at most
    ``max(abs_tol, rel_tol |estimate|)`` or ``max_n`` is reached (``converged`` says
    which); a sequence's earlier points are kept.

    Parameters
    ----------
    integrand : str or callable
        A family spec (``"keister:d=8"``) or a vectorized callable ``f(x)``, x of shape
        (m, d), returning m values.
    d : int, optional
        A callable's dimension (required for one).
    abs_tol, rel_tol : float, optional
        The tolerances (defaults 1e-3 and 0).
    rule : str, optional
        ``"replicated"`` (the default; probabilistic: Student's t interval at ``level``
        over ``replications`` randomizations of ``sampler``), ``"net"`` or ``"lattice"``
        (guaranteed for integrands in the cone of Hickernell & Jimenez Rugama 2016, on one
        randomized digital net, ``net.lms``, or shifted lattice sequence with the baker's
        transform).
    sampler : str, optional
        The replicated rule's sampler (``sobol.owen``).
    level : float, optional
        The replicated interval's level (0.99).
    replications : int, optional
        The replicated rule's randomizations (16).
    min_n, max_n : int, optional
        The first and the largest count per randomization (256, or 1024 for the guaranteed
        rules; 2^20).
    seed : int, optional
        The seed.
    exact : float, optional
        The integral, when known (reported beside the estimate).
    columns : bool, default False
        The callable takes x of shape (d, m), as ``scipy.integrate.qmc_quad`` does.

    Returns
    -------
    dict
        ``estimate``, ``bound``, ``kind`` (guaranteed or probabilistic, with its level),
        ``converged``, ``n``, ``evaluations``, ``steps``, ``seconds``, ``integrand``,
        ``exact``.

    Examples
    --------
    >>> r = samplab.cubature(lambda x: (x ** 2).sum(axis=1), d=3, abs_tol=1e-4)
    >>> r["converged"], abs(r["estimate"] - 1.0) <= 1e-4
    (True, True)
    """
    if callable(integrand) and d is None:
        raise Error("d: give the dimension of a callable integrand")
    integrand = _by_columns(integrand, columns)
    given: Dict[str, Any] = {}
    for name, value in (("abs_tol", abs_tol), ("rel_tol", rel_tol), ("level", level)):
        if value is not None:
            given[name] = _real(name, value)
    for name, value in (("replications", replications), ("min_n", min_n), ("max_n", max_n)):
        if value is not None:
            given[name] = _count(name, value)
    for name, text in (("rule", rule), ("sampler", sampler)):
        if text is not None:
            given[name] = str(text)
    if seed is not None:
        given["seed"] = _seed(seed)
    dims = 0 if d is None else _count("d", d)
    return _samplab.cubature(integrand, dims, None if exact is None else _real("exact", exact, finite=True), given)


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
    """The variance of samplers on integrands, predicted from their spectra
    (Pilleboue et al. 2015), as ``samplab predict --json``.

    Parameters
    ----------
    integrand : str, array_like, callable, or a list of these
        A spec (``"disk:r=0.3"``), a 2D float array (values on a grid over the unit square,
        row 0 at y = 0, box lookups: an image), or a vectorized callable ``f(x)`` taking an
        (m, d) array and returning m values (``d`` 1 or 2; its spectrum is the FFT of its
        values at the midpoints of a fine grid, the error of that estimate stated).
    samplers : str or sequence of str, optional
        The samplers; every registered sampler of the integrands' dimension when omitted.
    n : int or sequence of int, default (16, 64, 256, 1024)
        The counts.
    res : int, default 128
        Frequencies per axis of the spectra.
    sets : int, default 16
        Realizations per sampler spectrum.
    measure : int, optional
        Also measure the mean squared error over this many realizations (shifted when
        ``shift``).
    shift : bool, default False
        Measure over random toroidal shifts of each set.
    seed : int, optional
        The seed.
    d : int, default 2
        The callables' dimension.
    exact : float or sequence of float, optional
        The integral of each callable, in order, needed to measure.
    cache : bool, default True
        Read and keep measured sampler spectra in the user's cache (``$SAMPLAB_CACHE``,
        else ``$XDG_CACHE_HOME/samplab``, else ``~/.cache/samplab``).

    Returns
    -------
    dict
        ``{"integrands", "rows", "ranking", "rates", "skipped"}``: a row per integrand,
        sampler and count (the predicted variance over a random toroidal shift of each set
        and its standard error, the radial form of the same, where the sampler's spectrum
        comes from, and the measured mean squared error when asked); the ranking per
        integrand by predicted variance at the largest count with the fitted exponents; per
        sampler the small-frequency exponent of its spectrum and the best- and worst-case
        convergence exponents it implies.

    Examples
    --------
    >>> r = samplab.predict("disk:r=0.3", ["random", "jitter"], n=[64, 256], res=64, sets=8, cache=False)
    >>> sorted({row["sampler"] for row in r["rows"]})
    ['jitter', 'random']
    """
    names = [] if samplers is None else [samplers] if isinstance(samplers, str) else list(samplers)
    given = list(integrand) if isinstance(integrand, (list, tuple)) else [integrand]
    given = [np.ascontiguousarray(g, dtype=np.float64) if isinstance(g, np.ndarray) else g for g in given]
    integrals = [] if exact is None else [exact] if isinstance(exact, (int, float)) else list(exact)
    measured = None if measure is None else (_count("measure", measure), bool(shift))
    return _samplab.predict(
        names,
        given,
        _counts("n", n),
        _count("res", res),
        _count("sets", sets),
        measured,
        _seed(seed),
        _count("d", d),
        _reals("exact", integrals, finite=True),
        bool(cache),
    )


def integrand(spec: str, points: Any, instance: int = 0, seed: Optional[int] = None) -> "tuple[np.ndarray, float]":
    """An instance of an integrand family: its values at points and its exact integral.

    Parameters
    ----------
    spec : str
        The family (``integrands()`` lists them).
    points : array_like
        An (n, d) array.
    instance : int, default 0
        Which instance, as a study with ``seed`` draws it.
    seed : int, optional
        The seed.

    Returns
    -------
    (numpy.ndarray, float)
        The values at the rows of ``points``, and the exact integral.

    Examples
    --------
    >>> values, exact = samplab.integrand("keister:d=2", samplab.generate("sobol.owen", n=4096, seed=5))
    >>> bool(abs(values.mean() - exact) < 1e-3)
    True
    """
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
    """Reproduce the papers into a folder, as ``samplab reproduce``.

    Nothing is drawn on the terminal; ``progress`` hears of the run instead.

    Parameters
    ----------
    out : str, default "report"
        The folder, replaced only when the run completes.
    full : bool, default False
        The papers' own scales (slower).
    only : str or sequence of str, optional
        Only these papers' keys.
    seed : int, optional
        The run's seed.
    force : bool, default False
        Replace an ``out`` that holds files samplab did not write (as ``--force``).
    progress : callable, optional
        ``progress(paper, experiment, done, total)``, called as each experiment starts
        (``done`` 0), learns its length, advances (at most once per percent) and finishes
        (``done == total``), from any thread: experiments run side by side, so the calls of
        several interleave. An exception it raises stops the run and is raised here.

    Returns
    -------
    list of dict
        Each claim's paper, id and verdict.

    Examples
    --------
    >>> import os, tempfile
    >>> claims = samplab.reproduce(os.path.join(tempfile.mkdtemp(), "r"), only=["shirley1991"])  # doctest: +SKIP
    >>> {c["verdict"] for c in claims} <= {"reproduced", "checked", "not reproduced", "undecided"}  # doctest: +SKIP
    True
    """
    if progress is not None and not callable(progress):
        raise Error(f"progress: {progress!r} is not callable")
    keys = None if only is None else [only] if isinstance(only, str) else list(only)
    return _samplab.reproduce(str(out), bool(full), keys, None if seed is None else _seed(seed), bool(force), progress)


def render(scene: str, light: Optional[str] = None, reference_samples: Optional[int] = None, allow_paths_outside_scene: bool = False, **settings: Any) -> Dict[str, Any]:
    """Render a scene with any sampler, as ``samplab render``.

    Parameters
    ----------
    scene : str
        A built-in scene (``scenes()``) or a Mitsuba 3 XML file.
    light : str, optional
        ``"square"``, ``"disk"``, ``"linear"`` or ``"gaussian"``.
    reference_samples : int, optional
        Render the converged reference the CLI renders for these settings instead.
    allow_paths_outside_scene : bool, default False
        Let a Mitsuba scene name meshes outside its own folder (for scenes you trust).
    **settings
        The render settings, one keyword per CLI flag (``area_sampler`` is
        ``--area-sampler``), each at the CLI's default when not given; a setting moved
        from its default that the render would not read (``max_depth`` outside path mode,
        ``range`` outside obscurance, the strategies and, in path mode, ``n`` where a pixel
        sampler draws every dimension) raises ``samplab.Error``. Sizes are tuples
        (``res=(width, height)``, ``interleave=(w, h)``). The settings:

{settings}

    Returns
    -------
    dict
        ``{"rgb": (h, w, 3) float32, "visibility": (h, w) float32, "camera_rays",
        "shadow_rays"}``: the numbers ``samplab render -o x.exr`` writes.

    Examples
    --------
    >>> img = samplab.render("sphere-box", res=(32, 24), n=4)
    >>> img["rgb"].shape, img["visibility"].dtype.name
    ((24, 32, 3), 'float32')
    """
    if "seed" in settings:
        settings["seed"] = _seed(settings["seed"])
    samples = None if reference_samples is None else _count("reference_samples", reference_samples)
    return _samplab.render(scene, light, settings, samples, bool(allow_paths_outside_scene))


def _settings_doc() -> str:
    """The render settings' numpydoc lines, from the library's one table of them."""
    lines = []
    for s in _samplab.render_settings():
        default = "" if s["default"] is None else f", default {s['default']}"
        lines.append(f"        - ``{s['name']}`` ({s['flag']}{default}): {s['help']}")
    return "\n".join(lines)


assert render.__doc__ is not None
render.__doc__ = render.__doc__.replace("{settings}", _settings_doc())


def _image(a: Any, what: str, ndim: int) -> np.ndarray:
    arr = np.ascontiguousarray(np.asarray(a), dtype=np.float32)
    if arr.ndim != ndim:
        raise Error(f"{what}: expected {ndim} dimensions, got shape {arr.shape}")
    return arr


def image_errors(image: Any, reference: Any, penumbra: bool = False) -> Dict[str, float]:
    """Errors of an image against a reference, on luminance (as ``samplab render --json``).

    Parameters
    ----------
    image, reference : dict or array_like
        ``render()`` results or (h, w, 3) arrays.
    penumbra : bool, default False
        Compare only where the reference's visibility is strictly between 0 and 1 (it needs
        the reference's visibility).

    Returns
    -------
    dict
        ``pixels``, ``mse``, ``rmse``, ``relative`` (the RMSE over the reference's mean, None
        where that is 0), ``mean_abs``, ``sd_abs``, ``max_abs``, ``mean_signed`` (the bias).

    Examples
    --------
    >>> a = np.zeros((4, 4, 3), dtype=np.float32)
    >>> e = samplab.image_errors(a + 1, a)
    >>> e["rmse"], e["mean_signed"], e["relative"]
    (1.0, 1.0, None)
    """
    def parts(x: Any, what: str):
        if isinstance(x, dict):
            v = x.get("visibility")
            return _image(x["rgb"], what, 3), None if v is None else _image(v, what + " visibility", 2)
        return _image(x, what, 3), None

    rgb, _ = parts(image, "image")
    ref_rgb, ref_vis = parts(reference, "reference")
    return _samplab.image_errors(rgb, ref_rgb, ref_vis, bool(penumbra))


def read_exr(path: str) -> Dict[str, Any]:
    """An OpenEXR image as ``samplab render`` writes it.

    Parameters
    ----------
    path : str or path-like
        The file.

    Returns
    -------
    dict
        ``{"rgb": (h, w, 3), "visibility": (h, w) or None}``, float32.

    Raises
    ------
    samplab.FileError
        A file that cannot be read.
    """
    return _samplab.read_exr(str(path))


def _bad_text(value: Any, depth: int) -> Optional[Tuple[str, UnicodeEncodeError]]:
    """The first string in an argument (itself, or within lists, tuples and dicts down to
    depth 3: a call's arguments, a list among them, and its items) that is not valid Unicode
    text, with its error; None when there is none. Plain recursion, no generators: it runs
    before every call of the package with an argument that is not a number or ASCII text.
    """
    if isinstance(value, str):
        try:
            value.encode("utf-8")
        except UnicodeEncodeError as e:
            return value, e
    elif depth < 3 and isinstance(value, (list, tuple)):
        for v in value:
            bad = _bad_text(v, depth + 1)
            if bad is not None:
                return bad
    elif depth < 3 and isinstance(value, dict):
        for k, v in value.items():
            bad = _bad_text(k, depth + 1) or _bad_text(v, depth + 1)
            if bad is not None:
                return bad
    return None


_PLAIN = frozenset((int, float, bool, type(None), np.ndarray))


def _valid_text(f: Callable[..., Any]) -> Callable[..., Any]:
    """``f``, refusing with samplab.Error a string argument that is not valid Unicode text
    (a lone surrogate, which no UTF-8 encoding holds) before the call."""

    @functools.wraps(f)
    def checked(*args: Any, **kwargs: Any) -> Any:
        for value in (*args, *kwargs, *kwargs.values()):
            # most arguments are numbers and ASCII names: nothing to look into
            if type(value) in _PLAIN or (type(value) is str and value.isascii()):
                continue
            bad = _bad_text(value, 2)
            if bad is not None:
                text, e = bad
                raise Error(f"{f.__name__}: {text!r} is not valid text ({e.reason} at position {e.start})") from None
        return f(*args, **kwargs)

    return checked


for _name in __all__:
    if inspect.isfunction(globals().get(_name)):
        globals()[_name] = _valid_text(globals()[_name])
del _name
Sampler.__init__ = _valid_text(Sampler.__init__)  # type: ignore[method-assign]


from .study import Study, StudyResult  # noqa: E402  (study.py imports this package's names)
