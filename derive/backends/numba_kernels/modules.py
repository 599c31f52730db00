"""The text of every generated module: a law's kernels, a potential's, the special functions.

Printing only, nothing written: :mod:`fricgen.derive.driver` writes these texts into ``generated/``,
and :mod:`.accuracy` runs the text of a law module as plain Python to check its numbers against
mpmath, so both take the same code from here.
"""

from __future__ import annotations

import hashlib

import sympy as sp
from sympy.integrals.quadrature import gauss_legendre

from ...law import potentials
from ...law.catalogues import inert
from ...law.lawdata import potential_source_hash
from ...law.laws import FrictionLaw
from ...law.potentials import EXTERNAL_POTENTIALS, PAIR_POTENTIALS, Potential
from ...law.symbols import kT, s, u
from ...noise.derivation import NoiseModel, switches
from ..printing import (
    FORMULA_LIMIT,
    KernelPrinter,
    body,
    compact,
    cut,
    equation,
    fold_constants,
    header,
    short_formula,
    stabilize,
    zero_speed_guard,
    zero_speed_limit,
    zero_speed_note,
)
from ..special_functions import SPECIAL_SOURCE
from ..tables import TABLE_PIECES, TABLE_TOLERANCE, table_factor
from .kernel_code import (
    CONTACT_SIGNATURE,
    FIELD_KERNEL,
    INDENT,
    SYNTAX,
    TABLE_KERNEL,
    TABLED_AMPLITUDE,
    TABULATE_KERNEL,
    TABULATE_SIGNATURE,
    quote_doc,
    ranges_literal,
    tail_kernels,
)
from .kernel_code import decorator as _decorator

#: Gauss–Legendre order of the integral-form kernels (see fricgen.derive.backends.numba_kernels.kernel_code.TAIL_KERNEL).
QUADRATURE_ORDER = 10


# --- functions ---------------------------------------------------------------------------------


def _kernel(name: str, args: str, expr: sp.Expr, doc: str, parameters: list[sp.Symbol], at_zero: sp.Expr | None = None) -> str:
    """One Numba function: unpack the parameters it uses, then the printed expression."""
    printer = KernelPrinter()
    guard = zero_speed_guard(at_zero, printer, SYNTAX)  # at u <= 0, the limit u -> 0+ (zero_speed_limit)
    expr = fold_constants(stabilize(expr))
    used = {x.name for x in expr.free_symbols}
    unpack = [f"{INDENT}{printer.doprint(p)} = params[{k}]" for k, p in enumerate(parameters) if p.name in used]
    docstring = INDENT + quote_doc(doc.replace("\n", "\n" + INDENT))
    lines = [_decorator(args), f"def {name}({args}):", docstring, *unpack, *guard, *body(expr, printer, SYNTAX)]
    return "\n".join(lines) + "\n"


# --- law modules -------------------------------------------------------------------------------


def _quadrature_constants() -> str:
    nodes, weights = gauss_legendre(QUADRATURE_ORDER, 25)
    as_tuple = ", ".join
    return f"_GL_NODES = ({as_tuple(repr(float(x)) for x in nodes)},)\n_GL_WEIGHTS = ({as_tuple(repr(float(x)) for x in weights)},)\n"


def law_module(law: FrictionLaw, models: dict[str, NoiseModel], digest: str, source: str, regenerate: str = "") -> str:
    """The text of ``generated/laws/<law>.py`` for verified models of ``law``; ``regenerate`` is the
    command that regenerates it (``fricgen generate LAW`` by default). ``source`` and ``regenerate``, which
    hold the name of a user's folder, are printed into the header's comments by
    :func:`fricgen.derive.law.catalogues.inert` (quoted and escaped unless plain)."""
    params = [p.symbol for p in law.parameters]
    forms = ", ".join(f"{c} ({'closed form' if m.closed_form else 'integral (F-22), quadrature'})" for c, m in models.items())
    top = header(
        [
            f"Source: law '{law.name}' ({inert(source)}), f = {' '.join(law.source.split())}",
            f"Calculi: {forms}",
            *([f"Parameter ranges (RANGES): f >= 0 and finite over them, {law.range_check}"] if law.range_check else []),
            f"Source hash: {digest}",
            f"Regenerate: {inert(regenerate or f'fricgen generate {law.name}')}",
        ]
    )
    doc = (
        f"Kernels of the friction law {law.name}: f = {law.source}.\n\n"
        "Arguments: u tangential speed (>= 0), w weight value w(r), r centre distance, mu contact\n"
        "mobility, kT thermal energy, params parameter values in the order of PARAMETERS.\n"
        "contact_<calculus> returns (f/u, D); at u = 0 the direction is undefined and f/u is its\n"
        "limit u -> 0+ where finite (viscous laws) and 0 otherwise (static friction: no force).\n"
    )
    parts = [top, quote_doc(doc) + "\n", "import math\n", "import numba\n"]
    parts.append(
        f"\nLAW = {law.name!r}\nSOURCE_HASH = {digest!r}\n"
        f"PARAMETERS = {tuple(p.name for p in law.parameters)!r}\n"
        f"DEFAULTS = {tuple(float(p.default) for p in law.parameters)!r}\n"
        f"RANGES = {ranges_literal([p.range for p in law.parameters])}\n"
        f"UNITS = {tuple(p.unit for p in law.parameters)!r}\n"
        f"CALCULI = {tuple(models)!r}\n"
        f"CLOSED_FORM = {{{', '.join(f'{c!r}: {m.closed_form}' for c, m in models.items())}}}\n"
        f"HAS_WEIGHT = {law.weight is not None}\n"
    )
    needs_quadrature = not all(m.closed_form for m in models.values())
    if needs_quadrature:
        parts.append("\n" + _quadrature_constants())
    functions = []
    if law.weight is not None:
        lhs = f"w(r) = -dU/dr of the potential {law.weight_source}" if law.weight_source in PAIR_POTENTIALS else "w(r)"
        functions.append(_kernel("weight", "r, params", law.weight, equation(lhs, law.weight, "the weight in f"), params))
    doc = f"f(u, w, r) = {law.source}, the magnitude of the friction force (it opposes the sliding)."
    functions.append(_kernel("friction", "u, w, r, params", law.friction, doc, params))
    slope = sp.diff(sp.piecewise_fold(law.friction.rewrite(sp.Piecewise)), u)
    doc = equation("df/du", slope, "the slope of f in u (the Itô drift of the HK calculus needs it, D' = (u f' - f)/u**2)")
    functions.append(_kernel("friction_slope", "u, w, r, params", slope, doc, params))
    ratio = sp.piecewise_fold((law.friction / u).rewrite(sp.Piecewise))
    at_zero = zero_speed_limit(ratio)
    doc = equation("f/u", ratio, f"the factor of the tangential velocity{zero_speed_note(at_zero)}")
    functions.append(_kernel("friction_over_u", "u, w, r, params", ratio, doc, params, at_zero))
    if needs_quadrature:
        cuts = switches(law.friction)
        for k, g in enumerate(cuts):
            doc = f"A branch condition of f changes where this changes sign: {cut(str(compact(g)))} (see _next_cut)."
            functions.append(_kernel(f"_switch_{k}", "u, w, r, params", g, doc, params))
        functions.append(tail_kernels(QUADRATURE_ORDER, len(cuts)))
    factors = {c: table_factor(law, m) for c, m in models.items()}
    factor = next((h for h in factors.values() if h is not None), None)
    if factor is not None:  # noise tables (fricgen.derive.backends.tables)
        doc = f"h(w, r) = {cut(str(compact(factor)))}: f = h g(u), so D = h D_g(u) and the noise tables hold D_g."
        functions.append(_kernel("_factor", "w, r, params", factor, doc, params))
        functions.append(TABLE_KERNEL.format(pieces=TABLE_PIECES, tolerance=TABLE_TOLERANCE).lstrip("\n"))
    args = "u, w, r, mu, kT, params"
    for c, model in models.items():
        a = compact(model.variance_scale)
        if model.closed_form:
            at_zero = zero_speed_limit(model.amplitude)
            at_zero = None if at_zero is sp.nan else at_zero  # no limit known: D is evaluated at u = 0 as it stands
            how = "D = f/u as nu = 0" if a == 0 else f"(F-22) in closed form with kT nu = {a}"
            doc = equation("D(u)", model.amplitude, f"the {c} calculus: {how}{zero_speed_note(at_zero)}")
            functions.append(_kernel(f"noise_amplitude_{c}", args, model.amplitude, doc, params, at_zero))
        else:
            doc = (
                f"D(u) = (1/a) int_u^oo f(s) exp(-(s**2 - u**2)/(2*a)) ds (F-22), a = kT nu = {a} ({c} calculus),\n"
                f"f(s) = {cut(str(compact(law.friction.subs(u, s))))}: Gauss-Legendre quadrature on geometric panels (_gaussian_tail)."
                + (f"\nNo closed form: {cut(model.reason)}." if model.reason else "")
                + (f"\nFrom the noise table of tabulate_{c} where params carries one for a and the parameters." * (factors[c] is not None))
            )
            scale = KernelPrinter().doprint(model.variance_scale)
            tabled = TABLED_AMPLITUDE.format(scale=scale, n=len(params)) if factors[c] is not None else ""
            functions.append(
                f"{_decorator(args)}\ndef noise_amplitude_{c}({args}):\n"
                f"{INDENT}{quote_doc(doc.replace(chr(10), chr(10) + INDENT))}\n"
                + (tabled or f"{INDENT}return _gaussian_tail(u, {scale}, w, r, params)\n")
            )
            if tabled:
                kernel = TABULATE_KERNEL.format(signature=TABULATE_SIGNATURE, calculus=c, n=len(params), a=a, scale=scale)
                functions.append(kernel.lstrip("\n"))
        amplitude = short_formula(model.amplitude) if model.closed_form else None
        value = f" = sqrt({amplitude})" if amplitude else ""
        doc = f"sqrt(D(u)){value}, D = noise_amplitude_{c} ({c} calculus): the amplitude of the random contact force."
        functions.append(
            f"{_decorator(args)}\ndef noise_sqrt_{c}({args}):\n"
            f"{INDENT}{quote_doc(doc)}\n"
            f"{INDENT}return math.sqrt(noise_amplitude_{c}({args}))\n"
        )
        over_u = short_formula(ratio, FORMULA_LIMIT // 2 - len(amplitude or ""))
        value = f" = ({over_u}, {amplitude})" if amplitude and over_u else ""
        doc = f"(f/u, D){value} of one contact ({c} calculus): friction_over_u and noise_amplitude_{c} in one call."
        functions.append(
            f"{_decorator(args, CONTACT_SIGNATURE)}\ndef contact_{c}({args}):\n"
            f"{INDENT}{quote_doc(doc)}\n"
            f"{INDENT}return friction_over_u(u, w, r, params), noise_amplitude_{c}({args})\n"
        )
    code = "".join("\n\n" + f for f in functions)
    special = [name for name in ("erfcx", "expm1_given_exp") if f"{name}(" in code]
    if factor is not None:
        special += ["TABLE_ROW", "TABLE_ZONES", "table_block", "table_join", "table_points", "table_value", "table_zone"]
        parts[3] = "import numba\nimport numpy\n"
    if special:  # the hash: a new special.py rewrites this file, so Numba's cache (which tracks only its date) recompiles it
        parts.insert(4, f"\nfrom ..special import {', '.join(special)}  # special.py {_special_hash()[:16]}\n")
    return "".join(parts) + code


def potential_module(potential: Potential) -> str:
    """The text of ``generated/potentials/<name>.py``: energy and force of a potential, and for an
    external potential U(x) the force at many positions, force_field(xs, params, out)."""
    names = list(potential.defaults) + (["kT"] if potential.energy.has(kT) else [])
    symbols = {**potential.symbols, "kT": kT}
    params = [symbols[n] for n in names]
    defaults = [*potential.defaults.values(), *([1.0] if "kT" in names else [])]
    digest = potential_source_hash(potential.name, potentials.SOURCE)
    var = str(potential.variable)
    top = header(
        [
            f"Source: potential '{potential.name}' (derive/law/potentials.py, {potential.reference})",
            f"Source hash: {digest} (of derive/law/potentials.py, checked by fricgen.kernels.load_potential)",
            "Regenerate: fricgen generate",
        ]
    )
    doc = (
        f"Potential {potential.name} ({potential.reference}): energy U({var}, params) and force -dU/d{var};\n"
        "params in the order of PARAMETERS.\n"
    )
    constants = (
        f"\nNAME = {potential.name!r}\nSOURCE_HASH = {digest!r}\n"
        f"PARAMETERS = {tuple(names)!r}\nDEFAULTS = {tuple(float(v) for v in defaults)!r}\n"
    )
    functions = [
        _kernel("energy", f"{var}, params", potential.energy, equation(f"U({var})", potential.energy, "the potential energy"), params),
        _kernel("force", f"{var}, params", potential.force, equation(f"F({var}) = -dU/d{var}", potential.force, "the force"), params),
    ]
    if potential.name in EXTERNAL_POTENTIALS:
        functions.append(FIELD_KERNEL.format(decorator=_decorator("xs, params, out")).lstrip("\n"))
    return top + quote_doc(doc) + "\n" + "import math\n" + "import numba\n" + constants + "".join("\n\n" + f for f in functions)


def _special_hash() -> str:
    return hashlib.sha256(SPECIAL_SOURCE.read_text().encode()).hexdigest()


def special_module() -> str:
    return (
        header([f"Source: derive/backends/special_functions/special.py (hand-written numerics), hash {_special_hash()}"])
        + SPECIAL_SOURCE.read_text()
    )


def package_module(doc: str) -> str:
    """The text of an ``__init__.py`` of generated/: its docstring."""
    return header([]) + quote_doc(doc) + "\n"
