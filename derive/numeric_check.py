"""The numbers the engines use, checked: the printed noise-amplitude kernel against mpmath.

derive never imports Numba or the runtime, so the kernel is checked as *code*: the module text
that :func:`derive.modules.law_module` prints for the model is executed as plain Python, with
``numba.njit`` replaced by an identity decorator and ``erfcx`` taken from the hand-written source
that the generator copies (derive/kernel_sources/special.py, executed the same way). Its
``noise_amplitude_<calculus>`` is compared with an independent evaluation of D:

- closed form: the model's SymPy expression, evaluated by mpmath at 30 digits, the float inputs
  as exact rationals (this checks the printer: the stable rewrites erfcx/expm1, constant folding,
  CSE, branches and the guard at u = 0);
- integral form: (F-22) by adaptive quadrature (mpmath.quad, 20 digits) of the law's f, with the
  nu kT that the zero-current lemma reads off the phase space (not the model's own; see
  derive.verification), which also checks the kernel's Gauss–Legendre quadrature.

Points (:func:`reference_points`): u = 0 (where D or its limit u -> 0+ is finite), 1e-6 ... 1e3
sqrt(nu kT) and the branch points of f and D (and 1e-6 either side), for each case of
:data:`KERNEL_CASES` (kT != 1 among them, so that a lost kT cannot hide). The verifier also checks
the sign and finiteness of D on these reference values. Pure Python raises where Numba's error
model returns inf/nan (an overflowing exp, a division by zero); such a point fails the check.
"""

from __future__ import annotations

import builtins
import importlib
import math
import types
from dataclasses import dataclass

import mpmath
import sympy as sp

from . import modules
from .noise import NoiseModel, branches, sign_changes, switches
from .symbols import kT, mu, r, u, w

#: Largest relative error of the printed kernel that the check accepts.
KERNEL_TOLERANCE = 1e-8
#: Cases (kT, mu, w, r, factor on every parameter default).
KERNEL_CASES = ((1.0, 7.0, 1.0, 1.0, 1.0), (2.0, 7.0, 60.0, 1.05, 1.0), (0.3, 2.0, 0.05, 1.0, 0.5), (2.5, 3.5, 5.0, 1.0, 3.0))
#: Speeds in units of sqrt(a), a = nu kT (sqrt(mu kT) when nu = 0).
SPEEDS = (1e-6, 1e-3, 0.1, 0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 100.0, 300.0, 1000.0)
#: Working precision (digits) of the reference values.
DIGITS = 30
#: Working precision of the quadrature of (F-22) (about 1e-20; the kernels' own error is ~1e-13).
QUAD_DIGITS = 20


class _Numba:
    """Stands in for numba in the executed kernel code: ``njit`` leaves the function as it is."""

    @staticmethod
    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function


def execute(source: str, modules: dict[str, object]) -> dict:
    """Run module ``source`` as plain Python; its imports may reach only ``modules`` (by the name as
    written, with leading dots for relative imports). Returns the module's namespace."""

    def importer(name, globals=None, locals=None, fromlist=(), level=0):
        key = "." * level + name
        if key not in modules:
            raise ImportError(f"the checked kernel code may import only {sorted(modules)}, not {key!r}")
        return modules[key]

    namespace = {"__builtins__": {**vars(builtins), "__import__": importer}, "__name__": "derive_kernel_check"}
    exec(compile(source, "<printed kernels>", "exec"), namespace)  # noqa: S102 - code printed by derive.modules
    return namespace


def special_namespace() -> dict:
    """derive/kernel_sources/special.py (generated.special) run as plain Python: its functions and tables."""
    return execute(modules.SPECIAL_SOURCE.read_text(), {"math": math, "numba": _Numba(), "numpy": importlib.import_module("numpy")})


def python_kernels(model: NoiseModel) -> dict:
    """The namespace of the law module that derive.modules prints for ``model`` (as generate writes
    it), run as plain Python."""

    special = types.ModuleType("special")
    special.__dict__.update(special_namespace())
    imports = {"math": math, "numba": _Numba(), "..special": special}
    source = modules.law_module(model.law, {model.calculus.value: model}, "", "derive.verification")
    if "numpy" in source:  # generated code may use numpy (tests/test_layers.py); loaded only when it does
        imports["numpy"] = importlib.import_module("numpy")
    return execute(source, imports)


def reference_amplitude(model: NoiseModel, a: sp.Expr, values: dict) -> callable:
    """D as a function of u (mpmath, at the working precision of the caller), all other symbols
    given in ``values``: the closed form, or (F-22) with a = ``a`` by mpmath.quad.

    Float values enter as the exact rationals of their binary values: a Float substituted into
    SymPy would round products such as 1/(2a) to 15 digits, and exp(u^2/2a) at u = 1e3 sqrt(a)
    amplifies that to a relative error of 1e-10."""
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


def reference_points(model: NoiseModel, a: sp.Expr) -> list[Point]:
    """Reference values of D (:func:`reference_amplitude`, DIGITS digits) for every case of
    KERNEL_CASES: at u = 0 where D or its limit is finite, then at :func:`_speeds`."""
    found = []
    for temperature, mobility, weight, distance, factor in KERNEL_CASES:
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


def kernel_accuracy(model: NoiseModel, points: list[Point]) -> tuple[float, str]:
    """Largest relative error of the printed ``noise_amplitude_<calculus>`` against the reference
    ``points``, and where it occurs (or what failed). Infinite when the kernel cannot be printed or
    run, returns a non-finite value, or a reference value is missing."""
    try:
        kernel = python_kernels(model)[f"noise_amplitude_{model.calculus.value}"]
    except Exception as error:  # noqa: BLE001 - any failure to print or run the code is a failed check
        return math.inf, f"the kernel could not be printed or run: {type(error).__name__}: {error}"
    worst, where = 0.0, ""
    for p in points:
        if p.exact is None:
            return math.inf, f"no reference value at {p.where}: {p.problem}"
        try:
            got = kernel(p.speed, *p.arguments)
        except (ArithmeticError, ValueError, TypeError) as error:
            return math.inf, f"the kernel raised at {p.where}: {type(error).__name__}: {error}"
        if not isinstance(got, int | float):
            return math.inf, f"the kernel returned {got!r} at {p.where}"
        error = _relative(got, p.exact)
        if not error <= worst:
            worst, where = error, f"{p.where}: kernel {got!r}, mpmath {mpmath.nstr(p.exact, 17)}"
    return worst, where


def _relative(got: float, exact) -> float:
    if isinstance(exact, mpmath.mpc) or not mpmath.isfinite(exact) or not math.isfinite(got):
        return math.inf
    if exact == 0:
        return abs(got)
    return float(abs((mpmath.mpf(got) - exact) / exact))
