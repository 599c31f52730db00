"""Benchmark of Brownian cluster dynamics (issue 5 figures).

Hard rods, U0 = 6, sigma = 0.5, mean density 0.5, dt = 1e-5, lambda = 1: CPU microseconds per
particle-step (one thread, one replica) for N = 50, 500, 5000. Peer: the authors' C++ code costs
0.28 us (current version) and 0.07 us (older event-driven version); target <= 0.028 us. Then the
wall time to a profile within 1 % (L1 / rho_bar) of the exact theory at rho_bar sigma = 0.7,
dt = 1e-5, Monte Carlo start included (16 replicas on the available threads; chunks of 0.05 time units).
Run: python benchmarks/bcd.py
"""

from __future__ import annotations

import math
import statistics
import time

import numba
import numpy as np

from fricgen.rods import RodSimulation, exact_profile, rod_config

PEER_CURRENT, PEER_OLD, TARGET = 0.28, 0.07, 0.028


def cost_per_particle_step() -> None:
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    for n in (50, 500, 5000):
        simulation = RodSimulation(rod_config(n=n, length=2.0 * n, sigma=0.5, dt=1e-5, replicas=1))
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
    numba.set_num_threads(threads)


def time_to_one_percent(seed: int, chunk: float = 0.05, limit: float = 20.0) -> tuple[float, float]:
    """Sample in chunks until the L1 deviation of the running profile falls below 1 %; returns the
    sampled time units and the wall seconds (start included), or (inf, inf) within ``limit``."""
    config = rod_config(n=140, length=100.0, sigma=0.5, dt=1e-5, replicas=16, bins=25, seed=seed)
    exact = exact_profile(config).bin_means(config.sampling.bins)
    start = time.perf_counter()
    simulation = RodSimulation(config)
    simulation.equilibrate(0.25)
    rods, gaps = (
        np.zeros((config.sampling.replicas, config.sampling.bins)),
        np.zeros((config.sampling.replicas, config.sampling.bins, config.sampling.gap_bins)),
    )
    sampled = 0.0
    while sampled < limit:
        simulation.advance(round(chunk / config.numerics.dt), (rods, gaps))
        sampled += chunk
        rho = rods.sum(0) / rods.sum() * config.sampling.bins * config.model.mean_density
        if np.mean(np.abs(rho - exact)) / config.model.mean_density < 0.01:
            return sampled, time.perf_counter() - start
    return math.inf, math.inf


def main() -> None:
    cost_per_particle_step()
    runs = [time_to_one_percent(seed) for seed in (11, 12, 13, 14, 15)]
    for seed, (sampled, seconds) in zip((11, 12, 13, 14, 15), runs):
        print(f"rho_bar sigma = 0.70, dt = 1e-5, seed {seed}: L1/rho < 1 % after {sampled:g} time units, {seconds:.1f} s wall")
    print(f"median: {statistics.median(s for _, s in runs):.1f} s wall to a 1 % profile")


if __name__ == "__main__":
    main()
