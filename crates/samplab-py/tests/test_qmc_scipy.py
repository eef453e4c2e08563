"""scipy's own generic engine tests (``QMCEngineTests`` of scipy/stats/tests/test_qmc.py,
imported from the installed scipy, 1.17.1 when written) run against ``samplab.qmc.Engine``
for Sobol' and Halton, with scipy's reference values for the unscrambled sequences.

scipy's scrambled references are its own random draws (its tests compare them within 0.1),
which another scrambling cannot reproduce; for the scrambled engines the reference test
checks what Owen scrambling keeps instead: the first 8 points stratify each axis (base 2)
into eighths.
"""

import numpy as np
import pytest

pytest.importorskip("scipy")
from scipy.stats.tests import test_qmc as scipy_tests  # noqa: E402

from samplab.qmc import Engine  # noqa: E402


def factory(unscrambled, scrambled):
    def make(d=2, scramble=True, seed=None, optimization=None):
        return Engine(scrambled if scramble else unscrambled, d=d, seed=seed, optimization=optimization)

    return staticmethod(make)


class SamplabEngineTests(scipy_tests.QMCEngineTests):
    can_scramble = True

    @pytest.mark.parametrize("scramble", [True, False], ids=["Scrambled", "Unscrambled"])
    def test_sample(self, scramble):
        if not scramble:
            return super().test_sample(scramble)
        engine = self.engine(d=2, scramble=True)
        sample = engine.random(8)
        assert engine.num_generated == 8
        for axis in self.base_two_axes:
            assert sorted(np.floor(sample[:, axis] * 8).astype(int)) == list(range(8))


class TestSamplabSobol(SamplabEngineTests):
    qmce = factory("sobol", "sobol.owen")
    unscramble_nd = scipy_tests.TestSobol.unscramble_nd
    scramble_nd = None
    base_two_axes = (0, 1)


class TestSamplabHalton(SamplabEngineTests):
    qmce = factory("halton", "halton.owen")
    unscramble_nd = scipy_tests.TestHalton.unscramble_nd
    scramble_nd = None
    base_two_axes = (0,)
