"""Reference values of D: the noise amplitude evaluated independently of any printed kernel.

For each case of :data:`KERNEL_CASES` (kT != 1 among them, so that a lost kT cannot hide), D is
evaluated at u = 0 (where D or its limit u -> 0+ is finite), at 1e-6 ... 1e3 sqrt(nu kT) and at
the branch points of f and D (and 1e-6 either side):

- closed form: the model's SymPy expression, evaluated by mpmath at 30 digits, the float inputs
  as exact rationals;
- integral form: (F-22) by adaptive quadrature (mpmath.quad, 20 digits) of the law's f, with the
  nu kT that the zero-current lemma reads off the phase space (not the model's own; see
  :mod:`fricgen.derive.noise.verification`).

The proof uses these values to confirm that D is finite and >= 0; each backend checks its printed
kernels against them (``kernel_accuracy`` of the Numba backend).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import sympy as sp

from ..law.symbols import kT, mu, r, u, w
from .derivation import NoiseModel, branches, sign_changes, switches

#: Cases (kT, mu, w, r, factor on every parameter default).
KERNEL_CASES = ((1.0, 7.0, 1.0, 1.0, 1.0), (2.0, 7.0, 60.0, 1.05, 1.0), (0.3, 2.0, 0.05, 1.0, 0.5), (2.5, 3.5, 5.0, 1.0, 3.0))
#: Speeds in units of sqrt(a), a = nu kT (sqrt(mu kT) when nu = 0); not only powers of two and their simple
#: fractions, which are ends of the pieces of noise tables (fricgen.derive.backends.tables), where a table is exact.
SPEEDS = (1e-6, 1e-3, 0.1, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.5, 5.0, 7.0, 10.0, 20.0, 30.0, 60.0, 100.0, 300.0, 1000.0)
#: Working precision (digits) of the reference values.
DIGITS = 30
#: Working precision of the quadrature of (F-22) (about 1e-20; the kernels' own error is ~1e-13).
QUAD_DIGITS = 20


def reference_amplitude(model: NoiseModel, a: sp.Expr, values: dict) -> callable:
    """D(u) [kT t0/sigma^2] at high precision, as a reference: the closed form, or the integral (F-22)
    D = (1/a) int_u^oo f(s) exp(-(s^2 - u^2)/(2a)) ds with a = kT nu by mpmath.quad.

    Float values enter as the exact rationals of their binary values: a Float substituted into
    SymPy would round products such as 1/(2a) to 15 digits, and exp(u^2/2a) at u = 1e3 sqrt(a)
    amplifies that to a relative error of 1e-10.

    Parameters
    ----------
    model : NoiseModel
        The noise model (:func:`fricgen.derive.derive_noise`).
    a : sympy.Expr
        The velocity variance scale a = kT nu [sigma^2/t0^2], ``model.variance_scale``.
    values : dict
        The value of every other symbol (parameters, ``w``, ``r``, ``kT``, ``mu``), by SymPy symbol.

    Returns
    -------
    callable
        D(u) for u [sigma/t0], with mpmath numbers at the working precision of the caller.

    Examples
    --------
    >>> from fricgen.derive import derive_noise, kT, make_law, mu, reference_amplitude, w
    >>> law = make_law("constant", "w*kappa", parameters={"kappa": {"default": 1.0, "unit": "kT/sigma"}}, weight="wca")
    >>> model = derive_noise(law, "ito")
    >>> values = {kT: 1.0, mu: 2.0, w: 1.0, **{p.symbol: p.default for p in law.parameters}}
    >>> D = reference_amplitude(model, model.variance_scale, values)
    >>> print(f"{float(D(0.0)):.6f}")  # D(0) = w kappa sqrt(pi / (2 kT mu)) (F-31)
    0.886227
    """
    values = {k: sp.Rational(v) if isinstance(v, float) else v for k, v in values.items()}
    if model.closed_form:
        return sp.lambdify(u, model.amplitude.subs(values), modules="mpmath")
    f = sp.lambdify(u, model.law.friction.subs(values), modules="mpmath")
    scale = mpmath.mpf(str(sp.N(a.subs(values), DIGITS + 5)))
    # split at the kinks of f (Min, Max, Piecewise in u): a kink inside an interval costs mpmath.quad its accuracy
    kinks = [k for g in switches(model.law.friction) for k in sign_changes(g.subs(values), 60 * mpmath.sqrt(scale))]

    def integral(x):
        with mpmath.workdps(QUAD_DIGITS):
            x = mpmath.mpf(x)
            h = scale / (x + mpmath.sqrt(scale))  # the integrand decays on this scale
            points = sorted({x, x + h, x + 8 * h, x + 64 * h, *(k for k in kinks if k > x)}) + [mpmath.inf]
            return mpmath.quad(lambda t: f(t) * mpmath.exp(-(t - x) * (t + x) / (2 * scale)), points) / scale

    return integral


def _at_zero(model: NoiseModel, evaluate: callable, values: dict) -> mpmath.mpf | None:
    """D at u = 0: the value, else the limit u -> 0+ if finite, else None (no point at 0)."""
    try:
        value = mpmath.mpmathify(evaluate(mpmath.mpf(0)))
        if mpmath.isfinite(value):
            return value
    except (ZeroDivisionError, ValueError, TypeError):
        pass
    if not model.closed_form:
        return None
    pieces = branches(model.amplitude)
    first = (pieces[0].expr if pieces else model.amplitude).subs({k: sp.Rational(v) for k, v in values.items()})
    limit = sp.limit(first, u, 0, "+")
    return mpmath.mpf(str(sp.N(limit, DIGITS))) if limit.is_finite else None


def _speeds(model: NoiseModel, a: sp.Expr, values: dict) -> list[float]:
    """SPEEDS in units of sqrt(a) and the branch points of f and D (each also 1e-6 relative either side)."""
    scale = float(a.subs(values)) or float((kT * model.mobility).subs(values))
    points = {math.sqrt(scale) * x for x in SPEEDS}
    for expr in (model.law.friction, model.amplitude):
        for piece in branches(expr) or []:
            if piece.lower != 0:
                edge = float(piece.lower.subs(values))
                points |= {edge * (1 - 1e-6), edge, edge * (1 + 1e-6)}
    return sorted(x for x in points if x > 0)


@dataclass(frozen=True)
class Point:
    """One reference value: D at ``speed`` for the kernel ``arguments`` (w, r, mu, kT, params);
    ``exact`` is None when D could not be evaluated there (``problem`` says why)."""

    case: str
    speed: float
    arguments: tuple
    exact: mpmath.mpf | None
    problem: str = ""

    @property
    def where(self) -> str:
        return f"u = {self.speed:.6g} ({self.case})"


def _within(parameter, value: float) -> float:
    """``value`` if the parameter's declared range admits it, else its default (which it always admits)."""
    return value if value in parameter.range else parameter.default


def reference_points(model: NoiseModel, a: sp.Expr, cases: tuple[tuple[float, ...], ...] = KERNEL_CASES) -> list[Point]:
    """Reference values of D (:func:`reference_amplitude`, DIGITS digits) for every case (kT, mu, w, r,
    factor on every parameter default): at u = 0 where D or its limit is finite, then at :func:`_speeds`."""
    found = []
    for temperature, mobility, weight, distance, factor in cases:
        scaled = {p.symbol: _within(p, factor * p.default) for p in model.law.parameters}
        values = {**scaled, kT: temperature, mu: mobility, w: weight, r: distance}
        arguments = (weight, distance, mobility, temperature, [float(values[p.symbol]) for p in model.law.parameters])
        case = f"kT={temperature}, mu={mobility}, w={weight}, r={distance}, parameters x{factor}"
        with mpmath.workdps(DIGITS):
            try:
                evaluate = reference_amplitude(model, a, values)
                at_zero = _at_zero(model, evaluate, values)
                speeds = _speeds(model, a, values)
            except Exception as error:  # noqa: BLE001 - an amplitude that cannot be evaluated at all
                found.append(Point(case, math.nan, arguments, None, f"{type(error).__name__}: {error}"))
                continue
            if at_zero is not None:
                found.append(Point(case, 0.0, arguments, at_zero))
            for x in speeds:
                try:
                    found.append(Point(case, x, arguments, mpmath.mpmathify(evaluate(mpmath.mpf(x)))))
                except (ArithmeticError, ValueError, TypeError) as error:
                    found.append(Point(case, x, arguments, None, f"{type(error).__name__}: {error}"))
    return found


def sample_problem(points: list[Point]) -> str:
    """The first reference value that is not a finite real >= 0, described; "" if there is none."""
    for p in points:
        if p.exact is None:
            return f"D cannot be evaluated at {p.where}: {p.problem}"
        if isinstance(p.exact, mpmath.mpc) or not mpmath.isfinite(p.exact):
            return f"D = {p.exact} at {p.where}"
        if p.exact < 0:
            return f"D = {mpmath.nstr(p.exact, 6)} < 0 at {p.where}"
    return ""
