"""Special functions for generated kernels (Numba has no scipy.special inside nopython code)."""

import math
from fractions import Fraction

import numba

_SQRT_PI = 1.7724538509055160273
_TERMS = 20  # depth of Laplace's continued fraction for x >= 4


def _convergent(terms):
    """The continued fraction t = x + (1/2)/(x + (2/2)/(x + ... (terms/2)/x)) as A(x)/B(x), by the
    recurrences P_k = x P_(k-1) + (k/2) P_(k-2). A is odd and B even, both with positive coefficients:
    returns (B(x), A(x)/x) as coefficient tuples in y = x^2, lowest power first, exact before rounding."""
    a_before, a = [Fraction(1)], [Fraction(0), Fraction(1)]
    b_before, b = [Fraction(0)], [Fraction(1)]
    for k in range(1, terms + 1):
        a_before, a = a, _times_x_plus(a, a_before, Fraction(k, 2))
        b_before, b = b, _times_x_plus(b, b_before, Fraction(k, 2))
    return tuple(float(c) for c in b[0::2]), tuple(float(c) for c in a[1::2])


def _times_x_plus(p, q, c):
    """Coefficients of x p(x) + c q(x)."""
    out = [Fraction(0)] * max(len(p) + 1, len(q))
    for j, value in enumerate(p):
        out[j + 1] += value
    for j, value in enumerate(q):
        out[j] += c * value
    return out


_NUMERATOR, _DENOMINATOR = _convergent(_TERMS)


@numba.njit(cache=True)
def erfcx(x):
    """Scaled complementary error function exp(x^2) erfc(x), relative error < 2e-15.

    exp(x^2) erfc(x) directly for 0 <= x < 4 (x^2 < 16 keeps the rounding of x*x harmless);
    beyond, Laplace's continued fraction erfcx = 1/(sqrt(pi) t) with 20 terms, evaluated as its
    convergent B(x)/(sqrt(pi) A(x)): two Horner sums in x^2 with positive terms (no cancellation) and
    one division; erfcx(-x) = 2 exp(x^2) - erfcx(x). Above x = 1e8, erfcx = 1/(x sqrt(pi)) to
    1/(2 x^2) < 1e-16 (no overflow for large x).
    """
    if x < 0.0:
        return 2.0 * math.exp(x * x) - erfcx(-x)
    if x < 4.0:
        return math.exp(x * x) * math.erfc(x)
    if x > 1e8:
        return 1.0 / (_SQRT_PI * x)
    y, top = x * x, len(_NUMERATOR) - 1
    numerator, denominator = _NUMERATOR[top], _DENOMINATOR[top]
    for j in range(top - 1, -1, -1):
        numerator = numerator * y + _NUMERATOR[j]
        denominator = denominator * y + _DENOMINATOR[j]
    return numerator / (_SQRT_PI * x * denominator)
