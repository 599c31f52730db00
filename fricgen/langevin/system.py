"""Particles, state and initial configurations of a Langevin simulation.

Units: sigma = 1 (diameter of the reference sphere), kT = 1, m = 1; the paper's defaults are
R = 1/2, m = 1, I = 2/5 m R^2 (solid spheres, also for 2-D discs as in the paper).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ConfigError
from ..rng import INITIAL, WALL_ROUGHNESS, normals
from .pairs import PAIR_FIELDS, WCA_RANGE


@dataclass(frozen=True)
class Particles:
    """Static per-particle properties; immobile (wall) particles have ``mobile = False``.

    Attributes
    ----------
    radius : numpy.ndarray
        Radii R_i [sigma], shape (N,).
    mass : numpy.ndarray
        Masses m_i [m].
    inertia : numpy.ndarray
        Moments of inertia I_i [m sigma^2].
    mobile : numpy.ndarray
        bool: whether a particle moves.
    """

    radius: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    mobile: np.ndarray

    def __post_init__(self):
        n = self.radius.size
        for name in ("mass", "inertia", "mobile"):
            if getattr(self, name).shape != (n,):
                raise ConfigError(name, f"must have shape ({n},), got {getattr(self, name).shape}", "give one value per particle")
        for name in ("radius", "mass", "inertia"):
            values = getattr(self, name)
            if not (np.all(np.isfinite(values)) and np.all(values > 0)):
                raise ConfigError(name, "every value must be finite and positive", "fix them")

    @classmethod
    def spheres(cls, n: int, radius: float = 0.5, mass: float = 1.0) -> Particles:
        """n identical solid spheres, I = 2/5 m R^2.

        Parameters
        ----------
        n : int
            The number of spheres.
        radius : float
            Their radius [sigma].
        mass : float
            Their mass [m].

        Returns
        -------
        Particles
            All mobile.
        """
        return cls(np.full(n, radius), np.full(n, mass), np.full(n, 0.4 * mass * radius**2), np.ones(n, dtype=bool))

    @property
    def inv_mass(self) -> np.ndarray:
        """1/m_i [1/m], 0 for immobile particles."""
        return np.where(self.mobile, 1.0 / self.mass, 0.0)

    @property
    def inv_inertia(self) -> np.ndarray:
        """1/I_i [1/(m sigma^2)], 0 for immobile particles."""
        return np.where(self.mobile, 1.0 / self.inertia, 0.0)


@dataclass
class State:
    """Dynamic state of the spheres; a :class:`Simulation` advances it in place.

    Attributes
    ----------
    position : numpy.ndarray
        Positions (N, 3) [sigma], wrapped into the box; z = 0 in 2-D.
    velocity : numpy.ndarray
        Velocities (N, 3) [sigma/t0].
    omega : numpy.ndarray
        Angular velocities (N, 3) [1/t0]; only z in 2-D.
    orientation : numpy.ndarray
        Unit quaternions (s, x, y, z) of the body frames, (N, 4).
    box : numpy.ndarray
        The periodic box lengths (3,) [sigma]; Lz = 0 in 2-D.
    dim : int
        2 or 3.
    step : int
        The step count.
    """

    position: np.ndarray
    velocity: np.ndarray
    omega: np.ndarray
    orientation: np.ndarray
    box: np.ndarray
    dim: int
    step: int = 0

    def copy(self) -> State:
        """A deep copy (arrays copied).

        Returns
        -------
        State
            The copy.
        """
        return State(
            self.position.copy(), self.velocity.copy(), self.omega.copy(), self.orientation.copy(), self.box.copy(), self.dim, self.step
        )


def packing_box(particles: Particles, dim: int, fraction: float) -> np.ndarray:
    """Cubic (square) box lengths for the area (2-D) or volume (3-D) fraction of the mobile particles.

    The side is L = (π Σ R_i² / φ)^(1/2) in 2-D and (4π/3 Σ R_i³ / φ)^(1/3) in 3-D.

    Parameters
    ----------
    particles : Particles
        The particles; only the mobile ones count.
    dim : int
        2 or 3.
    fraction : float
        The packing fraction φ [1], in (0, 1).

    Returns
    -------
    np.ndarray
        The box lengths (L_x, L_y, L_z) [sigma]; L_z = 0 in 2-D.

    Raises
    ------
    ConfigError
        For a fraction outside (0, 1).
    """
    if not 0 < fraction < 1:
        raise ConfigError("fraction", f"packing fraction must be in (0, 1), got {fraction}", "give a smaller value")
    r = particles.radius[particles.mobile]
    if dim == 2:
        side = math.sqrt(np.pi * np.sum(r**2) / fraction)
        return np.array([side, side, 0.0])
    side = (4.0 / 3.0 * np.pi * np.sum(r**3) / fraction) ** (1.0 / 3.0)
    return np.array([side, side, side])


CLOSE_PACKING = {2: math.pi / (2 * math.sqrt(3)), 3: math.pi / (3 * math.sqrt(2))}
"""Densest packing fraction of equal discs (hexagonal, 0.9069) and spheres (fcc, 0.7405)."""

LATTICE_LIMIT = {2: math.pi / 4, 3: math.pi / 6}
"""Densest square (2-D) or simple cubic (3-D) lattice start, 0.785 and 0.524."""

RANDOM_LIMIT = {2: 0.4, 3: 0.25}
"""Random starts above this fraction are refused (random sequential addition jams near 0.547 and 0.38)."""

BYTES_PER_PARTICLE, BYTES_PER_NEIGHBOUR = 1024, 8 * (2 + PAIR_FIELDS)
"""Memory of a run per particle (properties, state, the integrator's force terms and copies) and per
entry of its full Verlet list (the neighbour, its reverse slot and its pair slot): upper estimates."""


def ball_volume(radius: float, dim: int) -> float:
    """Area (2-D) or volume (3-D) of one sphere: pi R^2 or 4/3 pi R^3."""
    return math.pi * radius**2 if dim == 2 else 4 / 3 * math.pi * radius**3


def cubic_side(n: int, radius: float, dim: int, fraction: float) -> float:
    """Side of the square (cubic) box in which n spheres of ``radius`` fill the packing ``fraction``
    (no arrays: for estimates made before anything is allocated)."""
    return (n * ball_volume(radius, dim) / fraction) ** (1 / dim)


def lattice_limit(n: int, dim: int) -> float:
    """Densest packing fraction of a lattice start of n equal spheres in a cubic box: LATTICE_LIMIT
    when n is a square (cube), less otherwise (:func:`lattice_positions` puts ceil(n^(1/dim)) sites
    along each axis, at least a diameter apart)."""
    per_axis = math.ceil(n ** (1.0 / dim) - 1e-9)
    return LATTICE_LIMIT[dim] * n / per_axis**dim


def interaction_reach(radius: float, skin: float) -> float:
    """Cut-off of the neighbour list of WCA spheres of ``radius``: a box needs more than twice it."""
    return WCA_RANGE * 2 * radius + skin


def memory_estimate(n: int, box: tuple[float, ...], radius: float, skin: float) -> float:
    """Bytes that a run of n spheres in a periodic box of lengths ``box`` (2 or 3) needs, estimated
    from above before anything is allocated: per particle, per neighbour, per cell of the cell list
    and per candidate neighbour (the particles of a particle's own and adjacent cells, for which a
    list build makes room: at most as many as close packing fits in them)."""
    reach = interaction_reach(radius, skin)
    neighbours = min(n, n * ball_volume(reach, len(box)) / math.prod(box) + 1)
    cells = math.prod(max(1.0, length / reach) for length in box)
    cell_volume = math.prod(length / max(1, int(length // reach)) for length in box)
    candidates = min(n, 3 ** len(box) * (CLOSE_PACKING[len(box)] * cell_volume / ball_volume(radius, len(box)) + 1))
    return n * (BYTES_PER_PARTICLE + BYTES_PER_NEIGHBOUR * neighbours + 8 * candidates) + 16 * cells


def lattice_positions(n: int, lengths: np.ndarray, dim: int, min_spacing: float) -> np.ndarray:
    """n sites of a rectangular lattice filling the region [0, L_a) (a < dim), about equally spaced
    along every axis; raises ConfigError if two sites would be closer than ``min_spacing``."""
    lengths = np.asarray(lengths, dtype=float)[:dim]
    site = (np.prod(lengths) / n) ** (1.0 / dim)
    counts = [math.ceil(length / site - 1e-9) for length in lengths]
    spacing = lengths / counts
    if spacing.min() < min_spacing:
        limit = f"{LATTICE_LIMIT[dim]:.3f} ({'square' if dim == 2 else 'cubic'} lattice limit)"
        raise ConfigError(
            "fraction", f"{n} particles do not fit on a lattice here: packing fraction too high for a lattice start, above {limit}"
        )
    index = np.arange(n)
    position = np.zeros((n, 3))
    stride = 1
    for a in range(dim):
        position[:, a] = (index // stride % counts[a] + 0.5) * spacing[a]
        stride *= counts[a]
    return position


def random_positions(radius: np.ndarray, lengths: np.ndarray, dim: int, seed: int = 1, attempts: int = 1000) -> np.ndarray:
    """Random sequential addition of non-overlapping spheres (|r_i - r_k| >= R_i + R_k) into the
    periodic region [0, L_a) (a < dim); raises ConfigError when a sphere finds no place in ``attempts`` tries."""
    lengths = np.asarray(lengths, dtype=float)[:dim]
    reach = 2 * radius.max()
    cells = np.maximum(1, (lengths // reach).astype(int))
    grid: dict[tuple[int, ...], list[int]] = {}
    position = np.zeros((radius.size, 3))
    generator = np.random.default_rng(seed)
    offsets = np.stack(np.meshgrid(*([(-1, 0, 1)] * dim), indexing="ij"), axis=-1).reshape(-1, dim)
    for i, ri in enumerate(radius):
        for _ in range(attempts):
            trial = generator.random(dim) * lengths
            cell = (trial // (lengths / cells)).astype(int) % cells
            near = [k for o in offsets for k in grid.get(tuple((cell + o) % cells), ())]
            delta = position[near, :dim] - trial
            delta -= lengths * np.round(delta / lengths)
            if not near or np.all(np.sum(delta**2, axis=1) >= (ri + radius[near]) ** 2):
                break
        else:
            raise ConfigError("fraction", f"random start: no place for particle {i} of {radius.size} after {attempts} tries", "lower it")
        position[i, :dim] = trial
        grid.setdefault(tuple(cell), []).append(i)
    return position


def thermal_state(particles: Particles, position: np.ndarray, box: np.ndarray, dim: int, kT: float = 1.0, seed: int = 1) -> State:
    """A state at the given positions with Maxwell–Boltzmann velocities and spins at kT and random
    orientations (about z in 2-D); immobile particles are at rest.

    Each velocity component has variance kT/m, each spin component kT/I (in 2-D only v_x, v_y and
    ω_z are drawn); the draws come from the counter-based generator, keyed on ``seed``.

    Parameters
    ----------
    particles : Particles
        Radii, masses and moments of inertia.
    position : np.ndarray
        (N, 3) positions [sigma], inside ``box``.
    box : np.ndarray
        The box lengths [sigma].
    dim : int
        2 or 3.
    kT : float
        The temperature [kT].
    seed : int
        The noise seed (≥ 0).

    Returns
    -------
    State
        The state at step 0.
    """
    n = particles.radius.size
    z = normals(seed, 0, INITIAL, 12 * n).reshape(n, 12)
    velocity = z[:, :3] * np.sqrt(kT / particles.mass)[:, None]
    omega = z[:, 3:6] * np.sqrt(kT / particles.inertia)[:, None]
    orientation = z[:, 6:10] / np.linalg.norm(z[:, 6:10], axis=1)[:, None]
    if dim == 2:
        velocity[:, 2] = 0.0
        omega[:, :2] = 0.0
        angle = np.arctan2(z[:, 10], z[:, 11])
        orientation = np.stack([np.cos(angle / 2), 0 * angle, 0 * angle, np.sin(angle / 2)], axis=1)
    velocity[~particles.mobile] = 0.0
    omega[~particles.mobile] = 0.0
    return State(position, velocity, omega, orientation, np.asarray(box, dtype=float), dim)


def lattice_state(particles: Particles, dim: int, fraction: float, kT: float = 1.0, seed: int = 1) -> State:
    """Particles on a square (cubic) lattice in a periodic box, Maxwell–Boltzmann velocities and
    spins at kT, random orientations.

    Parameters
    ----------
    particles : Particles
        The particles; the box is sized for their packing fraction (:func:`packing_box`).
    dim : int
        2 or 3.
    fraction : float
        The area (2-D) or volume (3-D) fraction, below the lattice limit (π/4 in 2-D, π/6 in
        3-D for a square or cube number of particles).
    kT : float
        The temperature of the velocities and spins [kT].
    seed : int
        The noise seed (≥ 0).

    Returns
    -------
    State
        The state at step 0.

    Raises
    ------
    ConfigError
        For a dimension other than 2 or 3, or a lattice whose spheres would overlap.
    """
    if dim not in (2, 3):
        raise ConfigError("dim", f"must be 2 or 3, got {dim}", "give 2 or 3")
    box = packing_box(particles, dim, fraction)
    position = lattice_positions(particles.radius.size, box, dim, 2 * particles.radius.max())
    return thermal_state(particles, position, box, dim, kT, seed)


def add_slab_walls(
    particles: Particles, state: State, half_width: float, roughness: float = 0.0, seed: int = 1, spacing: float = 1.0
) -> tuple[Particles, State]:
    """Append two walls of immobile spheres (F-42): a square lattice of lattice constant ``spacing``
    in the xz-plane (a row along x in 2-D) at y = y_c ± half_width + roughness·ζ_j, y_c the box
    centre, with the same Gaussian ζ_j on both walls (as in the paper). Wall spheres copy the
    radius and mass of particle 0.

    Parameters
    ----------
    particles : Particles
        The mobile particles.
    state : State
        Their state; its box sets the walls' extent.
    half_width : float
        The distance of each wall from the box centre [sigma] (0 < 2·half_width < L_y).
    roughness : float
        The amplitude δ_w of the walls' Gaussian roughness [sigma] (≥ 0).
    seed : int
        The seed of the roughness ζ_j.
    spacing : float
        The walls' lattice constant [sigma].

    Returns
    -------
    tuple[Particles, State]
        The particles and the state with the wall spheres appended (immobile, at rest).

    Raises
    ------
    ConfigError
        For a negative roughness, a non-positive spacing or walls outside the box.
    """
    if roughness < 0 or spacing <= 0 or not 0 < 2 * half_width < state.box[1]:
        raise ConfigError("walls", "need roughness >= 0, spacing > 0 and 0 < 2 half_width < L_y", "fix them")
    counts = [max(1, int(round(state.box[0] / spacing))), max(1, int(round(state.box[2] / spacing))) if state.dim == 3 else 1]
    grid = np.stack(np.meshgrid(np.arange(counts[0]), np.arange(counts[1]), indexing="ij"), axis=-1).reshape(-1, 2)
    zeta = normals(seed, 0, WALL_ROUGHNESS, grid.shape[0])
    walls = []
    for side in (-1.0, 1.0):
        site = np.zeros((grid.shape[0], 3))
        site[:, 0] = (grid[:, 0] + 0.5) * state.box[0] / counts[0]
        site[:, 1] = 0.5 * state.box[1] + side * half_width + roughness * zeta
        if state.dim == 3:
            site[:, 2] = (grid[:, 1] + 0.5) * state.box[2] / counts[1]
        walls.append(site)
    wall = np.concatenate(walls)
    m = wall.shape[0]
    spheres = Particles.spheres(m, particles.radius[0], particles.mass[0])
    extended = Particles(
        *(np.concatenate([getattr(particles, a), getattr(spheres, a)]) for a in ("radius", "mass", "inertia")),
        np.concatenate([particles.mobile, np.zeros(m, bool)]),
    )
    still = np.zeros((m, 3))
    quat = np.tile([1.0, 0.0, 0.0, 0.0], (m, 1))
    return extended, State(
        np.concatenate([state.position, wall]),
        np.concatenate([state.velocity, still]),
        np.concatenate([state.omega, still]),
        np.concatenate([state.orientation, quat]),
        state.box.copy(),
        state.dim,
        state.step,
    )
