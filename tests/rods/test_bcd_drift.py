"""The field's drift scheme (fricgen.rods.bcd, RodNumerics.drift_scheme; docs/physics-bcd-field-drift.md):
the Leimkuhler-Matthews midpoint against Euler's drift, with the bridge contact layer."""

import numpy as np
import pytest
from scipy import stats

from fricgen.errors import ConfigError
from fricgen.rods import RodSimulation, rod_config

from .test_bcd_contact import SIGMA, contrast_bias, ring_gap_cdf


@pytest.mark.parametrize("scheme, exact", [("lm", True), ("euler", False)])
def test_free_rods_are_sampled_exactly_at_the_noise_midpoint(scheme, exact):
    """Two free rods on a ring of length 2 (sigma = 0.5) from gap 0.02, three steps of dt = 0.0025, then one sampled
    step, 20000 rings: with lm the sampled gaps are the midpoint's, the exact reflected law a quarter step after
    the third step, t = 3.25 dt (the bridge is exact for free rods at either variance). The histogram holds both
    gaps of a ring, g and 1 - g, in mirrored bins: folded, each ring counts twice in one of 10 bins; chi^2 against
    its 1e-4 quantile. Euler samples the end of the fourth step, t = 4 dt: against the law at 3.25 dt it is the
    negative control (the test resolves where in the step the rods are sampled)."""
    g0, dt, rings = 0.02, 0.0025, 20_000
    config = rod_config(
        n=2, length=2.0, sigma=SIGMA, U0=0.0, dt=dt, replicas=rings, bins=1, gap_width=0.05, gap_bins=21, start_sweeps=0, seed=3,
        drift_scheme=scheme,
    )  # fmt: skip
    simulation = RodSimulation(config, positions=[0.0, SIGMA + g0])
    simulation.advance(3)
    rods, gaps = np.zeros((rings, 1)), np.zeros((rings, 1, 21))
    simulation.advance(1, (rods, gaps))
    counts = gaps.sum((0, 1))[1:]  # gap bins [(k - 1) w, k w), k = 1 .. 20
    folded = (counts[:10] + counts[::-1][:10]) / 2
    cdf = ring_gap_cdf(np.linspace(0, 1, 21), g0, 3.25 * dt)
    probability = np.diff(cdf)
    expected = rings * (probability[:10] + probability[::-1][:10])
    chi2 = np.sum((folded - expected) ** 2 / expected)
    assert folded.sum() == rings
    assert (chi2 < stats.chi2.isf(1e-4, 9)) == exact, chi2


@pytest.mark.parametrize("scheme, within", [("lm", True), ("euler", False)])
def test_dilute_profile_within_error_at_a_long_step(scheme, within):
    """rho_bar sigma = 0.2, U0 = 6, 16 rings, 2.5 time units at dt = 4e-3 (40 times the default): the well
    contrast's bias c - 1 is within 3 errors of 0 with the midpoint (measured +0.0008 +- 0.0008 with 32 rings and
    5 time units) and resolved with Euler's drift, the negative control (-0.112 +- 0.001 there, about -28 dt)."""
    config = rod_config(n=40, length=100.0, sigma=0.5, dt=4e-3, replicas=16, bins=25, seed=11, drift_scheme=scheme)
    bias, error = contrast_bias(config, 2.5)
    assert (abs(bias) < 3 * error) == within, (bias, error)
    assert within or bias < -10 * error, (bias, error)


def test_the_midpoint_needs_the_bridge_layer():
    with pytest.raises(ConfigError, match="bridge"):
        rod_config(contact_layer="merge", drift_scheme="lm")
    with pytest.raises(ConfigError, match="drift_scheme"):
        rod_config(drift_scheme="heun")
    with pytest.raises(ConfigError, match="euler"):
        rod_config(gamma=1.0, eps=0.0, drift_scheme="lm")
