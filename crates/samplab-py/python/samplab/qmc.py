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
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
from scipy.stats import qmc as _qmc

from . import DEFAULT_SEED, Error, _samplab, _seed


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
        if n == 0 or self.d == 0:
            return np.empty((int(n), self.d))
        if self.sequence and self.num_generated:
            return _samplab.sequence_points(self.spec, self.num_generated, int(n), self.d, self.samplab_seed)
        if self.num_generated and not self.sequence:
            raise Error(
                f"{self.spec} makes whole sets, not a sequence: it cannot extend the {self.num_generated} "
                "points already drawn (call reset(), or draw all points at once)"
            )
        return _samplab.generate(self.spec, int(n), self.d, self.samplab_seed, 1)[0]

    def reset(self) -> "Engine":
        """Start again from the first point (the same points as before)."""
        super().reset()
        return self

    def fast_forward(self, n: int) -> "Engine":
        """Skip ``n`` points of a sequence; other samplers cannot skip."""
        if not self.sequence:
            raise Error(f"{self.spec} makes whole sets, not a sequence: it cannot fast-forward")
        self.num_generated += int(n)
        return self
