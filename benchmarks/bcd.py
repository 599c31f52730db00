"""Benchmark of Brownian cluster dynamics (issues 5 and 30): cost per step and time to a 1 % profile.

1. Cost: hard rods, U0 = 6, sigma = 0.5, rho_bar sigma = 0.25, dt = 1e-5, lambda = 1: CPU microseconds per
   particle-step (one thread, one replica, median of 5 repeats) for N = 50, 500, 5000, BCD's merge layer
   and the bridge layer. Peer: the authors' C++ code costs 0.28 us (current version) and 0.07 us (older
   event-driven version); target <= 0.028 us.
2. Dense cost: the configuration of part 3 (N = 140, L = 100, 16 replicas) at each layer's time step, CPU
   seconds per step on one thread (median of 5 repeats), and its ratio to merge at dt = 1e-5.
3. Time to a 1 % dense profile: rho_bar sigma = 0.7, sampled in chunks of 0.005 time units until the L1
   deviation of the running profile from the exact theory falls below 1 % of rho_bar. Every run starts as
   `fricgen bcd` does: the Monte Carlo start, then 0.25 time units of BCD at dt before sampling. Runs: merge
   at dt = 2.5e-6 (within error there), 1e-5 and 3e-5 (its L1 bias is below 1 % there, its chi^2 is not), bridge
   at 1e-4 (within error) and 3e-4 (L1 bias about 0.5 %), alternating in the same run and process on the same
   thread, so that all see the same load of a shared machine. Per run the median over the seeds of the sampled
   time, the wall seconds (Monte Carlo start included, and after it), and the times computed from the dense
   cost of part 2 times the steps, (0.25 time units + the median sampled time) / dt, and of the sampling alone;
   then the ratios of merge's times to bridge's, for every pair of their runs.

Run: NUMBA_NUM_THREADS=1 nice -n 5 python benchmarks/bcd.py [--quick: skip part 1] [--seeds 11,12,13,14,15]
[--limit 2: sampled time units before a run counts as not converged] (about 5 minutes on a loaded 2-core machine).
"""

from __future__ import annotations

import argparse
import math
import statistics
import time

import numba
import numpy as np

from fricgen.rods import RodSimulation, exact_profile, rod_config

PEER_CURRENT, PEER_OLD, TARGET = 0.28, 0.07, 0.028
LAYERS = ("merge", "bridge")
#: The runs of the time to a 1 % profile: (layer, time step); merge at 3e-5 and bridge at 3e-4 are the
#: largest steps whose bias (L1 / rho_bar about 0.7 % and 0.5 %, docs/physics-bcd-contact-layer.md) is below 1 %.
#: merge at 2.5e-6 is the step it needs for a profile within error (issue 30).
RUNS = (("merge", 2.5e-6), ("merge", 1e-5), ("merge", 3e-5), ("bridge", 1e-4), ("bridge", 3e-4))
EQUILIBRATE = 0.25  # time units of BCD after the Monte Carlo start, as fricgen bcd's default --equilibrate
REPEATS = 5


def cost_per_particle_step(layer: str) -> None:
    for n in (50, 500, 5000):
        simulation = RodSimulation(rod_config(n=n, length=2.0 * n, sigma=0.5, dt=1e-5, replicas=1, contact_layer=layer))
        simulation.equilibrate(1.0, dt=1e-4)
        steps = max(2000, 4_000_000 // n)
        costs = []
        for _ in range(REPEATS):
            start = time.process_time()
            simulation.advance(steps)
            costs.append((time.process_time() - start) / (steps * n) * 1e6)
        cost = statistics.median(costs)
        print(
            f"{layer}, N = {n:5d}: {cost:.4f} us CPU per particle-step; vs C++ current {PEER_CURRENT / cost:.1f}x faster, "
            f"vs C++ event-driven {PEER_OLD / cost:.1f}x; target {TARGET} us: {'met' if cost <= TARGET else 'not met'}",
            flush=True,
        )


def dense_config(layer: str, dt: float, seed: int = 11):
    """rho_bar sigma = 0.7: N = 140 rods of sigma = 0.5 on L = 100, U0 = 6, 16 replicas, 25 bins."""
    return rod_config(n=140, length=100.0, sigma=0.5, dt=dt, replicas=16, bins=25, seed=seed, contact_layer=layer)


def dense_cost(layer: str, dt: float) -> float:
    """CPU seconds per step of the dense configuration at dt (median of REPEATS runs of 2000 steps, after 0.05
    time units at dt, so that the gaps near contact are those of the layer at that step)."""
    simulation = RodSimulation(dense_config(layer, dt))
    simulation.equilibrate(0.05)
    costs = []
    for _ in range(REPEATS):
        start = time.process_time()
        simulation.advance(2000)
        costs.append((time.process_time() - start) / 2000)
    return statistics.median(costs)


def time_to_one_percent(seed: int, layer: str, dt: float, limit: float, chunk: float = 0.005) -> tuple[float, float, float]:
    """Sample in chunks of ``chunk`` time units until the L1 deviation of the running profile falls below 1 %;
    returns the sampled time units, the wall seconds (Monte Carlo start included) and the wall seconds after
    the start, or infinities if ``limit`` time units do not reach it."""
    config = dense_config(layer, dt, seed)
    exact = exact_profile(config).bin_means(config.sampling.bins)
    start = time.perf_counter()
    simulation = RodSimulation(config)
    started = time.perf_counter()
    simulation.equilibrate(EQUILIBRATE)
    c = config.sampling
    rods, gaps = np.zeros((c.replicas, c.bins)), np.zeros((c.replicas, c.bins, c.gap_bins))
    sampled, steps = 0.0, max(1, round(chunk / dt))
    while sampled < limit:
        simulation.advance(steps, (rods, gaps))
        sampled += steps * dt
        rho = rods.sum(0) / rods.sum() * c.bins * config.model.mean_density
        if np.mean(np.abs(rho - exact)) / config.model.mean_density < 0.01:
            end = time.perf_counter()
            return sampled, end - start, end - started
    return math.inf, math.inf, math.inf


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the cost per particle-step (part 1)")
    parser.add_argument("--seeds", default="11,12,13,14,15")
    parser.add_argument("--limit", type=float, default=2.0, help="sampled time units before a run counts as not converged")
    args = parser.parse_args()
    print(f"numba threads: {numba.get_num_threads()}")
    if not args.quick:
        threads = numba.get_num_threads()
        numba.set_num_threads(1)
        for layer in LAYERS:
            cost_per_particle_step(layer)
        numba.set_num_threads(threads)

    costs = {run: dense_cost(*run) for run in RUNS}
    print("\n| layer | dt | CPU ms per step (N = 140, 16 replicas) | us per particle-step | / merge at 1e-5 |")
    print("|---|---|---|---|---|")
    merge = costs[("merge", 1e-5)]
    for (layer, dt), cost in costs.items():
        print(f"| {layer} | {dt:g} | {1e3 * cost:.3f} | {1e6 * cost / (140 * 16):.4f} | {cost / merge:.2f} |", flush=True)

    seeds = [int(s) for s in args.seeds.split(",")]
    runs = {run: [] for run in RUNS}
    print()
    for seed in seeds:  # the runs alternate, so that all see the same load of a shared machine
        for run in RUNS:
            sampled, seconds, dynamics = time_to_one_percent(seed, *run, args.limit)
            runs[run].append((sampled, seconds, dynamics))
            print(
                f"{run[0]}, dt = {run[1]:g}, seed {seed}: L1/rho < 1 % after {sampled:.3g} sampled time units, "
                f"{seconds:.2f} s wall ({dynamics:.2f} s after the Monte Carlo start)",
                flush=True,
            )
    medians = {run: [statistics.median(t[k] for t in times) for k in range(3)] for run, times in runs.items()}
    computed = {run: (EQUILIBRATE + medians[run][0]) / run[1] * costs[run] for run in RUNS}
    sampling = {run: medians[run][0] / run[1] * costs[run] for run in RUNS}
    print(f"\nmedians over seeds {args.seeds}")
    print(
        "| layer | dt | sampled time to 1 % | wall s (MC start incl.) | wall s after start | computed s (cost x steps) "
        "| computed s, sampling alone |"
    )
    print("|---|---|---|---|---|---|---|")
    for run in RUNS:
        sampled, seconds, dynamics = medians[run]
        print(f"| {run[0]} | {run[1]:g} | {sampled:.3g} | {seconds:.2f} | {dynamics:.2f} | {computed[run]:.2f} | {sampling[run]:.2f} |")
    print("\nhow many times faster bridge reaches a 1 % profile than merge (merge's time / bridge's)")
    print("| bridge dt | merge dt | wall (MC start incl.) | wall after start | computed | sampling alone |")
    print("|---|---|---|---|---|---|")
    for run in (run for run in RUNS if run[0] == "bridge"):
        for ref in (run for run in RUNS if run[0] == "merge"):
            (_, seconds, dynamics), (_, ref_seconds, ref_dynamics) = medians[run], medians[ref]
            print(
                f"| {run[1]:g} | {ref[1]:g} | {ref_seconds / seconds:.1f} | {ref_dynamics / dynamics:.1f} | "
                f"{computed[ref] / computed[run]:.1f} | {sampling[ref] / sampling[run]:.1f} |"
            )


if __name__ == "__main__":
    main()
