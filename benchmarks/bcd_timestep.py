"""How large may the BCD time step be, per contact layer? (issues 5 and 30)

Rods in U = (U0/2) cos(2 pi x), U0 = 6, lambda = 1, sigma = 0.5, L = 100; 16 replicas (--replicas) started
from Monte Carlo equilibrium, 0.25 time units at dt, then sampled; the k-th step of --steps uses seed 11 + k
(--seed), so that the runs at different dt are independent (the slow modes of one start, the wells'
occupation and the ring's long density waves, would otherwise be shared by every dt). Cases: hard rods at rho_bar sigma = 0.2, 0.5, 0.7
(T = 1.25 sampled), and sticky rods gamma = 1, p = 3, eps = 0.05 at rho_bar sigma = 0.25 (T = 3). Per
layer and dt: L1 / rho_bar and chi^2 per bin of the profile, the contact density ratio (hard rods) with
its chi^2 per bin, and the well contrast c - 1 with its error: c is the profile's projection on the exact
one's deviation from rho_bar, sum (rho - rho_bar)(rho_ex - rho_bar) / sum (rho_ex - rho_bar)^2, one value
per replica (1 when exact; below 1 for rods that look shorter or, sticky, over-bound across barriers).
Then the fitted order q of |bias| = C dt^q, for the bias c - 1 and (hard rods) the contact ratio - 1,
over the steps where the bias exceeds 3 of its errors, and of c - 1 = C dt^q over every step (weighted
least squares). The contact ratio's error is that of the sum over bins, from their covariance between
replicas (RodProfiles.contact_cov).

Run: nice -n 10 python benchmarks/bcd_timestep.py [--layers merge,bridge] [--steps 1e-3,...] [--cases 0.2,0.5,0.7,sticky] [--time T]
[--replicas R] [--seed S] [--drifts euler,lm,metropolis] (lm: the Leimkuhler-Matthews midpoint; metropolis: the Metropolis
test of each step, the fraction of steps it rejected in the column "rejected"; docs/physics-bcd-field-drift.md)
(the full table: minutes per layer and case on two cores; dt = 1e-6 dominates).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from scipy.optimize import curve_fit

from fricgen.rods import RodSimulation, deviations, exact_profile, rod_config
from fricgen.rods.simulation import RodProfiles

STEPS = (1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6)
STICKY = {"gamma": 1.0, "p": 3.0, "eps": 0.05}


def case_config(case: str, dt: float, layer: str, replicas: int = 16, seed: int = 11, drift: str = "euler"):
    """The configuration of a case ("0.2", "0.5", "0.7": hard rods at that rho_bar sigma; "sticky")."""
    model = {"n": 50, **STICKY} if case == "sticky" else {"n": round(float(case) * 200)}
    numerics = {"dt": dt, "seed": seed, "contact_layer": layer, "drift_scheme": drift}
    config = rod_config(**model, **numerics, length=100.0, sigma=0.5, replicas=replicas, bins=25, gap_bins=40)
    return config.replace(gap_bins=max(40, config.contact_fit_bins()))


def measure(case: str, dt: float, layer: str, duration: float, replicas: int = 16, seed: int = 11, drift: str = "euler") -> dict:
    """One run: the deviations from the exact profile and the well contrast (mean and error over replicas)."""
    config = case_config(case, dt, layer, replicas, seed, drift)
    simulation = RodSimulation(config)
    simulation.equilibrate(0.25)
    c, steps = config.sampling, round(duration / dt)
    rods, gaps = np.zeros((c.replicas, c.bins)), np.zeros((c.replicas, c.bins, c.gap_bins))
    start = time.perf_counter()
    simulation.advance(steps, (rods, gaps))
    seconds = time.perf_counter() - start
    scale = steps * config.model.length / c.bins  # sampled length per bin (lambda = 1)
    rho = rods / scale
    contact, covariance = simulation._contact(gaps / (scale * c.gap_width))
    x, rho_err = (np.arange(c.bins) + 0.5) / c.bins, rho.std(0, ddof=1) / math.sqrt(c.replicas)
    profiles = RodProfiles(x, rho.mean(0), rho_err, contact, np.sqrt(np.diagonal(covariance)), steps, covariance)
    exact = exact_profile(config)
    figures = deviations(profiles, exact, contact=case != "sticky")
    shape = exact.bin_means(c.bins) - config.model.mean_density
    contrast = (rho - config.model.mean_density) @ shape / (shape @ shape)
    figures.update(contrast=contrast.mean() - 1, contrast_err=contrast.std(ddof=1) / math.sqrt(c.replicas), seconds=seconds)
    figures.update(rejected=simulation.rejection)
    return figures


def order(points: list[tuple[float, float, float]]) -> str:
    """The slope q of log |bias| against log dt over the points (dt, bias, error) with |bias| > 3 errors, weighted
    by the errors of log |bias| (error / |bias|), with its error from them (for two points: exact through both)."""
    resolved = [(dt, abs(bias), error / abs(bias)) for dt, bias, error in points if bias is not None and abs(bias) > 3 * error]
    if len(resolved) < 2:
        return f"not fitted ({len(resolved)} step(s) with a resolved bias)"
    x, y, s = (np.log([p[0] for p in resolved]), np.log([p[1] for p in resolved]), np.array([p[2] for p in resolved]))
    design = np.stack([x, np.ones_like(x)], axis=1) / s[:, None]
    covariance = np.linalg.inv(design.T @ design)
    slope = (covariance @ design.T @ (y / s))[0]
    span = f"dt = {min(p[0] for p in resolved):g} .. {max(p[0] for p in resolved):g} ({len(resolved)} steps)"
    return f"q = {slope:.2f} ± {math.sqrt(covariance[0, 0]):.2f} over {span}"


def power_law(points: list[tuple[float, float, float]]) -> str:
    """bias = C dt^q fitted to every point (dt, bias, error), resolved or not, by weighted least squares
    (errors taken as independent: each dt has its own seed), with the errors of q and C and the fit's
    chi^2 per degree of freedom."""
    dt, bias, error = (np.array(column, dtype=float) for column in zip(*points))
    if dt.size < 3:
        return "not fitted (fewer than 3 steps)"
    guess = (bias[np.argmax(dt)] / dt.max(), 1.0)
    (scale, q), covariance = curve_fit(lambda t, c, p: c * t**p, dt, bias, p0=guess, sigma=error, absolute_sigma=True, maxfev=20000)
    chi2 = float(np.sum(((bias - scale * dt**q) / error) ** 2)) / (dt.size - 2)
    errors = np.sqrt(np.diagonal(covariance))
    return f"q = {q:.2f} ± {errors[1]:.2f}, C = {scale:.3g} ± {errors[0]:.2g} over all {dt.size} steps (chi2/dof {chi2:.2f})"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--layers", default="merge,bridge")
    parser.add_argument("--steps", default=",".join(f"{dt:g}" for dt in STEPS))
    parser.add_argument("--cases", default="0.2,0.5,0.7,sticky")
    parser.add_argument("--drifts", default="euler", help="the field's drift schemes (euler; lm, metropolis: bridge layer only)")
    parser.add_argument("--time", type=float, default=None, help="sampled time (default 1.25 hard, 3 sticky)")
    parser.add_argument("--replicas", type=int, default=16, help="rings per run")
    parser.add_argument("--seed", type=int, default=11, help="the seed of the first step; the k-th step uses seed + k")
    args = parser.parse_args()
    steps = [float(value) for value in args.steps.split(",")]
    print("| case | layer | dt | L1/rho | chi2/bin | contact / exact | contact chi2/bin | c - 1 | rejected | s |")
    print("|---|---|---|---|---|---|---|---|---|---|", flush=True)
    fits = []
    for case in args.cases.split(","):
        duration = args.time or (3.0 if case == "sticky" else 1.25)
        layers, drifts = args.layers.split(","), args.drifts.split(",")
        for layer, drift in [(layer, drift) for layer in layers for drift in drifts if layer == "bridge" or drift == "euler"]:
            points, contacts = [], []
            label = layer if drift == "euler" else f"{layer}/{drift}"
            for k, dt in enumerate(steps):
                f = measure(case, dt, layer, duration, args.replicas, args.seed + k, drift)
                ratio = "-" if f.get("contact_ratio") is None else f"{f['contact_ratio']:.4f} ± {f['contact_ratio_err']:.4f}"
                chi2 = "-" if f.get("contact_chi2_per_dof") is None else f"{f['contact_chi2_per_dof']:.2f}"
                print(
                    f"| {case} | {label} | {dt:g} | {100 * f['l1_dev_over_rho']:.2f} % | {f['chi2_per_dof']:.2f} | {ratio} | {chi2} | "
                    f"{f['contrast']:+.4f} ± {f['contrast_err']:.4f} | {100 * f['rejected']:.1f} % | {f['seconds']:.0f} |",
                    flush=True,
                )
                points.append((dt, f["contrast"], f["contrast_err"]))
                if f.get("contact_ratio") is not None:
                    contacts.append((dt, f["contact_ratio"] - 1, f["contact_ratio_err"]))
            fits.append(f"{case}, {label}: c - 1: {order(points)}" + (f"; contact ratio - 1: {order(contacts)}" if contacts else ""))
            fits.append(f"{case}, {label}: c - 1 = C dt^q: {power_law(points)}")
    print("\nfitted order of |bias|:")
    print("\n".join(fits))


if __name__ == "__main__":
    main()
