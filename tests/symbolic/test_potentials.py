"""Conservative interactions: forces by differentiation, equal to the papers' forms."""

import pytest
import sympy as sp

from fricgen.derive.law.potentials import EXTERNAL_POTENTIALS, PAIR_POTENTIALS, Potential, check_external, x
from fricgen.derive.law.symbols import kT, r


def test_sticky_force_is_b32():
    sticky = PAIR_POTENTIALS["sticky"]
    g, p, eps, sigma = (sticky.symbols[n] for n in ("gamma", "p", "eps", "sigma"))
    paper = -kT * g * p * (eps + sigma - r) ** (p - 1) / (eps ** (p + 1) / (p + 1) + g * (eps + sigma - r) ** p)
    force = sticky.force
    assert sp.simplify(force.args[0][0] - paper) == 0
    assert force.args[1][0] == 0
    # continuous at the outer edge for p > 1 (B-31)
    q = sp.Symbol("q", positive=True)
    assert sp.simplify(paper.subs(p, 1 + q).subs(r, sigma + eps)) == 0


def test_wca_energy_and_force_vanish_at_the_cutoff():
    wca = PAIR_POTENTIALS["wca"]
    at = {wca.symbols["epsilon"]: 1, wca.symbols["sigma"]: 1}
    cut = 2 ** sp.Rational(1, 6)
    inner_energy, inner_force = wca.energy.args[0][0].subs(at), wca.force.args[0][0].subs(at)
    assert sp.simplify(inner_energy.subs(r, cut)) == 0 and sp.simplify(inner_force.subs(r, cut)) == 0
    assert sp.simplify(inner_force - (48 / r**13 - 24 / r**7)) == 0


def test_cosine_force():
    cosine = EXTERNAL_POTENTIALS["cosine"]
    u0, lam = cosine.symbols["U0"], cosine.symbols["lambda"]
    assert sp.simplify(cosine.force - sp.pi * u0 / lam * sp.sin(2 * sp.pi * x / lam)) == 0


@pytest.mark.parametrize("name", EXTERNAL_POTENTIALS)
def test_external_potentials_are_periodic_with_amplitude_and_period_parameters(name):
    check_external(EXTERNAL_POTENTIALS[name])


def test_a_tilted_or_unparametrised_field_is_refused():
    cosine = EXTERNAL_POTENTIALS["cosine"]
    tilted = Potential("tilted", cosine.energy - x / 7, x, cosine.defaults)
    with pytest.raises(ValueError, match="not periodic"):
        check_external(tilted)
    fixed_period = Potential("fixed", cosine.energy.subs(cosine.symbols["lambda"], 1), x, {"U0": 6.0})
    with pytest.raises(ValueError, match="lambda"):
        check_external(fixed_period)


def test_ratchet_with_a_0_is_the_cosine_field_shifted_by_a_quarter_wavelength():
    ratchet, cosine = EXTERNAL_POTENTIALS["ratchet"], EXTERNAL_POTENTIALS["cosine"]
    u0, lam = cosine.symbols["U0"], cosine.symbols["lambda"]
    shifted = ratchet.energy.subs(ratchet.symbols["a"], 0).subs({ratchet.symbols["U0"]: u0, ratchet.symbols["lambda"]: lam})
    assert sp.simplify(shifted - cosine.energy.subs(x, x - lam / 4)) == 0
