"""samplab's samplers as ``scipy.stats.qmc`` engines.

``Engine("sobol.owen", d=2, seed=7)`` is a ``scipy.stats.qmc.QMCEngine``: ``random(n)``,
``reset()``, ``fast_forward(n)``, and it works where scipy takes engines
(``scipy.integrate.qmc_quad``, ``scipy.stats.qmc.discrepancy``). Progressive sequences
(Sobol', Halton) extend: successive ``random`` calls continue the sequence. Every other
sampler makes whole sets (a grid of n = k^2 points, a Poisson disk): its first ``random(n)``
is a set of n points and a second call raises ``samplab.Error`` instead of returning points
that do not belong together; ``reset()`` starts again.

Seeds, as scipy's engines take them: an integer in [0, 2^64) is samplab's seed (the CLI's
``--seed``); a larger non-negative integer or a ``numpy.random.SeedSequence`` is mapped to
one by the SeedSequence's first 64-bit word; a ``numpy.random.Generator`` (as ``qmc_quad``
passes) by drawing one 64-bit integer from it, so engines made from one Generator differ;
None is samplab's default seed, so an engine is reproducible unless given a Generator.

``d = 0`` and ``random(0)`` give empty arrays, and ``optimization="random-cd"`` or
``"lloyd"`` applies scipy's optimizers to every draw, as scipy's own engines do.

``qmc_quad`` is ``scipy.integrate.qmc_quad``'s call and result computed by
``samplab.cubature`` (the points made and summed in Rust), with a tolerance on top.
"""

from __future__ import annotations

import warnings
from collections import namedtuple
from typing import Any, Optional

import numpy as np
from scipy.stats import qmc as _qmc

from . import DEFAULT_SEED, Error, _count, _samplab, _seed, cubature

#: ``qmc_quad``'s result, with the fields of scipy's ``QMCQuadResult``.
QMCQuadResult = namedtuple("QMCQuadResult", ["integral", "standard_error"])


def _samplab_seed(seed: Any) -> int:
    if seed is None:
        return DEFAULT_SEED
    if isinstance(seed, np.random.Generator):
        return int(seed.integers(0, 2**63, dtype=np.int64))
    if isinstance(seed, np.random.RandomState):
        return int(seed.randint(0, 2**63, dtype=np.int64))
    if isinstance(seed, np.random.SeedSequence):
        return int(seed.generate_state(1, np.uint64)[0])
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and int(seed) >= 2**64:
        return int(np.random.SeedSequence(int(seed)).generate_state(1, np.uint64)[0])
    return _seed(seed)


#: The randomizations a family's spec may end with (``sobol.owen``); ``scramble=True``
#: picks the first the family has.
_RANDOMIZATIONS = ("owen", "xor", "lms", "shift")


def _scrambled(spec: str, scramble: Optional[bool]) -> str:
    """``spec`` as ``scramble`` asks (scipy's keyword): None leaves it; False names the
    family's unrandomized construction (``sobol.owen`` -> ``sobol``); True its Owen (or
    first) randomization when ``spec`` names an unrandomized one (``sobol`` ->
    ``sobol.owen``)."""
    if scramble is None:
        return spec
    if not isinstance(scramble, (bool, np.bool_)):
        raise TypeError(f"scramble must be True or False, got {scramble!r}")
    name, colon, params = spec.partition(":")
    family, dot, last = name.rpartition(".")
    names = {e["name"] for e in _samplab.registry("samplers")}
    if not scramble:
        if dot and last in _RANDOMIZATIONS and family in names:
            return family + colon + params
        if name in names and any(f"{name}.{r}" in names for r in _RANDOMIZATIONS):
            return spec
        raise Error(f"scramble=False: {spec} has no unscrambled construction")
    if _samplab.Sampler(spec).randomized():
        return spec
    for r in _RANDOMIZATIONS:
        if f"{name}.{r}" in names:
            return f"{name}.{r}" + colon + params
    raise Error(f"scramble=True: {spec} has no randomization (samplab list samplers)")


def _base_2_net(spec: str) -> bool:
    """Whether ``spec`` is a digital net in base 2, whose balance needs n a power of two."""
    name, _, params = spec.partition(":")
    family = name.split(".")[0]
    return family in ("sobol", "pmj02") or (family in ("net", "niederreiter") and "base=" not in params)


class Engine(_qmc.QMCEngine):
    """A ``scipy.stats.qmc.QMCEngine`` drawing from the samplab sampler ``spec``.

    Parameters
    ----------
    spec : str
        A sampler spec, e.g. ``"sobol.owen"``, ``"halton.xor"``, ``"jitter"``, ``"nrooks"``.
    d : int
        Dimensions (more than the sampler makes is refused with scipy's message: "Maximum
        supported dimensionality is 1024." for Sobol').
    scramble : bool, optional
        scipy's keyword: False for the family's unrandomized construction (``sobol``),
        True for its randomized one (``sobol`` -> ``sobol.owen``); unset, ``spec`` as given.
    rng : int, numpy.random.Generator, numpy.random.RandomState, numpy.random.SeedSequence or None
        samplab's seed, or what is mapped to one (see the module's documentation);
        ``seed=`` is its older name, as in scipy.
    optimization : {None, "random-cd", "lloyd"}
        scipy's optimization of every draw, as its engines take it.

    A base-2 net (``sobol*``, ``net``, ``niederreiter``, ``pmj02``) warns as scipy's Sobol'
    does when its first draw is not a power of two, and ``random_base2(m)`` draws 2^m points
    while the total stays a power of two.
    """

    def __init__(
        self,
        spec: str = "sobol.owen",
        d: int = 2,
        *,
        scramble: Optional[bool] = None,
        rng: Any = None,
        optimization: Optional[str] = None,
        seed: Any = None,
    ) -> None:
        if isinstance(d, bool) or not isinstance(d, (int, np.integer)) or d < 0:
            raise Error(f"d must be a non-negative whole number, got {d!r}")
        if rng is not None and seed is not None:
            raise TypeError("give rng or seed (its older name), not both")
        rng = seed if rng is None else rng
        spec = _scrambled(spec, scramble)
        self._sampler = _samplab.Sampler(spec)
        if d > 0:
            most = self._sampler.dims()[1]
            if d > most:
                raise Error(f"Maximum supported dimensionality is {most}.")
        self.spec = spec
        self.sequence = self._sampler.is_sequence()
        self.samplab_seed = _samplab_seed(rng)
        # scipy's own state (qmc_quad spawns Generators from self.rng; the optimizers draw from it)
        state = rng if isinstance(rng, np.random.Generator) else np.random.default_rng(self.samplab_seed)
        self._initialize(int(d), rng=state, optimization=optimization)
        self._init_quad = {"spec": spec, "d": int(d), "optimization": optimization}

    def _random(self, n: int = 1, *, workers: int = 1) -> np.ndarray:
        n = _count("n", n)
        if n == 0 or self.d == 0:
            return np.empty((n, self.d))
        if self.num_generated == 0 and n & (n - 1) and _base_2_net(self.spec):
            # scipy's Sobol' warns so, in these words
            warnings.warn("The balance properties of Sobol' points require n to be a power of 2.", stacklevel=3)
        if self.sequence and self.num_generated:
            return self._sampler.points(self.num_generated, n, self.d, self.samplab_seed)
        if self.num_generated and not self.sequence:
            raise Error(
                f"{self.spec} makes whole sets, not a sequence: it cannot extend the {self.num_generated} "
                "points already drawn (call reset(), or draw all points at once)"
            )
        return self._sampler.generate(n, self.d, self.samplab_seed, 1)[0]

    def random_base2(self, m: int) -> np.ndarray:
        """2^m points, as scipy's ``Sobol.random_base2``: refused (ValueError, scipy's
        words) when the points drawn would no longer number a power of two."""
        m = _count("m", m)
        n = 2**m
        total = self.num_generated + n
        if total & (total - 1):
            raise Error(
                "The balance properties of Sobol' points require n to be a power of 2. "
                f"{self.num_generated} points have been previously generated, then: "
                f"n={self.num_generated}+2**{m}={total}. If you still want to do this, the function "
                "'Engine.random()' can be used."
            )
        return self.random(n)

    def reset(self) -> "Engine":
        """Start again from the first point (the same points as before)."""
        super().reset()
        return self

    def fast_forward(self, n: int) -> "Engine":
        """Skip ``n`` points of a sequence; other samplers cannot skip."""
        n = _count("n", n)
        if not self.sequence:
            raise Error(f"{self.spec} makes whole sets, not a sequence: it cannot fast-forward")
        self.num_generated += n
        return self


def qmc_quad(
    func: Any,
    a: Any,
    b: Any,
    *,
    n_estimates: int = 8,
    n_points: int = 1024,
    qrng: Any = None,
    log: bool = False,
    abs_tol: Optional[float] = None,
    rel_tol: Optional[float] = None,
    max_n: Optional[int] = None,
) -> QMCQuadResult:
    """The integral of ``func`` over the box [a, b], as ``scipy.integrate.qmc_quad`` computes
    it: ``func(x)`` takes x of shape (d, n) and returns n values; ``n_estimates``
    randomizations of ``n_points`` points each of ``qrng`` (a randomized samplab spec or None
    for ``"sobol.owen"``, both at samplab's default seed, or an ``Engine``, at its seed, of the
    box's dimensions); the result's ``integral`` is their mean and
    ``standard_error`` its standard error. With ``abs_tol`` or ``rel_tol`` (on the box's
    integral), ``n_points`` is only the first n: it is doubled, the earlier points kept, until
    Student's t bound at 0.99 over the randomizations meets the tolerance or ``max_n`` is
    reached (``samplab.cubature``). ``log=True`` (values as logarithms) is not supported."""
    if log:
        raise Error("log=True: samplab.qmc.qmc_quad integrates values, not their logarithms (use scipy.integrate.qmc_quad)")
    lo, hi = np.atleast_1d(np.asarray(a, dtype=float)), np.atleast_1d(np.asarray(b, dtype=float))
    if lo.shape != hi.shape or lo.ndim != 1 or not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        raise Error(f"a and b: finite bounds of one shape, got {a!r} and {b!r}")
    spec = qrng.spec if isinstance(qrng, Engine) else ("sobol.owen" if qrng is None else qrng)
    if not isinstance(spec, str):
        raise Error(f"qrng: a samplab spec or samplab.qmc.Engine, got {qrng!r}")
    # an engine brings its seed (a spec or None: samplab's default seed) and must have the
    # box's dimensions
    seed = qrng.samplab_seed if isinstance(qrng, Engine) else None
    if isinstance(qrng, Engine) and qrng.d != len(lo):
        raise Error(f"qrng: an engine of d={qrng.d} for a box of {len(lo)} dimensions")
    width = hi - lo
    volume = float(np.prod(width))

    def on_box(x: Any) -> Any:
        return func((lo + width * x).T)

    tolerance = abs_tol is not None or rel_tol is not None
    r = cubature(
        on_box,
        len(lo),
        abs_tol=(abs_tol / abs(volume) if abs_tol and volume else 0.0) if tolerance else 1e-300,
        rel_tol=rel_tol or 0.0,
        sampler=spec,
        replications=n_estimates,
        min_n=n_points,
        max_n=(max_n if max_n is not None else 1 << 20) if tolerance else n_points,
        seed=seed,
    )
    from scipy.stats import t as student_t

    t = float(student_t.ppf(0.995, n_estimates - 1))
    return QMCQuadResult(r["estimate"] * volume, r["bound"] / t * abs(volume))
