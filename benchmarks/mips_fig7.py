"""Fig. 7 of the paper at reduced size: Coulomb–Newton friction without its noise phase separates,
the consistent model (with the contact noise) does not, at one state point (F0, area fraction).

Both runs are ``fricgen run active`` (sec. II B 3: m = 0.05, WCA epsilon = 10, gamma = gamma_R = 1,
gamma_f = kappa_f = 1, time in t_R) from the same lattice start and seed; the MIPS verdict pools the
GSD frames (one per t_R) of the second half, at most the last 10. Prints each model's verdict,
dilute and dense area fractions and wall time; draws both histograms and final snapshots into
docs/mips-fig7.png. A finished run already in the output folder is reused, not rerun.
About 6 + 8 min of one core at the defaults (docs/mips.md).
Run: NUMBA_NUM_THREADS=1 python benchmarks/mips_fig7.py [--n 2000] [--phi 0.5] [--force 35]
     [--time 40] [--dt 2e-4] [--out /tmp/mips-fig7] [--figure docs/mips-fig7.png]
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

from matplotlib.figure import Figure

from fricgen.app.run.runner import execute, plan
from fricgen.app.studies.mips import Mips, draw_histogram, draw_snapshot, read_frames

MODELS = (("without contact noise", "false", "tab:red"), ("with contact noise (consistent)", "true", "tab:blue"))


def run(args, noise: str, folder: Path) -> tuple[Mips, float]:
    """One model's run (or the finished run already in ``folder``); its mips entry and wall time."""
    if not (folder / "summary.json").exists():
        steps = round(args.time / args.dt)
        frame, chunk = round(1 / args.dt), round(0.1 / args.dt)
        settings = {
            "system.n": args.n,
            "system.packing_fraction": args.phi,
            "active.force": args.force,
            "thermostat.dt": args.dt,
            "law.contact_noise": noise,
            "run.seed": args.seed,
            "run.equilibrate": steps // 2,
            "run.chunk": chunk,
            "output.period": chunk,
            "output.trajectory_period": frame,
            "output.checkpoint_period": 0,
        }
        status = execute(plan("active", [f"{key}={value}" for key, value in settings.items()], steps, str(folder), None))
        if status:
            raise SystemExit(f"{folder}: fricgen run ended with status {status}")
    summary = json.loads((folder / "summary.json").read_text())
    return Mips(**summary["mips"]), summary["seconds"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=2000)
    parser.add_argument("--phi", type=float, default=0.5, help="area fraction")
    parser.add_argument("--force", type=float, default=35.0, help="F0 in kT/sigma")
    parser.add_argument("--time", type=float, default=40.0, help="simulated time per run (t_R)")
    parser.add_argument("--dt", type=float, default=2e-4)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", type=Path, default=Path("/tmp/mips-fig7"))
    parser.add_argument("--figure", type=Path, default=Path(__file__).resolve().parents[1] / "docs" / "mips-fig7.png")
    args = parser.parse_args()
    figure = Figure(figsize=(14, 4.6), layout="constrained")
    histogram, *snapshots = figure.subplots(1, 3, width_ratios=(1, 1, 1))
    point = f"N = {args.n}, area fraction {args.phi}, F0 = {args.force:g}, dt = {args.dt:g} t_R, {args.time:g} t_R"
    print(f"Coulomb–Newton gamma_f = kappa_f = 1; {point}")
    for (label, noise, colour), axis in zip(MODELS, snapshots):
        folder = args.out / f"noise-{noise}"
        start = time.perf_counter()
        mips, seconds = run(args, noise, folder)
        verdict = f"phase separated (dilute {mips.phi_dilute:.3f}, dense {mips.phi_dense:.3f})" if mips.phase_separated else "not separated"
        dip = "none" if mips.dip_ratio is None else f"{mips.dip_ratio:.2f}"
        here = time.perf_counter() - start
        print(f"  {label:32s}: {verdict}; dip ratio {dip}; {mips.frames} frames; run {seconds:.0f} s (this call {here:.0f} s)")
        draw_histogram(histogram, mips, f"{label}: ", colour)
        frames, steps = read_frames(folder / "trajectory.gsd", last=1)
        mappable = draw_snapshot(axis, frames[-1], mips.kernel, mips.spacing)
        axis.set_title(f"{label}, t = {steps[-1] * args.dt:g} $t_R$", fontsize=10)
    histogram.set_title(f"{mips.frames} frames pooled, t = {mips.steps[0] * args.dt:g} to {mips.steps[-1] * args.dt:g} $t_R$", fontsize=10)
    figure.colorbar(mappable, ax=snapshots, label=r"local area fraction $\phi$", shrink=0.8)
    figure.suptitle(f"Active Langevin particles with Coulomb–Newton friction: {point}", fontsize=11)
    args.figure.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(args.figure, dpi=90)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()
