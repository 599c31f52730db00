"""Noise amplitude D(u, r) of a frictional contact from the zero-current condition (F-20).

For the calculus theta (Itô 0, Stratonovich 1/2, Hänggi–Klimontovich 1) and nu = (1 - theta) mu,

    nu kT dD/du - u D = -f,                                                   (F-20)

whose decaying solution for nu != 0 is, with a = kT nu,

    D(u) = (1/a) int_u^oo f(s) exp(-(s^2 - u^2) / (2a)) ds,                    (F-22)

and D = f/u for nu = 0 (HK; the paper's (F-23) carries a spurious kT). D has units of
force / velocity (friction coefficient); the random contact force is sqrt(D) times a white
noise of variance 2 kT per unit time.

Closed forms: f is split at its branch points (Min, Max, Piecewise) into pieces on intervals of
u; on each piece an exponential polynomial sum_c P_c(u) exp(c u) (polynomials P_c, rates c free of u:
Stribeck's law among them) integrates exactly with the Gaussian moments
I_n(x) = int_x^oo s^n exp(-s^2/2a) ds after completing the square (:mod:`.closed_forms`).
Other laws keep the exact integral (F-22), evaluated by quadrature downstream, and so do laws whose
branches SymPy cannot decide (a branch point it cannot solve for, order or place): then f stays one
piece on [0, oo). ``NoiseModel.reason`` says why a model has no closed form. A Min, Max or
Piecewise that does not depend on u (a weight in r, say) is no branch point in u: it stays a factor.

The physics: docs/physics.md#the-noise-amplitude-d.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import mpmath
import sympy as sp

from ..calculus import Calculus
from ..law.expressions import snippet, time_limit
from ..law.laws import FrictionLaw, LawError
from ..law.symbols import kT, mu, r, s, u, w
from .closed_forms import gaussian_tail_moment, tail


def contact_mobility(m_i, m_k, radius_i, radius_k, inertia_i=None, inertia_k=None) -> sp.Expr:
    """The contact mobility of a pair, mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (F-21).

    Parameters
    ----------
    m_i, m_k : float or sympy.Expr
        The masses [m].
    radius_i, radius_k : float or sympy.Expr
        The radii R_i, R_k [sigma].
    inertia_i, inertia_k : float or sympy.Expr, optional
        The moments of inertia [m sigma^2]; None: solid spheres, I = 2/5 m R^2.

    Returns
    -------
    sympy.Expr
        mu [1/m].

    Raises
    ------
    ValueError
        For non-positive masses, radii or moments of inertia.

    Examples
    --------
    >>> from sympy import Rational
    >>> from fricgen.derive import contact_mobility
    >>> contact_mobility(1, 1, Rational(1, 2), Rational(1, 2))  # two default spheres
    7
    """
    m_i, m_k, radius_i, radius_k = (sp.nsimplify(sp.sympify(v)) for v in (m_i, m_k, radius_i, radius_k))
    inertia_i = sp.Rational(2, 5) * m_i * radius_i**2 if inertia_i is None else sp.nsimplify(sp.sympify(inertia_i))
    inertia_k = sp.Rational(2, 5) * m_k * radius_k**2 if inertia_k is None else sp.nsimplify(sp.sympify(inertia_k))
    named = {"m_i": m_i, "m_k": m_k, "R_i": radius_i, "R_k": radius_k, "I_i": inertia_i, "I_k": inertia_k}
    for name, value in named.items():
        if value.is_positive is False or value.is_zero:
            raise ValueError(f"{name} must be positive, got {value}")
    return 1 / m_i + 1 / m_k + radius_i**2 / inertia_i + radius_k**2 / inertia_k


@dataclass(frozen=True)
class NoiseModel:
    """The noise amplitude D(u, w, r) [kT t0/sigma^2] of a law for one calculus.

    It solves the zero-current condition nu kT dD/du - u D = -f with nu = (1 - theta) mu (F-20); for
    nu != 0 the decaying solution D = (1/(kT nu)) int_u^oo f(s) exp(-(s^2 - u^2)/(2 kT nu)) ds (F-22),
    for HK (nu = 0) D = f/u.

    Attributes
    ----------
    law : FrictionLaw
        The friction law.
    calculus : Calculus
        The calculus D was derived for.
    amplitude : sympy.Expr
        D (Piecewise for branched laws); in integral form it contains an unevaluated ``Integral``
        over ``s`` from u to oo.
    closed_form : bool
        False when ``amplitude`` is the integral representation (F-22).
    mobility : sympy.Expr
        The contact mobility mu [1/m] (a symbol or an expression of particle properties).
    reason : str
        For the integral form, why no closed form was found (a branch of f that is no exponential
        polynomial in u, or branches SymPy cannot decide); D then keeps the integral, evaluated by
        quadrature. Empty for a closed form.
    """

    law: FrictionLaw
    calculus: Calculus
    amplitude: sp.Expr
    closed_form: bool
    mobility: sp.Expr = mu
    reason: str = field(default="", compare=False)

    @property
    def nu(self) -> sp.Expr:
        """nu = (1 - theta) mu (F-21)."""
        return (1 - sp.Rational(self.calculus.theta)) * self.mobility

    @property
    def variance_scale(self) -> sp.Expr:
        """a = kT nu, the velocity variance scale of the contact mode."""
        return kT * self.nu


def derive_noise(law: FrictionLaw, calculus: Calculus | str, mobility: sp.Expr | float | None = None) -> NoiseModel:
    """Derive the noise amplitude D(u, w, r) [kT t0/sigma^2] of a law for a calculus.

    D solves nu kT dD/du - u D = -f with nu = (1 - theta) mu (F-20): theta = 0 Ito, 1/2 Stratonovich,
    1 HK (D = f/u). In closed form where one is found, else as the integral (F-22).

    Parameters
    ----------
    law : FrictionLaw
        A validated friction law.
    calculus : str or Calculus
        "ito", "stratonovich" or "hk".
    mobility : sympy.Expr or float, optional
        The contact mobility mu [1/m]; the symbol ``mu`` by default, or a positive number or
        expression (:func:`contact_mobility`).

    Returns
    -------
    NoiseModel
        D with how it was found.

    Examples
    --------
    >>> from fricgen.derive import derive_noise, make_law
    >>> law = make_law("viscous", "gamma_f*u", parameters={"gamma_f": {"default": 2.0, "unit": "kT t0/sigma^2"}})
    >>> derive_noise(law, "ito").amplitude  # linear friction: D = gamma_f in every calculus (F-29)
    gamma_f
    >>> coulomb = make_law("constant", "w*kappa", parameters={"kappa": {"default": 1.0, "unit": "kT/sigma"}}, weight="wca")
    >>> derive_noise(coulomb, "hk").amplitude  # HK: D = f/u (F-23)
    kappa*w/u
    """
    calculus = Calculus(calculus)
    mobility = mu if mobility is None else sp.nsimplify(sp.sympify(mobility))
    if mobility.is_positive is not True:
        raise LawError(f"contact mobility must be positive, got {mobility}")
    model = NoiseModel(law, calculus, sp.Integer(0), True, mobility)
    if calculus is Calculus.HK:
        pieces = branches(law.friction)
        if len(pieces) == 1:
            amplitude = sp.simplify(law.friction / u)
        else:
            amplitude = _piecewise([(sp.simplify(p.expr / u), p) for p in pieces])
        _check_rest_limit(law, amplitude)
        return NoiseModel(law, calculus, amplitude, True, mobility)
    closed, reason = _closed_form(law.friction, model.variance_scale)
    if closed is not None:
        return NoiseModel(law, calculus, closed, True, mobility)
    amplitude = integral_amplitude(law.friction, model.variance_scale)
    return NoiseModel(law, calculus, amplitude, False, mobility, reason)


#: Wall-time limit (seconds) of the limit u -> 0+ of the HK amplitude.
REST_LIMIT_TIME = 60.0


class _SlowLimit(Exception):
    """sp.limit took longer than REST_LIMIT_TIME."""


def _check_rest_limit(law: FrictionLaw, amplitude: sp.Expr) -> None:
    """The HK amplitude D = f/u needs a limit u -> 0+ that SymPy can take (finite or not: an infinite
    one is reported by the verifier); a LawError with the reason otherwise."""
    first = branches(amplitude)[0].expr
    try:
        with time_limit(REST_LIMIT_TIME, _SlowLimit()):
            sp.limit(first, u, 0, "+")
    except (NotImplementedError, ValueError, TypeError, _SlowLimit) as error:
        why = snippet(str(error) or type(error).__name__, 100)
        raise LawError(
            f"law {law.name} (hk): SymPy cannot take the limit of D = f/u = {snippet(str(first), 60)} as u -> 0+ ({why}); "
            "write exponents as numbers, or leave hk out of the law's calculi"
        ) from None


def integral_amplitude(friction: sp.Expr, a: sp.Expr) -> sp.Expr:
    """The exact integral representation (F-22), D = (1/a) int_u^oo f(s) e^{-(s^2-u^2)/2a} ds."""
    return sp.exp(u**2 / (2 * a)) / a * sp.Integral(friction.subs(u, s) * sp.exp(-(s**2) / (2 * a)), (s, u, sp.oo))


# --- branches of f in u ---------------------------------------------------------------------


@dataclass(frozen=True)
class Branch:
    """The expression of a piecewise function on lower <= u < upper."""

    expr: sp.Expr
    lower: sp.Expr
    upper: sp.Expr

    @property
    def probe(self) -> sp.Expr:
        """A point strictly inside the interval."""
        if self.upper == sp.oo:
            return 2 * self.lower if self.lower != 0 else sp.Integer(1)
        return (self.lower + self.upper) / 2


def branches(expr: sp.Expr) -> list[Branch]:
    """Split ``expr`` (Min/Max/Piecewise in u) into branches on ordered intervals of u >= 0.

    Returns a single branch on [0, oo) for smooth expressions, and also (holding all of ``expr``)
    when the branch points cannot be solved for, ordered or placed symbolically (see :func:`split`).
    """
    return split(expr)[0]


def split(expr: sp.Expr) -> tuple[list[Branch], str]:
    """:func:`branches`, and why ``expr`` was left in one piece although it has branches ("" if not).

    Integrals (the representation F-22) and Min, Max, Piecewise that do not depend on u (a weight in
    r) are kept whole: they are no branch points in u.
    """
    hidden: dict[sp.Dummy, sp.Expr] = {}
    folded = sp.piecewise_fold(_hide(expr, hidden).rewrite(sp.Piecewise))
    if not isinstance(folded, sp.Piecewise):
        return [Branch(expr, sp.Integer(0), sp.oo)], ""
    found, why = _split(folded, lambda e: str(e.xreplace(hidden)))
    if found is None:
        return [Branch(expr, sp.Integer(0), sp.oo)], f"SymPy cannot decide the branches of {snippet(str(expr), 80)} in u ({why})"
    return [Branch(b.expr.xreplace(hidden), b.lower.xreplace(hidden), b.upper.xreplace(hidden)) for b in found], ""


_OPAQUE = (sp.Min, sp.Max, sp.Piecewise, sp.Abs, sp.Heaviside, sp.sign)


def _hide(expr: sp.Basic, hidden: dict[sp.Dummy, sp.Expr]) -> sp.Basic:
    """``expr`` with its integrals and its branched parts free of u replaced by dummies (kept in
    ``hidden``), outermost first; a dummy is positive or real where the part is."""
    if isinstance(expr, sp.Integral) or isinstance(expr, _OPAQUE) and u not in expr.free_symbols:
        kind = {"positive": True} if expr.is_positive else {"real": True} if expr.is_real else {}
        hidden[dummy := sp.Dummy("opaque", **kind)] = expr
        return dummy
    if not expr.args or not expr.has(sp.Integral, *_OPAQUE):
        return expr
    return expr.func(*[_hide(a, hidden) for a in expr.args])


def _split(folded: sp.Piecewise, show: Callable[[sp.Expr], str]) -> tuple[list[Branch] | None, str]:
    """The branches of a folded Piecewise in u, or None and the undecided question (expressions
    written by ``show``)."""
    points: list[sp.Expr] = []
    for _, condition in folded.args:
        for relation in condition.atoms(sp.core.relational.Relational):
            if u not in relation.free_symbols:
                return None, f"the condition {show(relation)} of a branch in u does not involve u"
            try:
                roots = sp.solve(sp.Eq(relation.lhs, relation.rhs), u)
            except (NotImplementedError, ValueError, TypeError):
                roots = None
            if not isinstance(roots, list):
                return None, f"cannot solve {show(relation)} for u"
            for root in roots:
                if root.is_positive and root not in points:
                    points.append(root)
                elif not root.is_nonpositive and root not in points:
                    return None, f"cannot tell whether the branch point {show(root)} is positive"
    ordered = _ordered(points)
    if ordered is None:
        return None, f"cannot order the branch points {', '.join(map(show, points))}"
    edges = [sp.Integer(0), *ordered, sp.oo]
    result = []
    for lower, upper in zip(edges, edges[1:]):
        probe = Branch(sp.Integer(0), lower, upper).probe
        chosen = _branch_at(folded, probe)
        if chosen is None:
            return None, f"cannot tell which branch holds at u = {show(probe)}"
        result.append(Branch(chosen, lower, upper))
    return result, ""


def switches(expr: sp.Expr) -> list[sp.Expr]:
    """lhs - rhs of each condition in u of the branches of ``expr`` (Min, Max, Piecewise, Abs, ...),
    decided or not: ``expr`` is smooth in u between the sign changes of these functions."""
    folded = sp.piecewise_fold(expr.rewrite(sp.Piecewise))
    found: list[sp.Expr] = []
    for condition in folded.atoms(sp.core.relational.Relational):
        if u in condition.free_symbols and (g := condition.lhs - condition.rhs) not in found and -g not in found:
            found.append(g)
    return sorted(found, key=sp.default_sort_key)


def _ordered(points: list[sp.Expr]) -> list[sp.Expr] | None:
    ordered: list[sp.Expr] = []
    for p in points:
        position = 0
        for q in ordered:
            greater = (p - q).is_positive
            if greater is None:
                return None
            position += bool(greater)
        ordered.insert(position, p)
    return ordered


def _branch_at(folded: sp.Piecewise, probe: sp.Expr) -> sp.Expr | None:
    for expr, condition in folded.args:
        truth = sp.simplify(condition.subs(u, probe))
        if truth == sp.true:
            return expr
        if truth != sp.false:
            return None
    return None


def _piecewise(parts: list[tuple[sp.Expr, Branch]]) -> sp.Expr:
    """Piecewise((D_0, u < b_1), ..., (D_n, True)) from branches; a plain expression if one."""
    if len(parts) == 1:
        return parts[0][0]
    return sp.Piecewise(*[(d, u < b.upper) for d, b in parts[:-1]], (parts[-1][0], True))


# --- closed forms ---------------------------------------------------------------------------


def closed_form_amplitude(friction: sp.Expr, a: sp.Expr) -> sp.Expr | None:
    """(F-22) in closed form when every branch of f is an exponential polynomial in u (.closed_forms), else None."""
    return _closed_form(friction, a)[0]


def _closed_form(friction: sp.Expr, a: sp.Expr) -> tuple[sp.Expr | None, str]:
    """:func:`closed_form_amplitude` and, for None, why."""
    pieces, undecided = split(friction)
    if undecided:
        return None, undecided
    parts = []
    for j, piece in enumerate(pieces):
        head = tail(piece.expr, u, a)
        if head is None:
            where = "" if len(pieces) == 1 else f" on {piece.lower} <= u < {piece.upper}"
            return None, f"f = {snippet(str(piece.expr), 80)}{where} is not a sum of polynomials in u times exp(c u)"
        total = head - tail(piece.expr, piece.upper, a)
        for later in pieces[j + 1 :]:
            total += tail(later.expr, later.lower, a) - tail(later.expr, later.upper, a)
        amplitude = sp.powsimp(sp.expand(sp.exp(u**2 / (2 * a)) / a * total))
        parts.append((sp.simplify(amplitude), piece))
    return _piecewise(parts), ""


# --- numbers --------------------------------------------------------------------------------


def sign_changes(g: sp.Expr, reach, samples: int = 2000) -> list:
    """Where ``g`` (an expression in u alone) changes sign on 0 < u < ``reach``: scanned on a
    geometric grid from 1e-12 reach, each change refined by bisection (mpmath)."""
    evaluate = sp.lambdify(u, g, modules="mpmath")
    grid = [mpmath.mpf(reach) * mpmath.mpf(10) ** (12 * (k / samples - 1)) for k in range(samples + 1)]
    found = []
    for lo, hi in zip(grid, grid[1:]):
        left = evaluate(lo) > 0
        if (evaluate(hi) > 0) != left:
            for _ in range(200):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if (evaluate(mid) > 0) == left else (lo, mid)
            found.append(hi)
    return found


__all__ = [
    "Branch",
    "Calculus",
    "NoiseModel",
    "branches",
    "closed_form_amplitude",
    "contact_mobility",
    "derive_noise",
    "gaussian_tail_moment",
    "integral_amplitude",
    "sign_changes",
    "split",
    "switches",
    "r",
    "w",
]
