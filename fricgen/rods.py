"""Hard (and sticky) rods in an external field with BCD: configuration, runs, profiles with errors.

Units as in the paper: lambda = 1, D = 1, kT = 1 (mu = D / kT). Observables are folded onto one
wavelength: rho(x) (B-25) and rho_2(x, x + sigma) (B-26) at bin centres, with standard errors from
block averages over time and over replicas.

Contact density: after a BCD step, rods of one cluster touch exactly (gap 0), a delta peak of
weight ~ rho_2 sqrt(2 D dt) that a window narrower than sqrt(2 D dt) over-counts (B-26 needs
dt << w^2 / 2D). We count gaps in [0, w] (density a) and (w, 2w] (density b) with w much wider than
sqrt(2 D dt) and extrapolate linearly to contact, rho_2 = (3a - b)/2 (bias O(w^2)).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from . import bcd
from .kernels import load_potential
from .rng import INITIAL, normals


@dataclass(frozen=True)
class RodConfig:
    """A BCD run: N rods of length sigma on a ring of length L in (U0/2) cos(2 pi x / lambda) (B-21),
    optional drive, optional sticky contact (B-31/32) of strength gamma (0: hard rods)."""

    n: int = 50
    length: float = 100.0
    sigma: float = 0.5
    U0: float = 6.0
    wavelength: float = 1.0
    kT: float = 1.0
    mu: float = 1.0
    drive: float = 0.0
    gamma: float = 0.0
    p: float = 3.0
    eps: float = 0.05
    dt: float = 1e-4
    seed: int = 1
    replicas: int = 1
    bins: int = 100
    contact_width: float = 0.02

    def __post_init__(self):
        if self.n < 2 or self.replicas < 1 or self.bins < 1:
            raise ValueError("need n >= 2 rods, replicas >= 1 and bins >= 1")
        for name in ("length", "sigma", "wavelength", "kT", "mu", "dt", "eps", "contact_width"):
            if not getattr(self, name) > 0:
                raise ValueError(f"{name} must be positive, got {getattr(self, name)}")
        if self.n * self.sigma >= self.length:
            raise ValueError(f"N sigma = {self.n * self.sigma} must be below the ring length L = {self.length} (close packing)")
        if abs(self.length / self.wavelength - round(self.length / self.wavelength)) > 1e-9:
            raise ValueError("the ring length must be a whole number of wavelengths")
        if self.gamma < 0 or self.p <= 1 or self.eps >= self.sigma:
            raise ValueError("need gamma >= 0, p > 1 (continuous force, B-31) and eps < sigma")

    @property
    def diffusion(self) -> float:
        return self.mu * self.kT

    @property
    def mean_density(self) -> float:
        return self.n / self.length


def sticky_force_max(gamma: float, p: float, eps: float, kT: float = 1.0, samples: int = 4001) -> float:
    """max |f_p(r)| over the interaction range (B-32): the s = sigma + eps - r in (0, eps] maximum."""
    s = np.linspace(eps / samples, eps, samples)
    return float(np.max(kT * gamma * p * s ** (p - 1) / (eps ** (p + 1) / (p + 1) + gamma * s**p)))


def best_exponent(eps: float, gamma: float = 1.0) -> float:
    """The exponent p > 1 minimising max |f_p| for given eps (the paper's Fig. 5: p ~ 2.95 at 0.05)."""
    from scipy.optimize import minimize_scalar

    return float(minimize_scalar(lambda p: sticky_force_max(gamma, p, eps), bounds=(1.01, 20.0), method="bounded").x)


def stability_ratio(config: RodConfig) -> float:
    """mu max|f_p| dt / eps of (B-33); the sticky force is resolved when this is << 1."""
    if config.gamma == 0:
        return 0.0
    return config.mu * sticky_force_max(config.gamma, config.p, config.eps, config.kT) * config.dt / config.eps


@dataclass(frozen=True)
class RodProfiles:
    """Profiles over one wavelength at bin centres x: rho, rho_2 at contact, their standard errors."""

    x: np.ndarray
    rho: np.ndarray
    rho_err: np.ndarray
    contact: np.ndarray
    contact_err: np.ndarray
    steps: int


class RodSimulation:
    """Replicas of one ring, evolved by BCD; ``run`` samples profiles in blocks."""

    def __init__(self, config: RodConfig):
        self.config = config
        if stability_ratio(config) > 0.1:
            warnings.warn(f"mu max|f| dt / eps = {stability_ratio(config):.2g} is not << 1 (B-33): reduce dt", stacklevel=2)
        cosine = load_potential("cosine")
        sticky = load_potential("sticky")
        self._external = (cosine.force, np.array([config.U0, config.wavelength]))
        self._pair = (sticky.force, np.array([config.gamma, config.p, config.eps, config.sigma, config.kT]))
        self.positions = self._initial()
        self.step = 0

    def _initial(self) -> np.ndarray:
        """Evenly spaced rods with a small random shift per replica (no overlaps)."""
        c = self.config
        spacing = c.length / c.n
        shift = normals(c.seed, 0, INITIAL, c.replicas) * 0.1 * (spacing - c.sigma)
        base = np.arange(c.n) * spacing
        return np.ascontiguousarray(base[None, :] + shift[:, None] % spacing)

    def equilibrate(self, duration: float, dt: float | None = None) -> None:
        """Run ``duration`` time units without sampling, at time step ``dt`` (default: the config's)."""
        dt = dt or self.config.dt
        self.advance(int(round(duration / dt)), dt=dt)

    def advance(self, steps: int, counts: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None, dt: float | None = None) -> None:
        """Advance all replicas by ``steps`` steps of ``dt`` (default: the config's); ``counts`` =
        (rods, gaps in [0, w], gaps in (w, 2w]) per replica and bin."""
        c = self.config
        counts = counts or tuple(np.zeros((c.replicas, c.bins)) for _ in range(3))
        status = bcd.advance_rods(
            self.positions,
            c.length,
            c.sigma,
            c.mu,
            c.diffusion,
            dt or c.dt,
            steps,
            self.step,
            c.seed,
            self._external[0],
            self._external[1],
            c.drive,
            self._pair[0],
            self._pair[1],
            c.eps,
            c.gamma > 0,
            c.wavelength,
            c.contact_width,
            *counts,
        )
        if status == bcd.PASSED:
            raise RuntimeError(f"rods overlapped near step {self.step + steps}: a bug or a non-finite force")
        if status == bcd.ALL_IN_CONTACT:
            raise RuntimeError("all rods are in contact (close packing): BCD cannot split the ring")
        self.step += steps

    def run(self, steps: int, blocks: int = 20) -> RodProfiles:
        """Sample ``steps`` steps in ``blocks`` blocks; errors from block-to-block scatter."""
        c = self.config
        if steps < blocks:
            raise ValueError("need at least one step per block")
        per_block = steps // blocks
        periods = c.length / c.wavelength
        width = c.wavelength / c.bins
        rho_blocks, contact_blocks = [], []
        for _ in range(blocks):
            rods, near, beyond = (np.zeros((c.replicas, c.bins)) for _ in range(3))
            self.advance(per_block, (rods, near, beyond))
            scale = per_block * width * periods
            rho_blocks.append(rods / scale)
            contact_blocks.append((1.5 * near - 0.5 * beyond) / (scale * c.contact_width))
        rho = np.concatenate(rho_blocks)  # (blocks * replicas, bins)
        contact = np.concatenate(contact_blocks)
        samples = rho.shape[0]
        return RodProfiles(
            (np.arange(c.bins) + 0.5) * width,
            rho.mean(0),
            rho.std(0, ddof=1) / math.sqrt(samples),
            contact.mean(0),
            contact.std(0, ddof=1) / math.sqrt(samples),
            per_block * blocks,
        )
