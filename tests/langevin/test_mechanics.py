"""Deterministic mechanics, reproducibility and the engine's contracts."""

import json
import os
import subprocess
import sys
import textwrap

import gsd.hoomd
import numpy as np
import pytest

from fricgen.errors import SimulationError
from fricgen.kernels import load_law_kernels, load_potential
from fricgen.langevin import (
    GSDWriter,
    Law,
    Particles,
    Simulation,
    State,
    Thermostat,
    add_slab_walls,
    lattice_state,
    load_checkpoint,
    save_checkpoint,
)

from .helpers import arrays, collision, config, passive

LAWS = ["linear", "coulomb", "coulomb_newton", "viscous_cubic", "smooth_coulomb", "stribeck"]


def energy(simulation):
    s, p = simulation.state, simulation.particles
    wca = load_potential("wca")
    d = s.position[1] - s.position[0]
    r = np.linalg.norm(d - s.box * np.rint(d / s.box))
    kinetic = 0.5 * np.sum(p.mass[:, None] * s.velocity**2) + 0.5 * np.sum(p.inertia[:, None] * s.omega**2)
    return kinetic + wca.energy(r, np.array([1.0, 1.0])), r


@pytest.mark.parametrize("law", LAWS)
def test_collision_dissipates_and_conserves_momentum(law):
    """Paper SI (A): E falls during the contact (dE/dt = -f u, F-9); sum of m v is conserved."""
    sim = collision(law, dt=1e-4)
    p0 = sim.state.velocity.sum(axis=0).copy()
    energies, distances = [], []
    for _ in range(1500):
        sim.advance(10)
        e, r = energy(sim)
        energies.append(e)
        distances.append(r)
    energies, distances = np.array(energies), np.array(distances)
    contact = distances < 2 ** (1 / 6)
    assert contact.any() and not contact[-1], "the spheres must collide and separate"
    before, after = energies[0], energies[-1]
    assert after < before - 1e-3, (law, before, after)
    rises = np.diff(energies[contact])
    assert rises.max() < 1e-4 * before  # no gain beyond the integrator's O(dt^2) error
    np.testing.assert_allclose(sim.state.velocity.sum(axis=0), p0, atol=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_same_seed_bit_identical_for_one_and_two_threads(dim):
    script = textwrap.dedent(f"""
        import hashlib, numpy as np
        from tests.langevin.helpers import passive, arrays
        sim = passive(dim={dim}, n=100, calculus="stratonovich")
        sim.advance(300)
        print(hashlib.sha256(arrays(sim).tobytes()).hexdigest())
    """)
    hashes = set()
    for threads in ("1", "2"):
        env = {**os.environ, "NUMBA_NUM_THREADS": threads}
        done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=env, check=True)
        hashes.add(done.stdout.strip())
    assert len(hashes) == 1


@pytest.mark.parametrize("contact_scheme", ["pairwise", "explicit"])
def test_independent_of_neighbour_lists_and_chunking(contact_scheme):
    """Skin (list contents, rebuild times) and chunking do not change a single bit."""
    a = passive(dim=3, n=125, skin=0.3, contact_scheme=contact_scheme)
    a.advance(400)
    b = passive(dim=3, n=125, skin=0.8, contact_scheme=contact_scheme)
    for _ in range(8):
        b.advance(50)
    assert np.array_equal(arrays(a), arrays(b))


def test_checkpoint_restart_is_bit_identical(tmp_path):
    straight = passive(dim=2, n=64, calculus="hk")
    straight.advance(300)
    first = passive(dim=2, n=64, calculus="hk")
    first.advance(120)
    resumed = load_checkpoint(save_checkpoint(tmp_path / "run.npz", first), first.law)
    resumed.advance(180)
    assert resumed.state.step == 300 and np.array_equal(arrays(straight), arrays(resumed))


def test_a_checkpoint_from_before_the_pairwise_step_resumes_the_explicit_kick(tmp_path):
    before = passive(dim=2, n=64, contact_scheme="explicit")
    path = save_checkpoint(tmp_path / "run.npz", before)
    with np.load(path) as data:
        saved = dict(data)
    stored = json.loads(str(saved["config"]))
    del stored["law"]["contact_scheme"]
    np.savez(path, **{**saved, "config": json.dumps(stored)})
    assert load_checkpoint(path, before.law).config.law.contact_scheme == "explicit"


def test_gsd_trajectory_reads_back(tmp_path):
    sim = passive(dim=2, n=64)
    path = tmp_path / "traj.gsd"
    with GSDWriter(path, sim.particles) as writer:
        sim.run(200, every=50, observers=[writer])
    with gsd.hoomd.open(str(path), "r") as traj:
        assert len(traj) == 4
        last = traj[-1]
        assert last.configuration.step == 200 and last.configuration.dimensions == 2
        assert last.particles.N == 64 and last.configuration.box[2] == 0
        expected = sim.state.position - sim.state.box / 2 * np.array([1, 1, 0])
        np.testing.assert_allclose(last.particles.position, expected, atol=1e-4)
        np.testing.assert_allclose(last.log["particles/angular_velocity"], sim.state.omega, rtol=1e-6)
        assert np.allclose(np.linalg.norm(last.particles.orientation, axis=1), 1.0, atol=1e-6)


def test_blow_up_stops_with_a_clear_error_and_keeps_the_file(tmp_path):
    sim = passive(dim=2, n=64, dt=0.05, law="linear", parameters={"gamma_f": 50.0})
    path = tmp_path / "traj.gsd"
    with GSDWriter(path, sim.particles) as writer, pytest.raises(SimulationError, match="reduce dt|dt = 0.05"):
        writer(sim)
        sim.run(10_000, every=1, observers=[writer])
    with gsd.hoomd.open(str(path), "r") as traj:
        assert len(traj) >= 1 and np.all(np.isfinite(traj[-1].particles.position))


def test_a_velocity_gone_infinite_is_reported_at_the_same_step_by_one_call_and_by_calls_of_one_step():
    """The step that went wrong, and the message, do not depend on how a run is cut into calls."""
    reports = []
    for every in (100, 1):
        sim = passive(dim=2, n=64, dt=1e-3, law="linear")
        sim.threads = 1  # one call for every = 100
        sim.run(5, every=5)
        sim.state.velocity[3, 0] = np.inf
        with pytest.raises(SimulationError, match="infinite or NaN") as error:
            sim.run(100, every=every)
        reports.append((str(error.value), sim.state.step))
    assert reports[0] == reports[1] and reports[0][1] == 5


def test_walls_do_not_move_and_rub_the_fluid():
    particles = Particles.spheres(64)
    state = lattice_state(particles, 2, 0.6, seed=2)
    mobile = np.ones(64, dtype=bool)
    mobile[:8] = False  # one row of the lattice
    walls = Particles(particles.radius, particles.mass, particles.inertia, mobile)
    state.velocity[:8] = 0.0
    state.omega[:8] = 0.0
    fixed = state.position[:8].copy()
    sim = Simulation(config("coulomb_newton", bulk_force=(0.5, 0.0, 0.0), seed=2), walls, state, load_law_kernels("coulomb_newton"))
    sim.advance(500)
    assert np.array_equal(sim.state.position[:8], fixed) and not sim.state.velocity[:8].any()
    assert sim.state.velocity[8:, 0].mean() > 0  # the bulk force drives the fluid


def test_active_force_pushes_along_the_body_axis():
    sim = passive(dim=2, n=16, law="linear", active_force=20.0, contact_noise=False, seed=4)
    sim.state.position[:] = sim.state.position * 3  # dilute: no contacts
    sim.state.box[:2] *= 3
    sim.advance(200)
    q = sim.state.orientation
    e1 = np.stack([1 - 2 * (q[:, 2] ** 2 + q[:, 3] ** 2), 2 * (q[:, 1] * q[:, 2] + q[:, 0] * q[:, 3])], axis=1)
    along = np.sum(sim.state.velocity[:, :2] * e1, axis=1)
    assert along.mean() > 20.0 / (3 * np.pi) * 0.5  # terminal speed F0 / gamma, up to noise and rotation


def test_mismatched_scheme_is_refused_unless_forced():
    with pytest.raises(ValueError, match="needs the ito scheme"):
        Law(calculus="ito", scheme="stratonovich")
    Law(calculus="ito", scheme="stratonovich", force_scheme=True)


def test_bad_inputs_are_refused():
    with pytest.raises(ValueError, match="positive"):
        Particles.spheres(4, radius=-1.0)
    with pytest.raises(ValueError, match="too high for a lattice"):
        lattice_state(Particles.spheres(100), 2, 0.85)
    with pytest.raises(ValueError, match="dt: must be positive"):
        Thermostat(dt=0.0)
    with pytest.raises(ValueError, match="law.calculus: law coulomb has no 'hk' noise"):
        passive(law="coulomb", calculus="hk")
    with pytest.raises(ValueError, match="set by the radii"):
        passive(parameters={"sigma": 2.0})


def test_slab_walls_follow_f42_and_drive_a_flow():
    particles = Particles.spheres(96)
    state = lattice_state(particles, 2, 0.3, seed=6)
    inside = np.abs(state.position[:, 1] - state.box[1] / 2) < state.box[1] / 2 - 2.0
    fluid = Particles(particles.radius[inside], particles.mass[inside], particles.inertia[inside], particles.mobile[inside])
    state = State(*(getattr(state, a)[inside] for a in ("position", "velocity", "omega", "orientation")), state.box, 2)
    walls, state = add_slab_walls(fluid, state, half_width=state.box[1] / 2 - 1.0, roughness=0.1, seed=3)
    fixed = ~walls.mobile
    y = state.position[fixed, 1]
    lower, upper = y[: fixed.sum() // 2], y[fixed.sum() // 2 :]
    np.testing.assert_allclose(upper - lower, 2 * (state.box[1] / 2 - 1.0))  # same zeta on both walls
    assert 0.05 < np.std(lower) < 0.2  # roughness delta_w = 0.1
    sim = Simulation(config("coulomb_newton", bulk_force=(2.0, 0.0, 0.0), seed=6), walls, state, load_law_kernels("coulomb_newton"))
    start = state.position[fixed].copy()
    flow = []
    for _ in range(20):  # samples 0.1 t0 = m / gamma apart: about independent
        sim.advance(100)
        flow.append(sim.state.velocity[~fixed, 0].mean())
    assert np.array_equal(sim.state.position[fixed], start)
    assert np.mean(flow) > 3 * np.std(flow) / np.sqrt(len(flow)), flow  # the fluid flows along the force


def test_the_kept_neighbour_list_follows_a_changed_state():
    """The engine keeps its neighbour list between calls while it is valid (one build for many short
    calls), and builds a new one when the state changes under it: after the particles are shuffled,
    the run is bit-identical to a new simulation of the shuffled state."""
    kept = passive(dim=2, n=64, skin=0.8)
    for _ in range(10):
        kept.advance(1)
    assert kept.neighbor_builds == 1
    shuffled = np.random.default_rng(1).permutation(64)
    s = kept.state
    for values in (s.position, s.velocity, s.omega, s.orientation):
        values[:] = values[shuffled]
    fresh = Simulation(kept.config, kept.particles, s.copy(), kept.law)
    kept.advance(100)
    fresh.advance(100)
    assert kept.neighbor_builds > 1 and np.array_equal(arrays(kept), arrays(fresh))
