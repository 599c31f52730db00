"""The fix fricgen/exact/<law> is fricgen's pairwise contact step (fricgen/langevin/contact_step.py), to 1e-12 per step.

Nine spheres (a pair on the Coulomb branch, one on the viscous branch, a triangle, a pair across the
periodic boundary; test_contact.spheres) under fix nve/sphere with no pair force (pair_style zero): each
step drifts the positions by v dt and the fix updates the velocities and spins of the pairs in contact.
For every step s of a short run, the engine's contact_step (the same seed, the key of step s) from
LAMMPS's velocities and spins at step s and its positions at step s + 1 must give LAMMPS's velocities
and spins at step s + 1. On one rank the fix takes the engine's pair order; on 2 ranks (processors 2 1
1, the periodic pair and the triangle on different ranks) the engine's step applied phase by phase,
the pairs split by the half sub-domain (x < L/4, ... ) of their atom of lower ID.
"""

from __future__ import annotations

import numpy as np
import pytest

from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, State, Thermostat
from fricgen.langevin.contact_step import contact_step
from fricgen.langevin.forces import conservative_forces
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import WCA_RANGE
from fricgen.langevin.records import Bodies, Motion
from fricgen.rng import CONTACT, stream_key

from .helpers import data_file, dump_lines, read_dump, run, vectors
from .test_contact import BOX, DT, EPSILON, KT, LAWS, SEED, spheres

STEPS = 6


def engine_steps(law: str, dim: int, noise: bool, snapshots, box_length: float = BOX, phases=None):
    """The engine's contact step of each step s from LAMMPS's velocities and spins at s and positions at s + 1:
    (velocities, spins) after it, per step. ``phases(position)``: the phase of each particle, the pairs then
    stepped phase after phase, by the phase of their particle of lower index."""
    out = {}
    first = snapshots[0]
    n = len(first["id"])
    particles = Particles.spheres(n)
    bodies = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia)
    box = np.array([box_length, box_length, box_length if dim == 3 else 0.0])
    for s in range(STEPS):
        position = np.ascontiguousarray(vectors(snapshots[s + 1], "x", "y", "z"))
        velocity = np.ascontiguousarray(vectors(snapshots[s], "vx", "vy", "vz"))
        omega = np.ascontiguousarray(vectors(snapshots[s], "omegax", "omegay", "omegaz"))
        wrapped = np.where(box > 0, np.mod(position, np.where(box > 0, box, 1.0)), position)
        state = State(wrapped, velocity, omega, np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), box, dim)
        law_section = Law(name=law, calculus="ito", contact_noise=noise, parameters=LAWS[law])
        config = LangevinConfig(law=law_section, thermostat=Thermostat(kT=KT, dt=DT), epsilon=EPSILON, seed=SEED)
        simulation = Simulation(config, particles, state, load_law_kernels(law))
        dyn = simulation.dynamics()
        force, contact, slope, weight = simulation.step_kernels()
        lists = build_neighbors(state.position, dyn.box, dim, WCA_RANGE + 0.3)
        touching = np.zeros(lists[1].size, dtype=np.bool_)
        conservative_forces(state.position, bodies, dyn, simulation.couplings, force, lists, np.zeros((n, 3)), touching)
        motion = Motion(state.position, state.velocity, state.omega, state.orientation)
        key = np.uint64(stream_key(SEED, s, CONTACT))
        owner = np.repeat(np.arange(n), np.diff(lists[0]))  # the particle of each slot (i of the pair i < k)
        groups = [touching] if phases is None else [touching & (phases(wrapped)[owner] == p) for p in (0, 1)]
        for part in groups:
            contact_step(motion, bodies, dyn, simulation.couplings, (contact, slope, weight), lists, part, key)
        out[s + 1] = (state.velocity.copy(), state.omega.copy())
    return out


def split_spheres(dim: int):
    """spheres(dim) in a box of 12 (half a sub-domain of 2 ranks, 3, exceeds two contact reaches and the skin) with
    the pair of atoms 3, 4 across the ranks' boundary x = 6, the pair of atoms 8, 9 across x = 0 and the triangle
    5, 6, 7 across x = 3, the halves of rank 0: atom 5 in phase 1, 6 and 7 in phase 0."""
    position, velocity, omega = spheres(dim)
    position[2, 0], position[8, 0] = 5.7, 11.32
    position[4:7, 0] = 3.2, 2.18, 2.7
    return position, velocity, omega


def lammps_run(lammps, plugin, folder, law: str, dim: int, noise: bool, ranks: int = 1):
    box, coordinates = (BOX, spheres(dim)) if ranks == 1 else (12.0, split_spheres(dim))
    data_file(folder / "data.spheres", box, dim, *coordinates)
    parameters = " ".join(f"{k} {v!r}" for k, v in LAWS[law].items())
    script = (
        f"units lj\ndimension {dim}\natom_style sphere\natom_modify map array\nboundary p p p\n"
        + ("processors 2 1 1\n" if ranks == 2 else "")
        + f"read_data data.spheres\nset type 1 mass 1.0\nplugin load {plugin}\npair_style zero 1.2\npair_coeff * *\n"
        "comm_modify vel yes\nneighbor 0.3 bin\nneigh_modify every 1 delay 0 check no\nfix 1 all nve/sphere\n"
        + ("fix 3 all enforce2d\n" if dim == 2 else "")
        + f"fix 2 all fricgen/exact/{law} {KT!r} {SEED} noise {'yes' if noise else 'no'} epsilon {EPSILON!r} {parameters}\n"
        f"timestep {DT!r}\n" + dump_lines("dump.steps") + f"run {STEPS}\n"
    )
    output = run(lammps, folder, script, ranks=ranks)
    assert f"on {ranks} procs" in output or ranks == 1
    return read_dump(folder / "dump.steps")


def deviation(snapshots, engine) -> float:
    """The largest |LAMMPS - engine| of velocities and spins over the steps, relative to the largest velocity."""
    worst, scale = 0.0, 0.0
    for step, (velocity, omega) in engine.items():
        got_v, got_w = vectors(snapshots[step], "vx", "vy", "vz"), vectors(snapshots[step], "omegax", "omegay", "omegaz")
        worst = max(worst, np.abs(got_v - velocity).max(), np.abs(got_w - omega).max())
        scale = max(scale, np.abs(velocity).max())
    return worst / scale


def moved(snapshots) -> float:
    """How much the contacts changed the velocities and spins over the run (the drift alone changes neither)."""
    columns = (("vx", "vy", "vz"), ("omegax", "omegay", "omegaz"))
    return max(np.abs(vectors(snapshots[STEPS], *c) - vectors(snapshots[0], *c)).max() for c in columns)


@pytest.mark.parametrize("noise", [False, True], ids=["friction", "friction+noise"])
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("law", sorted(LAWS))
def test_one_rank_is_the_engines_step(lammps, plugin, tmp_path, law, dim, noise):
    snapshots = lammps_run(lammps, plugin(law), tmp_path, law, dim, noise)
    assert moved(snapshots) > 0.05  # the contacts acted
    assert deviation(snapshots, engine_steps(law, dim, noise, snapshots)) < 1e-12


@pytest.mark.parametrize("dim", [2, 3])
def test_two_ranks_are_the_engines_step_phase_by_phase(lammps, plugin, tmp_path, dim):
    """processors 2 1 1 in a box of 12: rank 0 holds x < 6; the phase of an atom is 0 in the lower half of its
    rank's sub-domain (x mod 6 < 3), 1 in the upper. The triangle's pair (6, 7) runs first, in phase 0, where
    one rank would take it last (colour 2): the phases change the sweep, and the test sees it."""
    snapshots = lammps_run(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", dim, True, ranks=2)
    assert moved(snapshots) > 0.05

    def phases(position):
        return (np.mod(position[:, 0], 6.0) >= 3.0).astype(int)

    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots, 12.0, phases)) < 1e-12
    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots, 12.0)) > 1e-6
