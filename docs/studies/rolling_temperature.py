"""Issue 36 item 5: the peculiar temperatures per slab of the rolling slit, and whether the lower viscosity
without the rolling noise is a temperature effect, from finished ``fricgen run`` folders.

For each run folder of ``fricgen sweep docs/studies/rolling_temperature.toml`` (trajectory.gsd with a frame
every 1 t0) the GSD frames after ``run.equilibrate`` are pooled per slab in y (the velocity profile's
36 slabs) by :func:`fricgen.app.studies.poiseuille.slab_temperatures`: the streaming velocity u(y), the
translational temperature with the flow, T_trans = <m |v|^2> / 3 (the column of rolling.md's table),
the peculiar one, T_pec = <m |v - u(y)|^2> / 3, and T_rot = <I |omega|^2> / 3, per slab and over the
slit (sample-weighted). Errors: the standard error over BLOCKS consecutive blocks of frames. eta and b
are the run's fit of (F-43) with its frame errors (summary.json), as in rolling.md.

The temperature test (criterion fixed before the runs): the consistent model (every noise) at the lower
kT that matches the slit's T_pec without the rolling noise. Its eta is compared with rolling.md's two
800 t0 points at kappa_r = 5 (results/rolling.json beside this script: with every noise, ``r6k5_long``, and without the
rolling noise, ``r6k5_norolling_long``), errors in quadrature, and with the sqrt(T) scaling
eta_A sqrt(T_C / T_A) of the consistent point at kT = 1 (T: the slits' T_pec). A difference is seen at
two standard errors or more.

Written: ``rolling_temperature.json``. Usage (from the folder that holds the sweep's output)::

    nice -n 10 python docs/studies/rolling_temperature.py out/rolling_temperature/*/ --results docs/studies/results

Folders without summary.json are listed as not finished and skipped. Units: sigma = 1, m = 1, t0, and
kT = 1 of the reference runs (a run at a lower kT keeps the absolute epsilon, F, gamma_f, kappa_f,
gamma_r, kappa_r); eta in kT t0 / sigma^3, temperatures in kT.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from report import arguments, finished_runs  # docs/studies/report.py, beside this script

from fricgen.app.studies.poiseuille import slab_temperatures, trajectory_samples

DEFAULT = ("out/rolling_temperature/*/",)
#: rolling.md's results, beside this script.
ROLLING = Path(__file__).parent / "results" / "rolling.json"
#: Consecutive blocks of frames for the errors.
BLOCKS = 10
#: The temperatures per slab and over the slit.
KEYS = ("T_trans", "T_peculiar", "T_rot")
#: The test's runs, for eta (800 t0, 550 t0 of data) and for the slit's T_pec (with GSD frames every 1 t0):
#: A, every noise at kT = 1, B, without the rolling noise (eta: rolling.json's point and seeds 2-4;
#: the 400 t0 reruns are the first 400 t0 of rolling.json's runs, so their eta is left out), C, the
#: consistent model at the lower kT (seeds 1-4).
GROUPS = {
    "A": {"eta": ["point=r6k5_long"], "T": ["point=r6k5_T"]},
    "B": {
        "eta": ["point=r6k5_norolling_long", *(f"point=r6k5_norolling_long_s{k}" for k in (2, 3, 4))],
        "T": ["point=r6k5_norolling_T", *(f"point=r6k5_norolling_long_s{k}" for k in (2, 3, 4))],
    },
    "C": {kind: ["point=r6k5_kT080", *(f"point=r6k5_kT080_s{k}" for k in (2, 3, 4))] for kind in ("eta", "T")},
}


def pooled(frames: list[tuple], bins: int):
    """:func:`slab_temperatures` of the samples of ``frames`` (trajectory_samples) pooled."""
    columns = [np.concatenate([f[i] for f in frames]) for i in range(5)]
    return slab_temperatures(*columns, frames[0][5], bins)


def analyse(folder: Path) -> dict:
    """The slabs' and the slit's temperatures with their block errors, and the fit, of one run folder."""
    config = json.loads((folder / "config.json").read_text())
    summary = json.loads((folder / "summary.json").read_text())
    law, bins = config["law"], config["output"]["profile_bins"]
    frames = trajectory_samples(folder / "trajectory.gsd", config["run"]["equilibrate"])
    whole = pooled(frames, bins)
    blocks = [pooled([frames[i] for i in block], bins) for block in np.array_split(np.arange(len(frames)), BLOCKS)]

    def error(values: np.ndarray) -> np.ndarray:
        return np.std(values, axis=0, ddof=1) / np.sqrt(len(values))

    fit = summary["poiseuille"]
    return {
        "run": folder.name,
        "kT": config["thermostat"]["kT"],
        "noise": "sliding" if law.get("rolling_noise", True) is False else "all",
        "frames": len(frames),
        "eta": fit["eta"],
        "eta_err": fit["eta_err_frames"],
        "slip": fit["slip"],
        "slip_err": fit["slip_err_frames"],
        "slit": {key: {"mean": whole.slit(key), "error": float(error(np.array([b.slit(key) for b in blocks])))} for key in KEYS},
        "slabs": {
            "y": whole.y.tolist(),
            "count": whole.count.tolist(),
            "u_x": whole.flow[:, 0].tolist(),
            **{key: getattr(whole, key).tolist() for key in KEYS},
            **{f"{key}_err": error(np.array([getattr(b, key) for b in blocks])).tolist() for key in KEYS},
        },
        "seconds": round(summary["seconds"], 1),
    }


def compare(a: float, da: float, b: float, db: float) -> dict:
    """a - b, its error (quadrature) and the difference in standard errors."""
    error = float(np.hypot(da, db))
    return {"difference": a - b, "error": error, "sigmas": (a - b) / error}


def weighted(pairs: list[tuple[float, float]]) -> list[float]:
    """Inverse-variance mean of (value, error) pairs and its error."""
    values, errors = np.array(pairs).T
    weights = errors**-2
    return [float(np.sum(weights * values) / weights.sum()), float(weights.sum() ** -0.5)]


def combined(eta_runs: list[dict], t_runs: list[dict]) -> dict:
    """The group's eta and slit T_pec (inverse-variance means). With several seeds, eta's error is the larger of
    the frame errors' (inverse-variance) and the seeds' scatter (standard deviation / sqrt(seeds)); the seeds'
    chi^2 about the mean with the frame errors (n - 1 degrees of freedom) says which."""
    eta = weighted([(r["eta"], r["eta_err"]) for r in eta_runs])
    out = {
        "runs": {"eta": [r["run"] for r in eta_runs], "T": [r["run"] for r in t_runs]},
        "eta": eta,
        "T_peculiar": weighted([(r["slit"]["T_peculiar"]["mean"], r["slit"]["T_peculiar"]["error"]) for r in t_runs]),
    }
    if len(eta_runs) > 1:
        values = np.array([r["eta"] for r in eta_runs])
        scatter = float(values.std(ddof=1) / np.sqrt(values.size))
        chi2 = float(sum(((r["eta"] - eta[0]) / r["eta_err"]) ** 2 for r in eta_runs))
        out["seeds"] = {"values": values.tolist(), "scatter_error": scatter, "frame_error": eta[1], "chi2": chi2, "dof": values.size - 1}
        out["eta"] = [eta[0], max(eta[1], scatter)]
    return out


def temperature_test(runs: dict[str, dict]) -> dict | None:
    """The groups A, B, C (GROUPS; ``runs`` by name, rolling.json's and these) combined, and the test:
    C - B and C - A (errors in quadrature), eta_A sqrt(T_C / T_A) against eta_C, the exponent
    alpha = ln(eta_C / eta_A) / ln(T_C / T_A), eta_C moved to T_B with it, and the fraction of the drop
    A - B that C - A explains, (eta_A - eta_C) / (eta_A - eta_B) (errors to first order, the three
    independent). T: the slit's T_pec. None until every group has its runs for eta and T_pec."""
    chosen = {key: [[runs[name] for name in group[kind] if name in runs] for kind in ("eta", "T")] for key, group in GROUPS.items()}
    if not all(eta and t for eta, t in chosen.values()):
        return None
    groups = {key: combined(*pair) for key, pair in chosen.items()}
    (a, da), (b, db), (c, dc) = (groups[k]["eta"] for k in "ABC")
    (t_a, dt_a), (t_b, _), (t_c, dt_c) = (groups[k]["T_peculiar"] for k in "ABC")
    log_t = np.log(t_c / t_a)
    log_t_err = np.hypot(dt_a / t_a, dt_c / t_c)
    scaled = a * np.sqrt(t_c / t_a)
    scaled_err = scaled * np.hypot(da / a, 0.5 * log_t_err)
    alpha = np.log(c / a) / log_t
    alpha_err = np.hypot(np.hypot(dc / c, da / a) / log_t, alpha * log_t_err / log_t)
    moved = c * (t_b / t_c) ** alpha
    drop = a - b
    return {
        "groups": groups,
        "C_minus_B": compare(c, dc, b, db),
        "C_minus_A": compare(c, dc, a, da),
        "sqrt_T_prediction": [float(scaled), float(scaled_err)],
        "C_minus_sqrt_T": compare(c, dc, float(scaled), float(scaled_err)),
        "alpha": [float(alpha), float(alpha_err)],
        "C_at_T_B_minus_B": compare(float(moved), dc * moved / c, b, db),
        "explained": [(a - c) / drop, float(np.sqrt(((c - b) * da) ** 2 + (drop * dc) ** 2 + ((a - c) * db) ** 2) / drop**2)],
    }


def main(argv: list[str] | None = None) -> None:
    args = arguments(argv, __doc__.splitlines()[0], DEFAULT)
    runs, pending = finished_runs(args.folders, analyse)
    rolling = {run["run"]: run for run in json.loads(ROLLING.read_text())["runs"]}
    record = {
        "blocks": BLOCKS,
        "runs": runs,
        "temperature_test": temperature_test(rolling | {run["run"]: run for run in runs}),
        "not_finished": pending,
    }
    args.results.mkdir(parents=True, exist_ok=True)
    (args.results / "rolling_temperature.json").write_text(json.dumps(record, indent=1) + "\n")
    for run in runs:
        slit = "  ".join(f"{key} = {v['mean']:.3f} +- {v['error']:.3f}" for key, v in run["slit"].items())
        eta = f"eta = {run['eta']:.4f} +- {run['eta_err']:.4f}"
        print(f"{run['run']} (kT = {run['kT']}, noise: {run['noise']}, {run['frames']} frames): {eta}, {slit}")
        s = run["slabs"]
        print("   y     count   u_x    T_trans          T_pec            T_rot")
        for j in np.flatnonzero(np.array(s["count"]) > 1):
            cells = "  ".join(f"{s[k][j]:.3f} +- {s[k + '_err'][j]:.3f}" for k in KEYS)
            print(f"{s['y'][j]:7.2f} {s['count'][j]:7.0f} {s['u_x'][j]:6.3f}  {cells}")
    print(json.dumps(record["temperature_test"], indent=1))
    print("not finished:", pending)


if __name__ == "__main__":
    main()
