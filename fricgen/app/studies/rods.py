"""One BCD study as the ``fricgen bcd`` command runs it: equilibrate, sample, compare with the exact
theory, write the profile (CSV), a plot against the theory (PNG) and a summary (dict for JSON).

Everything that can be checked is checked before the Monte Carlo start: the :class:`Study` (times,
replicas, gap bins), the output folder and the exact theory (the field, the pair potential, sigma on
the theory's grid), which is computed first."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...rods import (
    Neighbours,
    RodConfig,
    RodProfile,
    RodProfiles,
    RodSimulation,
    deviations,
    exact_profile,
    extrapolate_to_zero_dt,
    field_energy,
    rod_profile,
)
from ...schema import Section
from ..run.outputs import check_folder

REFINEMENT = 4  # --extrapolate: a second run at dt / 4


@dataclass(frozen=True)
class Study(Section):
    """A BCD study: ``config``, sampled for ``time`` per replica after ``equilibrate`` time units of BCD
    (from the Monte Carlo start), and with ``extrapolate`` once more at dt / REFINEMENT. Its profiles
    need 2 replicas or more (the errors) and the gap bins of the contact fit."""

    config: RodConfig
    time: float = field(default=1.25, metadata={"key": "--time"})
    equilibrate: float = field(default=0.25, metadata={"key": "--equilibrate"})
    extrapolate: bool = False

    def __post_init__(self):
        self.require_positive("time")
        self.require_nonnegative("equilibrate")
        c = self.config
        finest = c.numerics.dt / (REFINEMENT if self.extrapolate else 1)
        self.require_steps("time", (self.time + self.equilibrate) / finest)
        c.require_sampling()


def _sample(config: RodConfig, duration: float, equilibration: float) -> RodProfiles:
    """From the Monte Carlo equilibrium start, ``equilibration`` at dt (the BCD contact layer forms), then sample."""
    simulation = RodSimulation(config)
    simulation.equilibrate(equilibration)
    return simulation.run(max(1, round(duration / config.numerics.dt)))


def study(plan: Study, out: Path) -> dict:
    """Run, compare and write ``profile.csv``, ``profile.png`` into ``out`` and return the summary."""
    config, duration, equilibration, extrapolate = plan.config, plan.time, plan.equilibrate, plan.extrapolate
    check_folder(out, "--out")
    exact = exact_profile(config)
    start = time.perf_counter()
    measured = _sample(config, duration, equilibration)
    if extrapolate:
        fine = _sample(config.replace(dt=config.numerics.dt / REFINEMENT), duration, equilibration)
        measured = extrapolate_to_zero_dt(measured, fine, REFINEMENT)
    seconds = time.perf_counter() - start
    summary = {
        **deviations(measured, exact, contact=config.model.hard_rods),
        "steps": measured.steps,
        "seconds": seconds,
        "extrapolated_to_zero_dt": extrapolate,
        "config": config.as_flat(),
    }
    baxter = None
    if config.model.gamma > 0:  # the delta_eps representation vs Baxter's limit (B-29): an O(eps) difference
        baxter = _baxter(config, exact)
        summary["representation_error_max"] = float(np.max(np.abs(exact.rho - baxter.rho)))
    out.mkdir(parents=True, exist_ok=True)
    _write_csv(measured, exact, out / "profile.csv")
    _plot(measured, exact, baxter, config, out / "profile.png")
    return summary


def _baxter(config: RodConfig, exact: RodProfile) -> RodProfile:
    c = config.model
    return rod_profile(field_energy(c), c.sigma, c.mean_density, c.wavelength, c.kT, Neighbours(c.gamma), exact.x.size)


def _write_csv(measured: RodProfiles, exact: RodProfile, path: Path) -> None:
    bins = measured.x.size
    columns = {
        "x": measured.x,
        "rho": measured.rho,
        "rho_err": measured.rho_err,
        "rho2_contact": measured.contact,
        "rho2_contact_err": measured.contact_err,
        "rho_exact": exact.bin_means(bins),
        "rho2_contact_exact": exact.bin_means(bins, "contact"),
    }
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",", header=",".join(columns), comments="", fmt="%.10g")


def _plot(measured: RodProfiles, exact: RodProfile, baxter: RodProfile | None, config: RodConfig, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c, dt = config.model, config.numerics.dt
    panels = 2 if c.hard_rods else 1
    figure, axes = plt.subplots(1, panels, figsize=(5 * panels, 3.6), squeeze=False)
    title = f"N = {c.n}, L = {c.length:g}, $\\sigma$ = {c.sigma:g}, {c.field} $U_0$ = {c.U0:g}, dt = {dt:g}"
    axis = axes[0, 0]
    axis.plot(exact.x, exact.rho, "k-", lw=1, label="exact")
    if baxter is not None:
        axis.plot(baxter.x, baxter.rho, "k--", lw=1, label="Baxter limit")
    axis.errorbar(measured.x, measured.rho, measured.rho_err, fmt="o", ms=3, label="BCD")
    axis.set(xlabel="x / $\\lambda$", ylabel="$\\rho(x)$", title=title if panels == 1 else None)
    axis.legend()
    if panels == 2:
        axis = axes[0, 1]
        axis.plot(exact.x, exact.contact, "k-", lw=1, label="exact")
        axis.errorbar(measured.x, measured.contact, measured.contact_err, fmt="o", ms=3, label="BCD")
        axis.set(xlabel="x / $\\lambda$", ylabel="$\\rho_2(x, x + \\sigma)$")
        figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
