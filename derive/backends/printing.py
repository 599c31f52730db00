"""SymPy printing shared by the backends: numerically stable rewrites, a Python printer subclass, the
shape of a kernel body in any language's :class:`Syntax` (branches, common subexpressions, the guard
at u = 0), and the formulas in the kernels' docstrings (:func:`equation`).

Rewrites (exact identities, applied before printing):

- exp(A) erfc(B) -> erfcx(B) exp(A - B^2) with erfcx(x) = exp(x^2) erfc(x): the product
  overflows/underflows for large arguments, erfcx ~ 1/(x sqrt(pi)) does not (docs/physics.md#the-noise-amplitude-d);
- c exp(x) - c -> c expm1(x): no cancellation for x -> 0 (branch thresholds of Min laws);
- 1 - tanh(x)^2 -> 1/cosh(x)^2: no cancellation for large x (the slope of a tanh law);
- products of numeric constants -> one float literal (no runtime sqrt(pi) etc.).

And per branch, just before common subexpressions are drawn (:func:`share_exp`): expm1(x) ->
expm1_given_exp(exp(x), x) where exp(x) appears beside it, so that exp(x) is computed once and, for
x < -ln 2, expm1 is taken as exp(x) - 1 (no cancellation there) instead of a second transcendental
call (Coulomb–Newton's D holds both).
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp
from sympy.codegen.cfunctions import expm1
from sympy.printing.pycode import PythonCodePrinter

from ..law.lawdata import GENERATOR_VERSION
from ..law.symbols import u
from ..noise.derivation import branches


class erfcx(sp.Function):  # noqa: N801 - the conventional name of the function
    """Scaled complementary error function erfcx(x) = exp(x^2) erfc(x)."""

    nargs = 1

    def fdiff(self, argindex=1):
        x = self.args[0]
        return 2 * x * erfcx(x) - 2 / sp.sqrt(sp.pi)

    def _eval_rewrite_as_erfc(self, x, **kwargs):
        return sp.exp(x**2) * sp.erfc(x)


def _scaled_erfc(expr: sp.Mul) -> sp.Expr:
    exps = [f for f in expr.args if isinstance(f, sp.exp)]
    erfcs = [f for f in expr.args if isinstance(f, sp.erfc)]
    if len(exps) != 1 or len(erfcs) != 1:
        return expr
    (growth,), (tail,) = exps, erfcs
    rest = [f for f in expr.args if f is not growth and f is not tail]
    b = tail.args[0]
    return sp.Mul(*rest) * erfcx(b) * sp.exp(sp.expand(growth.args[0] - b**2))


def _distribute_exp(expr: sp.Mul) -> sp.Expr:
    """exp(A) (t_1 + t_2 + ...) -> exp(A) t_1 + exp(A) t_2 + ... (each product's exps combined) where
    some t_k holds an erfc: the erfcx rewrite then sees exp and erfc in one product (the closed forms of
    exponential-polynomial laws, whose simplified D keeps exp(u^2/2a) outside the sum)."""
    exps = [f for f in expr.args if isinstance(f, sp.exp)]
    sums = [f for f in expr.args if f.is_Add and f.has(sp.erfc)]
    if len(exps) != 1 or len(sums) != 1:
        return expr
    rest = [f for f in expr.args if f is not exps[0] and f is not sums[0]]
    return sp.Mul(*rest) * sp.Add(*[sp.powsimp(exps[0] * term) for term in sums[0].args])


def _expm1_pairs(expr: sp.Add) -> sp.Expr:
    terms = list(expr.args)
    for i, term in enumerate(terms):
        exps = [f for f in sp.Mul.make_args(term) if isinstance(f, sp.exp)]
        if len(exps) != 1:
            continue
        coeff = sp.Mul(*[f for f in sp.Mul.make_args(term) if f is not exps[0]])
        if -coeff in terms:
            j = terms.index(-coeff)
            rest = [t for k, t in enumerate(terms) if k not in (i, j)]
            return _expm1_pairs(sp.Add(*rest, coeff * expm1(exps[0].args[0])))
    return expr


class expm1_given_exp(sp.Function):  # noqa: N801 - the name of the kernel function (fricgen.generated.special)
    """expm1(x) given e = exp(x): e - 1 where x < -ln 2, else expm1(x) (the value is expm1(x) either way)."""

    nargs = 2


def branch_cse(expr: sp.Expr) -> tuple[list[tuple[sp.Symbol, sp.Expr]], sp.Expr]:
    """Common subexpressions (cse0, cse1, ...) of one branch of a kernel, exp shared first (share_exp):
    (assignments, the reduced expression), for the Python and the C++ kernels alike."""
    replacements, (reduced,) = sp.cse([share_exp(expr)], symbols=sp.numbered_symbols("cse"), optimizations="basic")
    return replacements, reduced


def share_exp(expr: sp.Expr) -> sp.Expr:
    """expm1(x) -> expm1_given_exp(exp(x), x) where exp(x) also appears in ``expr``; not inside a
    Piecewise, whose branches CSE would then evaluate outside their conditions (exp(x) may overflow
    in a branch that does not use it)."""
    if expr.has(sp.Piecewise):
        return expr
    exps = {sp.expand(e.args[0]): e.args[0] for e in expr.atoms(sp.exp)}  # the same argument, any written form

    def given_exp(e: expm1) -> sp.Expr:
        x = exps.get(sp.expand(e.args[0]))
        return e if x is None else expm1_given_exp(sp.exp(x), x)

    return expr.replace(lambda e: isinstance(e, expm1), given_exp)


def _sech_squared(expr: sp.Add) -> sp.Expr:
    terms = list(expr.args)
    squares = [t for t in terms if (-t).is_Pow and (-t).exp == 2 and isinstance((-t).base, sp.tanh)]
    if not squares or sp.S.One not in terms:
        return expr
    rest = [t for t in terms if t not in (sp.S.One, squares[0])]
    return sp.Add(*rest, 1 / sp.cosh((-squares[0]).base.args[0]) ** 2)


def _fold_constants(expr: sp.Mul) -> sp.Expr:
    numbers = [f for f in expr.args if f.is_number]
    if len(numbers) < 2 and not any(not f.is_Rational for f in numbers):
        return expr
    symbolic = [f for f in expr.args if not f.is_number]
    value = sp.Float(sp.Mul(*numbers).evalf(25), 20)
    return sp.Mul(value, *symbolic, evaluate=False) if symbolic else value


def stabilize(expr: sp.Expr) -> sp.Expr:
    """Apply the numerically stable rewrites to ``expr`` (mathematically exact).

    Then powers with equal exponents are recombined, sqrt(kT) sqrt(mu) -> sqrt(kT mu): one square
    root instead of two. SymPy splits such powers of positive symbols automatically, so the result
    holds assumption-free symbols of the same names (it is meant for printing only; valid since
    all symbols of a law are positive, or nonnegative for a parameter whose range holds 0).
    """
    expr = expr.replace(lambda e: e.is_Mul, _distribute_exp)
    expr = expr.replace(lambda e: e.is_Mul, _scaled_erfc)
    expr = expr.replace(lambda e: e.is_Add, _expm1_pairs)
    expr = expr.replace(lambda e: e.is_Add, _sech_squared)
    plain = {x: sp.Symbol(x.name) for x in expr.free_symbols}
    return sp.powsimp(expr.xreplace(plain), combine="base", force=True, deep=True)


def fold_constants(expr: sp.Expr) -> sp.Expr:
    """Evaluate products of numeric constants to 20-digit floats."""
    return expr.replace(lambda e: e.is_Mul and any(f.is_number for f in e.args), _fold_constants)


class KernelPrinter(PythonCodePrinter):
    """Python printer for Numba nopython kernels (``math`` functions, ``erfcx`` from fricgen.generated.special)."""

    def __init__(self, settings=None):
        defaults = {"standard": "python3", "fully_qualified_modules": True, "reserved_word_suffix": "_"}
        super().__init__({**defaults, **(settings or {})})

    def _print_erfcx(self, expr):
        return f"erfcx({self._print(expr.args[0])})"

    def _print_expm1_given_exp(self, expr):
        return f"expm1_given_exp({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Float(self, expr):
        return repr(float(expr))


# --- kernel bodies: one shape, each backend's syntax ---------------------------------------------


@dataclass(frozen=True)
class Syntax:
    """How a backend's language spells a kernel body: templates with ``{name}``, ``{value}`` and
    ``{condition}``, and one level of indentation."""

    indent: str
    assign: str  #: a common subexpression
    give: str  #: the function's result
    first_branch: str  #: opens the first branch of a Piecewise
    next_branch: str  #: opens each later branch
    close: str | None  #: closes a branch (None where indentation does)
    nan: str  #: no branch holds
    guard: tuple[str, ...]  #: the lines of ``return {value}`` at u <= 0


def statements(expr: sp.Expr, printer, syntax: Syntax, depth: int) -> list[str]:
    """CSE assignments and the result of one branch, ``depth`` levels in."""
    replacements, reduced = branch_cse(expr)
    pad = syntax.indent * depth
    lines = [pad + syntax.assign.format(name=printer.doprint(name), value=printer.doprint(value)) for name, value in replacements]
    return [*lines, pad + syntax.give.format(value=printer.doprint(reduced))]


def body(expr: sp.Expr, printer, syntax: Syntax) -> list[str]:
    """A kernel's body: a top-level Piecewise becomes branches, each with its own CSE."""
    if not isinstance(expr, sp.Piecewise):
        return statements(expr, printer, syntax, 1)
    lines, pad = [], syntax.indent
    for k, (branch, condition) in enumerate(expr.args):
        if condition == sp.true:
            return [*lines, *statements(branch, printer, syntax, 1)]
        opening = (syntax.next_branch if k else syntax.first_branch).format(condition=printer.doprint(condition))
        lines += [pad + opening, *statements(branch, printer, syntax, 2), *([pad + syntax.close] if syntax.close else [])]
    return [*lines, pad + syntax.give.format(value=syntax.nan)]


def zero_speed_guard(limit: sp.Expr | None, printer, syntax: Syntax) -> list[str]:
    """The guard ``u <= 0 -> <limit u -> 0+>`` (0 if infinite or unknown); nothing for None (:func:`zero_speed_limit`)."""
    if limit is None:
        return []
    value = printer.doprint(fold_constants(limit if limit.is_finite else sp.Integer(0)))
    return [syntax.indent + line.format(value=value) for line in syntax.guard]


# --- formulas in docstrings ----------------------------------------------------------------------

#: Formulas in kernel docstrings longer than this are cut with "..." (a long Piecewise: per branch).
FORMULA_LIMIT = 200


def cut(text: str) -> str:
    """``text`` cut with "..." at FORMULA_LIMIT characters."""
    return text if len(text) <= FORMULA_LIMIT else text[: FORMULA_LIMIT - 3] + "..."


def compact(expr: sp.Expr) -> sp.Expr:
    """``expr`` for reading: sqrt(kT)*sqrt(mu) -> sqrt(kT*mu) (exact, all symbols being positive or nonnegative)."""
    plain = {x: sp.Symbol(x.name) for x in expr.free_symbols}
    return sp.powsimp(expr.xreplace(plain), combine="base", force=True, deep=True)


def equation(lhs: str, expr: sp.Expr, what: str, indent: str = "    ") -> str:
    """A docstring ``lhs = expr, what.``: ``str`` of the SymPy expression, or for a Piecewise longer than
    FORMULA_LIMIT ``lhs, what:`` and one line per branch (``value  if condition`` ... ``value  otherwise``).
    Longer expressions (values of branches) are cut with "..." at FORMULA_LIMIT."""
    expr = compact(expr)
    text = str(expr)
    if len(text) <= FORMULA_LIMIT or not isinstance(expr, sp.Piecewise):
        return f"{lhs} = {cut(text)}, {what}."
    lines = [f"{cut(str(value))}  " + ("otherwise" if condition == sp.true else f"if {condition}") for value, condition in expr.args]
    return f"{lhs}, {what}:\n" + "\n".join(indent + line for line in lines)


def short_formula(expr: sp.Expr, limit: int = FORMULA_LIMIT // 2) -> str | None:
    """The one-line formula of ``expr`` if it is at most ``limit`` characters long, else None."""
    text = str(compact(expr))
    return text if len(text) <= limit else None


# --- shared by every backend: headers of generated files, the limit u -> 0+ -------------------------


def header(lines: list[str]) -> str:
    intro = [f"Generated by fricgen's code generator (fricgen.derive, generator {GENERATOR_VERSION}). Do not edit by hand."]
    return "".join(f"# {line}\n" for line in intro + lines)


def zero_speed_limit(expr: sp.Expr) -> sp.Expr | None:
    """The limit u -> 0+ (possibly infinite) when evaluation at u = 0 is undefined, else None;
    ``sp.nan`` when SymPy cannot take the limit (a symbolic exponent: u**(alpha - 1))."""
    first = branches(expr)[0].expr
    if first.subs(u, 0).is_finite:
        return None
    try:
        return sp.limit(first, u, 0, "+")
    except (NotImplementedError, ValueError, TypeError):
        return sp.nan


def zero_speed_note(limit: sp.Expr | None) -> str:
    """What the guard returns, for the docstring."""
    if limit is None:
        return ""
    if limit is sp.nan:
        return "; 0 at u <= 0 (SymPy cannot take the limit u -> 0+; the force (f/u) u vanishes there)"
    return f"; at u <= 0 its limit u -> 0+, {compact(limit)}" if limit.is_finite else "; 0 at u <= 0 (the limit u -> 0+ is infinite)"
