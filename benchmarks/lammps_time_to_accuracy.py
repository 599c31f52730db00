"""Time to a 0.5 % temperature in LAMMPS: the fix fricgen/exact/coulomb_newton (the pairwise contact step)
against the explicit pair style fricgen/coulomb_newton, the same system on the same cores.

Integrators: the explicit pair style under velocity Verlet; the fix under velocity Verlet (WCA from lj/cut,
the contact step at the end of each step); the fix under run_style respa 2 n pair 1 ("fix+respa": WCA on
n inner steps of dt / n = 2.5e-3, the contact step once per outer step dt).

System: that of benchmarks/lammps_exact.py (in.coulomb_newton_2d_exact and its explicit twin: 2-D, discs
of diameter 1 at area fraction 0.6, WCA, kT = 1, no solvent: the contacts alone are the thermostat),
N = cells^2 discs, one MPI rank each.

Accuracy: for each integrator, the dt of its ladder from the largest down, ``--seeds`` runs each (seeds
1000, 1001, ...): ``--warmup`` t0 discarded (the spins start at rest), then ``--time`` t0 sampled every
0.05 t0. T_trans (LAMMPS's temp), T_rot (temp/sphere dof rotate) and the potential energy per atom are
pooled over the seeds: the mean of the runs' means, its error sigma the larger of the seeds' scatter over
sqrt(seeds) and the runs' own errors (from 20 block means, fricgen.langevin.analysis.block_estimate)
combined. One run alone is not enough: at dt = 2e-2 the fix's T_trans was 1.0021 +- 0.0015 for one seed and
1.0071-1.0095 for seven others (round-off apart, each +- 0.0016), so the block errors of one run miss
a slow fluctuation. The error of a dt is d = max(|T_trans - kT|, |T_rot - kT|) / kT. The ladder stops
at the first dt with d <= 0.5 %; the dt at which d crosses 0.5 % is interpolated between it and the
dt above it, d ~ dt^p through the two points (if the dt above was unstable or the first dt is already
within, that first dt within is taken). Printed beside each row: the verdict of the errors, *within*
(d + 2 sigma <= 0.5 % for both temperatures), *off* (d - 2 sigma > 0.5 % for either) or *undecided*.
A run with dangerous neighbour-list builds (a dt too large for the skin) counts as unstable. The potential
energy is the configurational error, which the temperatures do not show.

Cost: at each integrator's crossing dt, particle-steps per second from LAMMPS's "Loop time" of
``--steps``-step runs, medians of ``--repeats`` alternating repeats; the wall time per unit of simulated
time is N / (rate dt). Printed: the ladders, the crossings, the costs, and the explicit pair style's wall
time to simulate the same physical time over the fix's (the ratio by which the fix is ahead).

Run: python benchmarks/lammps_time_to_accuracy.py [--cells 50] [--time 100] [--seeds 3] [--jobs 2]
     python benchmarks/lammps_time_to_accuracy.py --crossings fix=1.8e-2,explicit=5.5e-4   (time only, at crossings
     found before: where only the speed of an integrator changed, not its arithmetic, its ladder is unchanged)
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


def pooled(runs: list[dict[str, Estimate]]) -> dict[str, Estimate]:
    """Each quantity's mean over the seeds' runs, its error the larger of their scatter and their own errors."""
    out = {}
    for name in runs[0]:
        means, errors = np.array([r[name].mean for r in runs]), np.array([r[name].error for r in runs])
        scatter = means.std(ddof=1) / np.sqrt(len(runs)) if len(runs) > 1 else 0.0
        out[name] = Estimate(float(means.mean()), float(max(scatter, np.sqrt((errors**2).sum()) / len(runs))), len(runs))
    return out


def deviations(found: dict[str, Estimate]) -> list[tuple[float, float]]:
    """(|T - kT| / kT, 2 sigma / kT) of T_trans and T_rot."""
    return [(abs(found[t].mean - KT) / KT, 2 * found[t].error / KT) for t in ("T_trans", "T_rot")]


def deviation(found: dict[str, Estimate]) -> float:
    """d = max(|T_trans - kT|, |T_rot - kT|) / kT."""
    return max(d for d, _ in deviations(found))


def verdict(found: dict[str, Estimate]) -> str:
    """within, off or undecided (module docstring) for T_trans and T_rot together."""
    if all(d + s <= TOLERANCE for d, s in deviations(found)):
        return "within"
    if any(d - s > TOLERANCE for d, s in deviations(found)):
        return "off"
    return "undecided"


def ladder(run, name: str, dts: tuple[float, ...], seeds: int) -> list[tuple[float, str, dict[str, Estimate]]]:
    """The pooled runs of one integrator, largest dt first, down to the first whose error d is at most TOLERANCE."""
    rows = []
    for dt in dts:
        try:
            found = pooled([sampled(run(name, dt, 1000 + k)) for k in range(seeds)])
            rows.append((dt, verdict(found), found))
        except RuntimeError as error:
            rows.append((dt, f"unstable ({str(error).splitlines()[-1][:60]})", {}))
        if rows[-1][2] and deviation(rows[-1][2]) <= TOLERANCE:
            break
    return rows


def crossing(rows: list[tuple[float, str, dict[str, Estimate]]]) -> float | None:
    """The dt at which d crosses TOLERANCE, d ~ dt^p through the last row (d <= TOLERANCE) and the one above it;
    the last row's dt where there is none above or it was unstable; None if no row came within."""
    dt, _, found = rows[-1]
    if not found or deviation(found) > TOLERANCE:
        return None
    if len(rows) < 2 or not rows[-2][2]:
        return dt
    above, _, over = rows[-2]
    power = np.log(deviation(over) / deviation(found)) / np.log(above / dt)
    return float(dt * (TOLERANCE / deviation(found)) ** (1.0 / power))


def accuracy_ladders(options, run, n: int) -> dict[str, float] | None:
    """Run and print the ladders (``run(name, dt, seed)`` gives a run's output); the crossing dt of each
    integrator, or None (printed why) if one has none."""
    with ThreadPoolExecutor(max_workers=options.jobs) as pool:
        futures = {name: pool.submit(ladder, run, name, dts, options.seeds) for name, dts in LADDERS.items()}
        ladders = {name: future.result() for name, future in futures.items()}
    print(f"2-D, N = {n}, no solvent, 1 rank; per dt and seed {options.warmup:g} t0 discarded, {options.time:g} t0 sampled every")
    print(f"{SAMPLE} t0; pooled over {options.seeds} seeds; d = max |T - kT| / kT; within: |T - kT| + 2 sigma <= {TOLERANCE:.1%} for")
    print(f"both, off: |T - kT| - 2 sigma > {TOLERANCE:.1%}")
    print(f"  {'integrator':10s} {'dt':>7s}  {'T_trans':>16s}  {'T_rot':>16s}  {'pe per atom':>16s}  {'d':>6s}  verdict")
    for name, rows in ladders.items():
        for dt, decided, found in rows:
            cells = "  ".join(f"{e.mean:.4f} +- {e.error:.4f}" for e in found.values()) or f"{'':16s}  {'':16s}  {'':16s}"
            d = f"{deviation(found):6.2%}" if found else f"{'':6s}"
            print(f"  {name:10s} {dt:7.1e}  {cells}  {d}  {decided}")
    chosen = {name: crossing(rows) for name, rows in ladders.items()}
    missing = [name for name, dt in chosen.items() if dt is None]
    if missing:
        print(f"no dt of the ladder came within {TOLERANCE:.1%} for {', '.join(missing)}: no ratio (extend the ladder)")
        return None
    return chosen


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cells", type=int, default=50, help="lattice cells per side (N = cells^2)")
    parser.add_argument("--time", type=float, default=100.0, help="sampled t0 per accuracy run")
    parser.add_argument("--warmup", type=float, default=5.0, help="discarded t0 per accuracy run")
    parser.add_argument("--seeds", type=int, default=3, help="runs per dt, pooled")
    parser.add_argument("--jobs", type=int, default=1, help="the ladders side by side (2 or 3) or one after the other (1)")
    parser.add_argument("--repeats", type=int, default=3, help="timed repeats at each integrator's dt")
    parser.add_argument("--steps", type=int, default=2000, help="timed steps per repeat")
    parser.add_argument("--crossings", help="NAME=DT,...: skip the ladders and time these integrators at these dt")
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

    def run(name: str, dt: float, seed: int) -> str:
        extra = variables(dt, round(options.warmup / dt), max(1, round(SAMPLE / dt)))
        return lammps_output(lammps, scripts[name], 1, round(options.time / dt), extra, work, seed)

    if options.crossings:
        chosen = {name: float(dt) for name, dt in (item.split("=") for item in options.crossings.split(","))}
        print(f"2-D, N = {n}, no solvent, 1 rank; timed at the crossings given: {options.crossings}")
    else:
        chosen = accuracy_ladders(options, run, n)
        if chosen is None:
            return
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
            f"{name:10s} at dt = {dt:.2e} (d = {TOLERANCE:.1%}): {1e6 / rate:.3f} us per particle-step ({spread} M particle-steps/s, "
            f"median of {options.repeats}), {seconds[name]:.3f} s of wall time per t0"
        )
    for name in seconds:
        if name != "explicit":
            ratio = seconds["explicit"] / seconds[name]
            print(f"time to a {TOLERANCE:.1%} temperature, explicit / {name} (same physical time, 1 rank): {ratio:.2f}")


if __name__ == "__main__":
    main()
