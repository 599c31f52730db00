"""Shear viscosity of a periodic bulk fluid from its transverse-current autocorrelation.

Without solvent (gamma = gamma_R = 0) the pairwise contacts and WCA forces conserve momentum, and a
transverse momentum mode j_b(k) = sum_i m_i v_ib exp(i k r_ia) (k along axis a, b != a) decays by
shear diffusion (linearised Navier–Stokes):

    C(k, t) = <j_b(k, t) j_b(-k, 0)> = C(k, 0) exp(-nu k^2 t),   nu = eta / rho_m,

with rho_m = sum_i m_i / V the mass density. The smallest wavenumbers of the box, k = 2 pi n / L_a,
give eta(k) per k (fitted after the first collisions, with a free amplitude); eta = lim eta(k) as
k -> 0 (eta(k) = eta - a k^2 + ...). Errors are the jackknife over independent time blocks.
Units: sigma = 1, kT = 1, m = 1, t0; nu in sigma^2 / t0, eta in kT t0 / sigma^3. See docs/poiseuille.md.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from scipy.optimize import curve_fit

from ...errors import ConfigError
from ...langevin.config import Bulk, Thermostat
from ...langevin.simulation import Simulation
from ..run.build import build
from ..run.config import Run, RunConfig, RunLaw, System

#: The (k axis a, current component b) pairs of transverse modes in 3-D and 2-D.
TRANSVERSE = {3: ((0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)), 2: ((0, 1), (1, 0))}


class CurrentSampler:
    """Observer for Simulation.run: records j_b(k) for k = 2 pi n / L, n = 1..``modes``, every call, in a
    cubic (square) box of side L; ``currents`` has shape (frames, modes, pairs) (complex), pairs as in TRANSVERSE."""

    def __init__(self, simulation: Simulation, modes: int = 3):
        state, particles = simulation.state, simulation.particles
        if not particles.mobile.all():
            raise ConfigError("walls", "the transverse-current method needs a periodic bulk without walls", "leave [walls] out")
        side = state.box[: state.dim]
        if not np.allclose(side, side[0]):
            raise ConfigError("system.box", f"the transverse currents need a cubic box, got {side.tolist()}", "give n and packing_fraction")
        self.pairs = TRANSVERSE[state.dim]
        self.mass = particles.mass
        self.k = 2 * np.pi * np.arange(1, modes + 1) / side[0]
        self.frames: list[np.ndarray] = []

    def __call__(self, simulation: Simulation) -> None:
        s = simulation.state
        phase = np.exp(1j * self.k[:, None, None] * s.position[None, :, : s.dim])  # (modes, N, axes)
        momentum = self.mass[:, None] * (s.velocity[:, : s.dim] - s.velocity[:, : s.dim].mean(axis=0))
        self.frames.append(np.stack([phase[:, :, a] @ momentum[:, b] for a, b in self.pairs], axis=1))

    @property
    def currents(self) -> np.ndarray:
        return np.array(self.frames)


def autocorrelation(series: np.ndarray, lags: int) -> np.ndarray:
    """Re <x(t + s) x*(t)> over all time origins t, for s = 0..lags-1, of complex series along axis 0
    (averaged over the other axes), by FFT."""
    n = series.shape[0]
    spectrum = np.fft.fft(series, 2 * n, axis=0)
    raw = np.fft.ifft(spectrum * spectrum.conj(), axis=0)[:lags].real
    return raw.reshape(lags, -1).mean(axis=1) / (n - np.arange(lags))


def decay_rate(t: np.ndarray, c: np.ndarray) -> float:
    """Least-squares rate lam of c(t) = A exp(-lam t) over the given points, c = C(t)/C(0) (A free: the
    hydrodynamic decay after the short-time, kinetic part)."""
    (_, rate), _ = curve_fit(lambda t, amplitude, rate: amplitude * np.exp(-rate * t), t, c, p0=(1.0, 1.0 / max(t[-1], 1e-12)))
    return float(rate)


@dataclass(frozen=True)
class BulkViscosity:
    """eta(k) per wavenumber with block errors, and the k -> 0 extrapolation eta = eta0 - a k^2."""

    k: np.ndarray
    eta_k: np.ndarray
    eta_k_err: np.ndarray
    eta: float
    eta_err: float
    mass_density: float
    blocks: int
    window: np.ndarray

    def as_dict(self) -> dict:
        return {key: value.tolist() if isinstance(value, np.ndarray) else value for key, value in dataclasses.asdict(self).items()}


def transverse_viscosity(
    currents: np.ndarray, k: np.ndarray, interval: float, mass_density: float, blocks: int = 16, fit_to: float = 1.0, after: float = 0.5
) -> BulkViscosity:
    """eta(k) = rho_m nu(k) from ``currents`` (frames, modes, pairs) sampled every ``interval`` t0 at
    wavenumbers ``k`` (one per mode): C(k, t)/C(k, 0) of the whole run is fitted by A exp(-nu k^2 t)
    over the lags from ``after`` t0 (past the collisional start) to where it first falls below
    exp(-fit_to) (at least 4 lags); the error is the jackknife over ``blocks`` time blocks (the fit
    repeated without each block). eta is the weighted fit eta0 - a k^2 (a single k: eta(k) itself)."""
    frames, modes = currents.shape[:2]
    if blocks < 2 or frames // blocks < 4:
        raise ConfigError("blocks", f"{frames} frames cannot make {blocks} blocks of at least 4", "sample longer or use fewer blocks")
    length = frames // blocks
    lags = np.arange(length) * interval
    window, eta_k, eta_k_err = np.empty(modes), np.empty(modes), np.empty(modes)
    for m in range(modes):
        parts = np.array([autocorrelation(currents[b * length : (b + 1) * length, m], length) for b in range(blocks)])
        whole = parts.mean(axis=0)
        first = min(round(after / interval), length - 4)
        below = np.nonzero(whole / whole[0] < np.exp(-fit_to))[0]
        last = max(below[0] if below.size else length - 1, first + 3)
        window[m] = lags[last]
        fitted = slice(first, last + 1)
        leave_one_out = (blocks * whole - parts) / (blocks - 1)
        rates = np.array([decay_rate(lags[fitted], c[fitted] / c[0]) for c in leave_one_out])
        eta_k[m] = mass_density * decay_rate(lags[fitted], whole[fitted] / whole[0]) / k[m] ** 2
        eta_k_err[m] = mass_density / k[m] ** 2 * np.sqrt((blocks - 1) * np.mean((rates - rates.mean()) ** 2))
    eta, eta_err = _extrapolate(k, eta_k, eta_k_err)
    return BulkViscosity(k, eta_k, eta_k_err, eta, eta_err, mass_density, blocks, window)


def _extrapolate(k: np.ndarray, eta_k: np.ndarray, eta_k_err: np.ndarray) -> tuple[float, float]:
    """Weighted least-squares eta0 of eta(k) = eta0 - a k^2, with its one-sigma error."""
    if k.size == 1:
        return float(eta_k[0]), float(eta_k_err[0])
    design = np.stack([np.ones_like(k), -(k**2)], axis=1) / eta_k_err[:, None]
    covariance = np.linalg.inv(design.T @ design)
    eta0 = covariance @ design.T @ (eta_k / eta_k_err)
    return float(eta0[0]), float(np.sqrt(covariance[0, 0]))


def bulk_config(law: RunLaw, n: int, packing_fraction: float, dimension: int = 3, dt: float = 1e-3, seed: int = 1) -> RunConfig:
    """A periodic cube (square) of n spheres at ``packing_fraction`` without solvent, walls or drive."""
    system = System(dimension=dimension, n=n, packing_fraction=packing_fraction)
    thermostat = Thermostat(gamma=0.0, gamma_rot=0.0, dt=dt)
    return RunConfig(system=system, law=law, thermostat=thermostat, bulk=Bulk(()), run=Run(seed=seed))


def measure_bulk_viscosity(
    config: RunConfig, equilibrate: float, duration: float, interval: float = 0.05, modes: int = 3, blocks: int = 16
):
    """Run ``config`` (periodic, no walls) for ``equilibrate`` t0, then sample the transverse currents
    every ``interval`` t0 for ``duration`` t0; returns (BulkViscosity, currents, k)."""
    if config.walls is not None or config.thermostat.gamma or config.thermostat.gamma_rot or any(config.bulk.force):
        raise ConfigError("config", "needs a periodic bulk without walls, solvent or bulk force (momentum conserved)", "use bulk_config")
    dt = config.thermostat.dt
    every = max(1, round(interval / dt))
    simulation = build(config)
    simulation.run(round(equilibrate / dt), every=every)
    sampler = CurrentSampler(simulation, modes)
    simulation.run(round(duration / dt), every=every, observers=[sampler])
    volume = np.prod(simulation.state.box[: simulation.state.dim])
    mass_density = float(simulation.particles.mass.sum() / volume)
    result = transverse_viscosity(sampler.currents, sampler.k, every * dt, mass_density, blocks)
    return result, sampler.currents, sampler.k
