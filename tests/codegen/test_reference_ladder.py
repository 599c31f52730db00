"""Every generated kernel against its source expression evaluated independently at 50 digits.

Closed forms: rtol 1e-12 on random and edge points, u from 0 to 1e3 sqrt(kT nu), at and around
branch thresholds, weights from 1e-2 to 60 (the WCA force at r ~ 0.9). Integral forms: rtol 1e-8
against adaptive quadrature (mpmath.quad).
"""

import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from fricgen.derive.law.potentials import EXTERNAL_POTENTIALS, PAIR_POTENTIALS
from fricgen.derive.law.symbols import kT, mu, r, u, w
from fricgen.derive.noise.derivation import branches
from fricgen.derive.noise.reference import reference_amplitude

CASES = [(1.0, 7.0, 0.01), (1.0, 7.0, 1.0), (0.5, 2.3, 8.4), (1.0, 7.0, 60.0)]  # (kT, mu, w)
RNG = np.random.default_rng(20261122)


def speeds(scale, thresholds):
    edge = [0.0, 1e-300, 1e-12, 1e-6 * scale, scale, 1e3 * scale]
    near = [t * (1 + e) for t in thresholds for e in (-1e-9, 0.0, 1e-9) if t > 0]
    return edge + near + list(RNG.uniform(0, 5 * scale, 12)) + list(scale * 10 ** RNG.uniform(-6, 3, 12))


def reference(expr, values):
    """Evaluate a closed-form expression at 50 digits (limit u -> 0+ where undefined at 0).

    Values enter as exact rationals of their binary floats: a 15-digit Float folded into
    exp(u^2/2a) at u^2/2a ~ 5e5 would cost 1e-9 of relative accuracy.
    """
    expr = expr.subs({k: sp.Rational(v) for k, v in values.items()})
    f = sp.lambdify(u, expr, modules="mpmath")

    def at(x):
        with mpmath.workdps(50):
            value = f(mpmath.mpf(x)) if x > 0 else None
            if value is None or not mpmath.isfinite(value):
                first = branches(expr)[0].expr if branches(expr) else expr
                value = sp.limit(first, u, 0, "+")
                value = float(value) if value.is_finite else 0.0
            return float(value)

    return at


def thresholds(model_expr, values):
    pieces = branches(model_expr.subs({k: sp.Rational(v) for k, v in values.items()})) or []
    return [float(p.lower) for p in pieces if p.lower != 0]


@pytest.mark.parametrize("case", CASES)
def test_noise_kernels_match_their_expressions(models, kernels, case):
    temperature, mobility, weight = case
    for (name, calculus), model in models.items():
        k = kernels[name]
        params = k.parameters()
        values = {**model.law.defaults, kT: temperature, mu: mobility, w: weight, r: 1.0}
        scale = math.sqrt(temperature * mobility)
        kernel = k.noise_amplitude(calculus)
        points = speeds(scale, thresholds(model.amplitude, values) + thresholds(model.law.friction, values))
        exact = reference(model.amplitude, values) if model.closed_form else reference_amplitude(model, model.variance_scale, values)
        rtol = 1e-12 if model.closed_form else 1e-8
        for x in points:
            got = kernel(x, weight, 1.0, mobility, temperature, params)
            want = float(exact(x)) if model.closed_form or x > 0 else float(exact(0.0))
            assert math.isfinite(got) and got >= 0, (name, calculus, x, got)
            assert got == pytest.approx(want, rel=rtol, abs=1e-300), (name, calculus, case, x)
            root = k.noise_sqrt(calculus)(x, weight, 1.0, mobility, temperature, params)
            assert root == pytest.approx(math.sqrt(want), rel=rtol)


def test_friction_kernels_match_their_expressions(laws, kernels):
    for name, law in laws.items():
        k = kernels[name]
        params = k.parameters()
        for weight in (0.01, 1.0, 60.0):
            values = {**law.defaults, w: weight, r: 1.0}
            f_exact = reference(law.friction, values)
            ratio_exact = reference(sp.piecewise_fold((law.friction / u).rewrite(sp.Piecewise)), values)
            slope = sp.simplify(sp.diff(sp.piecewise_fold(law.friction.rewrite(sp.Piecewise)), u))  # 1/cosh^2, not 1 - tanh^2
            slope_exact = reference(slope, values)
            kinks = thresholds(law.friction, values)
            for x in speeds(1.0, kinks):
                assert k.friction(x, weight, 1.0, params) == pytest.approx(f_exact(x), rel=1e-12, abs=1e-300)
                assert x in kinks or k.friction_slope(x, weight, 1.0, params) == pytest.approx(slope_exact(x), rel=1e-12, abs=1e-300)
                over = k.friction_over_u(x, weight, 1.0, params)
                assert math.isfinite(over)
                if x > 0:
                    assert over == pytest.approx(ratio_exact(x), rel=1e-12)
                elif law.friction.subs(values).subs(u, 0) != 0:
                    assert over == 0.0  # static friction at u = 0: no direction, no force


def test_weight_kernels_match_the_wca_force(laws, kernels):
    for name, law in laws.items():
        k = kernels[name]
        exact = sp.lambdify(r, law.weight.subs(law.defaults), modules="mpmath")
        for distance in [0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.12, 2 ** (1 / 6), 1.2, 3.0]:
            # absolute 1e-12: 48/r^13 - 24/r^7 cancels to 0 at the cutoff
            assert k.weight(distance, k.parameters()) == pytest.approx(float(exact(distance)), rel=1e-12, abs=1e-12)


@pytest.mark.parametrize("potential", [*PAIR_POTENTIALS.values(), *EXTERNAL_POTENTIALS.values()], ids=lambda p: p.name)
def test_potential_kernels_match_their_expressions(potential):
    import importlib

    module = importlib.import_module(f"fricgen.generated.potentials.{potential.name}")
    params = np.array(module.DEFAULTS)
    values = {potential.symbols[n]: v for n, v in potential.defaults.items()} | {kT: 1.0}
    energy = sp.lambdify(potential.variable, potential.energy.subs(values), modules="mpmath")
    force = sp.lambdify(potential.variable, potential.force.subs(values), modules="mpmath")
    lo = 1.0 if potential.name == "sticky" else (0.85 if potential.name == "wca" else -2.0)
    for x in np.linspace(lo, lo + 1.3, 97):
        assert module.energy(x, params) == pytest.approx(float(energy(x)), rel=1e-12, abs=1e-12)
        assert module.force(x, params) == pytest.approx(float(force(x)), rel=1e-12, abs=1e-11)
    if potential.name in EXTERNAL_POTENTIALS:  # the field kernel is the scalar one, bit for bit
        xs = np.concatenate([np.linspace(-3.0, 3.0, 61), [0.0, 1e-300, 1e4 + 0.3]])
        out = np.full(xs.size, np.nan)
        module.force_field(xs, params, out)
        assert np.array_equal(out, [module.force(x, params) for x in xs])
