"""The slit fit (F-43): the Stokes solution itself, recovery of a known eta and b with calibrated
errors from synthetic noisy profiles, a wrong profile shape caught by chi^2, and the ``poiseuille``
entry and ``profiles.png`` that ``fricgen run`` writes for a slit, and the count of contacts on the
Coulomb branch in a hand-built configuration (directly and through a GSD file), and the peculiar
temperature per slab of a synthetic shear flow."""

import json
from types import SimpleNamespace

import numpy as np
import pytest

from fricgen.app.cli import main
from fricgen.app.studies.poiseuille import (
    ContactBranches,
    contact_branches,
    fit_slit_profile,
    frame_errors,
    inside,
    slab_temperatures,
    slit_geometry,
    stokes_profile,
    trajectory_branches,
    trajectory_samples,
)
from fricgen.errors import ConfigError
from fricgen.kernels import load_law_kernels
from fricgen.langevin.system import Particles, State
from fricgen.langevin.trajectory import GSDWriter

#: The paper's slit: 36 bins across L_y = 2 x 8.5847 + 1, y_B = 7.5847, phi = 0.15, with a body force.
LY, BINS, Y_B, N_DENSITY, F = 18.1694, 36, 7.5847, 6 * 0.15 / np.pi, 0.02
WIDTH = LY / BINS
Y = (np.arange(BINS) + 0.5) * WIDTH - LY / 2
ETA, SLIP = 0.25, 1.5


def noisy_profile(seed: int, shape=None, noise: float = 0.01):
    """The profile (F-43 with ETA, SLIP unless ``shape``) plus Gaussian noise of a bin-dependent
    standard deviation, NaN beyond the accessible region (as empty bins are)."""
    rng = np.random.default_rng(seed)
    error = noise * (1 + 0.5 * rng.random(BINS))
    exact = stokes_profile(Y, ETA, SLIP, N_DENSITY, F, Y_B) if shape is None else shape(Y)
    v = np.where(np.abs(Y) < Y_B + 0.5, exact + error * rng.normal(size=BINS), np.nan)
    return v, error


def test_the_profile_solves_stokes_with_navier_slip():
    """eta v'' = -n F, and v(y_B) = -b v'(y_B) at y_B (b = v / |v'| at the wall)."""
    h = 1e-3
    v = lambda y: stokes_profile(y, ETA, SLIP, N_DENSITY, F, Y_B)  # noqa: E731
    second = (v(1.0 + h) - 2 * v(1.0) + v(1.0 - h)) / h**2
    slope = (v(Y_B + h) - v(Y_B - h)) / (2 * h)
    assert ETA * second == pytest.approx(-N_DENSITY * F, rel=1e-6)
    assert v(Y_B) == pytest.approx(-SLIP * slope, rel=1e-9)


def test_the_fit_uses_the_bins_inside_the_accessible_slit():
    boundary, volume = slit_geometry(8.5847, 0.5, (20.0, LY, 15.1694), 3)
    assert boundary == pytest.approx(Y_B) and volume == pytest.approx(20.0 * 2 * Y_B * 15.1694)
    assert np.flatnonzero(inside(Y, WIDTH, Y_B)).tolist() == list(range(3, 33))  # 30 bins of the paper's 36
    v, error = noisy_profile(1)
    v[2], v[33] = 5.0, -5.0  # bins that reach past y_B (particles in the wall's hollows) are left out
    fit = fit_slit_profile(Y, v, error, WIDTH, N_DENSITY, F, Y_B)
    assert fit.used.tolist() == list(range(3, 33)) and fit.dof == 28


def test_the_fit_recovers_eta_and_slip_with_calibrated_errors():
    """Over 300 synthetic profiles the pulls (fit - truth) / error of eta and b have mean 0 and
    standard deviation 1 within their sampling errors (0.06 and 0.04), and chi^2 / dof averages 1."""
    fits = [fit_slit_profile(Y, *noisy_profile(seed), WIDTH, N_DENSITY, F, Y_B) for seed in range(300)]
    for truth, value, error in ((ETA, "eta", "eta_err"), (SLIP, "slip", "slip_err")):
        pulls = np.array([(getattr(f, value) - truth) / getattr(f, error) for f in fits])
        assert abs(pulls.mean()) < 0.2 and 0.85 < pulls.std() < 1.15, (value, pulls.mean(), pulls.std())
    assert np.mean([f.reduced_chi2 for f in fits]) == pytest.approx(1.0, abs=0.05)
    assert fits[0].eta_err / ETA < 0.05  # the synthetic noise is that of a production run: a few per cent


def test_a_profile_of_the_wrong_shape_fails_chi2():
    """A plug-like flow (quartic, as the paper sees beyond linear response) with the same noise is
    not a Stokes profile: chi^2 / dof far above 1 (p < 1e-6), where the right shape gives about 1."""
    plug = lambda y: 0.8 * (1 - (y / Y_B) ** 4) + 0.3  # noqa: E731
    wrong = fit_slit_profile(Y, *noisy_profile(2, plug), WIDTH, N_DENSITY, F, Y_B)
    right = fit_slit_profile(Y, *noisy_profile(2), WIDTH, N_DENSITY, F, Y_B)
    assert wrong.reduced_chi2 > 3.0 and right.reduced_chi2 < 2.0


def test_frame_errors_count_slabs_that_fluctuate_together():
    """Frames whose curvature fluctuates coherently (A_t = A + xi_t, iid) on top of independent slab
    noise: frame_errors finds the exact error of eta (the weighted linear estimator's variance under
    the true slab covariance) within the 11 % scatter of a 40-block estimate; the per-slab errors of
    curve_fit miss more than half of it, and chi^2 / dof below 1 is the sign."""
    rng = np.random.default_rng(4)
    frames, spread, noise = 4000, 0.3, 0.1
    amplitude = N_DENSITY * F / (2 * ETA)
    shape = np.where(np.abs(Y) < Y_B + 0.5, Y_B**2 - Y**2, np.nan)
    xi = spread * amplitude * rng.normal(size=frames)
    v = stokes_profile(Y, ETA, SLIP, N_DENSITY, F, Y_B) + xi[:, None] * shape + noise * rng.normal(size=(frames, BINS))
    mean, error = v.mean(axis=0), v.std(axis=0) / np.sqrt(frames)
    fit = fit_slit_profile(Y, mean, error, WIDTH, N_DENSITY, F, Y_B)
    used, weight = fit.used, 1 / error[fit.used]
    solve = np.linalg.pinv(np.stack([Y_B**2 - Y[used] ** 2, np.ones(used.size)], axis=1) * weight[:, None]) * weight[None, :]
    covariance = noise**2 * np.eye(used.size) + (spread * amplitude) ** 2 * np.outer(shape[used], shape[used])
    exact = ETA / amplitude * np.sqrt((solve @ covariance @ solve.T)[0, 0] / frames)
    eta_err, slip_err = frame_errors(fit, Y, error, v, blocks=40)
    assert eta_err == pytest.approx(exact, rel=0.3) and slip_err > 0
    assert fit.eta_err < 0.6 * exact and fit.reduced_chi2 < 0.8


def test_bad_profiles_are_refused():
    v, error = noisy_profile(3)
    with pytest.raises(ConfigError, match="bins with data"):
        fit_slit_profile(Y, np.full(BINS, np.nan), error, WIDTH, N_DENSITY, F, Y_B)
    with pytest.raises(ConfigError, match="bulk force"):
        fit_slit_profile(Y, v, error, WIDTH, N_DENSITY, 0.0, Y_B)


def test_fricgen_run_fits_a_slit_and_draws_the_profiles(tmp_path, capsys):
    out = tmp_path / "slit"
    settings = {
        "system.box": "[6.0, 18.1694, 6.0]",
        "system.n": "156",
        "bulk.force": "[0.5, 0.0, 0.0]",
        "run.equilibrate": "100",
        "run.chunk": "10",
        "output.period": "10",
        "output.trajectory_period": "0",
        "output.checkpoint_period": "0",
    }
    args = [word for key, value in settings.items() for word in ("--set", f"{key}={value}")]
    assert main(["run", "poiseuille", "--out", str(out), "--steps", "400", *args, "--json"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    fit = summary["poiseuille"]
    assert fit["boundary"] == pytest.approx(7.5847) and fit["force"] == 0.5
    assert fit["density"] == pytest.approx(156 / (6.0 * 2 * 7.5847 * 6.0))
    assert set(fit["bins_used"]) <= set(range(3, 33)) and fit["dof"] == len(fit["bins_used"]) - 2
    assert all(np.isfinite(fit[key]) for key in ("eta", "eta_err", "slip", "slip_err", "chi2"))
    assert "eta_err_frames" in fit and "slip_err_frames" in fit  # None here: some slabs of this tiny run are empty in some frames
    assert (out / "profiles.png").stat().st_size > 10_000


def branch_configuration():
    """Hand-built pairs in a periodic 10^3 box (R = 1/2, Coulomb–Newton gamma_f = 6, kappa_f = 5; at r = 1
    w = 24, so the Coulomb branch starts at u = 20), returned as (particles, state):
    A: r = 1, u = 25 -> Coulomb; B: u = 15 tangential plus 100 along r_hat -> viscous;
    C: spins only, (R omega_i + R omega_k) x r_hat = 22 -> Coulomb; D: across the periodic x boundary,
    r = 0.9 (w = 138.7, threshold u = 115.5), u = 50 -> viscous; E: two wall spheres -> left out;
    F: wall and mobile sphere, u = 30 -> Coulomb; G: r = 1.2, beyond 2^(1/6) -> not in contact."""
    position = np.array([[1, 1, 1], [2, 1, 1], [1, 5, 1], [2, 5, 1], [5, 5, 5], [6, 5, 5], [9.6, 8, 8], [0.5, 8, 8],
                         [5, 1, 8], [6, 1, 8], [5, 8, 2], [5, 9, 2], [8, 3, 3], [9.2, 3, 3]], dtype=float)  # fmt: skip
    velocity, omega = np.zeros_like(position), np.zeros_like(position)
    velocity[1] = [0, 25, 0]
    velocity[3] = [100, 15, 0]
    omega[4] = omega[5] = [0, 0, 22]
    velocity[7] = [0, 50, 0]
    velocity[11] = [30, 0, 0]
    velocity[13] = [0, 500, 0]
    mobile = np.ones(14, bool)
    mobile[[8, 9, 10]] = False
    particles = Particles(np.full(14, 0.5), np.ones(14), np.full(14, 0.1), mobile)
    return particles, State(position, velocity, omega, np.tile([1.0, 0, 0, 0], (14, 1)), np.full(3, 10.0), 3)


def test_contact_branches_of_a_hand_built_configuration():
    particles, state = branch_configuration()
    kernels = load_law_kernels("coulomb_newton")
    parameters = kernels.parameters(gamma_f=6.0, kappa_f=5.0)
    args = (state.position, state.velocity, state.omega, particles.radius, particles.mobile, state.box)
    branches = contact_branches(*args, kernels, parameters)
    assert branches == ContactBranches(contacts=5, coulomb=3, wall_contacts=1, wall_coulomb=1)
    assert branches.fraction == pytest.approx(0.6) and branches.wall_fraction == 1.0
    # kappa_f = 7 moves the threshold at r = 1 to u = 28: A (25) and C (22) turn viscous, F (30) stays.
    assert contact_branches(*args, kernels, kernels.parameters(gamma_f=6.0, kappa_f=7.0)).coulomb == 1


def test_trajectory_branches_read_a_gsd_frame(tmp_path):
    particles, state = branch_configuration()
    path = tmp_path / "trajectory.gsd"
    with GSDWriter(path, particles) as writer:
        for step in (0, 10):
            state.step = step
            writer(SimpleNamespace(state=state))
    steps, counts = trajectory_branches(path, "coulomb_newton", {"gamma_f": 6.0, "kappa_f": 5.0}, first_step=5)
    assert steps == [10] and counts == [ContactBranches(contacts=5, coulomb=3, wall_contacts=1, wall_coulomb=1)]


def test_slab_temperatures_subtract_the_streaming_flow(tmp_path):
    """Thermal velocities at T = 0.7 (masses 1 and 2) on a parabolic flow u_x = U (1 - 4 y^2 / L^2), spins
    at 0.4: subtracting each slab's flow recovers T in every slab to 4 standard errors, while the
    temperature with the flow (the negative control) exceeds it by <m u^2> / 3; trajectory_samples reads
    the same samples back from a GSD file."""
    rng = np.random.default_rng(3)
    samples, length, bins, temperature, spin_temperature = 40000, 10.0, 20, 0.7, 0.4
    y = rng.uniform(-length / 2, length / 2, samples)
    mass = rng.choice([1.0, 2.0], samples)
    velocity = rng.normal(size=(samples, 3)) * np.sqrt(temperature / mass)[:, None]
    velocity[:, 0] += 1.0 - 4 * y**2 / length**2
    omega = rng.normal(size=(samples, 3)) * np.sqrt(spin_temperature / 0.1)
    slabs = slab_temperatures(y, velocity, omega, mass, 0.1, length, bins)
    error = temperature * np.sqrt(2 / (3 * slabs.count))  # chi^2 with 3 count degrees of freedom
    assert np.all(np.abs(slabs.T_peculiar - temperature) < 4 * error)
    assert slabs.slit("T_peculiar") == pytest.approx(temperature, abs=4 * temperature * np.sqrt(2 / (3 * samples)))
    assert slabs.slit("T_rot") == pytest.approx(spin_temperature, rel=0.02)
    flow = np.mean(mass * (1.0 - 4 * y**2 / length**2) ** 2) / 3  # <m u^2> / 3 = 1.5 x 8 / 45
    assert slabs.slit("T_trans") - temperature == pytest.approx(flow, abs=0.02)
    assert np.sum(np.abs(slabs.T_trans - temperature) > 4 * error) >= bins // 2
    assert slabs.flow[:, 0] == pytest.approx(1.0 - 4 * slabs.y**2 / length**2, abs=0.1)

    particles = Particles(np.full(50, 0.5), mass[:50], np.full(50, 0.1), np.ones(50, dtype=bool))
    position = np.column_stack([np.zeros(50), y[:50] + length / 2, np.zeros(50)])
    state = State(position, velocity[:50], omega[:50], np.tile([1.0, 0, 0, 0], (50, 1)), np.array([4.0, length, 4.0]), 3)
    path = tmp_path / "trajectory.gsd"
    with GSDWriter(path, particles) as writer:
        writer(SimpleNamespace(state=state))
    ((y_read, v_read, omega_read, mass_read, inertia_read, length_read),) = trajectory_samples(path)
    assert length_read == length and y_read == pytest.approx(y[:50], abs=1e-5) and v_read == pytest.approx(velocity[:50], rel=1e-6)
    assert omega_read == pytest.approx(omega[:50], rel=1e-6) and mass_read == pytest.approx(mass[:50])
    assert inertia_read[:, 2] == pytest.approx(0.1)
