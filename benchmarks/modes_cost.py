"""What a rolling or spinning law costs per step against sliding alone (docs/physics-modes.md).

System: 3-D, N = 1000 spheres at volume fraction 0.3, WCA + the solvent, dt = 1e-3, kT = 1, Itô noise,
the engine on one thread with its pairwise contact step (or the explicit kick with --explicit). Laws:
Coulomb–Newton on sliding (built in), and the linear rolling and spinning laws f = gamma u of a user's
folder (a temporary one, generated with `fricgen generate --laws DIR`). Setups: sliding alone, rolling
alone, sliding + rolling, all three modes. Each is equilibrated, then timed STEPS steps REPEATS times
in turn (alternately, so that a busy machine slows them alike); CPU time of the process on its one thread.

Printed: CPU ns per particle-step (median of the repeats) and the ratio to sliding alone.
Run: python benchmarks/modes_cost.py [--repeats 3] [--steps 500] [--explicit]
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from pathlib import Path

import numba

import fricgen
from fricgen.derive.driver import generate
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state

LAW = """name = "{mode}_linear"
description = "Linear {mode} friction f = gamma u."
friction = "gamma*u"
mode = "{mode}"
calculi = ["ito"]

[parameters.gamma]
default = 5.0
"""
SETUPS = {
    "sliding": ("coulomb_newton",),
    "rolling": ("rolling_linear",),
    "sliding + rolling": ("coulomb_newton", "rolling_linear"),
    "all three": ("coulomb_newton", "rolling_linear", "spinning_linear"),
}


def simulation(kernels: dict, names: tuple[str, ...], scheme: str, n: int = 1000) -> Simulation:
    modes = {kernels[name].mode: name for name in names[1:]}
    law = Law(name=names[0], contact_scheme=scheme, **modes)
    particles = Particles.spheres(n)
    state = lattice_state(particles, 3, 0.3, seed=1)
    sim = Simulation(LangevinConfig(law=law, thermostat=Thermostat(dt=1e-3)), particles, state, [kernels[x] for x in names])
    sim.threads = 1
    return sim


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=500)
    parser.add_argument("--explicit", action="store_true", help="time the explicit kick instead of the pairwise step")
    args = parser.parse_args()
    numba.set_num_threads(1)
    with tempfile.TemporaryDirectory() as folder:
        for mode in ("rolling", "spinning"):
            (Path(folder) / f"{mode}_linear.toml").write_text(LAW.format(mode=mode))
        generate(catalogue=Path(folder))
        kernels = {name: fricgen.load_law(name, folder=folder) for name in ("rolling_linear", "spinning_linear")}
        kernels["coulomb_newton"] = fricgen.load_law("coulomb_newton")
        sims = {label: simulation(kernels, names, "explicit" if args.explicit else "pairwise") for label, names in SETUPS.items()}
        for sim in sims.values():
            sim.advance(1000)  # compile, and leave the lattice
        times: dict[str, list[float]] = {label: [] for label in sims}
        for _ in range(args.repeats):
            for label, sim in sims.items():
                start = time.process_time()
                sim.advance(args.steps)
                times[label].append((time.process_time() - start) / (args.steps * sim.particles.radius.size) * 1e9)
    base = statistics.median(times["sliding"])
    print(f"{'explicit kick' if args.explicit else 'pairwise step'}, 3-D, N = 1000, phi = 0.3, {args.steps} steps x {args.repeats}")
    for label, values in times.items():
        cost = statistics.median(values)
        print(
            f"{label:18s} {cost:8.1f} ns per particle-step   {cost / base:5.2f} x sliding   (runs {', '.join(f'{v:.0f}' for v in values)})"
        )


if __name__ == "__main__":
    main()
