"""The pair phase space: zero-current lemma, dissipation (F-9), covariance identities (F-50)."""

import pytest
import sympy as sp

from fricgen.derive.law.symbols import kT
from fricgen.derive.noise import phase_space
from fricgen.derive.noise.phase_space import (
    CALCULI_THETA,
    D_SYM,
    DD_SYM,
    F_SYM,
    U_SYM,
    covariance_identities,
    current_per_boltzmann,
    derivative_coefficient,
    friction_drift,
    pair_phase_space,
    tangential_velocity,
    zero_current_lemma,
)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_zero_current_lemma(dim, calculus):
    """The identity holds, and the nu kT it reads off the current is (1 - theta) mu kT (F-21), theta
    being the calculus' own (fricgen.derive.calculus): the two definitions of the calculus agree."""
    lemma = zero_current_lemma(dim, calculus)
    assert lemma.holds
    assert lemma.nu_over_mu == 1 - CALCULI_THETA[calculus]
    space = pair_phase_space(dim)
    assert sp.simplify(lemma.nu_kT(space.mobility) - (1 - CALCULI_THETA[calculus]) * space.mobility * kT) == 0


def test_nu_kT_is_read_off_the_current_not_assumed(monkeypatch):
    """A noise without its kT (sigma = sqrt(D) sigma_hat, P_B still at kT) has the D' coefficient mu,
    not mu kT: the lemma's X follows the current, X/(kT mu) is then no number and the lemma fails."""
    space = pair_phase_space(2)
    direction = space.contact_map.T * tangential_velocity(space)
    current = current_per_boltzmann(space, "ito")
    assert sp.simplify(derivative_coefficient(space, current, direction) - space.mobility * kT) == 0
    paper = phase_space.reduced_noise_matrix
    monkeypatch.setattr(phase_space, "reduced_noise_matrix", lambda s: paper(s) / sp.sqrt(kT))
    without_kT = current_per_boltzmann(space, "ito")
    assert sp.simplify(derivative_coefficient(space, without_kT, direction) - space.mobility) == 0
    assert not zero_current_lemma.__wrapped__(2, "ito").holds  # uncached: proven again with the wrong noise


@pytest.mark.parametrize("dim", [2, 3])
def test_lemma_is_falsifiable_with_the_wrong_nu(dim):
    """The Stratonovich current is not the Itô residual times the direction."""
    space = pair_phase_space(dim)
    current = current_per_boltzmann(space, "stratonovich")
    wrong = F_SYM - U_SYM * D_SYM + (1 - CALCULI_THETA["ito"]) * space.mobility * kT * DD_SYM
    direction = space.contact_map.T * tangential_velocity(space)
    assert any(space.reduce(U_SYM * j + g * wrong) != 0 for j, g in zip(current, direction))


@pytest.mark.parametrize("dim", [2, 3])
def test_friction_dissipates_f_times_u(dim):
    """dE/dt = v . drift = -f u (F-9), with u^2 = |u_perp|^2."""
    space = pair_phase_space(dim)
    power = space.velocities.dot(friction_drift(space, F_SYM / U_SYM))
    u_perp = tangential_velocity(space)
    assert space.reduce(power * U_SYM + F_SYM * u_perp.dot(u_perp)) == 0


@pytest.mark.parametrize("dim", [2, 3])
def test_contact_map_is_the_tangential_velocity(dim):
    space = pair_phase_space(dim)
    assert all(space.reduce(a - b) == 0 for a, b in zip(space.contact_map * space.velocities, tangential_velocity(space)))


def test_contact_mode_has_mobility_mu():
    """C W C^T = mu P: the variance of u_perp at equilibrium is mu kT per tangential direction."""
    space = pair_phase_space(3)
    inverse_mass = sp.diag(*[v / p for v, p in zip(space.velocities, space.momenta)])
    n = sp.Matrix(space.normal)
    target = space.mobility * (sp.eye(3) - n * n.T)
    assert all(space.reduce(a - b) == 0 for a, b in zip(space.contact_map * inverse_mass * space.contact_map.T, target))


@pytest.mark.parametrize("dim", [2, 3])
def test_noise_covariance_identities(dim):
    facts = covariance_identities(dim)
    assert facts and all(facts.values())
