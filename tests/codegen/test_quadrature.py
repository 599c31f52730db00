"""Laws without closed form: the kernel's quadrature of (F-22) and its zero-current residual."""

import math

import numpy as np
import pytest

from fricgen.derive.law.symbols import kT, mu, r, w
from fricgen.derive.noise.reference import reference_amplitude


def integral_models(models):
    found = {key: m for key, m in models.items() if not m.closed_form}
    assert found, "the catalogue must hold a law without a closed-form D"
    return found


@pytest.mark.parametrize("temperature,mobility,weight", [(1.0, 7.0, 1.0), (0.3, 2.0, 60.0), (2.0, 7.0, 0.01)])
def test_quadrature_relative_error_below_1e_10_over_the_whole_u_range(models, kernels, temperature, mobility, weight):
    for (name, calculus), model in integral_models(models).items():
        kernel, params = kernels[name].noise_amplitude(calculus), kernels[name].parameters()
        exact = reference_amplitude(model, model.variance_scale, {**model.law.defaults, kT: temperature, mu: mobility, w: weight, r: 1.0})
        scale = math.sqrt(temperature * mobility)
        for x in np.concatenate([[0.0], scale * np.geomspace(1e-8, 1e3, 40)]):
            got = kernel(x, weight, 1.0, mobility, temperature, params)
            assert got == pytest.approx(float(exact(x)), rel=1e-10), (name, calculus, x)


def test_zero_current_residual_of_the_numerical_amplitude(models, kernels):
    """|nu kT D' - u D + f| / f with D' by central differences: small, printed for the record."""
    worst = 0.0
    for (name, calculus), model in integral_models(models).items():
        k = kernels[name]
        params, kernel = k.parameters(), k.noise_amplitude(calculus)
        a = float(model.variance_scale.subs({kT: 1.0, mu: 7.0}))
        for x in np.sqrt(a) * np.geomspace(1e-3, 30, 40):
            h = 1e-5 * max(x, np.sqrt(a) * 1e-2)
            slope = (kernel(x + h, 1.0, 1.0, 7.0, 1.0, params) - kernel(x - h, 1.0, 1.0, 7.0, 1.0, params)) / (2 * h)
            f = k.friction(x, 1.0, 1.0, params)
            residual = abs(a * slope - x * kernel(x, 1.0, 1.0, 7.0, 1.0, params) + f) / f
            worst = max(worst, residual)
    print(f"worst relative zero-current residual of the quadrature D: {worst:.2e}")
    assert worst < 1e-6
