"""Special functions for generated kernels (Numba has no scipy.special inside nopython code)."""

import math

import numba

_SQRT_PI = 1.7724538509055160273
#: Laplace's continued fraction t = x + (1/2)/(x + (2/2)/(x + ... (20/2)/x)) as A(x)/B(x), from the
#: recurrences P_k = x P_(k-1) + (k/2) P_(k-2): B is even and A odd, with positive coefficients, here
#: as polynomials in y = x^2, lowest power first: B(x) and A(x)/x. The values are exact dyadic
#: rationals (tests/codegen/test_special.py recomputes them with fractions).
_NUMERATOR = (3628800.0, 52979477.783203125, 122404170.41015625, 104750739.84375, 43369889.0625, 9816994.6875,
              1287706.875, 99577.5, 4437.0, 104.5, 1.0)  # fmt: skip
_DENOMINATOR = (13427061.108398438, 89513740.72265625, 161124733.30078125, 122761701.5625, 47740661.71875,
                10416144.375, 1335403.125, 101745.0, 4488.75, 105.0, 1.0)  # fmt: skip


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
