"""A sweep's results: one table row per point and the phase diagram over two axes.

A row holds the point's name, its value on each axis (the name of the override set on a named
axis), its ``status`` (``done``, or why it has no summary) and every scalar of its summary.json
by dotted key (``T_trans.mean``, ``mips.phase_separated``); lists (profiles, histograms) stay in the
point's folder. The phase diagram marks each point at (x, y) by a column: true/false as filled and
open markers, numbers by colour; one panel per value of the ``panels`` axis.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ...errors import ConfigError
from ..run.outputs import SUMMARY
from .config import Plot, Point, flatten, label, toml_value


def coordinate(value):
    """A point's value on an axis as the table holds it (a list as its label, ``20.0x18.0``)."""
    return label(value) if isinstance(value, list) else value


def result_row(point: Point, folder: Path, status: str) -> dict:
    """The table row of a point whose folder is ``folder``."""
    row = {"point": point.name, **{axis: coordinate(value) for axis, value in point.coordinates.items()}, "status": status}
    if status == "done":
        summary = flatten(json.loads((folder / SUMMARY).read_text()))
        row |= {key: value for key, value in summary.items() if value is None or isinstance(value, bool | int | float | str)}
    return row


def write_table(rows: list[dict], path: Path) -> Path:
    """``rows`` as CSV, columns in the order they first appear; true/false as in TOML, empty for none."""
    columns = list(dict.fromkeys(key for row in rows for key in row))
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, columns, restval="")
        writer.writeheader()
        for row in rows:
            writer.writerow({key: _cell(value) for key, value in row.items()})
    return path


def _cell(value):
    return "" if value is None else toml_value(value) if isinstance(value, bool) else value


def phase_diagram(rows: list[dict], plot: Plot, panels: tuple, path: Path) -> Path:
    """Each point at (plot.x, plot.y), marked by the column plot.color; one panel per value in
    ``panels`` of the axis plot.panels (one panel without it). ConfigError if there is no such column."""
    columns = list(dict.fromkeys(key for row in rows for key in row))
    if plot.color not in columns:
        raise ConfigError(
            "plot.color", f"results.csv has no column {plot.color!r}", f"choose one of {columns} and run the sweep again (no point reruns)"
        )
    figure = Figure(figsize=(4.2 * len(panels) + 1.2, 4), layout="constrained")
    axes = np.atleast_1d(figure.subplots(1, len(panels), sharex=True, sharey=True))
    values = [row.get(plot.color) for row in rows]
    numeric = [v for v in values if isinstance(v, int | float) and not isinstance(v, bool)]
    limits = (min(numeric), max(numeric)) if numeric else (0, 1)
    scales = []
    for axis, panel in zip(axes, panels):
        chosen = [row for row in rows if plot.panels is None or row[plot.panels] == coordinate(panel)]
        scales.append(_draw(axis, chosen, plot, limits))
        axis.set(xlabel=plot.x, title=plot.color if plot.panels is None else f"{plot.panels} = {panel}")
    axes[0].set_ylabel(plot.y)
    mappable = next((scale for scale in scales if scale is not None), None)
    if mappable is not None:
        figure.colorbar(mappable, ax=list(axes), label=plot.color)
    else:
        marks = {text: handle for axis in axes for handle, text in zip(*axis.get_legend_handles_labels())}
        figure.legend(marks.values(), marks.keys(), loc="outside right upper", fontsize="small", title=plot.color)
    figure.savefig(path, dpi=120)
    return path


def _draw(axis, rows: list[dict], plot: Plot, limits: tuple[float, float]):
    """One panel; returns the colour scale of numeric values (None for true/false)."""
    x = np.array([row[plot.x] for row in rows], dtype=float)
    y = np.array([row[plot.y] for row in rows], dtype=float)
    values = [row.get(plot.color) for row in rows]
    marks = {
        "true": ([v is True for v in values], {"color": "tab:red"}),
        "false": ([v is False for v in values], {"facecolors": "none", "edgecolors": "tab:blue"}),
        "no value": ([v is None or isinstance(v, str) for v in values], {"marker": "x", "color": "grey"}),
    }
    number = np.ones(len(rows), dtype=bool)
    for text, (chosen, style) in marks.items():
        chosen = np.array(chosen, dtype=bool)
        number &= ~chosen
        if chosen.any():
            axis.scatter(x[chosen], y[chosen], s=80, label=text, **style)
    if not number.any():
        return None
    colours = np.array([values[i] for i in np.flatnonzero(number)], dtype=float)
    return axis.scatter(x[number], y[number], c=colours, s=80, cmap="viridis", vmin=limits[0], vmax=limits[1])
