"""Tail integrals of (F-22) in closed form: int_x^oo f(s) exp(-s^2/(2a)) ds for the closed families.

A branch of f has a closed-form tail when it is an *exponential polynomial* in u,

    f(u) = sum_c P_c(u) exp(c u),                                              (E-1)

each P_c a polynomial in u and each rate c free of u (c = 0: a plain polynomial; Stribeck's
w (kappa_d + (kappa_s - kappa_d) exp(-u/u_s)) has rates 0 and -1/u_s; sinh and cosh of a linear
function of u are rewritten as exponentials first). Completing the square,

    -s^2/(2a) + c s = -(s - a c)^2/(2a) + a c^2/2,

so with t = s - a c each term is a sum of Gaussian moments at the shifted lower limit,

    int_x^oo s^n e^{c s} e^{-s^2/2a} ds = e^{a c^2/2} sum_m binom(n, m) (a c)^(n - m) I_m(x - a c),   (E-2)
    I_m(y) = int_y^oo t^m e^{-t^2/2a} dt   (I_0 with erfc, I_1 elementary, then I_m = a y^(m-1) e^{-y^2/2a} + (m - 1) a I_(m-2)).

D = e^{u^2/2a} (...) / a then holds exp(u^2/2a + a c^2/2) erfc((u - a c)/sqrt(2a)), which the printer
writes erfcx((u - a c)/sqrt(2a)) e^{c u} (fricgen.derive.backends.printing: no overflow for large u).
Everything else (tanh, rational functions, fractional powers, products of exponentials with
non-polynomial factors) has no closed form here: its D keeps the integral (F-22).
"""

from __future__ import annotations

import sympy as sp

from ..law.symbols import u


def gaussian_tail_moment(n: int, x: sp.Expr, a: sp.Expr) -> sp.Expr:
    """I_n(x) = int_x^oo s^n exp(-s^2/(2a)) ds, exactly; I_n(oo) = 0."""
    if x == sp.oo:
        return sp.Integer(0)
    if n == 0:
        return sp.sqrt(sp.pi * a / 2) * sp.erfc(x / sp.sqrt(2 * a))
    if n == 1:
        return a * sp.exp(-(x**2) / (2 * a))
    return a * x ** (n - 1) * sp.exp(-(x**2) / (2 * a)) + (n - 1) * a * gaussian_tail_moment(n - 2, x, a)


def _hyperbolic_as_exp(expr: sp.Expr) -> sp.Expr:
    """sinh, cosh of arguments in u as exponentials (the family E-1 then holds them); other functions untouched."""
    return expr.replace(lambda e: isinstance(e, sp.sinh | sp.cosh) and e.has(u), lambda e: e.rewrite(sp.exp))


def _rate(argument: sp.Expr) -> tuple[sp.Expr, sp.Expr] | None:
    """(c, d) with argument = c u + d, c and d free of u; None if the argument is not linear in u."""
    argument = sp.expand(argument)
    c = argument.coeff(u, 1)
    d = sp.expand(argument - c * u)
    if c.has(u) or d.has(u):
        return None
    return c, d


def exponential_polynomial(expr: sp.Expr) -> dict[sp.Expr, sp.Expr] | None:
    """{c: P_c(u)} with expr = sum_c P_c(u) exp(c u) (E-1), P_c polynomial in u; None if expr is not of that form."""
    groups: dict[sp.Expr, sp.Expr] = {}
    for term in sp.Add.make_args(sp.expand(sp.powsimp(sp.expand(_hyperbolic_as_exp(expr))))):
        c, rest = sp.Integer(0), []
        for factor in sp.Mul.make_args(term):
            if isinstance(factor, sp.exp) and factor.has(u):
                found = _rate(factor.args[0])
                if found is None:
                    return None
                c, rest = c + found[0], [*rest, sp.exp(found[1])]
            elif factor.has(u) and not (factor == u or factor.is_Pow and factor.base == u and factor.exp.is_Integer and factor.exp > 0):
                return None
            else:
                rest.append(factor)
        c = sp.simplify(c)
        groups[c] = groups.get(c, sp.Integer(0)) + sp.Mul(*rest)
    return groups


def tail(expr: sp.Expr, x: sp.Expr, a: sp.Expr) -> sp.Expr | None:
    """int_x^oo expr(s) exp(-s^2/2a) ds for expr an exponential polynomial in u (E-1, E-2), else None."""
    groups = exponential_polynomial(expr)
    if groups is None:
        return None
    total = sp.Integer(0)
    for c, polynomial in groups.items():
        shift = a * c
        try:
            poly = sp.Poly(sp.expand(polynomial.subs(u, u + shift)), u)  # P(t + a c) in t
        except sp.PolynomialError:
            return None
        if any(coefficient.has(u) for coefficient in poly.coeffs()):
            return None
        moments = sp.Add(*[k * gaussian_tail_moment(m[0], x - shift, a) for m, k in zip(poly.monoms(), poly.coeffs())])
        total += moments if c == 0 else sp.exp(a * c**2 / 2) * moments
    return total


__all__ = ["exponential_polynomial", "gaussian_tail_moment", "tail"]
