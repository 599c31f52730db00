"""Benchmark of the Langevin engine (issue 4 targets), with LAMMPS side by side when available.

2-D, N = 10 000, area fraction 0.6, WCA + solvent on translation and rotation (gamma = 3 pi,
gamma_R = pi) + Coulomb–Newton friction with its noise, dt = 1e-3. Prints particle-steps per
second on 1 and 2 threads for the pairwise contact step and the explicit kick side by side, the
cost split (neighbour list, pairs without friction, friction, noise, the pairwise step), and, if a
LAMMPS binary is found (env FRICGEN_LAMMPS, or `lmp` on PATH), the peer's systems A (WCA +
Langevin) and B1 (A + deterministic granular friction) run alternately with fricgen in the same
run, and the ratios. Medians over repeats. Run: python benchmarks/langevin.py
"""

from __future__ import annotations

import os
import re
import shutil
import statistics
import subprocess
import time
from pathlib import Path

import numba

from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state
from fricgen.langevin.config import CONTACT_SCHEMES
from fricgen.langevin.neighbors import build_neighbors

N, STEPS, REPEATS = 10_000, 1000, 3
PEERS = Path(__file__).resolve().parents[2] / "shared" / "peers" / "lammps"


def rate(threads: int, **law) -> tuple[float, Simulation]:
    """Particle-steps per second (median of the repeats); ``law`` switches of the contact (friction, contact_noise, contact_scheme)."""
    numba.set_num_threads(threads)
    particles = Particles.spheres(N)
    config = LangevinConfig(law=Law("coulomb_newton", **law), thermostat=Thermostat(dt=1e-3))
    simulation = Simulation(config, particles, lattice_state(particles, 2, 0.6))
    simulation.advance(200)
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        simulation.advance(STEPS)
        times.append(time.perf_counter() - start)
    return N * STEPS / statistics.median(times), simulation


def lammps_binary() -> list[str] | None:
    explicit = os.environ.get("FRICGEN_LAMMPS") or shutil.which("lmp")
    return [explicit] if explicit else None


def lammps_rate(binary: list[str], script: str) -> float:
    done = subprocess.run(
        [*binary, "-in", str(PEERS / script), "-var", "seed", "1000", "-var", "nrun", "2000", "-log", "none"],
        capture_output=True,
        text=True,
        check=True,
        cwd=PEERS,
    )
    loop = re.findall(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", done.stdout)[-1]
    return int(loop[2]) * int(loop[1]) / float(loop[0])


def main() -> None:
    for threads in (1, 2):
        rates = {scheme: rate(threads, contact_scheme=scheme)[0] for scheme in CONTACT_SCHEMES}
        print(
            f"fricgen, {threads} thread(s), WCA + solvent + Coulomb-Newton friction + noise: "
            + ", ".join(f"{scheme} {value / 1e6:.2f}" for scheme, value in rates.items())
            + f" M particle-steps/s (the pairwise step costs {rates['explicit'] / rates['pairwise']:.2f}x the explicit one per step)"
        )
    numba.set_num_threads(2)
    plain, simulation = rate(2, friction=False)
    no_noise, _ = rate(2, contact_noise=False, contact_scheme="explicit")
    full, _ = rate(2, contact_scheme="explicit")
    pairwise, _ = rate(2)
    s = simulation.state
    start = time.perf_counter()
    for _ in range(10):
        build_neighbors(s.position, s.box, 2, 2 ** (1 / 6) + 0.3)
    build = (time.perf_counter() - start) / 10
    per_step = {name: N / r for name, r in (("plain", plain), ("no_noise", no_noise), ("full", full), ("pairwise", pairwise))}
    builds_per_step = simulation.neighbor_builds / (200 + REPEATS * STEPS)
    print("cost split per step on 2 threads (ms):")
    print(f"  neighbour list   {1e3 * build * builds_per_step:7.3f}  ({builds_per_step:.3f} builds per step, {1e3 * build:.2f} ms each)")
    print(f"  WCA + solvent    {1e3 * per_step['plain']:7.3f}  (all of the frictionless step, neighbour list included)")
    print(f"  friction         {1e3 * (per_step['no_noise'] - per_step['plain']):7.3f}  (explicit kick)")
    print(f"  contact noise    {1e3 * (per_step['full'] - per_step['no_noise']):7.3f}  (explicit kick)")
    print(f"  pairwise step    {1e3 * (per_step['pairwise'] - per_step['plain']):7.3f}  (friction and noise, Metropolis-adjusted)")
    binary = lammps_binary()
    if binary is None:
        print("LAMMPS not found (set FRICGEN_LAMMPS to the lmp binary, see shared/peers/README.md): no ratios")
        return
    ratios_a, ratios_b = [], []
    for _ in range(3):  # alternate: the machine's drift hits both
        peer_a = lammps_rate(binary, "in.A_2d_wca_langevin")
        ours, _ = rate(2)
        peer_b = lammps_rate(binary, "in.B1_2d_wca_granhooke")
        ratios_a.append(ours / peer_a)
        ratios_b.append(ours / peer_b)
        print(f"  LAMMPS A {peer_a / 1e6:.2f} M, B1 {peer_b / 1e6:.2f} M, fricgen (friction + noise, 2 threads) {ours / 1e6:.2f} M")
    print(
        f"ratio fricgen / LAMMPS A (frictionless): {statistics.median(ratios_a):.2f}; "
        f"fricgen / LAMMPS B1 (friction, no noise): {statistics.median(ratios_b):.2f}"
    )


if __name__ == "__main__":
    main()
