"""The MIPS phase diagram of issue 28 (Fig. 8 of Hofmann et al. 2025) from finished ``fricgen run``
folders of a grid over the active force F0 and the area fraction, for the paper's three models.

Each folder is analysed as the Fig. 7 runs are (docs/studies/report.py: both criteria fixed in
advance, on the frames of the run's second half pooled, and on every frame alone): the paper's
criterion (exactly two maxima of the smoothed local-area-fraction histogram) and the strict one
(fricgen.app.studies.mips.bimodality: two maxima 0.2 apart, dip ratio at most 0.5). Written:
``fig8.json`` (the rows, with each run's per-frame series) and ``fig8.png`` (one panel per model,
F0 against area fraction: filled = strictly separated, open = bimodal only, cross = neither;
the dip ratio and the frames passing the strict criterion beside each point). Usage (from the
folder that holds the sweep's output)::

    nice -n 10 python docs/studies/fig8_report.py out/fig8_coarse/*/ --results docs/studies/results
    nice -n 10 python docs/studies/fig8_report.py out/fig8_baseline/*/ --name fig8_baseline   # the frictionless scan

Folders without summary.json (still running) are listed as not finished and skipped.
"""

from __future__ import annotations

import json

import numpy as np
from matplotlib.figure import Figure
from report import analyse, arguments, finished_runs, write_record  # docs/studies/report.py, beside this script

DEFAULT = ("out/fig8_coarse/*/",)
MODELS = ("no friction", "no noise", "consistent")


def verdict(run: dict) -> str:
    """'separated' (strict), 'bimodal' (the paper's criterion only) or 'mixed'."""
    pooled = run["pooled"]
    return "separated" if pooled["phase_separated"] else "bimodal" if pooled["bimodal"] else "mixed"


def separated_fraction(run: dict) -> tuple[float, float]:
    """The fraction f of the window's frames strictly separated and its error from the frames' autocorrelation:
    sqrt(f (1 - f) / n (1 + rho) / (1 - rho)), rho the lag-1 autocorrelation of the 0/1 series (0 if undefined;
    clipped to [0, 0.95]); 0 when every frame agrees."""
    flags = np.array([frame["separated"] for frame in run["series"] if frame["t"] >= run["window"][0]], dtype=float)
    f, n = flags.mean(), len(flags)
    rho = 0.0
    if flags[:-1].std() > 0.0 and flags[1:].std() > 0.0:
        rho = min(max(float(np.corrcoef(flags[:-1], flags[1:])[0, 1]), 0.0), 0.95)
    return float(f), float(np.sqrt(f * (1.0 - f) / n * (1.0 + rho) / (1.0 - rho)))


def by_point(runs: list[dict]) -> list[dict]:
    """Per model and state point: each seed's separated fraction (with its autocorrelation error), pooled verdict and
    paper's criterion, and the fractions' mean with the error from the seeds' scatter (std / sqrt(seeds); none for one
    seed)."""
    points = {}
    for run in runs:
        points.setdefault((run["model"], run["F0"], run["packing_fraction"]), []).append(run)
    rows = []
    for (model, f0, phi), group in points.items():
        fractions = [separated_fraction(run) for run in group]
        values = np.array([f for f, _ in fractions])
        scatter = float(values.std(ddof=1) / np.sqrt(len(values))) if len(values) > 1 else None
        rows.append(
            {
                "model": model,
                "F0": f0,
                "packing_fraction": phi,
                "seeds": [run["seed"] for run in group],
                "fractions": fractions,
                "verdicts": [verdict(run) for run in group],
                "bimodal": [run["pooled"]["bimodal"] for run in group],  # the paper's criterion, pooled
                "mean": float(values.mean()),
                "seed_error": scatter,
            }
        )
    return rows


def phase_figure(runs: list[dict], path) -> None:
    """F0 against area fraction, one panel per model, each point marked by its verdict."""
    models = [model for model in MODELS if any(run["model"] == model for run in runs)]  # a panel per model run
    figure = Figure(figsize=(4 * len(models), 4), layout="constrained")
    axes = figure.subplots(1, len(models), sharex=True, sharey=True, squeeze=False)[0]
    style = {"separated": {"marker": "o", "color": "C3"}, "bimodal": {"marker": "o", "facecolors": "none", "edgecolors": "C3"}}
    style["mixed"] = {"marker": "x", "color": "C0"}
    for axis, model in zip(axes, models):
        for run in (r for r in runs if r["model"] == model):
            axis.scatter(run["packing_fraction"], run["F0"], s=90, **style[verdict(run)])
            dip = run["pooled"]["dip_ratio"]
            label = f"{'-' if dip is None else f'{dip:.2f}'} ({run['frames_separated']}/{run['frames_window']})"
            axis.annotate(label, (run["packing_fraction"], run["F0"]), textcoords="offset points", xytext=(0, 9), ha="center", fontsize=7)
        axis.margins(x=0.15, y=0.15)
        axis.set_title(model)
        axis.set_xlabel("area fraction")
    axes[0].set_ylabel("F0 (kT / sigma)")
    figure.suptitle("filled: strictly separated, open: bimodal only, x: neither;\ndip ratio (frames passing / frames), second half pooled")
    figure.savefig(path, dpi=110)


def main(argv: list[str] | None = None) -> None:
    args = arguments(argv, __doc__.splitlines()[0], DEFAULT, name="fig8")
    runs, pending = finished_runs(args.folders, analyse)
    runs.sort(key=lambda run: (MODELS.index(run["model"]), run["F0"], run["packing_fraction"]))
    write_record(args.results / f"{args.name}.json", [{**run, "verdict": verdict(run)} for run in runs], pending)
    points = by_point(runs)
    record = json.loads((args.results / f"{args.name}.json").read_text())
    (args.results / f"{args.name}.json").write_text(json.dumps({**record, "points": points}, indent=1) + "\n")
    for point in points:
        seeds = ", ".join(
            f"seed {seed}: {f:.2f} +- {e:.2f} ({v})" for seed, (f, e), v in zip(point["seeds"], point["fractions"], point["verdicts"])
        )
        error = "" if point["seed_error"] is None else f" +- {point['seed_error']:.2f} (seeds)"
        where = f"{point['model']:12s} F0 {point['F0']:g} phi {point['packing_fraction']:g}"
        print(f"{where}: frames separated {point['mean']:.2f}{error}; {seeds}")
    phase_figure(runs, args.results / f"{args.name}.png")


if __name__ == "__main__":
    main()
