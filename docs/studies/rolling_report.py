"""The Poiseuille results of issue 29 item 6 (rolling resistance in the slit) from finished ``fricgen run`` folders.

Each run folder of ``fricgen sweep docs/studies/rolling.toml`` gets the row of the slit study
(:func:`fig6_report.analyse`: eta and b with their frame errors, the inner fit, T_trans, T_rot, the
sliding Coulomb-branch fraction) plus its rolling law and parameters (gamma_r, kappa_r; none for the
points without rolling) and which noise it ran with (NOISES: every mode's, the sliding law's alone, none).
Each point is then compared with its reference without rolling and with the sliding noise as its own:
with it, fig6's g6k5 (read from ``results/fig6.json``, the same settings at 800 t0; or a run folder
named ``point=g6k5`` when given), without it the point g6k5_nonoise: the difference of eta, b and
T_rot and its error, the frame errors of the two added in quadrature (independent runs). A point
without the rolling noise alone is also compared with the point of the same kappa_r and length with
every noise: what the rolling noise does.

Written: ``rolling.json`` and ``rolling.png`` (b, eta and T_rot against kappa_r for each noise, the
references as lines with their error bands). Usage (from the folder that holds the
sweep's output)::

    nice -n 10 python docs/studies/rolling_report.py out/rolling/*/ --results docs/studies/results

Folders without summary.json (still running) are listed as not finished and skipped. Units:
sigma = 1, kT = 1, m = 1, t0; eta in kT t0 / sigma^3, b in sigma, T_rot in kT.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from fig6_report import analyse as slit_row  # docs/studies/fig6_report.py, beside this script
from fig6_report import table_row as slit_table_row
from matplotlib.figure import Figure
from report import arguments, finished_runs  # docs/studies/report.py, beside this script

DEFAULT = ("out/rolling/*/",)
#: The reference with the noise and without rolling: fig6.toml's point at (gamma_f, kappa_f) = (6, 5).
REFERENCE = "point=g6k5"
#: The reference without the noise (law.contact_noise = false drops every mode's noise) and without rolling.
REFERENCE_NO_NOISE = "point=g6k5_nonoise"
#: The noises a point runs with: every mode's; the sliding law's alone (law.rolling_noise = false); none.
NOISES = ("all", "sliding", "none")
#: The quantities compared with the reference: (key, its error's key).
COMPARED = {"eta": ("eta", "eta_err"), "slip": ("slip", "slip_err"), "T_rot": ("T_rot", None)}


def analyse(folder: Path) -> dict:
    """The slit row of one finished run folder, its rolling law and its noise (JSON-simple; runs from before
    law.rolling_noise existed had the rolling noise wherever they had the contact noise)."""
    config = json.loads((folder / "config.json").read_text())
    law = config["law"]
    rolling = law.get("rolling")
    parameters = law.get("rolling_parameters", {}) if rolling else {}
    noise = "none" if not law["contact_noise"] else "all" if law.get("rolling_noise", True) or not rolling else "sliding"
    return slit_row(folder) | {
        "rolling": rolling,
        "gamma_r": parameters.get("gamma_r"),
        "kappa_r": parameters.get("kappa_r"),
        "contact_noise": law["contact_noise"],
        "noise": noise,
    }


def value_error(run: dict, key: str) -> tuple[float, float]:
    """The value of ``key`` (COMPARED) in a run's row and its error."""
    name, error = COMPARED[key]
    if error is None:
        return run[name]["mean"], run[name]["error"]
    return run[name], run[error]


def difference(run: dict, reference: dict) -> dict:
    """run - reference for each compared quantity: value, error (quadrature), and value / error."""
    out = {}
    for key in COMPARED:
        (a, da), (b, db) = value_error(run, key), value_error(reference, key)
        error = float(np.hypot(da, db))
        out[key] = {"difference": a - b, "error": error, "sigmas": (a - b) / error, "relative": (a - b) / b}
    return out


def references(runs: list[dict], fig6: Path) -> dict:
    """The references by noise (True, False): run folders named REFERENCE(_NO_NOISE) among ``runs``,
    else fig6's g6k5 from ``fig6`` (results/fig6.json) for the noise; missing ones are left out."""
    named = {run["run"]: run for run in runs}
    found = {True: named.get(REFERENCE), False: named.get(REFERENCE_NO_NOISE)}
    if found[True] is None and fig6.exists():
        found[True] = next((run for run in json.loads(fig6.read_text())["runs"] if run["run"] == REFERENCE), None)
    return {noise: run for noise, run in found.items() if run is not None}


def figure(runs: list[dict], refs: dict, path: Path) -> Path:
    """b, eta and T_rot against kappa_r: filled with the noise, open without; the references as bands."""
    fig = Figure(figsize=(5, 8), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    styles = {
        "all": ("C0", "o", "full", "with noise"),
        "sliding": ("C2", "^", "none", "without the rolling noise"),
        "none": ("C3", "s", "none", "without noise"),
    }
    for ax, key, label in zip(axes, COMPARED, (r"$\eta$ ($k_BT t_0/\sigma^3$)", r"$b$ ($\sigma$)", r"$T_\mathrm{rot}$ ($k_BT$)")):
        for noise, (colour, marker, fill, name) in styles.items():
            chosen = sorted((r for r in runs if r["rolling"] and r["noise"] == noise), key=lambda r: r["kappa_r"])
            if chosen:
                x = [r["kappa_r"] for r in chosen]
                y, dy = zip(*(value_error(r, key) for r in chosen))
                ax.errorbar(x, y, dy, color=colour, marker=marker, fillstyle=fill, capsize=3, label=name)
            if noise != "sliding" and (noise == "all") in refs:
                y, dy = value_error(refs[noise == "all"], key)
                ax.axhspan(y - dy, y + dy, color=colour, alpha=0.15, lw=0)
                ax.axhline(y, color=colour, ls="--", lw=0.8, label=f"no rolling, {name}")
        ax.set_ylabel(label)
        ax.set_xscale("log")
    kappas = [r["kappa_r"] for r in runs if r["rolling"]]
    if kappas:
        axes[-1].set_xlim(min(kappas) / 2, max(kappas) * 2)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel(r"$\kappa_r$ ($\gamma_r = 6$)")
    fig.savefig(path, dpi=120)
    return path


def table_row(run: dict) -> str:
    """The run's row of the table of docs/studies/rolling.md (markdown): the rolling columns, then
    fig6's row without its gamma_f, kappa_f, delta_w and seed columns."""
    rolling = [f"{run['kappa_r']:g}" if run["rolling"] else "–", {"all": "yes", "sliding": "sliding only", "none": "no"}[run["noise"]]]
    cells = slit_table_row(run).strip("| ").split(" | ")
    return "| " + " | ".join([cells[0], *rolling, *cells[5:]]) + " |"


def main(argv: list[str] | None = None) -> None:
    """Analyse the folders given (default: out/rolling/*/), write rolling.json and rolling.png, print the table."""
    args = arguments(argv, __doc__.splitlines()[0], DEFAULT)
    runs, pending = finished_runs(args.folders, analyse)
    refs = references(runs, args.results / "fig6.json")
    compared = [
        {"run": run["run"], "reference": refs[run["contact_noise"]]["run"]} | difference(run, refs[run["contact_noise"]])
        for run in runs
        if run["rolling"] and run["contact_noise"] in refs
    ]
    consistent = {(run["kappa_r"], run["length"]): run for run in runs if run["rolling"] and run["noise"] == "all"}
    for run in runs:  # what the rolling noise alone does: the same kappa_r and length with every noise
        same = consistent.get((run["kappa_r"], run["length"]))
        if run["noise"] == "sliding" and same is not None:
            compared.append({"run": run["run"], "reference": same["run"]} | difference(run, same))
    if True in refs and False in refs:  # the noise without rolling: what dropping the sliding noise alone does
        compared.append({"run": refs[False]["run"], "reference": refs[True]["run"]} | difference(refs[False], refs[True]))
    args.results.mkdir(parents=True, exist_ok=True)
    record = {"runs": runs, "references": {str(k): v["run"] for k, v in refs.items()}, "differences": compared, "not_finished": pending}
    (args.results / "rolling.json").write_text(json.dumps(record, indent=1) + "\n")
    figure(runs, refs, args.results / "rolling.png")
    for run in runs:
        print(table_row(run))
    for row in compared:
        changes = {k: f"{v['difference']:+.4f} ± {v['error']:.4f} ({v['sigmas']:+.1f})" for k, v in row.items() if isinstance(v, dict)}
        print(row["run"], "-", row["reference"], changes)
    print("not finished:", pending)


if __name__ == "__main__":
    main()
