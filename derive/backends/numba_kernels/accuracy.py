"""The Numba backend's check: the printed noise-amplitude kernel against mpmath.

derive never imports Numba or the runtime, so the kernel is checked as *code*: the module text
that :func:`.modules.law_module` prints for the model (as ``generate`` writes it) is executed as
plain Python, with ``numba.njit`` replaced by an identity decorator and ``erfcx`` taken from the
hand-written special functions (executed the same way). Its ``noise_amplitude_<calculus>`` is
compared with the independent reference values of :mod:`fricgen.derive.noise.reference` (this
checks the printer: the stable rewrites erfcx/expm1, constant folding, CSE, branches, the guard at
u = 0, and the Gauss–Legendre quadrature of the integral form). A law module with noise tables
(``tabulate_<calculus>``, fricgen.derive.backends.tables) is checked twice: with the parameters alone (the
quadrature) and with the tables that its ``tabulate_<calculus>`` builds for each case's kT and mu appended
(the tables, and the quadrature where they leave a zone to it). Pure Python raises where Numba's
error model returns inf/nan (an overflowing exp, a division by zero); such a point fails the check.
"""

from __future__ import annotations

import importlib
import math
import types

import mpmath

from ...noise.derivation import NoiseModel
from ...noise.reference import Point
from ..special_functions import Numba, execute, special_namespace
from .modules import law_module

#: Largest relative error of the printed kernel that the check accepts.
KERNEL_TOLERANCE = 1e-10


def python_kernels(model: NoiseModel) -> dict:
    """The namespace of the law module that :func:`.modules.law_module` prints for ``model`` (as generate writes
    it), run as plain Python."""

    special = types.ModuleType("special")
    special.__dict__.update(special_namespace())
    imports = {"math": math, "numba": Numba(), "..special": special}
    source = law_module(model.law, {model.calculus.value: model}, "", "fricgen.derive.driver")
    if "numpy" in source:  # generated code may use numpy (tests/test_layers.py); loaded only when it does
        imports["numpy"] = importlib.import_module("numpy")
    return execute(source, imports)


def kernel_accuracy(model: NoiseModel, points: list[Point]) -> tuple[float, str]:
    """Largest relative error of the printed ``noise_amplitude_<calculus>`` against the reference
    ``points``, and where it occurs (or what failed). Infinite when the kernel cannot be printed or
    run, returns a non-finite value, or a reference value is missing."""
    try:
        kernels = python_kernels(model)
        kernel = kernels[f"noise_amplitude_{model.calculus.value}"]
        tabulate = kernels.get(f"tabulate_{model.calculus.value}")
        tables = {} if tabulate is None else _tables(tabulate, points)
        plain_tables = {case: table[: len(points[0].arguments[-1])] for case, table in tables.items()}
    except Exception as error:  # noqa: BLE001 - any failure to print or run the code is a failed check
        return math.inf, f"the kernel could not be printed or run: {type(error).__name__}: {error}"
    worst, where = 0.0, ""
    for p in points:
        if p.exact is None:
            return math.inf, f"no reference value at {p.where}: {p.problem}"
        runs = [("", p.arguments)]
        if p.case in tables:  # params as an array (table_value reads its size), then with the tables
            runs = [("", (*p.arguments[:-1], plain_tables[p.case])), (" (noise table)", (*p.arguments[:-1], tables[p.case]))]
        for how, arguments in runs:
            try:
                got = kernel(p.speed, *arguments)
            except (ArithmeticError, ValueError, TypeError) as error:
                return math.inf, f"the kernel{how} raised at {p.where}: {type(error).__name__}: {error}"
            if not isinstance(got, int | float):
                return math.inf, f"the kernel{how} returned {got!r} at {p.where}"
            error = _relative(got, p.exact)
            if not error <= worst:
                worst, where = error, f"{p.where}: kernel{how} {got!r}, mpmath {mpmath.nstr(p.exact, 17)}"
    return worst, where


def _tables(tabulate, points: list[Point]) -> dict:
    """params with the noise tables appended that ``tabulate`` builds for each case of ``points`` (its mu and kT)."""
    numpy = importlib.import_module("numpy")
    tables = {}
    for p in points:
        if p.case not in tables and p.exact is not None:
            _, _, mobility, temperature, params = p.arguments
            tables[p.case] = tabulate(numpy.array([mobility]), temperature, numpy.array(params, dtype=float))
    return tables


def _relative(got: float, exact) -> float:
    if isinstance(exact, mpmath.mpc) or not mpmath.isfinite(exact) or not math.isfinite(got):
        return math.inf
    if exact == 0:
        return abs(got)
    return float(abs((mpmath.mpf(got) - exact) / exact))


__all__ = ["KERNEL_TOLERANCE", "kernel_accuracy", "python_kernels"]
