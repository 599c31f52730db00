"""D at the run's parameters (fricgen.accuracy; docs/trust-model.md): the corpus of
tests/inputs/accuracy_cases.py, the reference against exact D, the noise tables, and the run's guard.

The corpus laws run as the code that ``fricgen generate`` would write for them, executed as plain
Python (fricgen.derive.backends.numba_kernels.accuracy.python_kernels: no Numba compilation);
the noise tables are those of a built-in law, compiled.
"""

from __future__ import annotations

import math
import types

import numpy as np
import pytest

import fricgen.accuracy as accuracy
import fricgen.langevin.simulation as simulation
from fricgen.derive import derive_noise, load_law
from fricgen.derive.backends.numba_kernels.accuracy import python_kernels
from fricgen.derive.calculus import Calculus
from fricgen.errors import KernelError
from fricgen.kernels import LawKernels, load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Thermostat, thermal_state
from fricgen.langevin.mobility import mode_mobilities

from .accuracy_cases import LAWS, ROWS, exact

MU, KT = 7.0, 1.0


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    """(law, calculus) -> the law's kernels, as plain Python."""
    folder = tmp_path_factory.mktemp("accuracy_laws")
    found = {}
    for name, text in LAWS.items():
        (folder / f"{name}.toml").write_text(text)
        law = load_law(folder / f"{name}.toml")
        for calculus in law.calculi:
            found[name, calculus] = LawKernels(name, types.SimpleNamespace(**python_kernels(derive_noise(law, calculus))))
    return found


@pytest.mark.parametrize("law, calculus, overrides, refusal", ROWS, ids=lambda x: str(x) if not isinstance(x, dict) else "")
def test_the_check_accepts_accurate_kernels_and_refuses_wrong_ones(corpus, law, calculus, overrides, refusal):
    """At the defaults (and alpha = 12) the kernels are accurate and pass; where their fixed quadrature
    misses the narrow bump or the power law's peak, the run is refused on one line naming the law,
    every parameter value and the error, which is far beyond the tolerance."""
    kernels = corpus[law, calculus]
    values = kernels.parameters(**overrides)
    if refusal is None:
        report = accuracy.check_noise(kernels, calculus, values, [MU], KT)
        assert report.error <= accuracy.RUN_TOLERANCE and report.reference_error <= accuracy.REFERENCE_TOLERANCE
        return
    with pytest.raises(KernelError) as caught:
        accuracy.check_noise(kernels, calculus, values, [MU], KT)
    message = str(caught.value)
    assert "\n" not in message and refusal in message and f"law {law} (sliding, {calculus})" in message
    assert all(f"{name}={value:.6g}" in message for name, value in zip(kernels.parameter_names, values))
    assert float(message.split("off by ")[1].split()[0]) > 10 * accuracy.RUN_TOLERANCE


@pytest.mark.parametrize("law, calculus, overrides", [(r[0], r[1], r[2]) for r in ROWS if r[3]], ids=str)
def test_the_reference_is_exact_where_the_kernels_are_wrong(corpus, law, calculus, overrides):
    """The adaptive reference against the exact D at every checked speed (to its error estimate, and
    within REFERENCE_TOLERANCE); the kernels' D is off there (the refusal is the kernels' fault)."""
    kernels = corpus[law, calculus]
    values = kernels.parameters(**overrides)
    a = float(1 - Calculus(calculus).theta) * MU * KT
    speeds = accuracy._speeds(math.sqrt(MU * KT))
    reference, estimate = accuracy._reference(kernels.friction, 1.0, 1.0, values, speeds, a)
    named = dict(zip(kernels.parameter_names, values))
    truth = np.array([float(exact(law, named, a, u)) for u in speeds])
    error = np.abs(reference - truth) / truth
    assert error.max() <= max(2 * estimate.max(), 1e-12) and estimate.max() <= accuracy.REFERENCE_TOLERANCE
    amplitude = kernels.noise_amplitude(calculus)
    wrong = max(abs(amplitude(u, 1.0, 1.0, MU, KT, values) - t) / t for u, t in zip(speeds, truth))
    assert wrong > 10 * accuracy.RUN_TOLERANCE


def test_the_noise_tables_are_checked_against_the_reference():
    """smooth_coulomb's compiled tables (and its quadrature) pass; the same tables with their
    coefficients 1e-4 off (the header kept, so that the kernel still reads them) are refused."""
    kernels = load_law_kernels("smooth_coulomb")
    plain = kernels.parameters(u0=0.02)
    tabled = kernels.module.tabulate_ito(np.array([MU]), KT, plain)
    report = accuracy.check_noise(kernels, "ito", tabled, [MU], KT)
    assert report.error <= accuracy.RUN_TOLERANCE and report.compared > 2 * accuracy.CELLS
    damaged = tabled.copy()
    head = plain.size + 1 + 3 + plain.size + 2 * kernels.module.TABLE_ZONES  # params, count, the table's header
    damaged[head:] *= 1 + 1e-4
    accuracy._CHECKED.clear()
    with pytest.raises(KernelError, match=r"off by .*, noise table\): kernel"):
        accuracy.check_noise(kernels, "ito", damaged, [MU], KT)
    accuracy._CHECKED.clear()


def _simulation(kernels: LawKernels, alpha: float) -> simulation.Simulation:
    config = LangevinConfig(law=Law(name="power", parameters={"alpha": alpha}), thermostat=Thermostat(kT=KT))
    particles = Particles.spheres(2, 0.5, 1.0)
    position = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    return simulation.Simulation(config, particles, thermal_state(particles, position, np.array([4.0, 4.0, 0.0]), 2, KT, 1), kernels)


def test_a_run_is_refused_and_without_the_guard_the_wrong_d_runs(corpus, monkeypatch):
    """A simulation of the power law at alpha = 60 is refused before it starts (alpha = 12 starts);
    with the check bypassed (the negative control) it starts with the kernels' D, off by > 1e-5."""
    kernels = corpus["power", "ito"]
    _simulation(kernels, 12.0)
    with pytest.raises(KernelError, match="alpha=60: its D is off by"):
        _simulation(kernels, 60.0)
    monkeypatch.setattr(simulation, "check_noise", lambda *args: None)
    run = _simulation(kernels, 60.0)
    mu = float(mode_mobilities(run.particles, "sliding")[0])
    values, u = run.couplings.law, 4.0 * math.sqrt(mu * KT)
    truth = float(exact("power", {"kappa_f": 1.0, "alpha": 60.0}, mu * KT, u))
    assert abs(kernels.noise_amplitude("ito")(u, 1.0, 1.0, mu, KT, values) - truth) / truth > 1e-5


def test_each_run_value_set_is_checked_once():
    """The second check of the same law, calculus, parameters, mobilities and kT is the first's report."""
    kernels = load_law_kernels("coulomb_newton")
    values = kernels.parameters(kappa_f=3.0)
    first = accuracy.check_noise(kernels, "stratonovich", values, [MU], KT)
    assert accuracy.check_noise(kernels, "stratonovich", values.copy(), [MU], KT) is first
    assert accuracy.check_noise(kernels, "stratonovich", values, [MU / 2], KT) is not first


def test_fricgen_noise_refuses_what_a_run_would(corpus):
    """``fricgen noise`` checks its --mu and --kT the same way: the narrow bump is refused, its defaults answer."""
    from fricgen.app.cli.noise import NoiseQuery, evaluate

    kernels, query = corpus["bump", "ito"], NoiseQuery(u=(0.5,), mu=MU, kT=KT)
    assert evaluate(kernels, "ito", query, {})["D"][0] > 0
    with pytest.raises(KernelError, match="delta=0.01: its D is off by"):
        evaluate(kernels, "ito", query, {"kappa_b": 100.0, "u_b": 4.0, "delta": 0.01})
