"""The MIPS results of issue 28 (Fig. 7 of Hofmann et al. 2025) from finished ``fricgen run`` folders:
both criteria fixed in advance, per run pooled over its second half and per GSD frame.

For each run folder (config.json, summary.json, trajectory.gsd with a frame every t_R) the local area
fraction phi(r) of every frame is computed on the detector's grid
(:func:`fricgen.app.studies.mips.local_area_fraction`, Gaussian kernel s = 1.5 sigma), and the smoothed
histogram p(phi) of the frames at steps >= ``run.equilibrate`` (the second half) is judged by

- the paper's criterion (sec. II B 3: "A bimodal distribution in the resulting density histogram
  indicates phase separation"): the number of local maxima of p (:func:`~fricgen.app.studies.mips.local_maxima`),
  bimodal when it is 2;
- the strict criterion of :func:`fricgen.app.studies.mips.bimodality`: two maxima at least 0.2 apart
  whose dip ratio p_min / min(p_max1, p_max2) is at most 0.5, at least 5 % of the grid on each side.

The same two numbers and the dip ratio are computed for every frame alone (the dip ratio against
time). Written: ``fig7.json`` (a table per run, the per-frame series) and ``fig7_dip_vs_time.png``.

Usage (from the folder that holds the sweep's output, e.g. ``fricgen sweep fig7.toml --out out/fig7``)::

    nice -n 10 python docs/studies/report.py out/fig7/*/ cross/out/*/ --results docs/studies/results

Folders without summary.json (still running) are listed as such and skipped. Time is in t_R (the
engine's unit of the active runs, gamma = 1), area fractions are dimensionless.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from fricgen.app.studies import mips

DEFAULT = ("out/fig7/*/",)


def model_name(config: dict) -> str:
    """'no friction', 'no noise' (Coulomb-Newton without its contact noise) or 'consistent'."""
    law = config["law"]
    if not law["friction"]:
        return "no friction"
    return "consistent" if law["contact_noise"] else "no noise"


def judge(values: np.ndarray) -> dict:
    """Both criteria for the pooled grid values of one or more frames.

    Args:
        values: local area fractions phi (dimensionless), any shape.

    Returns:
        ``maxima`` (their phi), ``bimodal`` (exactly two maxima: the paper's criterion),
        ``phase_separated`` (the strict criterion), ``dip_ratio`` (None without a second maximum
        0.2 away), ``dense_share``, ``phi_dilute``, ``phi_dense`` (None unless strictly separated).
    """
    centres, probability, verdict = mips.bimodality(np.ravel(values))
    peaks = mips.local_maxima(probability)
    return {
        "maxima": [round(float(centres[i]), 3) for i in peaks],
        "maxima_heights": [round(float(probability[i]), 3) for i in peaks],
        "bimodal": len(peaks) == 2,
        **{key: value if value is None or isinstance(value, bool) else round(value, 4) for key, value in verdict.items()},
    }


def frame_fields(trajectory: Path) -> tuple[list[int], list[np.ndarray]]:
    """The steps and local-area-fraction grids of every frame of a 2-D GSD trajectory."""
    frames, steps = mips.read_frames(trajectory, last=10**9)
    return steps, [mips.local_area_fraction(frame) for frame in frames]


def attempts(folder: Path) -> int:
    """How many times the run was started (the '# ' lines a sweep writes into run.log; 1 without it)."""
    log = folder / "run.log"
    if not log.exists():
        return 1
    return max(1, sum(line.startswith("# ") for line in log.read_text(errors="replace").splitlines()))


def analyse(folder: Path) -> dict:
    """The table row and the per-frame series of one finished run folder.

    Args:
        folder: a ``fricgen run active`` output folder with summary.json and trajectory.gsd.

    Returns:
        A JSON-simple dict; ``seconds`` is the wall time of the run's last attempt (summary.json),
        not CPU time.
    """
    config = json.loads((folder / "config.json").read_text())
    summary = json.loads((folder / "summary.json").read_text())
    dt, equilibrate = config["thermostat"]["dt"], config["run"]["equilibrate"]
    steps, fields = frame_fields(folder / "trajectory.gsd")
    second = [field for step, field in zip(steps, fields) if step >= equilibrate]
    series = []
    for step, field in zip(steps, fields):
        verdict = judge(field)
        series.append(
            {
                "t": round(step * dt, 4),
                "maxima": len(verdict["maxima"]),
                "dip_ratio": None if verdict["dip_ratio"] is None else round(verdict["dip_ratio"], 4),
                "separated": verdict["phase_separated"],
            }
        )
    late = [row for row in series if row["t"] >= equilibrate * dt]
    initial = config["system"].get("initial")
    return {
        "run": folder.name,
        "model": model_name(config),
        "seed": config["run"]["seed"],
        "n": config["system"]["n"],
        "mass": config["system"]["mass"],
        "F0": config["active"]["force"],
        "packing_fraction": config["system"]["packing_fraction"],
        "dt": dt,
        "length": summary["time"],
        "window": [equilibrate * dt, summary["time"]],
        "initial": None if initial is None else Path(initial).parent.name,
        "pooled": {"frames": len(second), **judge(np.concatenate([f.ravel() for f in second]))},
        "frames_bimodal": sum(row["maxima"] == 2 for row in late),
        "frames_by_maxima": {str(k): sum(row["maxima"] == k for row in late) for k in sorted({row["maxima"] for row in late})},
        "frames_separated": sum(bool(row["separated"]) for row in late),
        "frames_window": len(late),
        "summary_verdict": {key: summary["mips"].get(key) for key in ("phase_separated", "dip_ratio", "frames")},
        "T_trans": summary["T_trans"],
        "T_rot": summary["T_rot"],
        "seconds": round(summary["seconds"], 1),
        "attempts": attempts(folder),
        "series": series,
    }


def dip_figure(runs: list[dict], path: Path) -> Path:
    """The dip ratio of each frame against time: a panel for runs from a lattice and, where there are any,
    one for cross-starts.

    Colour: the model; line style: the seed (1 solid, 2 dashed, 3 dotted). A frame with no second
    maximum 0.2 away (no dip) is drawn at 1 with an open marker; the black dashed line is the strict
    threshold 0.5.
    """
    groups = [r for r in runs if not r["initial"]], [r for r in runs if r["initial"]]
    sizes = ", ".join(f"{n:g}" for n in sorted({r["n"] for r in groups[0]}))
    fractions = ", ".join(f"{phi:g}" for phi in sorted({r["packing_fraction"] for r in groups[0]}))
    titles = (f"from a lattice (N = {sizes}, area fraction {fractions})", "cross-starts (time since the restart)")
    count = 2 if groups[1] else 1
    figure = Figure(figsize=(5.5 * count, 4.6), layout="constrained")
    panels = np.atleast_1d(figure.subplots(1, count, sharey=True))
    colours = {"no noise": "C1", "consistent": "C0", "no friction": "C2"}
    for axis, title, group in zip(panels, titles, groups):
        for run in group:
            colour, style = colours[run["model"]], ("-", "--", ":")[(run["seed"] - 1) % 3]
            t = np.array([row["t"] for row in run["series"]])
            dip = np.array([np.nan if row["dip_ratio"] is None else row["dip_ratio"] for row in run["series"]])
            label = f"{run['model']}, seed {run['seed']}" if not run["initial"] else f"{run['run']}: {run['model']}"
            label += f", F0 = {run['F0']:g}, m = {run['mass']:g}"
            axis.plot(t, dip, style, color=colour, lw=1, label=label)
            none = np.isnan(dip)
            axis.plot(t[none], np.ones(none.sum()), "o", mfc="none", color=colour, ms=3)
        axis.axhline(mips.DIP, color="k", ls="--", lw=0.8)
        axis.set_title(title, fontsize=9)
        axis.set_xlabel(r"$t$ / $t_R$")
        axis.set_ylim(0, 1.05)
        if group:
            axis.legend(frameon=False, fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    panels[0].set_ylabel("dip ratio of the frame (1: no dip)")
    figure.savefig(path, dpi=80)
    return path


def table_row(run: dict) -> str:
    """The run's row of the tables of docs/studies/results.md (markdown)."""
    pooled, temperature = run["pooled"], "{mean:.3f} ± {error:.3f}"
    phases = "–" if pooled["phi_dense"] is None else f"{pooled['phi_dilute']} / {pooled['phi_dense']}"
    cells = [
        run["run"],
        run["model"],
        run["seed"],
        run["n"],
        f"{run['length']:g} t_R",
        f"{len(pooled['maxima'])} ({', '.join(map(str, pooled['maxima']))}): {'bimodal' if pooled['bimodal'] else 'not bimodal'}",
        "separated" if pooled["phase_separated"] else "not separated",
        "–" if pooled["dip_ratio"] is None else f"{pooled['dip_ratio']:.2f}",
        phases,
        f"{run['frames_separated']} of {run['frames_window']}",
        temperature.format(**run["T_trans"]),
        temperature.format(**run["T_rot"]),
        f"{run['seconds']:.0f} s",
    ]
    return "| " + " | ".join(str(cell) for cell in cells) + " |"


def arguments(
    argv: list[str] | None, description: str, default: tuple[str, ...], name: str | None = None, parents: tuple = ()
) -> argparse.Namespace:
    """The command line of a report script: ``folders`` (the glob patterns ``default`` when none are
    given), ``--results`` (default: results/ beside this file), where ``name`` is given ``--name``
    (the stem of the files written, default ``name``), and the options of the ``parents`` parsers."""
    parser = argparse.ArgumentParser(description=description, parents=list(parents))
    parser.add_argument("folders", nargs="*", help=f"run folders (default: {' '.join(default)})")
    parser.add_argument("--results", type=Path, default=Path(__file__).parent / "results")
    if name is not None:
        parser.add_argument("--name", default=name, help=f"the stem of the files written (default: {name})")
    args = parser.parse_args(argv)
    args.folders = [Path(f) for f in args.folders] or sorted(p for pattern in default for p in Path().glob(pattern))
    return args


def finished_runs(folders: list[Path], analyse) -> tuple[list[dict], list[str]]:
    """``analyse(folder)`` of the folders with a summary.json, and the names of those without (still running)."""
    runs, pending = [], []
    for folder in folders:
        if (folder / "summary.json").exists():
            runs.append(analyse(folder))
        else:
            pending.append(folder.name)
    return runs, pending


def write_record(path: Path, runs: list[dict], pending: list[str]) -> None:
    """``path`` as JSON: both criteria and the detector's settings, the runs, the folders not finished;
    the runs' table rows and the pending folders printed."""
    path.parent.mkdir(parents=True, exist_ok=True)
    record = {"criterion_paper": "exactly two local maxima of the smoothed pooled histogram", "criterion_strict": mips.CRITERION}
    record.update(kernel=mips.KERNEL, spacing=mips.SPACING, bin=mips.BIN, smoothing=mips.SMOOTHING, runs=runs, not_finished=pending)
    path.write_text(json.dumps(record, indent=1) + "\n")
    for run in runs:
        print(table_row(run))
    print("not finished:", pending)


def main(argv: list[str] | None = None) -> None:
    """Analyse the folders given (default: out/fig7/*/), write NAME.json and NAME_dip_vs_time.png (NAME: --name, fig7)."""
    args = arguments(argv, __doc__.splitlines()[0], DEFAULT, name="fig7")
    runs, pending = finished_runs(args.folders, analyse)
    write_record(args.results / f"{args.name}.json", runs, pending)
    dip_figure(runs, args.results / f"{args.name}_dip_vs_time.png")


if __name__ == "__main__":
    main()
