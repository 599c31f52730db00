"""Benchmark of Brownian cluster dynamics (issue 5 figures).

Hard rods, U0 = 6, sigma = 0.5, mean density 0.5, dt = 1e-5, lambda = 1: CPU microseconds per
particle-step (one thread, one replica) for N = 50, 500, 5000. Peer: the authors' C++ code costs
0.28 us (current version) and 0.07 us (older event-driven version); target <= 0.028 us.
Run: python benchmarks/bcd.py
"""

from __future__ import annotations

import statistics
import time

import numba

from fricgen.rods import RodConfig, RodSimulation

PEER_CURRENT, PEER_OLD, TARGET = 0.28, 0.07, 0.028


def main() -> None:
    numba.set_num_threads(1)
    for n in (50, 500, 5000):
        simulation = RodSimulation(RodConfig(n=n, length=2.0 * n, sigma=0.5, dt=1e-5, replicas=1))
        simulation.equilibrate(1.0, dt=1e-4)
        steps = max(2000, 4_000_000 // n)
        costs = []
        for _ in range(5):
            start = time.process_time()
            simulation.advance(steps)
            costs.append((time.process_time() - start) / (steps * n) * 1e6)
        cost = statistics.median(costs)
        print(
            f"N = {n:5d}: {cost:.4f} us CPU per particle-step; vs C++ current {PEER_CURRENT / cost:.1f}x faster, "
            f"vs C++ event-driven {PEER_OLD / cost:.1f}x; target {TARGET} us: {'met' if cost <= TARGET else 'not met'}"
        )


if __name__ == "__main__":
    main()
