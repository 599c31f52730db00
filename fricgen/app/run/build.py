"""From a validated run configuration to a simulation at step 0: the law and its kernels, the
particles, the initial state (lattice or random, in the box or in the slab between walls), walls.

The law's names are resolved here, once (:func:`resolve_law`: the law search handed in by the edge,
with the configuration's ``law.folder``), into the checked contact law the engine is handed. Each failure is a
:class:`~fricgen.errors.ConfigError` naming the key, raised before any file is written.
:func:`check` makes the checks of :func:`build` that need no particles (a sweep checks its points
with it).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from fricgen.derive.law.catalogues import BUILT_IN, CatalogueError, LawSearch

from ...errors import ConfigError, KernelError
from ...kernels import load_law_kernels
from ...langevin.config import Law
from ...langevin.contact_law import ContactLaw, bind, named_keys
from ...langevin.simulation import Simulation
from ...langevin.system import (
    Particles,
    State,
    add_slab_walls,
    ball_volume,
    interaction_reach,
    lattice_positions,
    packing_box,
    random_positions,
    thermal_state,
)
from .checkpoints import check_checkpoint
from .config import RunConfig, RunLaw, check_fraction, slab_half_height


def resolve_law(section: Law, dim: int, search: LawSearch = BUILT_IN) -> ContactLaw:
    """The contact law of a ``[law]`` section for ``dim``-D pairs: the kernels of its laws (``name``,
    then ``rolling`` and ``spinning`` where given) looked up in ``search`` (the edge's: ``--laws``,
    FRICGEN_LAWS) and then in a run's ``law.folder``, loaded fresh, and checked once
    (:func:`fricgen.langevin.contact_law.bind`). ConfigError naming the key otherwise."""
    if isinstance(section, RunLaw):
        try:
            search = search.then(LawSearch.of(*section.folders, named_by="law.folder"))
        except CatalogueError as error:
            raise ConfigError("law.folder", str(error)) from error
    found = []
    for key, _, _ in named_keys(section):
        try:
            found.append(load_law_kernels(getattr(section, key), search))
        except KernelError as error:
            raise ConfigError(f"law.{key}", str(error)) from error
    return bind(section, found, dim)


def check(c: RunConfig, search: LawSearch = BUILT_IN) -> None:
    """What :func:`build` checks before it places the particles: the law (:func:`resolve_law`) and the box."""
    resolve_law(c.law, c.system.dimension, search)
    layout(c)


def layout(c: RunConfig) -> tuple[np.ndarray, np.ndarray, int]:
    """The box (3 lengths, the unused ones 0), the region the particles start in (the box, or the
    slab between walls: 2 (half_width - 2 radius) high) and the number of particles; ConfigError if
    the box is not wider than twice the interaction range or ``n`` exceeds close packing."""
    s, dim = c.system, c.system.dimension
    if s.box is None:
        box = packing_box(Particles.spheres(s.n, s.radius, s.mass), dim, s.packing_fraction)
    else:
        box = np.array([*s.box, 0.0][:3], dtype=float)
    reach = 2 * interaction_reach(s.radius, c.langevin().skin)
    if not box[:dim].min() > reach:
        raise ConfigError(
            "system.box" if s.box is not None else "system.n",
            f"the box {box[:dim].round(3).tolist()} is too small for the interaction range (each length must exceed {reach:.2f})",
            "use more particles or a larger box",
        )
    region = box.copy()
    if c.walls is not None:
        region[1] = 2 * (c.walls.half_width - 2 * s.radius)
    volume = np.prod(region[:dim])
    per_particle = ball_volume(s.radius, dim)
    n = s.n if s.n is not None else max(2, round(s.packing_fraction * volume / per_particle))
    if s.packing_fraction is None:
        check_fraction("system.n", n * per_particle / volume, s)
    return box, region, n


def initial_state(c: RunConfig, particles: Particles, box: np.ndarray) -> State:
    """The state of ``system.initial``: the positions and body axes of a checkpoint, velocities and
    spins drawn at kT for ``particles``; ConfigError unless the checkpoint holds as many mobile
    particles of the same radius in the same box and dimension."""
    path, dim = Path(c.system.initial), c.system.dimension
    refuse = functools.partial(ConfigError, "system.initial")
    if c.walls is not None:
        raise refuse("a start from a checkpoint is for runs without walls", "leave it out, or remove [walls]")
    check_checkpoint(path, "system.initial")  # whole, finite, of fricgen run
    with np.load(path, allow_pickle=False) as data:
        stored = {k: np.array(data[k]) for k in ("position", "orientation", "radius", "mobile", "box", "dim")}
    n = particles.radius.size
    same = int(stored["dim"]) == dim and stored["radius"].shape == (n,)  # positions: one per radius (check_checkpoint)
    same = same and bool(stored["mobile"].all()) and np.array_equal(stored["radius"], particles.radius)
    same = same and np.allclose(stored["box"], box, rtol=1e-12, atol=0.0)
    if not same:
        held = f"{stored['radius'].size} particles in a {int(stored['dim'])}-D box {np.round(stored['box'], 4).tolist()}"
        raise refuse(
            f"{path} holds {held}, not {n} mobile particles of radius {c.system.radius} in {np.round(box, 4).tolist()}",
            "give the same system as the run that wrote it",
        )
    state = thermal_state(particles, stored["position"], box, dim, c.thermostat.kT, c.run.seed)
    state.orientation[:] = stored["orientation"]
    return state


def build(c: RunConfig, search: LawSearch = BUILT_IN) -> Simulation:
    """The simulation of a validated configuration, from its initial state (step 0); ``search``: where
    its laws' names are looked up (:func:`resolve_law`)."""
    law = resolve_law(c.law, c.system.dimension, search)
    config, s, dim = c.langevin(), c.system, c.system.dimension
    box, region, n = layout(c)
    particles = Particles.spheres(n, s.radius, s.mass)
    place = region.copy()
    if c.walls is not None:
        place[1] = 2 * slab_half_height(c)
    if s.initial is not None:
        return Simulation(config, particles, initial_state(c, particles, box), law)
    try:
        if s.start == "lattice":
            position = lattice_positions(n, place, dim, 2 * s.radius)
        else:
            position = random_positions(particles.radius, place, dim, seed=c.run.seed)
    except ConfigError as error:
        raise ConfigError("system.packing_fraction" if s.packing_fraction is not None else "system.n", error.problem, "lower it") from error
    if c.walls is not None:
        position[:, 1] += box[1] / 2 - slab_half_height(c)
    state = thermal_state(particles, position, box, dim, c.thermostat.kT, c.run.seed)
    if c.walls is not None:
        particles, state = add_slab_walls(particles, state, c.walls.half_width, c.walls.roughness, c.run.seed, c.walls.spacing)
    return Simulation(config, particles, state, law)
