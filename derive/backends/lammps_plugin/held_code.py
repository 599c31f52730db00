"""A law's kernels in u for the LAMMPS fix, with their parts free of u held once per pair.

The fix evaluates f/u and D of a pair's mode twice per step (at x and at the proposal y), with the same w,
r, mu and kT: everything of those formulas that does not depend on the speed u (a threshold such as
kappa_f w/gamma_f, 1/sqrt(kT mu), an erfcx of w alone) is the same both times. :func:`held_kernel` prints a
kernel as two functions: ``hold_NAME`` computes its largest subexpressions free of u into ``held[0..K-1]``
(once per pair), ``NAME`` (the kernel's signature plus ``held``) the rest. The arithmetic is the kernel's
(:func:`fricgen.derive.backends.lammps_plugin.code.kernel`), regrouped: the factors free of u of a
product (the terms of a sum) are multiplied (added) first, which moves results by round-off only.
A held part that belongs to a branch the speed does not take may be inf or NaN; it is never read.
"""

from __future__ import annotations

import sympy as sp

from ...law.laws import FrictionLaw
from ...noise.derivation import NoiseModel
from ..printing import body, fold_constants, share_exp, stabilize, zero_speed_guard
from .code import (
    INDENT,
    SYNTAX,
    CxxKernelPrinter,
    Formula,
    amplitude_formula,
    amplitude_kernel,
    comment,
    law_kernels,
    ratio_formula,
    slope_formula,
    unpacking,
)
from .fix_code import THETA


def free_of_u(expr: sp.Basic) -> bool:
    """Whether ``expr`` does not depend on the speed u (by name: the printers' symbols carry no assumptions)."""
    return not any(x.name == "u" for x in expr.free_symbols)


def lift(expr: sp.Basic, held: dict[sp.Expr, sp.Symbol]) -> sp.Basic:
    """``expr`` with each largest numeric subexpression free of u (not a bare symbol or number) replaced by a
    symbol ``held[k]``; ``held`` maps the subexpressions to their symbols (extended here, shared ones once)."""
    if expr.is_Atom:
        return expr
    if free_of_u(expr):
        return held.setdefault(expr, sp.Symbol(f"held[{len(held)}]")) if isinstance(expr, sp.Expr) else expr
    if isinstance(expr, (sp.Add, sp.Mul)):
        free = [a for a in expr.args if free_of_u(a)]
        moving = [lift(a, held) for a in expr.args if not free_of_u(a)]
        if free:
            free = [lift(expr.func(*free), held)]
        return expr.func(*free, *moving)
    return expr.func(*(lift(a, held) for a in expr.args))


def signature(arguments: str) -> str:
    """C++ parameters of a Python argument list ("u, w, r, params" -> double u, ..., const double *params)."""
    return ", ".join("const double *params" if a == "params" else f"double {a}" for a in arguments.split(", "))


def held_kernel(formula: Formula, parameters: list[sp.Symbol]) -> tuple[str, int]:
    """(C++ text of ``hold_NAME`` and ``NAME``, K the number of values held) of a kernel in u (its argument list
    begins with u)."""
    name, args, expr, doc, at_zero = formula
    printer = CxxKernelPrinter()
    held: dict[sp.Expr, sp.Symbol] = {}
    expr = fold_constants(stabilize(expr))
    if isinstance(expr, sp.Piecewise):  # exp and expm1 of one argument paired per branch, as body's CSE does
        expr = sp.Piecewise(*((share_exp(value), condition) for value, condition in expr.args))
    else:
        expr = share_exp(expr)
    moving = lift(expr, held)
    guard = zero_speed_guard(at_zero, printer, SYNTAX)
    replacements, reduced = sp.cse(list(held), symbols=sp.numbered_symbols("pair"), optimizations="basic")
    hold = [f"{INDENT}const double {printer.doprint(s)} = {printer.doprint(v)};" for s, v in replacements]
    hold += [f"{INDENT}{printer.doprint(s)} = {printer.doprint(v)};" for s, v in zip(held.values(), reduced)]
    limit = at_zero if at_zero is not None else sp.S.Zero
    pair_args = args.removeprefix("u, ")
    silent = [] if held else [f"{INDENT}(void) held;"]
    hold_unpack = unpacking({x.name for x in sp.Tuple(*held).free_symbols}, parameters, pair_args, False, printer)
    unpack = unpacking({x.name for x in sp.Tuple(moving, limit).free_symbols}, parameters, args, bool(guard), printer)
    texts = [
        f"inline void hold_{name}(double *held, {signature(pair_args)})",
        "{",
        *hold_unpack,
        *silent,
        *hold,
        "}",
        f"inline double {name}({signature(args)}, const double *held)",
        "{",
        *unpack,
        *silent,
        *guard,
        *body(moving, printer, SYNTAX),
        "}",
    ]
    doc = comment(doc + f"\nIts parts free of u ({len(held)}) are held once per pair (hold_{name}).")
    return doc + "\n".join(texts) + "\n", len(held)


def fix_kernels(law: FrictionLaw, models: dict[str, NoiseModel], order: int) -> tuple[str, str]:
    """(the fix's kernels, the functions hold and noise_amplitude over its calculi ``models``): weight, friction and
    the quadrature of (F-22) as the pair style prints them (code.law_kernels); f/u, df/du and every closed-form D with
    their parts free of u held. A pair holds [f/u's | df/du's (HK only) | D's of its calculus]."""
    params = [p.symbol for p in law.parameters]
    base = next((m for m in models.values() if not m.closed_form), next(iter(models.values())))
    ratio, ratio_count = held_kernel(ratio_formula(law), params)
    slope, slope_count = held_kernel(slope_formula(law), params)
    parts, counts, holds, calls = [law_kernels(law, base, order, in_u=False), ratio, slope], [0], [], []
    for k, c in enumerate(THETA):
        if c not in models:
            continue
        if models[c].closed_form:
            text, count = held_kernel(amplitude_formula(models[c]), params)
            holds.append(f"  if (c == {k}) hold_noise_amplitude_{c}(held + AMPLITUDE_AT, w, r, mu, kT, params);\n")
            calls.append(f"  if (c == {k}) return noise_amplitude_{c}(u, w, r, mu, kT, params, held + AMPLITUDE_AT);\n")
            parts.append(text)
            counts.append(count)
        else:
            parts.append(amplitude_kernel(law, models[c]))
            calls.append(f"  if (c == {k}) return noise_amplitude_{c}(u, w, r, mu, kT, params);\n")
    held = max(1, ratio_count + slope_count + max(counts))
    unused = "" if holds else "  (void) held;    // no D of the law's calculi has a closed form\n"
    functions = f"""
// What a pair holds (the parts free of u of its kernels): f/u's, then df/du's (HK), then D's of the calculus.
const int SLOPE_AT = {ratio_count}, AMPLITUDE_AT = {ratio_count + slope_count}, HELD = {held};

// The held parts of a pair (w, r, mu) for the calculus with index c (CALCULI).
inline void hold(int c, double *held, double w, double r, double mu, double kT, const double *params)
{{
  hold_friction_over_u(held, w, r, params);
  if (c == 2) hold_friction_slope(held + SLOPE_AT, w, r, params);
{"".join(holds)}}}

// D of the calculus with index c (CALCULI), from the pair's held parts.
inline double noise_amplitude(int c, double u, double w, double r, double mu, double kT, const double *params, const double *held)
{{
{unused}{"".join(calls)}  return NAN;
}}
"""
    return "\n".join(parts), functions
