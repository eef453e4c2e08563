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
    if isinstance(seed, np.random.SeedSequence):
        return int(seed.generate_state(1, np.uint64)[0])
    if isinstance(seed, (int, np.integer)) and not isinstance(seed, bool) and int(seed) >= 2**64:
        return int(np.random.SeedSequence(int(seed)).generate_state(1, np.uint64)[0])
    return _seed(seed)


class Engine(_qmc.QMCEngine):
    """A ``scipy.stats.qmc.QMCEngine`` drawing from the samplab sampler ``spec``.

    Parameters
    ----------
    spec : str
        A sampler spec, e.g. ``"sobol.owen"``, ``"halton.xor"``, ``"jitter"``, ``"nrooks"``.
    d : int
        Dimensions.
    seed : int, numpy.random.SeedSequence, numpy.random.Generator or None
        samplab's seed, or what is mapped to one (see the module's documentation).
    optimization : {None, "random-cd", "lloyd"}
        scipy's optimization of every draw, as its engines take it.
    """

    def __init__(
        self, spec: str = "sobol.owen", d: int = 2, *, seed: Any = None, optimization: Optional[str] = None
    ) -> None:
        if isinstance(d, bool) or not isinstance(d, (int, np.integer)) or d < 0:
            raise Error(f"d must be a non-negative whole number, got {d!r}")
        self.spec = spec
        self.sequence = _samplab.is_sequence(spec)
        self.samplab_seed = _samplab_seed(seed)
        # scipy's own state (qmc_quad spawns Generators from self.rng; the optimizers draw from it)
        rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(self.samplab_seed)
        self._initialize(int(d), rng=rng, optimization=optimization)
        self._init_quad = {"spec": spec, "d": int(d), "optimization": optimization}

    def _random(self, n: int = 1, *, workers: int = 1) -> np.ndarray:
        n = _count("n", n)
        if n == 0 or self.d == 0:
            return np.empty((n, self.d))
        if self.sequence and self.num_generated:
            return _samplab.sequence_points(self.spec, self.num_generated, n, self.d, self.samplab_seed)
        if self.num_generated and not self.sequence:
            raise Error(
                f"{self.spec} makes whole sets, not a sequence: it cannot extend the {self.num_generated} "
                "points already drawn (call reset(), or draw all points at once)"
            )
        return _samplab.generate(self.spec, n, self.d, self.samplab_seed, 1)[0]

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
    randomizations of ``n_points`` points each of ``qrng`` (a randomized samplab spec, an
    ``Engine``, or None for ``"sobol.owen"``); the result's ``integral`` is their mean and
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
    )
    from scipy.stats import t as student_t

    t = float(student_t.ppf(0.995, n_estimates - 1))
    return QMCQuadResult(r["estimate"] * volume, r["bound"] / t * abs(volume))
