"""Benchmark of Brownian cluster dynamics (issues 5, 30 and 41): cost per step and time to a 1 % profile.

1. Cost: hard rods, U0 = 6, sigma = 0.5, rho_bar sigma = 0.25, dt = 1e-5, lambda = 1: CPU microseconds per
   particle-step (one thread, one replica, median of 5 repeats) for N = 50, 500, 5000, BCD's merge layer
   and the bridge layer. Peer: the authors' C++ code costs 0.28 us (current version) and 0.07 us (older
   event-driven version); target <= 0.028 us.
2. Each method's largest step within error, in the dense rings (rho_bar sigma = 0.7: N = 140 rods on L = 100,
   U0 = 6, 16 rings, 25 bins; bcd_timestep.py's case "0.7"). Methods: BCD's merge layer, the bridge layer
   with the Euler drift ("bridge"), with the Leimkuhler-Matthews midpoint ("bridge+lm") and with the Euler drift
   and the Metropolis test of each step ("bridge+metropolis"; docs/physics-bcd-field-drift.md,
   docs/physics-bcd-metropolis.md). Rule: a step is within error when its profile is statistically
   consistent with the exact one in the standard study (1.25 sampled time units after 0.25, the k-th step
   tried with seed 11 + k): the chi^2 per bin within 3 standard deviations of an exact profile's (chi2_bound)
   and the pooled contact density within 3 of its errors of exact (with the Metropolis test, also at most half
   of the steps rejected: beyond, the rings hardly move and a 1 % profile takes longer). Each method's
   CANDIDATES are tried from the largest down; the first within error is its step. A method with none is within
   error only below its smallest candidate: it is timed there, and the ratios against it are lower bounds.
3. Dense cost: CPU seconds per step of that configuration at each timed step (one thread, median of 5 repeats).
4. Time to a 1 % dense profile: sampled in chunks of 0.005 time units until the L1 deviation of the running
   profile from the exact theory falls below 1 % of rho_bar. Every run starts as `fricgen bcd` does: the
   Monte Carlo start, then 0.25 time units of BCD at dt before sampling. Timed: each method at its step of
   part 2; merge also at its next candidate up (not within error: its largest step within error lies between
   the two, and so does the ratio against it) and at REACHES (3e-5: its L1 bias, not its chi^2, lets it reach
   1 %). The runs alternate in the same process on the same thread, so that all see the same load of a
   shared machine. Per run the median over the seeds of the sampled time, the wall seconds (Monte Carlo start
   included, and after it) and the time computed from part 3's cost times the steps, (0.25 + the median
   sampled time) / dt; then how many times sooner each bridge method gets there than merge (merge's time /
   its), and against merge's largest step within error the range with the verdict on issue 41's
   TARGET_RATIO (its lower end, after the start and computed).

Run: NUMBA_NUM_THREADS=1 nice -n 5 python benchmarks/bcd.py [--quick: skip part 1] [--seeds 11,12,13,14,15]
[--limit 1: sampled time units before a run counts as not converged] (about 20 minutes on a loaded 2-core
machine; merge at 3e-7 dominates).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numba
import numpy as np

from fricgen.rods import RodSimulation, exact_profile, rod_config

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bcd_timestep import case_config, measure  # noqa: E402

PEER_CURRENT, PEER_OLD, TARGET = 0.28, 0.07, 0.028
LAYERS = ("merge", "bridge")
#: The methods: (contact layer, drift scheme).
METHODS = {
    "merge": ("merge", "euler"),
    "bridge": ("bridge", "euler"),
    "bridge+lm": ("bridge", "lm"),
    "bridge+metropolis": ("bridge", "metropolis"),
}
#: The steps tried for part 2, largest first, down to below each method's step as measured (docs/physics-bcd-contact-layer.md:
#: merge's contact density is 0.979 of exact at 1e-6 and 0.995 at 3e-7; bridge's chi^2 per bin 2.34 at 3e-4, 0.98 at 1.5e-4).
CANDIDATES = {
    "merge": (3e-5, 1e-5, 2.5e-6, 1e-6, 3e-7),
    "bridge": (1e-3, 3e-4, 1.5e-4, 1e-4, 3e-5),
    "bridge+lm": (2e-3, 1e-3, 5e-4, 3e-4, 2e-4, 1.5e-4, 1e-4),
    "bridge+metropolis": (4e-3, 2e-3, 1e-3, 5e-4),
}
REACHES = ("merge", 3e-5)  # merge's largest step that reaches a 1 % profile (through its bias), issue 30
STUDY = 1.25  # sampled time units of the standard study
MAX_REJECTED = 0.5  # the Metropolis test's largest fraction of rejected steps at a step "within error"
TARGET_RATIO = 10.0  # issue 41: the time to a 1 % dense profile at least 10 times below merge's
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


def chi2_bound(replicas: int, bins: int) -> float:
    """The chi^2 per bin below which an exact profile stays within 3 standard deviations: each bin's term is t^2
    of Student's t with nu = replicas - 1 degrees of freedom (the bin's error estimated from the replicas), of mean
    nu / (nu - 2) and variance 3 nu^2 / ((nu - 2)(nu - 4)) - mean^2, averaged over the bins (taken as
    independent). 16 rings, 25 bins: 1.15 + 3 x 0.37 = 2.26."""
    nu = replicas - 1
    mean = nu / (nu - 2)
    variance = 3 * nu**2 / ((nu - 2) * (nu - 4)) - mean**2
    return mean + 3 * math.sqrt(variance / bins)


def within_error(figures: dict, bound: float) -> bool:
    """The rule of part 2: chi^2 per bin <= bound and the contact density within 3 errors of exact; with the
    Metropolis test also at most MAX_REJECTED of the steps rejected (beyond, the rings hardly move per time unit)."""
    ratio, error = figures["contact_ratio"], figures["contact_ratio_err"]
    moving = figures["rejected"] <= MAX_REJECTED
    return figures["chi2_per_dof"] <= bound and ratio is not None and abs(ratio - 1.0) <= 3.0 * error and moving


def largest_within_error(method: str, bound: float) -> tuple[float, bool]:
    """The method's first candidate within error (part 2), printing each tried; (its smallest candidate, False) if none."""
    layer, drift = METHODS[method]
    for k, dt in enumerate(CANDIDATES[method]):
        f = measure("0.7", dt, layer, STUDY, seed=11 + k, drift=drift)
        ok = within_error(f, bound)
        contact = "-" if f["contact_ratio"] is None else f"{f['contact_ratio']:.4f} ± {f['contact_ratio_err']:.4f}"
        rejected = f"{100 * f['rejected']:.0f} %"
        print(f"| {method} | {dt:g} | {f['chi2_per_dof']:.2f} | {contact} | {rejected} | {'yes' if ok else 'no'} |", flush=True)
        if ok:
            return dt, True
    return CANDIDATES[method][-1], False


def dense_config(method: str, dt: float, seed: int = 11):
    """The dense rings of parts 2-4 (bcd_timestep.case_config "0.7") for the method."""
    layer, drift = METHODS[method]
    return case_config("0.7", dt, layer, seed=seed, drift=drift)


def dense_cost(method: str, dt: float) -> float:
    """CPU seconds per step of the dense configuration at dt (median of REPEATS runs of 2000 steps, after 0.05
    time units at dt, so that the gaps near contact are those of the method at that step)."""
    simulation = RodSimulation(dense_config(method, dt))
    simulation.equilibrate(0.05)
    costs = []
    for _ in range(REPEATS):
        start = time.process_time()
        simulation.advance(2000)
        costs.append((time.process_time() - start) / 2000)
    return statistics.median(costs)


def time_to_one_percent(seed: int, method: str, dt: float, limit: float, chunk: float = 0.005) -> tuple[float, float, float]:
    """Sample in chunks of ``chunk`` time units until the L1 deviation of the running profile falls below 1 %;
    returns the sampled time units, the wall seconds (Monte Carlo start included) and the wall seconds after
    the start, or infinities if ``limit`` time units do not reach it."""
    config = dense_config(method, dt, seed)
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
    parser.add_argument("--limit", type=float, default=1.0, help="sampled time units before a run counts as not converged")
    args = parser.parse_args()
    print(f"numba threads: {numba.get_num_threads()}")
    if not args.quick:
        threads = numba.get_num_threads()
        numba.set_num_threads(1)
        for layer in LAYERS:
            cost_per_particle_step(layer)
        numba.set_num_threads(threads)

    sampling = dense_config("merge", 1e-5).sampling
    bound = chi2_bound(sampling.replicas, sampling.bins)
    print(f"\nwithin error: chi^2/bin <= {bound:.2f} and the contact density within 3 errors ({STUDY} time units, 16 rings)")
    print("| method | dt | chi2/bin | contact / exact | rejected | within error |")
    print("|---|---|---|---|---|---|", flush=True)
    chosen = {method: largest_within_error(method, bound) for method in METHODS}
    for method, (dt, ok) in chosen.items():
        print(f"{method}: {'largest step within error' if ok else 'none within error down to'} {dt:g}")
    within = ("merge", chosen["merge"][0])
    k = CANDIDATES["merge"].index(within[1])
    above = ("merge", CANDIDATES["merge"][k - 1]) if chosen["merge"][1] and k > 0 else within  # merge's next step up
    runs = list(dict.fromkeys([*((method, dt) for method, (dt, _) in chosen.items()), above, REACHES]))

    costs = {run: dense_cost(*run) for run in runs}
    print("\n| method | dt | CPU ms per step (N = 140, 16 replicas) | us per particle-step |")
    print("|---|---|---|---|")
    for (method, dt), cost in costs.items():
        print(f"| {method} | {dt:g} | {1e3 * cost:.3f} | {1e6 * cost / (140 * 16):.4f} |", flush=True)

    seeds = [int(s) for s in args.seeds.split(",")]
    times = {run: [] for run in runs}
    print()
    for seed in seeds:  # the runs alternate, so that all see the same load of a shared machine
        for run in runs:
            sampled, seconds, dynamics = time_to_one_percent(seed, *run, args.limit)
            times[run].append((sampled, seconds, dynamics))
            print(
                f"{run[0]}, dt = {run[1]:g}, seed {seed}: L1/rho < 1 % after {sampled:.3g} sampled time units, "
                f"{seconds:.2f} s wall ({dynamics:.2f} s after the Monte Carlo start)",
                flush=True,
            )
    medians = {run: [statistics.median(t[k] for t in samples) for k in range(3)] for run, samples in times.items()}
    results = {run: np.array([*medians[run][1:], (EQUILIBRATE + medians[run][0]) / run[1] * costs[run]]) for run in runs}
    print(f"\nmedians over seeds {args.seeds}")
    print("| method | dt | within error | sampled time to 1 % | wall s (MC start incl.) | wall s after start | computed s (cost x steps) |")
    print("|---|---|---|---|---|---|---|")
    for run in runs:
        status = "yes" if chosen[run[0]] == (run[1], True) else "no"
        print(f"| {run[0]} | {run[1]:g} | {status} | {medians[run][0]:.3g} | " + " | ".join(f"{t:.2f}" for t in results[run]) + " |")
    print("\nhow many times sooner each bridge method reaches 1 % than merge (merge's time / its)")
    print("| method | dt | merge dt | wall (MC start incl.) | wall after start | computed |")
    print("|---|---|---|---|---|---|")
    for run in (run for run in runs if run[0] != "merge"):
        for ref in (ref for ref in runs if ref[0] == "merge"):
            print(f"| {run[0]} | {run[1]:g} | {ref[1]:g} | " + " | ".join(f"{r:.1f}" for r in results[ref] / results[run]) + " |")
    # merge's largest step within error lies in [within, above): its time to 1 % between theirs (above == within: none
    # within error down to its smallest candidate, only the lower bound)
    where = f"in [{within[1]:g}, {above[1]:g})" if above != within else f"below {within[1]:g}"
    print(f"\nagainst merge's largest step within error ({where}), target >= {TARGET_RATIO:g}x (wall after start and computed):")
    for run in (run for run in runs if run[0] != "merge"):
        low, high = results[above] / results[run], results[within] / results[run]
        span = " / ".join(f"{lo:.1f}" + (f"-{hi:.1f}" if above != within else "+") for lo, hi in zip(low, high, strict=True))
        verdict = "met" if min(low[1:]) >= TARGET_RATIO else "not met"
        print(f"{run[0]} at {run[1]:g}: {span} times sooner (wall MC start incl. / after start / computed): {verdict}")


if __name__ == "__main__":
    main()
