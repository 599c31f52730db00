"""Equipartition at kT = 2: the engine passes kT to the noise kernels and to the solvent.

At kT = 1 a lost factor kT (in the noise amplitude D, whose nu kT sets its shape, or in the impulse
sqrt(2 kT D dt)) is invisible; at kT = 2 it is not. Coulomb–Newton in 2-D (N = 256, area fraction
0.6, the paper's solvent, dt = 1e-3, where the contact kick's bias is about +0.8 % of kT on T_rot),
fixed seeds, about 20 s in all, on the explicit contact kick, where D shows (the pairwise step at
kT = 2: test_contact_step.py). Passed means T_trans and T_rot within 4 standard errors of kT and
KL divergences (F-41) below 2e-3, as in test_thermostat.py.
"""

import functools

from fricgen.app import thermostat_check

#: The check on the explicit contact kick, where a wrong D shows.
explicit_check = functools.partial(thermostat_check, contact_scheme="explicit")

KT = 2.0


def test_coulomb_newton_thermalises_at_kT_2():
    result = explicit_check("coulomb_newton", kT=KT, total_time=20.0, seed=11)
    assert result.passed, result
    assert abs(result.T_trans - KT) < 4 * result.T_trans_err, result
    assert abs(result.T_rot - KT) < 4 * result.T_rot_err, result


def test_coulomb_newton_without_its_noise_cools_at_kT_2():
    """Negative control: the same law at kT = 2 without the contact noise is detected as cooled."""
    result = explicit_check("coulomb_newton", kT=KT, contact_noise=False, total_time=10.0, seed=14)
    assert not result.passed
    assert result.T_trans < KT - 10 * result.T_trans_err and result.T_rot < KT - 10 * result.T_rot_err, result
