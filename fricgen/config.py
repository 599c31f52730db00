"""Run configurations from TOML, checked in full (keys, types, values; :mod:`fricgen.build` adds the
law, its kernels and the initial state) before anything is written. One section per dataclass
below, a key per field; missing keys take the defaults. Units: sigma = 1 (the diameter of a sphere
of radius 1/2), kT = 1, m = 1, t0 = sqrt(m sigma^2 / kT).
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import tomllib
import typing
from dataclasses import dataclass, field
from pathlib import Path
from types import UnionType

from derive.lawdata import CALCULI

from .observables import OBSERVABLES
from .system import CLOSE_PACKING, RANDOM_LIMIT

EXAMPLES = Path(__file__).with_name("examples")


class ConfigError(ValueError):
    """A configuration that cannot run: names the key, the problem and the fix."""

    def __init__(self, key: str, problem: str, fix: str = ""):
        self.key = key
        super().__init__(f"{key}: {problem}" + (f"; {fix}" if fix else ""))


@dataclass(frozen=True)
class System:
    """``[system]``: ``dimension`` 2 or 3; ``n`` and ``packing_fraction`` (a cubic box), or ``box`` =
    [Lx, Ly(, Lz)] with one of them; sphere ``radius``, ``mass`` (I = 2/5 m R^2); ``epsilon`` of WCA
    (F-34) in kT; ``start`` "lattice" or "random". With walls the packing fraction counts the slab
    the particles can reach, |y - Ly/2| <= half_width - 2 radius (the paper's accessible volume)."""

    dimension: int = 2
    n: int | None = None
    packing_fraction: float | None = None
    box: tuple[float, ...] | None = None
    radius: float = 0.5
    mass: float = 1.0
    epsilon: float = 1.0
    start: str = "lattice"


@dataclass(frozen=True)
class Law:
    """``[law]``: catalogue ``name``, ``calculus`` of the noise amplitude D (ito, stratonovich, hk),
    ``friction`` and ``contact_noise`` switches (no noise: the inconsistent model), and
    ``[law.parameters]`` NAME = value overrides of the law's defaults."""

    name: str = "coulomb_newton"
    calculus: str = "ito"
    friction: bool = True
    contact_noise: bool = True
    parameters: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Thermostat:
    """``[thermostat]``: ``kT``, solvent ``gamma`` (kT t0 / sigma^2) and ``gamma_rot`` (kT t0) of
    (F-39, 40), 0 for none; time step ``dt`` in t0."""

    kT: float = 1.0
    gamma: float = 3 * math.pi
    gamma_rot: float = math.pi
    dt: float = 1e-3


@dataclass(frozen=True)
class Active:
    """``[active]``: ``force`` F0 (kT / sigma) along each particle's body axis e1."""

    force: float = 0.0


@dataclass(frozen=True)
class Bulk:
    """``[bulk]``: ``force`` = [Fx, Fy(, Fz)] (kT / sigma) on every mobile particle."""

    force: tuple[float, ...] = ()


@dataclass(frozen=True)
class Walls:
    """``[walls]``: two walls of immobile spheres at y = Ly/2 +- ``half_width`` + ``roughness`` zeta_j
    on a square lattice of constant ``spacing`` (F-42; needs ``system.box``)."""

    half_width: float
    roughness: float = 0.0
    spacing: float = 1.0


@dataclass(frozen=True)
class Run:
    """``[run]``: ``steps`` in all, the first ``equilibrate`` left out of the averages, noise ``seed``,
    ``chunk`` = steps between observer calls (and Ctrl-C checks)."""

    steps: int = 10_000
    equilibrate: int = 0
    seed: int = 1
    chunk: int = 1000


@dataclass(frozen=True)
class Output:
    """``[output]``: ``observables`` (see :mod:`fricgen.observables`) every ``period`` steps, GSD frames
    every ``trajectory_period`` (0: none), checkpoints every ``checkpoint_period`` (0: only at the
    end or on Ctrl-C), ``profile_bins`` slabs of the velocity profile; periods are multiples of
    ``run.chunk``."""

    period: int = 1000
    trajectory_period: int = 10_000
    checkpoint_period: int = 0
    observables: tuple[str, ...] = ("temperatures",)
    profile_bins: int = 40


@dataclass(frozen=True)
class RunConfig:
    """A validated configuration; ``walls`` is None without a ``[walls]`` section."""

    system: System = field(default_factory=System)
    law: Law = field(default_factory=Law)
    thermostat: Thermostat = field(default_factory=Thermostat)
    active: Active = field(default_factory=Active)
    bulk: Bulk = field(default_factory=Bulk)
    walls: Walls | None = None
    run: Run = field(default_factory=Run)
    output: Output = field(default_factory=Output)

    def as_dict(self) -> dict:
        return dataclasses.asdict(self)


SECTIONS = {
    "system": System,
    "law": Law,
    "thermostat": Thermostat,
    "active": Active,
    "bulk": Bulk,
    "walls": Walls,
    "run": Run,
    "output": Output,
}


def example_names() -> list[str]:
    """Names of the bundled example configurations (``fricgen run NAME``)."""
    return sorted(p.stem for p in EXAMPLES.glob("*.toml"))


def resolve_source(source: str) -> Path:
    """The TOML file ``source``, or the bundled example of that name (``passive``, ...)."""
    path = Path(source)
    if path.is_file():
        return path
    example = EXAMPLES / f"{source}.toml"
    if path.name == source and example.is_file():
        return example
    raise ConfigError("CONFIG", f"no file {source!r} and no bundled example of that name", f"give a TOML file or one of {example_names()}")


def parse_override(text: str) -> tuple[str, object]:
    """``section.key=VALUE`` with VALUE in TOML syntax (a bare word is a string)."""
    key, sep, value = text.partition("=")
    if not sep or "." not in key:
        raise ConfigError(f"--set {text}", "expected SECTION.KEY=VALUE", "for example --set system.n=256")
    try:
        parsed = tomllib.loads(f"value = {value}")["value"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return key.strip(), parsed


def load_config(path: Path, overrides: list[tuple[str, object]] = ()) -> RunConfig:
    """Read, override (``section.key`` paths) and validate a configuration (no files written)."""
    try:
        data = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(str(path), f"not valid TOML: {error}", "fix the syntax at that line") from error
    for key, value in overrides:
        *sections, name = key.split(".")
        table = data
        for section in sections:
            table = table.setdefault(section, {})
            if not isinstance(table, dict):
                raise ConfigError(key, f"{section} is not a table", "override a key inside a section, e.g. system.n")
        table[name] = value
    config = _structure(data)
    _check_values(config)
    return config


def _describe(hint) -> tuple[str, str]:
    """What a value of type ``hint`` is, and how TOML writes one."""
    if typing.get_origin(hint) is tuple:
        return ("a list of numbers", "[1.0, 2.0]") if typing.get_args(hint)[0] is float else ("a list of strings", '["temperatures"]')
    if typing.get_origin(hint) is dict:
        return "a table of numbers", "a section [law.parameters] with NAME = 1.0 lines"
    return {int: ("an integer", "64"), float: ("a number", "0.6"), bool: ("true or false", "true"), str: ("a string", '"ito" (quoted)')}[
        hint
    ]


def _coerce(key: str, value, hint):
    """``value`` as the type ``hint`` (int, float, bool, str, tuple[float|str, ...], dict[str, float]) or ConfigError."""
    if typing.get_origin(hint) is UnionType:
        hint = typing.get_args(hint)[0]  # X | None: None is the default, TOML cannot write it
    origin = typing.get_origin(hint)
    if origin is tuple and isinstance(value, list):
        item = typing.get_args(hint)[0]
        return tuple(_coerce(f"{key}[{i}]", v, item) for i, v in enumerate(value))
    if origin is dict and isinstance(value, dict):
        return {name: _coerce(f"{key}.{name}", v, float) for name, v in value.items()}
    if hint is float and isinstance(value, int | float) and not isinstance(value, bool):
        return float(value)
    if origin is None and isinstance(value, hint) and (hint is bool or not isinstance(value, bool)):
        return value
    shown = f"{value!r} ({type(value).__name__})" if not isinstance(value, dict) else "a table"
    what, example = _describe(hint)
    raise ConfigError(key, f"must be {what}, got {shown}", f"write it like {example}")


def _unknown(key: str, name: str, known: list[str]) -> ConfigError:
    close = difflib.get_close_matches(name, known, n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    return ConfigError(key, "unknown key", f"{hint}known keys here: {', '.join(known)}")


def _structure(data: dict) -> RunConfig:
    sections = {}
    for section, values in data.items():
        if section not in SECTIONS:
            raise _unknown(f"[{section}]", section, list(SECTIONS))
        if not isinstance(values, dict):
            raise ConfigError(section, "must be a table", f"write it as a section [{section}] with key = value lines")
        cls = SECTIONS[section]
        hints = typing.get_type_hints(cls)
        for name in values:
            if name not in hints:
                raise _unknown(f"{section}.{name}", name, list(hints))
        missing = [f.name for f in dataclasses.fields(cls) if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING]
        for name in missing:
            if name not in values:
                raise ConfigError(f"{section}.{name}", "missing", f"[{section}] needs {name} = ...")
        sections[section] = cls(**{name: _coerce(f"{section}.{name}", value, hints[name]) for name, value in values.items()})
    return RunConfig(**sections)


def require(condition: bool, key: str, problem: str, fix: str) -> None:
    """Raise ConfigError(key, problem, fix) unless ``condition``."""
    if not condition:
        raise ConfigError(key, problem, fix)


def _check_values(c: RunConfig) -> None:
    _check_system(c)
    if c.walls is not None:
        _check_walls(c)
    _check_dynamics(c)
    _check_run(c)


def _check_system(c: RunConfig) -> None:
    s = c.system
    require(s.dimension in (2, 3), "system.dimension", f"must be 2 or 3, got {s.dimension}", "set dimension = 2 or 3")
    for key in ("radius", "mass"):
        require(getattr(s, key) > 0, f"system.{key}", f"must be positive, got {getattr(s, key)}", "give a positive value")
    require(s.epsilon >= 0, "system.epsilon", f"must be >= 0, got {s.epsilon}", "give the WCA strength in kT")
    require(s.start in ("lattice", "random"), "system.start", f"must be 'lattice' or 'random', got {s.start!r}", 'set start = "lattice"')
    if s.box is None:
        require(s.n is not None and s.packing_fraction is not None, "system", "needs n and packing_fraction, or a box", "add them")
        require(c.walls is None, "system.box", "slab walls need an explicit box (taller than 2 half_width)", "add box = [Lx, Ly(, Lz)]")
    else:
        require(len(s.box) == s.dimension, "system.box", f"needs {s.dimension} lengths, got {len(s.box)}", "give [Lx, Ly] or [Lx, Ly, Lz]")
        require(all(x > 0 for x in s.box), "system.box", f"lengths must be positive, got {list(s.box)}", "give positive lengths")
        require((s.n is None) != (s.packing_fraction is None), "system", "with a box give one of n and packing_fraction", "remove one")
    if s.n is not None:
        require(s.n >= 2, "system.n", f"needs at least 2 particles, got {s.n}", "give n >= 2")
    if s.packing_fraction is not None:
        check_fraction("system.packing_fraction", s.packing_fraction, s)


def _check_walls(c: RunConfig) -> None:
    w, ly = c.walls, c.system.box[1]
    require(w.roughness >= 0, "walls.roughness", f"must be >= 0, got {w.roughness}", "give delta_w >= 0 (0: smooth walls)")
    require(w.spacing > 0, "walls.spacing", f"must be positive, got {w.spacing}", "give the walls' lattice constant (the paper: 1)")
    require(
        2 * w.half_width < ly and slab_half_height(c) > 0,
        "walls.half_width",
        f"{w.half_width} leaves no room: need 2 radius + 3 roughness < half_width < Ly/2 = {ly / 2:g}",
        "change half_width or system.box[1]",
    )


def _check_dynamics(c: RunConfig) -> None:
    t, dim = c.thermostat, c.system.dimension
    for key in ("kT", "dt"):
        require(getattr(t, key) > 0, f"thermostat.{key}", f"must be positive, got {getattr(t, key)}", "give a positive value")
    for key in ("gamma", "gamma_rot"):
        require(getattr(t, key) >= 0, f"thermostat.{key}", f"must be >= 0, got {getattr(t, key)}", "give 0 (no solvent) or more")
    require(math.isfinite(c.active.force), "active.force", "must be finite", "give F0 in kT/sigma")
    require(len(c.bulk.force) in (0, dim), "bulk.force", f"needs {dim} components", "give [Fx, Fy] in 2-D, [Fx, Fy, Fz] in 3-D")
    require(all(map(math.isfinite, c.bulk.force)), "bulk.force", "must be finite", "give the force in kT/sigma")
    require(c.law.calculus in CALCULI, "law.calculus", f"must be one of {CALCULI}, got {c.law.calculus!r}", 'for example calculus = "ito"')


def _check_run(c: RunConfig) -> None:
    r, o = c.run, c.output
    require(r.steps >= 1, "run.steps", f"must be >= 1, got {r.steps}", "give the number of steps")
    require(0 <= r.equilibrate < r.steps, "run.equilibrate", f"must be in [0, steps = {r.steps}), got {r.equilibrate}", "lower it")
    require(r.seed >= 0, "run.seed", f"must be >= 0, got {r.seed}", "give a non-negative integer")
    require(r.chunk >= 1, "run.chunk", f"must be >= 1, got {r.chunk}", "give the steps between observer calls, e.g. 1000")
    for key in ("period", "trajectory_period", "checkpoint_period"):
        value = getattr(o, key)
        smallest = "a positive" if key == "period" else "0 (never) or a positive"
        allowed = (value > 0 or (value == 0 and key != "period")) and value % r.chunk == 0
        require(allowed, f"output.{key}", f"must be {smallest} multiple of run.chunk = {r.chunk}, got {value}", "adjust it or run.chunk")
    for name in o.observables:
        require(name in OBSERVABLES, "output.observables", f"unknown observable {name!r}", f"choose from {list(OBSERVABLES)}")
    require(o.profile_bins >= 1, "output.profile_bins", f"must be >= 1, got {o.profile_bins}", "give the number of slabs along y")


def check_fraction(key: str, fraction: float, s: System) -> None:
    """A packing fraction below close packing (and the random-start limit), else ConfigError at ``key``."""
    densest = CLOSE_PACKING[s.dimension]
    require(
        0 < fraction < densest,
        key,
        f"{fraction:g} is impossible: close packing is {densest:.4f} in {s.dimension}-D",
        "give a smaller value",
    )
    if s.start == "random":
        limit = RANDOM_LIMIT[s.dimension]
        require(fraction <= limit, key, f"{fraction:g} is too dense for a random start (at most {limit})", 'use start = "lattice"')


def slab_half_height(c: RunConfig) -> float:
    """Half height of the region where particles start: the accessible slab less 3 roughness."""
    return c.walls.half_width - 2 * c.system.radius - 3 * c.walls.roughness
