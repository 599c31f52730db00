"""``fricgen demo``: the paper's passive check (sec. II B 1) in small, the built-in main job.

A 2-D system of N = 512 discs (R = 1/2, m = 1, I = 2/5 m R^2) at area fraction 0.6 with WCA
(epsilon = kT), the solvent gamma = 3 pi, gamma_R = pi and Coulomb–Newton friction
f = min(gamma_f u, w kappa_f) (F-32; gamma_f = 6, kappa_f = 5), Itô calculus, dt = 1e-3, is run
for 10 t0 (the first t0 equilibrates from a lattice), once with the frictional noise D of (F-33)
and once without it. With the noise both effective temperatures equal kT; without it the friction
cools the system, translation and rotation to different T_eff (about 0.82 and 0.69 kT).

Writes ``histograms.png``, ``temperatures.png`` and ``summary.json`` into the output folder: checked
before the runs (writable; a ``summary.json`` there that the demo did not write is refused, an
earlier demo's files are replaced).
"""

from __future__ import annotations

import json
import math
import time
from contextlib import closing
from pathlib import Path

from ...errors import ConfigError
from ...kernels import load_law_kernels
from ..run.outputs import check_folder, dumps
from ..run.progress import ProgressBar
from .plots import histogram_figure, temperature_figure
from .thermostat_check import passive_check, passive_run

#: The demo's system and run (the thermostat check's solvent and WCA are the paper's).
DEMO = {"law": "coulomb_newton", "calculus": "ito", "dim": 2, "n": 512, "phi": 0.6, "dt": 1e-3, "total_time": 10.0, "seed": 1}


def run_demo(folder: Path, **changes) -> dict:
    """Run the demo, with and without the contact noise, and write its files.

    Parameters
    ----------
    folder : Path
        The output folder (histograms.png, temperatures.png, summary.json).
    **changes
        Overrides of entries of ``DEMO`` (``n``, ``dt``, ``total_time`` [t0], ``seed``, ...).

    Returns
    -------
    dict
        The summary, as written to summary.json.
    """
    setup = {**DEMO, **changes}
    checks = [passive_check(**setup, contact_noise=noise) for noise in (True, False)]
    check_demo_folder(folder)
    law = load_law_kernels(setup["law"])  # a built-in law: the demo runs the same anywhere
    steps = checks[0].steps
    clock = time.perf_counter()
    runs = []
    with closing(ProgressBar(2 * steps, "fricgen demo")) as bar:
        for index, check in enumerate(checks):
            bar.offset = index * steps
            bar.describe(f"fricgen demo: {'with' if check.law.contact_noise else 'without'} contact noise")
            runs.append(passive_run(check, law, observers=[bar]))
    folder.mkdir(parents=True, exist_ok=True)
    files = [histogram_figure(runs, folder / "histograms.png"), temperature_figure(runs, folder / "temperatures.png")]
    summary = {
        **setup,
        "kT": 1.0,
        "gamma": 3 * math.pi,
        "gamma_rot": math.pi,
        "steps": steps,
        "runs": {
            ("with_contact_noise" if result.contact_noise else "without_contact_noise"): {
                **result.as_dict(),
                "z_trans": (result.T_trans - 1.0) / result.T_trans_err,
                "z_rot": (result.T_rot - 1.0) / result.T_rot_err,
            }
            for result, _ in runs
        },
        "seconds": time.perf_counter() - clock,
        "files": [path.name for path in files] + ["summary.json"],
    }
    (folder / "summary.json").write_text(dumps(summary))
    return summary


def check_demo_folder(folder: Path) -> None:
    """The demo can write into ``folder`` without losing another command's files (ConfigError at --out)."""
    check_folder(folder, "--out")
    summary = folder / "summary.json"
    if summary.exists():
        try:
            ours = "with_contact_noise" in json.loads(summary.read_text()).get("runs", {})
        except (OSError, ValueError, AttributeError, TypeError):
            ours = False
        if not ours:
            raise ConfigError("--out", f"{folder} holds a summary.json that the demo did not write", "give another folder")


def describe(summary: dict, folder: Path) -> str:
    """The summary as a short table."""
    lines = [f"fricgen demo: {summary['law']} ({summary['calculus']}), N = {summary['n']}, {summary['steps']} steps per run"]
    for name, r in summary["runs"].items():
        lines.append(
            f"  {name.replace('_', ' '):22s} T_trans = {r['T_trans']:.4f} +- {r['T_trans_err']:.4f} ({r['z_trans']:+.1f} sigma)   "
            f"T_rot = {r['T_rot']:.4f} +- {r['T_rot_err']:.4f} ({r['z_rot']:+.1f} sigma)   "
            f"KL = {r['kl_trans']:.1e} / {r['kl_rot']:.1e}   {'consistent' if r['passed'] else 'NOT at kT'}"
        )
    lines.append(f"  {summary['seconds']:.1f} s; wrote {', '.join(str(folder / f) for f in summary['files'])}")
    return "\n".join(lines)
