"""Poiseuille flow in a slit: the partial-slip Stokes profile (F-43) fitted to a measured v_x(y).

A body force F e_x on every particle of number density n is the pressure gradient -dP/dx = n F.
Stokes, eta v'' = -n F, with Navier slip at the hydrodynamic boundaries y = +-y_B
(v(y_B) = -b v'(y_B), b the slip length) gives

    v_x(y) = n F (y_B^2 - y^2) / (2 eta) + n F y_B b / eta,

which is (F-43) with n = 6 phi / pi (phi the volume fraction, sigma = 1). y_B is the accessible
boundary of the centres, the wall half-width less one contact distance (7.5847 sigma for the
paper's slit), and n = N / V with V the accessible volume. The fit uses the bins that lie entirely
inside |y| <= y_B and holds particles; each bin's weight is its block error (curve_fit with
absolute_sigma), so the errors of eta and b are one standard deviation and chi^2 / dof tests the
model, if the bins fluctuate independently; :func:`frame_errors` gives the errors when they do not
(the slow flow modes move all bins together). Units: sigma = 1, kT = 1, m = 1, t0; eta in
kT t0 / sigma^3, b in sigma. See docs/poiseuille.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import curve_fit

from ..errors import ConfigError
from .config import RunConfig


def stokes_profile(y: np.ndarray, eta: float, slip: float, density: float, force: float, boundary: float) -> np.ndarray:
    """v_x(y) = n F (y_B^2 - y^2) / (2 eta) + n F y_B b / eta (F-43)."""
    return density * force / eta * ((boundary**2 - np.asarray(y) ** 2) / 2 + boundary * slip)


@dataclass(frozen=True)
class SlitFit:
    """The fitted viscosity ``eta`` and slip length ``slip`` with one-sigma errors and their
    correlation, chi^2 over ``dof`` degrees of freedom, and the inputs: number ``density`` n,
    ``force`` F, ``boundary`` y_B, and which profile bins entered (``used``)."""

    eta: float
    eta_err: float
    slip: float
    slip_err: float
    correlation: float
    chi2: float
    dof: int
    density: float
    force: float
    boundary: float
    used: np.ndarray

    @property
    def reduced_chi2(self) -> float:
        return self.chi2 / self.dof if self.dof > 0 else float("nan")

    def profile(self, y: np.ndarray) -> np.ndarray:
        return stokes_profile(y, self.eta, self.slip, self.density, self.force, self.boundary)

    def as_dict(self) -> dict:
        names = ("eta", "eta_err", "slip", "slip_err", "correlation", "chi2", "dof", "density", "force", "boundary")
        return {name: getattr(self, name) for name in names} | {"reduced_chi2": self.reduced_chi2, "bins_used": self.used.tolist()}


def inside(y: np.ndarray, width: float, boundary: float) -> np.ndarray:
    """Bins of centre y and ``width`` that lie entirely in |y| <= y_B (to 1e-9 sigma)."""
    return np.abs(np.asarray(y)) + width / 2 <= boundary + 1e-9


def fit_slit_profile(y, v, v_err, width: float, density: float, force: float, boundary: float) -> SlitFit:
    """Fit (F-43) to the profile bins (centres y, ``width``) inside |y| <= y_B with a finite mean v and a
    positive error v_err; raises ConfigError with fewer than 3 such bins or without a force."""
    y, v, v_err = (np.asarray(a, dtype=float) for a in (y, v, v_err))
    used = inside(y, width, boundary) & np.isfinite(v) & np.isfinite(v_err) & (v_err > 0)
    if used.sum() < 3:
        raise ConfigError("velocity_profile", f"only {used.sum()} bins with data inside the slit", "run longer or use narrower bins")
    if force == 0 or density <= 0:
        raise ConfigError("bulk.force", "the slit fit needs a bulk force along x and particles", "give bulk.force = [F, 0, 0]")
    ys, vs, es = y[used], v[used], v_err[used]
    # The model is linear in A = n F / (2 eta) and C = n F y_B b / eta: the weighted linear solve is the
    # chi^2 minimum, the start that curve_fit refines in (eta, b).
    design = np.stack([boundary**2 - ys**2, np.ones_like(ys)], axis=1) / es[:, None]
    (curvature, offset), *_ = np.linalg.lstsq(design, vs / es, rcond=None)
    start = (density * force / (2 * curvature), offset / (2 * curvature * boundary)) if curvature else (1.0, 0.0)

    def model(y, eta, slip):
        return stokes_profile(y, eta, slip, density, force, boundary)

    parameters, covariance = curve_fit(model, ys, vs, p0=start, sigma=es, absolute_sigma=True)
    errors = np.sqrt(np.diag(covariance))
    chi2 = float(np.sum(((vs - model(ys, *parameters)) / es) ** 2))
    correlation = float(covariance[0, 1] / (errors[0] * errors[1]))
    return SlitFit(*map(float, (parameters[0], errors[0], parameters[1], errors[1])), correlation, chi2, int(used.sum() - 2),
                   density, force, boundary, np.flatnonzero(used))  # fmt: skip


def slit_geometry(half_width: float, radius: float, box, dim: int) -> tuple[float, float]:
    """The accessible boundary y_B = half_width - 2 radius (a centre touching a wall sphere of the same
    radius) and the accessible volume (area in 2-D): box with L_y replaced by 2 y_B."""
    boundary = half_width - 2 * radius
    lengths = [2 * boundary if axis == 1 else box[axis] for axis in range(dim)]
    return boundary, float(np.prod(lengths))


def frame_errors(fit: SlitFit, y, v_err, frames: np.ndarray, blocks: int = 20) -> tuple[float, float]:
    """One-sigma errors of eta and b from the time series of per-frame fits: each frame's profile
    (rows of ``frames``, one column per bin) gives A_t = n F / (2 eta) and C_t = n F y_B b / eta by the
    fit's weighted linear solve (their means are the fit of the mean profile); the covariance of their
    ``blocks`` block means is propagated to (eta, b). Unlike the per-bin errors this counts bins that
    fluctuate together (the slow flow modes of the slit); frames with an empty used bin are skipped."""
    used = fit.used
    frames = np.asarray(frames, dtype=float)[:, used]
    frames = frames[np.all(np.isfinite(frames), axis=1)]
    if frames.shape[0] < 2 * blocks:
        return float("nan"), float("nan")
    weight = 1 / np.asarray(v_err, dtype=float)[used]
    design = np.stack([fit.boundary**2 - np.asarray(y)[used] ** 2, np.ones(used.size)], axis=1) * weight[:, None]
    series = frames @ (np.linalg.pinv(design) * weight[None, :]).T  # (frames, 2): A_t, C_t
    means = series[: frames.shape[0] // blocks * blocks].reshape(blocks, -1, 2).mean(axis=1)
    covariance = np.cov(means.T) / blocks
    a = fit.density * fit.force / (2 * fit.eta)
    jacobian = np.array([[-fit.eta / a, 0.0], [-fit.slip / a, 1 / (2 * a * fit.boundary)]])
    errors = np.sqrt(np.diag(jacobian @ covariance @ jacobian.T))
    return float(errors[0]), float(errors[1])


def fit_slit_run(config: RunConfig, n: int, profile: dict, width: float) -> SlitFit:
    """The fit of a slit run's profile (``summary["velocity_profile"]``, bins of ``width``): n = N / V
    and y_B from the configuration, F = bulk.force[0]."""
    s = config.system
    boundary, volume = slit_geometry(config.walls.half_width, s.radius, s.box, s.dimension)
    v, v_err = ([np.nan if x is None else x for x in profile[key]] for key in ("v_x", "v_x_err"))
    return fit_slit_profile(profile["y"], v, v_err, width, n / volume, config.bulk.vector[0], boundary)
