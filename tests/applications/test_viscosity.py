"""The transverse-current viscosity: a known nu recovered from synthetic exponentially decaying
currents with calibrated block errors, the k -> 0 extrapolation, and a tiny real bulk run."""

import dataclasses

import numpy as np
import pytest

from fricgen.app.run.build import build
from fricgen.app.run.config import RunLaw, load_config, resolve_source
from fricgen.app.studies.viscosity import CurrentSampler, autocorrelation, bulk_config, measure_bulk_viscosity, transverse_viscosity
from fricgen.errors import ConfigError
from fricgen.langevin.config import Thermostat

K = 2 * np.pi * np.arange(1, 4) / 17.37  # the three smallest k of a box of side 17.37
RHO, DT = 0.2865, 0.05


def ornstein_uhlenbeck(rates: np.ndarray, frames: int, pairs: int, seed: int) -> np.ndarray:
    """Complex stationary currents (frames, modes, pairs) with <j(t + s) j*(t)> = exp(-rate s)."""
    rng = np.random.default_rng(seed)
    decay = np.exp(-rates * DT)[:, None]
    kick = np.sqrt((1 - decay**2) / 2)
    noise = rng.normal(size=(frames, rates.size, pairs, 2)) @ np.array([1, 1j])
    currents = np.empty((frames, rates.size, pairs), complex)
    currents[0] = noise[0] / np.sqrt(2)
    for t in range(1, frames):
        currents[t] = decay * currents[t - 1] + kick * noise[t]
    return currents


def test_the_autocorrelation_is_that_of_the_process():
    c = autocorrelation(ornstein_uhlenbeck(np.array([1.0]), 20_000, 6, 0)[:, 0], 21)
    assert c / c[0] == pytest.approx(np.exp(-np.arange(21) * DT), abs=0.02)


def test_a_known_viscosity_is_recovered_within_its_errors():
    """eta(k) = 0.3 - 0.15 k^2: each eta(k) and the k -> 0 value within their errors (pulls over 30
    seeds: mean 0 within 0.6, about 3 standard errors; spread about 1, a bit more for 16 jackknife
    blocks), and errors of a few per cent at the smallest k as in production."""
    eta_k = 0.3 - 0.15 * K**2
    pulls, errors = [], []
    for seed in range(30):
        result = transverse_viscosity(ornstein_uhlenbeck(eta_k * K**2 / RHO, 6000, 6, seed), K, DT, RHO, blocks=16)
        pulls.append([*(result.eta_k - eta_k) / result.eta_k_err, (result.eta - 0.3) / result.eta_err])
        errors.append(result.eta_k_err[1] / eta_k[1])
    pulls = np.array(pulls)
    assert np.all(np.abs(pulls.mean(axis=0)) < 0.6), pulls.mean(axis=0)
    assert 0.7 < pulls.std() < 1.5, pulls.std()
    assert np.median(errors) < 0.1


def test_bad_inputs_are_refused():
    with pytest.raises(ConfigError, match="blocks"):
        transverse_viscosity(np.ones((10, 3, 6), complex), K, DT, RHO, blocks=16)
    with_solvent = dataclasses.replace(bulk_config(RunLaw(), 200, 0.15), thermostat=Thermostat())
    with pytest.raises(ConfigError, match="periodic bulk"):
        measure_bulk_viscosity(with_solvent, 0.1, 1.0)
    slit = load_config(resolve_source("poiseuille"), [("system.n", 100), ("system.box", [6.0, 18.1694, 6.0])])
    with pytest.raises(ConfigError, match="without walls"):
        CurrentSampler(build(slit))


def test_a_tiny_frictional_fluid_has_a_positive_finite_viscosity():
    """200 spheres at phi = 0.15, Coulomb–Newton (gamma_f = 6, kappa_f = 5), 10 t0: eta(k) > 0 at the
    smallest k, finite everywhere (the value itself needs hundreds of t0: docs/poiseuille.md)."""
    config = bulk_config(RunLaw(parameters={"gamma_f": 6.0, "kappa_f": 5.0}), 200, 0.15, seed=3)
    result, currents, k = measure_bulk_viscosity(config, equilibrate=1.0, duration=10.0, blocks=4)
    assert currents.shape == (200, 3, 6) and k[0] == pytest.approx(2 * np.pi / (200 * np.pi / 6 / 0.15) ** (1 / 3))
    assert result.mass_density == pytest.approx(0.15 * 6 / np.pi)
    assert result.eta_k[0] > 0 and np.all(np.isfinite(result.eta_k_err)) and np.isfinite(result.eta)
