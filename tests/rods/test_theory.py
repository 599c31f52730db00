"""Percus's exact hard-rod profile (B-20..23): limits, normalisation, convergence."""

import numpy as np
import pytest

from fricgen.rods_theory import hard_rod_profile, tonks


def cosine(amplitude=6.0):
    return lambda x: amplitude / 2 * np.cos(2 * np.pi * x)


@pytest.mark.parametrize("density", [0.4, 1.2, 1.8])
def test_uniform_limit_is_tonks(density):
    profile = hard_rod_profile(lambda x: 0 * x, 0.5, density)
    pressure, beta_mu = tonks(density, 0.5)
    np.testing.assert_allclose(profile.rho, density, rtol=1e-12)
    assert profile.beta_mu == pytest.approx(beta_mu, rel=1e-10)
    np.testing.assert_allclose(profile.contact, density * pressure, rtol=1e-10)  # contact theorem


@pytest.mark.parametrize(("sigma", "density"), [(0.5, 0.4), (0.5, 1.4), (0.2, 2.0)])
def test_profile_is_normalised_symmetric_and_converged(sigma, density):
    profile = hard_rod_profile(cosine(), sigma, density)
    assert profile.rho.mean() == pytest.approx(density, rel=1e-12)
    assert profile.eta.max() < 1 and profile.rho.min() > 0
    np.testing.assert_allclose(profile.rho[1:], profile.rho[1:][::-1], rtol=1e-4)  # U(x) = U(-x), up to O(h^2)
    finer = hard_rod_profile(cosine(), sigma, density, points=1200)
    assert np.max(np.abs(finer.rho[::2] - profile.rho)) < 1e-4 * profile.rho.max()


def test_dilute_limit_is_boltzmann():
    profile = hard_rod_profile(cosine(), 0.5, 1e-4)
    boltzmann = np.exp(-cosine()(profile.x))
    np.testing.assert_allclose(profile.rho / profile.rho.mean(), boltzmann / boltzmann.mean(), rtol=1e-3)


def test_beyond_close_packing_is_refused():
    with pytest.raises(ValueError, match="close packing"):
        hard_rod_profile(cosine(), 0.5, 2.0)
