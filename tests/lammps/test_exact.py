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

from fricgen.derive.law.catalogues import GENERATED
from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, State, Thermostat
from fricgen.langevin.neighbors import build_neighbors
from fricgen.langevin.pairs import WCA_RANGE
from fricgen.langevin.records import Bodies, Motion
from fricgen.rng import CONTACT, SOLVENT, stream_key, ziggurat_normal

from .. import engine
from .helpers import data_file, dump_lines, read_dump, run, thermo_table, vectors, wrapped
from .test_contact import BOX, DT, EPSILON, KT, LAWS, SEED, spheres

STEPS = 6


def engine_steps(law: str, dim: int, noise: bool, snapshots, box_length: float = BOX, phases=None, calculus: str = "ito"):
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
        inside = wrapped(position, box)
        state = State(inside, velocity, omega, np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)), box, dim)
        law_section = Law(name=law, calculus=calculus, contact_noise=noise, parameters=LAWS[law])
        config = LangevinConfig(law=law_section, thermostat=Thermostat(kT=KT, dt=DT), epsilon=EPSILON, seed=SEED)
        simulation = Simulation(config, particles, state, load_law_kernels(law))
        dyn = simulation.dynamics()
        force, contact, slope, weight = simulation.step_kernels()
        lists = build_neighbors(state.position, dyn.box, dim, WCA_RANGE + 0.3)
        touching = np.zeros(lists[1].size, dtype=np.bool_)
        engine.conservative_forces(state.position, bodies, dyn, simulation.couplings, force, lists, np.zeros((n, 3)), touching)
        motion = Motion(state.position, state.velocity, state.omega, state.orientation)
        key = np.uint64(stream_key(SEED, s, CONTACT))
        owner = np.repeat(np.arange(n), np.diff(lists[0]))  # the particle of each slot (i of the pair i < k)
        groups = [touching] if phases is None else [touching & (phases(inside)[owner] == p) for p in range(4)]
        for part in groups:
            engine.contact_step(motion, bodies, dyn, simulation.couplings, (contact, slope, weight), lists, part, key)
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


def corner_spheres(dim: int):
    """split_spheres(dim) for 2 x 2 ranks (processors 2 2 1, sub-domains 6 x 6) with the pair of atoms 3, 4 across the
    corner (6, 6): atom 3 on the upper right rank, atom 4 on the lower left, below it, so that with newton on the rank of
    atom 4 lists the pair (its ghost partner lies above it) and sends it through a third rank to atom 3's owner."""
    position, velocity, omega = split_spheres(dim)
    position[2, :2], position[3, :2] = (6.3, 6.4), (5.7, 5.7)
    return position, velocity, omega


def _dynamics(plugin, law: str, dim: int, noise: bool, calculus: str = "ito") -> str:
    """The input lines after the atoms: no pair force, fix nve/sphere and the fix (every step reneighboured)."""
    parameters = " ".join(f"{k} {v!r}" for k, v in LAWS[law].items())
    return (
        f"plugin load {plugin}\npair_style zero 1.2\npair_coeff * *\n"
        "comm_modify vel yes\nneighbor 0.3 bin\nneigh_modify every 1 delay 0 check no\nfix 1 all nve/sphere\n"
        + ("fix 3 all enforce2d\n" if dim == 2 else "")
        + f"fix 2 all fricgen/exact/{law} {KT!r} {SEED} noise {'yes' if noise else 'no'} calculus {calculus}"
        f" epsilon {EPSILON!r} {parameters}\n"
        f"timestep {DT!r}\n"
    )


def lammps_run(lammps, plugin, folder, law: str, dim: int, noise: bool, ranks: int = 1, newton: str = "on", runs: str = "", calculus="ito"):
    """STEPS steps dumped every step (or the input lines ``runs`` after the dump) from the nine spheres."""
    box, coordinates = (BOX, spheres(dim)) if ranks == 1 else (12.0, split_spheres(dim) if ranks == 2 else corner_spheres(dim))
    data_file(folder / "data.spheres", box, dim, *coordinates)
    script = (
        f"units lj\ndimension {dim}\natom_style sphere\natom_modify map array\nboundary p p p\nnewton {newton}\n"
        + {1: "", 2: "processors 2 1 1\n", 4: "processors 2 2 1\n"}[ranks]
        + "read_data data.spheres\nset type 1 mass 1.0\n"
        + _dynamics(plugin, law, dim, noise, calculus)
        + dump_lines("dump.steps")
        + (runs or f"run {STEPS}\n")
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
@pytest.mark.parametrize("law", ["coulomb_newton", "smooth_coulomb"])  # closed form; D from noise tables (Stribeck passed too, not kept)
def test_one_rank_is_the_engines_step(lammps, plugin, tmp_path, law, dim, noise):
    snapshots = lammps_run(lammps, plugin(law), tmp_path, law, dim, noise)
    assert moved(snapshots) > 0.05  # the contacts acted
    assert deviation(snapshots, engine_steps(law, dim, noise, snapshots)) < 1e-12


@pytest.mark.parametrize("dim", [2, 3])
def test_one_rank_with_newton_off_is_the_engines_step(lammps, plugin, tmp_path, dim):
    """On one rank the fix shares the pair style's half list; with newton off it holds the periodic pair (8, 9) from
    both atoms, as ghost images of each other: the pair must still be stepped once."""
    snapshots = lammps_run(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", dim, True, newton="off")
    assert moved(snapshots) > 0.05
    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots)) < 1e-12


@pytest.mark.parametrize(
    "law, calculus, dim",
    [
        ("coulomb_newton", "stratonovich", 2),
        ("coulomb_newton", "hk", 3),
        ("smooth_coulomb", "stratonovich", 3),
    ],
)
def test_every_calculus_is_the_engines_step(lammps, plugin, tmp_path, law, calculus, dim):
    """The Stratonovich and Haenggi-Klimontovich drifts of the proposal (theta = 1/2, 1; HK through df/du), one rank
    (each law and calculus costs a compilation of the engine's step, about 20 s: three cases)."""
    snapshots = lammps_run(lammps, plugin(law), tmp_path, law, dim, True, calculus=calculus)
    assert moved(snapshots) > 0.05
    assert deviation(snapshots, engine_steps(law, dim, True, snapshots, calculus=calculus)) < 1e-12
    assert deviation(snapshots, engine_steps(law, dim, True, snapshots)) > 1e-9  # the Ito step differs


@pytest.mark.parametrize("newton", ["on", "off"])
@pytest.mark.parametrize("dim", [2, 3])
def test_two_ranks_are_the_engines_step_phase_by_phase(lammps, plugin, tmp_path, dim, newton):
    """processors 2 1 1 in a box of 12: rank 0 holds x < 6; the phase of an atom is 0 in the lower half of its
    rank's sub-domain (x mod 6 < 3), 1 in the upper. The triangle's pair (6, 7) runs first, in phase 0, where
    one rank would take it last (colour 2): the phases change the sweep, and the test sees it."""
    snapshots = lammps_run(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", dim, True, ranks=2, newton=newton)
    assert moved(snapshots) > 0.05

    def phases(position):
        return (np.mod(position[:, 0], 6.0) >= 3.0).astype(int)

    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots, 12.0, phases)) < 1e-12
    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots, 12.0)) > 1e-6


@pytest.mark.parametrize("dim", [2, 3])
def test_four_ranks_are_the_engines_step_phase_by_phase(lammps, plugin, tmp_path, dim):
    """processors 2 2 1 in a box of 12 (4 ranks on 2 cores: oversubscribed, for correctness): the phase of an atom is
    (x mod 6 >= 3) + 2 (y mod 6 >= 3); the pair across the corner reaches the rank of its lower ID through a third."""
    snapshots = lammps_run(lammps, plugin("coulomb_newton"), tmp_path, "coulomb_newton", dim, True, ranks=4)
    assert moved(snapshots) > 0.05

    def phases(position):
        return (np.mod(position[:, 0], 6.0) >= 3.0).astype(int) + 2 * (np.mod(position[:, 1], 6.0) >= 3.0).astype(int)

    assert deviation(snapshots, engine_steps("coulomb_newton", dim, True, snapshots, 12.0, phases)) < 1e-12


def _lattice_script(plugin, law: str = "coulomb_newton", pair: str = "", box: str = "", nve: bool = True, atom_map: bool = True) -> str:
    """36 discs on a square lattice under lj/cut WCA and the fix (``pair``, ``box`` replace the pair style and the box)."""
    return (
        "units lj\ndimension 2\natom_style sphere\n"
        + ("atom_modify map array\n" if atom_map else "")
        + "lattice sq 0.7639437268\n"
        + (box or "region box block 0 6 0 6 -0.5 0.5\ncreate_box 1 box\n")
        + f"create_atoms 1 box\nset type 1 mass 1.0\nplugin load {plugin}\n"
        + (pair or "pair_style lj/cut 1.122462048309373\npair_coeff * * 1.0 1.0\n")
        + "comm_modify vel yes\n"
        + ("fix 1 all nve/sphere\n" if nve else "")
        + f"fix 2 all fricgen/exact/{law} 1.0 5\nfix 3 all enforce2d\nrun 10\n"
    )


@pytest.mark.parametrize(
    "case, message",
    [
        (
            {"pair": "pair_style fricgen/coulomb_newton 1.0 1\npair_coeff * * 1.0 1.0\n"},
            "would apply the friction of coulomb_newton twice",
        ),
        ({"box": "region box prism 0 6 0 6 -0.5 0.5 0.5 0 0\ncreate_box 1 box\n"}, "triclinic boxes are not supported"),
        ({"nve": False}, "needs fix nve/sphere"),
        ({"atom_map": False}, "needs an atom map: put atom_modify map array before the box is created"),
    ],
    ids=["explicit-pair-style", "triclinic", "no-nve", "no-atom-map"],
)
def test_the_fix_refuses_what_cannot_hold(lammps, plugin, tmp_path, case, message):
    with pytest.raises(AssertionError, match=message):
        run(lammps, tmp_path, _lattice_script(plugin("coulomb_newton"), **case))


def test_sub_domains_too_thin_for_the_phases_are_refused(lammps, plugin, tmp_path):
    """6 x 6 discs on 2 ranks: half a sub-domain (1.96) is within two contact reaches and the skin."""
    with pytest.raises(AssertionError, match="sub-domains too thin along x"):
        run(lammps, tmp_path, "processors 2 1 1\n" + _lattice_script(plugin("coulomb_newton")), ranks=2)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_exact_templates_run(lammps, plugin, tmp_path, dim):
    """in.coulomb_newton_<dim>d_exact as shipped, smaller and shorter, without solvent, on 2 ranks."""
    template = (GENERATED / "lammps" / "coulomb_newton" / f"in.coulomb_newton_{dim}d_exact").read_text()
    cells = 24 if dim == 2 else 12
    shorter = (("nrun index 10000", "nrun index 100"), ("thermo index 1000", "thermo index 50"), ("solvent index 1", "solvent index 0"))
    for old, new in shorter:
        template = template.replace(old, new)
    template = template.replace(f"cells index {100 if dim == 2 else 22}", f"cells index {cells}")
    template = template.replace("plugin index fricgen_coulomb_newton.so", f"plugin index {plugin('coulomb_newton')}")
    output = run(lammps, tmp_path, template, ranks=2)
    rows = thermo_table(output, ["Step", "Temp", "c_trot"])
    assert "Loop time" in output and rows.shape[0] == 3 and (rows[1:, 1:3] > 0.3).all()  # the contacts spin the discs up from rest


NO_FORCE = "pair_style zero 1.2\npair_coeff * *\n"


def free_flight(plugin, noise: bool = True, steps: int = 12000, wca: bool = False) -> str:
    """in.coulomb_newton_2d_exact with 400 discs in free flight (pair_style zero: velocity Verlet is then exact,
    and the contact step is the only dynamics of the velocities) or with its WCA (``wca``), no solvent,
    dt = 5e-3, T sampled every 10 steps after 1000 steps (5 t0)."""
    template = (GENERATED / "lammps" / "coulomb_newton" / "in.coulomb_newton_2d_exact").read_text()
    wca_lines = "pair_style      lj/cut 1.122462048309373\npair_coeff      * * 1.0 1.0\npair_modify     shift yes\n"
    replacements = (
        (wca_lines, wca_lines if wca else NO_FORCE),
        ("cells index 100", "cells index 20"),
        ("solvent index 1", "solvent index 0"),
        ("thermo index 1000", "thermo index 10"),
        ("seed index 12345", "seed index 3"),
        ("plugin index fricgen_coulomb_newton.so", f"plugin index {plugin}"),
        ("kappa_f 5.0 solvent", "kappa_f 5.0" + ("" if noise else " noise no") + " solvent"),
        ("run             ${nrun}", f"run 1000\nrun {steps}"),
    )
    for old, new in replacements:
        assert old in template, old
        template = template.replace(old, new)
    return template


def sampled(output: str) -> dict[str, tuple[float, float]]:
    """Mean and error (20 blocks) of T_trans and T_rot after the first 1000 steps."""
    table = thermo_table(output, ["Step", "Temp", "c_trot"])
    table = table[table[:, 0] > 1000]
    values = {"T_trans": table[: len(table) // 20 * 20, 1], "T_rot": table[: len(table) // 20 * 20, 2]}
    return {name: (v.mean(), v.reshape(20, -1).mean(axis=1).std(ddof=1) / np.sqrt(20)) for name, v in values.items()}


@pytest.mark.parametrize("ranks", [1, 2])
def test_the_fix_keeps_kT_at_dt_5e_3(lammps, plugin, tmp_path, ranks):
    """Free flight (Verlet exact) at dt = 5e-3: T_trans and T_rot at kT within 4 errors (measured on 1 / 2 ranks:
    0.997 +- 0.006 / 1.004 +- 0.004, 1.002 +- 0.005 / 1.000 +- 0.004); without the contact noise they fall
    (negative control, below)."""
    found = sampled(run(lammps, tmp_path, free_flight(plugin("coulomb_newton")), ranks=ranks))
    for name, (value, error) in found.items():
        assert 0.0 < error < 0.01, (name, error)
        assert abs(value - 1.0) < 4.0 * error, f"{name} = {value:.4f} +- {error:.4f} ({found})"


def test_with_wca_the_fix_keeps_kT_at_dt_5e_3(lammps, plugin, tmp_path):
    """With WCA at dt = 5e-3 the step at the end of velocity Verlet's step (B A B C) holds kT (measured here
    0.9993 +- 0.0033 and 0.9953 +- 0.0031; 1.0018 +- 0.0016 in T_trans with 2500 discs); between the half kicks
    (B A C B) T_trans was 0.9813 +- 0.0017, outside the bound below (4 errors of about 0.003)."""
    found = sampled(run(lammps, tmp_path, free_flight(plugin("coulomb_newton"), steps=40000, wca=True)))
    for name, (value, error) in found.items():
        assert 0.0 < error < 0.004, (name, error)
        assert abs(value - 1.0) < 4.0 * error, f"{name} = {value:.4f} +- {error:.4f} ({found})"


def test_without_its_noise_the_fix_cools(lammps, plugin, tmp_path):
    found = sampled(run(lammps, tmp_path, free_flight(plugin("coulomb_newton"), noise=False, steps=2000)))
    assert found["T_trans"][0] < 0.5 and found["T_rot"][0] < 0.5, found


def test_a_restart_continues_the_same_trajectory(lammps, plugin, tmp_path):
    """3 steps, write_restart, read_restart (the fix given again), 3 steps: the velocities and spins of 6 steps in
    one run, bit for bit (2 ranks, 3-D)."""
    library = plugin("coulomb_newton")
    whole = lammps_run(lammps, library, tmp_path, "coulomb_newton", 3, True, ranks=2)
    first = tmp_path / "first"
    first.mkdir()
    lammps_run(lammps, library, first, "coulomb_newton", 3, True, ranks=2, runs=f"run {STEPS // 2}\nwrite_restart restart.half\n")
    (tmp_path / "second").mkdir()
    script = (
        f"atom_modify map array\nprocessors 2 1 1\nread_restart {first / 'restart.half'}\n"
        + _dynamics(library, "coulomb_newton", 3, True)
        + dump_lines("dump.steps")
        + f"run {STEPS // 2}\n"
    )
    run(lammps, tmp_path / "second", script, ranks=2)
    continued = read_dump(tmp_path / "second" / "dump.steps")[STEPS]
    assert moved(whole) > 0.05
    for columns in (("vx", "vy", "vz"), ("omegax", "omegay", "omegaz")):
        assert np.array_equal(vectors(continued, *columns), vectors(whole[STEPS], *columns)), columns


def test_the_fix_solvent_is_the_engines_ornstein_uhlenbeck_step(lammps, plugin, tmp_path):
    """solvent gamma gamma_R: 27 spheres 3 apart (no contacts), one step: v <- c v + s xi, w <- c_R w + s_R xi with
    the engine's normals of the SOLVENT stream (single_particle.kick_drift_solvent), to 1e-14."""
    grid = np.arange(3) * 3.0 + 1.0
    position = np.array([[x, y, z] for x in grid for y in grid for z in grid])
    rng = np.random.default_rng(11)
    velocity, omega = rng.normal(size=position.shape), rng.normal(size=position.shape)
    data_file(tmp_path / "data.spheres", 9.0, 3, position, velocity, omega)
    gamma, gamma_rot, dt, seed = 2.0, 0.15, 0.01, 21
    script = (
        "units lj\ndimension 3\natom_style sphere\natom_modify map array\nboundary p p p\nread_data data.spheres\nset type 1 mass 1.0\n"
        f"plugin load {plugin('coulomb_newton')}\npair_style zero 1.2\npair_coeff * *\ncomm_modify vel yes\nfix 1 all nve/sphere\n"
        f"fix 2 all fricgen/exact/coulomb_newton {KT!r} {seed} solvent {gamma!r} {gamma_rot!r}\ntimestep {dt!r}\n"
        + dump_lines("dump.steps")
        + "run 1\n"
    )
    run(lammps, tmp_path, script)
    before, after = (read_dump(tmp_path / "dump.steps")[s] for s in (0, 1))
    key = np.uint64(stream_key(seed, 0, SOLVENT))
    inertia = 0.4 * 1.0 * 0.25
    c, cr = np.exp(-gamma * dt), np.exp(-gamma_rot / inertia * dt)
    s, sr = np.sqrt(KT * (1 - c * c)), np.sqrt(KT / inertia * (1 - cr * cr))
    xi = np.array([[ziggurat_normal(key, np.uint64(6 * i + j)) for j in range(6)] for i in range(len(position))])
    v0, w0 = vectors(before, "vx", "vy", "vz"), vectors(before, "omegax", "omegay", "omegaz")
    want_v = c * v0 + s * xi[:, [0, 1, 3]]
    want_w = cr * w0 + sr * xi[:, [4, 5, 2]]
    assert np.abs(vectors(after, "vx", "vy", "vz") - want_v).max() < 1e-14
    assert np.abs(vectors(after, "omegax", "omegay", "omegaz") - want_w).max() < 1e-14
    assert np.abs(want_v - v0).max() > 0.1  # the solvent acted
