"""Rolling and spinning laws in LAMMPS (docs/guide/lammps.md, docs/physics-modes.md): the pair style of a
law on a mode exerts the couples of the engine's explicit kick, to 1e-12, and combines with a sliding law's
pair style under pair_style hybrid/overlay; its fix fricgen/exact/<law> takes the engine's pairwise step of
the mode, to 1e-12 per step.

Nine spheres of two kinds (radius 0.5, mass 1 and radius 0.4, mass 0.7: unequal radii, R_eff and mu_m) in
contact: a pair, a triangle across the middle of the box (the boundary between two ranks), a pair across
the periodic boundary and a fast pair, with random velocities and spins. LAMMPS's per-atom force and
torque after `run 0` (noise keyed on step 0 and the atom IDs) against the engine's pair_slots + gather
and mode_slots + gather_modes with the same seed (fricgen/langevin/pairs.py, modes.py). Laws: the
catalogue's rolling_coulomb_newton (a kink and a weight, closed-form D) and a spinning law of a folder of
one's own whose D has no closed form (noise tables for the mode's mobility, in both codes).
"""

from __future__ import annotations

import shutil
import subprocess

import numba
import numpy as np
import pytest

import fricgen
from fricgen.app.cli.lammps import build_plugin, emit_plugin, ziggurat
from fricgen.derive.backends.lammps_plugin.mode_code import STREAMS, ziggurat_support
from fricgen.derive.backends.lammps_plugin.support_code import support
from fricgen.derive.driver import generate
from fricgen.derive.law.catalogues import GENERATED
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, State, Thermostat
from fricgen.langevin.modes import MODE_FIELDS, gather_modes
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import PAIR_FIELDS, TERMS, WCA_RANGE, gather
from fricgen.langevin.records import Bodies, Motion
from fricgen.rng import CONTACT, ROLLING, SPINNING, _word, pair_key, stream_key, ziggurat_normal

from .. import engine
from .helpers import data_file, dump_lines, read_dump, run, vectors, wrapped
from .test_thermostat import temperatures

BOX, SEED, KT, DT, EPSILON = 10.0, 77, 1.3, 2e-3, 1.2
SPINNING_LAW = """name = "spinning_soft"
description = "Saturating spinning friction f = gamma_s u / (1 + u / u0): D in integral form (noise tables)."
friction = "gamma_s*u/(1 + u/u0)"
mode = "spinning"
calculi = ["ito"]

[parameters.gamma_s]
default = 5.0

[parameters.u0]
default = 0.5
"""
PARAMETERS = {
    "coulomb_newton": {"gamma_f": 4.5, "kappa_f": 2.5},
    "rolling_coulomb_newton": {"gamma_r": 4.0, "kappa_r": 0.8},
    "spinning_soft": {"gamma_s": 3.0, "u0": 0.4},
}
#: Per kind: diameter, mass; the pair_coeff sigma of kinds a, b is R_a + R_b, as the engine's sigma_ik.
KINDS = ((1.0, 1.0), (0.8, 0.7))


@pytest.fixture(scope="module")
def laws(lammps, plugin, tmp_path_factory):
    """name -> (the engine's kernels, the built plugin), the spinning law generated in a folder of one's own."""
    root = tmp_path_factory.mktemp("mode-laws")
    folder = root / "laws"
    folder.mkdir()
    (folder / "spinning_soft.toml").write_text(SPINNING_LAW)
    generate(catalogue=folder)
    law_file = folder / "spinning_soft.toml"
    sources, _ = emit_plugin(law_file, out=root / "sources")
    found = {"spinning_soft": (fricgen.load_law("spinning_soft", folder=folder), build_plugin(sources, lammps, law_file, root / "build"))}
    return found | {name: (fricgen.load_law(name), plugin(name)) for name in ("coulomb_newton", "rolling_coulomb_newton")}


def spheres(dim: int):
    """Kinds (0, 1), positions, velocities and spins of 9 spheres in contact (module docstring)."""
    kinds = np.array([0, 1, 0, 0, 1, 1, 1, 0, 0])
    position = np.array(
        [
            [2.0, 2.0, 2.0],
            [2.95, 2.1, 2.0],
            [4.6, 5.0, 2.0],
            [5.55, 5.1, 2.0],
            [5.05, 5.82, 2.0],
            [0.3, 8.0, 2.0],
            [9.45, 8.1, 2.0],
            [2.0, 8.0, 2.0],
            [3.08, 8.0, 2.0],
        ]  # fmt: skip
    )
    rng = np.random.default_rng(7)
    velocity, omega = rng.normal(size=position.shape), rng.normal(size=position.shape) * 2.0
    if dim == 2:
        position[:, 2], velocity[:, 2], omega[:, :2] = 0.0, 0.0, 0.0
    else:
        position[:, 2] += rng.uniform(-0.1, 0.1, size=len(position))
    return kinds, (position, velocity, omega)


def engine_terms(laws, names, dim: int, noise: bool, coordinates, kinds):
    """(force, torque) of the sliding pass (WCA and the law ``names[0]`` if it slides) and the torque of the
    rolling and spinning laws among ``names``, from the engine with the noise impulses over dt."""
    position, velocity, omega = (np.ascontiguousarray(a) for a in coordinates)
    n = len(position)
    radius, mass = np.array([KINDS[k][0] / 2 for k in kinds]), np.array([KINDS[k][1] for k in kinds])
    particles = Particles(radius, mass, 0.4 * mass * radius * radius, np.ones(n, dtype=bool))  # I = c m R R, as the plugin
    box = np.array([BOX, BOX, BOX if dim == 3 else 0.0])
    state = State(position.copy(), velocity.copy(), omega.copy(), np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), box, dim)
    first, *others = names
    extra = {}
    for name in others:
        mode = laws[name][0].mode
        extra |= {mode: name, f"{mode}_parameters": PARAMETERS[name]}
    section = Law(name=first, calculus="ito", contact_noise=noise, parameters=PARAMETERS[first], contact_scheme="explicit", **extra)
    config = LangevinConfig(law=section, thermostat=Thermostat(kT=KT, dt=DT), epsilon=EPSILON, seed=SEED)
    simulation = Simulation(config, particles, state, [laws[name][0] for name in names])
    dyn, couplings = simulation.dynamics(), simulation.couplings
    lists = build_neighbors(state.position, dyn.box, dim, WCA_RANGE + 0.3)
    bodies = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia)
    coordinates = (state.position, state.velocity, state.omega)
    slots, terms = np.zeros((lists[1].size, PAIR_FIELDS)), np.zeros((TERMS, n, 3))
    switches = (np.uint64(stream_key(SEED, 0, CONTACT)), couplings.sliding, noise, True)  # keys as the engine's, uint64
    force, contact, _, weight = simulation.step_kernels()
    kernels = (force, contact, weight)
    engine.pair_slots(coordinates, bodies, dyn, couplings, *kernels, lists, switches, slots)
    gather(particles.radius, lists, slots, terms)
    sliding = (terms[0] + terms[1] + terms[3] / DT, terms[2] + terms[4] / DT)
    modes, keys = np.zeros((TERMS, n, 3)), (np.uint64(stream_key(SEED, 0, ROLLING)), np.uint64(stream_key(SEED, 0, SPINNING)))
    spin_slots = np.zeros((lists[1].size, MODE_FIELDS))
    engine.mode_slots(coordinates, bodies, dyn, couplings, simulation.mode_kernels(), lists, keys, noise, spin_slots)
    gather_modes(n, lists, spin_slots, modes)
    return sliding, modes[2] + modes[4] / DT


def coefficients(name: str, style: str) -> str:
    """pair_coeff lines of a law for both kinds and their pair (``style``: the sub-style's name under hybrid/overlay)."""
    parameters = " ".join(f"{k} {v!r}" for k, v in PARAMETERS[name].items())
    lines = []
    for a, b in ((1, 1), (2, 2), (1, 2)):
        sigma = (KINDS[a - 1][0] + KINDS[b - 1][0]) / 2
        lines.append(f"pair_coeff {a} {b} {style}{EPSILON!r} {sigma!r} {parameters}\n")
    return "".join(lines)


def lammps_terms(lammps, laws, folder, names, dim: int, noise: bool, coordinates, kinds, ranks: int = 1, newton: str = "on"):
    """(force, torque) per atom from LAMMPS with the pair styles of ``names`` (overlaid if more than one)."""
    diameter = np.array([KINDS[k][0] for k in kinds])
    data_file(folder / "data.spheres", BOX, dim, *coordinates, diameter=diameter, types=kinds + 1)
    switch = f"{KT!r} {SEED} noise {'yes' if noise else 'no'}"
    styles = " ".join(f"fricgen/{name} {switch}" for name in names)
    hybrid = len(names) > 1
    script = (
        f"units lj\ndimension {dim}\natom_style sphere\nboundary p p p\nnewton {newton}\nprocessors {ranks} 1 1\n"
        "read_data data.spheres\n"
        f"set type 1 mass {KINDS[0][1]!r}\nset type 2 mass {KINDS[1][1]!r}\n"
        + "".join(f"plugin load {laws[name][1]}\n" for name in names)
        + f"pair_style {'hybrid/overlay ' if hybrid else ''}{styles}\n"
        + "".join(coefficients(name, f"fricgen/{name} " if hybrid else "") for name in names)
        + ("pair_modify neigh/trim no\n" if len(names) > 2 else "")  # LAMMPS 22Jul2025 fails to order 3 trimmed lists
        + f"comm_modify vel yes\nneighbor 0.3 bin\ntimestep {DT!r}\n"
        + dump_lines("dump.forces")
        + "run 0\n"
    )
    output = run(lammps, folder, script, ranks=ranks)
    assert f"{ranks} by 1 by 1 MPI processor grid" in output  # split at x = 5: the triangle and the periodic pair across ranks
    snapshot = read_dump(folder / "dump.forces")[0]
    return vectors(snapshot, "fx", "fy", "fz"), vectors(snapshot, "tqx", "tqy", "tqz")


def assert_equal(got, want, scale):
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-12 * scale)


@pytest.mark.parametrize("noise", [False, True], ids=["friction", "friction+noise"])
@pytest.mark.parametrize(("name", "dim"), [("rolling_coulomb_newton", 2), ("rolling_coulomb_newton", 3), ("spinning_soft", 3)])
def test_a_mode_laws_couples_equal_the_engines(lammps, laws, tmp_path, name, dim, noise):
    """The pair style of a rolling or spinning law alone: no force at all, the engine's torques to 1e-12."""
    kinds, coordinates = spheres(dim)
    force, torque = lammps_terms(lammps, laws, tmp_path, [name], dim, noise, coordinates, kinds)
    _, want = engine_terms(laws, [name], dim, noise, coordinates, kinds)
    assert np.abs(want).max() > 0.1 and (np.abs(want).max(axis=1) > 1e-3).sum() == 9  # every sphere in a contact
    assert not force.any()
    assert_equal(torque, want, np.abs(want).max())
    assert np.abs(torque.sum(axis=0)).max() < 1e-12 * np.abs(want).max()  # couples: tau_k = -tau_i


COMBINED = {
    "2d": (("coulomb_newton", "rolling_coulomb_newton"), 2),
    "3d": (("coulomb_newton", "rolling_coulomb_newton", "spinning_soft"), 3),
}


@pytest.mark.parametrize(("ranks", "newton"), [(1, "on"), (2, "on"), (2, "off")], ids=["1-rank", "2-ranks", "2-ranks-newton-off"])
@pytest.mark.parametrize("case", sorted(COMBINED))
def test_overlaid_laws_on_every_mode_equal_the_engine(lammps, laws, tmp_path, case, ranks, newton):
    """Sliding + rolling (2-D) and sliding + rolling + spinning (3-D) under pair_style hybrid/overlay, with
    their noises, on 1 and 2 ranks: the engine's forces and torques with one seed, to 1e-12."""
    names, dim = COMBINED[case]
    kinds, coordinates = spheres(dim)
    force, torque = lammps_terms(lammps, laws, tmp_path, list(names), dim, True, coordinates, kinds, ranks, newton)
    (want_force, want_torque), mode_torque = engine_terms(laws, names, dim, True, coordinates, kinds)
    want_torque = want_torque + mode_torque
    scale = np.abs(want_force).max()
    assert scale > 1.0 and np.abs(mode_torque).max() > 0.5
    assert_equal(force, want_force, scale)
    assert_equal(torque, want_torque, scale)


def test_spinning_is_refused_in_2d(lammps, laws, tmp_path):
    kinds, coordinates = spheres(2)
    with pytest.raises(AssertionError, match="acts on spinning, which does not exist in 2-D"):
        lammps_terms(lammps, laws, tmp_path, ["spinning_soft"], 2, True, coordinates, kinds)


HARNESS = """#include <cmath>
#include <cstdint>
#include <cstdio>
namespace {
%s
}
int main()
{
  const uint64_t key = stream_key(%d, 3, MODE_STREAM);
  for (uint64_t i = 0; i < %d; ++i) {
    const uint64_t draws = pair_key(key, i, i + 5);
    std::printf("%%a %%a\\n", ziggurat_normal(draws, 0), ziggurat_normal(draws, 1));
  }
}
"""


@numba.njit
def engine_normals(seed, stream, count, table_k):
    """The engine's normals of the pairs (i, i + 5) at step 3, as in fricgen.langevin.modes (uint64 keys), and how
    many of them took the ziggurat's slow branches (u >= K[layer])."""
    key, out, slow = stream_key(seed, 3, stream), np.empty((count, 2)), 0
    for i in range(count):
        draws = pair_key(key, i, i + 5)
        for j in range(2):
            out[i, j] = ziggurat_normal(draws, j)
            z = _word(draws, j)
            slow += (z >> np.uint64(11)) >= table_k[np.int64(z & np.uint64(255))]
    return out, slow


@pytest.mark.parametrize("mode", sorted(STREAMS))
def test_the_ziggurat_in_cpp_draws_the_engines_normals_bit_for_bit(tmp_path, mode):
    """The pair style's normals (mode_code.ziggurat_support) against fricgen.rng.ziggurat_normal for 40 000
    draws, among them some hundred of the ziggurat's rare branches (wedges and the tail)."""
    assert STREAMS == {"rolling": ROLLING, "spinning": SPINNING}
    compiler = shutil.which("c++") or shutil.which("g++")
    assert compiler, "a C++ compiler is needed for tests/lammps"
    count, seed = 20000, 31
    source = tmp_path / "harness.cpp"
    source.write_text(HARNESS % (support() + ziggurat_support(mode, *ziggurat()), seed, count))
    subprocess.run([compiler, "-std=c++17", "-O2", "-ffp-contract=off", str(source), "-o", str(tmp_path / "harness")], check=True)
    printed = subprocess.run([str(tmp_path / "harness")], capture_output=True, text=True, check=True).stdout.split()
    got = np.array([float.fromhex(x) for x in printed]).reshape(count, 2)
    want, slow = engine_normals(seed, STREAMS[mode], count, ziggurat()[0][1])
    assert np.array_equal(got, want)
    assert slow > 100 and np.abs(want).max() > ziggurat()[1]  # the wedges and the tail were drawn


#: The no-solvent fluids, each overlaid on Coulomb–Newton (gamma_f 6, kappa_f 5): 400 discs at area fraction 0.6
#: with the rolling law, dt = 1e-3, 6 t0 sampled every 10 steps; 512 spheres at volume fraction 0.3 with the
#: spinning law, dt = 5e-4 (at 1e-3 the first-order step heats the translation: T_trans = 1.028 +- 0.006, 1.013 +- 0.005,
#: 1.014 +- 0.006 for three seeds; at 5e-4 1.010 +- 0.007, 1.006 +- 0.007, 0.992 +- 0.006), 6 t0 sampled every 20 steps.
#: Per law: dimension, box, parameters, dt, steps.
FLUIDS = {
    "rolling_coulomb_newton": (2, "lattice sq 0.7639437268\nregion box block 0 20 0 20 -0.5 0.5\n", "gamma_r 6.0 kappa_r 5.0", 1e-3, 6000),
    "spinning_soft": (3, "lattice sc 0.6100854603\nregion box block 0 8 0 8 0 8\n", "gamma_s 10.0 u0 1.0", 5e-4, 12000),
}


def fluid(laws, name: str, noise: bool) -> str:
    """The fluid of the law ``name`` (FLUIDS) whose noises are the only thermostat, the law's own noise on or off;
    1000 steps to equilibrate, then ``steps`` sampled 600 times (FLUIDS)."""
    dim, box, parameters, dt, steps = FLUIDS[name]
    return (
        f"units lj\ndimension {dim}\natom_style sphere\nboundary p p p\n{box}create_box 1 box\ncreate_atoms 1 box\n"
        "set type 1 diameter 1.0\nset type 1 mass 1.0\nvelocity all create 1.0 5 mom yes rot no dist gaussian\n"
        f"plugin load {laws['coulomb_newton'][1]}\nplugin load {laws[name][1]}\n"
        f"pair_style hybrid/overlay fricgen/coulomb_newton 1.0 7 fricgen/{name} 1.0 7 noise {'yes' if noise else 'no'}\n"
        f"pair_coeff * * fricgen/coulomb_newton 1.0 1.0 gamma_f 6.0 kappa_f 5.0\npair_coeff * * fricgen/{name} 1.0 1.0 {parameters}\n"
        "neighbor 0.3 bin\nneigh_modify every 1 delay 0 check yes\ncomm_modify vel yes\nfix 1 all nve/sphere\n"
        + ("fix 2 all enforce2d\n" if dim == 2 else "")
        + f"timestep {dt!r}\ncompute trot all temp/sphere dof rotate\nthermo_style custom step temp c_trot\nthermo {steps // 600}\n"
        f"run 1000\nrun {steps}\n"
    )


@pytest.mark.parametrize("name", sorted(FLUIDS))
def test_a_modes_noise_keeps_kT_and_without_it_the_spins_cool(lammps, laws, tmp_path, name):
    """Without a solvent the contact noises are the only thermostat (2 ranks): with the rolling (2-D) or spinning
    (3-D) law's noise T_trans and T_rot stay at kT within 3 errors (20 blocks); with `noise no` on that law's
    style alone T_rot falls by more than 4 errors (the negative control: the sliding noise cannot make up for it)."""
    found = {}
    for noise in (True, False):
        folder = tmp_path / f"noise-{noise}"
        folder.mkdir()
        found[noise] = temperatures(run(lammps, folder, fluid(laws, name, noise), ranks=2))
    for key, (value, error) in found[True].items():
        assert 0.0 < error < 0.02 and abs(value - 1.0) < 3.0 * error, (key, value, error, found)
    value, error = found[False]["T_rot"]
    assert value < 1.0 - 4.0 * error, found


def test_the_rolling_laws_3d_template_runs(lammps, laws, tmp_path):
    template = (GENERATED / "lammps" / "rolling_coulomb_newton" / "in.rolling_coulomb_newton_3d").read_text()
    for old, new in (("cells index 22", "cells index 10"), ("nrun index 10000", "nrun index 200")):
        template = template.replace(f"variable        {old}", f"variable        {new}")
    plugin = laws["rolling_coulomb_newton"][1]
    output = run(lammps, tmp_path, template.replace("plugin index fricgen_rolling_coulomb_newton.so", f"plugin index {plugin}"))
    assert "Loop time" in output and "352 atoms" in output


# --- the exact step of a mode law: fix fricgen/exact/<law> -------------------------------------------------

FIX_STEPS = 6


def fix_run(lammps, laws, folder, name: str, dim: int, noise: bool, coordinates, kinds):
    """FIX_STEPS steps of the nine spheres in free flight (pair_style zero) under fix nve/sphere and the fix of the
    law ``name``, every step dumped."""
    diameter = np.array([KINDS[k][0] for k in kinds])
    data_file(folder / "data.spheres", BOX, dim, *coordinates, diameter=diameter, types=kinds + 1)
    parameters = " ".join(f"{k} {v!r}" for k, v in PARAMETERS[name].items())
    parameters += f" epsilon {EPSILON!r}" if laws[name][0].has_weight else ""  # the weight's WCA epsilon
    script = (
        f"units lj\ndimension {dim}\natom_style sphere\natom_modify map array\nboundary p p p\nread_data data.spheres\n"
        f"set type 1 mass {KINDS[0][1]!r}\nset type 2 mass {KINDS[1][1]!r}\nplugin load {laws[name][1]}\n"
        "pair_style zero 1.2\npair_coeff * *\ncomm_modify vel yes\nneighbor 0.3 bin\nneigh_modify every 1 delay 0 check no\n"
        "fix 1 all nve/sphere\n"
        + ("fix 3 all enforce2d\n" if dim == 2 else "")
        + f"fix 2 all fricgen/exact/{name} {KT!r} {SEED} noise {'yes' if noise else 'no'} {parameters}\n"
        + f"timestep {DT!r}\n"
        + dump_lines("dump.steps")
        + f"run {FIX_STEPS}\n"
    )
    run(lammps, folder, script)
    return read_dump(folder / "dump.steps")


def engine_mode_steps(laws, name: str, dim: int, noise: bool, snapshots, kinds):
    """The engine's contact step (contact_step_modes) of each step s from LAMMPS's velocities and spins at s and
    positions at s + 1: (velocities, spins) after it, by step."""
    n = len(kinds)
    radius, mass = np.array([KINDS[k][0] / 2 for k in kinds]), np.array([KINDS[k][1] for k in kinds])
    particles = Particles(radius, mass, 0.4 * mass * radius * radius, np.ones(n, dtype=bool))
    bodies = Bodies(particles.radius, particles.inv_mass, particles.inv_inertia)
    box = np.array([BOX, BOX, BOX if dim == 3 else 0.0])
    out = {}
    for s in range(FIX_STEPS):
        position = wrapped(vectors(snapshots[s + 1], "x", "y", "z"), box)
        velocity, omega = vectors(snapshots[s], "vx", "vy", "vz"), vectors(snapshots[s], "omegax", "omegay", "omegaz")
        state = State(*(np.ascontiguousarray(a) for a in (position, velocity, omega)), np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), box, dim)
        section = Law(name=name, calculus="ito", contact_noise=noise, parameters=PARAMETERS[name])
        config = LangevinConfig(law=section, thermostat=Thermostat(kT=KT, dt=DT), epsilon=EPSILON, seed=SEED)
        simulation = Simulation(config, particles, state, [laws[name][0]])
        dyn, couplings = simulation.dynamics(), simulation.couplings
        force, contact, slope, weight = simulation.step_kernels()
        lists = build_neighbors(state.position, dyn.box, dim, WCA_RANGE + 0.3)
        touching = np.zeros(lists[1].size, dtype=np.bool_)
        engine.conservative_forces(state.position, bodies, dyn, couplings, force, lists, np.zeros((n, 3)), touching)
        motion = Motion(state.position, state.velocity, state.omega, state.orientation)
        keys = tuple(np.uint64(stream_key(SEED, s, stream)) for stream in (CONTACT, ROLLING, SPINNING))
        law = (contact, slope, weight)
        engine.contact_step_modes(motion, bodies, dyn, couplings, law, simulation.mode_kernels(), lists, touching, keys)
        out[s + 1] = (state.velocity.copy(), state.omega.copy())
    return out


@pytest.mark.parametrize(
    ("name", "dim", "noise"),
    [
        ("rolling_coulomb_newton", 2, True),
        ("rolling_coulomb_newton", 3, True),
        ("rolling_coulomb_newton", 3, False),
        ("spinning_soft", 3, True),
    ],
)
def test_a_mode_laws_fix_is_the_engines_step(lammps, laws, tmp_path, name, dim, noise):
    """The fix of a rolling or spinning law (noise tables for spinning_soft): the engine's pairwise step of the mode,
    velocities untouched and spins to 1e-12 per step, for unequal radii and masses."""
    kinds, coordinates = spheres(dim)
    snapshots = fix_run(lammps, laws, tmp_path, name, dim, noise, coordinates, kinds)
    engine = engine_mode_steps(laws, name, dim, noise, snapshots, kinds)
    scale = max(np.abs(omega).max() for _, omega in engine.values())
    first, last = snapshots[0], snapshots[FIX_STEPS]
    assert np.abs(vectors(last, "omegax", "omegay", "omegaz") - vectors(first, "omegax", "omegay", "omegaz")).max() > 0.01  # it acted
    for step, (velocity, omega) in engine.items():
        np.testing.assert_array_equal(vectors(snapshots[step], "vx", "vy", "vz"), velocity)  # untouched in both
        assert np.abs(vectors(snapshots[step], "omegax", "omegay", "omegaz") - omega).max() < 1e-12 * scale, step


def test_a_spinning_laws_fix_is_refused_in_2d(lammps, laws, tmp_path):
    kinds, coordinates = spheres(2)
    with pytest.raises(AssertionError, match="fix fricgen/exact/spinning_soft acts on spinning, which does not exist in 2-D"):
        fix_run(lammps, laws, tmp_path, "spinning_soft", 2, True, coordinates, kinds)
