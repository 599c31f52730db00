"""Time to a 0.5 % temperature in LAMMPS: the fix fricgen/exact/coulomb_newton (the pairwise contact step)
against the explicit pair style fricgen/coulomb_newton, the same system on the same cores.

Integrators: the explicit pair style under velocity Verlet; the fix under velocity Verlet (WCA from lj/cut,
the contact step at the end of each step); the fix under run_style respa 2 n pair 1 ("fix+respa": WCA on
n inner steps of dt / n = 2.5e-3, the contact step once per outer step dt).

System: that of benchmarks/lammps_exact.py (in.coulomb_newton_2d_exact and its explicit twin: 2-D, discs
of diameter 1 at area fraction 0.6, WCA, kT = 1, no solvent: the contacts alone are the thermostat),
N = cells^2 discs, one MPI rank each.

Accuracy: for each integrator, the dt of its ladder from the largest down, one run each: ``--warmup`` t0
discarded (the spins start at rest), then ``--time`` t0 sampled every 0.05 t0. T_trans (LAMMPS's temp)
and T_rot (temp/sphere dof rotate) are means with errors sigma from 20 block means
(fricgen.langevin.analysis.block_estimate). A dt is *within* when |T - kT| + 2 sigma <= 0.5 % kT for
both, *off* when |T - kT| - 2 sigma > 0.5 % kT for either, else *undecided* (the run cannot tell).
Each integrator's dt is its largest not off (within, or undecided: the benefit of the doubt, the same for
all); its ladder stops there (smaller dt cost more and are not needed). A run with dangerous neighbour-list
builds (a dt too large for the skin) counts as unstable. The potential energy per atom is printed beside the
temperatures: the configurational error, which the temperatures do not show.

Cost: at the dt within, particle-steps per second from LAMMPS's "Loop time" of ``--steps``-step runs,
medians of ``--repeats`` alternating repeats; the wall time per unit of simulated time is
N / (rate dt). Printed: the ladder, the costs, and the explicit pair style's wall time to simulate
the same physical time over the fix's (the ratio by which the fix is ahead).

Run: python benchmarks/lammps_time_to_accuracy.py [--cells 50] [--time 100] [--jobs 2]
"""

from __future__ import annotations

import argparse
import re
import statistics
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
from lammps_exact import inputs
from lammps_plugin import built_plugin, lammps_output, lammps_rate

from fricgen.langevin.analysis import Estimate, block_estimate

KT = 1.0
TOLERANCE = 0.005  # relative
SAMPLE = 0.05  # t0 between thermo samples
INNER = 2.5e-3  # t0, the inner step of fix+respa
LADDERS = {
    "fix": (2e-2, 1.5e-2, 1e-2, 5e-3, 2.5e-3, 1e-3),
    "fix+respa": (4e-2, 3e-2, 2e-2, 1e-2, 5e-3),
    "explicit": (5e-3, 2e-3, 1e-3, 7e-4, 5e-4, 2e-4, 1e-4),
}  # t0


def sampled(output: str) -> dict[str, Estimate]:
    """T_trans, T_rot and the potential energy per atom of the last thermo table of a LAMMPS output (Step Temp
    c_trot PotEng ...), block estimates; RuntimeError if a neighbour-list build came too late (a dt too large
    for the skin)."""
    dangerous = re.findall(r"Dangerous builds = (\d+)", output)
    if dangerous and int(dangerous[-1]) > 0:
        raise RuntimeError(f"{dangerous[-1]} dangerous neighbour-list builds")
    lines = output.splitlines()
    start = max(i for i, line in enumerate(lines) if line.split()[:3] == ["Step", "Temp", "c_trot"])
    rows = []
    for line in lines[start + 1 :]:
        try:
            rows.append([float(x) for x in line.split()[:4]])
        except ValueError:
            break
    table = np.array(rows[1:])  # the first row is the warm-up's last state
    return {"T_trans": block_estimate(table[:, 1]), "T_rot": block_estimate(table[:, 2]), "pe": block_estimate(table[:, 3])}


def verdict(found: dict[str, Estimate]) -> str:
    """within, off or undecided (module docstring) for T_trans and T_rot together."""
    deviations = [(abs(found[t].mean - KT) / KT, 2 * found[t].error / KT) for t in ("T_trans", "T_rot")]
    if all(d + s <= TOLERANCE for d, s in deviations):
        return "within"
    if any(d - s > TOLERANCE for d, s in deviations):
        return "off"
    return "undecided"


#: The verdicts at which an integrator's ladder stops: its dt (module docstring).
STOP = ("within", "undecided")


def ladder(run, name: str, dts: tuple[float, ...]) -> list[tuple[float, str, dict[str, Estimate]]]:
    """The runs of one integrator, largest dt first, up to the first not off (a verdict of STOP)."""
    rows = []
    for dt in dts:
        try:
            found = sampled(run(name, dt))
            rows.append((dt, verdict(found), found))
        except RuntimeError as error:
            rows.append((dt, f"unstable ({str(error).splitlines()[-1][:60]})", {}))
        if rows[-1][1] in STOP:
            break
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=50, help="lattice cells per side (N = cells^2)")
    parser.add_argument("--time", type=float, default=100.0, help="sampled t0 per accuracy run")
    parser.add_argument("--warmup", type=float, default=5.0, help="discarded t0 per accuracy run")
    parser.add_argument("--jobs", type=int, default=1, help="the ladders side by side (2 or 3) or one after the other (1)")
    parser.add_argument("--repeats", type=int, default=3, help="timed repeats at each integrator's dt")
    parser.add_argument("--steps", type=int, default=2000, help="timed steps per repeat")
    options = parser.parse_args()
    lammps, folder, plugin = built_plugin()
    work = Path(tempfile.mkdtemp(prefix="fricgen-bench-"))
    scripts = inputs(folder, work, warmup="${nwarm}")
    respa = Path(scripts["fix"]).read_text().replace("timestep ", "run_style       respa 2 ${inner} pair 1\ntimestep ", 1)
    (work / "in.fix_respa").write_text(respa)
    scripts["fix+respa"] = str(work / "in.fix_respa")
    n = options.cells**2

    def variables(dt: float, warmup_steps: int, thermo: int) -> list[str]:
        values = {"plugin": plugin, "solvent": 0, "cells": options.cells, "dt": dt, "nwarm": warmup_steps, "thermo": thermo}
        values["inner"] = max(1, round(dt / INNER))
        return [word for key, value in values.items() for word in ("-var", key, str(value))]

    def run(name: str, dt: float) -> str:
        extra = variables(dt, round(options.warmup / dt), max(1, round(SAMPLE / dt)))
        return lammps_output(lammps, scripts[name], 1, round(options.time / dt), extra, work)

    with ThreadPoolExecutor(max_workers=options.jobs) as pool:
        futures = {name: pool.submit(ladder, run, name, dts) for name, dts in LADDERS.items()}
        ladders = {name: future.result() for name, future in futures.items()}
    print(f"2-D, N = {n}, no solvent, 1 rank; per dt {options.warmup:g} t0 discarded, {options.time:g} t0 sampled every {SAMPLE} t0,")
    print(f"errors from 20 blocks; within: |T - kT| + 2 sigma <= {TOLERANCE:.1%} for both, off: |T - kT| - 2 sigma > {TOLERANCE:.1%}")
    print(f"  {'integrator':10s} {'dt':>7s}  {'T_trans':>16s}  {'T_rot':>16s}  {'pe per atom':>16s}  verdict")
    for name, rows in ladders.items():
        for dt, decided, found in rows:
            cells = "  ".join(f"{e.mean:.4f} +- {e.error:.4f}" for e in found.values()) or f"{'':16s}  {'':16s}  {'':16s}"
            print(f"  {name:10s} {dt:7.1e}  {cells}  {decided}")
    chosen = {name: next((dt for dt, decided, _ in rows if decided in STOP), None) for name, rows in ladders.items()}
    missing = [name for name, dt in chosen.items() if dt is None]
    if missing:
        print(f"every dt of the ladder is off for {', '.join(missing)}: no ratio (extend the ladder)")
        return
    undecided = [name for name, rows in ladders.items() if rows[-1][1] == "undecided"]
    rates: dict[str, list[float]] = {}
    for _ in range(options.repeats):
        for name, dt in chosen.items():
            extra = variables(dt, 200, options.steps)
            rates.setdefault(name, []).append(lammps_rate(lammps, scripts[name], 1, options.steps, extra, work))
    seconds = {}
    for name, dt in chosen.items():
        rate = statistics.median(rates[name])
        seconds[name] = n / (rate * dt)
        spread = ", ".join(f"{v / 1e6:.2f}" for v in rates[name])
        print(
            f"{name:10s} at dt = {dt:.1e}: {1e6 / rate:.3f} us per particle-step ({spread} M particle-steps/s, median of "
            f"{options.repeats}), {seconds[name]:.2f} s of wall time per t0"
        )
    for name in seconds:
        if name != "explicit":
            ratio = seconds["explicit"] / seconds[name]
            print(f"time to a {TOLERANCE:.1%} temperature, explicit / {name} (same physical time, 1 rank): {ratio:.2f}")
    if undecided:
        print(f"  undecided at its dt ({', '.join(undecided)}): 2 sigma reaches across {TOLERANCE:.1%}; longer runs would decide")


if __name__ == "__main__":
    main()
