"""The scipy.stats.qmc engine: sequences extend, sets refuse to, qmc_quad works."""

import numpy as np
import pytest
from scipy.integrate import qmc_quad
from scipy.stats import qmc

import samplab
from samplab.qmc import Engine


def test_sequence_engine_extends_and_resets():
    e = Engine("sobol.owen", d=3, seed=7)
    # a first draw of 100 unbalances the net: scipy's warning says so
    with pytest.warns(UserWarning, match="balance properties"):
        first = e.random(100)
    second = e.random(28)
    whole = samplab.generate("sobol.owen", n=128, d=3, seed=7)
    assert np.vstack([first, second]).tobytes() == whole.tobytes()
    e.reset()
    with pytest.warns(UserWarning, match="balance properties"):
        assert e.random(100).tobytes() == first.tobytes()
    e.reset().fast_forward(100)
    assert e.random(28).tobytes() == second.tobytes()


def test_whole_set_engines_refuse_to_extend():
    e = Engine("jitter", d=2, seed=1)
    assert e.random(16).tobytes() == samplab.generate("jitter", n=16, seed=1).tobytes()
    with pytest.raises(samplab.Error, match="cannot extend"):
        e.random(16)
    with pytest.raises(samplab.Error, match="cannot fast-forward"):
        Engine("jitter").fast_forward(4)
    assert isinstance(e, qmc.QMCEngine)


@pytest.mark.parametrize("call", [lambda e: e.random(-1), lambda e: e.fast_forward(-1), lambda e: e.random(2.5)])
def test_negative_or_fractional_counts_are_refused_by_name(call):
    # a ValueError, as scipy's engines raise, and the count's position left as it was
    e = Engine("sobol.owen", d=2)
    with pytest.raises(ValueError, match="^n = "):
        call(e)
    assert e.num_generated == 0


def test_generator_seeds_are_deterministic():
    a = Engine("halton.owen", d=2, seed=np.random.default_rng(3)).random(8)
    b = Engine("halton.owen", d=2, seed=np.random.default_rng(3)).random(8)
    c = Engine("halton.owen", d=2, seed=np.random.default_rng(4)).random(8)
    assert a.tobytes() == b.tobytes() and a.tobytes() != c.tobytes()


def test_qmc_quad_with_samplab_engines():
    """Failure probability about 3e-3: scipy's interval of 5 standard errors from 8
    randomizations (Student's t with 7 degrees of freedom: 1.6e-3 each; measured at seeds
    0-299 with samplab's qmc_quad: Sobol' 0 beyond, Halton 2), and the standard error under
    1e-3 (measured: at most 1.2e-4 over seeds 0-49). Fixed seed. Least work: 8 x 1024 points, scipy's defaults."""
    # the integral of prod(x_i^2) over [0,1]^3 is 1/27
    def f(x):
        return np.prod(x**2, axis=0)

    for spec in ("sobol.owen", "halton.owen"):
        res = qmc_quad(f, [0, 0, 0], [1, 1, 1], n_estimates=8, n_points=1024, qrng=Engine(spec, d=3, seed=1))
        assert res.integral == pytest.approx(1 / 27, abs=5 * res.standard_error + 1e-6)
        assert res.standard_error < 1e-3


def test_samplab_qmc_quad_draws_at_the_engines_seed():
    # an engine's seed picks the randomizations (it was ignored: every seed gave the default
    # seed's integral), as scipy's qmc_quad draws from its engine's generator; an engine of
    # other dimensions than the box is refused
    from samplab.qmc import qmc_quad as ours

    def f(x):
        return np.prod(x**2, axis=0)

    box = ([0, 0, 0], [1, 1, 1])
    run = lambda seed: ours(f, *box, qrng=Engine("sobol.owen", d=3, seed=seed))
    assert run(1) == run(1)
    assert run(1).integral != run(2).integral
    assert run(None) == ours(f, *box)
    with pytest.raises(samplab.Error, match="d=2 for a box of 3 dimensions"):
        ours(f, *box, qrng=Engine("sobol.owen", d=2, seed=1))


def test_scipy_discrepancy_takes_engine_points():
    x = Engine("sobol.owen", d=2, seed=2).random(64)
    assert qmc.discrepancy(x, method="L2-star") == pytest.approx(samplab.discrepancy("l2-star", x), rel=1e-10)
