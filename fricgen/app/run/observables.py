"""Observables of a run, written as they are measured: CSV tables appended and flushed per row.

Writers say what, :class:`Periodic` says when (every ``period`` steps). A table starts with the
columns ``step`` and ``time`` (= step dt, in t0); a run that stops keeps every row written so far,
and a resumed run appends to it after dropping the rows later than its checkpoint.

- ``temperatures.csv``: ``T_trans``, ``T_rot`` = <m v_a^2>, <I omega_a^2> of the mobile particles.
- ``velocity_profile.csv``: ``vx_j`` and ``wz_j``, the mean v_x and omega_z in slab j of ``bins``
  equal slabs along y (the wall normal), j = 0 at the box's lower edge; empty when no particle is in it.
"""

from __future__ import annotations

import csv
import math
import os
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ...langevin.analysis import block_estimate, temperatures, velocity_profile
from ...langevin.system import Particles

if TYPE_CHECKING:  # a name only: the Poiseuille study reads tables with this module and compiles no engine
    from ...langevin.simulation import Simulation


class Periodic:
    """Calls ``observer`` after the chunks that end on a multiple of ``period`` steps."""

    def __init__(self, observer: Callable[[Simulation], None], period: int):
        self.observer, self.period = observer, period

    def __call__(self, simulation: Simulation) -> None:
        if simulation.state.step % self.period == 0:
            self.observer(simulation)


class Table:
    """Observer that appends the row (step, time, *measure(simulation)) to a CSV file."""

    def __init__(self, path: str | Path, columns: list[str], measure: Callable[[Simulation], np.ndarray]):
        self.path = Path(path)
        new = not self.path.exists()
        self.handle = open(self.path, "a", newline="")
        self.writer = csv.writer(self.handle)
        self.measure = measure
        if new:
            self.writer.writerow(["step", "time", *columns])
            self.handle.flush()

    def __call__(self, simulation: Simulation) -> None:
        values = np.atleast_1d(self.measure(simulation))
        step = simulation.state.step
        time = f"{step * simulation.config.thermostat.dt:.10g}"
        self.writer.writerow([step, time, *("" if math.isnan(v) else f"{v:.10g}" for v in values)])
        self.handle.flush()

    def close(self) -> None:
        self.handle.close()


def observable_table(name: str, folder: Path, particles: Particles, bins: int) -> Table:
    """The writer of observable ``name`` (one of fricgen.app.run.config.OBSERVABLES) into ``folder/name.csv``."""
    path = folder / f"{name}.csv"
    if name == "temperatures":
        return Table(path, ["T_trans", "T_rot"], lambda simulation: np.array(temperatures(simulation.state, particles)))
    columns = [f"vx_{j}" for j in range(bins)] + [f"wz_{j}" for j in range(bins)]
    return Table(path, columns, lambda simulation: np.concatenate(velocity_profile(simulation.state, particles, bins)))


def read_table(path: str | Path) -> tuple[list[str], np.ndarray]:
    """Header and rows (float array, NaN for empty cells) of a table."""
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    values = np.array([[float(x) if x else math.nan for x in row] for row in rows[1:]]).reshape(-1, len(rows[0]))
    return rows[0], values


def truncate_table(path: str | Path, step: int) -> None:
    """Drop the rows after ``step`` (atomically)."""
    path = Path(path)
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    temporary = path.with_name(path.name + ".tmp")
    with open(temporary, "w", newline="") as handle:
        csv.writer(handle).writerows([rows[0], *(row for row in rows[1:] if int(row[0]) <= step)])
    os.replace(temporary, path)


def series_summary(series: np.ndarray) -> dict:
    """Mean and standard error (block averages, up to 20 blocks) of a time series, NaN samples left
    out; ``error`` is None below 4 samples and ``mean`` None without samples."""
    series = np.asarray(series, dtype=float)
    series = series[~np.isnan(series)]
    if series.size < 4:
        return {"mean": float(series.mean()) if series.size else None, "error": None, "samples": int(series.size)}
    estimate = block_estimate(series, blocks=min(20, series.size // 2))
    return {"mean": estimate.mean, "error": estimate.error, "samples": int(series.size)}
