"""The proof of a noise model: each check is an exact symbolic fact (plus numeric confirmations).

Checks of :func:`prove` (names as in the report and in ``fricgen verify --json``):

- ``ode_residual``: X dD/du - u D + f simplifies to exactly 0 on every branch of u, and D is
  continuous at the branch points (a jump would put a delta function into dD/du). X = nu kT is
  *not* the model's own (``NoiseModel.variance_scale``, from noise.py): it is the coefficient of
  dD/du that the zero-current lemma reads off the current of the calculus on the pair phase space
  (symbolic masses, inertias, radii and kT; theta from the definitions F-47..49), times the
  model's mobility. So a model whose D was derived with a wrong nu kT (kT dropped, the wrong
  theta, another calculus' amplitude) fails here. For the integral form (F-22) SymPy
  differentiates under the integral sign (Leibniz rule).
- ``zero_current_3d`` / ``zero_current_2d``: (J^f + J^fn) P_B = 0 on the full pair phase space
  (12 resp. 6 momentum components) in each dimension where the law's contact mode exists (spinning:
  3-D only): the current of the calculus, from its definition (F-47..49), equals
  -(residual / u) C_m^T v_m for arbitrary D(u), f(u) (:func:`fricgen.derive.noise.mode_proofs.zero_current`),
  and the residual with that dimension's X vanishes.
- ``contact_mode``: the facts of the mode (:func:`fricgen.derive.noise.mode_proofs.mode_facts`): the
  engines' velocity is C_m v, their forces and torques are -C_m^T v_m f/u (power -f u), and
  C_m M^-1 C_m^T = mu_m x projector with mu_m read off and equal to the engines' formula.
- ``noise_covariance``: sigma sigma^T / 2 = kT D C_m^T C_m (F-50) for every written form of the
  noise (sliding: the paper's sigma_hat and its random force and torque, F-24, F-25), in each dimension.
- ``boundary_condition``: for nu != 0, D is the decaying solution, D exp(-u^2/2X) -> 0 as
  u -> oo (the ODE alone admits adding C exp(u^2/2X)); HK has no free constant.
- ``nonnegative_finite``: D >= 0 and finite for u >= 0: proven from the representation (F-22)
  (or D = f/u) with f >= 0, or by SymPy's assumptions; the limit u -> 0+ is finite (and >= 0 for
  kT = 1, mu = 7, equal spheres R = 1/2, m = 1); and confirmed numerically at the reference points
  of the kernel check (several kT, mu, w, r and parameter values, u up to 1e3 sqrt(nu kT)).

Every law is proven by this one path, whatever its contact mode (``mode = "sliding"``, the default,
``"rolling"`` or ``"spinning"``; docs/physics-modes.md): C_m is the mode's map and mu_m its mobility
(the model's ``mobility``). The law-independent facts (lemma, mode facts) are read from the on-disk
cache of :mod:`fricgen.derive.noise.lemma_cache` when present, and proven (and stored) otherwise.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import sympy as sp

from ..law.symbols import kT, mu, r, u, w
from . import lemma_cache, modes
from .derivation import Calculus, NoiseModel, branches, integral_amplitude
from .reference import Point, reference_points, sample_problem

#: Numeric values at which nonnegative_finite checks the sign of D(0+).
SAMPLE_VALUES = {kT: 1.0, mu: 7.0, r: 1.0}
SAMPLE_WEIGHTS = (0.05, 1.0, 60.0)


@dataclass(frozen=True)
class Report:
    """The verification report of one noise model: named checks, details, timing.

    Attributes
    ----------
    law : str
        The law's name.
    calculus : str
        The calculus of the model.
    closed_form : bool
        Whether D is in closed form.
    checks : dict of str to bool
        Each check by name (the ODE residual, zero current in 3-D and 2-D, the covariance, the
        boundary condition, D >= 0 and finite, ...): True where it passed.
    details : dict of str to str
        What a check found, for the report.
    seconds : float
        The wall time of the verification [s].
    reference_points : tuple
        The reference values of D that the proof checked for sign and finiteness; the backends check
        their printed kernels against the same values (:func:`verify`).
    """

    law: str
    calculus: str
    closed_form: bool
    checks: dict[str, bool]
    details: dict[str, str] = field(default_factory=dict)
    seconds: float = 0.0
    reference_points: tuple[Point, ...] = field(default=(), repr=False, compare=False)

    @property
    def verified(self) -> bool:
        """Whether every check passed."""
        return all(self.checks.values())

    def as_dict(self) -> dict:
        """The report as plain data (the JSON of ``fricgen verify --json``).

        Returns
        -------
        dict
            law, calculus, closed_form, verified, checks, details and seconds.
        """
        return {
            "law": self.law,
            "calculus": self.calculus,
            "closed_form": self.closed_form,
            "verified": self.verified,
            "checks": dict(self.checks),
            "details": dict(self.details),
            "seconds": round(self.seconds, 3),
        }


def prove(model: NoiseModel) -> Report:
    """The symbolic facts of a noise model.

    The ODE residual f - u D + nu kT dD/du = 0 (F-20), zero current on the pair phase space in 3-D and
    2-D, the noise covariance (F-50), the boundary condition (F-22), D >= 0 and finite. No printed code
    is checked here (see :func:`fricgen.derive.verify`).

    Parameters
    ----------
    model : NoiseModel
        The noise model of one law and calculus (:func:`fricgen.derive.derive_noise`).

    Returns
    -------
    Report
        One boolean per check, details, seconds. A wrong amplitude is reported there, never raised.
    """
    start = time.perf_counter()
    checks: dict[str, bool] = {}
    details: dict[str, str] = {}
    mode = model.law.mode
    dims = modes.dimensions(mode)  # (3, 2); spinning (3,)
    scales = {dim: lemma_scale(model, dim) for dim in dims}
    a = scales[3]
    if a is None:
        checks["ode_residual"] = False
        details["ode_residual"] = "the zero-current lemma gives no nu kT for this calculus"
    else:
        details["nu_kT"] = str(a)
        residuals = [_reduced(x) for x in ode_residuals(model, a)]
        checks["ode_residual"] = all(x == 0 for x in residuals)
        if not checks["ode_residual"]:
            details["ode_residual"] = _describe_residuals(model, residuals)
    for dim in dims:
        lemma = lemma_cache.lemma(mode, dim, model.calculus.value)
        same = scales[dim] is not None and a is not None and sp.simplify(scales[dim] - a) == 0
        checks[f"zero_current_{dim}d"] = lemma.holds and checks["ode_residual"] and same
    facts = {f"{d}d_{k}": v for d in dims for k, v in lemma_cache.facts(mode, d).items()}
    identities = {k: v for k, v in facts.items() if k.endswith("noise_covariance")}
    checks["contact_mode"] = all(facts.values())
    details["contact_mode"] = f"{mode}: mu_m = C_m M^-1 C_m^T / projector, read off and equal to the formula"
    if not checks["contact_mode"]:
        details["contact_mode"] = f"{mode}: failed {[k for k, v in facts.items() if not v]}"
    checks["noise_covariance"] = all(identities.values())
    if not checks["noise_covariance"]:
        details["noise_covariance"] = f"failed: {[k for k, v in identities.items() if not v]}"
    checks["boundary_condition"] = a is not None and _decays(model, a)
    points = reference_points(model, a if a is not None else model.variance_scale)
    checks["nonnegative_finite"], why = _nonnegative_finite(model, checks, points)
    if why:
        details["nonnegative_finite"] = why
    seconds = time.perf_counter() - start
    return Report(model.law.name, model.calculus.value, model.closed_form, checks, details, seconds, tuple(points))


def lemma_scale(model: NoiseModel, dim: int = 3) -> sp.Expr | None:
    """nu kT of the model's calculus as the zero-current lemma derives it on the ``dim``-D pair phase
    space (independently of noise.py) for the law's contact mode, for the model's contact mobility
    (mu_m of that mode); None if the lemma fails."""
    return lemma_cache.lemma(model.law.mode, dim, model.calculus.value).nu_kT(model.mobility)


def _reduced(expr: sp.Expr) -> sp.Expr:
    """``expr`` simplified, 0 exactly when it vanishes identically.

    Each distinct unevaluated Integral (the representation F-22, after differentiation under the
    integral sign) is treated as an independent symbol while simplifying. That is sound (zero for
    every value of the symbol implies zero), and exact for the residuals of this module, in which
    the integral enters linearly; it spares SymPy's simplify from working on integrals, which is
    slow when the expression is not zero.
    """
    integrals = {i: sp.Dummy("integral") for i in expr.atoms(sp.Integral)}
    cheap = sp.expand(sp.powsimp(sp.expand(expr.xreplace(integrals))))
    if cheap != 0:
        cheap = sp.simplify(cheap)
    return cheap.xreplace({d: i for i, d in integrals.items()})


def _is_zero(expr: sp.Expr) -> bool:
    return _reduced(expr) == 0


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


def ode_residuals(model: NoiseModel, a: sp.Expr | None = None) -> list[sp.Expr]:
    """Residuals a D' - u D + f per interval, then jumps of D at interior branch points; a = nu kT
    from the zero-current lemma (:func:`lemma_scale`) unless given."""
    intervals = _intervals(model)
    a = lemma_scale(model) if a is None else a
    if a is None:
        raise ValueError(f"the zero-current lemma gives no nu kT for the {model.calculus.value} calculus")
    residuals = [a * sp.diff(d, u) - u * d + f for _, _, d, f in intervals]
    for (_, point, left, _), (_, _, right, _) in zip(intervals, intervals[1:]):
        residuals.append(left.subs(u, point) - right.subs(u, point))
    return residuals


def _describe_residuals(model: NoiseModel, residuals: list[sp.Expr]) -> str:
    """What is wrong, in words: residuals on intervals of u, and jumps of D at branch points (listed
    after the intervals' residuals, as ode_residuals orders them)."""
    intervals = _intervals(model)
    parts = [f"nonzero on {lo} <= u < {hi}: {x}" for (lo, hi, _, _), x in zip(intervals, residuals) if x != 0]
    jumps = residuals[len(intervals) :]
    for (_, point, _, _), x in zip(intervals, jumps):
        if x != 0:
            parts.append(f"D jumps by {-x} at u = {point} (f is discontinuous there)")
    if model.calculus is Calculus.HK and any(x != 0 for x in jumps):
        parts.append("with HK, D = f/u inherits every jump of f: leave hk out of the law's calculi")
    return "; ".join(parts)


def _decays(model: NoiseModel, a: sp.Expr) -> bool:
    if a == 0:
        return model.calculus is Calculus.HK
    if not model.closed_form:
        return _is_zero(model.amplitude - integral_amplitude(model.law.friction, a))
    last = _pieces(model.amplitude)[-1].expr
    scaled = sp.powsimp(sp.expand(last * sp.exp(-(u**2) / (2 * a))))
    try:
        return sp.limit(scaled, u, sp.oo) == 0
    except (NotImplementedError, ValueError):
        return False


def _nonnegative_finite(model: NoiseModel, checks: dict[str, bool], points: list) -> tuple[bool, str]:
    """D >= 0 and finite on u >= 0: symbolic argument, finite limit at 0, numeric confirmation on the
    reference values of the kernel check (:func:`fricgen.derive.noise.reference.reference_points`)."""
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
    problem = sample_problem(points)
    return not problem, problem
