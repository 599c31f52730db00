"""Exact rod profiles (transfer operator) against Percus's functional (B-20), the sticky functional
(B-34), the contact formula (B-23) and the uniform equations of state (Tonks, Baxter)."""

import numpy as np
import pytest

from fricgen.rods import Neighbours, percus_residual, rod_profile, sticky_residual, sticky_rods, tonks


def cosine(amplitude=6.0):
    return lambda x: amplitude / 2 * np.cos(2 * np.pi * x)


def flat(x):
    return 0 * x


@pytest.mark.parametrize("density", [0.4, 1.2, 1.8])
def test_uniform_hard_rods_are_tonks(density):
    profile = rod_profile(flat, 0.5, density)
    pressure, beta_mu = tonks(density, 0.5)
    np.testing.assert_allclose(profile.rho, density, rtol=1e-12)
    assert profile.beta_pressure == pytest.approx(pressure, rel=1e-10)  # exp(-beta P r) is integrated exactly
    assert profile.beta_mu == pytest.approx(beta_mu, rel=1e-10)
    np.testing.assert_allclose(profile.contact, density * pressure, rtol=1e-10)  # contact theorem


@pytest.mark.parametrize("gamma", [0.3, 1.0, 3.0])
def test_uniform_sticky_rods_are_baxter(gamma):
    profile = rod_profile(flat, 0.5, 1.0, neighbours=Neighbours(gamma))
    pressure, beta_mu = sticky_rods(1.0, 0.5, gamma)
    assert profile.beta_pressure == pytest.approx(pressure, rel=1e-10)
    assert profile.beta_mu == pytest.approx(beta_mu, abs=1e-10)
    assert sticky_rods(1.0, 0.5, 0.0) == pytest.approx(tonks(1.0, 0.5))


def soft_shell(r, sigma=0.5, reach=0.1, height=2.0):
    """A continuous repulsive shell V = height (1 - (r - sigma) / reach)^2 on [sigma, sigma + reach)."""
    return np.where(r < sigma + reach, height * (1 - (r - sigma) / reach) ** 2, 0.0)


@pytest.mark.parametrize("density", [0.4, 1.2])
def test_uniform_rods_with_a_pair_potential_follow_the_nearest_neighbour_equation_of_state(density):
    """Takahashi's exact equation of state of a nearest-neighbour fluid: 1 / rho_bar = <r> with
    weight exp(-beta P r - beta V(r)) on r >= sigma, solved for beta P by quadrature."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    def mean_spacing(beta_p):
        weight = [quad(lambda r, k=k: r**k * np.exp(-beta_p * r - soft_shell(r)), 0.5, 0.6, epsabs=0)[0] for k in (0, 1)]
        tail = [np.exp(-0.6 * beta_p) / beta_p, np.exp(-0.6 * beta_p) * (0.6 / beta_p + 1 / beta_p**2)]
        return (weight[1] + tail[1]) / (weight[0] + tail[0])

    pressure = brentq(lambda b: mean_spacing(b) - 1 / density, 1e-3, 1e3, xtol=1e-14)
    profile = rod_profile(flat, 0.5, density, neighbours=Neighbours(pair=soft_shell, pair_range=0.1))
    np.testing.assert_allclose(profile.rho, density, rtol=1e-10)
    assert profile.beta_pressure == pytest.approx(pressure, rel=1e-6)  # V interpolated between grid points
    assert abs(rod_profile(flat, 0.5, density).beta_pressure / pressure - 1) > 0.01  # the shell matters (2 % at 0.4)


def test_the_sticky_representation_as_a_pair_potential_is_the_sticky_profile():
    gamma, eps, p = 1.0, 0.05, 3.0

    def sticky(r):
        return -np.log1p(gamma * (p + 1) / eps ** (p + 1) * (eps - (r - 0.5)) ** p)

    direct = rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(gamma, eps, p))
    as_pair = rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(pair=sticky, pair_range=eps))
    np.testing.assert_allclose(as_pair.rho, direct.rho, rtol=1e-9)
    np.testing.assert_allclose(as_pair.contact, direct.contact, rtol=1e-9)


@pytest.mark.parametrize(("sigma", "density"), [(0.5, 0.4), (0.5, 1.4), (0.2, 2.0)])
def test_hard_rods_solve_percus_functional_and_contact_formula(sigma, density):
    """The residual of (B-20b) and the deviation from (B-23) vanish as h^2 under grid refinement."""
    coarse, fine = (rod_profile(cosine(), sigma, density, points=m) for m in (600, 1200))
    assert coarse.rho.mean() == pytest.approx(density, rel=1e-12) and coarse.eta.max() < 1
    np.testing.assert_allclose(coarse.rho[1:], coarse.rho[1:][::-1], rtol=1e-9)  # U(x) = U(-x)
    residuals = [np.abs(percus_residual(p, cosine(), sigma)).max() for p in (coarse, fine)]
    assert residuals[1] < 2e-4 and residuals[0] / residuals[1] > 3.5, residuals
    for profile in (coarse, fine):
        s = round(sigma * profile.x.size)
        b23 = profile.rho * np.roll(profile.rho, -s) / (1 - np.roll(profile.eta, -s))
        assert np.max(np.abs(profile.contact - b23)) < 3e-4 * b23.max()
    assert np.max(np.abs(fine.rho[::2] - coarse.rho)) < 1e-4 * coarse.rho.max()


@pytest.mark.parametrize("gamma", [0.5, 2.0])
def test_baxter_rods_solve_the_sticky_functional(gamma):
    """(B-34) as printed is stationary at the exact profile (to O(h^2)); the hard-rod profile is not."""
    coarse, fine = (rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(gamma), points=m) for m in (600, 1200))
    residuals = [np.abs(sticky_residual(p, cosine(), 0.5, gamma)).max() for p in (coarse, fine)]
    assert residuals[1] < 1e-5 and residuals[0] / residuals[1] > 3.5, residuals
    hard = rod_profile(cosine(), 0.5, 1.0)
    assert np.abs(sticky_residual(hard, cosine(), 0.5, gamma)).max() > 0.05


def test_sticky_representation_converges_to_baxter_linearly_in_eps():
    """The delta_eps model (B-31) that BCD simulates differs from Baxter's limit by O(eps)."""
    baxter = rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0))
    errors = [np.abs(rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0, e)).rho - baxter.rho).mean() for e in (0.05, 0.01, 0.005)]
    assert 0.002 < errors[0] < 0.02 and 1.7 < errors[1] / errors[2] < 2.2, errors
    finer = rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0, 0.01), points=1200)  # the delta_eps peak is resolved
    assert np.abs(finer.rho[::2] - rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0, 0.01)).rho).max() < 1e-4


def test_dilute_limit_is_boltzmann():
    profile = rod_profile(cosine(), 0.5, 1e-4)
    boltzmann = np.exp(-cosine()(profile.x))
    np.testing.assert_allclose(profile.rho / profile.rho.mean(), boltzmann / boltzmann.mean(), rtol=1e-3)


def test_ring_correction_is_order_one_over_length():
    """rho_N - rho = -chi / (2L) d^2 rho / d rho_bar^2: zero without a field, ~1/L otherwise."""
    infinite = rod_profile(cosine(), 0.5, 1.4)
    shifts = [np.abs(rod_profile(cosine(), 0.5, 1.4, ring_length=length).rho - infinite.rho).max() for length in (50.0, 100.0)]
    assert shifts[0] == pytest.approx(2 * shifts[1], rel=1e-3) and 1e-5 < shifts[1] < 1e-2
    uniform = rod_profile(flat, 0.5, 1.4, ring_length=10.0)
    np.testing.assert_allclose(uniform.rho, 1.4, rtol=1e-6)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="close packing"):
        rod_profile(cosine(), 0.5, 2.0)
    with pytest.raises(ValueError, match="whole number of grid steps"):
        rod_profile(cosine(), 0.5004, 1.0)
    with pytest.raises(ValueError, match="eps"):
        rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0, 0.6))
    with pytest.raises(ValueError, match="not both"):
        rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(1.0, pair=soft_shell, pair_range=0.1))
    with pytest.raises(ValueError, match="0 < a < sigma"):
        rod_profile(cosine(), 0.5, 1.0, neighbours=Neighbours(pair=soft_shell, pair_range=0.5))
