"""Verification of a noise model: each check is an exact symbolic fact (plus a numeric confirmation).

Checks of :func:`verify` (names as in the report and in ``fricgen verify --json``):

- ``ode_residual``: nu kT dD/du - u D + f simplifies to exactly 0 on every branch of u, and D is
  continuous at the branch points (a jump would put a delta function into dD/du). For the
  integral form (F-22) SymPy differentiates under the integral sign (Leibniz rule).
- ``zero_current_3d`` / ``zero_current_2d``: (J^f + J^fn) P_B = 0 on the full pair phase space
  (12 resp. 6 momentum components): the current of the calculus, from its definition (F-47..49),
  equals -(residual / u) C^T u_perp for arbitrary D(u), f(u) (:mod:`derive.phase_space`), and the
  residual vanishes.
- ``noise_covariance``: sigma sigma^T / 2 = kT D C^T C (F-50) for the paper's sigma_hat and for the
  random force and torque (F-24, F-25), in 3-D and 2-D.
- ``boundary_condition``: for nu != 0, D is the decaying solution, D exp(-u^2/2kTnu) -> 0 as
  u -> oo (the ODE alone admits adding C exp(u^2/2kTnu)); HK has no free constant.
- ``nonnegative_finite``: D >= 0 and finite for u >= 0: proven from the representation (F-22)
  (or D = f/u) with f >= 0, or by SymPy's assumptions; the limit u -> 0+ is finite; and
  confirmed numerically on a grid of u, w (with kT = 1, mu = 7: equal spheres R = 1/2, m = 1).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import mpmath
import sympy as sp

from . import phase_space
from .noise import Calculus, NoiseModel, branches, integral_amplitude, numeric_amplitude
from .symbols import kT, mu, r, u, w

#: Numeric values used for the sample confirmation of nonnegative_finite.
SAMPLE_VALUES = {kT: 1.0, mu: 7.0, r: 1.0}
SAMPLE_WEIGHTS = (0.05, 1.0, 60.0)


@dataclass(frozen=True)
class Report:
    """Verification report of one model: named checks, details, timing."""

    law: str
    calculus: str
    closed_form: bool
    checks: dict[str, bool]
    details: dict[str, str] = field(default_factory=dict)
    seconds: float = 0.0

    @property
    def verified(self) -> bool:
        return all(self.checks.values())

    def as_dict(self) -> dict:
        return {
            "law": self.law,
            "calculus": self.calculus,
            "closed_form": self.closed_form,
            "verified": self.verified,
            "checks": dict(self.checks),
            "details": dict(self.details),
            "seconds": round(self.seconds, 3),
        }


def verify(model: NoiseModel) -> Report:
    """Verify a noise model; never raises for a wrong amplitude, reports it instead."""
    start = time.perf_counter()
    checks: dict[str, bool] = {}
    details: dict[str, str] = {}
    residuals = ode_residuals(model)
    checks["ode_residual"] = all(_is_zero(x) for x in residuals)
    if not checks["ode_residual"]:
        details["ode_residual"] = "nonzero: " + "; ".join(str(sp.simplify(x)) for x in residuals if not _is_zero(x))
    for dim in (3, 2):
        lemma = phase_space.zero_current_lemma(dim, model.calculus.value)
        checks[f"zero_current_{dim}d"] = lemma and checks["ode_residual"]
    identities = {f"{d}d_{k}": v for d in (3, 2) for k, v in phase_space.covariance_identities(d).items()}
    checks["noise_covariance"] = all(identities.values())
    if not checks["noise_covariance"]:
        details["noise_covariance"] = f"failed: {[k for k, v in identities.items() if not v]}"
    checks["boundary_condition"] = _decays(model)
    checks["nonnegative_finite"], why = _nonnegative_finite(model, checks)
    if why:
        details["nonnegative_finite"] = why
    return Report(model.law.name, model.calculus.value, model.closed_form, checks, details, time.perf_counter() - start)


def _is_zero(expr: sp.Expr) -> bool:
    cheap = sp.expand(sp.powsimp(sp.expand(expr)))
    return cheap == 0 or sp.simplify(cheap) == 0


def _pieces(expr: sp.Expr) -> list:
    found = branches(expr)
    if found is None:
        raise ValueError(f"cannot split {expr} into branches of u")
    return found


def _intervals(model: NoiseModel) -> list[tuple[sp.Expr, sp.Expr, sp.Expr, sp.Expr]]:
    """(lower, upper, D branch, f branch) on the common refinement of D's and f's branches."""
    d_pieces, f_pieces = _pieces(model.amplitude), _pieces(model.law.friction)
    edges = sorted({p.lower for p in d_pieces + f_pieces} | {sp.oo}, key=lambda e: _position(e, d_pieces + f_pieces))
    result = []
    for lower, upper in zip(edges, edges[1:]):
        probe = (lower + upper) / 2 if upper != sp.oo else (2 * lower if lower != 0 else sp.Integer(1))
        result.append((lower, upper, _at(d_pieces, probe), _at(f_pieces, probe)))
    return result


def _position(edge: sp.Expr, pieces: list) -> int:
    """Rank of a branch point among all branch points (they are ordered within each function)."""
    if edge == sp.oo:
        return 10**9
    return sum(bool((edge - p.lower).is_positive) for p in pieces)


def _at(pieces: list, probe: sp.Expr) -> sp.Expr:
    for p in pieces:
        if sp.simplify(probe - p.lower).is_nonnegative and (p.upper == sp.oo or sp.simplify(p.upper - probe).is_positive):
            return p.expr
    raise ValueError(f"no branch contains u = {probe}")


def ode_residuals(model: NoiseModel) -> list[sp.Expr]:
    """Residuals nu kT D' - u D + f per interval, then jumps of D at interior branch points."""
    intervals = _intervals(model)
    a = model.variance_scale
    residuals = [a * sp.diff(d, u) - u * d + f for _, _, d, f in intervals]
    for (_, point, left, _), (_, _, right, _) in zip(intervals, intervals[1:]):
        residuals.append(left.subs(u, point) - right.subs(u, point))
    return residuals


def _decays(model: NoiseModel) -> bool:
    if model.calculus is Calculus.HK:
        return True
    a = model.variance_scale
    if not model.closed_form:
        return sp.simplify(model.amplitude - integral_amplitude(model.law.friction, a)) == 0
    last = _pieces(model.amplitude)[-1].expr
    scaled = sp.powsimp(sp.expand(last * sp.exp(-(u**2) / (2 * a))))
    try:
        return sp.limit(scaled, u, sp.oo) == 0
    except (NotImplementedError, ValueError):
        return False


def _nonnegative_finite(model: NoiseModel, checks: dict[str, bool]) -> tuple[bool, str]:
    """D >= 0 and finite on u >= 0: symbolic argument, finite limit at 0, numeric confirmation."""
    represented = checks["ode_residual"] and checks["boundary_condition"]
    proven = bool(model.amplitude.is_nonnegative) or represented  # (F-22) or f/u with f >= 0
    if not proven:
        return False, "no symbolic proof: D is not the solution (F-22) of a law with f >= 0"
    values = {**SAMPLE_VALUES, **model.law.defaults}
    first = _pieces(model.amplitude)[0].expr
    if model.closed_form:
        at_zero = sp.limit(first, u, 0, "+")
        if not at_zero.is_finite:
            return False, f"D -> {at_zero} as u -> 0+"
        for weight in SAMPLE_WEIGHTS:
            if sp.N(at_zero.subs({**values, w: weight})) < 0:
                return False, f"D(0+) = {at_zero} < 0 at w = {weight}"
    return _samples(model, values)


def _samples(model: NoiseModel, values: dict) -> tuple[bool, str]:
    """D finite and >= 0 at u > 0 on a grid spanning 1e-6 ... 1e3 sqrt(kT mu) and the branch points."""
    a = float((kT * model.mobility).subs(values))
    grid = {a**0.5 * x for x in (1e-6, 1e-3, 0.1, 0.5, 1, 2, 5, 10, 30, 100, 1000)}
    for weight in SAMPLE_WEIGHTS:
        evaluate = numeric_amplitude(model, {**values, w: weight})
        points = grid | {float(p.lower.subs({**values, w: weight})) for p in _pieces(model.amplitude)} - {0.0}
        with mpmath.workdps(30):
            for point in sorted(points):
                try:
                    value = mpmath.mpmathify(evaluate(mpmath.mpf(point)))
                except (ZeroDivisionError, ValueError, OverflowError):
                    return False, f"D cannot be evaluated at u = {point:g}, w = {weight}"
                if isinstance(value, mpmath.mpc) or not mpmath.isfinite(value):
                    return False, f"D = {value} at u = {point:g}, w = {weight}"
                if value < 0:
                    return False, f"D = {mpmath.nstr(value, 6)} < 0 at u = {point:g}, w = {weight}"
    return True, ""
