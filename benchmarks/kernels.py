"""Benchmark of the generated kernels (issue 3 targets).

1. Cost per call of the generated Coulomb–Newton noise kernel (Itô) vs a hand-written Numba
   function of the same formula, called from the same compiled loop (target ratio <= 1.1).
2. Time to regenerate the whole catalogue (derive + verify + emit) in a fresh process.
3. First-call latency of a kernel in a fresh process with a warm Numba cache (target < 1 s).
Medians over repeats; run: python benchmarks/kernels.py
"""

from __future__ import annotations

import math
import statistics
import subprocess
import sys
import tempfile
import time

import numba
import numpy as np

from fricgen.generated.special import erfcx
from fricgen.kernels import load_law_kernels

SQRT_PI = math.sqrt(math.pi)


@numba.njit
def hand_coulomb_newton_ito(u, w, r, mu, kT, params):
    """(F-33) written by hand, with the same erfcx."""
    gamma, kappa = params[0], params[1]
    s = math.sqrt(2.0 * kT * mu)
    c = kappa * w / gamma
    if u < c:
        x = (u * u - c * c) / (s * s)
        return -gamma * math.expm1(x) + kappa * w * SQRT_PI / s * math.exp(x) * erfcx(c / s)
    return kappa * w * SQRT_PI / s * erfcx(u / s)


@numba.njit
def drive(kernel, us, ws, params):
    total = 0.0
    for j in range(us.size):
        total += kernel(us[j], ws[j], 1.0, 7.0, 1.0, params)
    return total


def per_call(kernel, us, ws, params, repeats=9):
    drive(kernel, us[:10], ws[:10], params)  # compile
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        drive(kernel, us, ws, params)
        times.append((time.perf_counter() - t) / us.size)
    return statistics.median(times)


def fresh_process(code: str) -> float:
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return float(done.stdout.strip().splitlines()[-1])


def main() -> None:
    kernels = load_law_kernels("coulomb_newton")
    params = kernels.parameters()
    rng = np.random.default_rng(1)
    distances = rng.uniform(0.9, 1.12, 1_000_000)
    ws = np.array([kernels.weight(x, params) for x in distances[:1000]])
    ws = np.resize(ws, distances.size)
    us = np.abs(rng.normal(0.0, math.sqrt(7.0), distances.size)) * rng.choice([1.0, 10.0], distances.size)
    generated = kernels.noise_amplitude("ito")
    assert np.allclose(
        [generated(u, w, 1.0, 7.0, 1.0, params) for u, w in zip(us[:1000], ws[:1000])],
        [hand_coulomb_newton_ito(u, w, 1.0, 7.0, 1.0, params) for u, w in zip(us[:1000], ws[:1000])],
        rtol=1e-13,
    )
    ratios, gen_ns, hand_ns = [], [], []
    for _ in range(5):  # alternate to share the machine's noise
        g, h = per_call(generated, us, ws, params), per_call(hand_coulomb_newton_ito, us, ws, params)
        gen_ns.append(g * 1e9)
        hand_ns.append(h * 1e9)
        ratios.append(g / h)
    print(
        f"coulomb_newton ito noise kernel: generated {statistics.median(gen_ns):.2f} ns/call, "
        f"hand-written {statistics.median(hand_ns):.2f} ns/call, ratio {statistics.median(ratios):.3f} (target <= 1.1)"
    )

    with tempfile.TemporaryDirectory() as out:
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "fricgen", "generate", "--output", out], check=True, capture_output=True)
        print(f"regenerate the whole catalogue (derive + verify + emit, fresh process): {time.perf_counter() - t:.1f} s")

    code = (
        "import time; t = time.perf_counter()\n"
        "from fricgen.kernels import load_law_kernels\n"
        "k = load_law_kernels('coulomb_newton'); k.contact('ito')(1.0, 1.0, 1.0, 7.0, 1.0, k.parameters())\n"
        "print(time.perf_counter() - t)"
    )
    fresh_process(code)  # warms the cache if needed
    latencies = [fresh_process(code) for _ in range(5)]
    print(f"first call in a fresh process, warm cache (import + load + call): median {statistics.median(latencies):.3f} s (target < 1 s)")


if __name__ == "__main__":
    main()
