"""One BCD study as the ``fricgen bcd`` command runs it: equilibrate, sample, compare with the exact
theory, write the profile (CSV), a plot against the theory (PNG) and a summary (dict for JSON).

Everything that can be checked is checked before the Monte Carlo start: the :class:`Study` (times,
replicas, gap bins), the output folder and every output path in it (a folder where a file goes is
refused, with or without ``--force``), the time step against the schemes' range
(fricgen.rods.stability) and the exact theory (the field, the pair potential, sigma on the theory's
grid, a density it can solve), which is computed first. A folder that holds a result already is refused
unless ``--force``; the new files are written beside the old ones, each a new file of its own (never
through a link planted in the folder), and renamed over them at the end."""

from __future__ import annotations

import os
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...errors import ConfigError
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
from ...rods.stability import refuse_step
from ...schema import Section
from ..run.outputs import check_folder

REFINEMENT = 4  # --extrapolate: a second run at dt / 4
#: The files a study writes into its folder.
OUTPUTS = ("profile.csv", "profile.png")


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


def _sample(config: RodConfig, duration: float, equilibration: float) -> tuple[RodProfiles, float]:
    """From the Monte Carlo equilibrium start, ``equilibration`` at dt (the BCD contact layer forms), then sample;
    the profiles and the fraction of steps that the Metropolis test rejected (0 without it)."""
    simulation = RodSimulation(config)
    simulation.equilibrate(equilibration)
    return simulation.run(max(1, round(duration / config.numerics.dt))), simulation.rejection


def study(plan: Study, out: Path, force: bool = False) -> dict:
    """Run, compare and write ``profile.csv``, ``profile.png`` into ``out`` and return the summary.

    Args:
        plan: the study.
        out: the output folder; one that holds a result already is refused unless ``force``.
        force: replace the result in ``out``.

    Returns:
        The summary (deviations from the exact theory, steps, seconds, the configuration).

    Raises:
        ConfigError: ``--out`` holds a result (without ``force``), or ``--time`` was too short for
            every bin's error (chi^2 would be infinite); nothing is written then.
    """
    config, duration, equilibration, extrapolate = plan.config, plan.time, plan.equilibrate, plan.extrapolate
    check_folder(out, "--out")
    taken = [name for name in OUTPUTS if (out / name).exists() or (out / name).is_symlink()]
    for name in taken:  # a link is replaced itself (never its target); anything else but a file cannot be replaced
        path = out / name
        if not (path.is_symlink() or path.is_file()):
            what = "a folder" if path.is_dir() else "not a regular file"
            problem = f"{path} is {what}: the result cannot replace it; nothing was run"
            raise ConfigError("--out", problem, "move it away, or give another --out")
    if taken and not force:
        raise ConfigError("--out", f"{out} already holds a result ({', '.join(taken)})", "give another --out, or --force to replace it")
    refuse_step(config.model, config.numerics.dt)
    exact = exact_profile(config)
    start = time.perf_counter()
    measured, rejection = _sample(config, duration, equilibration)
    if extrapolate:
        fine, _ = _sample(config.replace(dt=config.numerics.dt / REFINEMENT), duration, equilibration)
        measured = extrapolate_to_zero_dt(measured, fine, REFINEMENT, config.numerics.error_order)
    seconds = time.perf_counter() - start
    with np.errstate(divide="ignore", invalid="ignore"):
        compared = deviations(measured, exact, contact=config.model.hard_rods or config.model.sticky_boundary)
    if not np.isfinite(compared["chi2_per_dof"]):
        raise ConfigError(
            "--time",
            f"{duration:g} per replica left bins without scatter between replicas: chi^2 cannot be estimated; nothing was written",
            "give a longer --time",
        )
    summary = {
        **compared,
        "steps": measured.steps,
        "seconds": seconds,
        "extrapolated_to_zero_dt": extrapolate,
        **({"rejected_fraction": rejection} if config.numerics.tested else {}),
        "config": config.as_flat(),
    }
    baxter = None
    if config.model.gamma > 0 and not config.model.sticky_boundary:  # the delta_eps representation vs Baxter's limit (B-29)
        baxter = _baxter(config, exact)
        summary["representation_error_max"] = float(np.max(np.abs(exact.rho - baxter.rho)))
    out.mkdir(parents=True, exist_ok=True)
    written = []
    try:  # beside the old result, then each renamed over it: a stop leaves old files or new ones, never half of one
        for name, write in zip(
            OUTPUTS, (lambda file: _write_csv(measured, exact, file), lambda file: _plot(measured, exact, baxter, config, file))
        ):
            handle, path = _new_file(out, name)
            written.append(path)
            with os.fdopen(handle, "wb") as file:
                write(file)
        for name, path in zip(OUTPUTS, written):
            os.replace(path, out / name)  # replaces a link at out / name itself, never its target
    finally:
        for path in written:
            path.unlink(missing_ok=True)
    return summary


def _new_file(out: Path, name: str) -> tuple[int, Path]:
    """A new file ``out/.new-NAME.XXXXXXXX`` of our own, opened for writing (O_EXCL: never a name that
    exists, so never a link planted in the folder), with the permissions the umask gives new files."""
    handle, path = tempfile.mkstemp(prefix=f".new-{name}.", dir=out)
    mask = os.umask(0)
    os.umask(mask)
    os.fchmod(handle, 0o666 & ~mask)
    return handle, Path(path)


def _baxter(config: RodConfig, exact: RodProfile) -> RodProfile:
    c = config.model
    return rod_profile(field_energy(c), c.sigma, c.mean_density, c.wavelength, c.kT, Neighbours(c.gamma), exact.x.size)


def _write_csv(measured: RodProfiles, exact: RodProfile, file) -> None:
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
    np.savetxt(file, np.column_stack(list(columns.values())), delimiter=",", header=",".join(columns), comments="", fmt="%.10g")


def _plot(measured: RodProfiles, exact: RodProfile, baxter: RodProfile | None, config: RodConfig, file) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c, dt = config.model, config.numerics.dt
    panels = 2 if c.hard_rods or c.sticky_boundary else 1
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
    figure.savefig(file, dpi=120, format="png")
    plt.close(figure)
