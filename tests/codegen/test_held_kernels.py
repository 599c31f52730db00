"""The LAMMPS fix's kernels in u with their parts free of u held per pair (held_code).

- lift: putting each held part back gives the printed kernel's expression, for every catalogue law's
  f/u, df/du and closed-form D, at random points on both sides of every branch; what stays is maximal (no
  part free of u is left in it but bare symbols and numbers).
- The fix's text: Coulomb-Newton's D evaluates erfcx once per pair for its stick branch (in hold), not at
  every speed; the kernels the fix calls take the held parts.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
import sympy as sp

from fricgen.derive.backends.lammps_plugin.code import amplitude_formula, ratio_formula, slope_formula
from fricgen.derive.backends.lammps_plugin.held_code import fix_kernels, free_of_u, lift
from fricgen.derive.backends.printing import fold_constants, stabilize


def formulas(laws, models):
    for name, law in laws.items():
        yield name, ratio_formula(law)
        yield name, slope_formula(law)
        for c in law.calculi:
            if models[name, c].closed_form:
                yield name, amplitude_formula(models[name, c])


def test_lift_gives_back_the_kernel_and_holds_every_part_free_of_u(laws, models):
    rng = np.random.default_rng(7)
    checked = 0
    for name, formula in formulas(laws, models):
        expr = fold_constants(stabilize(formula.expr))
        held: dict[sp.Expr, sp.Symbol] = {}
        moving = lift(expr, held)
        assert all(free_of_u(part) for part in held), (name, formula.name)
        leftover = [e for e in sp.preorder_traversal(moving) if isinstance(e, sp.Expr) and not e.is_Atom and free_of_u(e)]
        assert not leftover, (name, formula.name, leftover[:3])  # maximal: nothing free of u left unheld
        back = moving.xreplace({symbol: part for part, symbol in held.items()})
        symbols = sorted(expr.free_symbols | back.free_symbols, key=lambda x: x.name)
        plain, restored = (sp.lambdify(symbols, e, modules=["scipy", "numpy"]) for e in (expr, back))
        for u in (0.05, 0.5, 2.0, 9.0):  # both sides of a stick-slip threshold kappa_f w / gamma_f ~ 1
            values = {x.name: rng.uniform(0.5, 2.0) for x in symbols} | {"u": u}
            args = [values[x.name] for x in symbols]
            assert restored(*args) == pytest.approx(plain(*args), rel=1e-12, abs=1e-300), (name, formula.name, u)
        checked += 1
    assert checked >= 3 * len(laws)


def test_coulomb_newton_holds_its_stick_erfcx(laws, models):
    law = laws["coulomb_newton"]
    text, functions = fix_kernels(law, {c: models["coulomb_newton", c] for c in law.calculi}, 8)
    ito = re.search(r"inline double noise_amplitude_ito\(double u.*?\n}\n", text, re.S).group(0)
    hold = re.search(r"inline void hold_noise_amplitude_ito\(.*?\n}\n", text, re.S).group(0)
    assert ito.count("fricgen_erfcx(") == 1 and "held[" in ito  # the slip branch's erfcx(u ...) only
    assert hold.count("fricgen_erfcx(") == 1 and "std::sqrt" in hold
    assert "const double *held)" in re.search(r"inline double friction_over_u\(.*?\)", text).group(0)
    assert "noise_amplitude_ito(u, w, r, mu, kT, params, held + AMPLITUDE_AT)" in functions
