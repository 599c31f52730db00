"""The generated special functions: erfcx against scipy over the whole range, negative arguments
included; expm1_given_exp against mpmath, and the printer's rewrite that uses it."""

import math
from fractions import Fraction

import mpmath
import numpy as np
import sympy as sp
from scipy.special import erfcx as reference
from sympy.codegen.cfunctions import expm1

from fricgen.derive.backends.printing import expm1_given_exp as given_exp_function
from fricgen.derive.backends.printing import share_exp
from fricgen.derive.backends.special_functions.pieces import erfcx_pieces
from fricgen.generated.special import _DENOMINATOR, _NUMERATOR, _PIECES, erfcx, expm1_given_exp


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


def test_expm1_given_exp_is_within_one_ulp_on_both_sides_of_minus_ln_2():
    xs = np.concatenate([np.random.default_rng(6).uniform(-40.0, 3.0, 3000), -math.log(2) + np.linspace(-1e-12, 1e-12, 11), [0.0, -1e-300]])
    with mpmath.workdps(40):
        exact = np.array([float(mpmath.expm1(mpmath.mpf(x))) for x in xs])
    got = np.array([expm1_given_exp(math.exp(x), x) for x in xs])
    assert np.all(np.abs(got - exact) <= np.spacing(np.abs(exact)))


def test_the_printer_shares_exp_only_where_it_is_safe():
    u, a = sp.symbols("u a", positive=True)
    both = 3 * sp.exp((u**2 - 1) / a) - 2 * expm1(u**2 / a - 1 / a)  # one argument, written two ways
    assert share_exp(both) == 3 * sp.exp((u**2 - 1) / a) - 2 * given_exp_function(sp.exp((u**2 - 1) / a), (u**2 - 1) / a)
    assert share_exp(expm1(u)) == expm1(u)  # no exp(u) beside it: nothing to share
    branch = sp.Piecewise((both, u < 1), (u, True)) * 2  # CSE would evaluate exp outside the condition
    assert share_exp(branch) == branch
