"""Statistical physics of the engine: equipartition at kT with the frictional noise, and its failures.

Each run is a passive system (2-D area fraction 0.6, N = 256, or 3-D volume fraction 0.3, N = 216;
WCA; solvent gamma = 3 pi, gamma_R = pi unless stated), fixed seeds. "Passed" means T_trans and T_rot
within 4 standard errors (block averages) of kT and KL divergences (F-41) below 2e-3. These tests
check the laws' D, so they run the explicit contact kick, where a wrong D shows in the temperatures
(the pairwise step keeps kT for any D: tests/langevin/test_contact_step.py). The kick is first order
in dt, with a bias of about mu D dt / 2 on the contact mode (docs/physics.md#integrators-that-match-the-calculus);
each law runs at a dt where that bias is below the statistical error, and one test extrapolates in dt.
"""

import functools

import pytest

from fricgen.app import thermostat_check

#: The check on the explicit contact kick, where a wrong D shows.
explicit_check = functools.partial(thermostat_check, contact_scheme="explicit")

CONSISTENT = [
    # law, dim, dt, simulated time, n, parameter overrides
    ("coulomb_newton", 2, 1e-3, 40.0, None, {}),
    ("coulomb_newton", 3, 1e-3, 40.0, None, {}),
    ("linear", 2, 2e-4, 20.0, None, {}),
    ("linear", 3, 2e-4, 20.0, None, {}),
    ("coulomb", 2, 5e-5, 8.0, None, {}),
    ("coulomb", 3, 5e-5, 8.0, None, {}),
    ("smooth_coulomb", 2, 5e-4, 10.0, 128, {"kappa_f": 2.0, "u0": 0.5}),
    ("smooth_coulomb", 3, 5e-4, 10.0, 125, {"kappa_f": 2.0, "u0": 0.5}),
]


@pytest.mark.parametrize(("law", "dim", "dt", "total", "n", "params"), CONSISTENT, ids=lambda x: str(x))
def test_frictional_noise_thermalises_translation_and_rotation(law, dim, dt, total, n, params):
    result = explicit_check(law, dim=dim, dt=dt, total_time=total, n=n, parameters=params, seed=11)
    assert result.passed, result


@pytest.mark.parametrize("calculus", ["stratonovich", "hk"])
def test_each_calculus_with_its_own_scheme_gives_kT(calculus):
    result = explicit_check("coulomb_newton", calculus=calculus, seed=12)
    assert result.passed and result.scheme == calculus, result


def test_friction_thermostat_alone_thermalises():
    """Paper Fig. 2: 3-D, no solvent, Coulomb–Newton gamma_f = 3, kappa_f = 5."""
    result = explicit_check("coulomb_newton", dim=3, solvent=False, parameters={"gamma_f": 3.0}, seed=13)
    assert result.passed, result


def test_friction_without_its_noise_is_detected():
    """Paper Figs. 3-4: the inconsistent model cools below kT, rotation differently from translation."""
    result = explicit_check("coulomb_newton", contact_noise=False, seed=14)
    assert not result.passed
    assert result.T_trans < 1 - 10 * result.T_trans_err and result.T_rot < 1 - 10 * result.T_rot_err
    assert abs(result.T_trans - result.T_rot) > 10 * (result.T_trans_err + result.T_rot_err)


@pytest.mark.parametrize(("calculus", "scheme"), [("ito", "stratonovich"), ("stratonovich", "ito")])
def test_amplitude_with_the_wrong_scheme_is_detected(calculus, scheme):
    """Constant friction, where D depends strongly on u: the matched pairing passes, the mismatch fails. In 7 t0
    the wrong scheme's T_rot is off by 8.5 and 8.7 of its errors beyond the matched one's deviation (0.922 +- 0.009
    and 1.101 +- 0.010; in 10 t0 9.6 and 12.9, in 5 t0 only 6.3 and 6.4)."""
    common = dict(n=256, dt=1e-4, total_time=7.0, seed=15)
    matched = explicit_check("coulomb", calculus=calculus, **common)
    wrong = explicit_check("coulomb", calculus=calculus, scheme=scheme, force_scheme=True, **common)
    assert matched.passed, matched
    assert not wrong.passed, wrong
    assert abs(wrong.T_rot - 1) > 5 * wrong.T_rot_err + abs(matched.T_rot - 1)


def test_time_step_bias_is_first_order_and_extrapolates_to_kT():
    """Linear friction, strongest coupling: T(dt) - kT ~ dt; 2 T(dt/2) - T(dt) = kT within errors."""
    coarse = explicit_check("linear", dt=1e-3, total_time=40.0, seed=16)
    fine = explicit_check("linear", dt=5e-4, total_time=40.0, seed=16)
    extrapolated = 2 * fine.T_rot - coarse.T_rot
    error = (4 * fine.T_rot_err**2 + coarse.T_rot_err**2) ** 0.5
    assert coarse.T_rot - 1 > 4 * coarse.T_rot_err  # the bias is resolved at dt = 1e-3 ...
    assert abs(extrapolated - 1) < 4 * error  # ... and it is linear in dt
