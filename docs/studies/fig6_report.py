"""The Poiseuille results of issue 28 (Fig. 6 of Hofmann et al. 2025) from finished ``fricgen run`` folders.

For each slit run folder (config.json, summary.json with its ``poiseuille`` fit, trajectory.gsd with a
frame every 10 t0) the row of the table: gamma_f, kappa_f, delta_w, seed, eta and b with their frame
errors (:func:`fricgen.app.studies.poiseuille.frame_errors`), chi^2/dof, T_trans, T_rot, wall seconds,
and the fraction of contacts on the Coulomb branch, gamma_f u > w kappa_f
(:func:`fricgen.app.studies.poiseuille.trajectory_branches`), per frame after ``run.equilibrate``:
mean and standard error over the frames (10 t0 apart, far longer than a contact lasts), for all
contacts and for the wall contacts.

The trends the paper states are then measured on the seed-averaged points (inverse-variance means of
the seeds at the same parameters): a weighted straight line in log10 of the parameter (slope per
decade, its error, slope / error) and the chi^2 of a constant with its p-value, for eta and b against
gamma_f (kappa_f = 5, delta_w = 0) and kappa_f (gamma_f = 6, delta_w = 0); against delta_w
(gamma_f = 6, kappa_f = 5) the differences of neighbouring points in units of their combined error.
Where a point was run with several seeds (and, at delta_w > 0, so with several wall realizations:
the roughness is drawn from the seed), the seeds' scatter tests the frame errors: per point the
seeds' mean and standard error, and the chi^2 of the seeds about their weighted mean; pooled over the
points, sqrt(chi^2 / dof) is the factor by which the frame errors are scaled up (never down) for the
trends (:func:`seed_scatter`). Runs at another dt than DT (the time-step check) are compared with the
seed mean at their parameters and kept out of the trends. The chi^2 of one eta over all gamma_f = 6
runs tests the errors across runs. Each run is also refitted
without the slabs within MARGIN = 1 sigma of the walls, and its frame errors are recomputed with 40,
10 and 5 blocks instead of 20 (:func:`refit`; y_B, n, F unchanged).

Written: ``fig6.json`` and ``fig6.png`` (b, eta and the Coulomb-branch fraction against gamma_f,
kappa_f and delta_w). Usage (from the folder that holds the sweep's output)::

    nice -n 10 python docs/studies/fig6_report.py out/fig6/*/ --results docs/studies/results

``--earlier FILE`` adds the rows of a fig6.json written before (runs whose folders are gone; a run
analysed now replaces its earlier row), e.g. fig6_seeds.toml's folders with fig6.toml's rows::

    python docs/studies/fig6_report.py out/fig6_seeds/*/ --earlier docs/studies/results/fig6.json

Folders without summary.json (still running) are listed as not finished and skipped (the command
line and the run log's attempts as in docs/studies/report.py, the Fig. 7 report). Units: sigma = 1,
kT = 1, m = 1, t0; eta in kT t0 / sigma^3, b in sigma.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from report import arguments, attempts, finished_runs  # docs/studies/report.py, beside this script
from scipy.stats import chi2 as chi2_distribution

from fricgen.app.studies.poiseuille import fit_slit_profile, frame_errors, profile_frames, trajectory_branches

DEFAULT = ("out/fig6/*/",)
#: The inner fit leaves out the slabs within MARGIN sigma of the boundaries y_B (the layered fluid at the walls).
MARGIN = 1.0
#: The block counts of the frame errors compared (the runs' own: 20 blocks).
BLOCKS = (40, 10, 5)
#: The time step of the trends (t0); runs at another dt check it.
DT = 1e-3
#: The series of the figure and the trends: the parameter varied, and the others held fixed.
SERIES = {
    "gamma_f": {"kappa_f": 5.0, "roughness": 0.0, "dt": DT},
    "kappa_f": {"gamma_f": 6.0, "roughness": 0.0, "dt": DT},
    "roughness": {"gamma_f": 6.0, "kappa_f": 5.0, "dt": DT},
}
#: What makes runs repeats of one point (they differ in the seed only).
POINT = ("gamma_f", "kappa_f", "roughness", "dt")
LABELS = {"gamma_f": r"$\gamma_f$ ($\sqrt{m k_BT}/\sigma$)", "kappa_f": r"$\kappa_f$", "roughness": r"$\delta_w$ ($\sigma$)"}


def mean_error(values: list[float]) -> dict:
    """Mean and standard error of independent samples."""
    values = np.asarray(values, dtype=float)
    return {"mean": float(values.mean()), "error": float(values.std(ddof=1) / np.sqrt(values.size)), "samples": int(values.size)}


def refit(folder: Path, config: dict, summary: dict, margin: float = 0.0, blocks: int = 20) -> dict:
    """eta and b with their frame errors over ``blocks`` blocks, and chi^2/dof, of (F-43) fitted to the
    slabs inside |y| <= y_B - margin only (y_B, n and F unchanged). margin = 0, blocks = 20 is the
    run's own fit; margin > 0 leaves out the shape of the profile near the walls, and fewer, longer
    blocks test whether the blocks outlast the slow flow modes."""
    fit, profile = summary["poiseuille"], summary["velocity_profile"]
    bins = config["output"]["profile_bins"]
    y = np.array(profile["y"])
    v, error = (np.array([np.nan if x is None else x for x in profile[key]], dtype=float) for key in ("v_x", "v_x_err"))
    width = summary["box"][1] / bins
    v = np.where(np.abs(y) + width / 2 <= fit["boundary"] - margin + 1e-9, v, np.nan)
    inner = fit_slit_profile(y, v, error, width, fit["density"], fit["force"], fit["boundary"])
    eta_err, slip_err = frame_errors(inner, y, error, profile_frames(folder, config["run"]["equilibrate"], bins), blocks)
    return {"margin": margin, "blocks": blocks, "eta": inner.eta, "eta_err": eta_err, "slip": inner.slip, "slip_err": slip_err,
            "reduced_chi2": inner.reduced_chi2, "dof": inner.dof}  # fmt: skip


def analyse(folder: Path) -> dict:
    """The table row of one finished slit run folder (JSON-simple); ``seconds`` is the wall time of the
    run's last attempt (summary.json), not CPU time."""
    config = json.loads((folder / "config.json").read_text())
    summary = json.loads((folder / "summary.json").read_text())
    fit, law = summary["poiseuille"], config["law"]
    _, counts = trajectory_branches(folder / "trajectory.gsd", law["name"], law["parameters"], config["run"]["equilibrate"])
    return {
        "run": folder.name,
        "gamma_f": law["parameters"]["gamma_f"],
        "kappa_f": law["parameters"]["kappa_f"],
        "roughness": config["walls"]["roughness"],
        "seed": config["run"]["seed"],
        "dt": config["thermostat"]["dt"],
        "n": summary["n"],
        "walls": summary["walls"],
        "box": summary["box"],
        "force": fit["force"],
        "length": summary["time"],
        "sampled": summary["time"] - config["run"]["equilibrate"] * config["thermostat"]["dt"],
        "eta": fit["eta"],
        "eta_err": fit["eta_err_frames"],
        "eta_err_bins": fit["eta_err"],
        "slip": fit["slip"],
        "slip_err": fit["slip_err_frames"],
        "slip_err_bins": fit["slip_err"],
        "reduced_chi2": fit["reduced_chi2"],
        "dof": fit["dof"],
        "inner": refit(folder, config, summary, MARGIN),
        "blocks": {str(b): refit(folder, config, summary, blocks=b) for b in BLOCKS},
        "T_trans": summary["T_trans"],
        "T_rot": summary["T_rot"],
        "seconds": round(summary["seconds"], 1),
        "attempts": attempts(folder),
        "contacts": mean_error([c.contacts for c in counts]),
        "coulomb_fraction": mean_error([c.fraction for c in counts]),
        "wall_contacts": mean_error([c.wall_contacts for c in counts]),
        "wall_coulomb_fraction": mean_error([c.wall_fraction for c in counts]),
    }


def constant(values: np.ndarray, errors: np.ndarray) -> tuple[float, float, float]:
    """The inverse-variance mean of ``values`` with ``errors``, its error, and the chi^2 of that constant."""
    weights = errors**-2
    mean = float(np.sum(weights * values) / weights.sum())
    return mean, float(weights.sum() ** -0.5), float(np.sum(((values - mean) / errors) ** 2))


def combined(points: list[dict], key: str, scale: float = 1.0) -> tuple[float, float]:
    """Inverse-variance mean of ``key`` over points (seeds) with errors ``scale`` x ``key_err``, and its error."""
    values, errors = (np.array([p[k] for p in points]) for k in (key, f"{key}_err"))
    return constant(values, scale * errors)[:2]


def series(runs: list[dict], name: str, scale: dict[str, float] | None = None) -> list[dict]:
    """The seed-averaged points of the series varying ``name`` (SERIES), sorted by it; the frame errors
    of ``key`` scaled by ``scale[key]`` (:func:`seed_scatter`; 1 if not given)."""
    fixed = SERIES[name]
    chosen = [r for r in runs if all(r[k] == v for k, v in fixed.items())]
    points = []
    for x in sorted({r[name] for r in chosen}):
        seeds = [r for r in chosen if r[name] == x]
        point = {name: x, "seeds": [r["seed"] for r in seeds]}
        for key in ("eta", "slip"):
            point[key], point[f"{key}_err"] = combined(seeds, key, (scale or {}).get(key, 1.0))
        points.append(point)
    return points


def trend(points: list[dict], name: str, key: str) -> dict:
    """Weighted straight line of ``key`` against log10(``name``) (slope per decade, error, slope/error)
    and the chi^2 of a constant (weighted mean) over the points, with its p-value."""
    x = np.log10([p[name] for p in points])
    y, e = np.array([p[key] for p in points]), np.array([p[f"{key}_err"] for p in points])
    design = np.stack([np.ones_like(x), x], axis=1) / e[:, None]
    covariance = np.linalg.inv(design.T @ design)
    _, slope = covariance @ design.T @ (y / e)
    slope_err = float(np.sqrt(covariance[1, 1]))
    chi2 = constant(y, e)[2]
    return {
        "slope_per_decade": float(slope),
        "slope_err": slope_err,
        "slope_over_err": float(slope / slope_err),
        "constant_chi2": chi2,
        "constant_dof": len(points) - 1,
        "constant_p": float(chi2_distribution.sf(chi2, len(points) - 1)),
    }


def steps(points: list[dict], name: str, key: str) -> list[dict]:
    """Differences of ``key`` between neighbouring points of a series, in units of their combined error."""
    rows = []
    for a, b in zip(points, points[1:]):
        difference, error = b[key] - a[key], float(np.hypot(a[f"{key}_err"], b[f"{key}_err"]))
        rows.append({"from": a[name], "to": b[name], "difference": difference, "error": error, "z": difference / error})
    return rows


def seed_scatter(runs: list[dict]) -> dict:
    """The points run with several seeds (POINT equal): per point and for eta and b the seeds' mean, its
    standard error from their scatter, the frame error of their weighted mean, and the chi^2 of the seeds
    about that mean with the frame errors; pooled over the points, chi^2, dof, p and the factor
    max(1, sqrt(chi^2 / dof)) by which the frame errors are scaled for the trends."""
    groups: dict[tuple, list[dict]] = {}
    for run in runs:
        groups.setdefault(tuple(run[k] for k in POINT), []).append(run)
    repeated = [seeds for seeds in groups.values() if len(seeds) > 1]
    points = [{k: seeds[0][k] for k in POINT} | {"runs": [r["run"] for r in seeds]} for seeds in repeated]
    pooled = {}
    for key in ("eta", "slip"):
        total, dof = 0.0, 0
        for point, seeds in zip(points, repeated):
            values, errors = np.array([r[key] for r in seeds]), np.array([r[f"{key}_err"] for r in seeds])
            _, error, chi2 = constant(values, errors)
            point[key] = {"mean": float(values.mean()), "seed_error": float(values.std(ddof=1) / np.sqrt(values.size)),
                          "frame_error": error, "chi2": chi2}  # fmt: skip
            total, dof = total + chi2, dof + values.size - 1
        scale = max(1.0, float(np.sqrt(total / dof)))
        pooled[key] = {"chi2": total, "dof": dof, "p": float(chi2_distribution.sf(total, dof)), "scale": scale}
    return {"points": points, "pooled": pooled}


def time_step_check(runs: list[dict], scale: dict[str, float]) -> list[dict]:
    """Each run at another dt than DT against the seeds at DT with its other parameters: the difference of
    eta and b, its error (both sides' frame errors scaled by ``scale``) and the difference over it."""
    rows = []
    for run in (r for r in runs if r["dt"] != DT):
        twins = [r for r in runs if r["dt"] == DT and all(r[k] == run[k] for k in POINT if k != "dt")]
        if not twins:
            continue
        row = {"run": run["run"], "dt": run["dt"], "against": [r["run"] for r in twins]}
        for key in ("eta", "slip"):
            mean, error = combined(twins, key, scale[key])
            difference, total = run[key] - mean, float(np.hypot(error, scale[key] * run[f"{key}_err"]))
            row[key] = {"difference": difference, "error": total, "z": difference / total}
        rows.append(row)
    return rows


def scatter(runs: list[dict], which: str | None = None, scale: float = 1.0) -> dict:
    """chi^2 of one constant eta over the gamma_f = 6 runs at DT (kappa_f, delta_w and seeds varied; the paper's
    eta depends on none of them), with the frame errors: a test of those errors and of the fit.
    ``which``: None for the runs' own fit, "inner" or a block count of ``blocks`` for a refit; the errors
    scaled by ``scale`` (:func:`seed_scatter`)."""
    chosen = [r for r in runs if r["gamma_f"] == 6.0 and r["dt"] == DT]
    chosen = [r if which is None else r["inner"] if which == "inner" else r["blocks"][which] for r in chosen]
    y, e = np.array([r["eta"] for r in chosen]), scale * np.array([r["eta_err"] for r in chosen])
    mean, _, chi2 = constant(y, e)
    dof = len(chosen) - 1
    return {"runs": len(chosen), "mean": float(mean), "chi2": chi2, "dof": dof, "p": float(chi2_distribution.sf(chi2, dof)),
            "spread": float(y.std(ddof=1)), "rms_error": float(np.sqrt(np.mean(e**2)))}  # fmt: skip


def figure(runs: list[dict], path: Path) -> Path:
    """b (top), eta (middle) and the Coulomb-branch fraction (bottom) against gamma_f, kappa_f and
    delta_w (columns), at DT; filled circles seed 1, open squares seed 2, open triangles seed 3 (each
    shifted a little to the right of the one before); grey: the fit without the slabs within MARGIN of
    the walls (:func:`refit`); errors: the runs' frame errors."""
    figure = Figure(figsize=(11, 8.5), layout="constrained")
    axes = figure.subplots(3, 3, sharex="col")
    rows = (("slip", r"slip length $b$ ($\sigma$)"), ("eta", r"$\eta$ ($k_BT t_0/\sigma^3$)"), ("coulomb_fraction", "Coulomb branch"))
    for column, name in enumerate(SERIES):
        fixed = SERIES[name]
        chosen = [r for r in runs if all(r[k] == v for k, v in fixed.items())]
        for row, (key, label) in enumerate(rows):
            axis = axes[row, column]
            for seed, marker in ((1, "o"), (2, "s"), (3, "^")):
                points = sorted((r for r in chosen if r["seed"] == seed), key=lambda r: r[name])
                if not points:
                    continue
                x = np.array([r[name] for r in points])
                # beside the seed before: 6 % to the right on a log axis, 0.004 on the linear one
                x = x + 0.004 * (seed - 1) if name == "roughness" else x * 1.06 ** (seed - 1)
                face = "C0" if seed == 1 else "none"
                if key == "coulomb_fraction":
                    for k, colour, text in (("coulomb_fraction", "C0", "all contacts"), ("wall_coulomb_fraction", "C3", "wall contacts")):
                        y, e = (np.array([r[k][q] for r in points]) for q in ("mean", "error"))
                        axis.errorbar(x, y, e, fmt=marker, color=colour, mfc=colour if seed == 1 else "none", capsize=2,
                                      label=f"{text}, seed {seed}")  # fmt: skip
                else:
                    y, e = np.array([r[key] for r in points]), np.array([r[f"{key}_err"] for r in points])
                    axis.errorbar(x, y, e, fmt=marker, color="C0", mfc=face, capsize=2, label=f"seed {seed}")
                    y, e = np.array([r["inner"][key] for r in points]), np.array([r["inner"][f"{key}_err"] for r in points])
                    inner = f"without the slabs within {MARGIN:g} of the walls" if seed == 1 else None
                    beside = x * 1.03 if name != "roughness" else x + 0.002
                    axis.errorbar(beside, y, e, fmt=marker, color="0.6", mfc="0.6" if seed == 1 else "none", capsize=2, ms=4, label=inner)
            if name != "roughness":
                axis.set_xscale("log")
            if column == 0:
                axis.set_ylabel(label)
            if row == 2:
                axis.set_xlabel(LABELS[name])
        fixed_text = ", ".join(f"{LABELS[k].split(' (')[0]} = {v:g}" for k, v in fixed.items() if k in LABELS)
        axes[0, column].set_title(fixed_text, fontsize=9)
    axes[0, 0].legend(frameon=False, fontsize=8)
    axes[2, 0].legend(frameon=False, fontsize=7)
    figure.suptitle(f"Fig. 6 of Hofmann et al. 2025: N = 1318, L_x = 20, F = 0.02, dt = {DT:g}, 650 t0 of data per point (frame errors)")
    figure.savefig(path, dpi=80)
    return path


def table_row(run: dict) -> str:
    """The run's row of the table of docs/studies/fig6.md (markdown)."""
    temperature = "{mean:.3f} ± {error:.3f}"
    cells = [
        run["run"].removeprefix("point="),
        f"{run['gamma_f']:g}",
        f"{run['kappa_f']:g}",
        f"{run['roughness']:g}",
        run["seed"],
        f"{run['eta']:.4f} ± {run['eta_err']:.4f}",
        f"{run['slip']:.3f} ± {run['slip_err']:.3f}",
        f"{run['reduced_chi2']:.2f}",
        f"{run['inner']['eta']:.4f} ± {run['inner']['eta_err']:.4f}",
        f"{run['inner']['slip']:.3f} ± {run['inner']['slip_err']:.3f}",
        f"{run['inner']['reduced_chi2']:.2f}",
        temperature.format(**run["T_trans"]),
        temperature.format(**run["T_rot"]),
        "{mean:.3f} ± {error:.3f}".format(**run["coulomb_fraction"]),
        "{mean:.3f} ± {error:.3f}".format(**run["wall_coulomb_fraction"]),
        f"{run['contacts']['mean']:.0f}",
        f"{run['seconds']:.0f} s" + ("" if run["attempts"] == 1 else f" (last of {run['attempts']})"),
    ]
    return "| " + " | ".join(str(cell) for cell in cells) + " |"


def main(argv: list[str] | None = None) -> None:
    """Analyse the folders given (default: out/fig6/*/), write fig6.json and fig6.png, print the table."""
    earlier = argparse.ArgumentParser(add_help=False)
    earlier.add_argument("--earlier", type=Path, help="a fig6.json written before: its runs are added (a run analysed now replaces its)")
    args = arguments(argv, __doc__.splitlines()[0], DEFAULT, parents=(earlier,))
    runs, pending = finished_runs(args.folders, analyse)
    if args.earlier is not None:
        names = {r["run"] for r in runs}
        runs = [r for r in json.loads(args.earlier.read_text())["runs"] if r["run"] not in names] + runs
    seeds = seed_scatter(runs)
    scale = {key: seeds["pooled"][key]["scale"] for key in ("eta", "slip")}
    trends = {}
    for name in ("gamma_f", "kappa_f"):
        points = series(runs, name, scale)
        if len(points) >= 2:
            trends[name] = {"points": points, "eta": trend(points, name, "eta"), "slip": trend(points, name, "slip")}
    points = series(runs, "roughness", scale)
    trends["roughness"] = {"points": points, "eta": steps(points, "roughness", "eta"), "slip": steps(points, "roughness", "slip")}
    args.results.mkdir(parents=True, exist_ok=True)
    spread = {"all slabs": scatter(runs), "inner slabs": scatter(runs, "inner")}
    spread |= {f"{b} blocks": scatter(runs, str(b)) for b in BLOCKS}
    spread["all slabs, errors scaled"] = scatter(runs, scale=scale["eta"])
    record = {"runs": runs, "error_scale": scale, "trends": trends, "seeds": seeds, "time_step": time_step_check(runs, scale),
              "eta_scatter": spread, "not_finished": pending}  # fmt: skip
    (args.results / "fig6.json").write_text(json.dumps(record, indent=1) + "\n")
    figure(runs, args.results / "fig6.png")
    for run in runs:
        print(table_row(run))
    print(json.dumps({key: record[key] for key in ("error_scale", "trends", "seeds", "time_step", "eta_scatter")}, indent=1))
    print("not finished:", pending)


if __name__ == "__main__":
    main()
