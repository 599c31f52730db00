"""How large may the BCD time step be? (issue 5)

Hard rods, U0 = 6, lambda = 1, sigma = 0.5, L = 100, 16 replicas started from Monte Carlo
equilibrium, 0.25 time units of BCD at each dt, then sampled for T time units: L1 / rho_bar and chi^2 per bin of the profile
and the contact density ratio against the exact theory, and the Richardson extrapolation in
sqrt(dt) from the two smallest steps. BCD's bias is O(sqrt(dt)) (see fricgen.rods). The speed
figures (CPU per particle-step, wall time to a 1 % profile) are in benchmarks/bcd.py.
Run: python benchmarks/bcd_timestep.py [T]
"""

from __future__ import annotations

import sys
import time

from fricgen.rods import RodSimulation, deviations, exact_profile, extrapolate_to_zero_dt, rod_config

STEPS = (1e-4, 4e-5, 1e-5, 2.5e-6)


def study(n: int, duration: float) -> None:
    profiles = []
    for dt in STEPS:
        config = rod_config(n=n, length=100.0, sigma=0.5, dt=dt, replicas=16, bins=25, seed=11)
        simulation = RodSimulation(config)
        simulation.equilibrate(0.25)
        start = time.perf_counter()
        profiles.append(simulation.run(round(duration / dt)))
        seconds = time.perf_counter() - start
        report(f"rho_bar sigma = {n * 0.005:.2f}, dt = {dt:.1e}", deviations(profiles[-1], exact_profile(config)), seconds)
    extrapolated = extrapolate_to_zero_dt(profiles[-2], profiles[-1], STEPS[-2] / STEPS[-1])
    report(f"rho_bar sigma = {n * 0.005:.2f}, extrapolated", deviations(extrapolated, exact_profile(config)), 0.0)


def report(label: str, figures: dict[str, float], seconds: float) -> None:
    print(
        f"{label:40s} L1/rho {figures['l1_dev_over_rho']:.4f}  chi2/bin {figures['chi2_per_dof']:6.2f}  "
        f"contact ratio {figures['contact_ratio']:.3f} (chi2/bin {figures['contact_chi2_per_dof']:6.1f})  {seconds:6.1f} s",
        flush=True,
    )


if __name__ == "__main__":
    duration = float(sys.argv[1]) if len(sys.argv) > 1 else 1.25
    for n in (40, 140):
        study(n, duration)
