"""The pairwise contact step: its mechanics, its statics at a large dt, and its rejection rate.

Mechanics: one pair's update moves only that pair's contact mode (fixed seeds, exact to rounding).
Statics: the passive check (2-D area fraction 0.6, N = 256, or 3-D volume fraction 0.3, N = 216;
WCA, the paper's solvent) at dt = 1e-3, where the explicit kick is 8 % hot in T_rot for coulomb and
blows up for linear at gamma_f = 3, passes within 4 block standard errors (about 0.5 % of kT here).
Rejection rate: for the right D it falls like dt^1.5 (the kink of coulomb_newton's f at u_c makes it
about dt^1.3), for D of the wrong calculus or D x 1.1 like dt^0.5.
"""

import copy
import math

import numba
import numpy as np
import pytest

from fricgen.app import thermostat_check
from fricgen.kernels import CONTACT_KERNEL, load_law_kernels
from fricgen.langevin import Particles, Simulation, lattice_state
from fricgen.langevin.contact_step import colour_classes, update_pair
from fricgen.langevin.records import Bodies, Dynamics, Motion
from fricgen.rng import CONTACT, pair_key, stream_key, uniform, ziggurat_normal

from .helpers import config, passive

RADIUS, MASS, INERTIA = np.array([0.5, 0.4, 0.6]), np.array([1.0, 0.7, 1.8]), np.array([0.1, 0.05, 0.3])


def _pair_system(dims, noise, law="coulomb_newton", calculus="ito"):
    """Three unequal spheres, 0 and 2 in contact (normal n from 0 to 2), 1 apart; random velocities and spins."""
    rng = np.random.default_rng(dims)
    n = np.array([0.6, 0.8, 0.0]) if dims == 2 else np.array([0.48, 0.6, 0.64])
    r = 1.02 * (RADIUS[0] + RADIUS[2])
    position = np.array([[5.0, 5.0, 5.0 if dims == 3 else 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 0.0]])
    position[2] = position[0] + r * n
    velocity, omega = rng.normal(size=(3, 3)), rng.normal(size=(3, 3)) * 3
    if dims == 2:
        velocity[:, 2] = omega[:, :2] = 0.0
    motion = Motion(position, velocity, omega, np.tile([1.0, 0.0, 0.0, 0.0], (3, 1)))
    kernels = load_law_kernels(law)
    params = kernels.parameters(sigma=1.0)
    w = kernels.weight(r / (RADIUS[0] + RADIUS[2]), params) / (RADIUS[0] + RADIUS[2])
    mu = 1 / MASS[0] + 1 / MASS[2] + RADIUS[0] ** 2 / INERTIA[0] + RADIUS[2] ** 2 / INERTIA[2]
    box = np.array([10.0, 10.0, 10.0 if dims == 3 else 0.0])
    dyn = Dynamics(box, np.where(box > 0, 1 / np.where(box > 0, box, 1), 0.0), np.zeros(3), dims, 0.01, 1.0, 0.0, 0.0, 0.0, 1,
                   ["ito", "stratonovich", "hk"].index(calculus), True, noise, True, 0.3, 0.6, 1)  # fmt: skip
    law_kernels = (kernels.contact(calculus), kernels.friction_slope, kernels.weight)
    return motion, Bodies(RADIUS, 1 / MASS, 1 / INERTIA), dyn, params, law_kernels, np.array([*n, r, w, mu])


def _contact_velocity(motion, n):
    v, o = motion.velocity, motion.omega
    relative = v[2] - v[0]
    return relative - (relative @ n) * n - np.cross(RADIUS[0] * o[0] + RADIUS[2] * o[2], n)


@pytest.mark.parametrize("dims", [2, 3])
@pytest.mark.parametrize("noise", [True, False])
def test_a_pair_update_moves_only_its_contact_mode(dims, noise):
    """Impulse J on 0, -J on 2, torques R n x J on both: J tangential, momentum kept, u_perp -> u_perp - mu J,
    the third sphere untouched; without noise u_perp decays by exp(-mu (f/u) dt)."""
    motion, bodies, dyn, params, law, geometry = _pair_system(dims, noise)
    n, mu = geometry[:3], geometry[5]
    moved = 0
    for step in range(20):
        after = Motion(*(a.copy() for a in motion))
        key = np.uint64(stream_key(1, step, CONTACT))
        update_pair(after.velocity, after.omega, bodies, dyn, params, law, key, np.array([[0, 2]]), geometry[None], 0)
        assert np.array_equal(after.velocity[1], motion.velocity[1]) and np.array_equal(after.omega[1], motion.omega[1])
        impulse = MASS[0] * (after.velocity[0] - motion.velocity[0])
        if not impulse.any():
            continue
        moved += 1
        scale = np.abs(impulse).max()
        np.testing.assert_allclose(MASS[2] * (after.velocity[2] - motion.velocity[2]), -impulse, atol=1e-13 * scale)
        assert abs(impulse @ n) < 1e-13 * scale
        for j in (0, 2):
            np.testing.assert_allclose(after.omega[j] - motion.omega[j], RADIUS[j] / INERTIA[j] * np.cross(n, impulse), atol=1e-12 * scale)
        u, u_after = _contact_velocity(motion, n), _contact_velocity(after, n)
        np.testing.assert_allclose(u_after, u - mu * impulse, atol=1e-12)
        if not noise:
            speed = np.linalg.norm(u)
            ratio = law[0](speed, geometry[4], geometry[3], mu, 1.0, params)[0]
            np.testing.assert_allclose(u_after, u * math.exp(-mu * ratio * dyn.dt), rtol=1e-12)
        if dims == 2:
            assert not after.velocity[:, 2].any() and not after.omega[:, :2].any()
    assert moved >= (10 if noise else 20)


def test_colours_share_no_particle_and_keep_the_pair_order():
    rng = np.random.default_rng(4)
    pairs = np.unique(np.sort(rng.integers(0, 40, size=(300, 2)), axis=1), axis=0)
    pairs = pairs[pairs[:, 0] < pairs[:, 1]]
    order, first = colour_classes(pairs, 40)
    assert sorted(order) == list(range(len(pairs)))
    for c in range(first.size - 1):
        members = order[first[c] : first[c + 1]]
        assert np.all(np.diff(members) > 0)
        particles = pairs[members].ravel()
        assert len(set(particles)) == particles.size


@numba.njit
def _draws(key, count):
    out = np.empty((count, 3))
    for j in range(count):
        pair = pair_key(key, j, j + 1)  # as the contact step draws: normals 0 and 1, the uniform 2
        out[j, 0], out[j, 1], out[j, 2] = ziggurat_normal(pair, 0), ziggurat_normal(pair, 1), uniform(pair, 2)
    return out


def test_the_pair_draws_are_normal_uniform_and_independent():
    draws = _draws(np.uint64(stream_key(3, 7, CONTACT)), 200_000)
    uniform = draws[:, 2]
    assert uniform.min() >= 0 and uniform.max() < 1
    error = 1 / math.sqrt(uniform.size)
    assert abs(uniform.mean() - 0.5) < 5 * error * math.sqrt(1 / 12)
    assert abs(np.sort(uniform) - np.linspace(0, 1, uniform.size)).max() < 5 * error  # Kolmogorov–Smirnov
    for column in (0, 1):
        normal = draws[:, column]
        assert abs(normal.mean()) < 5 * error and abs(normal.var() - 1) < 5 * error * math.sqrt(2)
        assert abs(np.corrcoef(normal, uniform)[0, 1]) < 5 * error
    assert abs(np.corrcoef(draws[:, 0], draws[:, 1])[0, 1]) < 5 * error


STATICS = [
    # law, dim, parameter overrides, kT, simulated time (smooth_coulomb's D is a quadrature: slower)
    ("coulomb", 2, {}, 1.0, 20.0),
    ("smooth_coulomb", 2, {}, 1.0, 10.0),
    ("coulomb_newton", 2, {}, 1.0, 20.0),
    ("linear", 2, {"gamma_f": 3.0}, 1.0, 20.0),
    ("coulomb", 3, {}, 1.0, 20.0),
    ("coulomb_newton", 2, {}, 2.0, 20.0),
]


@pytest.mark.parametrize(("law", "dim", "params", "kT", "total"), STATICS, ids=str)
def test_pairwise_step_keeps_kT_at_dt_1e_3(law, dim, params, kT, total):
    result = thermostat_check(law, dim=dim, dt=1e-3, kT=kT, total_time=total, parameters=params, seed=21)
    assert result.passed, result
    assert abs(result.T_trans - kT) < 4 * result.T_trans_err and abs(result.T_rot - kT) < 4 * result.T_rot_err, result
    assert result.rejection_rate < 0.05, result


def test_no_contact_noise_is_detected_as_cooled():
    """Without its noise the pairwise step relaxes each contact deterministically: the system cools."""
    result = thermostat_check("coulomb_newton", contact_noise=False, seed=14)
    assert not result.passed and result.rejection_rate is None
    assert result.T_trans < 1 - 10 * result.T_trans_err and result.T_rot < 1 - 10 * result.T_rot_err, result


def _scaled(contact, factor):
    """The contact kernel with D multiplied by ``factor`` (a wrong amplitude, for the negative control)."""
    root_factor = math.sqrt(factor)

    @numba.njit(CONTACT_KERNEL.signature)
    def scaled(u, w, r, mu, kT, params):
        ratio, root = contact(u, w, r, mu, kT, params)
        return ratio, root * root_factor

    return scaled


def test_rejection_rate_falls_fast_for_the_right_D_only():
    """Slopes of log(rejection rate) against log dt, 2-D, N = 64, from one equilibrated configuration."""
    particles = Particles.spheres(64)
    law = load_law_kernels("coulomb_newton")
    start = Simulation(config("coulomb_newton", dt=2e-3, seed=5), particles, lattice_state(particles, 2, 0.6, seed=5), law)
    start.advance(2000)
    steps = np.array([1e-4, 4e-4, 1.6e-3, 6.4e-3])
    variants = {"right": {}, "wrong calculus": {"calculus": "stratonovich", "scheme": "ito", "force_scheme": True}, "D x 1.1": {}}
    rates = {}
    for name, options in variants.items():
        rates[name] = []
        for dt in steps:
            simulation = Simulation(config("coulomb_newton", dt=dt, seed=7, **options), particles, copy.deepcopy(start.state), law)
            if name == "D x 1.1":
                simulation.contact = _scaled(simulation.contact, 1.1)
            simulation.advance(3000)
            rates[name].append(simulation.tally.rejection_rate)
    slopes = {name: np.polyfit(np.log(steps), np.log(values), 1)[0] for name, values in rates.items()}
    assert slopes["right"] > 1.1, (slopes, rates)
    assert 0.3 < slopes["wrong calculus"] < 0.7 and 0.3 < slopes["D x 1.1"] < 0.7, (slopes, rates)
    assert rates["right"][0] < rates["wrong calculus"][0] / 20 and rates["right"][0] < rates["D x 1.1"][0] / 20, rates


def test_friction_off_skips_the_step_and_explicit_reports_no_rate():
    for options in ({"friction": False}, {"contact_scheme": "explicit"}):
        simulation = passive(n=64, **options)
        simulation.advance(50)
        assert simulation.tally.proposals == 0 and simulation.tally.rejection_rate is None
