"""Sweep files: a base configuration, fixed overrides and a grid of axes, checked before anything runs.

A sweep file (format in docs/sweeps.md) has ``base`` (a bundled example or a configuration file
relative to the sweep file), ``[set]`` (overrides of every point, as ``fricgen run --set``),
``[grid]`` (the axes; a point is each combination of their values, in the order of the file) and
an optional ``[plot]``. An axis is a configuration key and its list of values, or a named axis (a
name that is no section of a configuration) whose values are named sets of overrides. Each point
becomes the ``--set`` arguments of one ``fricgen run``; what these mean is checked by the runner's
own validation (:mod:`fricgen.app.sweep.runner`), not here.
"""

from __future__ import annotations

import dataclasses
import difflib
import itertools
import json
import math
import re
from dataclasses import dataclass
from pathlib import Path

from ...errors import ConfigError
from ...schema import Section, structure, unknown_key
from ..run.config import EXAMPLES, RunConfig, example_names, read_toml

KEYS = ("base", "set", "grid", "plot")
#: Most points of a sweep: each is checked (its configuration built) before anything runs, and each
#: is a folder of its own; a larger grid is refused at once, before it is planned.
MAX_POINTS = 10_000
SECTIONS = tuple(f.name for f in dataclasses.fields(RunConfig))
#: What a point's folder name may hold (anything else in a value becomes "-").
SAFE = re.compile(r"[^A-Za-z0-9_.+-]")
NAME = re.compile(r"[A-Za-z0-9_+-]+")


@dataclass(frozen=True)
class Axis:
    """One axis of the grid: ``name`` is a configuration key (a key axis) or the name of a named axis;
    ``values`` are the key's values or the names of the override sets, ``overrides`` the keys and
    values that each sets, ``label`` its name in point names."""

    name: str
    values: tuple
    overrides: tuple[dict, ...]
    label: str

    @property
    def keyed(self) -> bool:
        return "." in self.name


@dataclass(frozen=True)
class Plot(Section):
    """``[plot]``: ``x`` and ``y`` are key axes with numbers, ``color`` a column of results.csv
    (true/false or numbers), ``panels`` an axis with one panel per value."""

    SECTION = "plot"
    x: str
    y: str
    color: str
    panels: str | None = None


@dataclass(frozen=True)
class Point:
    """A state point: its folder name, its value on each axis and its ``--set`` arguments."""

    name: str
    coordinates: dict
    settings: tuple[str, ...]


@dataclass(frozen=True)
class Sweep:
    """A checked sweep file; ``base`` is what ``fricgen run`` takes (an example name or an absolute path)."""

    name: str
    base: str
    settings: tuple[str, ...]
    axes: tuple[Axis, ...]
    plot: Plot | None

    def points(self) -> list[Point]:
        """Every combination of the axes' values, the last axis varying fastest."""
        points = []
        for index in itertools.product(*(range(len(axis.values)) for axis in self.axes)):
            chosen = [(axis, i) for axis, i in zip(self.axes, index)]
            name = "__".join(f"{axis.label}={SAFE.sub('-', label(axis.values[i]))}" for axis, i in chosen)
            settings = [*self.settings, *(setting(k, v) for axis, i in chosen for k, v in axis.overrides[i].items())]
            points.append(Point(name, {axis.name: axis.values[i] for axis, i in chosen}, tuple(settings)))
        return points


def sweep_names() -> list[str]:
    """Names of the bundled sweeps (``fricgen sweep NAME`` reads examples/NAME_sweep.toml)."""
    return sorted(p.stem.removesuffix("_sweep") for p in EXAMPLES.glob("*_sweep.toml"))


def load_sweep(source: str) -> Sweep:
    """The sweep file ``source`` (or the bundled sweep of that name), checked; ConfigError otherwise."""
    path = Path(source)
    if not path.is_file():
        if source not in sweep_names():
            raise ConfigError(
                "SWEEP", f"no file {source!r} and no bundled sweep of that name", f"give a TOML file or one of {sweep_names()}"
            )
        path = EXAMPLES / f"{source}_sweep.toml"
    data = read_toml(path)
    for key in data:
        if key not in KEYS:
            raise unknown_key(key, key, list(KEYS))
    for key in ("set", "grid", "plot"):
        if not isinstance(data.get(key, {}), dict):
            raise ConfigError(key, "must be a table", f"write it as a section [{key}]")
    base = _base(data, path)
    axes = _axes(data.get("grid", {}))
    plot = structure(Plot, data["plot"], "plot") if "plot" in data else None
    if plot is not None:
        _check_plot(plot, axes)
    settings = tuple(setting(key, value) for key, value in _overrides("set", data.get("set", {})).items())
    name = path.stem.removesuffix("_sweep") if path.parent == EXAMPLES else path.stem
    count = math.prod(len(axis.values) for axis in axes)
    if count > MAX_POINTS:
        raise ConfigError("grid", f"has {count:.3g} points, more than a sweep runs ({MAX_POINTS})", "give fewer values, or split the sweep")
    sweep = Sweep(name, base, settings, axes, plot)
    names = [point.name for point in sweep.points()]
    if len(set(names)) < len(names):
        twice = next(text for text in names if names.count(text) > 1)
        raise ConfigError("grid", f"two points have the folder name {twice}", "give values that differ in letters, digits, _ . + -")
    return sweep


def _base(data: dict, path: Path) -> str:
    base = data.get("base")
    if not isinstance(base, str):
        raise ConfigError(
            "base", "missing" if base is None else f"must be a string, got {base!r}", f'give base = "NAME" of {example_names()} or a file'
        )
    file = path.parent / Path(base).expanduser()
    if file.is_file():
        return str(file.resolve())
    if base in example_names():
        return base
    raise ConfigError(
        "base",
        f"no file {file} and no bundled example {base!r}",
        f"give a configuration file relative to {path} or one of {example_names()}",
    )


def _axes(grid: dict) -> tuple[Axis, ...]:
    if not grid:
        raise ConfigError("grid", "has no axes", 'give at least one, e.g. "system.packing_fraction" = [0.3, 0.5]')
    axes = []
    for name, value in grid.items():
        if name.split(".")[0] in SECTIONS:
            axes += [_key_axis(key, values) for key, values in flatten({name: value}).items()]
        else:
            axes.append(_named_axis(name, value))
    _unique("grid", [axis.name for axis in axes])
    short = [axis.name.rsplit(".", 1)[-1] for axis in axes]  # a key's last part, unless two axes share it
    return tuple(dataclasses.replace(axis, label=s if short.count(s) == 1 else axis.name) for axis, s in zip(axes, short))


def _key_axis(key: str, values) -> Axis:
    where = f"grid.{key}"
    if not isinstance(values, list) or not values:
        raise ConfigError(where, f"must be a non-empty list of values, got {values!r}", f"write it like {key} = [1.0, 2.0]")
    for value in values:
        if not _plain(value) and not (isinstance(value, list) and all(_plain(v) for v in value)):
            raise ConfigError(where, f"{value!r} is not a number, string, boolean or list of them", "use a named axis for sets of keys")
    _unique(where, [label(v) for v in values])
    return Axis(key, tuple(values), tuple({key: v} for v in values), key)


def _named_axis(name: str, variants) -> Axis:
    where = f"grid.{name}"
    if not isinstance(variants, dict) or not all(isinstance(v, dict) for v in variants.values()):
        close = difflib.get_close_matches(name.split(".")[0], SECTIONS, n=1)
        hint = f"did you mean the section {close[0]!r}? " if close else ""
        raise ConfigError(
            where,
            f"{name!r} is no section, so it is a named axis, whose values are tables of overrides",
            f"{hint}write e.g. [{where}] a = {{}}",
        )
    if not NAME.fullmatch(name) or not variants:
        raise ConfigError(
            where, "a named axis needs a plain name and at least one named set", 'write e.g. [grid.model] plain = {"law.friction" = false}'
        )
    for variant in variants:
        if not NAME.fullmatch(variant):
            raise ConfigError(f"{where}.{variant}", "names a folder: use letters, digits, _, + and -", "rename it")
    return Axis(name, tuple(variants), tuple(_overrides(f"{where}.{v}", o) for v, o in variants.items()), name)


def _check_plot(plot: Plot, axes: tuple[Axis, ...]) -> None:
    names = {axis.name: axis for axis in axes}
    for key in ("x", "y", "panels"):
        name = getattr(plot, key)
        if name is not None and name not in names:
            raise ConfigError(f"plot.{key}", f"{name!r} is not an axis of the grid", f"choose one of {list(names)}")
    for key in ("x", "y"):
        axis = names[getattr(plot, key)]
        if not axis.keyed or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in axis.values):
            raise ConfigError(f"plot.{key}", f"the axis {axis.name!r} does not have numbers", "choose a key axis with numbers")
    if plot.x == plot.y:
        raise ConfigError("plot.y", f"is the same axis as plot.x ({plot.x!r})", "choose another axis")
    for axis in axes:
        if axis.name not in (plot.x, plot.y, plot.panels) and len(axis.values) > 1:
            raise ConfigError(
                "plot", f"the axis {axis.name!r} has {len(axis.values)} values, whose points would overlap", "name it as panels"
            )


def _overrides(where: str, table: dict) -> dict:
    """A table of overrides as ``section.key`` -> value (nested tables by their dotted keys)."""
    flat = flatten(table)
    for key in flat:
        if "." not in key:
            raise ConfigError(f"{where}.{key}", "is not SECTION.KEY", "write e.g. system.n = 256")
        if key.split(".")[0] not in SECTIONS:
            raise unknown_key(f"{where}.{key}", key.split(".")[0], list(SECTIONS))
    return flat


def flatten(table: dict, prefix: str = "") -> dict:
    """Nested tables as dotted keys (``{"a": {"b": 1}}`` -> ``{"a.b": 1}``); an empty nested table is a value."""
    flat = {}
    for key, value in table.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            for inner, leaf in flatten(value, f"{path}.").items():
                if inner in flat:
                    raise ConfigError(inner, "is given twice", "keep one")
                flat[inner] = leaf
        elif path in flat:
            raise ConfigError(path, "is given twice", "keep one")
        else:
            flat[path] = value
    return flat


def _plain(value) -> bool:
    return isinstance(value, bool | int | float | str)


def _unique(where: str, texts: list[str]) -> None:
    for text in texts:
        if texts.count(text) > 1:
            raise ConfigError(where, f"{text} is given twice", "keep one")


def label(value) -> str:
    """A value as it appears in a point's name: ``0.5``, ``true``, ``ito``, ``20.0x18.0``."""
    if isinstance(value, list | tuple):
        return "x".join(label(v) for v in value)
    return value if isinstance(value, str) else toml_value(value)


def toml_value(value) -> str:
    """``value`` in TOML syntax, read back unchanged by ``--set KEY=TEXT``."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int | float):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    return "{" + ", ".join(f"{json.dumps(k, ensure_ascii=False)} = {toml_value(v)}" for k, v in value.items()) + "}"


def setting(key: str, value) -> str:
    """The ``--set`` argument for ``key = value`` (:func:`~fricgen.app.run.config.parse_override` reads it back)."""
    return f"{key}={toml_value(value)}"
