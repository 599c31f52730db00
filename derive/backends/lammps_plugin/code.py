"""C++ kernels of a verified law for the LAMMPS pair style: SymPy's C++ printer subclassed like
:class:`fricgen.derive.backends.printing.KernelPrinter`, the same stable rewrites, the same guards at u = 0, and the
quadrature of (F-22) ported from fricgen.derive.backends.numba_kernels.kernel_code (TAIL_KERNEL, SPLIT_TAIL_KERNEL).

Every kernel has the signature of its Numba twin, ``double name(double u, double w, double r, const
double *params)`` etc., with ``params`` in the order of the law's parameters, and lives in an
anonymous namespace of the pair style's .cpp file (two plugins loaded together never share a
symbol). The hand-written numerics, erfcx and the counter-based normals of fricgen.rng, are
:func:`support`; :mod:`fricgen.derive.backends.lammps_plugin.module` assembles the files.
"""

from __future__ import annotations

from typing import NamedTuple

import sympy as sp
from sympy.integrals.quadrature import gauss_legendre
from sympy.printing.cxx import CXX17CodePrinter

from ...law.laws import FrictionLaw
from ...law.potentials import PAIR_POTENTIALS, Potential
from ...law.symbols import s, u
from ...noise.derivation import NoiseModel, switches
from ..printing import Syntax, body, compact, cut, equation, fold_constants, stabilize, zero_speed_guard, zero_speed_limit, zero_speed_note
from ..tables import table_factor
from .table_code import table_builder, tabled_amplitude

INDENT = "  "
#: C++'s spelling of a kernel body (printing.body): a Piecewise as a chain of ``if`` blocks.
SYNTAX = Syntax(
    indent=INDENT,
    assign="const double {name} = {value};",
    give="return {value};",
    first_branch="if ({condition}) {{",
    next_branch="if ({condition}) {{",
    close="}",
    nan="NAN",
    guard=("if (u <= 0.0) return {value};",),
)
#: C++ parameter lists of the kernel signatures (the Python kernels' argument names, as in the Numba backend's SIGNATURES).
SIGNATURES = {
    "r, params": "double r, const double *params",
    "u, w, r, params": "double u, double w, double r, const double *params",
    "u, w, r, mu, kT, params": "double u, double w, double r, double mu, double kT, const double *params",
    "w, r, params": "double w, double r, const double *params",
}


class CxxKernelPrinter(CXX17CodePrinter):
    """C++17 for the pair style: integer powers by multiplication (fricgen_powi), Min/Max as nested
    std::fmin/fmax (std::min(1, x) would not compile), erfcx as fricgen_erfcx, floats as the
    shortest literal that reads back to the same double, a Piecewise inside an expression as ``?:``."""

    def __init__(self, settings=None):
        super().__init__({"reserved_word_suffix": "_", **(settings or {})})

    def _print_erfcx(self, expr):
        return f"fricgen_erfcx({self._print(expr.args[0])})"

    def _print_expm1_given_exp(self, expr):  # as fricgen.generated.special.expm1_given_exp
        e, x = (self._print(a) for a in expr.args)
        return f"(({x}) < -0.6931471805599453 ? ({e}) - 1.0 : std::expm1({x}))"

    def _print_Float(self, expr):
        return repr(float(expr))

    def _print_Integer(self, expr):
        return f"{int(expr)}.0"

    def _print_Rational(self, expr):
        return f"({expr.p}.0/{expr.q}.0)"

    def _nested(self, name, args):
        first, *rest = (self._print(a) for a in args)
        for other in rest:
            first = f"std::{name}({first}, {other})"
        return first

    def _print_Min(self, expr):
        return self._nested("fmin", expr.args)

    def _print_Max(self, expr):
        return self._nested("fmax", expr.args)

    def _print_Pow(self, expr):
        base, exponent = expr.args
        if exponent == sp.S.Half:
            return f"std::sqrt({self._print(base)})"
        if exponent == -sp.S.Half:
            return f"(1.0/std::sqrt({self._print(base)}))"
        if exponent.is_Integer:
            n = int(exponent)
            power = self._print(base) if abs(n) == 1 else f"fricgen_powi({self._print(base)}, {abs(n)})"
            return f"(1.0/{power})" if n < 0 else power
        return f"std::pow({self._print(base)}, {self._print(exponent)})"

    def _print_Piecewise(self, expr):
        *pairs, (last, condition) = expr.args
        text = self._print(last) if condition == sp.true else "NAN"
        for value, test in reversed(pairs):
            text = f"(({self._print(test)}) ? ({self._print(value)}) : ({text}))"
        return text


def comment(text: str, indent: str = "") -> str:
    """``text`` as // comment lines; a line that would end in a backslash (a line continuation of a law's
    f) gets a mark after it, so that it cannot splice the next line into the comment."""
    lines = (f"{indent}// {line}".rstrip() for line in text.splitlines())
    return "".join(line + (" (continued)" if line.endswith("\\") else "") + "\n" for line in lines)


def kernel(name: str, args: str, expr: sp.Expr, doc: str, parameters: list[sp.Symbol], at_zero: sp.Expr | None = None) -> str:
    """One C++ function: the parameters it uses read from ``params``, then the printed expression."""
    printer = CxxKernelPrinter()
    guard = zero_speed_guard(at_zero, printer, SYNTAX)  # at u <= 0, the limit u -> 0+ (zero_speed_limit)
    expr = fold_constants(stabilize(expr))
    unpack = unpacking({x.name for x in expr.free_symbols}, parameters, args, bool(guard), printer)
    signature = f"inline double {name}({SIGNATURES[args]})"
    lines = [comment(doc).rstrip("\n"), signature, "{", *unpack, *guard, *body(expr, printer, SYNTAX), "}"]
    return "\n".join(lines) + "\n"


def unpacking(used: set[str], parameters: list[sp.Symbol], args: str, guarded: bool, printer) -> list[str]:
    """A kernel's first lines: the ``parameters`` it ``used`` read from ``params``, and (void) for each argument of
    ``args`` it does not use (u is used by a zero-speed guard if ``guarded``)."""
    unpack = [f"{INDENT}const double {printer.doprint(p)} = params[{k}];" for k, p in enumerate(parameters) if p.name in used]
    if not used & {"params", *(p.name for p in parameters)}:
        unpack.append(f"{INDENT}(void) params;")
    for arg in ("u", "w", "r", "mu", "kT"):
        if arg in args.split(", ") and arg not in used and not (arg == "u" and guarded):
            unpack.append(f"{INDENT}(void) {arg};")
    return unpack


# --- a law's kernels ---------------------------------------------------------------------------------


class Formula(NamedTuple):
    """A kernel in u as both printers take it (:func:`kernel`, held_code.held_kernel): its name, Python argument
    list (SIGNATURES), expression, docstring and limit at u -> 0+ (None: no guard)."""

    name: str
    args: str
    expr: sp.Expr
    doc: str
    at_zero: sp.Expr | None


def law_kernels(law: FrictionLaw, model: NoiseModel, order: int, in_u: bool = True) -> str:
    """weight (if the law has one), friction, friction_over_u and noise_amplitude of ``model``'s calculus (these two
    only ``in_u``: the fix prints its kernels in u with parts held per pair, held_code), with the quadrature helpers
    of (F-22) when D has no closed form."""
    params = [p.symbol for p in law.parameters]
    parts = []
    if law.weight is not None:
        parts.append(
            kernel("weight", "r, params", law.weight, equation("w(r)", law.weight, f"the weight in f ({law.weight_source})", ""), params)
        )
    doc = f"f(u, w, r) = {law.source}, the magnitude of the friction force (it opposes the sliding)."
    parts.append(kernel("friction", "u, w, r, params", law.friction, doc, params))
    if in_u:
        formula = ratio_formula(law)
        parts.append(kernel(*formula[:4], params, formula.at_zero))
    if not model.closed_form:
        parts += quadrature_helpers(law, model, order)
    if in_u:
        parts.append(amplitude_kernel(law, model))
    return "\n".join(parts)


def ratio_formula(law: FrictionLaw) -> Formula:
    """f/u, the factor of the tangential velocity."""
    ratio = sp.piecewise_fold((law.friction / u).rewrite(sp.Piecewise))
    at_zero = zero_speed_limit(ratio)
    doc = equation("f/u", ratio, f"the factor of the tangential velocity{zero_speed_note(at_zero)}", "")
    return Formula("friction_over_u", "u, w, r, params", ratio, doc, at_zero)


def quadrature_helpers(law: FrictionLaw, model: NoiseModel, order: int) -> list[str]:
    """The switches of f, the quadrature of (F-22) and (where the law has them) the noise tables' factor and builder."""
    params = [p.symbol for p in law.parameters]
    parts = []
    cuts = switches(law.friction)
    for k, g in enumerate(cuts):
        doc = f"A branch condition of f changes where this changes sign: {cut(str(compact(g)))} (see next_cut)."
        parts.append(kernel(f"switch_{k}", "u, w, r, params", g, doc, params))
    parts.append(tail_kernels(order, len(cuts)))
    if (factor := table_factor(law, model)) is not None:  # noise tables (fricgen.derive.backends.tables): f = h g(u), D = h D_g(u)
        parts += [kernel("factor", "w, r, params", factor, f"h(w, r) = {cut(str(compact(factor)))}", params), table_builder()]
    return parts


def amplitude_formula(model: NoiseModel) -> Formula:
    """noise_amplitude_<calculus> of ``model`` in closed form."""
    c, a = model.calculus.value, compact(model.variance_scale)
    at_zero = zero_speed_limit(model.amplitude)
    at_zero = None if at_zero is sp.nan else at_zero
    how = "D = f/u as nu = 0" if a == 0 else f"(F-22) in closed form with kT nu = {a}"
    doc = equation("D(u)", model.amplitude, f"the {c} calculus: {how}{zero_speed_note(at_zero)}", "")
    return Formula(f"noise_amplitude_{c}", "u, w, r, mu, kT, params", model.amplitude, doc, at_zero)


def amplitude_kernel(law: FrictionLaw, model: NoiseModel) -> str:
    """noise_amplitude_<calculus> of ``model``: its closed form, or the quadrature of (F-22) (quadrature_helpers)."""
    params = [p.symbol for p in law.parameters]
    if model.closed_form:
        formula = amplitude_formula(model)
        return kernel(*formula[:4], params, formula.at_zero)
    c, a = model.calculus.value, compact(model.variance_scale)
    args = "u, w, r, mu, kT, params"
    factor = table_factor(law, model)
    doc = (
        f"D(u) = (1/a) int_u^oo f(s) exp(-(s**2 - u**2)/(2*a)) ds (F-22), a = kT nu = {a} ({c} calculus),\n"
        f"f(s) = {cut(str(compact(law.friction.subs(u, s))))}: Gauss-Legendre quadrature on geometric panels (gaussian_tail)."
        + (f"\nNo closed form: {cut(model.reason)}." if model.reason else "")
        + ("\nFrom the noise table for a and the parameters (noise_table_for) where there is one." if factor is not None else "")
    )
    scale = CxxKernelPrinter().doprint(model.variance_scale)
    body = tabled_amplitude(scale) if factor is not None else f"{{\n{INDENT}return gaussian_tail(u, {scale}, w, r, params);\n}}\n"
    return f"{comment(doc)}inline double noise_amplitude_{c}({SIGNATURES[args]})\n{body}"


def slope_formula(law: FrictionLaw) -> Formula:
    """friction_slope, df/du (the Itô drift of the HK calculus in the pairwise step), as the Numba kernels print it."""
    slope = sp.diff(sp.piecewise_fold(law.friction.rewrite(sp.Piecewise)), u)
    doc = equation("df/du", slope, "the slope of f in u (the Itô drift of the HK calculus needs it, D' = (u f' - f)/u**2)", "")
    return Formula("friction_slope", "u, w, r, params", slope, doc, None)


def potential_kernels(potential: Potential) -> str:
    """energy and force (-dU/dr) of a pair potential, params = its parameters in the order of its defaults."""
    params = [potential.symbols[n] for n in potential.defaults]
    return "\n".join(
        [
            kernel(
                "pair_energy",
                "r, params",
                potential.energy,
                equation("U(r)", potential.energy, f"{potential.name} ({potential.reference})", ""),
                params,
            ),
            kernel("pair_force", "r, params", potential.force, equation("F(r) = -dU/dr", potential.force, "the pair force", ""), params),
        ]
    )


def wca() -> Potential:
    return PAIR_POTENTIALS["wca"]


# --- the quadrature of (F-22) ----------------------------------------------------------------------


def quadrature_constants(order: int) -> str:
    nodes, weights = gauss_legendre(order, 25)
    return (
        f"const double GL_NODES[{order}] = {{{', '.join(repr(float(x)) for x in nodes)}}};\n"
        f"const double GL_WEIGHTS[{order}] = {{{', '.join(repr(float(x)) for x in weights)}}};\n"
    )


_PANEL = """// {order}-point Gauss-Legendre of f(u + t) exp(-(2ut + t^2)/(2a)) over lo <= t <= hi.
inline double panel(double u, double a, double lo, double hi, double w, double r, const double *params)
{{
  const double mid = 0.5 * (lo + hi);
  const double half = 0.5 * (hi - lo);
  double total = 0.0;
  for (int j = 0; j < {order}; ++j) {{
    const double t = mid + half * GL_NODES[j];
    total += half * GL_WEIGHTS[j] * friction(u + t, w, r, params) * std::exp(-(2.0 * u * t + t * t) / (2.0 * a));
  }}
  return total;
}}
"""

_CUT = """  {{
    const bool left = switch_{k}(u + lo, w, r, params) > 0.0;
    if ((switch_{k}(u + end, w, r, params) > 0.0) != left) {{
      double a = lo, b = end;
      while (true) {{
        const double m = 0.5 * (a + b);
        if (m <= a || m >= b) break;
        if ((switch_{k}(u + m, w, r, params) > 0.0) == left) a = m;
        else b = m;
      }}
      end = b;
    }}
  }}"""

_NEXT_CUT = """// The first t in (lo, hi] up to which no branch condition of f changes sign between lo and t:
// hi, or a sign change of a switch_<k> of f(u + t), found by bisection to the last bit.
inline double next_cut(double u, double lo, double hi, double w, double r, const double *params)
{{
  double end = hi;
{cuts}
  return end;
}}
"""

_TAIL = """// (1/a) int_u^oo f(s) exp(-(s^2 - u^2)/(2a)) ds (F-22), with t = s - u: {order}-point Gauss-Legendre on the
// panels [0, h], [h, 2h], [2h, 4h], ... with h = a / (u + sqrt(a)) / 256 (for u < h from [0, h/2^16]
// up to h), until the Gaussian weight exp(-(2ut + t^2)/(2a)) is below exp(-46){split}
// (fricgen.derive.backends.numba_kernels.kernel_code's _gaussian_tail, step for step).
inline double gaussian_tail(double u, double a, double w, double r, const double *params)
{{
  const double h = a / (u + std::sqrt(a)) / 256.0;
  double lo = 0.0, hi = u >= h ? h : h / 65536.0, total = 0.0;
  while (true) {{
{panels}
    if ((2.0 * u * hi + hi * hi) / (2.0 * a) > 46.0) return total / a;
    lo = hi;
    hi = 2.0 * hi;
  }}
}}
"""

_PANELS = """    const double mid = 0.5 * (lo + hi);
    const double half = 0.5 * (hi - lo);
    for (int j = 0; j < {order}; ++j) {{
      const double t = mid + half * GL_NODES[j];
      total += half * GL_WEIGHTS[j] * friction(u + t, w, r, params) * std::exp(-(2.0 * u * t + t * t) / (2.0 * a));
    }}"""

_SPLIT_PANELS = """    double start = lo;
    for (int piece = 0; piece < 64; ++piece) {
      const double end = next_cut(u, start, hi, w, r, params);
      total += panel(u, a, start, end, w, r, params);
      if (end >= hi) break;
      start = end;
    }"""


def tail_kernels(order: int, count: int) -> str:
    """The quadrature of (F-22) for a law with ``count`` switch functions (fricgen.derive.noise.derivation.switches)."""
    if count == 0:
        return "\n".join([quadrature_constants(order), _TAIL.format(order=order, split="", panels=_PANELS.format(order=order))])
    parts = [quadrature_constants(order), _PANEL.format(order=order)]
    cuts = "\n".join(_CUT.format(k=k) for k in range(count))
    parts.append(_NEXT_CUT.format(cuts=cuts))
    split = ";\n// each panel cut at the branch points of f inside it (next_cut; at most 64 pieces)"
    return "\n".join([*parts, _TAIL.format(order=order, split=split, panels=_SPLIT_PANELS)])
