"""Fig. 8's diagram at N >= 5000 from the records of fig8_report.py: every run of the named records
(results/<name>.json) with at least 5000 discs, pooled by model and state point across the records (the seeds of
one point may come from several sweeps), each point's fraction of frames strictly separated (the mean over its
seeds, the error from their scatter, or from the frames' autocorrelation for one seed: fig8_report.by_point), and how
many seeds' pooled histograms pass the strict criterion and the paper's.

Written: results/fig8_n5000.png (one panel per model, F0 against area fraction, each point coloured by its fraction
of frames separated and labelled with it and its seeds); printed: the same as a Markdown table per model.

Usage: python docs/studies/fig8_diagram.py [--results docs/studies/results] [NAME ...]
       (default: the records of NAMES below, those of every N >= 5000 sweep)
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from fig8_report import MODELS, by_point  # docs/studies/fig8_report.py, beside this script
from matplotlib.figure import Figure

NAMES = (
    "fig8_boundary", "fig8_outside", "fig8_low", "fig8_edges", "fig8_edges_seeds", "fig8_edges_rest", "fig8_edges_seeds2",
    "fig8_frictionless", "fig8_frictionless_map", "fig8_frictionless_seeds", "fig8_frictionless_seeds2",
    "fig8_frictionless_seeds3", "fig8_edges_last", "fig8_frictionless_rim", "fig8_edges_07", "fig8_low_force",
)  # fmt: skip
SMALLEST = 5000


def pooled_runs(results: Path, names) -> tuple[list[dict], list[str]]:
    """The runs with N >= SMALLEST of the records that exist, and the names of those that do not (yet)."""
    runs, missing = [], []
    for name in names:
        path = results / f"{name}.json"
        if not path.is_file():
            missing.append(name)
            continue
        runs += [run for run in json.loads(path.read_text())["runs"] if run["n"] >= SMALLEST]
    return runs, missing


def cell(point: dict) -> str:
    """'0.46 ± 0.13 · 1/3 · 3/3': the fraction of frames strictly separated and its error, then how many of the seeds'
    pooled histograms are strictly separated and how many bimodal by the paper's criterion, out of the seeds."""
    error = point["seed_error"] if point["seed_error"] is not None else point["fractions"][0][1]
    seeds, strict = len(point["seeds"]), point["verdicts"].count("separated")
    return f"{point['mean']:.2f} ± {error:.2f} · {strict}/{seeds} · {sum(point['bimodal'])}/{seeds}"


def tables(points: list[dict]) -> str:
    """A Markdown table per model: F0 down, area fraction across, each cell a point's cell(); '–' where not run."""
    text = []
    for model in (m for m in MODELS if any(p["model"] == m for p in points)):
        mine = {(p["F0"], p["packing_fraction"]): p for p in points if p["model"] == model}
        forces, fractions = sorted({f for f, _ in mine}), sorted({phi for _, phi in mine})
        text.append(f"{model}:\n\n| F0 \\ area fraction | " + " | ".join(f"{phi:g}" for phi in fractions) + " |")
        text.append("|---" * (len(fractions) + 1) + "|")
        for f0 in forces:
            text.append(f"| {f0:g} | " + " | ".join(cell(mine[f0, phi]) if (f0, phi) in mine else "–" for phi in fractions) + " |")
        text.append("")
    return "\n".join(text)


def diagram(points: list[dict], path: Path) -> None:
    """One panel per model: the points coloured by their fraction of frames separated (0 blue to 1 red)."""
    models = [m for m in MODELS if any(p["model"] == m for p in points)]
    figure = Figure(figsize=(4 * len(models) + 1, 4), layout="constrained")
    axes = figure.subplots(1, len(models), sharex=True, sharey=True, squeeze=False)[0]
    for axis, model in zip(axes, models):
        mine = [p for p in points if p["model"] == model]
        where = ([p["packing_fraction"] for p in mine], [p["F0"] for p in mine])
        dots = axis.scatter(*where, c=[p["mean"] for p in mine], cmap="coolwarm", vmin=0, vmax=1, s=140)
        for p in mine:
            label = f"{p['mean']:.2f} ({len(p['seeds'])})"
            axis.annotate(label, (p["packing_fraction"], p["F0"]), textcoords="offset points", xytext=(0, 10), ha="center", fontsize=7)
        axis.margins(x=0.15, y=0.15)
        axis.set_title(model)
        axis.set_xlabel("area fraction")
    forces = sorted({p["F0"] for p in points})
    axes[0].set_yscale("log")  # the forces' grid is about geometric (20 ... 200): a linear axis crowds the friction models
    axes[0].set_yticks(forces, [f"{f:g}" for f in forces])
    axes[0].minorticks_off()
    axes[0].set_ylabel("F0 (kT / sigma)")
    figure.colorbar(dots, ax=list(axes), label="fraction of frames strictly separated")
    figure.suptitle(f"N >= {SMALLEST}: fraction of the last 50 t_R's frames strictly separated (seeds)")
    figure.savefig(path, dpi=110)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", default=list(NAMES))
    parser.add_argument("--results", type=Path, default=Path(__file__).parent / "results")
    args = parser.parse_args(argv)
    runs, missing = pooled_runs(args.results, args.names)
    if not runs:
        raise SystemExit(f"no run with N >= {SMALLEST} in {args.results} for {', '.join(args.names)}: run fig8_report.py first")
    points = sorted(by_point(runs), key=lambda p: (MODELS.index(p["model"]), p["F0"], p["packing_fraction"]))
    print(tables(points))
    if missing:
        print(f"not yet recorded: {', '.join(missing)}")
    diagram(points, args.results / "fig8_n5000.png")


if __name__ == "__main__":
    main()
