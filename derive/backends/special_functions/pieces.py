"""The piecewise polynomials of erfcx(x) = exp(x^2) erfc(x) on 0 <= x < PIECES * WIDTH.

Piece j covers [j WIDTH, (j + 1) WIDTH) and holds the interpolant of erfcx at the DEGREE + 1
Chebyshev points of that interval, as coefficients of powers of t = x - (j + 1/2) WIDTH (lowest
first), computed with mpmath at 40 digits and rounded to the nearest double. The interpolation
error is below 3e-16 relative (|t| <= WIDTH / 2 = 1/8 and erfcx is entire). The literal table in
derive/backends/special_functions/special.py is this function's output; tests/codegen/test_special.py checks
that they agree. Print it with ``python -m fricgen.derive.backends.special_functions.pieces``.
"""

from __future__ import annotations

import textwrap

import mpmath

WIDTH, PIECES, DEGREE = 0.25, 16, 12


def erfcx_pieces() -> list[list[float]]:
    """Coefficients of the PIECES polynomials, one row per piece."""
    with mpmath.workdps(40):
        rows = []
        for j in range(PIECES):
            centre, half = (j + mpmath.mpf(1) / 2) * WIDTH, mpmath.mpf(WIDTH) / 2
            nodes = [centre + half * mpmath.cos(mpmath.pi * (n + mpmath.mpf(1) / 2) / (DEGREE + 1)) for n in range(DEGREE + 1)]
            powers = mpmath.matrix([[(x - centre) ** p for p in range(DEGREE + 1)] for x in nodes])
            values = mpmath.matrix([mpmath.exp(x * x) * mpmath.erfc(x) for x in nodes])
            rows.append([float(c) for c in mpmath.lu_solve(powers, values)])
        return rows


def literal(rows: list[list[float]], indent: str = "    ") -> str:
    """The rows as Python tuples, one per piece, wrapped to lines of at most 120 characters."""
    wrap = textwrap.TextWrapper(width=120, initial_indent=indent + "(", subsequent_indent=indent + " ")
    return "\n".join(wrap.fill(", ".join(repr(c) for c in row)) + ")," for row in rows)


if __name__ == "__main__":
    print(literal(erfcx_pieces()))
