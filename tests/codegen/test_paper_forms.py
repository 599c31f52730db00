"""Generated kernels against independent scipy implementations of (F-29), (F-31), (F-33)."""

import numpy as np
import pytest
from scipy.special import erfcx

MU, KT = 7.0, 1.0


def d_linear(u, w, gamma):
    return w * gamma + 0 * u


def d_constant(u, w, kappa, a):
    return w * kappa * np.sqrt(np.pi / (2 * a)) * erfcx(u / np.sqrt(2 * a))


def d_coulomb_newton(u, w, gamma, kappa, a):
    c = w * kappa / gamma
    d = d_constant(u, w, kappa, a)
    x = (u[u < c] ** 2 - c**2) / (2 * a)
    d[u < c] = -gamma * np.expm1(x) + w * kappa * np.sqrt(np.pi / (2 * a)) * np.exp(x) * erfcx(c / np.sqrt(2 * a))
    return d


U = np.concatenate([[0.0], np.geomspace(1e-8, 3e3, 200), np.linspace(0, 60, 301)])


@pytest.mark.parametrize("calculus,theta", [("ito", 0.0), ("stratonovich", 0.5)])
@pytest.mark.parametrize("w", [0.05, 1.0, 8.4, 60.0])
def test_closed_forms_against_scipy(kernels, calculus, theta, w):
    a = KT * (1 - theta) * MU
    lin, con, cn = kernels["linear"], kernels["coulomb"], kernels["coulomb_newton"]
    gamma_l = lin.parameters()[0]
    kappa_c = con.parameters()[0]
    gamma_cn, kappa_cn = cn.parameters()[:2]
    checks = [
        (lin.noise_amplitude(calculus), lin.parameters(), d_linear(U, w, gamma_l)),
        (con.noise_amplitude(calculus), con.parameters(), d_constant(U, w, kappa_c, a)),
        (cn.noise_amplitude(calculus), cn.parameters(), d_coulomb_newton(U, w, gamma_cn, kappa_cn, a)),
    ]
    for kernel, params, expected in checks:
        got = np.array([kernel(x, w, 1.0, MU, KT, params) for x in U])
        np.testing.assert_allclose(got, expected, rtol=1e-12)
