"""Equilibrium observables: effective temperatures, Maxwell–Boltzmann histograms, KL divergence.

T_eff is the maximum-likelihood fit of a Maxwell–Boltzmann distribution to the sampled velocity
(angular velocity) components: T = <m v_a^2> over particles, components and frames. Its error is
the standard error of block means over time (blocks much longer than the velocity correlation
time). The Kullback–Leibler divergence (F-41) compares the histogram of one component scaled by
its fitted width with the fitted Gaussian.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .system import Particles, State


def scaled_components(state: State, particles: Particles) -> tuple[np.ndarray, np.ndarray]:
    """√m v and √I ω of the mobile particles, one column per degree of freedom (2-D: v_x, v_y and
    ω_z; 3-D: three each); each has variance kT at equilibrium.

    Parameters
    ----------
    state : State
        The state.
    particles : Particles
        Masses and moments of inertia, and which particles are mobile.

    Returns
    -------
    tuple[np.ndarray, np.ndarray]
        (√m v, √I ω), each of shape (mobile particles, degrees of freedom) [sqrt(kT)].
    """
    mobile = particles.mobile
    spin_axes = slice(2, 3) if state.dim == 2 else slice(0, 3)
    velocities = state.velocity[mobile, : state.dim] * np.sqrt(particles.mass[mobile, None])
    spins = state.omega[mobile, spin_axes] * np.sqrt(particles.inertia[mobile, None])
    return velocities, spins


def temperatures(state: State, particles: Particles) -> tuple[float, float]:
    """Instantaneous kinetic temperatures of translation and rotation of the mobile particles,
    T_trans = ⟨m v_a²⟩ and T_rot = ⟨I ω_a²⟩ over their degrees of freedom.

    Parameters
    ----------
    state : State
        The state.
    particles : Particles
        Masses and moments of inertia, and which particles are mobile.

    Returns
    -------
    tuple[float, float]
        (T_trans, T_rot) [kT].
    """
    velocities, spins = scaled_components(state, particles)
    return float(np.mean(velocities**2)), float(np.mean(spins**2))


def velocity_profile(state: State, particles: Particles, bins: int) -> tuple[np.ndarray, np.ndarray]:
    """Mean v_x and ω_z of the mobile particles in ``bins`` equal slabs along y (slab j spans
    [j, j + 1) L_y / bins): the flow and spin profiles of a slit.

    Parameters
    ----------
    state : State
        The state.
    particles : Particles
        Which particles are mobile.
    bins : int
        The number of slabs.

    Returns
    -------
    tuple[np.ndarray, np.ndarray]
        (v_x, ω_z) per slab [sigma/t0] and [1/t0]; NaN where a slab is empty.
    """
    mobile = particles.mobile
    slab = np.minimum((state.position[mobile, 1] / state.box[1] * bins).astype(int), bins - 1)
    counts = np.bincount(slab, minlength=bins).astype(float)
    counts[counts == 0] = np.nan
    vx = np.bincount(slab, state.velocity[mobile, 0], bins) / counts
    wz = np.bincount(slab, state.omega[mobile, 2], bins) / counts
    return vx, wz


@dataclass(frozen=True)
class Estimate:
    """A mean with its standard error from block averages (:func:`block_estimate`).

    Attributes
    ----------
    mean : float
        The mean, in the series' units.
    error : float
        Its standard error, in the same units.
    blocks : int
        The number of blocks.
    """

    mean: float
    error: float
    blocks: int


def block_estimate(series: np.ndarray, blocks: int = 20) -> Estimate:
    """Mean and standard error of a time series from ``blocks`` contiguous block means.

    The error is the standard deviation of the block means over √blocks, which counts the series'
    correlations as long as a block is longer than its correlation time.

    Parameters
    ----------
    series : np.ndarray
        The samples, in time order (a trailing remainder shorter than a block is dropped).
    blocks : int
        The number of blocks.

    Returns
    -------
    Estimate
        The mean, its standard error and the number of blocks.

    Raises
    ------
    ValueError
        For fewer than 2·blocks samples.
    """
    series = np.asarray(series, dtype=float)
    if series.size < 2 * blocks:
        raise ValueError(f"need at least {2 * blocks} samples for {blocks} blocks, got {series.size}")
    usable = series.size // blocks * blocks
    means = series[:usable].reshape(blocks, -1).mean(axis=1)
    return Estimate(float(means.mean()), float(means.std(ddof=1) / math.sqrt(blocks)), blocks)


def kl_divergence(samples: np.ndarray, bins: int = 41, span: float = 4.0) -> float:
    """D_KL(P_sim || P_fit) (F-41) of zero-mean samples against their fitted Gaussian.

    Samples are scaled by the fitted width; the histogram on [-span, span] with ``bins`` bins is
    compared with the Gaussian's exact bin probabilities. The plug-in estimate has a positive bias
    of about (bins - 1) / (2 n) for n independent samples.

    Parameters
    ----------
    samples : np.ndarray
        Zero-mean samples, e.g. √m v components.
    bins : int
        The number of histogram bins.
    span : float
        The half width of the histogram, in fitted standard deviations.

    Returns
    -------
    float
        The divergence [1] (0 for a perfect Gaussian).
    """
    x = np.asarray(samples, dtype=float).ravel()
    x = x / math.sqrt(np.mean(x**2))
    edges = np.linspace(-span, span, bins + 1)
    counts, _ = np.histogram(x, edges)
    p = counts / x.size
    from math import erf

    cdf = np.array([0.5 * (1 + erf(e / math.sqrt(2))) for e in edges])
    q = np.diff(cdf)
    nonzero = p > 0
    return float(np.sum(p[nonzero] * np.log(p[nonzero] / q[nonzero])))


def maxwell_boltzmann(x: np.ndarray, mass: float, kT: float) -> np.ndarray:
    """Density of one velocity component, √(m / 2πkT) exp(−m x² / 2kT).

    Parameters
    ----------
    x : np.ndarray
        Velocity values [sigma/t0].
    mass : float
        The mass m [m].
    kT : float
        The temperature [kT].

    Returns
    -------
    np.ndarray
        The probability density at each x [t0/sigma].
    """
    return np.sqrt(mass / (2 * np.pi * kT)) * np.exp(-mass * x**2 / (2 * kT))


class Sampler:
    """An observer for :meth:`Simulation.run`: records temperatures and velocity components per frame.

    Parameters
    ----------
    particles : Particles
        The particles (masses, moments of inertia, which are mobile).
    keep_samples : int
        How many scaled velocity components to keep at most (the temperatures are kept for every frame).
    """

    def __init__(self, particles: Particles, keep_samples: int = 200_000):
        self.particles = particles
        self.trans: list[float] = []
        self.rot: list[float] = []
        self.velocities: list[np.ndarray] = []
        self.spins: list[np.ndarray] = []
        self.keep = keep_samples

    def __call__(self, simulation) -> None:
        velocities, spins = scaled_components(simulation.state, self.particles)
        self.trans.append(float(np.mean(velocities**2)))
        self.rot.append(float(np.mean(spins**2)))
        if sum(v.size for v in self.velocities) < self.keep:
            self.velocities.append(velocities.ravel())
            self.spins.append(spins.ravel())

    def scaled_velocities(self) -> np.ndarray:
        """The recorded sqrt(m) v components.

        Returns
        -------
        numpy.ndarray
            One flat array [sqrt(kT)]; variance kT at equilibrium.
        """
        return np.concatenate(self.velocities)

    def scaled_spins(self) -> np.ndarray:
        """The recorded sqrt(I) omega components.

        Returns
        -------
        numpy.ndarray
            One flat array [sqrt(kT)]; variance kT at equilibrium.
        """
        return np.concatenate(self.spins)
