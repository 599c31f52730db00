"""Special functions for generated kernels (Numba has no scipy.special inside nopython code)."""

import math

import numba

_SQRT_PI = 1.7724538509055160273


@numba.njit(cache=True)
def erfcx(x):
    """Scaled complementary error function exp(x^2) erfc(x), relative error < 1e-15.

    exp(x^2) erfc(x) directly for 0 <= x < 4 (x^2 < 16 keeps the rounding of x*x harmless);
    Laplace's continued fraction 1/sqrt(pi) / (x + (1/2)/(x + 1/(x + (3/2)/(x + ...))))
    beyond, with 20 terms below x = 10 and 10 above; erfcx(-x) = 2 exp(x^2) - erfcx(x).
    Asymptotically erfcx(x) ~ 1/(x sqrt(pi)): no overflow for large x.
    """
    if x < 0.0:
        return 2.0 * math.exp(x * x) - erfcx(-x)
    if x < 4.0:
        return math.exp(x * x) * math.erfc(x)
    terms = 20 if x < 10.0 else 10
    t = x
    for k in range(terms, 0, -1):
        t = x + 0.5 * k / t
    return 1.0 / (_SQRT_PI * t)
