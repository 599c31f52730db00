"""The text of Numba kernels, piece by piece: decorators and signatures (the kernel ABI), headers and
docstrings, Python's spelling of branches and of the guards at u = 0 (:data:`SYNTAX`), and the quadrature of (F-22).

:mod:`.modules` assembles modules from these pieces (and prints each expression through its
``_kernel``, which applies the stable rewrites of :mod:`..printing`). Nothing here imports Numba:
the kernels are text.
"""

from __future__ import annotations

import math

from ...law.lawdata import Interval
from ..printing import Syntax

#: Every kernel is inlined into the kernels that call it (contact_<c> -> noise_amplitude_<c> ->
#: _gaussian_tail ...): a compiled call that passes ``params`` on holds a reference to it, two atomic
#: reference-count operations per call, which cost as much as the arithmetic of a closed-form D.
DECORATOR = '@numba.njit(cache=True, error_model="numpy", inline="always")'
#: Explicit signatures: the engines take these kernels as first-class functions (one compiled engine
#: for every law), which needs each kernel compiled for exactly this signature. They are the kernel
#: ABI of fricgen.kernels (SCALAR_KERNEL, FRICTION_KERNEL, NOISE_KERNEL, FIELD_KERNEL, CONTACT_KERNEL),
#: spelled as strings since derive does not import Numba; tests/codegen/test_abi.py checks that they agree.
SIGNATURES = {
    "r, params": "float64(float64, float64[::1])",
    "x, params": "float64(float64, float64[::1])",
    "u, w, r, params": "float64(float64, float64, float64, float64[::1])",
    "u, w, r, mu, kT, params": "float64(float64, float64, float64, float64, float64, float64[::1])",
    "xs, params, out": "void(float64[::1], float64[::1], float64[::1])",
    "w, r, params": "float64(float64, float64, float64[::1])",
}
#: tabulate_<c>(mobilities, kT, params) -> params followed by the noise tables (fricgen.derive.backends.tables).
TABULATE_SIGNATURE = "float64[::1](float64[::1], float64, float64[::1])"
CONTACT_SIGNATURE = "UniTuple(float64, 2)(float64, float64, float64, float64, float64, float64[::1])"
INDENT = "    "
#: Python's spelling of a kernel body (printing.body).
SYNTAX = Syntax(
    indent=INDENT,
    assign="{name} = {value}",
    give="return {value}",
    first_branch="if {condition}:",
    next_branch="elif {condition}:",
    close=None,
    nan="math.nan",
    guard=("if u <= 0.0:", INDENT + "return {value}"),
)


def decorator(args: str, signature: str | None = None) -> str:
    return f'@numba.njit("{signature or SIGNATURES[args]}", cache=True, error_model="numpy", inline="always")'


def quote_doc(text: str) -> str:
    return '"""' + text.replace("\\", "\\\\").replace('"""', "'''") + '"""'


def ranges_literal(ranges: list[Interval]) -> str:
    """``RANGES``: (lower, upper, lower_closed, upper_closed) per parameter, inf as ``math.inf``."""

    def end(x: float) -> str:
        return "math.inf" if x == math.inf else repr(float(x))

    items = [f"({end(i.lower)}, {end(i.upper)}, {i.lower_closed}, {i.upper_closed})" for i in ranges]
    return "(" + ", ".join(items) + ("," if len(items) == 1 else "") + ")"


# --- the quadrature of (F-22) ------------------------------------------------------------------------

TAIL_KERNEL = '''
{decorator}
def _gaussian_tail(u, a, w, r, params):
    """(1/a) int_u^oo f(s) exp(-(s^2 - u^2)/(2a)) ds (F-22), with t = s - u.

    {order}-point Gauss-Legendre on the panels [0, h], [h, 2h], [2h, 4h], ... with
    h = a / (u + sqrt(a)) / 256 (the weight decays on the scale a/(u + sqrt(a))), until the
    Gaussian weight exp(-(2ut + t^2)/(2a)) is below exp(-46). For u < h the first panel starts
    as [0, h/2^16] and doubles up to h: f may not be analytic at s = 0 (u**alpha).
    """
    h = a / (u + math.sqrt(a)) / 256.0
    lo = 0.0
    hi = h if u >= h else h / 65536.0
    total = 0.0
    while True:
        mid = 0.5 * (lo + hi)
        half = 0.5 * (hi - lo)
        for j in range({order}):
            t = mid + half * _GL_NODES[j]
            total += half * _GL_WEIGHTS[j] * friction(u + t, w, r, params) * math.exp(-(2.0 * u * t + t * t) / (2.0 * a))
        if (2.0 * u * hi + hi * hi) / (2.0 * a) > 46.0:
            return total / a
        lo = hi
        hi = 2.0 * hi
'''

#: The quadrature of a law whose f has branches in u: each panel is cut where a branch condition of f
#: changes sign (_next_cut), so that no kink or jump of f lies inside a Gauss-Legendre panel.
SPLIT_TAIL_KERNEL = '''
{decorator}
def _panel(u, a, lo, hi, w, r, params):
    """{order}-point Gauss-Legendre of f(u + t) exp(-(2ut + t^2)/(2a)) over lo <= t <= hi."""
    mid = 0.5 * (lo + hi)
    half = 0.5 * (hi - lo)
    total = 0.0
    for j in range({order}):
        t = mid + half * _GL_NODES[j]
        total += half * _GL_WEIGHTS[j] * friction(u + t, w, r, params) * math.exp(-(2.0 * u * t + t * t) / (2.0 * a))
    return total


{decorator}
def _next_cut(u, lo, hi, w, r, params):
    """The first t in (lo, hi] up to which no branch condition of f changes sign between lo and t:
    hi, or a sign change of a _switch_<k> of f(u + t), found by bisection to the last bit."""
    end = hi
{cuts}
    return end


{decorator}
def _gaussian_tail(u, a, w, r, params):
    """(1/a) int_u^oo f(s) exp(-(s^2 - u^2)/(2a)) ds (F-22), with t = s - u.

    {order}-point Gauss-Legendre on the panels [0, h], [h, 2h], [2h, 4h], ... with
    h = a / (u + sqrt(a)) / 256 (the weight decays on the scale a/(u + sqrt(a))), until the
    Gaussian weight exp(-(2ut + t^2)/(2a)) is below exp(-46); each panel cut at the branch
    points of f inside it (_next_cut; at most 64 pieces). For u < h the first panel starts as
    [0, h/2^16] and doubles up to h: f may not be analytic at s = 0 (u**alpha).
    """
    h = a / (u + math.sqrt(a)) / 256.0
    lo = 0.0
    hi = h if u >= h else h / 65536.0
    total = 0.0
    while True:
        start = lo
        for _ in range(64):
            end = _next_cut(u, start, hi, w, r, params)
            total += _panel(u, a, start, end, w, r, params)
            if end >= hi:
                break
            start = end
        if (2.0 * u * hi + hi * hi) / (2.0 * a) > 46.0:
            return total / a
        lo = hi
        hi = 2.0 * hi
'''

_CUT = """    left = _switch_{k}(u + lo, w, r, params) > 0.0
    if (_switch_{k}(u + end, w, r, params) > 0.0) != left:
        a = lo
        b = end
        while True:
            m = 0.5 * (a + b)
            if m <= a or m >= b:
                break
            if (_switch_{k}(u + m, w, r, params) > 0.0) == left:
                a = m
            else:
                b = m
        end = b"""


def tail_kernels(order: int, count: int) -> str:
    """The quadrature helpers of (F-22) for a law with ``count`` switch functions (fricgen.derive.noise.derivation.switches)."""
    if count == 0:
        return TAIL_KERNEL.format(decorator=DECORATOR, order=order).lstrip("\n")
    cuts = "\n".join(_CUT.format(k=k) for k in range(count))
    return SPLIT_TAIL_KERNEL.format(decorator=DECORATOR, order=order, cuts=cuts).lstrip("\n")


# --- the noise tables of an integral-form D (fricgen.derive.backends.tables) ------------------------------

TABLE_KERNEL = '''
@numba.njit(cache=True, error_model="numpy")
def _noise_table(a, params):
    """The noise table of D_g(u) = D(u) / _factor(w, r, params) for a = kT nu (layout: special.table_value):
    zone by zone, the fewest equal pieces (1, 2, 4, ... {pieces}) whose polynomials pass the checks against
    _gaussian_tail at relative {tolerance!r} (special.table_zone); a zone that needs more keeps the quadrature."""
    scale = _factor(1.0, 1.0, params)
    root = math.sqrt(a)
    zones = []
    for k in range(TABLE_ZONES):
        rows = numpy.empty((0, TABLE_ROW))
        pieces = 1
        while scale > 0.0 and scale < math.inf and pieces <= {pieces}:
            xs = table_points(k, pieces)
            values = numpy.empty(xs.size)
            for i in range(xs.size):
                values[i] = _gaussian_tail(root * xs[i], a, 1.0, 1.0, params) / scale
            rows = table_zone(k, pieces, values, {tolerance!r})
            if rows.shape[0] > 0:
                break
            pieces *= 2
        zones.append(rows)
    return table_block(a, params, zones)
'''

TABULATE_KERNEL = '''
@numba.njit("{signature}", cache=True, error_model="numpy")
def tabulate_{calculus}(mobilities, kT, params):
    """params[:{n}] followed by the noise tables of the {calculus} calculus, a = kT nu = {a}, one for each contact
    mobility mu in mobilities: noise_amplitude_{calculus} uses a table where its a and params[:{n}] are the
    table's, the quadrature elsewhere (fricgen.derive.backends.tables)."""
    own = params[:{n}].copy()
    blocks = []
    for mu in mobilities:
        blocks.append(_noise_table({scale}, own))
    return table_join(own, blocks)
'''

TABLED_AMPLITUDE = """    a = {scale}
    tabled = table_value(u, a, params, {n})
    if tabled >= 0.0:
        return _factor(w, r, params) * tabled
    return _gaussian_tail(u, a, w, r, params)
"""


FIELD_KERNEL = '''
{decorator}
def force_field(xs, params, out):
    """out[i] = force(xs[i], params) at every position xs[i]: one call per configuration, the
    scalar kernel inlined (an engine calling force per particle pays an indirect call each time)."""
    for i in range(xs.size):
        out[i] = force(xs[i], params)
'''
