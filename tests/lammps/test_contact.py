"""The plugin's pair forces and torques are fricgen's engine's, to 1e-12.

A handful of spheres in contact (a sliding pair on the Coulomb branch, one on the viscous branch, a
triangle of three, a pair across the periodic boundary), random velocities and spins: LAMMPS's
per-atom force and torque after `run 0` (the plugin's noise keyed on step 0 and the atom IDs) against
the engine's pair_slots + gather with the same seed (fricgen/langevin/pairs.py: the conservative
force, the friction, and the noise impulse over dt), through the generated Numba kernels.
"""

from __future__ import annotations

import numpy as np
import pytest

from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, State, Thermostat
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import PAIR_FIELDS, TERMS, WCA_RANGE, gather
from fricgen.langevin.records import Bodies
from fricgen.rng import CONTACT, stream_key

from .. import engine
from .helpers import data_file, dump_lines, read_dump, run, vectors

BOX, SEED, KT, DT, EPSILON = 10.0, 77, 1.3, 2e-3, 1.2
LAWS = {
    "coulomb_newton": {"gamma_f": 4.5, "kappa_f": 2.5},
    "smooth_coulomb": {"kappa_f": 3.0, "u0": 0.2},  # D from noise tables (fricgen.derive.backends.tables), the plugin's and the engine's
    "stribeck": {"kappa_s": 4.0, "kappa_d": 2.5, "u_s": 0.3},  # a closed form through erfcx and exp(-u/u_s)
}


def spheres(dim: int):
    """Positions, velocities and spins of 9 spheres: contacts at r = 1.11 (fast), 0.95 (slow), a triangle, and across x = 0."""
    position = np.array(
        [
            [2.0, 2.0, 2.0],
            [3.11, 2.0, 2.0],
            [6.0, 2.0, 2.0],
            [6.3, 2.9, 2.0],
            [2.0, 6.0, 2.0],
            [3.02, 6.1, 2.0],
            [2.5, 6.95, 2.0],
            [0.3, 8.0, 2.0],
            [9.32, 8.1, 2.0],
        ]  # fmt: skip
    )
    rng = np.random.default_rng(5)
    velocity = rng.normal(size=position.shape) * np.array([[2.0]] * 2 + [[0.3]] * 2 + [[1.0]] * 5)
    omega = rng.normal(size=position.shape) * 2.0
    if dim == 2:
        position[:, 2], velocity[:, 2], omega[:, :2] = 0.0, 0.0, 0.0
    else:
        position[:, 2] += rng.uniform(-0.2, 0.2, size=len(position))
    return position, velocity, omega


def engine_forces(law: str, dim: int, noise: bool, coordinates):
    """Force and torque on each sphere from fricgen's engine: terms of one pass, the noise impulse over dt."""
    position, velocity, omega = (np.ascontiguousarray(a) for a in coordinates)
    n = len(position)
    particles = Particles.spheres(n)
    box = np.array([BOX, BOX, BOX if dim == 3 else 0.0])
    state = State(position.copy(), velocity.copy(), omega.copy(), np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), box, dim)
    law_section = Law(name=law, calculus="ito", contact_noise=noise, parameters=LAWS[law], contact_scheme="explicit")
    config = LangevinConfig(law=law_section, thermostat=Thermostat(kT=KT, dt=DT), epsilon=EPSILON, seed=SEED)
    simulation = Simulation(config, particles, state, load_law_kernels(law))
    dyn = simulation.dynamics()
    lists = build_neighbors(state.position, dyn.box, dim, WCA_RANGE + 0.3)
    slots = np.zeros((lists[1].size, PAIR_FIELDS))
    bodies = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia)
    weight = simulation.kernels.module.weight
    switches = (np.uint64(stream_key(SEED, 0, CONTACT)), True, noise, True)  # a uint64 as in the engine (an int below 2^63 types as int64)
    kernels = (simulation.potential.force, simulation.contact, weight)
    engine.pair_slots((state.position, state.velocity, state.omega), bodies, dyn, simulation.couplings, *kernels, lists, switches, slots)
    terms = np.zeros((TERMS, n, 3))
    gather(particles.radius, lists, slots, terms)
    return terms[0] + terms[1] + terms[3] / DT, terms[2] + terms[4] / DT


def lammps_forces(lammps, plugin, folder, law: str, dim: int, noise: bool, coordinates, newton: str = "on"):
    data_file(folder / "data.spheres", BOX, dim, *coordinates)
    parameters = " ".join(f"{k} {v!r}" for k, v in LAWS[law].items())
    script = (
        f"units lj\ndimension {dim}\natom_style sphere\nboundary p p p\nnewton {newton}\nread_data data.spheres\n"
        f"set type 1 mass 1.0\nplugin load {plugin}\npair_style fricgen/{law} {KT!r} {SEED} noise {'yes' if noise else 'no'}\n"
        f"pair_coeff * * {EPSILON!r} 1.0 {parameters}\ncomm_modify vel yes\nneighbor 0.3 bin\ntimestep {DT!r}\n"
        + dump_lines("dump.forces")
        + "run 0\n"
    )
    run(lammps, folder, script)
    snapshot = read_dump(folder / "dump.forces")[0]
    return vectors(snapshot, "fx", "fy", "fz"), vectors(snapshot, "tqx", "tqy", "tqz")


@pytest.mark.parametrize("noise", [False, True], ids=["friction", "friction+noise"])
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("law", sorted(LAWS))
def test_forces_and_torques_equal_the_engines(lammps, plugin, tmp_path, law, dim, noise):
    coordinates = spheres(dim)
    force, torque = lammps_forces(lammps, plugin(law), tmp_path, law, dim, noise, coordinates)
    want_force, want_torque = engine_forces(law, dim, noise, coordinates)
    assert np.abs(want_force).max() > 1.0 and np.abs(want_torque).max() > 0.1  # contacts, not an empty comparison
    scale = np.abs(want_force).max()
    np.testing.assert_allclose(force, want_force, rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_allclose(torque, want_torque, rtol=1e-12, atol=1e-12 * scale)


def test_newton_off_gives_the_same_forces(lammps, plugin, tmp_path):
    """Pairs with a ghost are computed on both sides with newton_pair off: the same force, noise included."""
    coordinates = spheres(3)
    on = lammps_forces(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", 3, True, coordinates, "on")
    off = lammps_forces(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", 3, True, coordinates, "off")
    for a, b in zip(on, off):
        np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-12)
