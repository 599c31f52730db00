"""Benchmark: the Langevin engine with another busy process on the machine (users' machines are busy).

2-D, N = 10 000, area fraction 0.6, WCA + solvent + Coulomb–Newton friction with its noise,
dt = 1e-3. Prints particle-steps per second on 1 thread and on 2 threads with OpenMP's active
(spinning) and passive (sleeping) wait policies, quiet and with one competing busy process that the
benchmark starts and stops itself. Each figure is measured in a
fresh process (the wait policy is read when the OpenMP runtime starts), the configurations
alternate, and the medians over the rounds are printed. Run: python benchmarks/contention.py
"""

from __future__ import annotations

import multiprocessing
import os
import statistics
import subprocess
import sys

ROUNDS = 3
MEASURE = """
import statistics, time
import numba
numba.set_num_threads({threads})
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state
particles = Particles.spheres(10_000)
config = LangevinConfig(law=Law("coulomb_newton"), thermostat=Thermostat(dt=1e-3))
simulation = Simulation(config, particles, lattice_state(particles, 2, 0.6))
simulation.advance(100)
times = []
for _ in range(3):
    start = time.perf_counter()
    simulation.advance(300)
    times.append(time.perf_counter() - start)
print(10_000 * 300 / statistics.median(times))
"""


def spin() -> None:
    """A busy process: one core's worth of work until it is terminated."""
    x = 0
    while True:
        x += 1


def rate(threads: int, policy: str) -> float:
    env = {**os.environ, "OMP_WAIT_POLICY": policy}
    done = subprocess.run([sys.executable, "-c", MEASURE.format(threads=threads)], capture_output=True, text=True, env=env, check=True)
    return float(done.stdout.split()[-1])


def main() -> None:
    setups = [(1, "ACTIVE"), (2, "ACTIVE"), (2, "PASSIVE")]
    for busy in (False, True):
        rates = {setup: [] for setup in setups}
        competitor = multiprocessing.Process(target=spin, daemon=True) if busy else None
        if competitor:
            competitor.start()
        try:
            for _ in range(ROUNDS):
                for setup in setups:
                    rates[setup].append(rate(*setup))
        finally:
            if competitor:
                competitor.terminate()
                competitor.join()
        print("with one competing busy process:" if busy else "quiet machine:")
        for (threads, policy), values in rates.items():
            print(f"  {threads} thread(s), OMP_WAIT_POLICY={policy:7s}: median {statistics.median(values) / 1e6:.2f} M particle-steps/s")
        single = statistics.median(rates[(1, "ACTIVE")])
        for policy in ("ACTIVE", "PASSIVE"):
            print(f"  2 threads ({policy.lower()}) / 1 thread: {statistics.median(rates[(2, policy)]) / single:.2f}")


if __name__ == "__main__":
    main()
