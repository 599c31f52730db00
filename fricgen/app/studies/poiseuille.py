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
kT t0 / sigma^3, b in sigma. See docs/poiseuille.md. A ``fricgen run`` of the kind ``slit_flow``
gets the fit as the ``poiseuille`` entry of its summary and its figure ``profiles.png``
(:func:`summarize_run`). :func:`contact_branches` counts the contacts of a frame on the Coulomb branch
of the Coulomb–Newton law (F-32), :func:`trajectory_branches` those of every frame of a run.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import gsd.hoomd
import numpy as np
from matplotlib.figure import Figure
from scipy.optimize import curve_fit
from scipy.spatial import cKDTree

from ...errors import ConfigError
from ...kernels import LawKernels, load_law_kernels
from ...langevin.pairs import WCA_RANGE
from ..run.config import RunConfig
from ..run.observables import read_table

if TYPE_CHECKING:  # a name only: importing the study (as fricgen.app does) compiles no engine
    from ...langevin.simulation import Simulation

PROFILES = "profiles.png"  # the velocity and spin profiles of a slit run, with the Stokes fit


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


def profile_frames(folder: Path, equilibrate: int, bins: int) -> np.ndarray:
    """The v_x profiles (rows: frames after step ``equilibrate``, columns: the ``bins`` slabs; NaN where
    empty) of a run folder's velocity_profile.csv."""
    header, rows = read_table(Path(folder) / "velocity_profile.csv")
    rows = rows[rows[:, 0] > equilibrate]
    return rows[:, [header.index(f"vx_{j}") for j in range(bins)]]


def summarize_run(config: RunConfig, simulation: Simulation, folder: Path, summary: dict) -> dict | None:
    """The ``poiseuille`` entry of a slit run's summary: the fit of its velocity profile (``{"error":
    why}`` when it cannot be fitted) with the errors of the per-frame fits (the velocity_profile table's
    rows after ``run.equilibrate``), and the figure ``profiles.png``; None without that observable."""
    profile = summary.get("velocity_profile")
    if profile is None:
        return None
    bins = config.output.profile_bins
    width = simulation.state.box[1] / bins
    frames = profile_frames(folder, config.run.equilibrate, bins)
    try:
        fit = fit_slit_run(config, summary["n"], profile, width)
    except ConfigError as error:
        fit, result = None, {"error": str(error)}
    else:
        errors = frame_errors(fit, profile["y"], [np.nan if e is None else e for e in profile["v_x_err"]], frames)
        result = fit.as_dict() | dict(zip(("eta_err_frames", "slip_err_frames"), errors))
    profiles_figure(profile, fit, folder / PROFILES)
    return result


def describe_run(fit: dict) -> list[str]:
    """The fit's line in the report of ``fricgen run``."""
    if "eta" not in fit:
        return []
    eta, slip = (f"{fit[key]:.4g} +- {fit[f'{key}_err']:.2g} (frames: {fit[f'{key}_err_frames']:.2g})" for key in ("eta", "slip"))
    return [f"Stokes fit (F-43): eta = {eta}, b = {slip}, chi2/dof = {fit['reduced_chi2']:.2f}; {PROFILES}"]


def profiles_figure(profile: dict, fit: SlitFit | None, path: Path) -> Path:
    """A slit's v_x(y) with block errors and the fitted partial-slip Stokes profile (F-43) (left), and
    omega_z(y) with half the vorticity of the fit, -v_x'(y) / 2 = n F y / (2 eta) (right); grey: bins
    left out of the fit, dotted: the boundaries +-y_B."""
    figure = Figure(figsize=(10, 4), layout="constrained")
    axes = figure.subplots(1, 2)
    y = np.asarray(profile["y"])
    used = np.zeros(y.size, bool)
    if fit is not None:
        used[fit.used] = True
    for axis, key, label in zip(axes, ("v_x", "omega_z"), (r"$v_x$ ($\sigma/t_0$)", r"$\omega_z$ ($1/t_0$)")):
        mean, error = (np.array([np.nan if x is None else x for x in profile[k]], dtype=float) for k in (key, f"{key}_err"))
        for chosen, colour in ((used, "tab:blue"), (~used, "0.6")):
            axis.errorbar(y[chosen], mean[chosen], error[chosen], fmt="o", ms=3, color=colour, capsize=2)
        axis.set_xlabel(r"$y$ ($\sigma$)")
        axis.set_ylabel(label)
    if fit is not None:
        inner = np.linspace(-fit.boundary, fit.boundary, 200)
        axes[0].plot(inner, fit.profile(inner), color="black", label=f"F-43: $\\eta = {fit.eta:.3g} \\pm {fit.eta_err:.2g}$, "
                     f"$b = {fit.slip:.3g} \\pm {fit.slip_err:.2g}$, $\\chi^2/dof = {fit.reduced_chi2:.2f}$")  # fmt: skip
        axes[1].plot(inner, fit.density * fit.force * inner / (2 * fit.eta), "--", color="black", label=r"$-v_x'(y)/2$ of the fit")
        for axis in axes:
            for side in (-1, 1):
                axis.axvline(side * fit.boundary, color="black", ls=":", lw=1)
            axis.legend(fontsize=8, loc="lower center", frameon=False)
    figure.suptitle("Poiseuille flow in the slit: velocity and spin profiles (block errors)")
    figure.savefig(path, dpi=120)
    return path


@dataclass(frozen=True)
class ContactBranches:
    """Pairs in contact (centre distance r < 2^(1/6) sigma_ik, at least one partner mobile) and how many
    of them are on the Coulomb branch of f = min(gamma_f u, w kappa_f) (F-32), i.e. gamma_f u > w kappa_f;
    ``wall``: the same counts for the pairs of a mobile and an immobile (wall) sphere."""

    contacts: int
    coulomb: int
    wall_contacts: int
    wall_coulomb: int

    @property
    def fraction(self) -> float:
        return self.coulomb / self.contacts if self.contacts else float("nan")

    @property
    def wall_fraction(self) -> float:
        return self.wall_coulomb / self.wall_contacts if self.wall_contacts else float("nan")


def contact_branches(position, velocity, omega, radius, mobile, box, kernels: LawKernels, parameters: np.ndarray) -> ContactBranches:
    """The contacts of one configuration and their branch of the Coulomb–Newton law (F-32).

    For each pair i < k within the WCA range (periodic in every direction with a positive box length),
    as the engine evaluates it: u = |P (v_k - v_i) - (R_i omega_i + R_k omega_k) x r_hat| (F-4) and
    w = weight(r / sigma_ik) / sigma_ik (= -dU_WCA/dr); the pair is on the Coulomb branch when
    gamma_f u > w kappa_f. Pairs of two immobile spheres are left out (the engine skips them).

    Args:
        position, velocity, omega: (N, 3) arrays (sigma, sigma/t0, 1/t0); positions anywhere (wrapped here).
        radius: (N,) radii (sigma); mobile: (N,) bool.
        box: the box lengths (sigma); a length 0 is a non-periodic axis (2-D: L_z = 0).
        kernels, parameters: the law's kernels and parameter array; the law must have a weight and the
            parameters gamma_f and kappa_f.
    """
    names = kernels.parameter_names
    if not kernels.has_weight or "gamma_f" not in names or "kappa_f" not in names:
        raise ConfigError("law", f"law {kernels.name} is not a Coulomb–Newton law with a weight", "use coulomb_newton")
    gamma_f, kappa_f = parameters[names.index("gamma_f")], parameters[names.index("kappa_f")]
    position, velocity, omega = (np.asarray(a, dtype=float) for a in (position, velocity, omega))
    radius, mobile = np.asarray(radius, dtype=float), np.asarray(mobile, dtype=bool)
    box = np.asarray(box, dtype=float)[:3]
    periodic = box > 0
    reach = WCA_RANGE * 2 * radius.max()
    data = np.where(periodic, np.mod(position, np.where(periodic, box, 1.0)), position - position.min(axis=0))
    size = np.where(periodic, box, data.max(axis=0) + 2 * reach)  # a non-periodic axis: no image within reach
    data = np.minimum(data, np.nextafter(size, 0))  # float rounding can give exactly L
    pairs = cKDTree(data, boxsize=size).query_pairs(reach, output_type="ndarray")
    i, k = pairs[:, 0], pairs[:, 1]
    d = position[k] - position[i]
    d -= np.where(periodic, box * np.round(d / np.where(periodic, box, 1.0)), 0.0)
    r = np.linalg.norm(d, axis=1)
    sigma = radius[i] + radius[k]
    keep = (r < WCA_RANGE * sigma) & (mobile[i] | mobile[k])
    i, k, d, r, sigma = i[keep], k[keep], d[keep], r[keep], sigma[keep]
    n = d / r[:, None]
    relative = velocity[k] - velocity[i]
    spin = radius[i, None] * omega[i] + radius[k, None] * omega[k]
    tangential = relative - np.sum(relative * n, axis=1)[:, None] * n - np.cross(spin, n)
    u = np.linalg.norm(tangential, axis=1)
    w = np.array([kernels.weight(x, parameters) for x in r / sigma]) / sigma
    coulomb = gamma_f * u > w * kappa_f
    wall = ~(mobile[i] & mobile[k])
    return ContactBranches(int(r.size), int(coulomb.sum()), int(wall.sum()), int((coulomb & wall).sum()))


def trajectory_branches(path: str | Path, law: str, parameters: dict, first_step: int = 0) -> tuple[list[int], list[ContactBranches]]:
    """The steps and :func:`contact_branches` of the frames at steps >= ``first_step`` of a fricgen GSD
    trajectory (positions, velocities, ``log/particles/angular_velocity``; type 0 mobile), for the law
    ``law`` with ``parameters`` (a run's config.json ``law.name`` and ``law.parameters``)."""
    kernels = load_law_kernels(law)
    values = kernels.parameters(**parameters)
    steps, counts = [], []
    with gsd.hoomd.open(str(path), "r") as trajectory:
        for frame in trajectory:
            if int(frame.configuration.step) < first_step:
                continue
            p = frame.particles
            counts.append(contact_branches(p.position, p.velocity, frame.log["particles/angular_velocity"], p.diameter / 2,
                                           p.typeid == 0, frame.configuration.box[:3], kernels, values))  # fmt: skip
            steps.append(int(frame.configuration.step))
    return steps, counts


@dataclass(frozen=True)
class SlabTemperatures:
    """The temperatures of a slit in ``bins`` equal slabs along y (slab j spans [j, j + 1) L_y / bins from
    -L_y / 2, as the velocity profile's), pooled over samples (particle and frame): per slab the number
    of samples ``count``, the streaming velocity ``flow`` u_j = sum m v / sum m (sigma/t0, one row per
    slab) and, in kT, ``T_trans`` = <m |v|^2> / d (with the flow), ``T_peculiar`` = <m |v - u_j|^2> / d
    times count / (count - 1) (u_j is estimated from the same samples) and ``T_rot`` = <I |omega|^2> / d_rot,
    averaged over the d (d_rot) components; NaN where a slab has fewer than two samples."""

    y: np.ndarray
    count: np.ndarray
    flow: np.ndarray
    T_trans: np.ndarray
    T_peculiar: np.ndarray
    T_rot: np.ndarray

    def slit(self, key: str) -> float:
        """The sample-weighted mean of a temperature over the slabs (the whole slit)."""
        values, used = getattr(self, key), self.count > 1
        return float(np.sum(values[used] * self.count[used]) / np.sum(self.count[used]))


def slab_temperatures(y, velocity, omega, mass, inertia, length: float, bins: int) -> SlabTemperatures:
    """:class:`SlabTemperatures` of samples at heights ``y`` (sigma, in [-length / 2, length / 2)) with
    velocities (S, d) [sigma/t0], spins (S, d_rot) [1/t0], masses (S,) [m] and moments of inertia
    (a number, (S,) or (S, d_rot)) [m sigma^2]; ``length`` = L_y."""
    y, velocity, omega, mass = (np.asarray(a, dtype=float) for a in (y, velocity, omega, mass))
    inertia = np.asarray(inertia, dtype=float)
    inertia = inertia if inertia.ndim == 2 else np.broadcast_to(inertia, len(y))[:, None]
    slab = np.clip(((y / length + 0.5) * bins).astype(int), 0, bins - 1)
    count = np.bincount(slab, minlength=bins).astype(float)
    used = np.where(count > 1, count, np.nan)
    weight = np.bincount(slab, mass, bins)
    flow = np.stack([np.bincount(slab, mass * v, bins) for v in velocity.T], axis=1) / np.where(count > 1, weight, np.nan)[:, None]
    peculiar = velocity - flow[slab]
    dims = velocity.shape[1]

    def slab_mean(values: np.ndarray) -> np.ndarray:
        return np.bincount(slab, values, bins) / used

    return SlabTemperatures(
        y=(np.arange(bins) + 0.5) * length / bins - length / 2,
        count=count,
        flow=flow,
        T_trans=slab_mean(mass * np.sum(velocity**2, axis=1)) / dims,
        T_peculiar=slab_mean(mass * np.sum(peculiar**2, axis=1)) / dims * used / (used - 1),
        T_rot=slab_mean(np.sum(inertia * omega**2, axis=1)) / omega.shape[1],
    )


def trajectory_samples(path: str | Path, first_step: int = 0) -> list[tuple]:
    """Per frame at steps >= ``first_step`` of a fricgen GSD trajectory, its mobile particles (type 0)
    as (y, velocity, omega, mass, moment of inertia), and L_y last: the arguments of
    :func:`slab_temperatures` but ``bins``."""
    frames = []
    with gsd.hoomd.open(str(path), "r") as trajectory:
        for frame in trajectory:
            if int(frame.configuration.step) < first_step:
                continue
            p, mobile = frame.particles, frame.particles.typeid == 0
            omega, length = frame.log["particles/angular_velocity"][mobile], float(frame.configuration.box[1])
            frames.append((p.position[mobile, 1], p.velocity[mobile], omega, p.mass[mobile], p.moment_inertia[mobile], length))
    return frames
