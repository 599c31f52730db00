"""The Euler–Lagrange equations of the rod functionals at a profile, zero at equilibrium: the check that
fricgen.rods.theory's transfer-operator profiles minimise Percus's hard-rod functional (B-20b) and the
sticky-rod functional (B-34a..c) of the BCD paper, independent of how they were computed."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .theory import Grid, RodProfile


def percus_residual(profile: RodProfile, potential: Callable[[np.ndarray], np.ndarray], sigma: float, kT: float = 1.0) -> np.ndarray:
    """The Euler-Lagrange equation of Percus's hard-rod functional (B-20b), zero at equilibrium.

    ln rho(x) - ln(1 - eta(x)) - beta mu_ch + beta U(x) + int_x^{x+sigma} rho/(1 - eta) dy.

    Parameters
    ----------
    profile : RodProfile
        A hard-rod :func:`rod_profile`.
    potential : callable
        U(x) [kT] it was computed in.
    sigma : float
        The rod length [lambda].
    kT : float
        The thermal energy [kT].

    Returns
    -------
    numpy.ndarray
        The residual on the profile's grid [1].
    """
    grid = Grid(profile.x[1] * profile.x.size, profile.x.size, sigma)
    phi = profile.rho / (1 - profile.eta)
    return np.log(phi) - profile.beta_mu + potential(profile.x) / kT + grid.window(phi, True)


def sticky_residual(
    profile: RodProfile, potential: Callable[[np.ndarray], np.ndarray], sigma: float, gamma: float, kT: float = 1.0
) -> np.ndarray:
    """The functional derivative (B-34a..c) of the sticky-rod functional, zero at equilibrium.

    Parameters
    ----------
    profile : RodProfile
        Baxter's rods (:func:`rod_profile` with ``Neighbours(gamma, eps=None)``).
    potential : callable
        U(x) [kT] it was computed in.
    sigma : float
        The rod length [lambda].
    gamma : float
        The stickiness [lambda].
    kT : float
        The thermal energy [kT].

    Returns
    -------
    numpy.ndarray
        The residual on the profile's grid [1].
    """
    grid = Grid(profile.x[1] * profile.x.size, profile.x.size, sigma)
    rho, eta = profile.rho, profile.eta
    ahead, gap_ahead = grid.shift(rho), 1 - grid.shift(eta)  # rho(x + sigma), 1 - eta(x + sigma)
    difference = (ahead - rho) / gap_ahead
    k_hat = (-(1 - gamma * difference) + np.sqrt((1 - gamma * difference) ** 2 + 4 * gamma * ahead / gap_ahead)) / (2 * gamma)  # (B-34b)
    k_hat_behind = np.roll(k_hat, grid.steps)  # K^(x - sigma)
    k = k_hat_behind - (rho - np.roll(rho, grid.steps)) / (1 - eta)  # K(x) (B-34c)
    root = np.sqrt(1 + 2 * gamma * (ahead + rho) / gap_ahead + gamma**2 * difference**2) / (2 * gamma)
    return (
        np.log(grid.shift(k) * k_hat_behind / rho)
        + potential(profile.x) / kT
        - profile.beta_mu
        + 0.5 * np.log((1 - eta) * gap_ahead)
        - sigma / (2 * gamma)
        + grid.window(root, False)
    )
