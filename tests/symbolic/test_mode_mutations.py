"""Mutations of laws on the rolling and spinning modes are caught by ``verify``, as for sliding
(tests/symbolic/test_mutations.py): a wrong nu_m, a wrong theta, D x 1.01, another calculus' D.

The proof takes nu_m kT from the mode's own zero-current lemma on the pair phase space
(fricgen.derive.noise.mode_proofs), times the model's mobility mu_m: a D derived with another
nu_m solves the ODE written with that nu_m, but not with the lemma's.
"""

import dataclasses
from fractions import Fraction

import pytest
import sympy as sp

from fricgen.derive import derive_noise, verify
from fricgen.derive.calculus import Calculus
from fricgen.derive.noise import modes
from fricgen.derive.noise.derivation import NoiseModel

#: (catalogue law, mode): closed forms (with a branch point; a polynomial), the integral form. (The
#: linear law's D = gamma_f is the same in every calculus and for every nu: no mutation shows there.)
CASES = [("coulomb_newton", "rolling"), ("viscous_cubic", "spinning"), ("smooth_coulomb", "rolling")]


def physics(mode):
    return {"ode_residual", "zero_current_3d"} | ({"zero_current_2d"} if mode != "spinning" else set())


def failed(report):
    return {k for k, v in report.checks.items() if not v}


@pytest.fixture(scope="module")
def on_modes(laws):
    return {(name, mode): dataclasses.replace(laws[name], name=f"{name}_{mode}", mode=mode) for name, mode in CASES}


@pytest.mark.parametrize(("name", "mode"), CASES)
@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_amplitude_times_1_01_is_caught(on_modes, name, mode, calculus):
    law = on_modes[name, mode]
    if calculus not in law.calculi:
        pytest.skip(f"{name} leaves out {calculus}")
    model = derive_noise(law, calculus)
    assert verify(model).verified
    report = verify(dataclasses.replace(model, amplitude=sp.Rational(101, 100) * model.amplitude))
    assert not report.verified and physics(mode) <= failed(report), report.checks


@pytest.mark.parametrize(("name", "mode"), CASES[:2])
def test_a_D_derived_with_another_mobility_is_caught(on_modes, name, mode):
    """D derived with sliding's mu = 7 (equal solid spheres, m = 1, R = 1/2) but used with the mode's
    mu_m (5/4 for rolling and spinning): a wrong nu_m."""
    right = modes.mode_mobility(mode, 1, 1, 0.5, 0.5)
    assert right == sp.Rational(5, 4)
    assert verify(derive_noise(on_modes[name, mode], "ito", mobility=right)).verified
    wrong = dataclasses.replace(derive_noise(on_modes[name, mode], "ito", mobility=7), mobility=right)
    report = verify(wrong)
    assert not report.verified and physics(mode) <= failed(report), report.checks


@pytest.mark.parametrize(("name", "mode"), CASES)
def test_dropping_kT_from_nu_kT_is_caught(on_modes, monkeypatch, name, mode):
    monkeypatch.setattr(NoiseModel, "variance_scale", property(lambda self: self.nu))
    report = verify(derive_noise(on_modes[name, mode], "stratonovich"))
    assert not report.verified and physics(mode) <= failed(report), report.checks
    assert "kT" in report.details["ode_residual"]


@pytest.mark.parametrize(("name", "mode"), CASES)
def test_stratonovich_with_theta_0_is_caught(on_modes, monkeypatch, name, mode):
    theta = Calculus.theta
    monkeypatch.setattr(Calculus, "theta", property(lambda c: Fraction(0) if c is Calculus.STRATONOVICH else theta.fget(c)))
    model = derive_noise(on_modes[name, mode], "stratonovich")
    report = verify(model)
    assert not report.verified and physics(mode) <= failed(report), report.checks
    assert report.details["nu_kT"] == "kT*mu/2"  # read off the mode's current, not from theta


@pytest.mark.parametrize(("name", "mode"), CASES[:2])
@pytest.mark.parametrize(("derived", "labelled"), [("ito", "stratonovich"), ("stratonovich", "ito"), ("ito", "hk")])
def test_amplitude_of_another_calculus_is_caught(on_modes, name, mode, derived, labelled):
    model = dataclasses.replace(derive_noise(on_modes[name, mode], derived), calculus=Calculus(labelled))
    report = verify(model)
    assert not report.verified and physics(mode) <= failed(report), report.checks
