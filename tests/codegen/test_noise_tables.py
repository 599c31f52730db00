"""Noise tables (fricgen.derive.backends.tables): the tabulated D of an integral-form law against its
quadrature and against mpmath, where they apply and where they must not, and the engine's use of them."""

import math

import mpmath
import numpy as np
import pytest
import sympy as sp

from fricgen.derive import derive_noise, make_law
from fricgen.derive.backends.numba_kernels.accuracy import python_kernels
from fricgen.derive.backends.tables import table_factor
from fricgen.derive.law.symbols import kT, mu, r, w
from fricgen.derive.noise.reference import reference_amplitude
from fricgen.generated.special import table_value
from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state
from fricgen.langevin.mobility import pair_mobilities

CASES = [(1.0, 7.0, 1.0), (0.3, 2.0, 0.5), (2.5, 3.5, 3.0), (1.0, 7.0, 0.02), (1.0, 7.0, 50.0)]  # kT, mu, factor on the parameters


def smooth(kernels, factor):
    k = kernels["smooth_coulomb"]
    return k, k.parameters(kappa_f=5.0 * factor, u0=0.1 * factor)


@pytest.mark.parametrize("temperature,mobility,factor", CASES)
@pytest.mark.parametrize("calculus", ["ito", "stratonovich"])
def test_the_table_is_the_quadrature_to_1e_12_from_rest_to_a_million_sqrt_a(kernels, calculus, temperature, mobility, factor):
    k, params = smooth(kernels, factor)
    tables = getattr(k.module, f"tabulate_{calculus}")(np.array([mobility]), temperature, params)
    assert tables.size > params.size + 1000  # tables, not an empty block
    a = temperature * mobility * (0.5 if calculus == "stratonovich" else 1.0)
    kernel = k.noise_amplitude(calculus)
    xs = np.concatenate([[0.0], np.geomspace(1e-7, 1.04e6, 4000), np.linspace(0.0, 10.0, 1001)])
    for x in xs * math.sqrt(a):
        assert table_value(x, a, tables, params.size) >= 0.0  # the table applies ...
        tabled, quadrature = kernel(x, 1.7, 1.0, mobility, temperature, tables), kernel(x, 1.7, 1.0, mobility, temperature, params)
        assert tabled == pytest.approx(quadrature, rel=1e-12, abs=0.0), x  # ... and is the quadrature


@pytest.mark.parametrize("temperature,mobility,factor", CASES[:3])
def test_the_table_is_mpmaths_integral_to_1e_11(models, kernels, temperature, mobility, factor):
    model = models["smooth_coulomb", "ito"]
    k, params = smooth(kernels, factor)
    values = {sp.Symbol("kappa_f", positive=True): params[0], sp.Symbol("u0", positive=True): params[1]}
    exact = reference_amplitude(
        model, model.variance_scale, {**model.law.defaults, **values, kT: temperature, mu: mobility, w: 1.0, r: 1.0}
    )
    tables = k.module.tabulate_ito(np.array([mobility]), temperature, params)
    rng = np.random.default_rng(3)
    with mpmath.workdps(20):
        for x in math.sqrt(temperature * mobility) * np.exp(rng.uniform(np.log(1e-4), np.log(3e3), 40)):
            got = k.noise_amplitude("ito")(x, 1.0, 1.0, mobility, temperature, tables)
            assert got == pytest.approx(float(exact(x)), rel=1e-11), x


def test_no_table_applies_to_another_a_other_parameters_or_speeds_beyond_its_zones(kernels):
    k, params = smooth(kernels, 1.0)
    tables = k.module.tabulate_ito(np.array([7.0]), 1.0, params)
    kernel = k.noise_amplitude("ito")
    assert table_value(1.0, 7.0 * (1 + 1e-15), tables, params.size) == -1.0
    assert table_value(1.0, 7.0, tables, params.size) >= 0.0
    other = tables.copy()
    other[1] = 0.2  # u0 changed after the tables were built: they no longer apply
    assert table_value(1.0, 7.0, other, params.size) == -1.0
    assert kernel(1.0, 1.0, 1.0, 7.0, 1.0, other) == kernel(1.0, 1.0, 1.0, 7.0, 1.0, other[: params.size].copy())
    for u in (2.0**20 * math.sqrt(7.0) * 1.01, math.inf, math.nan, -1.0):
        assert table_value(u, 7.0, tables, params.size) == -1.0
    far = 3e6 * math.sqrt(7.0)
    assert kernel(far, 1.0, 1.0, 7.0, 1.0, tables) == kernel(far, 1.0, 1.0, 7.0, 1.0, params)  # the quadrature beyond the zones


def test_tables_for_several_mobilities(kernels):
    k, params = smooth(kernels, 1.0)
    tables = k.module.tabulate_ito(np.array([7.0, 3.5, 12.0]), 1.3, params)
    for mobility in (7.0, 3.5, 12.0):
        assert table_value(0.7, 1.3 * mobility, tables, params.size) >= 0.0
        assert k.noise_amplitude("ito")(0.7, 1.0, 1.0, mobility, 1.3, tables) == pytest.approx(
            k.noise_amplitude("ito")(0.7, 1.0, 1.0, mobility, 1.3, params), rel=1e-12
        )


def test_the_checked_python_tables_are_the_compiled_ones(models, kernels):
    """verify checks the tables that the printed code builds run as plain Python; Numba builds the same numbers."""
    k, params = smooth(kernels, 1.0)
    compiled = k.module.tabulate_stratonovich(np.array([7.0]), 1.0, params)
    checked = python_kernels(models["smooth_coulomb", "stratonovich"])["tabulate_stratonovich"](np.array([7.0]), 1.0, params.copy())
    np.testing.assert_array_equal(compiled, checked)


def test_closed_forms_and_hk_have_no_tables(kernels):
    for name, k in kernels.items():
        for calculus in k.calculi:
            tabulated = hasattr(k.module, f"tabulate_{calculus}")
            assert tabulated == (not k.module.CLOSED_FORM[calculus]), (name, calculus)


def test_which_laws_are_tabulated(models):
    assert table_factor(models["smooth_coulomb", "ito"].law, models["smooth_coulomb", "ito"]) is not None
    assert table_factor(models["coulomb_newton", "ito"].law, models["coulomb_newton", "ito"]) is None  # closed form
    kinked = make_law(
        "kinked",
        "Min(gamma_f*u, w*kappa_f*tanh(u/u0))",
        {"gamma_f": {"default": 6.0}, "kappa_f": {"default": 5.0}, "u0": {"default": 0.1}},
        weight="wca",
    )
    assert table_factor(kinked, derive_noise(kinked, "ito")) is None  # a branch point in u: quadrature alone
    mixed = make_law("mixed", "w*kappa_f*tanh(u*r/u0)", {"kappa_f": {"default": 5.0}, "u0": {"default": 0.1}}, weight="wca")
    assert table_factor(mixed, derive_noise(mixed, "ito")) is None  # r inside g(u)
    shape = make_law(
        "shape",
        "w*(kappa_f*tanh(u/u0) + gamma_f*u)",
        {"kappa_f": {"default": 5.0}, "u0": {"default": 0.1}, "gamma_f": {"default": 1.0}},
        weight="wca",
    )
    assert table_factor(shape, derive_noise(shape, "ito")) == w  # the common factor w is pulled out of the sum


def test_pair_mobilities_are_the_engines():
    particles = Particles.spheres(6)
    particles.mass[:2] = 2.0
    particles.inertia[:2] = 0.4 * 2.0 * 0.25
    particles.mobile[5] = False
    found = pair_mobilities(particles)
    inv_mass, radius, inv_inertia = particles.inv_mass, particles.radius, particles.inv_inertia
    engine = {
        inv_mass[i] + inv_mass[k] + radius[i] ** 2 * inv_inertia[i] + radius[k] ** 2 * inv_inertia[k]
        for i in range(6)
        for k in range(6)
        if i != k
    }
    engine.discard(0.0)
    assert set(found) <= engine and len(found) == min(4, len(engine))
    assert list(pair_mobilities(Particles.spheres(10))) == [7.0]


def test_a_simulation_runs_on_its_tables_and_a_closed_form_law_on_its_parameters():
    particles = Particles.spheres(64)
    sims = {}
    for name in ("smooth_coulomb", "coulomb_newton"):
        config = LangevinConfig(law=Law(name), thermostat=Thermostat(kT=1.3, dt=1e-3))
        sims[name] = Simulation(config, particles, lattice_state(particles, 2, 0.6), load_law_kernels(name))
    values = sims["smooth_coulomb"].couplings.law
    assert values.size > 4 and table_value(0.5, 1.3 * 7.0, values, 4) >= 0.0  # a = kT mu of every pair in the engine
    assert sims["coulomb_newton"].couplings.law.size == len(sims["coulomb_newton"].kernels.parameter_names)
    sims["smooth_coulomb"].advance(20)  # runs
