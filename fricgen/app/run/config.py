"""Run configurations from TOML, checked in full (keys, types, values; :mod:`fricgen.app.run.build` adds
the law's kernels and the initial state) before anything is written. One section per dataclass, a
key per field; missing keys take the defaults. ``[law]``, ``[thermostat]``, ``[active]`` and
``[bulk]`` are the Langevin engine's own sections (fricgen.langevin.config; ``law.folder`` is added
here); ``[system]``, ``[walls]``, ``[run]`` and ``[output]`` are defined here. Units: sigma = 1 (the diameter of a
sphere of radius 1/2), kT = 1, m = 1, t0 = sqrt(m sigma^2 / kT).
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from ...errors import ConfigError
from ...langevin.config import Active, Bulk, LangevinConfig, Law, Thermostat
from ...langevin.system import CLOSE_PACKING, RANDOM_LIMIT, ball_volume, cubic_side, memory_estimate
from ...schema import Section, structure

EXAMPLES = Path(__file__).with_name("examples")


#: The observables a run can tabulate (fricgen.app.run.observables writes them).
OBSERVABLES = ("temperatures", "velocity_profile")
#: Most slabs of the velocity profile (each is two columns of its table, every period).
PROFILE_BINS = 10_000
#: The kinds of run that a study analyses (:attr:`RunConfig.kinds`; fricgen.app.run.registry).
KINDS = ("slit_flow", "active")


@dataclass(frozen=True)
class RunLaw(Law):
    """``[law]`` of a run: the engine's law section and ``folder``, a folder of your own law files
    (relative to the configuration file; its kernels in folder/generated/), searched with those of
    ``--laws`` and FRICGEN_LAWS, before the built-in catalogue."""

    folder: str | None = None

    @property
    def folders(self) -> tuple[str, ...]:
        return () if self.folder is None else (self.folder,)

    def engine(self) -> Law:
        """The engine's section (without ``folder``)."""
        return Law(**{f.name: getattr(self, f.name) for f in dataclasses.fields(Law)})


@dataclass(frozen=True)
class System(Section):
    """``[system]``: ``dimension`` 2 or 3; ``n`` and ``packing_fraction`` (a cubic box), or ``box`` =
    [Lx, Ly(, Lz)] with one of them; sphere ``radius``, ``mass`` (I = 2/5 m R^2); ``epsilon`` of WCA
    (F-34) in kT; ``start`` "lattice" or "random". With walls the packing fraction counts the slab
    the particles can reach, |y - Ly/2| <= half_width - 2 radius (the paper's accessible volume).
    ``initial``: a checkpoint.npz whose positions and body axes the run starts from instead (a
    cross-start: the state of one run continued with another model or mass; velocities and spins are
    drawn at kT for this configuration's masses), with the same dimension, box, n and radius."""

    SECTION = "system"
    dimension: int = 2
    n: int | None = None
    packing_fraction: float | None = None
    box: tuple[float, ...] | None = None
    radius: float = 0.5
    mass: float = 1.0
    epsilon: float = 1.0
    start: str = "lattice"
    initial: str | None = None

    def __post_init__(self):
        self.require(self.dimension in (2, 3), "dimension", f"must be 2 or 3, got {self.dimension}", "set dimension = 2 or 3")
        self.require_positive("radius", "mass")
        self.require_scale("radius", "mass")
        self.require(
            self.start in ("lattice", "random"), "start", f"must be 'lattice' or 'random', got {self.start!r}", 'set start = "lattice"'
        )
        if self.box is None:
            self.require(
                self.n is not None and self.packing_fraction is not None, "n", "needs n and packing_fraction, or a box", "add them"
            )
        else:
            self.require(
                len(self.box) == self.dimension, "box", f"needs {self.dimension} lengths, got {len(self.box)}", "give [Lx, Ly(, Lz)]"
            )
            self.require(
                all(0 < x < math.inf for x in self.box), "box", f"lengths must be finite and positive, got {list(self.box)}", "fix them"
            )
            self.require(
                (self.n is None) != (self.packing_fraction is None), "n", "with a box give one of n and packing_fraction", "remove one"
            )
        if self.n is not None:
            self.require(self.n >= 2, "n", f"needs at least 2 particles, got {self.n}", "give n >= 2")
        if self.packing_fraction is not None:
            check_fraction(self.key("packing_fraction"), self.packing_fraction, self)


@dataclass(frozen=True)
class Walls(Section):
    """``[walls]``: two walls of immobile spheres at y = Ly/2 +- ``half_width`` + ``roughness`` zeta_j
    on a square lattice of constant ``spacing`` (F-42; needs ``system.box``)."""

    SECTION = "walls"
    half_width: float
    roughness: float = 0.0
    spacing: float = 1.0

    def __post_init__(self):
        self.require_nonnegative("roughness")
        self.require(
            0 < self.spacing < math.inf,
            "spacing",
            f"must be positive and finite, got {self.spacing}",
            "give the walls' lattice constant (the paper: 1)",
        )
        self.require_positive("half_width")


@dataclass(frozen=True)
class Run(Section):
    """``[run]``: ``steps`` in all, the first ``equilibrate`` left out of the averages, noise ``seed``,
    ``chunk`` = steps between observer calls (and Ctrl-C checks)."""

    SECTION = "run"
    steps: int = 10_000
    equilibrate: int = 0
    seed: int = 1
    chunk: int = 1000

    def __post_init__(self):
        self.require(self.steps >= 1, "steps", f"must be >= 1, got {self.steps}", "give the number of steps")
        self.require_steps("steps", self.steps)
        self.require(
            0 <= self.equilibrate < self.steps, "equilibrate", f"must be in [0, steps = {self.steps}), got {self.equilibrate}", "lower it"
        )
        self.require(self.chunk >= 1, "chunk", f"must be >= 1, got {self.chunk}", "give the steps between observer calls, e.g. 1000")


@dataclass(frozen=True)
class Output(Section):
    """``[output]``: ``observables`` (see :mod:`fricgen.app.run.observables`) every ``period`` steps, GSD
    frames every ``trajectory_period`` (0: none), checkpoints every ``checkpoint_period`` (0: only at
    the end or on Ctrl-C), ``profile_bins`` slabs of the velocity profile; periods are multiples of
    ``run.chunk``."""

    SECTION = "output"
    period: int = 1000
    trajectory_period: int = 10_000
    checkpoint_period: int = 0
    observables: tuple[str, ...] = ("temperatures",)
    profile_bins: int = 40

    def __post_init__(self):
        for name in self.observables:
            self.require(name in OBSERVABLES, "observables", f"unknown observable {name!r}", f"choose from {list(OBSERVABLES)}")
        self.require(
            1 <= self.profile_bins <= PROFILE_BINS,
            "profile_bins",
            f"must be >= 1 and at most {PROFILE_BINS}, got {self.profile_bins}",
            "give the number of slabs along y",
        )


@dataclass(frozen=True)
class RunConfig(Section):
    """A validated run file (``fricgen run``): its sections, each checked once.

    Attributes
    ----------
    system : System
        ``[system]``: dimension, particles, box or packing fraction, WCA strength [kT], start.
    law : RunLaw
        ``[law]``: the engine's law section and ``folder``, a folder of your own law files.
    thermostat : Thermostat
        ``[thermostat]``: kT [kT], gamma [kT t0/sigma^2], gamma_rot [kT t0], dt [t0].
    active : Active
        ``[active]``: the self-propulsion force [kT/sigma].
    bulk : Bulk
        ``[bulk]``: the body force [kT/sigma].
    walls : Walls or None
        ``[walls]``: two walls of immobile spheres (F-42); None without the section.
    run : Run
        ``[run]``: steps, equilibration, seed, chunk.
    output : Output
        ``[output]``: observables and their periods, trajectory, checkpoints.

    Examples
    --------
    >>> from fricgen.app import load_config, resolve_source
    >>> config = load_config(resolve_source("passive"), [("system.n", 64), ("thermostat.dt", 5e-4)])
    >>> config.system.n, config.thermostat.dt, config.langevin().law.name
    (64, 0.0005, 'coulomb_newton')
    """

    system: System
    law: RunLaw = field(default_factory=RunLaw)
    thermostat: Thermostat = field(default_factory=Thermostat)
    active: Active = field(default_factory=Active)
    bulk: Bulk = field(default_factory=Bulk)
    walls: Walls | None = None
    run: Run = field(default_factory=Run)
    output: Output = field(default_factory=Output)

    def __post_init__(self):
        dim = self.system.dimension
        self.require(len(self.bulk.force) in (0, dim), "bulk.force", f"needs {dim} components", "give [Fx, Fy] in 2-D, [Fx, Fy, Fz] in 3-D")
        for key in ("period", "trajectory_period", "checkpoint_period"):
            value, chunk = getattr(self.output, key), self.run.chunk
            smallest = "a positive" if key == "period" else "0 (never) or a positive"
            allowed = (value > 0 or (value == 0 and key != "period")) and value % chunk == 0
            self.require(
                allowed, f"output.{key}", f"must be {smallest} multiple of run.chunk = {chunk}, got {value}", "adjust it or run.chunk"
            )
        if self.walls is not None:
            self._check_walls()
        self._check_memory()

    def _check_walls(self) -> None:
        s = self.system
        self.require(
            s.box is not None, "system.box", "slab walls need an explicit box (taller than 2 half_width)", "add box = [Lx, Ly(, Lz)]"
        )
        w, ly = self.walls, s.box[1]
        self.require(
            2 * w.half_width < ly and slab_half_height(self) > 0,
            "walls.half_width",
            f"{w.half_width} leaves no room: need 2 radius + 3 roughness < half_width < Ly/2 = {ly / 2:g}",
            "change half_width or system.box[1]",
        )

    def _check_memory(self) -> None:
        """The particles (mobile, estimated from the packing fraction if need be, and walls) and the cell
        list fit this machine's memory: checked before anything is allocated."""
        s, dim = self.system, self.system.dimension
        if s.box is None:
            n, box = s.n, (cubic_side(s.n, s.radius, dim, s.packing_fraction),) * dim
        else:
            n, box = s.n or round(s.packing_fraction * math.prod(s.box) / ball_volume(s.radius, dim)), s.box
        walls = 0 if self.walls is None else 2 * math.prod(max(1, round(box[a] / self.walls.spacing)) for a in range(0, dim, 2))
        needed = memory_estimate(n + walls, box, s.radius, self.langevin().skin)  # also checks the engine's scalars
        what = f"{n} particles" + (f" and {walls} wall spheres" if walls else "") + (f" in a box of {list(box)}" if s.box else "")
        self.require_memory("system.n" if s.box is None else "system.box", needed, what)

    @property
    def kinds(self) -> tuple[str, ...]:
        """What this run is beyond a fluid in a box, in the order of :data:`KINDS`: ``slit_flow``
        (walls and a bulk force along x: Poiseuille flow, F-42) and ``active`` (an active force);
        none for a passive run."""
        found = {"slit_flow": self.walls is not None and self.bulk.vector[0] != 0, "active": self.active.force != 0}
        return tuple(kind for kind in KINDS if found[kind])

    def langevin(self) -> LangevinConfig:
        """The engine's configuration: its own sections, the WCA strength and the seed.

        Returns
        -------
        LangevinConfig
            What :class:`fricgen.langevin.Simulation` takes.
        """
        return LangevinConfig(self.law.engine(), self.thermostat, self.active, self.bulk, epsilon=self.system.epsilon, seed=self.run.seed)

    def as_dict(self) -> dict:
        """The configuration as nested plain data.

        Returns
        -------
        dict
            Section name to its fields.
        """
        return dataclasses.asdict(self)


def example_names() -> list[str]:
    """Names of the bundled example configurations (``fricgen run NAME``); ``*_sweep.toml`` are sweeps."""
    return sorted(p.stem for p in EXAMPLES.glob("*.toml") if not p.stem.endswith("_sweep"))


def resolve_source(source: str) -> Path:
    """The run file of a ``fricgen run`` argument.

    Parameters
    ----------
    source : str
        A TOML file, or the name of a bundled example (``passive``, ``poiseuille``, ``active``).

    Returns
    -------
    pathlib.Path
        The file.
    """
    path = Path(source)
    if path.is_file():
        return path
    example = EXAMPLES / f"{source}.toml"
    if source in example_names():
        return example
    raise ConfigError("CONFIG", f"no file {source!r} and no bundled example of that name", f"give a TOML file or one of {example_names()}")


def parse_override(text: str) -> tuple[str, object]:
    """``section.key=VALUE`` with VALUE in TOML syntax (a bare word is a string)."""
    key, sep, value = text.partition("=")
    if not sep or "." not in key or not all(part.strip() for part in key.split(".")):
        raise ConfigError(f"--set {text}", "expected SECTION.KEY=VALUE", "for example --set system.n=256")
    try:
        parsed = tomllib.loads(f"value = {value}")["value"]
    except tomllib.TOMLDecodeError:
        parsed = value.strip()
    return key.strip(), parsed


def read_toml(path: Path) -> dict:
    """The table of a TOML file; ConfigError naming the file if it cannot be read or is not UTF-8 TOML."""
    try:
        return tomllib.loads(path.read_text(encoding="utf-8-sig"))
    except UnicodeDecodeError as error:
        raise ConfigError(
            str(path), f"not UTF-8 text (byte {error.start} is {error.object[error.start : error.start + 1]!r})", "save it as UTF-8 TOML"
        ) from error
    except OSError as error:
        raise ConfigError(str(path), f"cannot be read: {error.strerror or error}", "give a readable TOML file") from error
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(str(path), f"not valid TOML: {error}", "fix the syntax at that line") from error


def load_config(path: Path, overrides: list[tuple[str, object]] = ()) -> RunConfig:
    """Read, override and validate a run file (no files written).

    Parameters
    ----------
    path : pathlib.Path
        The TOML file.
    overrides : list of (str, object)
        ``("section.key", value)`` pairs applied before validation, as ``--set``.

    Returns
    -------
    RunConfig
        The configuration; a ``law.folder`` becomes an absolute path (relative ones are taken from
        the file's folder).

    Raises
    ------
    ConfigError
        Naming the key, the problem and the fix.
    """
    data = read_toml(path)
    for key, value in overrides:
        *sections, name = key.split(".")
        table = data
        for section in sections:
            table = table.setdefault(section, {})
            if not isinstance(table, dict):
                raise ConfigError(key, f"{section} is not a table", "override a key inside a section, e.g. system.n")
        table[name] = value
    config = structure(RunConfig, {"system": {}, **data})
    if config.law.folder is None:
        return config
    folder = path.parent / Path(config.law.folder).expanduser()
    if not folder.is_dir():
        raise ConfigError(
            "law.folder",
            f"{folder} {'is a file, not a folder' if folder.exists() else 'does not exist'}",
            "give the folder of your law files, relative to the configuration file",
        )
    return dataclasses.replace(config, law=dataclasses.replace(config.law, folder=str(folder.resolve())))


def check_fraction(key: str, fraction: float, s: System) -> None:
    """A packing fraction below close packing (and the random-start limit), else ConfigError at ``key``."""
    densest = CLOSE_PACKING[s.dimension]
    if not 0 < fraction < densest:
        raise ConfigError(key, f"{fraction:g} is impossible: close packing is {densest:.4f} in {s.dimension}-D", "give a smaller value")
    limit = RANDOM_LIMIT[s.dimension]
    if s.start == "random" and fraction > limit:
        raise ConfigError(key, f"{fraction:g} is too dense for a random start (at most {limit})", 'use start = "lattice"')


def slab_half_height(c: RunConfig) -> float:
    """Half height of the region where particles start: the accessible slab less 3 roughness."""
    return c.walls.half_width - 2 * c.system.radius - 3 * c.walls.roughness
