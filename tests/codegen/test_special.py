"""The generated erfcx against scipy over the whole range, negative arguments included."""

import numpy as np
from scipy.special import erfcx as reference

from generated.special import erfcx


def test_erfcx_matches_scipy():
    xs = np.concatenate([-np.geomspace(1e-10, 25, 200), [0.0], np.geomspace(1e-10, 1e300, 2000), np.linspace(0, 10, 1001)])
    got = np.array([erfcx(x) for x in xs])
    np.testing.assert_allclose(got, reference(xs), rtol=2e-15)


def test_erfcx_has_the_asymptote_and_no_overflow():
    for x in (30.0, 1e3, 1e8, 1e150):
        assert 0 < 1 - erfcx(x) * x * np.sqrt(np.pi) <= 1 / (2 * x**2) + 1e-15  # 1 - 1/(2x^2) + ...
