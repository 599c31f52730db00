"""The plugin's noise does not depend on the domain decomposition: 1 and 2 MPI ranks, newton_pair on
and off, give the same trajectory to round-off over the first steps, Coulomb–Newton alone and overlaid
with a rolling law.

The contact noise is keyed on (seed, step, atom IDs), never on a rank's random stream, so the only
difference between decompositions is the order in which each atom's pair forces are summed. The
runs integrate friction and its noise with fix nve/sphere and no solvent (fix langevin draws its
noise per rank), in 2-D and 3-D.
"""

from __future__ import annotations

import numpy as np
import pytest

from .helpers import data_file, dump_lines, read_dump, run, vectors

STEPS = 20


def lattice(dim: int):
    """A square (2-D, area fraction 0.6) or simple cubic (3-D, volume fraction 0.3) lattice with random
    velocities and spins: the atom IDs are the same for any decomposition (create_atoms would number
    atoms rank by rank)."""
    cells, spacing = (18, 1.1441) if dim == 2 else (7, 1.1791)
    grid = np.stack(np.meshgrid(*[np.arange(cells)] * dim, indexing="ij"), -1).reshape(-1, dim) * spacing
    position = np.zeros((len(grid), 3))
    position[:, :dim] = grid + 0.25
    rng = np.random.default_rng(11)
    velocity, omega = rng.normal(size=position.shape) * 1.7, rng.normal(size=position.shape) * 3.0
    if dim == 2:
        velocity[:, 2], omega[:, :2] = 0.0, 0.0
    return cells * spacing, position, velocity - velocity.mean(axis=0), omega


def script(plugin, dim: int, newton: str, rolling=None) -> str:
    """Coulomb–Newton, overlaid with rolling Coulomb–Newton (the plugin ``rolling``) if given."""
    if rolling is None:
        pair = f"plugin load {plugin}\npair_style fricgen/coulomb_newton 1.0 99\npair_coeff * * 1.0 1.0 gamma_f 6.0 kappa_f 5.0\n"
    else:
        pair = (
            f"plugin load {plugin}\nplugin load {rolling}\n"
            "pair_style hybrid/overlay fricgen/coulomb_newton 1.0 99 fricgen/rolling_coulomb_newton 1.0 99\n"
            "pair_coeff * * fricgen/coulomb_newton 1.0 1.0 gamma_f 6.0 kappa_f 5.0\n"
            "pair_coeff * * fricgen/rolling_coulomb_newton 1.0 1.0 gamma_r 6.0 kappa_r 5.0\n"
        )
    return (
        f"units lj\ndimension {dim}\natom_style sphere\nboundary p p p\nnewton {newton}\nread_data data.lattice\n"
        f"set type 1 mass 1.0\n{pair}"
        "comm_modify vel yes\nneighbor 0.3 bin\nneigh_modify every 1 delay 0 check yes\nfix 1 all nve/sphere\n"
        + ("fix 2 all enforce2d\n" if dim == 2 else "")
        + "timestep 0.002\n"
        + dump_lines("dump.trajectory", STEPS)
        + f"run {STEPS}\n"
    )


@pytest.mark.parametrize("rolling", [False, True], ids=["sliding", "sliding+rolling"])
@pytest.mark.parametrize("dim", [2, 3])
def test_one_and_two_ranks_and_newton_off_agree(lammps, plugin, tmp_path, dim, rolling):
    """(With a rolling law overlaid too: its couples and its noise, keyed on the atom IDs as well.)"""
    box, *state = lattice(dim)
    runs = {}
    extra = plugin("rolling_coulomb_newton") if rolling else None
    for ranks, newton in ((1, "on"), (2, "on"), (2, "off")):
        folder = tmp_path / f"{ranks}-{newton}"
        folder.mkdir()
        data_file(folder / "data.lattice", box, dim, *state)
        output = run(lammps, folder, script(plugin("coulomb_newton"), dim, newton, extra), ranks=ranks)
        assert f"on {ranks} procs" in output
        runs[ranks, newton] = read_dump(folder / "dump.trajectory")
    reference = runs[1, "on"]
    moved = vectors(reference[STEPS], "x", "y", "z") - vectors(reference[0], "x", "y", "z")
    assert np.abs(moved).max() > 1e-3  # the atoms moved: a trajectory, not a start
    for key, snapshots in runs.items():
        for step in (0, STEPS):
            for columns in (("x", "y", "z"), ("vx", "vy", "vz"), ("omegax", "omegay", "omegaz"), ("fx", "fy", "fz")):
                got, want = vectors(snapshots[step], *columns), vectors(reference[step], *columns)
                scale = max(np.abs(want).max(), 1.0)
                assert np.abs(got - want).max() <= 1e-10 * scale, (key, step, columns, np.abs(got - want).max())
