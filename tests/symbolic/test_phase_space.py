"""The paper's sliding mode on the pair phase space, proven by the one proof path of every mode: the
zero-current lemma in 3-D (the other modes and 2-D: test_modes.py), nu kT read off the current."""

import dataclasses

import pytest
import sympy as sp

from fricgen.derive.calculus import Calculus
from fricgen.derive.law.symbols import kT
from fricgen.derive.noise import mode_proofs, modes
from fricgen.derive.noise.mode_proofs import current, derivative_coefficient, placeholders, reduce_unit
from fricgen.derive.noise.phase_space import pair_phase_space


def one_minus_theta(calculus):
    value = 1 - Calculus(calculus).theta
    return sp.Rational(value.numerator, value.denominator)


@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_zero_current_lemma_of_sliding_in_3d(calculus):
    """The identity holds, and the nu kT it reads off the current is (1 - theta) mu kT with mu the
    paper's (F-21), theta being the calculus' own (fricgen.derive.calculus): the two definitions of
    the calculus agree."""
    lemma = mode_proofs.zero_current("sliding", 3, calculus)
    assert lemma.holds and lemma.nu_over_mu == one_minus_theta(calculus)
    space = pair_phase_space(3)
    m_i, m_k, inertia_i, inertia_k = space.masses
    radius_i, radius_k = space.radii
    paper = 1 / m_i + 1 / m_k + radius_i**2 / inertia_i + radius_k**2 / inertia_k
    assert sp.simplify(lemma.nu_kT(modes.describe("sliding", 3).mobility) - one_minus_theta(calculus) * paper * kT) == 0


def test_nu_kT_is_read_off_the_current_not_assumed(monkeypatch):
    """A noise without its kT (sigma = sqrt(D) sigma_hat, P_B still at kT) has the D' coefficient mu,
    not mu kT: the lemma's X follows the current, X/(kT mu) is then no number and the lemma fails."""
    space, held, sliding = pair_phase_space(2), placeholders("sliding"), modes.describe("sliding", 2)
    direction = sliding.contact_map.T * sliding.velocity
    assert sp.simplify(derivative_coefficient(space, current(space, ("sliding",), "ito"), direction, held) - sliding.mobility * kT) == 0
    without_kT = dataclasses.replace(sliding, noises=(sliding.noise_matrix / sp.sqrt(kT),))
    monkeypatch.setattr(mode_proofs, "describe", lambda *a: without_kT)
    flux = current(space, ("sliding",), "ito")
    assert sp.simplify(derivative_coefficient(space, flux, direction, held) - sliding.mobility) == 0
    assert not mode_proofs.zero_current.__wrapped__("sliding", 2, "ito").holds  # uncached: proven again with the wrong noise


@pytest.mark.parametrize("dim", [2, 3])
def test_lemma_is_falsifiable_with_the_wrong_nu(dim):
    """The Stratonovich current is not the Itô residual times the direction."""
    space, held, sliding = pair_phase_space(dim), placeholders("sliding"), modes.describe("sliding", dim)
    flux = current(space, ("sliding",), "stratonovich")
    wrong = held.residual + sliding.mobility * kT * held.slope
    direction = sliding.contact_map.T * sliding.velocity
    assert any(reduce_unit(space, held.speed * j + g * wrong) != 0 for j, g in zip(flux, direction))
