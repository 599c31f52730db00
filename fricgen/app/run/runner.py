"""``fricgen run``: a configured simulation with its outputs, a progress bar, a clean stop on Ctrl-C
and resume from a checkpoint.

The output folder holds ``config.json`` (the validated configuration), ``trajectory.gsd`` (a frame
every ``trajectory_period`` steps from step 0), one CSV table per observable (every ``period``
steps, see :mod:`fricgen.app.run.observables`), ``checkpoint.npz`` (every ``checkpoint_period`` steps,
at the end and on Ctrl-C) and, when the run completes, ``summary.json``: averages over the steps after
``run.equilibrate`` with block standard errors, and the entry of the study of each kind of the run
(:mod:`fricgen.app.run.registry`: the Stokes fit of a slit flow, MIPS of active discs). Everything is
validated before the folder is touched. Exit status: 0 done, 1 the simulation blew up, 2 a bad
configuration, 130 stopped by Ctrl-C.
"""

from __future__ import annotations

import os
import shlex
import sys
import time
from collections.abc import Sequence
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fricgen.derive.law.catalogues import BUILT_IN, LawSearch

from ...errors import ConfigError, SimulationError
from ...langevin.simulation import Simulation
from ...langevin.trajectory import GSDWriter, load_checkpoint, save_checkpoint, truncate_trajectory
from ...schema import differences
from .build import build, check
from .checkpoints import check_checkpoint
from .config import OBSERVABLES, RunConfig, load_config, parse_override, resolve_source
from .observables import Periodic, observable_table, read_table, series_summary, truncate_table
from .outputs import CHECKPOINT, CONFIG, SUMMARY, TRAJECTORY, check_folder, check_temporaries, dumps
from .progress import ProgressBar, RunInterrupted, StopOnInterrupt
from .registry import STUDIES, Study

RUN_FILES = (CHECKPOINT, TRAJECTORY, SUMMARY, CONFIG, *(f"{name}.csv" for name in OBSERVABLES))


@dataclass(frozen=True)
class Plan:
    """A validated run: what to simulate, from which state, into which folder."""

    config: RunConfig
    simulation: Simulation
    folder: Path
    resumed: bool
    command: list[str]


def plan(source: str, settings: list[str], steps: int | None, out: str | None, resume: str | None, search: LawSearch = BUILT_IN) -> Plan:
    """A run of ``fricgen run``, everything checked and nothing written.

    Parameters
    ----------
    source : str
        A TOML file, or the name of a bundled example (``passive``, ``poiseuille``, ``active``).
    settings : list[str]
        Overrides ``SECTION.KEY=VALUE`` (TOML values), as ``--set``.
    steps : int | None
        Overrides ``run.steps``; None keeps the file's.
    out : str | None
        The output folder; None: ``fricgen-<config name>``.
    resume : str | None
        A checkpoint of a stopped run to continue, or None.
    search : LawSearch
        Where law names are looked up (the edge's ``--laws`` and FRICGEN_LAWS), with the
        configuration's ``law.folder``.

    Returns
    -------
    Plan
        The plan: the validated configuration, the simulation at its first step and the folder.

    Raises
    ------
    ConfigError
        Naming the key, the problem and the fix.
    """
    path = resolve_source(source)
    overrides = [parse_override(text) for text in settings] + ([("run.steps", steps)] if steps is not None else [])
    config = load_config(path, overrides)
    command = ["fricgen", "run", source, *(arg for text in settings for arg in ("--set", text))]
    command += ["--steps", str(steps)] if steps is not None else []
    command += [arg for folder in search.folders for arg in ("--laws", str(folder))]
    return _plan(config, command, out, resume, path.stem, search)


def check_run(source: str, settings: list[str], search: LawSearch = BUILT_IN) -> RunConfig:
    """The configuration of a run, checked as :func:`plan` checks a fresh one up to placing the
    particles (the file, the overrides, the law, the box), without building the simulation: a
    sweep's check of its points. ConfigError naming the key and the fix."""
    config = load_config(resolve_source(source), [parse_override(text) for text in settings])
    check(config, search)
    return config


def _plan(config: RunConfig, command: list[str], out: str | None, resume: str | None, name: str, search: LawSearch) -> Plan:
    if resume is None:
        folder = Path(out) if out else Path(f"fricgen-{name}")
        check_folder(folder, "--out")
        check_temporaries(folder, "--out")
        taken = [name for name in RUN_FILES if (folder / name).exists()]
        if taken:
            raise ConfigError(
                "--out",
                f"{folder} already holds a run ({', '.join(taken)})",
                f"give another --out, delete it, or continue it with --resume {folder / CHECKPOINT}",
            )
        return Plan(config, build(config, search), folder, False, command)
    checkpoint = Path(resume)
    if not checkpoint.is_file():
        raise ConfigError("--resume", f"no checkpoint file {checkpoint}", "give the checkpoint.npz of the interrupted run")
    if out and Path(out).resolve() != checkpoint.parent.resolve():
        raise ConfigError("--out", f"{out} is not the folder of the checkpoint {checkpoint}", "leave --out away when resuming")
    check_folder(checkpoint.parent, "--resume")
    check_temporaries(checkpoint.parent, "--resume")
    check_checkpoint(checkpoint)
    fresh = build(config, search)
    try:
        simulation = load_checkpoint(checkpoint, law=fresh.law)
    except ConfigError:  # a checkpoint of another version of the law
        raise
    except (OSError, ValueError, KeyError, TypeError) as error:  # a file that is no checkpoint, or one of another version
        raise ConfigError(
            "--resume", f"cannot read the checkpoint {checkpoint}: {error}", "give a checkpoint.npz written by fricgen run"
        ) from error
    _check_resume(config, simulation, fresh)
    _check_outputs(checkpoint.parent, simulation.state.step)
    return Plan(config, simulation, checkpoint.parent, True, command)


def _check_outputs(folder: Path, step: int) -> None:
    """The files a resume continues (the trajectory, the tables) can be read back to ``step``: a
    damaged one is refused before anything in the folder changes."""
    import gsd.hoomd

    path = folder / TRAJECTORY
    try:
        if path.exists():
            with gsd.hoomd.open(str(path), "r") as trajectory:
                len(trajectory)
        for name in OBSERVABLES:
            path = folder / f"{name}.csv"
            if path.exists():
                _, rows = read_table(path)
                if rows.size and rows[:, 0].min() > step:
                    raise ValueError(f"its first row is after step {step}")
    except Exception as error:  # whatever a damaged file makes its reader raise
        raise ConfigError(
            "--resume", f"{path} is damaged ({' '.join(str(error).split()) or type(error).__name__})", "start a new run with another --out"
        ) from error


def _check_resume(config: RunConfig, resumed: Simulation, fresh: Simulation) -> None:
    """The checkpoint continues this configuration: same model, same particles, a step to go on from."""
    for key, wanted, stored in differences(config.langevin(), resumed.config):
        raise ConfigError(key, f"the checkpoint was run with {stored!r}, the configuration gives {wanted!r}", "resume with the same value")
    a, b = resumed.particles, fresh.particles
    same = a.radius.size == b.radius.size and np.array_equal(resumed.state.box, fresh.state.box)
    same = same and all(np.array_equal(getattr(a, k), getattr(b, k)) for k in ("radius", "mass", "mobile"))
    walls = ~b.mobile
    if same and walls.any() and not np.array_equal(resumed.state.position[walls], fresh.state.position[walls]):
        raise ConfigError(
            "walls",
            "the checkpoint's wall spheres stand elsewhere than this configuration's (another half_width, roughness or spacing)",
            "resume with the same [walls]",
        )
    if not same:
        raise ConfigError(
            "system",
            "the checkpoint holds other particles or another box than this configuration",
            "resume with the same [system] and [walls]",
        )
    step, r = resumed.state.step, config.run
    if step % r.chunk:
        raise ConfigError(
            "run.chunk", f"the checkpoint is at step {step}, not a multiple of {r.chunk}", "resume with the chunk of the interrupted run"
        )
    if step >= r.steps:
        raise ConfigError("run.steps", f"the checkpoint is already at step {step} >= {r.steps}", "raise run.steps (--steps N) to go on")


def execute(plan: Plan, as_json: bool = False) -> int:
    """Run a plan to the end or to Ctrl-C, writing its outputs (tables, trajectory, checkpoints, summary).

    Parameters
    ----------
    plan : Plan
        A plan of :func:`plan`.
    as_json : bool
        Print the summary as JSON instead of the report.

    Returns
    -------
    int
        The exit status: 0 done, 1 blew up, 130 interrupted (a checkpoint to resume from is written).
    """
    config, simulation, folder = plan.config, plan.simulation, plan.folder
    o, start, clock = config.output, simulation.state.step, time.perf_counter()
    studies = [STUDIES[kind] for kind in config.kinds]  # a kind without its study fails here, before the run
    folder.mkdir(parents=True, exist_ok=True)
    if plan.resumed:
        _continue_from(folder, start)
    (folder / CONFIG).write_text(dumps({"command": plan.command, **config.as_dict()}))
    writers = [observable_table(name, folder, simulation.particles, o.profile_bins) for name in o.observables]
    periods = [o.period] * len(writers)
    if o.trajectory_period:
        writers.append(GSDWriter(folder / TRAJECTORY, simulation.particles, mode="a" if plan.resumed else "w"))
        periods.append(o.trajectory_period)
    observers = [Periodic(writer, period) for writer, period in zip(writers, periods)]
    if o.checkpoint_period:
        observers.append(Periodic(lambda sim: save_checkpoint(folder / CHECKPOINT, sim), o.checkpoint_period))
    interrupted = False
    try:
        with StopOnInterrupt() as stop, closing(ProgressBar(config.run.steps, f"fricgen run {folder}", initial=start)) as bar:
            if not plan.resumed:
                for writer in writers:
                    writer(simulation)  # step 0
            simulation.run(config.run.steps - start, every=config.run.chunk, observers=[*observers, bar, stop])
    except RunInterrupted:
        interrupted = simulation.state.step < config.run.steps
    except SimulationError as error:
        print(f"fricgen run: {error}; the files in {folder} hold the steps before", file=sys.stderr)
        return 1
    finally:
        for writer in writers:
            writer.close()
    save_checkpoint(folder / CHECKPOINT, simulation)
    if interrupted:
        resume = shlex.join([*plan.command, "--resume", str(folder / CHECKPOINT)])
        print(
            f"fricgen run: stopped at step {simulation.state.step} of {config.run.steps}; {folder} holds every output up to it "
            f"and the checkpoint {folder / CHECKPOINT}. Resume with:\n  {resume}",
            file=sys.stderr,
        )
        return 130
    summary = summarize(config, simulation, folder, time.perf_counter() - clock, studies)
    temporary = folder / f".{SUMMARY}.tmp"
    temporary.write_text(dumps(summary))
    os.replace(temporary, folder / SUMMARY)
    print(dumps(summary) if as_json else _describe(summary, folder, studies))
    return 0


def _continue_from(folder: Path, step: int) -> None:
    """Drop what was written after the checkpoint (a resume from a periodic checkpoint); the summary
    of an earlier end is kept as ``summary-<its step>.json`` (never deleted)."""
    if (folder / SUMMARY).exists():
        (folder / SUMMARY).rename(_free_name(folder, f"summary-{step}", ".json"))
    if (folder / TRAJECTORY).exists():
        truncate_trajectory(folder / TRAJECTORY, step)
    for name in OBSERVABLES:
        if (folder / f"{name}.csv").exists():
            truncate_table(folder / f"{name}.csv", step)


def _free_name(folder: Path, stem: str, suffix: str) -> Path:
    """``folder/stem+suffix``, or with ``-2``, ``-3``, ... the first that does not exist."""
    path, count = folder / f"{stem}{suffix}", 1
    while path.exists() or path.is_symlink():
        count += 1
        path = folder / f"{stem}-{count}{suffix}"
    return path


def summarize(config: RunConfig, simulation: Simulation, folder: Path, seconds: float, studies: Sequence[Study] = ()) -> dict:
    """Averages of the observables over the steps after ``run.equilibrate``, with block errors, and
    the entry of each study of the run's kinds."""
    state, particles = simulation.state, simulation.particles
    summary = {
        "steps": state.step,
        "time": state.step * config.thermostat.dt,
        "n": int(particles.mobile.sum()),
        "walls": int((~particles.mobile).sum()),
        "box": state.box[: state.dim].tolist(),
        "seconds": seconds,
    }
    for name in config.output.observables:
        header, rows = read_table(folder / f"{name}.csv")
        rows = rows[rows[:, 0] > config.run.equilibrate]
        if name == "temperatures":
            summary["T_trans"], summary["T_rot"] = (series_summary(rows[:, header.index(k)]) for k in ("T_trans", "T_rot"))
        else:
            bins = config.output.profile_bins
            width = state.box[1] / bins
            profile = {"y": ((np.arange(bins) + 0.5) * width - state.box[1] / 2).tolist()}
            for label, column in (("v_x", "vx"), ("omega_z", "wz")):
                slabs = [series_summary(rows[:, header.index(f"{column}_{j}")]) for j in range(bins)]
                profile[label] = [s["mean"] for s in slabs]
                profile[f"{label}_err"] = [s["error"] for s in slabs]
            summary["velocity_profile"] = profile
    for study in studies:
        entry = study.summarize(config, simulation, folder, summary)
        if entry is not None:
            summary[study.key] = entry
    return summary


def _describe(summary: dict, folder: Path, studies: Sequence[Study] = ()) -> str:
    lines = [f"fricgen run: {summary['steps']} steps (t = {summary['time']:g}) of {summary['n']} particles in {summary['seconds']:.1f} s"]
    for key in ("T_trans", "T_rot"):
        if key in summary and summary[key]["mean"] is not None:
            error = summary[key]["error"]
            lines.append(f"  {key} = {summary[key]['mean']:.4f}" + (f" +- {error:.4f}" if error is not None else ""))
    lines += [f"  {line}" for study in studies if study.key in summary for line in study.describe(summary[study.key])]
    files = sorted(p.name for p in folder.iterdir() if p.name in RUN_FILES)
    lines.append(f"  outputs in {folder}: {', '.join(files)}")
    return "\n".join(lines)
