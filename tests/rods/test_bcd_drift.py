"""The field's drift scheme (fricgen.rods.bcd, RodNumerics.drift_scheme; docs/physics-bcd-field-drift.md):
the Leimkuhler-Matthews midpoint against Euler's drift, with the bridge contact layer."""

import pytest

from fricgen.errors import ConfigError
from fricgen.rods import rod_config

from .test_bcd_contact import contrast_bias


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
