"""f >= 0, real and finite for every admissible parameter value, not only at the defaults.

A law declares the admissible values of each parameter (``Parameter.range``, an Interval; the
positive reals by default). :func:`check_ranges` establishes that f is >= 0, real and finite for
all u >= 0, w > 0, r > 0 and every combination of parameter values in their ranges:

1. symbolically where SymPy can ("proven"): each parameter of f is replaced in turn by each closed
   end of its range and by an interior point written with a positive symbol t, lo + t for an
   unbounded range and lo + (hi - lo) t/(1 + t) for a bounded one (these cover the open interval
   exactly). Every branch of f (split at Min, Max, Piecewise) must then be nonnegative and finite by
   SymPy's assumptions, as it stands or as a fraction with a nonnegative numerator and a positive
   denominator, for u > 0 and at u = 0;
2. else numerically ("checked numerically"): f at the defaults on a grid of u, w, r at 30 digits
   (mpmath), then on a grid of u, w, r and parameter values across the ranges (log-spaced offsets
   from the lower end of an unbounded range, fractions of a bounded one, closed ends and the default
   included) in double precision, each suspicious value (negative, not finite, not real) computed
   again at 30 digits before it counts.

A negative, complex or infinite value raises LawError naming u, w, r and the parameter values.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import sympy as sp

from .expressions import LawError, snippet, time_limit
from .symbols import r, u, w

PROVEN = "proven"
CHECKED_NUMERICALLY = "checked numerically"

#: Speeds at which sign and realness are sampled at the defaults, in units where kT nu ~ 1 (plus u = 0).
SAMPLE_SPEEDS = (0, *(10.0**e for e in range(-8, 9)), *(0.1 * k for k in range(1, 40)))
SAMPLE_WEIGHTS = (1e-3, 0.5, 1.0, 60.0, 1e4)
SAMPLE_DISTANCES = (0.5, 0.9, 1.0, 1.1, 2.0)
#: Speeds of the sweep over the parameter ranges (double precision, so not beyond 1e4).
SWEEP_SPEEDS = (0.0, 1e-8, 1e-6, 1e-4, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0, 10.0, 15.0, 20.0)
SWEEP_SPEEDS += (30.0, 50.0, 100.0, 300.0, 1e3, 1e4)
#: Interior points of a bounded range (fractions of its width) and of an unbounded one (offsets from its lower end).
FRACTIONS = (1e-6, 1e-3, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999, 1 - 1e-6)
OFFSETS = (1e-6, 1e-4, 1e-2, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6)
#: Most points of the sweep (u, w, r and parameter values together); more parameters get fewer values each.
MAX_SWEEP_POINTS = 2_000_000
#: Most values recomputed at 30 digits; a law with more suspicious double-precision values (beyond
#: overflows of positive values) is refused. Points of the sweep at 30 digits when f cannot be evaluated on arrays.
MAX_RECHECKS = 5000
MAX_EXACT_POINTS = 20_000
#: Most combinations of range ends and interiors the symbolic proof tries, and its wall-time limit (s).
MAX_SYMBOLIC_CASES = 81
SYMBOLIC_TIME_LIMIT = 20.0


class _Slow(Exception):
    """The symbolic proof took longer than SYMBOLIC_TIME_LIMIT."""


def check_ranges(law) -> str:
    """PROVEN or CHECKED_NUMERICALLY: how f >= 0, real and finite was established over the parameters'
    ranges (see the module's docstring); raises LawError naming the values where it fails."""
    if prove(law):
        return PROVEN
    check_samples(law)
    sweep(law)
    return CHECKED_NUMERICALLY


def _parameters(law) -> list:
    """The parameters that f depends on (those of the weight alone enter through w)."""
    return [p for p in law.parameters if p.symbol in law.friction.free_symbols]


# --- symbolic ----------------------------------------------------------------------------------


def _cases(p) -> list[sp.Expr]:
    """Expressions that together cover the range of parameter ``p``: an interior point in a positive
    symbol t, and each closed end."""
    i = p.range
    lower, t = sp.Rational(repr(float(i.lower))), sp.Dummy(p.name, positive=True)
    if i.upper == math.inf:
        cases = [lower + t]
    else:
        cases = [lower + (sp.Rational(repr(float(i.upper))) - lower) * t / (1 + t)]
    return cases + ([lower] if i.lower_closed else []) + ([sp.Rational(repr(float(i.upper)))] if i.upper_closed else [])


def prove(law) -> bool:
    """True when SymPy shows every branch of f nonnegative and finite over the whole ranges."""
    parameters = _parameters(law)
    options = [_cases(p) for p in parameters]
    if math.prod(len(o) for o in options) > MAX_SYMBOLIC_CASES:
        return False
    try:
        with time_limit(SYMBOLIC_TIME_LIMIT, _Slow()):
            for combination in itertools.product(*options):
                f = law.friction.xreplace({p.symbol: value for p, value in zip(parameters, combination)})
                if not all(_nonnegative_finite(value) for value in _branch_values(f)):
                    return False
    except (_Slow, TypeError, ValueError, NotImplementedError, RecursionError, AttributeError):
        return False
    return True


def _branch_values(f: sp.Expr) -> list[sp.Expr]:
    """The expressions of f's branches (all of them, whatever their conditions); [nan] if f has no
    value for some u (a Piecewise without an otherwise-branch)."""
    folded = sp.piecewise_fold(f.rewrite(sp.Piecewise))
    if not isinstance(folded, sp.Piecewise):
        return [folded]
    if folded.args[-1].cond != sp.true:
        return [sp.nan]
    return [value for value, _ in folded.args]


def _nonnegative_finite(value: sp.Expr) -> bool:
    for v in (value, value.subs(u, 0)):
        if v.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            return False
        if v.is_nonnegative and v.is_finite:
            continue
        numerator, denominator = sp.fraction(sp.together(v))
        numerator = sp.expand(numerator)
        if not (numerator.is_nonnegative and numerator.is_finite and denominator.is_positive):
            return False
    return True


# --- numbers -------------------------------------------------------------------------------------


def _problem(value) -> str:
    """What is wrong with one value of f (mpmath), or "" if it is a finite real >= 0."""
    value = mpmath.mpmathify(value)
    if isinstance(value, mpmath.mpc) and abs(value.imag) > 0:
        return f"not real (f = {mpmath.nstr(value, 6)})"
    value = mpmath.re(value)
    if not mpmath.isfinite(value):
        return "not finite"
    if value < 0:
        return f"negative (f = {mpmath.nstr(value, 6)})"
    return ""


def check_samples(law) -> None:
    """f real, finite and >= 0 on a grid of u, w, r at the default parameters (30 digits)."""
    with mpmath.workdps(30):
        evaluate = sp.lambdify((u, w, r), law.friction.subs(law.defaults), modules="mpmath")
        for ww in SAMPLE_WEIGHTS:
            for rr in SAMPLE_DISTANCES:
                for uu in SAMPLE_SPEEDS:
                    try:
                        problem = _problem(evaluate(mpmath.mpf(uu), mpmath.mpf(ww), mpmath.mpf(rr)))
                    except (ZeroDivisionError, ValueError, OverflowError) as error:
                        raise LawError(f"law {law.name}: f is not finite at u={uu}, w={ww}, r={rr} ({type(error).__name__})") from error
                    if problem:
                        kind, detail = problem.split(" (")[0], _detail(problem)
                        tail = "; friction must oppose sliding, f >= 0" if kind == "negative" else ""
                        raise LawError(f"law {law.name}: f is {kind} at u={uu}, w={ww}, r={rr}{detail}{tail}")


def _detail(problem: str) -> str:
    return f" ({problem.split(' (', 1)[1]}" if " (" in problem else ""


def range_values(p, count: int | None = None) -> list[float]:
    """Values of parameter ``p`` across its range: interior points, closed ends, the default; with
    ``count``, about that many of them, evenly chosen (the smallest and largest always)."""
    i = p.range
    inner = [i.lower + x for x in OFFSETS] if i.upper == math.inf else [i.lower + (i.upper - i.lower) * x for x in FRACTIONS]
    ends = ([i.lower] if i.lower_closed else []) + ([i.upper] if i.upper_closed else [])
    values = sorted({float(v) for v in [*ends, *inner, p.default] if v in i})
    if count is None or len(values) <= count:
        return values
    chosen = {values[round(k * (len(values) - 1) / (count - 1))] for k in range(count)} if count > 1 else {values[0]}
    return sorted(chosen | {float(p.default)})


def _grid(law, budget: int, base: np.ndarray) -> tuple[list, np.ndarray]:
    """The swept parameters and the points (u, w, r, parameter values; one column each) of the sweep:
    ``base`` (rows u, w, r) for every combination of parameter values, within ``budget`` points."""
    parameters = _parameters(law)
    combinations = max(1, budget // base.shape[1])
    lists = [range_values(p) for p in parameters]
    count = max((len(v) for v in lists), default=1)
    while count > 2 and math.prod(len(v) for v in lists) > combinations:
        count -= 1
        lists = [range_values(p, count) for p in parameters]
    values = np.array(list(itertools.product(*lists)), dtype=float).reshape(-1, len(parameters)).T
    return parameters, values


def _base(speeds, weights, distances) -> np.ndarray:
    return np.array(list(itertools.product(speeds, weights, distances)), dtype=float).T


def sweep(law) -> None:
    """f on the grid of u, w, r and parameter values over their ranges; LawError at a value that is
    negative, not real or not finite (each confirmed at 30 digits)."""
    base = _base(SWEEP_SPEEDS, SAMPLE_WEIGHTS, SAMPLE_DISTANCES)
    parameters, values = _grid(law, MAX_SWEEP_POINTS, base)
    symbols = [p.symbol for p in parameters]
    f = law.friction.subs({p.symbol: p.default for p in law.parameters if p not in parameters})
    exact = sp.lambdify((u, w, r, *symbols), f, modules="mpmath")
    defaults = np.log([max(p.default, 1e-300) for p in parameters]).reshape(-1, 1)
    try:
        fast = sp.lambdify((u, w, r, *symbols), f.replace(lambda e: isinstance(e, (sp.Min, sp.Max)), lambda e: e.rewrite(sp.Piecewise)))
        keys, points, dropped = np.empty(0), np.empty((3 + len(parameters), 0)), None
        chunk = max(1, 200_000 // base.shape[1])
        for start in range(0, values.shape[1], chunk):
            block = values[:, start : start + chunk]
            grid = np.vstack([np.tile(base, block.shape[1]), np.repeat(block, base.shape[1], axis=1)])
            rank = _ranks(fast, grid)
            # negative and not real first, then not finite, then overflows; each nearest the defaults first
            distance = np.abs(np.log(np.maximum(grid[3:], 1e-300)) - defaults).sum(axis=0)
            keep = np.flatnonzero(rank >= 0)
            keys, points = np.concatenate([keys, rank[keep] * 1e9 + distance[keep]]), np.hstack([points, grid[:, keep]])
            if keys.size > MAX_RECHECKS:
                order = np.argpartition(keys, MAX_RECHECKS)
                serious = [k for k in order[MAX_RECHECKS:] if keys[k] < 2e9]  # not an overflow of a positive value
                dropped = points[:, serious[0]] if serious and dropped is None else dropped
                keys, points = keys[order[:MAX_RECHECKS]], points[:, order[:MAX_RECHECKS]]
    except Exception:  # noqa: BLE001 - f cannot be evaluated on arrays: a smaller grid, every point at 30 digits
        parameters, values = _grid(law, MAX_EXACT_POINTS, _base(SWEEP_SPEEDS[::2], SAMPLE_WEIGHTS[::2], SAMPLE_DISTANCES[::2]))
        base = _base(SWEEP_SPEEDS[::2], SAMPLE_WEIGHTS[::2], SAMPLE_DISTANCES[::2])
        points = np.vstack([np.tile(base, values.shape[1]), np.repeat(values, base.shape[1], axis=1)])
        keys, dropped = np.zeros(points.shape[1]), None
    for k in np.argsort(keys, kind="stable"):
        point = tuple(float(x) for x in points[:, k])
        problem = _exact_problem(exact, point)
        if problem:
            raise LawError(_message(law, parameters, point, problem))
    if dropped is not None:
        raise LawError(
            f"law {law.name}: f is negative, not real or not finite in double precision at more than {MAX_RECHECKS} points of "
            f"the parameters' ranges (e.g. {_where(parameters, tuple(dropped))}): too many to check at 30 digits; narrow the "
            "ranges or simplify f"
        )


def _ranks(fast, points: np.ndarray) -> np.ndarray:
    """Per point: 0 where f in double precision is negative or not real, 1 not finite (nan, -inf),
    2 +inf (an overflow), -1 fine. Raises where f cannot be evaluated on arrays."""
    with np.errstate(all="ignore"):
        values = np.broadcast_to(np.asarray(fast(*points)), points.shape[1:])
    unreal = values.imag != 0 if np.iscomplexobj(values) else np.zeros(values.shape, dtype=bool)
    values = values.real.astype(float)
    rank = np.where(np.isfinite(values), -1, np.where(values == np.inf, 2, 1))
    return np.where(unreal | (values < 0), 0, rank)


def _exact_problem(exact, point: tuple) -> str:
    with mpmath.workdps(30):
        try:
            return _problem(exact(*(mpmath.mpf(x) for x in point)))
        except (ZeroDivisionError, ValueError, OverflowError, TypeError) as error:
            return f"not finite ({type(error).__name__})"


def _where(parameters: list, point: tuple) -> str:
    names = ["u", "w", "r", *(p.name for p in parameters)]
    return ", ".join(f"{name}={x:.6g}" for name, x in zip(names, point))


def _message(law, parameters: list, point: tuple, problem: str) -> str:
    kind, detail = problem.split(" (")[0], _detail(problem)
    ranges = ", ".join(f"{p.name} in {p.range}" for p in parameters)
    return snippet(
        f"law {law.name}: f is {kind} at {_where(parameters, point)}{detail}: f must be >= 0, real and finite for every value in "
        f"the parameters' ranges ({ranges}); narrow a range or fix f",
        400,
    )
