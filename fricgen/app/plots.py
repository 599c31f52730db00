"""Figures of the demo: velocity and spin histograms against Maxwell–Boltzmann, and T_eff; the
velocity and spin profiles of a slit run with their Stokes fit.

Samples are the scaled components sqrt(m) v_a and sqrt(I) omega_z, so every histogram is compared
with one density, sqrt(1 / 2 pi kT) exp(-x^2 / 2 kT), at the bath's kT and at the fitted T_eff.
Drawn with matplotlib's object interface (no pyplot state, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..langevin.analysis import Sampler, maxwell_boltzmann
from ..langevin.thermostat_check import CheckResult
from .poiseuille import SlitFit

COLOURS = ("tab:blue", "tab:red")


def _label(result: CheckResult) -> str:
    return "with contact noise" if result.contact_noise else "without contact noise"


def histogram_figure(runs: list[tuple[CheckResult, Sampler]], path: Path, kT: float = 1.0) -> Path:
    """Histograms of sqrt(m) v_a (left) and sqrt(I) omega_z (right) of each run, the Maxwell–Boltzmann
    density at kT (black) and at each run's T_eff (dashed)."""
    figure = Figure(figsize=(10, 4), layout="constrained")
    axes = figure.subplots(1, 2)
    edges = np.linspace(-4.5, 4.5, 61) * np.sqrt(kT)
    x = np.linspace(edges[0], edges[-1], 400)
    for axis, kind, title in zip(axes, ("trans", "rot"), (r"velocity $\sqrt{m}\,v_a$", r"angular velocity $\sqrt{I}\,\omega_z$")):
        axis.plot(x, maxwell_boltzmann(x, 1.0, kT), color="black", lw=1.5, label=f"Maxwell–Boltzmann, $k_BT = {kT:g}$")
        for (result, sampler), colour in zip(runs, COLOURS):
            samples = sampler.scaled_velocities() if kind == "trans" else sampler.scaled_spins()
            density, _ = np.histogram(samples, edges, density=True)
            temperature = result.T_trans if kind == "trans" else result.T_rot
            centres = 0.5 * (edges[1:] + edges[:-1])
            axis.plot(centres, density, "o", ms=3.5, color=colour, label=f"{_label(result)}: $T_{{eff}} = {temperature:.3f}$")
            axis.plot(x, maxwell_boltzmann(x, 1.0, temperature), "--", color=colour, lw=1)
        axis.set_title(title)
        axis.set_xlabel(r"$\sqrt{m}\,v_a$" if kind == "trans" else r"$\sqrt{I}\,\omega_z$")
        axis.set_ylabel("probability density")
        axis.set_ylim(0, 0.62)
        axis.legend(fontsize=7.5, loc="upper left", frameon=False)
    first = runs[0][0]
    figure.suptitle(f"{first.law} friction ({first.calculus}), {first.dim}-D passive system; dashed: Maxwell–Boltzmann at each run's T_eff")
    figure.savefig(path, dpi=120)
    return path


def temperature_figure(runs: list[tuple[CheckResult, Sampler]], path: Path, kT: float = 1.0) -> Path:
    """T_eff of translation and rotation of each run (bars with standard errors) and their table."""
    figure = Figure(figsize=(7, 5), layout="constrained")
    bars, table = figure.subplots(2, 1, height_ratios=(3, 1))
    for offset, ((result, _), colour) in enumerate(zip(runs, COLOURS)):
        bars.bar(
            np.arange(2) + 0.4 * offset - 0.2,
            [result.T_trans, result.T_rot],
            0.38,
            yerr=[result.T_trans_err, result.T_rot_err],
            color=colour,
            capsize=4,
            label=_label(result),
        )
    bars.axhline(kT, color="black", lw=1, label=f"$k_BT = {kT:g}$")
    bars.set_xticks([0, 1], ["translation", "rotation"])
    bars.set_ylabel(r"$T_{eff}$")
    bars.set_ylim(0, 1.25)
    bars.legend(fontsize=8, loc="upper center", ncols=3, frameon=False)
    table.axis("off")
    rows = [
        [_label(r), f"{r.T_trans:.4f} ± {r.T_trans_err:.4f}", f"{r.T_rot:.4f} ± {r.T_rot_err:.4f}", f"{r.kl_trans:.1e} / {r.kl_rot:.1e}"]
        for r, _ in runs
    ]
    table.table(cellText=rows, colLabels=["run", "T_trans", "T_rot", "KL trans / rot"], loc="center").scale(1, 1.4)
    figure.savefig(path, dpi=120)
    return path


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
