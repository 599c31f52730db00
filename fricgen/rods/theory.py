"""Exact equilibrium of hard and sticky rods in a periodic external potential.

Rods of length sigma interact only with their nearest neighbours (hard core plus a contact range
eps < sigma), so the equilibrium of the infinite line at pressure P is a Markov chain of positions:
a rod at x is followed by the next at y > x with kernel

    G(x, y) = z W(y - x) exp[-beta P (y - x) - beta U(y)],   W(r) = exp[-beta V_int(r)] for r >= sigma,

W = 1 for hard rods, W = 1 + gamma delta_eps(r - sigma) for the sticky representation (B-31) that
the simulation uses, W = exp[-beta V(r)] for any continuous pair potential V of range sigma + a,
a < sigma (B-28; nearest neighbours only), and W = 1 + gamma delta(r - sigma) for Baxter's sticky
rods (B-29). Folded onto one wavelength lambda, G is a circulant matrix times the Boltzmann factor;
with z = 1 / Lambda (its Perron root) and left/right eigenvectors l, r:

    rho(x) ~ l(x) r(x),   1 / rho_bar = <y - x> = -d ln Lambda / d(beta P),   beta mu_ch = -ln Lambda,

and the nearest-neighbour pair density at contact is rho_2(x, x + sigma+) = rho(x) G(x, x + sigma+)
r(x + sigma) / r(x): for hard rods the two-particle density at contact (B-23, B-26). beta P is found
from rho_bar. The profile solves Percus's functional (B-20b) and, for Baxter's rods, the stationarity
condition (B-34): ``percus_residual`` and ``sticky_residual`` evaluate both. Uniform limits: Tonks
(``tonks``) and Baxter's sticky rods (``sticky_rods``), in fricgen.rods.uniform. Integrals use linear interpolation on a grid
with sigma a whole number of steps h, exp(-beta P r) integrated exactly (error O(h^2), none uniform).

On a ring of length L with a fixed number of rods the profile differs by O(1/L) (canonical versus
grand canonical): rho_N(x) = rho(x) - chi / (2L) d^2 rho(x) / d rho_bar^2, chi = d rho_bar / d(beta mu_ch)
(``ring_length``).

The physics: docs/physics.md#exact-theory-of-rods.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.sparse.linalg import ArpackError, LinearOperator, eigs

from ..errors import ConfigError
from .neighbours import HARD_RODS, Neighbours, PairWeight


@dataclass(frozen=True)
class RodProfile:
    """The exact equilibrium of rods over one period (:func:`rod_profile`).

    Attributes
    ----------
    x : numpy.ndarray
        The grid [lambda].
    rho : numpy.ndarray
        The density rho(x) [1/lambda].
    eta : numpy.ndarray
        The local packing fraction eta(x) = int_{x-sigma}^x rho dy [1].
    contact : numpy.ndarray
        The pair density at contact rho_2(x, x + sigma+) [1/lambda^2].
    beta_mu : float
        The chemical potential beta mu_ch [1].
    beta_pressure : float
        The pressure beta P [1/lambda].

    Examples
    --------
    >>> import numpy as np
    >>> from fricgen.rods import rod_profile, tonks
    >>> flat = rod_profile(lambda x: np.zeros_like(x), sigma=0.5, mean_density=1.0)
    >>> print(f"{flat.beta_pressure:.6f} {tonks(1.0, 0.5)[0]:.6f}")  # no field: Tonks, beta P = rho/(1 - rho sigma)
    2.000000 2.000000
    """

    x: np.ndarray
    rho: np.ndarray
    eta: np.ndarray
    contact: np.ndarray
    beta_mu: float
    beta_pressure: float

    def at(self, points: np.ndarray, field: str = "rho") -> np.ndarray:
        """Periodic linear interpolation of a field at arbitrary points.

        Parameters
        ----------
        points : numpy.ndarray
            Positions [lambda].
        field : str
            "rho", "eta" or "contact".

        Returns
        -------
        numpy.ndarray
            The field's values there, in its units.
        """
        period = self.x[1] * self.x.size
        values = getattr(self, field)
        return np.interp(np.mod(points, period), np.append(self.x, period), np.append(values, values[0]))

    def bin_means(self, bins: int, field: str = "rho") -> np.ndarray:
        """Means of a field over equal bins of one period (to compare with histograms).

        Parameters
        ----------
        bins : int
            The number of bins.
        field : str
            "rho", "eta" or "contact".

        Returns
        -------
        numpy.ndarray
            One mean per bin, in the field's units.
        """
        period = self.x[1] * self.x.size
        edges = np.linspace(0.0, period, bins + 1)
        return np.array([self.at(np.linspace(a, b, 41), field).mean() for a, b in zip(edges, edges[1:])])


@dataclass(frozen=True)
class Grid:
    """Periodic grid of one wavelength with sigma = steps * h."""

    wavelength: float
    points: int
    sigma: float

    @property
    def h(self) -> float:
        return self.wavelength / self.points

    @property
    def steps(self) -> int:
        steps = round(self.sigma / self.h)
        if steps < 1 or abs(steps * self.h - self.sigma) > 1e-9 * self.sigma:
            raise ConfigError("rod_profile", f"sigma = {self.sigma} must be a whole number of grid steps wavelength / points = {self.h}")
        return steps

    @property
    def x(self) -> np.ndarray:
        return np.arange(self.points) * self.h

    def window(self, values: np.ndarray, forward: bool) -> np.ndarray:
        """Periodic trapezoidal integral of ``values`` over [x - sigma, x] (or [x, x + sigma])."""
        m, steps = self.points, self.steps
        cell = 0.5 * self.h * (values + np.roll(values, -1))  # integral over [x_j, x_j+1]
        cumulative = np.concatenate([[0.0], np.cumsum(cell)])
        j = np.arange(m)
        lower, upper = (j, j + steps) if forward else (j - steps, j)

        def primitive(index):
            periods, rest = np.divmod(index, m)
            return periods * cumulative[-1] + cumulative[rest]

        return primitive(upper) - primitive(lower)

    def shift(self, values: np.ndarray) -> np.ndarray:
        """values(x + sigma)."""
        return np.roll(values, -self.steps)


def _hat_integrals(a: float) -> tuple[float, float, float, float]:
    """Exponential integrals of the linear hat functions in units of h, with a = beta P h:
    interior phi(a) = int hat(t) e^(-a t) dt = (2 cosh a - 2) / a^2, end point psi(a) = (a - 1 + e^-a) / a^2,
    and their derivatives (series below a = 0.5 to avoid cancellation)."""
    if a < 0.5:
        from math import factorial

        phi = sum(2 * a ** (2 * n) / factorial(2 * n + 2) for n in range(10))
        dphi = sum(4 * n * a ** (2 * n - 1) / factorial(2 * n + 2) for n in range(1, 10))
        psi = sum((-a) ** n / factorial(n + 2) for n in range(18))
        dpsi = sum(n * (-1) ** n * a ** (n - 1) / factorial(n + 2) for n in range(1, 18))
        return phi, dphi, psi, dpsi
    phi = (2 * np.cosh(a) - 2) / a**2
    psi = (a - 1 + np.exp(-a)) / a**2
    return phi, 2 * np.sinh(a) / a**2 - 2 * phi / a, psi, -np.expm1(-a) / a**2 - 2 * psi / a


def _excess_weights(grid: Grid, beta_p: float, weight: PairWeight) -> tuple[np.ndarray, np.ndarray]:
    """int hat_k(r) [W(r) - 1] exp(-beta P r) dr and its first moment in r, for the hat functions at
    r_k = sigma + k h (Gauss–Legendre on each piece of [sigma, sigma + reach])."""
    h, reach = grid.h, weight.reach
    nodes, weights = np.polynomial.legendre.leggauss(12)
    count = int(np.ceil(reach / h)) + 1
    row, moment = np.zeros(count), np.zeros(count)
    for k in range(count):
        for lo, hi in ((k - 1) * h, k * h), (k * h, (k + 1) * h):
            lo, hi = max(lo, 0.0), min(hi, reach)
            if hi <= lo:
                continue
            g = 0.5 * (hi - lo) * nodes + 0.5 * (hi + lo)
            integrand = (1 - np.abs(g / h - k)) * weight.excess(g) * np.exp(-beta_p * (grid.sigma + g))
            row[k] += 0.5 * (hi - lo) * weights @ integrand
            moment[k] += 0.5 * (hi - lo) * weights @ (integrand * (grid.sigma + g))
    return row, moment


def _kernel_rows(grid: Grid, beta_p: float, weight: PairWeight) -> tuple[np.ndarray, np.ndarray]:
    """First row of the circulant kernel c(d) (d = (j - i) mod m) and of its first moment in r,
    summed over all images y - x = r0(d) + n lambda >= sigma: the integrand is interpolated linearly
    between grid points and integrated exactly against exp(-beta P r) W(r) (exact when uniform)."""
    m, h, s = grid.points, grid.h, grid.steps
    d = np.arange(m)
    k = d + m * np.ceil((s - d) / m).astype(int)  # r0 = k h, the smallest image at or beyond sigma
    r0 = k * h
    phi, dphi, psi, dpsi = _hat_integrals(beta_p * h)
    edge = k == s  # the core edge r = sigma is an end point
    q = np.exp(-beta_p * grid.wavelength)
    images = q / (1 - q)
    decay = h * np.exp(-beta_p * r0)
    row = decay * (np.where(edge, psi, phi) + phi * images)
    image_moment = phi * images * (r0 + grid.wavelength / (1 - q)) - h * dphi * images
    moment = decay * (np.where(edge, psi * r0 - h * dpsi, phi * r0 - h * dphi) + image_moment)
    if weight.excess is not None:  # W = 1 + excess, first image only (reach < sigma)
        extra, extra_moment = _excess_weights(grid, beta_p, weight)
        where = (s + np.arange(extra.size)) % m
        row[where] += extra
        moment[where] += extra_moment
    if weight.bond > 0:  # Baxter: gamma delta(r - sigma) (B-29)
        bond = weight.bond * np.exp(-beta_p * grid.sigma)
        row[s % m] += bond
        moment[s % m] += bond * grid.sigma
    return row, moment


def _correlate(row: np.ndarray, values: np.ndarray, transpose: bool = False) -> np.ndarray:
    """(C v)_i = sum_j c((j - i) mod m) v_j for the circulant kernel with first row c (or C^T v), by FFT."""
    spectrum = np.fft.rfft(row)
    return np.fft.irfft((spectrum if transpose else np.conj(spectrum)) * np.fft.rfft(values), n=row.size)


def _perron(apply, size: int, start: np.ndarray | None) -> tuple[float, np.ndarray]:
    """Perron root and vector (sum 1) of a positive operator; ARPACK starts from ``start`` or, to be
    reproducible bit for bit, from the uniform vector (not from a random one)."""
    operator = LinearOperator((size, size), matvec=apply, dtype=float)
    value, vector = eigs(operator, k=1, which="LR", v0=np.ones(size) if start is None else start, tol=0)
    vector = np.real(vector[:, 0])
    return float(np.real(value[0])), vector / vector.sum()


class _Chain:
    """The folded transfer operator K = C diag(B) at given beta P; caches eigenvectors for warm starts."""

    def __init__(self, grid: Grid, boltzmann: np.ndarray, weight: PairWeight):
        self.grid, self.boltzmann, self.weight = grid, boltzmann, weight
        self.left = self.right = None

    def solve(self, beta_p: float) -> float:
        """Perron root and eigenvectors at beta P; returns the mean spacing <y - x>."""
        row, moment = _kernel_rows(self.grid, beta_p, self.weight)
        b, m = self.boltzmann, row.size
        self.row = row
        self.value, self.right = _perron(lambda v: _correlate(row, b * v.ravel()), m, self.right)
        _, self.left = _perron(lambda v: b * _correlate(row, v.ravel(), transpose=True), m, self.left)
        self.beta_p = beta_p
        return float(self.left @ _correlate(moment, b * self.right) / (self.value * (self.left @ self.right)))

    def residual(self) -> float:
        """The largest error of the eigenvectors relative to each of their points, |K r - Lambda r| / (Lambda r)
        and the same for l: near close packing the vectors span more decades than double precision holds
        (factors exp(-beta P lambda)), and their small entries, hence rho = l r, are noise. Points where the
        field's Boltzmann factor is below 1e-100 of its largest are left out."""
        b, value = self.boltzmann, self.value
        right = _correlate(self.row, b * self.right) - value * self.right
        left = b * _correlate(self.row, self.left, transpose=True) - value * self.left
        where = b > 1e-100  # not where the field alone empties the line (rho there below exp(-230) of its peak)
        with np.errstate(divide="ignore", invalid="ignore"):
            worst = np.max(np.abs(np.concatenate([right / self.right, left / self.left])[np.tile(where, 2)])) / value
        return float(worst) if np.isfinite(worst) else np.inf


#: The largest relative error of the transfer operator's eigenvectors at any point that a profile may have.
EIGENVECTOR_TOLERANCE = 1e-6


def _infinite_profile(beta_u: np.ndarray, grid: Grid, mean_density: float, weight: PairWeight) -> tuple[RodProfile, _Chain]:
    chain = _Chain(grid, np.exp(-(beta_u - beta_u.min())), weight)
    tonks_pressure = mean_density / (1 - mean_density * grid.sigma)

    def excess(log_beta_p: float) -> float:
        with np.errstate(invalid="ignore", divide="ignore"):  # NaN near close packing: refused below
            return float(np.log(mean_density * chain.solve(np.exp(log_beta_p))))

    lo, hi = np.log(tonks_pressure) - 1.0, np.log(tonks_pressure) + 1.0
    try:
        while excess(lo) < 0:
            lo -= 2.0
        while excess(hi) > 0:
            hi += 2.0
        brentq(excess, lo, hi, xtol=1e-14, rtol=1e-15)
        chain.solve(chain.beta_p)  # the state of the root
        error = chain.residual()
    except ConfigError:
        raise
    except (ValueError, ArithmeticError, ArpackError):  # NaN spacings, no convergence: vectors beyond double precision
        error = np.inf
    if not error <= EIGENVECTOR_TOLERANCE:
        packing = mean_density * grid.sigma
        raise ConfigError(
            "rod_profile",
            f"the exact theory cannot be solved in double precision at rho_bar sigma = {packing:.4g} (too close to close packing, "
            f"relative eigenvector error {error:.1e})",
            "lower the density",
        )
    rho = chain.left * chain.right
    rho *= mean_density / rho.mean()
    right = chain.right
    contact = rho * np.exp(-chain.beta_p * grid.sigma) * grid.shift(chain.boltzmann * right) / (chain.value * right)
    if weight.excess is not None:
        contact *= 1 + float(weight.excess(np.zeros(1))[0])  # W(sigma+)
    beta_mu = beta_u.min() - np.log(chain.value)
    return RodProfile(grid.x, rho, grid.window(rho, False), contact, float(beta_mu), chain.beta_p), chain


def rod_profile(
    potential: Callable[[np.ndarray], np.ndarray],
    sigma: float,
    mean_density: float,
    wavelength: float = 1.0,
    kT: float = 1.0,
    neighbours: Neighbours = HARD_RODS,
    points: int = 600,
    ring_length: float | None = None,
) -> RodProfile:
    """Exact equilibrium profile of rods of length σ at mean density ρ̄ in U(x), by the transfer operator.

    Parameters
    ----------
    potential : Callable[[np.ndarray], np.ndarray]
        U(x) [kT], for arrays of positions [lambda].
    sigma : float
        The rod length σ [lambda] (any one length unit works; λ = 1 in fricgen.rods).
    mean_density : float
        The mean density ρ̄ [1/lambda], with ρ̄σ < 1.
    wavelength : float
        The period λ of U [lambda].
    kT : float
        The thermal energy [kT].
    neighbours : Neighbours
        The interaction beyond the hard core (default: hard rods).
    points : int
        Grid points per wavelength (σ must lie on a grid point).
    ring_length : float | None
        L of a ring of fixed N = ρ̄L, for its O(1/L) correction; None: the infinite line.

    Returns
    -------
    RodProfile
        ρ(x), the pair density at contact ρ₂(x, x + σ⁺) (including W(σ⁺); for Baxter without the
        bonded delta weight), βμ_ch and βP.

    Raises
    ------
    ConfigError
        At or beyond close packing (ρ̄σ ≥ 1).
    """
    if not 0 < mean_density * sigma < 1:
        raise ConfigError("rod_profile", f"need 0 < rho_bar sigma < 1 (close packing), got {mean_density * sigma}")
    weight = neighbours.weight(sigma, wavelength, kT)
    grid = Grid(wavelength, points, sigma)
    beta_u = np.asarray(potential(grid.x), dtype=float) / kT
    profile, _ = _infinite_profile(beta_u, grid, mean_density, weight)
    if ring_length is None:
        return profile
    step = 1e-3 * mean_density
    below, above = (_infinite_profile(beta_u, grid, mean_density + sign * step, weight)[0] for sign in (-1, 1))
    chi = 2 * step / (above.beta_mu - below.beta_mu)  # d rho_bar / d beta mu
    curvature = (above.rho - 2 * profile.rho + below.rho) / step**2
    rho = profile.rho - chi / (2 * ring_length) * curvature
    contact_curvature = (above.contact - 2 * profile.contact + below.contact) / step**2
    contact = profile.contact - chi / (2 * ring_length) * contact_curvature
    return RodProfile(grid.x, rho, grid.window(rho, False), contact, profile.beta_mu, profile.beta_pressure)
