"""Benchmark: the Langevin engine with another busy process on the machine (users' machines are busy).

2-D, N = 10 000, area fraction 0.6, WCA + solvent + Coulomb–Newton friction with its noise,
dt = 1e-3, timed after 2 t0 from the lattice. Prints particle-steps per second on 1 and 2 threads
with Numba's TBB threading layer (fricgen's default where the tbb wheel is installed, see
fricgen/__init__.py) and with OpenMP (its default wait policy, and passive), quiet and with one
competing busy process that the benchmark starts and stops itself. Each figure is measured in a
fresh process (the layer and the wait policy are fixed when the threads start), the configurations
alternate, and the medians over the rounds are printed. Run: python benchmarks/contention.py
"""

from __future__ import annotations

import multiprocessing
import os
import statistics
import subprocess
import sys

ROUNDS = 3
SETUPS = [("tbb", 1, ""), ("tbb", 2, ""), ("omp", 1, ""), ("omp", 2, ""), ("omp", 2, "PASSIVE")]
MEASURE = """
import statistics, time
import fricgen.compiled, numba
numba.set_num_threads({threads})
from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state
particles = Particles.spheres(10_000)
config = LangevinConfig(law=Law("coulomb_newton"), thermostat=Thermostat(dt=1e-3))
simulation = Simulation(config, particles, lattice_state(particles, 2, 0.6), load_law_kernels(config.law.name))
simulation.threads = {threads}
simulation.advance(2000)
times = []
for _ in range(3):
    start = time.perf_counter()
    simulation.advance(300)
    times.append(time.perf_counter() - start)
assert numba.threading_layer() == "{layer}", numba.threading_layer()
print(10_000 * 300 / statistics.median(times))
"""


def spin() -> None:
    """A busy process: one core's worth of work until it is terminated."""
    x = 0
    while True:
        x += 1


def rate(layer: str, threads: int, policy: str) -> float:
    env = {**os.environ, "NUMBA_THREADING_LAYER": layer, **({"OMP_WAIT_POLICY": policy} if policy else {})}
    command = [sys.executable, "-c", MEASURE.format(threads=threads, layer=layer)]
    return float(subprocess.run(command, capture_output=True, text=True, env=env, check=True).stdout.split()[-1])


def main() -> None:
    for busy in (False, True):
        rates = {setup: [] for setup in SETUPS}
        competitor = multiprocessing.Process(target=spin, daemon=True) if busy else None
        if competitor:
            competitor.start()
        try:
            for _ in range(ROUNDS):
                for setup in SETUPS:
                    rates[setup].append(rate(*setup))
        finally:
            if competitor:
                competitor.terminate()
                competitor.join()
        print("with one competing busy process:" if busy else "quiet machine:")
        for (layer, threads, policy), values in rates.items():
            figure = statistics.median(values) / 1e6
            print(f"  {layer:3s} {threads} thread(s) {policy or 'default':7s}: median {figure:.2f} M particle-steps/s")
        for layer, threads, policy in SETUPS:
            if threads == 2:
                ratio = statistics.median(rates[layer, 2, policy]) / statistics.median(rates[layer, 1, ""])
                print(f"  {layer} 2 threads ({policy.lower() or 'default'}) / 1 thread: {ratio:.2f}")


if __name__ == "__main__":
    main()
