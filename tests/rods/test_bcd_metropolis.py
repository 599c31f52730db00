"""The Metropolis-adjusted bridge step (drift_scheme "metropolis", fricgen.rods.adjusted;
docs/physics-bcd-field-drift.md): the exact equilibrium of hard rods in a field at any time step."""

import math

import numpy as np
import pytest

from fricgen.errors import ConfigError
from fricgen.rods import RodSimulation, deviations, exact_profile, rod_config
from fricgen.rods.adjusted import log_proposal
from fricgen.rods.contact import BRIDGE, bridge_work, propagate

from .test_bcd_contact import SIGMA


def test_an_isolated_free_pair_is_always_accepted():
    """Two free rods on a ring of length 20 (the gap around the ring never touches), from gap 0.01, 2000 rings of
    5 steps of dt = 0.01 (a gap's spread sqrt(4 D dt) = 0.2, 20 times the start): the bridge is the exact reflected
    motion of an isolated pair, so its step is as likely as the step back and the test accepts every one. A wrong
    density of the proposal (a Gaussian's variance, E's factors) rejects some."""
    config = rod_config(n=2, length=20.0, sigma=SIGMA, U0=0.0, dt=0.01, replicas=2000, bins=1, gap_bins=9, start_sweeps=0,
                        drift_scheme="metropolis")  # fmt: skip
    simulation = RodSimulation(config, positions=[0.0, SIGMA + 0.01])
    simulation.advance(5)
    assert simulation.rejection == 0.0


def test_a_free_chain_of_three_has_the_density_of_its_step_back():
    """Three free rods in a row on a long ring, gaps 0.01 and 0.06, dt = 0.002 (a gap's spread 0.09), 400 steps
    from there: where one pair was pushed, the step and the step back have the same density (the bridge is the
    exact reflected motion of an isolated pair); where both were (a chain, where it is not), the densities differ,
    so that the test rejects some steps of free rods. Both are finite: the step back is always possible."""
    x0 = np.array([0.0, SIGMA + 0.01, 2 * SIGMA + 0.07])
    dt, length, diffusion = 0.002, 50.0, 1.0
    variance, chains, singles = 4.0 * diffusion * dt, [], 0
    rng = np.random.default_rng(3)
    for k in range(400):
        x, d, work = x0.copy(), math.sqrt(2 * diffusion * dt) * rng.standard_normal(3), bridge_work(3)
        _, exchanges = propagate(x, d, length, SIGMA, variance, k + 1, BRIDGE, work)  # any key: the bridge mixes it
        push = work[0].copy()
        if exchanges:
            continue
        zero = np.zeros(3)
        forward = log_proposal(x0, x, push, zero, 1.0, dt, diffusion, length, SIGMA)
        backward = log_proposal(x, x0, push, zero, 1.0, dt, diffusion, length, SIGMA)
        assert math.isfinite(forward) and math.isfinite(backward)
        if push[0] > 0 and push[1] > 0:
            chains.append(forward - backward)
        elif push[0] > 0 or push[1] > 0:
            singles += 1
            assert abs(forward - backward) < 1e-9 * max(1.0, abs(forward)), (push, forward, backward)
    assert len(chains) > 20 and singles > 20, (len(chains), singles)
    assert np.mean(np.abs(chains)) > 1e-3, chains


@pytest.mark.parametrize("scheme", ["metropolis", "lm"])
def test_dense_rods_are_exact_at_twenty_times_the_default_step(scheme):
    """rho_bar sigma = 0.7, U0 = 6, 32 rings, 5 time units at dt = 2e-3 (20 times the default step; 16 times the
    standard study's statistics), seed 11. With the Metropolis test the profile is within error (measured
    chi^2/bin 1.16, c - 1 = +0.0012 +- 0.0009 over 10 time units; 40 % of the steps rejected) and so is the contact
    density from the gaps; the Leimkuhler-Matthews midpoint, the scheme before it, fails at this step (c - 1 =
    -0.011 +- 0.001): the negative control. Dropping the Jacobian of the pushes from the proposal's density moves
    the contact density 10 errors low (0.972 +- 0.003)."""
    config = rod_config(n=140, length=100.0, sigma=0.5, dt=2e-3, replicas=32, bins=25, seed=11, drift_scheme=scheme)
    config = config.replace(gap_bins=max(40, config.contact_fit_bins()))
    with pytest.warns(UserWarning, match="rejects many steps" if scheme == "metropolis" else "the profile is biased"):
        simulation = RodSimulation(config)  # mu max|U''| dt = 0.24: the field's step is long
    simulation.equilibrate(0.25)
    profiles = simulation.run(round(5.0 / config.numerics.dt))
    figures = deviations(profiles, exact_profile(config), contact=True)
    within = figures["chi2_per_dof"] < 2.0 and abs(figures["contact_ratio"] - 1) < 3 * figures["contact_ratio_err"]
    assert within == (scheme == "metropolis"), figures
    assert scheme != "metropolis" or 0.2 < simulation.rejection < 0.6, simulation.rejection


def test_the_metropolis_test_needs_the_bridge_hard_rods_and_no_drive():
    with pytest.raises(ConfigError, match="bridge"):
        rod_config(contact_layer="reflect", drift_scheme="metropolis")
    with pytest.raises(ConfigError, match="hard rods"):
        rod_config(pair="wca", pair_range=0.06, drift_scheme="metropolis")
    with pytest.raises(ConfigError, match="drive"):
        rod_config(drive=1.0, drift_scheme="metropolis")
