"""Friction laws as data: a name, f(u, r) as a SymPy expression, parameters, an optional weight.

A law file is plain TOML (see ``derive/law/catalogue/``)::

    name = "coulomb_newton"
    reference = "F-32"
    description = "Viscous below the slip threshold, Coulomb above."
    friction = "Min(gamma_f*u, w*kappa_f)"
    weight = "wca"            # w(r) = -dU/dr of a potential, or an expression in r
    calculi = ["ito", "stratonovich", "hk"]
    mode = "sliding"          # the relative motion f acts on: sliding (default), rolling, spinning

    [parameters.gamma_f]
    default = 6.0
    unit = "sqrt(m kT)/sigma"
    description = "viscous friction coefficient"
    range = "(0, inf)"        # the admissible values (the default): [ ] closed, ( ) open ends

f is the magnitude of the friction force (units of force) as a function of the speed u >= 0 of the law's contact mode
(``mode``; the tangential sliding speed by default, docs/physics-modes.md), the centre distance r and the weight value
w = w(r). Parameters are real numbers in their ranges (within [0, oo); the positive reals unless ``range`` says
otherwise), and f must be >= 0, real and finite for every combination of them (fricgen.derive.law.ranges: proven by
SymPy where it can, else checked on a grid; ``FrictionLaw.range_check`` says which). Expressions are data, never run:
see fricgen.derive.law.expressions for their grammar (numbers, u, r, w, the parameters, pi, + - * / **, a list of
functions, Piecewise) and size limits. ``calculi`` lists the calculi the law claims to support (default: all three);
one is left out only with a physical reason (constant friction has f(0+) > 0: the HK amplitude f/u diverges at u = 0).
"""

from __future__ import annotations

import dataclasses
import keyword
import math
from dataclasses import dataclass, field

import mpmath
import sympy as sp

from ..calculus import CALCULI
from . import lawdata, potentials
from .expressions import CONSTANTS, LawError, check_expression, check_parameter_name, expression_text, parse_expression, snippet, time_limit
from .lawdata import POSITIVE, Interval, LawFileError, parse_range
from .ranges import check_ranges
from .symbols import r, u, w

#: Wall-time limits (seconds) of a law's validation, and of the symbolic limit in its tail check.
VALIDATION_TIME_LIMIT = 120.0
TAIL_LIMIT_TIME = 20.0


@dataclass(frozen=True)
class Parameter:
    """A named parameter of a law with its default, unit and range of admissible values.

    Attributes
    ----------
    name : str
        The parameter's symbol in the friction expression.
    default : float
        Its default value, in ``unit``.
    unit : str
        Its unit in the model's units, e.g. ``"kT t0/sigma^2"`` or ``"1"`` (dimensionless).
    description : str
        One line on its meaning.
    range : Interval
        Its admissible values, within [0, oo); the positive reals by default.
    """

    name: str
    default: float
    unit: str = "1"
    description: str = ""
    range: Interval = POSITIVE

    @property
    def symbol(self) -> sp.Symbol:
        """Positive, or nonnegative when the range holds 0."""
        if self.range.lower == 0 and self.range.lower_closed:
            return sp.Symbol(self.name, nonnegative=True)
        return sp.Symbol(self.name, positive=True)


@dataclass(frozen=True)
class FrictionLaw:
    """A tangential friction law: the magnitude f(u, r) >= 0 [kT/sigma] with its parameters and weight.

    Build one with :func:`make_law` or read one with :func:`load_law`.

    Attributes
    ----------
    name : str
        Identifier, also the law file's stem.
    friction : sympy.Expr
        f in ``u`` [sigma/t0], ``r`` [sigma], ``w`` [1] and the parameter symbols.
    parameters : tuple of Parameter
        The law's parameters, including those of the weight's potential.
    weight : sympy.Expr or None
        w(r) in ``r``, or None when ``w`` is not used.
    weight_source : str
        The weight as written in the law file ("wca" or an expression).
    calculi : tuple of str
        The calculi the law supports ('ito', 'stratonovich', 'hk').
    mode : str
        The contact mode f acts on ('sliding', 'rolling', 'spinning'), u the speed of that mode.
    description : str
        One paragraph on the law.
    reference : str
        Where the law comes from (a paper, an equation).
    source : str
        The friction expression as written.
    source_hash : str
        For a law read by :func:`load_law`, the hash of the very bytes it was built from; generated
        kernels carry it. Empty otherwise.
    range_check : str
        How f >= 0, real and finite was established for every parameter value in the ranges:
        "proven" (symbolically) or "checked numerically".
    """

    name: str
    friction: sp.Expr
    parameters: tuple[Parameter, ...] = ()
    weight: sp.Expr | None = None
    weight_source: str = ""
    calculi: tuple[str, ...] = CALCULI
    mode: str = lawdata.DEFAULT_MODE
    description: str = ""
    reference: str = ""
    source: str = field(default="", compare=False)
    source_hash: str = field(default="", compare=False)
    range_check: str = field(default="", compare=False)

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        """Parameter symbols by name."""
        return {p.name: p.symbol for p in self.parameters}

    @property
    def defaults(self) -> dict[sp.Symbol, float]:
        """The parameters' default values by SymPy symbol (to substitute into f or D)."""
        return {p.symbol: p.default for p in self.parameters}


def make_law(
    name: str,
    friction: str | sp.Expr,
    parameters: dict[str, dict] | tuple[Parameter, ...] = (),
    weight: str | None = None,
    calculi: tuple[str, ...] | list[str] = CALCULI,
    description: str = "",
    reference: str = "",
    mode: str = lawdata.DEFAULT_MODE,
) -> FrictionLaw:
    """Build and validate a friction law.

    Parameters
    ----------
    name : str
        Identifier (ASCII letters, digits, underscores; not starting with an underscore).
    friction : str or sympy.Expr
        f [kT/sigma] as text (parsed as data, never evaluated) or as a SymPy expression in u
        [sigma/t0], r [sigma], w [1] and the parameters.
    parameters : dict or tuple of Parameter
        ``{name: {"default": x, "unit": ..., "description": ..., "range": "[0, 2]"}}`` (range as in a
        law file, or an Interval), or Parameters.
    weight : str, optional
        None, the name of a potential of derive/law/potentials.py (w = -dU/dr), or an expression in r.
    calculi : sequence of str
        The calculi the law supports.
    description : str
        One paragraph on the law.
    reference : str
        Where the law comes from.
    mode : str
        The contact mode the law acts on: 'sliding', 'rolling' or 'spinning'.

    Returns
    -------
    FrictionLaw
        The validated law (f >= 0, real and finite over the parameters' ranges).

    Raises
    ------
    LawError
        Naming the problem, e.g. an unknown symbol or an f that can be negative.

    Examples
    --------
    >>> from fricgen.derive import make_law
    >>> law = make_law("viscous", "gamma_f*u", parameters={"gamma_f": {"default": 2.0, "unit": "kT t0/sigma^2"}})
    >>> law.friction, law.calculi
    (gamma_f*u, ('ito', 'stratonovich', 'hk'))
    """
    _check_name(name)
    if why := lawdata.mode_refusal(mode):
        raise LawError(f"law {name}: mode: {why}")
    if not isinstance(parameters, (dict, tuple, list)):
        raise LawError(f"law {name}: parameters must be a table of parameter tables, got {type(parameters).__name__}")
    params = tuple(
        p if isinstance(p, Parameter) else Parameter(key, **_parameter_fields(name, key, p))
        for key, p in (parameters.items() if isinstance(parameters, dict) else ((q.name, q) for q in parameters))
    )
    for p in params:
        _check_parameter(name, p)
    weight_expr, weight_params = _weight(name, weight, params)
    params = params + weight_params
    for key, value in (("description", description), ("reference", reference)):
        if not isinstance(value, str):
            raise LawError(f"law {name}: {key} must be a string, got {type(value).__name__}")
    if isinstance(calculi, str) or not isinstance(calculi, (tuple, list)) or not calculi or not set(calculi) <= set(CALCULI):
        raise LawError(f"law {name}: calculi must be a non-empty list from {list(CALCULI)}, got {snippet(repr(calculi))}")
    names = {"u": u, "r": r, "w": w, **{p.name: p.symbol for p in params}}
    if isinstance(friction, str):
        expr, source = parse_expression(friction, names, f"law {name}: f"), friction
    else:
        check_expression(friction, f"law {name}: f")
        expr, source = friction, expression_text(friction)
        parse_expression(source, names, f"law {name}: f as a law file writes it")  # save_law must write a loadable file
    law = FrictionLaw(
        name=name,
        friction=expr,
        parameters=params,
        weight=weight_expr,
        weight_source=weight or "",
        calculi=tuple(c for c in CALCULI if c in calculi),
        mode=mode,
        description=description,
        reference=reference,
        source=source,
    )
    with time_limit(VALIDATION_TIME_LIMIT, LawError(f"law {name}: validation took longer than {VALIDATION_TIME_LIMIT:g} s; simplify f")):
        checked = validate(law)
    return dataclasses.replace(law, range_check=checked)


def _check_name(name: object) -> None:
    """A law's name is a file stem and a module name: an ASCII identifier, not private, not a keyword."""
    if not (isinstance(name, str) and name.isascii() and name.isidentifier() and len(name) <= 64):
        raise LawError(f"law name {snippet(repr(name))} must be an identifier of at most 64 ASCII letters, digits and underscores")
    if name.startswith("_") or keyword.iskeyword(name):
        raise LawError(f"law name {name!r} must not start with an underscore or be a Python keyword")


def _check_parameter(law: str, p: Parameter) -> None:
    """A parameter's name becomes a symbol and a variable of the kernels; its default a float in its range."""
    name = p.name
    check_parameter_name(name, f"law {law}")
    if not isinstance(p.range, Interval):
        raise LawError(f"law {law}: parameter {name}: range must be an Interval or a string such as '[0, 2]', got {type(p.range).__name__}")
    try:
        number = not isinstance(p.default, bool) and isinstance(p.default, (int, float))
        valid = number and math.isfinite(p.default) and p.default in p.range
    except OverflowError:
        valid = False
    if not valid:
        wanted = "a finite positive default" if p.range == POSITIVE else f"a finite default in its range {p.range}"
        raise LawError(f"law {law}: parameter {name} needs {wanted}, got {snippet(repr(p.default))}")
    for key in ("unit", "description"):
        if not isinstance(getattr(p, key), str):
            raise LawError(f"law {law}: parameter {name}: {key} must be a string, got {type(getattr(p, key)).__name__}")


def _parameter_fields(law: str, key: str, spec: dict) -> dict:
    if not isinstance(spec, dict) or "default" not in spec:
        raise LawError(f"law {law}: parameter {snippet(repr(key))} needs a table with a 'default'")
    if unknown := set(spec) - {"default", "unit", "description", "range"}:
        raise LawError(f"law {law}: parameter {snippet(repr(key))} has unknown keys {sorted(unknown)}")
    interval = spec.get("range", POSITIVE)
    if not isinstance(interval, Interval):
        try:
            interval = parse_range(interval, f"law {law}: parameter {snippet(str(key))}: range")
        except LawFileError as error:
            raise LawError(str(error)) from None
    return {"default": spec["default"], "unit": spec.get("unit", "1"), "description": spec.get("description", ""), "range": interval}


def _weight(name: str, weight: str | None, params: tuple[Parameter, ...]) -> tuple[sp.Expr | None, tuple[Parameter, ...]]:
    """w(r) from a potential's name (w = -dU/dr) or from an expression in r."""
    if weight is None or weight == "":
        return None, ()
    if not isinstance(weight, str):
        raise LawError(f"law {name}: weight must be a string (a potential or an expression in r), got {type(weight).__name__}")
    if weight in potentials.PAIR_POTENTIALS:
        potential = potentials.PAIR_POTENTIALS[weight]
        own = {p.name for p in params}
        extra = tuple(
            Parameter(p, float(v), potential.units.get(p, "1"), f"parameter of the weight's potential {weight}")
            for p, v in potential.defaults.items()
            if p not in own
        )
        return potential.force, extra
    names = {"r": r, **{p.name: p.symbol for p in params}}
    if weight.isidentifier() and weight not in names and weight not in CONSTANTS:
        known = ", ".join(potentials.PAIR_POTENTIALS)
        raise LawError(f"law {name}: weight {snippet(weight)!r} is neither a potential ({known}) nor an expression in r")
    expr = parse_expression(weight, names, f"law {name}: weight", excluded=("u", "w"))
    return expr, ()


# --- validation -----------------------------------------------------------------------------


def validate(law: FrictionLaw) -> str:
    """Raise :class:`LawError` for a law without a consistent noise amplitude; else return how f >= 0
    was established over the parameters' ranges ("proven" or "checked numerically", fricgen.derive.law.ranges).

    Checks: only known symbols; depends on u, w or r (a constant law needs its weight); w used only with a weight; f real and finite and
    f >= 0 for u >= 0 and every parameter value in the ranges (symbolically where SymPy decides it,
    else on grids); the tail integral (F-22) converges for every kT nu > 0, i.e. ln f / u^2 -> 0 as
    u -> oo (at the defaults).
    """
    f = law.friction
    allowed = {u, r, w, *law.symbols.values()}
    if unknown := f.free_symbols - allowed:
        raise LawError(
            f"law {law.name}: unknown symbol(s) {sorted(map(str, unknown))} in f = {_short(f)}; "
            f"allowed: u, r, w and parameters {sorted(law.symbols)}"
        )
    if not f.free_symbols & {u, w, r}:
        raise LawError(
            f"law {law.name}: f = {_short(f)} depends on none of u, w, r: a friction law must depend on the "
            f"sliding speed u or (constant friction, F-30) vanish off contact through w(r) or r"
        )
    if w in f.free_symbols and law.weight is None:
        raise LawError(f"law {law.name}: f uses w but the law defines no weight (set weight = 'wca' or an expression in r)")
    if f.has(sp.I) or f.is_real is False:
        raise LawError(f"law {law.name}: f = {_short(f)} is not real")
    checked = check_ranges(law)
    _check_tail(law)
    return checked


def _check_tail(law: FrictionLaw) -> None:
    """The integral (F-22) converges for all kT nu > 0 iff ln f / u^2 -> 0 (for f > 0 at large u)."""
    f = law.friction.subs(law.defaults).subs({w: 1, r: 1})
    tail = _asymptotic_branch(f)
    growth = None
    if tail.is_polynomial(u):
        growth = sp.Integer(0)  # ln of a polynomial grows like ln u (and sp.limit recurses on high degrees)
    elif not tail.has(sp.Min, sp.Max, sp.Piecewise):
        try:
            with time_limit(TAIL_LIMIT_TIME, _SlowLimit()):
                growth = sp.limit(sp.log(tail) / u**2, u, sp.oo)
        except (NotImplementedError, ValueError, TypeError, RecursionError, _SlowLimit):
            growth = None  # decided numerically below
    if growth is None or growth.has(sp.Limit) or not growth.is_comparable and growth not in (sp.oo, -sp.oo):
        evaluate = sp.lambdify(u, sp.log(tail) / u**2, modules="mpmath")
        with mpmath.workdps(30):
            growth = sp.Float(str(evaluate(mpmath.mpf(10) ** 8)))
        if abs(growth) < 1e-10:
            growth = sp.Integer(0)
    if growth != 0 and growth != -sp.oo:
        raise LawError(
            f"law {law.name}: f grows like exp(c u^2) with c = {growth} as u -> oo; the integral (F-22) "
            f"diverges for kT nu >= 1/(2c), so no noise amplitude exists"
        )


class _SlowLimit(Exception):
    """sp.limit took longer than TAIL_LIMIT_TIME."""


def _short(expr: sp.Expr) -> str:
    return snippet(str(expr), 80)


def _asymptotic_branch(f: sp.Expr) -> sp.Expr:
    """The expression f reduces to for large u (last branch of Min/Max/Piecewise)."""
    pw = sp.piecewise_fold(f.rewrite(sp.Piecewise))
    if not isinstance(pw, sp.Piecewise):
        return f
    for expr, cond in pw.args:
        if cond == sp.true or sp.sympify(cond.subs(u, sp.oo)) == sp.true:
            return expr
    return f


# --- files ------------------------------------------------------------------------------------
