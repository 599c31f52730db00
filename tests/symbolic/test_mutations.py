"""Mutations of the derivation and of the printed kernels are caught by ``verify`` (and so refused by
``generate``): each names the check that fails.

The noise model's own nu kT (NoiseModel.variance_scale) cannot vouch for itself: a D derived with a
wrong nu kT solves the ODE written with that same wrong nu kT. The verifier therefore takes nu kT
from the zero-current lemma on the pair phase space (fricgen.derive.noise.mode_proofs), and the blind spot that
it closes is shown here first. Mutations are made by monkeypatching or dataclasses.replace, never by
editing a source file.
"""

import dataclasses
from fractions import Fraction

import pytest
import sympy as sp

from fricgen.derive import contact_mobility, derive_noise, driver, verify
from fricgen.derive.backends import special_functions
from fricgen.derive.backends.numba_kernels import modules
from fricgen.derive.calculus import Calculus
from fricgen.derive.noise.derivation import NoiseModel
from fricgen.derive.noise.modes import describe
from fricgen.derive.noise.phase_space import pair_phase_space
from fricgen.derive.noise.verification import lemma_scale, ode_residuals

CLOSED = ["coulomb", "coulomb_newton", "viscous_cubic"]
INTEGRAL = ["smooth_coulomb"]
PHYSICS = {"ode_residual", "zero_current_3d", "zero_current_2d"}


def failed(report):
    return {k for k, v in report.checks.items() if not v}


def solves(model, a):
    """The model's D solves a D' - u D + f = 0 on every branch (and is continuous)."""
    return all(sp.simplify(sp.expand(sp.powsimp(sp.expand(x)))) == 0 for x in ode_residuals(model, a))


@pytest.fixture
def kT_dropped(monkeypatch):
    """noise.py with nu in place of nu kT: every D is derived at kT = 1."""
    monkeypatch.setattr(NoiseModel, "variance_scale", property(lambda self: self.nu))


@pytest.fixture
def stratonovich_at_theta_0(monkeypatch):
    """fricgen.derive.calculus with theta = 0 for Stratonovich: its D becomes the Itô one."""
    theta = Calculus.theta
    monkeypatch.setattr(Calculus, "theta", property(lambda c: Fraction(0) if c is Calculus.STRATONOVICH else theta.fget(c)))


@pytest.mark.parametrize("name", [*CLOSED, *INTEGRAL])
@pytest.mark.parametrize("calculus", ["ito", "stratonovich"])
def test_dropping_kT_from_nu_kT_is_caught(laws, kT_dropped, name, calculus):
    model = derive_noise(laws[name], calculus)
    assert not model.variance_scale.has(sp.Symbol("kT", positive=True))
    # the blind spot: the model's D solves the ODE written with its own (wrong) nu kT ...
    assert solves(model, model.variance_scale)
    # ... but not with the nu kT of the zero-current lemma
    report = verify(model)
    assert not report.verified
    assert PHYSICS <= failed(report), report.checks
    assert "kT" in report.details["ode_residual"]
    if name in INTEGRAL:  # the quadrature kernel uses the model's a = nu kT: its numbers are wrong at kT != 1
        assert "kernel_accuracy" in failed(report)


def test_generate_refuses_the_kT_mutation(laws, kT_dropped):
    with pytest.raises(driver.GenerationError, match="ode_residual"):
        driver.verified_models(laws["coulomb_newton"])


@pytest.mark.parametrize("name", ["coulomb", "coulomb_newton", "smooth_coulomb"])
def test_stratonovich_with_theta_0_is_caught(laws, stratonovich_at_theta_0, name):
    model = derive_noise(laws[name], "stratonovich")
    assert model.variance_scale == derive_noise(laws[name], "ito").variance_scale  # the mutation took effect
    assert solves(model, model.variance_scale)  # the blind spot
    report = verify(model)
    assert not report.verified and PHYSICS <= failed(report), report.checks
    assert report.details["nu_kT"] == "kT*mu/2"  # from the phase space, not from theta


@pytest.mark.parametrize("name", ["coulomb", "coulomb_newton", "viscous_cubic", "smooth_coulomb"])
@pytest.mark.parametrize(("derived", "labelled"), [("ito", "stratonovich"), ("stratonovich", "ito")])
def test_amplitude_of_another_calculus_is_caught(laws, name, derived, labelled):
    model = dataclasses.replace(derive_noise(laws[name], derived), calculus=Calculus(labelled))
    report = verify(model)
    assert not report.verified and PHYSICS <= failed(report), report.checks


@pytest.mark.parametrize("name", ["linear", *CLOSED])
@pytest.mark.parametrize("calculus", ["ito", "stratonovich", "hk"])
def test_amplitude_times_1_01_is_caught(laws, name, calculus):
    model = derive_noise(laws[name], calculus)
    report = verify(dataclasses.replace(model, amplitude=sp.Rational(101, 100) * model.amplitude))
    assert not report.verified and PHYSICS <= failed(report), report.checks


@pytest.mark.parametrize("calculus", ["ito", "stratonovich"])
def test_integral_times_1_01_is_caught(laws, calculus):
    model = derive_noise(laws["smooth_coulomb"], calculus)
    assert not model.closed_form
    report = verify(dataclasses.replace(model, amplitude=sp.Rational(101, 100) * model.amplitude))
    assert not report.verified and PHYSICS <= failed(report), report.checks


def test_integral_with_the_ito_exponent_labelled_stratonovich_is_caught(laws):
    """The integral (F-22) with a = kT mu under the Stratonovich label: not the decaying solution of
    the Stratonovich ODE. (Its kernel is printed with the label's a, so it is right by accident.)"""
    ito = derive_noise(laws["smooth_coulomb"], "ito")
    report = verify(dataclasses.replace(ito, calculus=Calculus.STRATONOVICH))
    assert PHYSICS | {"boundary_condition"} <= failed(report), report.checks


def test_mobility_of_noise_py_is_the_sliding_modes_mobility():
    """contact_mobility (derivation.py) and the sliding mode on the pair phase space (modes.py) agree on mu."""
    space = pair_phase_space(3)
    m_i, m_k, inertia_i, inertia_k = space.masses
    radius_i, radius_k = space.radii
    mobility = describe("sliding", 3).mobility
    assert sp.simplify(contact_mobility(m_i, m_k, radius_i, radius_k, inertia_i, inertia_k) - mobility) == 0


def test_lemma_scale_follows_the_models_mobility(laws):
    model = derive_noise(laws["coulomb_newton"], "stratonovich", mobility=7)
    assert lemma_scale(model) == sp.Rational(7, 2) * sp.Symbol("kT", positive=True)


# --- the printed kernels -------------------------------------------------------------------------


def test_a_printer_error_is_caught_by_kernel_accuracy_alone(laws, monkeypatch):
    """The symbolic D is right, the printed code 1e-6 off: only the kernel check can see it."""
    stabilize = modules.stabilize
    monkeypatch.setattr(modules, "stabilize", lambda expr: stabilize(expr) * sp.Rational(1000001, 1000000))
    report = verify(derive_noise(laws["coulomb_newton"], "ito"))
    assert failed(report) == {"kernel_accuracy"}, report.checks
    assert float(report.details["kernel_max_rel_error"]) == pytest.approx(1e-6, rel=1e-3)


def test_a_coarse_quadrature_is_caught_by_kernel_accuracy(laws, monkeypatch):
    monkeypatch.setattr(modules, "QUADRATURE_ORDER", 3)
    report = verify(derive_noise(laws["smooth_coulomb"], "stratonovich"))
    assert failed(report) == {"kernel_accuracy"}, report.checks
    assert float(report.details["kernel_max_rel_error"]) > 1e-8


def test_a_coarse_noise_table_is_caught_by_kernel_accuracy(laws, monkeypatch):
    """Tables whose pieces need only 1e-2 (their two highest Chebyshev coefficients and their checks against the
    quadrature): the polynomials stay good to about 1e-9, which the reference values at speeds off the pieces' ends catch."""
    monkeypatch.setattr(modules, "TABLE_TOLERANCE", 1e-2)
    report = verify(derive_noise(laws["smooth_coulomb"], "stratonovich"))
    assert failed(report) == {"kernel_accuracy"}, report.checks
    assert "(noise table)" in report.details["kernel_accuracy"]
    assert float(report.details["kernel_max_rel_error"]) > 1e-10


def test_a_wrong_erfcx_is_caught_by_kernel_accuracy(laws, monkeypatch, tmp_path):
    """The convergent of generated/special.py's erfcx cut to its lowest 3 powers of x^2: wrong for large u."""
    source = special_functions.SPECIAL_SOURCE.read_text()
    assert "y, top = x * x, len(_NUMERATOR) - 1" in source
    broken = tmp_path / "special.py"
    broken.write_text(source.replace("y, top = x * x, len(_NUMERATOR) - 1", "y, top = x * x, 2"))
    monkeypatch.setattr(special_functions, "SPECIAL_SOURCE", broken)
    report = verify(derive_noise(laws["coulomb"], "ito"))
    assert failed(report) == {"kernel_accuracy"}, report.checks
