"""Noise tables: the fast evaluation of an integral-form D, shared by the backends.

A law without a closed-form D pays the quadrature of (F-22) at every evaluation (about 140 evaluations
of f and of an exponential). Where f factorises as f = h(w, r) g(u), h free of u and g free of w and r,
D = h(w, r) D_g(u) with D_g the (F-22) integral of g, which depends on u, a = kT nu and the parameters
only. A simulation knows a (its kT and the contact mobilities of its particles) and the parameters,
so at its start the kernels tabulate D_g for each a: piecewise polynomials of degree 11 in
x = u/sqrt(a) on geometric zones (fricgen.generated.special: table_points, table_zone, table_value),
each zone cut into as few equal pieces (a power of two, at most TABLE_PIECES) as pass two checks against
the quadrature: the two highest Chebyshev coefficients of each piece below TABLE_TOLERANCE times its
lowest, and its polynomial within TABLE_TOLERANCE (relative) of the quadrature at both ends, the middle
and the quarter points. A zone that would need more pieces (a kink, an underflowing D) and speeds
beyond x = 2^20 keep the quadrature, and so does every call whose a or parameters are not those of a
table. The tables are appended to ``params`` (the kernel ABI is unchanged): the engine's Simulation
builds them with the law module's ``tabulate_<calculus>(mobilities, kT, params)``, the LAMMPS plugin
lazily per (a, parameters) on first use. ``verify``'s kernel check builds them for each of its cases
and checks the tabulated D against mpmath like the quadrature (fricgen.derive.backends.numba_kernels.accuracy).

Not tabulated (quadrature only): laws whose f has branch points in u (a table piece across a kink
converges slowly), laws whose g is not analytic at u = 0 (a power u**alpha with alpha not a
nonnegative integer: polynomial pieces near u = 0 reach only about 1e-9, measured for alpha = 1/2)
and laws where w or r enters f other than as a factor.
"""

from __future__ import annotations

import sympy as sp

from ..law.laws import FrictionLaw
from ..law.symbols import r, u, w
from ..noise.derivation import NoiseModel, switches

#: Relative accuracy each table piece must reach against the quadrature (the kernel check demands 1e-10 against mpmath).
TABLE_TOLERANCE = 1e-11
#: Most pieces of one zone; a zone that needs more keeps the quadrature.
TABLE_PIECES = 256


def table_factor(law: FrictionLaw, model: NoiseModel) -> sp.Expr | None:
    """h(w, r) with f = h g(u), g free of w and r, when ``model``'s D is the integral (F-22) of a law without
    branches in u; None otherwise (the kernels keep the quadrature alone)."""
    if model.closed_form or model.variance_scale == 0 or switches(law.friction):
        return None
    factor, shape = sp.factor_terms(law.friction).as_independent(u, as_Add=False)
    if shape.free_symbols & {w, r} or not _analytic_at_zero(shape):
        return None
    return factor


def _analytic_at_zero(shape: sp.Expr) -> bool:
    """No power of an expression that vanishes at u = 0 with an exponent other than a nonnegative
    integer (u**alpha, sqrt(u)): such a g has no convergent polynomial expansion at u = 0."""
    for power in shape.atoms(sp.Pow):
        whole = power.exp.is_integer and power.exp.is_nonnegative
        if power.base.has(u) and not whole and sp.simplify(power.base.subs(u, 0)) == 0:
            return False
    return True


__all__ = ["TABLE_PIECES", "TABLE_TOLERANCE", "table_factor"]
