"""Friction laws as data: a name, f(u, r) as a SymPy expression, parameters, an optional weight.

A law file is plain TOML (see ``derive/catalogue/``)::

    name = "coulomb_newton"
    reference = "F-32"
    description = "Viscous below the slip threshold, Coulomb above."
    friction = "Min(gamma_f*u, w*kappa_f)"
    weight = "wca"            # w(r) = -dU/dr of a potential, or an expression in r
    calculi = ["ito", "stratonovich", "hk"]

    [parameters.gamma_f]
    default = 6.0
    unit = "sqrt(m kT)/sigma"
    description = "viscous friction coefficient"

f is the magnitude of the tangential contact force (units of force) as a function of the
tangential speed u >= 0, the centre distance r and the weight value w = w(r). Parameters are
positive reals. ``calculi`` lists the calculi the law claims to support (default: all three); a
calculus is left out only with a physical reason, e.g. constant friction has f(0+) > 0, so the
Hänggi–Klimontovich amplitude f/u diverges at u = 0.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import mpmath
import sympy as sp
from sympy.core.function import AppliedUndef
from sympy.parsing.sympy_parser import parse_expr

from . import potentials
from .calculus import CALCULI
from .lawdata import CATALOGUE, LawFileError, read_law_data
from .symbols import RESERVED, r, u, w


class LawError(LawFileError):
    """A friction law that cannot have a thermodynamically consistent noise amplitude."""


@dataclass(frozen=True)
class Parameter:
    """A named positive parameter with its default value and unit."""

    name: str
    default: float
    unit: str = "1"
    description: str = ""

    @property
    def symbol(self) -> sp.Symbol:
        return sp.Symbol(self.name, positive=True)


@dataclass(frozen=True)
class FrictionLaw:
    """Tangential friction magnitude f(u, r) >= 0 with its parameters and distance weight.

    Attributes:
        name: identifier, also the law file's stem.
        friction: SymPy expression in ``u``, ``r``, ``w`` and the parameter symbols.
        parameters: the law's parameters, including those of the weight's potential.
        weight: w(r) as a SymPy expression in ``r``, or None when ``w`` is not used.
        weight_source: the weight as written in the law file ("wca" or an expression).
        calculi: calculi the law supports.
    """

    name: str
    friction: sp.Expr
    parameters: tuple[Parameter, ...] = ()
    weight: sp.Expr | None = None
    weight_source: str = ""
    calculi: tuple[str, ...] = CALCULI
    description: str = ""
    reference: str = ""
    source: str = field(default="", compare=False)  # the friction expression as written

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        """Parameter symbols by name."""
        return {p.name: p.symbol for p in self.parameters}

    @property
    def defaults(self) -> dict[sp.Symbol, float]:
        return {p.symbol: p.default for p in self.parameters}


def _parse(text: str, names: dict[str, sp.Symbol], what: str) -> sp.Expr:
    try:
        expr = parse_expr(text, local_dict=dict(names), evaluate=True)
    except Exception as error:  # SymPy raises many types for malformed text
        raise LawError(f"{what}: cannot parse {text!r}: {error}") from error
    if not isinstance(expr, sp.Expr):
        raise LawError(f"{what}: {text!r} is not an expression")
    undefined = sorted(str(f.func) for f in expr.atoms(AppliedUndef))
    if undefined:
        raise LawError(f"{what}: unknown function(s) {', '.join(undefined)} in {text!r}")
    return expr


def make_law(
    name: str,
    friction: str | sp.Expr,
    parameters: dict[str, dict] | tuple[Parameter, ...] = (),
    weight: str | None = None,
    calculi: tuple[str, ...] | list[str] = CALCULI,
    description: str = "",
    reference: str = "",
) -> FrictionLaw:
    """Build and validate a law; raises :class:`LawError` naming the problem.

    Args:
        name: identifier (letters, digits, underscores).
        friction: f as text or SymPy expression in u, r, w and the parameters.
        parameters: ``{name: {"default": x, "unit": ..., "description": ...}}`` or Parameters.
        weight: None, the name of a potential in :mod:`derive.potentials` (w = -dU/dr), or an
            expression in r.
        calculi: the calculi the law supports.
    """
    if not name.isidentifier():
        raise LawError(f"law name {name!r} must be an identifier (letters, digits, underscores)")
    params = tuple(
        p if isinstance(p, Parameter) else Parameter(key, **_parameter_fields(name, key, p))
        for key, p in (parameters.items() if isinstance(parameters, dict) else ((q.name, q) for q in parameters))
    )
    weight_expr, weight_params = _weight(name, weight, params)
    params = params + weight_params
    for p in params:
        if p.name in RESERVED or p.name.startswith(("cse", "_")) or not p.name.isidentifier():
            raise LawError(f"law {name}: parameter name {p.name!r} is reserved or not an identifier")
        if not (isinstance(p.default, (int, float)) and math.isfinite(p.default) and p.default > 0):
            raise LawError(f"law {name}: parameter {p.name} needs a finite positive default, got {p.default!r}")
    names = {"u": u, "r": r, "w": w, **{p.name: p.symbol for p in params}}
    expr = _parse(friction, names, f"law {name}") if isinstance(friction, str) else sp.sympify(friction)
    unknown_calculi = sorted(set(calculi) - set(CALCULI))
    if unknown_calculi or not calculi:
        raise LawError(f"law {name}: calculi must be a non-empty subset of {CALCULI}, got {list(calculi)}")
    law = FrictionLaw(
        name=name,
        friction=expr,
        parameters=params,
        weight=weight_expr,
        weight_source=weight or "",
        calculi=tuple(c for c in CALCULI if c in calculi),
        description=description,
        reference=reference,
        source=friction if isinstance(friction, str) else sp.sstr(expr),
    )
    validate(law)
    return law


def _parameter_fields(law: str, key: str, spec: dict) -> dict:
    if not isinstance(spec, dict) or "default" not in spec:
        raise LawError(f"law {law}: parameter {key} needs a table with a 'default'")
    unknown = set(spec) - {"default", "unit", "description"}
    if unknown:
        raise LawError(f"law {law}: parameter {key} has unknown keys {sorted(unknown)}")
    return {"default": spec["default"], "unit": str(spec.get("unit", "1")), "description": str(spec.get("description", ""))}


def _weight(name: str, weight: str | None, params: tuple[Parameter, ...]) -> tuple[sp.Expr | None, tuple[Parameter, ...]]:
    """w(r) from a potential's name (w = -dU/dr) or from an expression in r."""
    if weight is None or weight == "":
        return None, ()
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
    expr = _parse(weight, names, f"law {name} weight")
    stray = expr.free_symbols - set(names.values())
    if stray:
        raise LawError(f"law {name}: weight {weight!r} uses unknown symbol(s) {sorted(map(str, stray))}")
    return expr, ()


# --- validation -----------------------------------------------------------------------------

#: Speeds at which sign and realness are sampled, in units where kT nu ~ 1 (plus u = 0).
SAMPLE_SPEEDS = (0, *(10.0**e for e in range(-8, 9)), *(0.1 * k for k in range(1, 40)))
SAMPLE_WEIGHTS = (1e-3, 0.5, 1.0, 60.0, 1e4)
SAMPLE_DISTANCES = (0.5, 0.9, 1.0, 1.1, 2.0)


def validate(law: FrictionLaw) -> None:
    """Raise :class:`LawError` for a law without a consistent noise amplitude.

    Checks: only known symbols; depends on u, w or r (a constant law needs its weight); w used only with a weight; f real and finite and
    f >= 0 for u >= 0 (symbolically where SymPy decides it, else on a sample grid); the tail
    integral (F-22) converges for every kT nu > 0, i.e. ln f / u^2 -> 0 as u -> oo.
    """
    f = law.friction
    allowed = {u, r, w, *law.symbols.values()}
    unknown = f.free_symbols - allowed
    if unknown:
        raise LawError(
            f"law {law.name}: unknown symbol(s) {sorted(map(str, unknown))} in f = {f}; "
            f"allowed: u, r, w and parameters {sorted(law.symbols)}"
        )
    if not f.free_symbols & {u, w, r}:
        raise LawError(
            f"law {law.name}: f = {f} depends on none of u, w, r: a friction law must depend on the "
            f"sliding speed u or (constant friction, F-30) vanish off contact through w(r) or r"
        )
    if w in f.free_symbols and law.weight is None:
        raise LawError(f"law {law.name}: f uses w but the law defines no weight (set weight = 'wca' or an expression in r)")
    if f.has(sp.I) or f.is_real is False:
        raise LawError(f"law {law.name}: f = {f} is not real")
    _check_samples(law)
    _check_tail(law)


def _check_samples(law: FrictionLaw) -> None:
    """f real, finite and >= 0 on a grid of u, w, r at the default parameters."""
    if law.friction.is_nonnegative and law.friction.is_finite:
        return
    with mpmath.workdps(30):
        evaluate = sp.lambdify((u, w, r), law.friction.subs(law.defaults), modules="mpmath")
        for ww in SAMPLE_WEIGHTS:
            for rr in SAMPLE_DISTANCES:
                for uu in SAMPLE_SPEEDS:
                    try:
                        value = evaluate(mpmath.mpf(uu), mpmath.mpf(ww), mpmath.mpf(rr))
                    except (ZeroDivisionError, ValueError, OverflowError) as error:
                        raise LawError(f"law {law.name}: f is not finite at u={uu}, w={ww}, r={rr} ({type(error).__name__})") from error
                    value = mpmath.mpmathify(value)
                    if isinstance(value, mpmath.mpc) and abs(value.imag) > 0:
                        raise LawError(f"law {law.name}: f is not real at u={uu}, w={ww}, r={rr} (f = {value})")
                    value = mpmath.re(value)
                    if not mpmath.isfinite(value):
                        raise LawError(f"law {law.name}: f is not finite at u={uu}, w={ww}, r={rr}")
                    if value < 0:
                        raise LawError(
                            f"law {law.name}: f is negative at u={uu}, w={ww}, r={rr} "
                            f"(f = {mpmath.nstr(value, 6)}); friction must oppose sliding, f >= 0"
                        )


def _check_tail(law: FrictionLaw) -> None:
    """The integral (F-22) converges for all kT nu > 0 iff ln f / u^2 -> 0 (for f > 0 at large u)."""
    f = law.friction.subs(law.defaults).subs({w: 1, r: 1})
    tail = _asymptotic_branch(f)
    growth = None
    if not tail.has(sp.Min, sp.Max, sp.Piecewise):
        try:
            growth = sp.limit(sp.log(tail) / u**2, u, sp.oo)
        except (NotImplementedError, ValueError, TypeError):
            growth = None
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


def load_law(path: str | Path) -> FrictionLaw:
    """Read and validate a law file (TOML)."""
    path = Path(path)
    try:
        data = read_law_data(path)
    except LawFileError as error:
        raise LawError(str(error)) from error
    known = {"name", "friction", "parameters", "weight", "calculi", "description", "reference"}
    unknown = set(data) - known
    if unknown:
        raise LawError(f"{path}: unknown key(s) {sorted(unknown)}; allowed: {sorted(known)}")
    for key in ("name", "friction"):
        if key not in data:
            raise LawError(f"{path}: missing key {key!r}")
    if data["name"] != path.stem:
        raise LawError(f"{path}: name {data['name']!r} must equal the file name {path.stem!r}")
    return make_law(
        name=data["name"],
        friction=str(data["friction"]),
        parameters=data.get("parameters", {}),
        weight=data.get("weight"),
        calculi=tuple(data.get("calculi", CALCULI)),
        description=data.get("description", ""),
        reference=data.get("reference", ""),
    )


def law_text(law: FrictionLaw) -> str:
    """The law as TOML text (the inverse of :func:`load_law`); weight parameters are implied."""
    quote = json.dumps  # TOML basic strings accept JSON string escapes
    implied = set(potentials.PAIR_POTENTIALS[law.weight_source].defaults) if law.weight_source in potentials.PAIR_POTENTIALS else set()
    lines = [f"name = {quote(law.name)}"]
    if law.reference:
        lines.append(f"reference = {quote(law.reference)}")
    if law.description:
        lines.append(f"description = {quote(law.description)}")
    lines.append(f"friction = {quote(law.source or str(law.friction))}")
    if law.weight_source:
        lines.append(f"weight = {quote(law.weight_source)}")
    lines.append(f"calculi = [{', '.join(quote(c) for c in law.calculi)}]")
    for p in law.parameters:
        if p.name in implied:
            continue
        lines += ["", f"[parameters.{p.name}]", f"default = {float(p.default)!r}", f"unit = {quote(p.unit)}"]
        if p.description:
            lines.append(f"description = {quote(p.description)}")
    return "\n".join(lines) + "\n"


def save_law(law: FrictionLaw, folder: str | Path = CATALOGUE) -> Path:
    """Write the law to ``folder/<name>.toml`` and return the path."""
    path = Path(folder) / f"{law.name}.toml"
    path.write_text(law_text(law))
    return path


def catalogue(folder: str | Path = CATALOGUE) -> dict[str, FrictionLaw]:
    """All laws in a catalogue folder, by name, in sorted order."""
    return {p.stem: load_law(p) for p in sorted(Path(folder).glob("*.toml"))}
