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


# scipy's Sobol'-specific behaviour, with scipy's own assertions and reference values: the
# scramble= and rng= keywords, the warning for a first draw that is not a power of two,
# random_base2, and the dimension limit.


def sobol(d, scramble=True, rng=None):
    return Engine("sobol", d, scramble=scramble, rng=rng)


def test_scramble_picks_the_construction_as_scipy_does():
    assert sobol(2, scramble=False).spec == "sobol" and sobol(2).spec == "sobol.owen"
    assert Engine("sobol.owen", 2, scramble=False).spec == "sobol"
    assert Engine("halton", 2, scramble=True).spec == "halton.owen"
    assert Engine("jitter", 2, scramble=True).spec == "jitter"  # random by construction
    import samplab

    with pytest.raises(samplab.Error, match="no unscrambled construction"):
        Engine("jitter", 2, scramble=False)
    with pytest.raises(TypeError):
        Engine("sobol", 2, scramble="yes")
    with pytest.raises(TypeError):
        Engine("sobol", 2, rng=1, seed=1)
    # rng= as scipy takes it: an int is samplab's seed, a Generator or RandomState is drawn from
    assert np.array_equal(sobol(3, rng=7).random(8), Engine("sobol.owen", 3, seed=7).random(8))
    assert sobol(2, rng=np.random.RandomState(1)).random(4).shape == (4, 2)


def test_a_first_draw_not_a_power_of_two_warns_in_scipys_words():
    with pytest.warns(UserWarning, match=r"The balance properties of Sobol' points"):
        sobol(1).random(10)
    for spec in ("net.lms", "pmj02"):
        with pytest.warns(UserWarning, match=r"The balance properties"):
            Engine(spec, 2).random(12)
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sobol(2).random(16)
        Engine("halton.owen", 2).random(10)  # not a base-2 net: no warning


def test_random_base2_keeps_the_balance_or_refuses():
    engine = sobol(2, scramble=False)
    reference = scipy_tests.TestSobol.unscramble_nd
    assert np.array_equal(engine.random_base2(2), reference[:4])
    assert np.array_equal(engine.random_base2(2), reference[4:8])
    with pytest.raises(ValueError, match=r"The balance properties of Sobol' points"):
        engine.random_base2(2)


def test_dimensions_past_the_table_are_refused_as_scipy_refuses():
    with pytest.raises(ValueError, match=r"Maximum supported dimensionality is 1024\."):
        sobol(1025)
    assert sobol(1024, scramble=False).random(2).shape == (2, 1024)
