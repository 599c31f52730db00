"""BCD against the exact theory: the exact profile of the model a RodConfig simulates, and the
deviations of a measured profile from it (docs/physics.md#exact-theory-of-rods)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConfigError
from .config import RodConfig
from .interactions import field_energy, on_arrays, pair_kernels
from .neighbours import HARD_RODS, Neighbours
from .theory import RodProfile, rod_profile


@dataclass(frozen=True)
class RodProfiles:
    """Measured profiles over one wavelength at bin centres (:meth:`RodSimulation.run`).

    Attributes
    ----------
    x : numpy.ndarray
        The bin centres [lambda].
    rho : numpy.ndarray
        The density [1/lambda].
    rho_err : numpy.ndarray
        Its standard error, from the replicas.
    contact : numpy.ndarray
        The pair density at contact rho_2(x, x + sigma+) [1/lambda^2].
    contact_err : numpy.ndarray
        Its standard error.
    steps : int
        The sampled steps.
    contact_cov : numpy.ndarray or None
        The covariance of the contact estimates between bins (from the replicas); None: not known.
    """

    x: np.ndarray
    rho: np.ndarray
    rho_err: np.ndarray
    contact: np.ndarray
    contact_err: np.ndarray
    steps: int
    contact_cov: np.ndarray | None = None


def exact_profile(config: RodConfig) -> RodProfile:
    """The exact equilibrium (fricgen.rods.theory) of the model a RodConfig simulates, on a ring of its length;
    the grid (600 to 2400 points per wavelength) has sigma on a grid point.

    Parameters
    ----------
    config : RodConfig
        The rods' configuration.

    Returns
    -------
    RodProfile
        The exact profile over one wavelength, with the O(1/L) correction of the ring.

    Raises
    ------
    ConfigError
        For an open line, a σ/λ that is no fraction k/m with 600 ≤ m ≤ 2400, or a density
        too close to close packing for the theory in double precision (at model.n).
    """
    c = config.model
    try:
        return rod_profile(field_energy(c), c.sigma, c.mean_density, c.wavelength, c.kT, *_theory(config), ring_length=c.length)
    except ConfigError as error:
        if error.key != "rod_profile":
            raise
        raise ConfigError("model.n", error.problem, "use fewer rods") from error


def _theory(config: RodConfig) -> tuple[Neighbours, int]:
    """The neighbours and the grid (points per wavelength, sigma on a point) of the exact theory; ConfigError as
    in :func:`exact_profile`."""
    c = config.model
    if c.open_line:
        raise ConfigError("model.length", "the exact theory is for a ring of finite length, not an open line", "give a finite length")
    ratio = c.sigma / c.wavelength
    points = next((m for m in range(600, 2401) if abs(ratio * m - round(ratio * m)) < 1e-9), None)
    if points is None:
        raise ConfigError("model.sigma", f"sigma / lambda = {ratio} is not a fraction k / m with 600 <= m <= 2400", "round sigma")
    neighbours = Neighbours(c.gamma, c.eps or None, c.p) if c.gamma > 0 else HARD_RODS  # eps = 0: Baxter (B-29)
    if c.pair is not None:
        module, params, reach = pair_kernels(c)
        neighbours = Neighbours(pair=on_arrays(module.energy, params), pair_range=reach)
    return neighbours, points


def compressibility(config: RodConfig) -> float:
    """chi = d rho_bar / d(beta mu_ch) of the infinite line (1 / lambda), by a central difference of the exact
    theory at rho_bar (1 +- 1e-3): the mean of |sum_j exp(i k x_j)|^2 / L for 2 pi / L <= k << 2 pi / lambda.
    ConfigError as in :func:`exact_profile`."""
    c = config.model
    neighbours, points = _theory(config)
    step = 1e-3 * c.mean_density
    below, above = (
        rod_profile(field_energy(c), c.sigma, c.mean_density + sign * step, c.wavelength, c.kT, neighbours, points).beta_mu
        for sign in (-1, 1)
    )
    return 2 * step / (above - below)


def deviations(measured: RodProfiles, exact: RodProfile, contact: bool = True) -> dict[str, float | None]:
    """A measured profile against the exact one's bin means.

    Parameters
    ----------
    measured : RodProfiles
        The profiles of :meth:`RodSimulation.run`, with their errors from the replicas.
    exact : RodProfile
        The exact profile (:func:`exact_profile`).
    contact : bool
        Also compare the contact density ρ₂(x, x + σ⁺) (hard rods), over the bins where the
        exact one exceeds 30 % of its maximum.

    Returns
    -------
    dict[str, float | None]
        ``max_abs_dev`` (``max |Δρ|`` [1/lambda]), ``l1_dev_over_rho`` (``mean |Δρ| / ρ̄``), ``chi2_per_dof`` (χ²
        per bin); with ``contact``: ``contact_chi2_per_dof``, ``contact_ratio`` (measured / exact, summed
        over the bins) and ``contact_ratio_err`` (from ``measured.contact_cov`` where known: the bins of
        a ring are correlated), None where too few pairs were measured.
    """
    bins = measured.x.size
    rho = exact.bin_means(bins)
    result = {
        "max_abs_dev": float(np.max(np.abs(measured.rho - rho))),
        "l1_dev_over_rho": float(np.mean(np.abs(measured.rho - rho)) / rho.mean()),
        "chi2_per_dof": float(np.mean(((measured.rho - rho) / measured.rho_err) ** 2)),
    }
    if contact:
        expected = exact.bin_means(bins, "contact")
        where = (expected > 0.3 * expected.max()) & np.isfinite(measured.contact) & (measured.contact_err > 0)
        figures = (None, None, None)  # too few pairs beyond the BCD layer to measure
        if where.sum() >= 2:
            total = expected[where].sum()
            if measured.contact_cov is None:  # bins taken as independent
                variance = np.sum(measured.contact_err[where] ** 2)
            else:  # the bins of one ring are correlated: their sum's variance is the covariance's sum
                variance = measured.contact_cov[np.ix_(where, where)].sum()
            figures = (
                float(np.mean(((measured.contact - expected) / measured.contact_err)[where] ** 2)),
                float(measured.contact[where].sum() / total),
                float(np.sqrt(variance) / total),
            )
        result.update(zip(("contact_chi2_per_dof", "contact_ratio", "contact_ratio_err"), figures))
    return result
