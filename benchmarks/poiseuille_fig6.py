"""Fig. 6 of the paper at reduced cost: slip length b and viscosity eta of Poiseuille flow in the slit
against gamma_f (kappa_f = 5) and kappa_f (gamma_f = 6), the linear-response check (F and 2F), and
eta of the same fluid from the transverse currents of a periodic bulk (fricgen.app.studies.viscosity).

Reduced set-up (docs/poiseuille.md): the paper's slit (walls at y = +-8.5847, phi = 0.15 of the
accessible volume, no solvent, Coulomb–Newton, Ito, dt = 1e-3) with L_x = L_z = 10 (N = 435 instead
of 10 000), run for 600 t0 with the first 200 left out (instead of 500 + 6000 t0), at F = 0.02 (and
0.04) instead of 0.01. The bulk: 1500 spheres at phi = 0.15 in a periodic cube, 20 + 300 t0. Each
point runs ``fricgen run poiseuille --set ...`` single-threaded, ``--jobs`` at a time (the bulk run
is one of the jobs); a finished point is not rerun and an interrupted one resumes from its
checkpoint. Prints the table and the wall times and draws docs/poiseuille-fig6.png.
Run: python benchmarks/poiseuille_fig6.py [--out poiseuille-fig6] [--jobs 2] [--figure docs/poiseuille-fig6.png]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from fricgen.app.run.config import RunConfig, RunLaw
from fricgen.app.run.observables import read_table
from fricgen.app.studies.poiseuille import fit_slit_run, frame_errors
from fricgen.app.studies.viscosity import bulk_config, measure_bulk_viscosity, transverse_viscosity
from fricgen.langevin.analysis import block_estimate
from fricgen.schema import structure

LX, LZ, N, FORCE, STEPS, EQUILIBRATE, BLOCKS, FRAME_BLOCKS = 10.0, 10.0, 435, 0.02, 600_000, 200_000, 20, 10
#: (folder, gamma_f, kappa_f, F): the gamma_f series at kappa_f = 5, the kappa_f series at gamma_f = 6, and 2F.
POINTS = [
    ("g1k5F02", 1.0, 5.0, FORCE),
    ("g6k5F02", 6.0, 5.0, FORCE),
    ("g6k5F04", 6.0, 5.0, 2 * FORCE),
    ("g20k5F02", 20.0, 5.0, FORCE),
    ("g6k1F02", 6.0, 1.0, FORCE),
    ("g6k20F02", 6.0, 20.0, FORCE),
]
BULK_N, BULK_EQUILIBRATE, BULK_TIME = 1500, 20.0, 300.0


def settings(gamma_f: float, kappa_f: float, force: float) -> list[str]:
    values = {
        "system.box": f"[{LX}, 18.1694, {LZ}]",
        "system.n": N,
        "law.parameters.gamma_f": gamma_f,
        "law.parameters.kappa_f": kappa_f,
        "bulk.force": f"[{force}, 0.0, 0.0]",
        "run.steps": STEPS,
        "run.equilibrate": EQUILIBRATE,
        "run.chunk": 200,
        "output.period": 200,
        "output.trajectory_period": 0,
        "output.checkpoint_period": 20000,
    }
    return [word for key, value in values.items() for word in ("--set", f"{key}={value}")]


def run_point(out: Path, name: str, gamma_f: float, kappa_f: float, force: float) -> None:
    folder = out / name
    summary = folder / "summary.json"
    if summary.exists() and json.loads(summary.read_text())["steps"] >= STEPS:
        return
    resume = ["--resume", str(folder / "checkpoint.npz")] if (folder / "checkpoint.npz").exists() else ["--out", str(folder)]
    command = [sys.executable, "-m", "fricgen", "run", "poiseuille", *settings(gamma_f, kappa_f, force), *resume]
    with open(out / f"{name}.log", "a") as log:
        subprocess.run(command, env=os.environ | {"NUMBA_NUM_THREADS": "1"}, stdout=log, stderr=log, check=True)


def run_bulk(path: Path, gamma_f: float = 6.0, kappa_f: float = 5.0) -> None:
    """The transverse currents of the bulk fluid, saved to ``path`` (npz) unless it is there."""
    if path.exists():
        return
    clock = time.perf_counter()
    config = bulk_config(RunLaw(parameters={"gamma_f": gamma_f, "kappa_f": kappa_f}), BULK_N, 0.15)
    result, currents, k = measure_bulk_viscosity(config, BULK_EQUILIBRATE, BULK_TIME, interval=0.05)
    np.savez(path, currents=currents, k=k, interval=0.05, mass_density=result.mass_density, seconds=time.perf_counter() - clock)


def slit_result(folder: Path) -> dict:
    """Refit a slit run from its table: the profile after ``run.equilibrate`` with per-slab errors from
    BLOCKS blocks (the weights of the fit, as summary.json), the fit (F-43), and the errors of eta and b
    from FRAME_BLOCKS blocks of 40 t0 of the per-frame fits (the slow flow modes move all slabs
    together; docs/poiseuille.md)."""
    stored = json.loads((folder / "config.json").read_text())
    stored.pop("command")
    config = structure(RunConfig, stored)
    summary = json.loads((folder / "summary.json").read_text())
    header, rows = read_table(folder / "velocity_profile.csv")
    rows = rows[rows[:, 0] > config.run.equilibrate]
    bins, ly = config.output.profile_bins, config.system.box[1]
    profile = {"y": list((np.arange(bins) + 0.5) * ly / bins - ly / 2)}
    for label, column in (("v_x", "vx"), ("omega_z", "wz")):
        estimates = [_estimate(rows[:, header.index(f"{column}_{j}")]) for j in range(bins)]
        profile[label], profile[f"{label}_err"] = ([e[i] for e in estimates] for i in (0, 1))
    fit = fit_slit_run(config, summary["n"], profile, ly / bins)
    result = {"config": config, "profile": profile, "fit": fit, "seconds": summary["seconds"], "T_trans": summary["T_trans"]["mean"]}
    frames = rows[:, [header.index(f"vx_{j}") for j in range(bins)]]
    errors = frame_errors(fit, profile["y"], profile["v_x_err"], frames, FRAME_BLOCKS)
    return result | {"frames": dict(zip(("eta_err", "slip_err"), errors))}


def _estimate(series: np.ndarray) -> tuple[float | None, float | None]:
    series = series[np.isfinite(series)]
    if series.size < 2 * BLOCKS:
        return None, None
    estimate = block_estimate(series, BLOCKS)
    return estimate.mean, estimate.error


def linear_response(low: dict, high: dict) -> tuple[float, int]:
    """chi^2 and bins of v(2F)/2 - v(F) = 0 over the bins of both fits (linear response: chi^2 ~ bins)."""
    used = np.intersect1d(low["fit"].used, high["fit"].used)
    a, b = (np.array(r["profile"]["v_x"], dtype=float)[used] for r in (low, high))
    ea, eb = (np.array(r["profile"]["v_x_err"], dtype=float)[used] for r in (low, high))
    return float(np.sum((b / 2 - a) ** 2 / (ea**2 + eb**2 / 4))), int(used.size)


def figure(results: dict, bulk, path: Path) -> None:
    """Profiles of the gamma_f series (left), b and eta against gamma_f (middle) and kappa_f (right)."""
    fig = Figure(figsize=(13, 7), layout="constrained")
    axes = fig.subplots(2, 3)
    for name, colour in zip(("g1k5F02", "g6k5F02", "g20k5F02"), ("tab:blue", "tab:orange", "tab:green")):
        r, y = results[name], np.array(results[name]["profile"]["y"])
        fit = r["fit"]
        label = f"$\\gamma_f = {r['config'].law.parameters['gamma_f']:g}$"
        for axis, key in zip(axes[:, 0], ("v_x", "omega_z")):
            mean, error = (np.array(r["profile"][k], dtype=float) for k in (key, f"{key}_err"))
            axis.errorbar(y[fit.used], mean[fit.used], error[fit.used], fmt="o", ms=3, color=colour, capsize=2, label=label)
        inner = np.linspace(-fit.boundary, fit.boundary, 200)
        axes[0, 0].plot(inner, fit.profile(inner), color=colour)
        axes[1, 0].plot(inner, fit.density * fit.force * inner / (2 * fit.eta), "--", color=colour)
    axes[0, 0].set(xlabel=r"$y$ ($\sigma$)", ylabel=r"$v_x$ ($\sigma/t_0$)", title=r"$\kappa_f = 5$, $F = 0.02$: fits to (F-43)")
    axes[1, 0].set(xlabel=r"$y$ ($\sigma$)", ylabel=r"$\omega_z$ ($1/t_0$)", title=r"dashed: $-v_x'/2$ of the fit")
    axes[0, 0].legend(fontsize=8, frameon=False)
    series = {"gamma_f": ("g1k5F02", "g6k5F02", "g20k5F02"), "kappa_f": ("g6k1F02", "g6k5F02", "g6k20F02")}
    for column, (parameter, names) in enumerate(series.items(), start=1):
        x = [results[n]["config"].law.parameters[parameter] for n in names]
        for row, (key, label) in enumerate((("slip", r"slip length $b$ ($\sigma$)"), ("eta", r"$\eta$ ($k_BT t_0/\sigma^3$)"))):
            values = [getattr(results[n]["fit"], key) for n in names]
            errors = [results[n]["frames"][f"{key}_err"] for n in names]
            axis = axes[row, column]
            axis.errorbar(x, values, errors, fmt="o-", capsize=3, label="slit fit, $F = 0.02$")
            if key == "eta" and bulk is not None:
                axis.axhspan(bulk.eta - bulk.eta_err, bulk.eta + bulk.eta_err, color="0.85", label="bulk, transverse currents (6, 5)")
            axis.set(xscale="log", xlabel=rf"$\{parameter.split('_')[0]}_f$", ylabel=label)
            axis.set_title(r"$\kappa_f = 5$" if parameter == "gamma_f" else r"$\gamma_f = 6$", fontsize=10)
            axis.legend(fontsize=8, frameon=False)
    reduced = f"L_x = {LX:g}, L_z = {LZ:g}, N = {N}, {(STEPS - EQUILIBRATE) * 1e-3:g} t0 of data"
    fig.suptitle(f"Poiseuille flow at reduced cost ({reduced}): cf. Figs. 5 and 6 of Hofmann et al. 2025")
    fig.savefig(path, dpi=120)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("poiseuille-fig6"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--figure", type=Path, default=Path(__file__).resolve().parents[1] / "docs" / "poiseuille-fig6.png")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    clock = time.perf_counter()
    with ThreadPoolExecutor(args.jobs) as pool:
        jobs = [pool.submit(run_point, args.out, *point) for point in POINTS]
        jobs.append(pool.submit(run_bulk, args.out / "bulk.npz"))
        for job in jobs:
            job.result()
    results = {name: slit_result(args.out / name) for name, *_ in POINTS}
    data = np.load(args.out / "bulk.npz")
    bulk = transverse_viscosity(data["currents"], data["k"], float(data["interval"]), float(data["mass_density"]))
    print(f"errors: curve_fit with {BLOCKS} blocks per slab; [frames]: {FRAME_BLOCKS} blocks of the per-frame fit parameters")
    print(f"{'point':9s} {'gamma_f':>7s} {'kappa_f':>7s} {'F':>5s} {'eta':>16s} {'[frames]':>8s} {'b':>15s} {'[frames]':>8s} "
          f"{'chi2/dof':>8s} {'T_trans':>7s} {'s':>5s}")  # fmt: skip
    for name, gamma_f, kappa_f, force in POINTS:
        r = results[name]
        f, c = r["fit"], r["frames"]
        print(f"{name:9s} {gamma_f:7g} {kappa_f:7g} {force:5g} {f.eta:8.4f} +- {f.eta_err:.4f} {c['eta_err']:8.4f} {f.slip:7.3f} +- "
              f"{f.slip_err:.3f} {c['slip_err']:8.3f} {f.reduced_chi2:8.2f} {r['T_trans']:7.3f} {r['seconds']:5.0f}")  # fmt: skip
    print("bulk eta(k):", ", ".join(f"k = {k:.3f}: {e:.4f} +- {s:.4f}" for k, e, s in zip(bulk.k, bulk.eta_k, bulk.eta_k_err)))
    print(f"bulk eta (k -> 0): {bulk.eta:.4f} +- {bulk.eta_err:.4f}  ({float(data['seconds']):.0f} s)")
    slit, slit_err = results["g6k5F02"]["fit"], results["g6k5F02"]["frames"]["eta_err"]
    difference = (slit.eta - bulk.eta) / np.hypot(slit_err, bulk.eta_err)
    print(f"slit - bulk (gamma_f = 6, kappa_f = 5): {slit.eta - bulk.eta:+.4f} = {difference:+.2f} combined standard errors")
    chi2, bins = linear_response(results["g6k5F02"], results["g6k5F04"])
    print(f"linear response: v(2F)/2 - v(F) has chi^2 = {chi2:.1f} over {bins} bins")
    for key in ("eta", "slip"):
        low, high = (getattr(results[name]["fit"], key) for name in ("g6k5F02", "g6k5F04"))
        error = np.hypot(*(results[name]["frames"][f"{key}_err"] for name in ("g6k5F02", "g6k5F04")))
        print(f"linear response: {key}(2F) - {key}(F) = {high - low:+.4f} +- {error:.4f} ({(high - low) / error:+.2f} standard errors)")
    figure(results, bulk, args.figure)
    compute = sum(r["seconds"] for r in results.values())
    print(f"compute: {compute:.0f} s in the slit runs and {float(data['seconds']):.0f} s in the bulk run (each single-threaded)")
    print(f"figure {args.figure}; wall time of this script {time.perf_counter() - clock:.0f} s")


if __name__ == "__main__":
    main()
