"""The generated erfcx against scipy over the whole range, negative arguments included."""

from fractions import Fraction

import mpmath
import numpy as np
from scipy.special import erfcx as reference

from derive.erfcx_pieces import erfcx_pieces
from generated.special import _DENOMINATOR, _NUMERATOR, _PIECES, erfcx


def test_erfcx_matches_scipy():
    xs = np.concatenate([-np.geomspace(1e-10, 25, 200), [0.0], np.geomspace(1e-10, 1e300, 2000), np.linspace(0, 10, 1001)])
    got = np.array([erfcx(x) for x in xs])
    np.testing.assert_allclose(got, reference(xs), rtol=2e-15)


def test_the_pieces_are_within_two_ulp_of_the_exact_function():
    xs = np.random.default_rng(5).uniform(0.0, 4.0, 3000)
    with mpmath.workdps(40):
        exact = np.array([float(mpmath.exp(mpmath.mpf(x) ** 2) * mpmath.erfc(mpmath.mpf(x))) for x in xs])
    assert np.max(np.abs(np.array([erfcx(x) for x in xs]) / exact - 1)) <= 2 * np.finfo(float).eps


def test_the_pieces_are_derives_chebyshev_interpolants():
    assert _PIECES.tolist() == erfcx_pieces()


def test_erfcx_has_the_asymptote_and_no_overflow():
    for x in (30.0, 1e3, 1e8, 1e150):
        assert 0 < 1 - erfcx(x) * x * np.sqrt(np.pi) <= 1 / (2 * x**2) + 1e-15  # 1 - 1/(2x^2) + ...


def _times_x_plus(p, q, c):
    """Coefficients (lowest power first) of x p(x) + c q(x)."""
    out = [Fraction(0)] * max(len(p) + 1, len(q))
    for j, value in enumerate(p):
        out[j + 1] += value
    for j, value in enumerate(q):
        out[j] += c * value
    return out


def test_the_continued_fraction_coefficients_are_its_exact_convergent():
    a_before, a, b_before, b = [Fraction(1)], [Fraction(0), Fraction(1)], [Fraction(0)], [Fraction(1)]
    for k in range(1, 21):  # t = x + (1/2)/(x + (2/2)/(x + ... (20/2)/x)) = A/B
        a_before, a = a, _times_x_plus(a, a_before, Fraction(k, 2))
        b_before, b = b, _times_x_plus(b, b_before, Fraction(k, 2))
    assert all(c == 0 for c in a[0::2]) and all(c == 0 for c in b[1::2])  # A odd, B even
    assert [Fraction(c) for c in _NUMERATOR] == b[0::2] and [Fraction(c) for c in _DENOMINATOR] == a[1::2]
