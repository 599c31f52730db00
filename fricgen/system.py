"""Particles, state and initial configurations of a Langevin simulation.

Units: sigma = 1 (diameter of the reference sphere), kT = 1, m = 1; the paper's defaults are
R = 1/2, m = 1, I = 2/5 m R^2 (solid spheres, also for 2-D discs as in the paper).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .rng import INITIAL, normals


@dataclass(frozen=True)
class Particles:
    """Static per-particle properties; immobile (wall) particles have ``mobile = False``."""

    radius: np.ndarray
    mass: np.ndarray
    inertia: np.ndarray
    mobile: np.ndarray

    def __post_init__(self):
        n = self.radius.size
        for name in ("mass", "inertia", "mobile"):
            if getattr(self, name).shape != (n,):
                raise ValueError(f"{name} must have shape ({n},), got {getattr(self, name).shape}")
        for name in ("radius", "mass", "inertia"):
            values = getattr(self, name)
            if not (np.all(np.isfinite(values)) and np.all(values > 0)):
                raise ValueError(f"every {name} must be finite and positive")

    @classmethod
    def spheres(cls, n: int, radius: float = 0.5, mass: float = 1.0) -> Particles:
        """n identical solid spheres, I = 2/5 m R^2."""
        return cls(np.full(n, radius), np.full(n, mass), np.full(n, 0.4 * mass * radius**2), np.ones(n, dtype=bool))

    @property
    def inv_mass(self) -> np.ndarray:
        return np.where(self.mobile, 1.0 / self.mass, 0.0)

    @property
    def inv_inertia(self) -> np.ndarray:
        return np.where(self.mobile, 1.0 / self.inertia, 0.0)


@dataclass
class State:
    """Dynamic state: positions (N, 3) wrapped into the box, velocities, angular velocities, unit
    quaternions (s, x, y, z) of the body frames, the step count and the box lengths (Lz = 0 in 2-D)."""

    position: np.ndarray
    velocity: np.ndarray
    omega: np.ndarray
    orientation: np.ndarray
    box: np.ndarray
    dim: int
    step: int = 0

    def copy(self) -> State:
        return State(
            self.position.copy(), self.velocity.copy(), self.omega.copy(), self.orientation.copy(), self.box.copy(), self.dim, self.step
        )


def packing_box(particles: Particles, dim: int, fraction: float) -> np.ndarray:
    """Cubic (square) box lengths for the area (2-D) or volume (3-D) fraction of the mobile particles."""
    if not 0 < fraction < 1:
        raise ValueError(f"packing fraction must be in (0, 1), got {fraction}")
    r = particles.radius[particles.mobile]
    if dim == 2:
        side = math.sqrt(np.pi * np.sum(r**2) / fraction)
        return np.array([side, side, 0.0])
    side = (4.0 / 3.0 * np.pi * np.sum(r**3) / fraction) ** (1.0 / 3.0)
    return np.array([side, side, side])


def lattice_state(particles: Particles, dim: int, fraction: float, kT: float = 1.0, seed: int = 1) -> State:
    """Particles on a square (cubic) lattice in a periodic box, Maxwell–Boltzmann velocities and
    spins at kT, random orientations; raises ValueError if the lattice would overlap."""
    if dim not in (2, 3):
        raise ValueError(f"dim must be 2 or 3, got {dim}")
    n = particles.radius.size
    box = packing_box(particles, dim, fraction)
    per_side = math.ceil(n ** (1.0 / dim) - 1e-9)
    spacing = box[0] / per_side
    if spacing < 2 * particles.radius.max():
        limit = {2: "pi/4 = 0.785", 3: "pi/6 = 0.524"}[dim]
        raise ValueError(f"packing fraction {fraction} too high for a lattice start (square/cubic lattice limit {limit})")
    index = np.arange(n)
    position = np.zeros((n, 3))
    for a in range(dim):
        position[:, a] = (index // per_side**a % per_side + 0.5) * spacing
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
    return State(position, velocity, omega, orientation, box, dim)


def add_slab_walls(
    particles: Particles, state: State, half_width: float, roughness: float = 0.0, seed: int = 1, spacing: float = 1.0
) -> tuple[Particles, State]:
    """Append two walls of immobile spheres (F-42): a square lattice of lattice constant ``spacing``
    in the xz-plane (a row along x in 2-D) at y = y_c +- half_width + roughness * zeta_j, y_c the box
    centre, with the same Gaussian zeta_j on both walls (as in the paper). Wall spheres copy the
    radius and mass of particle 0. Returns the extended particles and state.
    """
    if roughness < 0 or spacing <= 0 or not 0 < 2 * half_width < state.box[1]:
        raise ValueError("need roughness >= 0, spacing > 0 and 0 < 2 half_width < L_y")
    counts = [max(1, int(round(state.box[0] / spacing))), max(1, int(round(state.box[2] / spacing))) if state.dim == 3 else 1]
    grid = np.stack(np.meshgrid(np.arange(counts[0]), np.arange(counts[1]), indexing="ij"), axis=-1).reshape(-1, 2)
    zeta = normals(seed, 0, INITIAL + 1, grid.shape[0])
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
