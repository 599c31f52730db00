"""Benchmark of fricgen's engine against LAMMPS with the fix fricgen/exact/coulomb_newton: the same scheme
(the pairwise contact step, Metropolis-adjusted, with WCA), one core each, measured alternately in one run.

System: 2-D, N = 10 000 discs at area fraction 0.6, WCA + Coulomb–Newton (gamma_f = 6, kappa_f = 5) with its
Itô noise, no solvent (the contacts are the thermostat), dt = 5e-3, kT = 1:

- LAMMPS: generated/lammps/coulomb_newton/in.coulomb_newton_2d_exact (lj/cut + fix nve/sphere + the fix),
  `lmp` on 1 rank (OMP_NUM_THREADS=1), particle-steps per second from "Loop time" after a 200-step warm-up;
- fricgen: the engine's passive run of the same system (gamma = gamma_R = 0, contact_scheme "pairwise"),
  one Numba thread, timed by `Simulation.advance` after 200 steps.

Printed: the rate of each (medians of the repeats) and the engine over LAMMPS per core.

Run: python benchmarks/lammps_engine.py [--repeats 3] [--steps 1000]
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
from pathlib import Path

from lammps_exact import inputs
from lammps_plugin import N, built_plugin, engine, engine_rate, lammps_rate

from fricgen.langevin import Thermostat

DT = 5e-3


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1000, help="timed steps per measurement")
    options = parser.parse_args()
    lammps, folder, plugin = built_plugin()
    work = Path(tempfile.mkdtemp(prefix="fricgen-bench-"))
    script = inputs(folder, work)["fix"]
    extra = ["-var", "plugin", str(plugin), "-var", "solvent", "0", "-var", "cells", "100", "-var", "dt", str(DT)]
    simulation = engine(1, Thermostat(gamma=0.0, gamma_rot=0.0, dt=DT))
    rates: dict[str, list[float]] = {"LAMMPS + fix": [], "fricgen engine": []}
    for _ in range(options.repeats):
        rates["LAMMPS + fix"].append(lammps_rate(lammps, script, 1, options.steps, extra, work))
        rates["fricgen engine"].append(engine_rate(simulation, 1, options.steps))
    median = {name: statistics.median(values) for name, values in rates.items()}
    print(f"2-D, N = {N}, dt = {DT:g}, no solvent, pairwise contact step, 1 core each, medians of {options.repeats} alternating repeats:")
    for name, values in rates.items():
        spread = ", ".join(f"{v / 1e6:.2f}" for v in values)
        print(f"  {name:15s} {median[name] / 1e6:.2f} M particle-steps/s ({1e6 / median[name]:.3f} us per particle-step; {spread})")
    print(f"fricgen engine / LAMMPS + fix, per core: {median['fricgen engine'] / median['LAMMPS + fix']:.2f}")


if __name__ == "__main__":
    main()
