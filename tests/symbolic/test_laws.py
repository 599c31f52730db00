"""Friction laws as data: catalogue, files, and clear errors for laws without a consistent noise."""

import pytest
import sympy as sp

from fricgen.derive import LawError, catalogue, contact_mobility, derive_noise, load_law, make_law, save_law
from fricgen.derive.law.symbols import u, w

GAMMA = {"gamma_f": {"default": 1.0}}


def test_catalogue_has_the_pinned_laws_and_parameter_names(laws):
    assert {"linear", "coulomb", "coulomb_newton"} <= set(laws)
    assert set(laws["linear"].symbols) >= {"gamma_f"}
    assert set(laws["coulomb"].symbols) >= {"kappa_f"}
    assert set(laws["coulomb_newton"].symbols) >= {"gamma_f", "kappa_f"}
    g, k = sp.symbols("gamma_f kappa_f", positive=True)
    assert laws["coulomb_newton"].friction == sp.Min(g * u, w * k)


def test_catalogue_has_one_closed_form_and_one_integral_form_law_beyond_the_paper(laws):
    extra = [law for name, law in laws.items() if name not in {"linear", "coulomb", "coulomb_newton"}]
    forms = {derive_noise(law, "ito").closed_form for law in extra}
    assert forms == {True, False}


def test_wca_weight_is_minus_the_wca_derivative(laws):
    r, eps, sigma = sp.symbols("r epsilon sigma", positive=True)
    weight = laws["coulomb"].weight
    at = {r: sp.Rational(21, 20), eps: 1, sigma: 1}
    expected = 48 / r**13 - 24 / r**7
    assert sp.simplify(weight.subs(at) - expected.subs(at)) == 0
    assert weight.subs({r: 2, eps: 1, sigma: 1}) == 0


def test_law_file_round_trip(tmp_path):
    law = make_law(
        "stick_slip",
        "w*kappa_f*(1 - exp(-u/u0))",
        {"kappa_f": {"default": 2.0, "unit": "1"}, "u0": {"default": 0.5, "unit": "sigma/t0"}},
        weight="wca",
        description="soft onset",
    )
    path = save_law(law, tmp_path)
    again = load_law(path)
    assert again == law
    assert catalogue(tmp_path) == {"stick_slip": law}


@pytest.mark.parametrize(
    ("friction", "message"),
    [
        ("gamma_f*(u - 1)", "negative"),
        ("gamma_f*sin(u)", "negative"),
        ("gamma_f*sqrt(u - 1)", "not real"),
        ("sqrt(-1)*gamma_f*u", "not real"),
        ("I*gamma_f*u", "unknown name 'I'"),
        ("gamma_f", "depends on none of u, w, r"),
        ("gamma_f*v", "unknown name 'v': declare it as a parameter"),
        ("gamma_f*g(u)", "unknown function 'g'"),
        ("gamma_f*exp(u**2)", "diverges"),
        ("gamma_f*exp(u**3)", "diverges"),
        ("gamma_f*u/(u - 1)**2", "not finite"),
        ("gamma_f*w*u", "defines no weight"),
        ("gamma_f*u +", "cannot parse"),
    ],
)
def test_bad_laws_are_rejected_with_a_clear_error(friction, message):
    with pytest.raises(LawError, match=message):
        make_law("bad", friction, GAMMA)


def test_slowly_growing_tail_is_accepted():
    """exp(u^1.9) is dominated by the Gaussian of (F-22): the integral converges."""
    make_law("fast", "gamma_f*exp(u**(19/10))", GAMMA)


def test_bad_parameters_and_files(tmp_path):
    with pytest.raises(LawError, match="positive default"):
        make_law("bad", "gamma_f*u", {"gamma_f": {"default": -1.0}})
    with pytest.raises(LawError, match="reserved"):
        make_law("bad", "kT*u", {"kT": {"default": 1.0}})
    (tmp_path / "other.toml").write_text('name = "mismatch"\nfriction = "u"\n')
    with pytest.raises(LawError, match="file name"):
        load_law(tmp_path / "other.toml")
    (tmp_path / "typo.toml").write_text('name = "typo"\nfriction = "u"\nfrictoin = "u"\n')
    with pytest.raises(LawError, match="unknown key"):
        load_law(tmp_path / "typo.toml")


def test_non_positive_mobility_is_rejected(laws):
    with pytest.raises(LawError, match="mobility must be positive"):
        derive_noise(laws["linear"], "ito", mobility=-1.0)
    with pytest.raises(LawError, match="mobility must be positive"):
        derive_noise(laws["linear"], "ito", mobility=0)
    with pytest.raises(ValueError, match="m_i must be positive"):
        contact_mobility(0, 1, 0.5, 0.5)


def test_mobility_from_particle_properties():
    """Equal solid spheres m = 1, R = 1/2, I = 2/5 m R^2: mu = 2 + 2 * (1/4) / (1/10) = 7."""
    assert contact_mobility(1, 1, sp.Rational(1, 2), sp.Rational(1, 2)) == 7
