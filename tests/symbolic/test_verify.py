"""The verifier proves the catalogue and is proven able to fail."""

import dataclasses

import pytest
import sympy as sp

from fricgen.derive import derive_noise, verify
from fricgen.derive.law.symbols import kT, mu, u, w
from fricgen.derive.noise.derivation import Calculus, integral_amplitude

ALL_CHECKS = {
    "ode_residual",
    "zero_current_3d",
    "zero_current_2d",
    "noise_covariance",
    "contact_mode",
    "boundary_condition",
    "nonnegative_finite",
    "kernel_accuracy",
}


def test_every_catalogue_law_verifies_for_its_calculi(reports, laws):
    assert reports
    for key, report in reports.items():
        # every law, sliding or not, also proves its mode (C_m, mu_m; docs/physics-modes.md)
        assert set(report.checks) == ALL_CHECKS, key
        assert report.verified, (key, report.checks, report.details)


def test_reports_carry_the_lemmas_nu_kT_and_the_kernel_error(reports):
    expected = {"ito": kT * mu, "stratonovich": kT * mu / 2, "hk": 0}
    for (name, calculus), report in reports.items():
        assert sp.sympify(report.details["nu_kT"], locals={"kT": kT, "mu": mu}) == expected[calculus], name
        assert float(report.details["kernel_max_rel_error"]) < 1e-10, (name, calculus)
        assert "kernel_max_rel_error" in report.as_dict()["details"]


def test_coulomb_is_not_consistent_in_hk(laws):
    """Constant friction has f(0+) > 0: D = f/u diverges at u = 0, so the law excludes HK."""
    assert "hk" not in laws["coulomb"].calculi
    report = verify(derive_noise(laws["coulomb"], "hk"))
    assert not report.verified and not report.checks["nonnegative_finite"]
    assert report.checks["ode_residual"]


def _wrong(model, amplitude=None, calculus=None):
    return dataclasses.replace(
        model, amplitude=model.amplitude if amplitude is None else amplitude, calculus=model.calculus if calculus is None else calculus
    )


@pytest.mark.parametrize("name", ["coulomb", "coulomb_newton", "viscous_cubic", "smooth_coulomb", "stribeck"])
def test_ito_amplitude_with_stratonovich_current_fails(laws, name):
    model = _wrong(derive_noise(laws[name], "ito"), calculus=Calculus.STRATONOVICH)
    report = verify(model)
    assert not report.verified
    assert not report.checks["ode_residual"] and not report.checks["zero_current_3d"] and not report.checks["zero_current_2d"]


@pytest.mark.parametrize("name", ["coulomb", "coulomb_newton"])
def test_amplitude_without_nu_fails(laws, name):
    """D derived as if nu were 1 (the mobility dropped)."""
    model = derive_noise(laws[name], "ito")
    assert not verify(_wrong(model, model.amplitude.subs(mu, 1))).verified


def test_paper_f23_with_its_kT_fails(laws):
    model = derive_noise(laws["coulomb_newton"], "hk")
    report = verify(_wrong(model, kT * laws["coulomb_newton"].friction / u))
    assert not report.verified and not report.checks["ode_residual"]
    assert "kT" in report.details["ode_residual"]


@pytest.mark.parametrize("name", ["linear", "coulomb", "coulomb_newton", "smooth_coulomb"])
def test_sign_flip_fails(laws, name):
    model = derive_noise(laws[name], "ito")
    report = verify(_wrong(model, -model.amplitude))
    assert not report.verified and not report.checks["ode_residual"] and not report.checks["nonnegative_finite"]


def test_growing_homogeneous_solution_fails_the_boundary_condition(laws):
    model = derive_noise(laws["linear"], "ito")
    growing = model.amplitude + sp.exp(u**2 / (2 * model.variance_scale))
    report = verify(_wrong(model, growing))
    assert report.checks["ode_residual"] and not report.checks["boundary_condition"] and not report.verified


def test_jump_at_the_branch_point_fails(laws):
    model = derive_noise(laws["coulomb_newton"], "ito")
    (inner, c1), (outer, c2) = model.amplitude.args
    report = verify(_wrong(model, sp.Piecewise((inner + 1, c1), (outer, c2))))
    assert not report.checks["ode_residual"]


def test_integral_form_is_verified_by_differentiation_under_the_integral(laws):
    """The integral representation also holds for a law with a closed form."""
    model = derive_noise(laws["coulomb"], "stratonovich")
    model = dataclasses.replace(model, amplitude=integral_amplitude(model.law.friction, model.variance_scale), closed_form=False)
    assert verify(model).verified


def test_model_with_mobility_of_particle_properties(laws):
    """mu from properties (equal spheres, mu = 7) instead of the symbol."""
    model = derive_noise(laws["coulomb_newton"], "ito", mobility=7)
    assert not model.amplitude.has(mu) and model.amplitude.has(w)
    assert verify(model).verified
