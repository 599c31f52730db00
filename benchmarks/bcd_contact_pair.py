"""The contact layers on one pair, without sampling noise: the stationary law of the gap's Markov chain (issue 30).

The gap g of two rods (D = mu = kT = 1) moves per step by the Euler drift c(g) dt, c = 2 f(g) (each rod feels
the pair force f), plus a normal increment of variance v = 4 dt, and the layer restores g >= 0:
merge g' = max(z, 0), reflect g' = |z|, bridge g' = z - min(0, m) with m the bridge minimum (for a
constant drift: P(g' <= y) = Phi((y - g - c dt) / sqrt(v)) - exp(2 c dt y / v) Phi((-y - g - c dt) / sqrt(v))).
The chain's transition between cells (from two points of each cell) gives its stationary law by a
linear solve, compared with exp(-V(g)):

* sticky: the delta_eps pair (gamma = 1, p = 3, eps = 0.05, B-31) on [0, 1/2] (two rods on a ring of
  length 2 without field, folded at the symmetric point): the bonded fraction P(g < eps) / exact;
* hard, pushed: a constant force -10 on the gap (c = -20) on [0, 0.6], exact law 10 exp(-10 g) / (1 - exp(-6)):
  the probability of the first cell at contact (merge: the second, the first holds its atom) and the mean
  gap / those of the exact law on the same cells.

The order q is the slope of log |ratio - 1| between neighbouring steps.
Run: nice -n 10 python benchmarks/bcd_contact_pair.py (about a minute).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.stats import norm

GAMMA, P, EPS = 1.0, 3.0, 0.05
STEPS = (1e-4, 3e-5, 1e-5, 3e-6, 1e-6)
CELLS_PER_STEP = 24
PUSHED = 0.6  # the hard pair's domain: exact law 10 exp(-10 g) / (1 - exp(-6)) with the mirror


def sticky_force(g: np.ndarray) -> np.ndarray:
    """-dV/dg of the delta_eps pair, V = -ln(1 + A s^p), s = eps - g, A = gamma (p + 1) / eps^(p + 1)."""
    a, s = GAMMA * (P + 1) / EPS ** (P + 1), np.clip(EPS - g, 0.0, None)
    return -P * a * s ** (P - 1) / (1 + a * s**P)


def sticky_energy(g: np.ndarray) -> np.ndarray:
    a, s = GAMMA * (P + 1) / EPS ** (P + 1), np.clip(EPS - g, 0.0, None)
    return -np.log1p(a * s**P)


def stationary(layer: str, dt: float, force, size: float) -> tuple[np.ndarray, np.ndarray]:
    """Cell centres and the stationary probabilities of the layer's chain on [0, size] (mirrored at size),
    cells of sqrt(v) / CELLS_PER_STEP, each transition averaged over two start points in the cell."""
    spread = math.sqrt(4 * dt)
    cell = size / math.ceil(size * CELLS_PER_STEP / spread)
    edges = np.linspace(0.0, size, round(size / cell) + 1)
    g = 0.5 * (edges[1:] + edges[:-1])
    kernel = np.zeros((g.size, g.size))
    for start in (g - cell / 4, g + cell / 4):
        drift = (2 * force(start) * dt)[:, None]
        shift = start[:, None] + drift
        upper = edges[None, :]
        if layer == "merge":
            cdf = norm.cdf((upper - shift) / spread)
            cdf[:, 0] = 0.0  # the atom at g = 0 goes to the first cell
        elif layer == "reflect":
            cdf = norm.cdf((upper - shift) / spread) - norm.cdf((-upper - shift) / spread)
        else:
            with np.errstate(over="ignore", invalid="ignore"):
                image = np.exp(np.clip(2 * drift * upper / spread**2, None, 700.0)) * norm.cdf((-upper - shift) / spread)
            cdf = norm.cdf((upper - shift) / spread) - np.nan_to_num(image)
        kernel += np.diff(cdf, axis=1)
        kernel += norm.cdf((2 * size - edges[None, :-1] - shift) / spread) - norm.cdf((2 * size - edges[None, 1:] - shift) / spread)
    kernel /= kernel.sum(1, keepdims=True)
    system = kernel.T - np.eye(g.size)
    system[-1] = 1.0
    right = np.zeros(g.size)
    right[-1] = 1.0
    return g, np.linalg.solve(system, right)


def order(rows: list[tuple[float, float]]) -> list[str]:
    out = ["-"]
    for (dt0, r0), (dt1, r1) in zip(rows, rows[1:]):
        out.append(f"{math.log(abs(r0 - 1) / abs(r1 - 1)) / math.log(dt0 / dt1):.2f}" if r0 != 1 and r1 != 1 else "-")
    return out


def main() -> None:
    grid = np.arange(0, 0.5, 1e-6) + 0.5e-6
    weight = np.exp(-sticky_energy(grid) - sticky_energy(1.0 - grid))
    exact = weight[grid < EPS].sum() / weight.sum()
    print(f"sticky pair (gamma = {GAMMA:g}, p = {P:g}, eps = {EPS:g}), bonded fraction / exact ({exact:.4f})")
    print("| layer | " + " | ".join(f"dt = {dt:g}" for dt in STEPS) + " | order between neighbours |")
    print("|---|" + "---|" * (len(STEPS) + 1))
    for layer in ("merge", "reflect", "bridge"):
        rows = []
        for dt in STEPS:
            g, pi = stationary(layer, dt, lambda x: sticky_force(x) - sticky_force(1.0 - x), 0.5)
            rows.append((dt, pi[g < EPS].sum() / exact))
        print(f"| {layer} | " + " | ".join(f"{r:.4f}" for _, r in rows) + " | " + ", ".join(order(rows)[1:]) + " |", flush=True)
    print("\nhard pair pushed together by a constant force (c = -20): density at contact / exact, mean gap / exact")
    print("| layer | " + " | ".join(f"dt = {dt:g}" for dt in STEPS) + " |")
    print("|---|" + "---|" * len(STEPS))
    for layer in ("merge", "reflect", "bridge"):
        cells = []
        for dt in STEPS:
            g, pi = stationary(layer, dt, lambda x: np.full_like(x, -10.0), PUSHED)
            half = 0.5 * (g[1] - g[0])
            exact = np.exp(-10 * (g - half)) - np.exp(-10 * (g + half))  # the exact law's cell probabilities
            exact /= exact.sum()
            k = 1 if layer == "merge" else 0  # merge: the first cell holds the atom
            cells.append(f"{pi[k] / exact[k]:.4f}, {np.sum(g * pi) / np.sum(g * exact):.4f}")
        print(f"| {layer} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
