"""Figures of the demo: velocity and spin histograms against Maxwell–Boltzmann, and T_eff.

Samples are the scaled components sqrt(m) v_a and sqrt(I) omega_z, so every histogram is compared
with one density, sqrt(1 / 2 pi kT) exp(-x^2 / 2 kT), at the bath's kT and at the fitted T_eff.
Drawn with matplotlib's object interface (no pyplot state, no display needed).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ...langevin.analysis import Sampler, maxwell_boltzmann
from .thermostat_check import CheckResult

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
