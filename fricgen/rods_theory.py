"""Exact equilibrium of hard rods in an external potential: Percus's density functional (B-20..23).

Minimising (B-20a) gives the Euler–Lagrange equation

    rho(x) = (1 - eta(x)) exp[beta mu_ch - beta U(x) - int_x^{x+sigma} rho(y) / (1 - eta(y)) dy],
    eta(x) = int_{x-sigma}^{x} rho(y) dy                                                (B-20b)

solved here on a periodic grid over one wavelength lambda: the infinite-system profile at mean
density rho_bar (B-22). The two-particle density at contact is (B-23)
rho_2(x, x + sigma) = rho(x) rho(x + sigma) / (1 - eta(x + sigma)). Uniform limit: Tonks,
beta P = rho / (1 - rho sigma), beta mu_ch = ln(rho / (1 - rho sigma)) + rho sigma / (1 - rho sigma).
Integrals use the trapezoidal rule with sigma a whole number of grid steps (error O(h^2)).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq


@dataclass(frozen=True)
class RodProfile:
    """Equilibrium profile over one period: grid x, rho(x), eta(x), rho_2(x, x + sigma), beta mu_ch."""

    x: np.ndarray
    rho: np.ndarray
    eta: np.ndarray
    contact: np.ndarray
    beta_mu: float

    def at(self, points: np.ndarray, field: str = "rho") -> np.ndarray:
        """Periodic linear interpolation of a field at arbitrary points."""
        period = self.x[1] * self.x.size
        values = getattr(self, field)
        return np.interp(np.mod(points, period), np.append(self.x, period), np.append(values, values[0]))


def _window(values: np.ndarray, h: float, steps: int, forward: bool) -> np.ndarray:
    """Periodic trapezoidal integral of ``values`` over [x - steps h, x] (or [x, x + steps h])."""
    m = values.size
    cell = 0.5 * h * (values + np.roll(values, -1))  # integral over [x_j, x_j+1]
    cumulative = np.concatenate([[0.0], np.cumsum(cell)])  # over [0, x_j], j = 0..m
    total = cumulative[-1]
    j = np.arange(m)
    lower = j - steps if not forward else j
    upper = j if not forward else j + steps

    def primitive(index):
        periods, rest = np.divmod(index, m)
        return periods * total + cumulative[rest]

    return primitive(upper) - primitive(lower)


def _window_matrix(m: int, h: float, steps: int, forward: bool) -> np.ndarray:
    """The linear map values -> _window(values) as a dense matrix."""
    return np.column_stack([_window(column, h, steps, forward) for column in np.eye(m)])


def hard_rod_profile(
    potential: Callable[[np.ndarray], np.ndarray],
    sigma: float,
    mean_density: float,
    wavelength: float = 1.0,
    kT: float = 1.0,
    points: int = 600,
    tolerance: float = 1e-12,
) -> RodProfile:
    """Percus's exact profile of hard rods of length sigma at mean density rho_bar in U(x) (period lambda).

    With phi = rho / (1 - eta) the Euler–Lagrange equation reads ln phi(x) = beta mu_ch - beta U(x)
    - int_x^{x+sigma} phi: for given mu it is solved for ln phi by Newton's method, rho then follows
    from the linear equation rho(x) + phi(x) int_{x-sigma}^x rho = phi(x), and mu is adjusted until
    the mean of rho is rho_bar. Raises ValueError beyond close packing (rho_bar sigma >= 1).
    """
    if not 0 < mean_density * sigma < 1:
        raise ValueError(f"need 0 < rho_bar sigma < 1 (close packing), got {mean_density * sigma}")
    steps = round(sigma / wavelength * points)
    h = wavelength / points
    if steps < 1 or abs(steps * h - sigma) > 1e-9 * sigma:
        raise ValueError(f"sigma = {sigma} must be a whole number of grid steps wavelength / points = {h}")
    x = np.arange(points) * h
    beta_u = potential(x) / kT
    ahead, behind = _window_matrix(points, h, steps, True), _window_matrix(points, h, steps, False)
    identity = np.eye(points)

    state = {"log_phi": np.full(points, -np.log1p(sigma)) - beta_u, "beta_mu": 0.0}

    def density(beta_mu: float) -> np.ndarray:
        log_phi = state["log_phi"] + (beta_mu - state["beta_mu"])  # warm start from the last solution
        for _ in range(200):
            phi = np.exp(log_phi)
            residual = log_phi - beta_mu + beta_u + ahead @ phi
            if np.max(np.abs(residual)) < tolerance:
                break
            log_phi -= np.linalg.solve(identity + ahead * phi[None, :], residual)
        else:
            raise ValueError(f"Newton iteration for ln phi did not converge at beta mu = {beta_mu}")
        state["log_phi"], state["beta_mu"] = log_phi, beta_mu
        return np.linalg.solve(identity + phi[:, None] * behind, phi)

    packing = mean_density * sigma
    guess = np.log(mean_density / (1 - packing)) + packing / (1 - packing)  # Tonks

    def excess(m: float) -> float:
        return float(np.log(density(m).mean() / mean_density))

    lo, hi, width = guess - 1.0, guess + 1.0, 1.0
    while excess(lo) > 0:
        width *= 2
        lo -= width
    while excess(hi) < 0:
        width *= 2
        hi += width
    beta_mu = brentq(excess, lo, hi, xtol=1e-12)
    rho = density(beta_mu)
    eta = behind @ rho
    contact = rho * np.roll(rho, -steps) / (1.0 - np.roll(eta, -steps))
    return RodProfile(x, rho, eta, contact, float(beta_mu))


def tonks(mean_density: float, sigma: float) -> tuple[float, float]:
    """(beta P, beta mu_ch) of the uniform hard-rod fluid (Tonks)."""
    packing = mean_density * sigma
    return mean_density / (1 - packing), float(np.log(mean_density / (1 - packing)) + packing / (1 - packing))
