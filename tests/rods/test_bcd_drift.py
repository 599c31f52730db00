"""The field's drift scheme (fricgen.rods.bcd, RodNumerics.drift_scheme; docs/physics-bcd-field-drift.md):
the Leimkuhler-Matthews midpoint against Euler's drift, with the bridge contact layer."""

import numpy as np
import pytest
from scipy import stats

from fricgen.errors import ConfigError
from fricgen.rods import RodSimulation, rod_config

from .test_bcd_contact import SIGMA, contrast_bias, ring_gap_cdf


@pytest.mark.parametrize("scheme, sampled_at", [("lm", 3.25), ("euler", 4.0)])
def test_the_profile_is_sampled_at_the_noise_midpoint(scheme, sampled_at):
    """Two free rods (ring of length 20, wavelength 1) from x = 0.5 and 10.5, which do not meet, three steps of
    dt = 0.0025, then one sampled step, 20000 rings: with lm the profile is the midpoint's, a Gaussian of variance
    2 D t at t = 3.25 dt (the law at the step's start convolved with half the step's noise; the hard core is not
    restored there); with euler the step's end, t = 4 dt. Each scheme is checked against both laws (chi^2 on 20
    bins against its 1e-4 quantile): the other scheme's law is the negative control, so the test resolves where
    in the step the profile is sampled."""
    dt, rings, bins = 0.0025, 20_000, 20
    config = rod_config(
        n=2, length=20.0, sigma=SIGMA, U0=0.0, dt=dt, replicas=rings, bins=bins, gap_bins=2, start_sweeps=0, seed=5,
        drift_scheme=scheme,
    )  # fmt: skip
    simulation = RodSimulation(config, positions=[0.5, 10.5])
    simulation.advance(3)
    rods, gaps = np.zeros((rings, bins)), np.zeros((rings, bins, 2))
    simulation.advance(1, (rods, gaps))
    counts = rods.sum(0)
    edges = np.linspace(0.0, 1.0, bins + 1)
    for t in (3.25, 4.0):
        expected = 2 * rings * np.diff(stats.norm.cdf(edges, 0.5, np.sqrt(2 * t * dt)))  # the tails beyond +-0.5: 4 sd
        chi2 = np.sum((counts - expected) ** 2 / expected)
        assert (chi2 < stats.chi2.isf(1e-4, bins - 1)) == (t == sampled_at), (t, chi2)


@pytest.mark.parametrize("scheme", ["lm", "euler"])
def test_the_gaps_are_sampled_at_the_step_end(scheme):
    """Two free rods on a ring of length 2 (sigma = 0.5) from gap 0.02, three steps of dt = 0.0025, then one sampled
    step, 20000 rings: with either scheme the gaps are the step's end, the exact reflected law at t = 4 dt (the bridge
    is exact for free rods); the law at the midpoint, t = 3.25 dt, is the negative control. The histogram holds both
    gaps of a ring, g and 1 - g, in mirrored bins: folded, each ring counts twice in one of 10 bins; chi^2 against its
    1e-4 quantile."""
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
    assert folded.sum() == rings
    for t, exact in ((4.0, True), (3.25, False)):
        probability = np.diff(ring_gap_cdf(np.linspace(0, 1, 21), g0, t * dt))
        expected = rings * (probability[:10] + probability[::-1][:10])
        chi2 = np.sum((folded - expected) ** 2 / expected)
        assert (chi2 < stats.chi2.isf(1e-4, 9)) == exact, (t, chi2)


@pytest.mark.parametrize("scheme, within", [("lm", True), ("euler", False)])
def test_dilute_profile_within_error_at_a_long_step(scheme, within):
    """rho_bar sigma = 0.2, U0 = 6, 16 rings, 2.5 time units at dt = 4e-3 (40 times the default): the well
    contrast's bias c - 1 is within 3 errors of 0 with the midpoint (measured +0.0008 +- 0.0008 with 32 rings and
    5 time units) and resolved with Euler's drift, the negative control (-0.112 +- 0.001 there, about -28 dt)."""
    config = rod_config(n=40, length=100.0, sigma=0.5, dt=4e-3, replicas=16, bins=25, seed=11, drift_scheme=scheme)
    bias, error = contrast_bias(config, 2.5)
    assert (abs(bias) < 3 * error) == within, (bias, error)
    assert within or bias < -10 * error, (bias, error)


@pytest.mark.parametrize("scheme", ["lm", "euler"])
def test_dense_bias_below_the_reflected_midpoints(scheme):
    """rho_bar sigma = 0.7, U0 = 6, 32 rings, 5 time units at dt = 1e-3, seed 11 (8 times the standard study; a few
    seconds): with the unreflected midpoint c - 1 = -0.0073 +- 0.0011, with the reflected one (the hard core restored
    at the midpoint, this scheme's earlier form) -0.0130 +- 0.0010 and with Euler's drift -0.0288 +- 0.0009. The
    bound -0.0105 lies about 3 errors from both midpoints': a reflected midpoint fails it, and so does Euler, the
    negative control."""
    config = rod_config(n=140, length=100.0, sigma=0.5, dt=1e-3, replicas=32, bins=25, seed=11, drift_scheme=scheme)
    bias, error = contrast_bias(config, 5.0)
    assert (bias > -0.0105) == (scheme == "lm"), (bias, error)


def test_the_midpoint_needs_the_bridge_layer_and_hard_rods():
    with pytest.raises(ConfigError, match="bridge"):
        rod_config(contact_layer="merge", drift_scheme="lm")
    with pytest.raises(ConfigError, match="drift_scheme"):
        rod_config(drift_scheme="heun")
    for interaction in ({"gamma": 1.0, "eps": 0.0}, {"gamma": 1.0, "eps": 0.05}, {"pair": "wca", "pair_range": 0.06}):
        with pytest.raises(ConfigError, match="hard rods"):
            rod_config(**interaction, drift_scheme="lm")
