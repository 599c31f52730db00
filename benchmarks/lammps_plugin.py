"""Benchmark of the LAMMPS plugin fricgen/coulomb_newton against LAMMPS without friction and against
fricgen's own engine, on the same cores, measured alternately in one run.

System (the paper's, and the peers' system A): 2-D, N = 10 000 discs, area fraction 0.6, WCA + the
solvent (fix langevin, gamma = 3 pi, omega yes), dt = 1e-3, kT = 1; the plugin adds Coulomb–Newton
friction (gamma_f = 6, kappa_f = 5) with its Itô noise. Rates are particle-steps per second of the
timed run (after a 500-step warm-up, from LAMMPS's "Loop time"), medians over the repeats:

- LAMMPS A: pair_style lj/cut (WCA) + fix langevin, the peers' in.A_2d_wca_langevin;
- plugin:   generated/lammps/coulomb_newton/in.coulomb_newton_2d (the same system plus the contact);
- fricgen:  the engine's passive run of the same system (its default pairwise contact step).

LAMMPS runs under `mpirun -np 1` and `-np 2` (OMP_NUM_THREADS=1), fricgen on 1 and 2 Numba threads
(2 only if NUMBA_NUM_THREADS allows). Printed: each rate, the plugin's cost over frictionless LAMMPS,
its strong scaling 1 -> 2 ranks, and the plugin against fricgen's engine. LAMMPS and the plugin are
found and built as `fricgen lammps coulomb_newton --build` does (fricgen.app.cli.lammps).

Run: python benchmarks/lammps_plugin.py [--repeats 3] [--steps 1000]
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numba

from fricgen.app.cli.lammps import Lammps, build_plugin, locate_lammps, plugin_folder
from fricgen.derive.law.catalogues import BUILT_IN
from fricgen.kernels import load_law_kernels
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state

N = 10_000
PEERS = Path(__file__).resolve().parents[2] / "shared" / "peers" / "lammps"
LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")


def built_plugin(law: str = "coulomb_newton") -> tuple[Lammps, Path, Path]:
    """(LAMMPS, the plugin's folder, the built .so) of a built-in law, found and built as `fricgen lammps LAW --build` does."""
    lammps, law_file = locate_lammps(), BUILT_IN.find(law)
    folder = plugin_folder(law_file)
    return lammps, folder, build_plugin(folder, lammps, law_file)


def plugin_input(folder: Path) -> str:
    """The 2-D template with a 500-step warm-up before the timed run (as the peers' inputs)."""
    template = (plugin_folder(BUILT_IN.find("coulomb_newton")) / "in.coulomb_newton_2d").read_text()
    (folder / "in.plugin").write_text(template.replace("run             ${nrun}", "run             500\nrun             ${nrun}"))
    return str(folder / "in.plugin")


def lammps_output(lammps, script: str, ranks: int, steps: int, extra: list[str], cwd: Path, seed: int = 1000) -> str:
    """The screen output of LAMMPS running ``script`` (``seed``, nrun ``steps``, the variables of ``extra``) on ``ranks`` ranks."""
    command = [*lammps.command(ranks), "-in", script, "-var", "seed", str(seed), "-var", "nrun", str(steps)]
    command += ["-log", "none", "-nocite", *extra]
    done = subprocess.run(command, capture_output=True, text=True, env=lammps.environment(), cwd=cwd)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{(done.stdout + done.stderr)[-2000:]}")
    return done.stdout


def loop_rate(output: str) -> float:
    """Particle-steps per second of the last run of a LAMMPS output (its "Loop time" line)."""
    seconds, _, count, atoms = LOOP.findall(output)[-1]
    return int(atoms) * int(count) / float(seconds)


def lammps_rate(lammps, script: str, ranks: int, steps: int, extra: list[str], cwd: Path) -> float:
    """Particle-steps per second of the last run of ``script`` (:func:`lammps_output`)."""
    return loop_rate(lammps_output(lammps, script, ranks, steps, extra, cwd))


PAPER = Thermostat(dt=1e-3)  # the paper's solvent


def engine(threads: int, thermostat: Thermostat = PAPER) -> Simulation:
    """fricgen's engine on the system of the module docstring (``thermostat``: the solvent and dt) on ``threads``
    Numba threads (fixed: not the engine's own choice), after 200 steps."""
    numba.set_num_threads(threads)
    particles = Particles.spheres(N)
    config = LangevinConfig(law=Law("coulomb_newton"), thermostat=thermostat)
    simulation = Simulation(config, particles, lattice_state(particles, 2, 0.6), load_law_kernels(config.law.name))
    simulation.threads = threads
    simulation.advance(200)
    return simulation


def engine_rate(simulation: Simulation, threads: int, steps: int) -> float:
    numba.set_num_threads(threads)
    start = time.perf_counter()
    simulation.advance(steps)
    return N * steps / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=1000, help="timed steps per measurement")
    options = parser.parse_args()
    lammps, _, plugin = built_plugin()
    work = Path(tempfile.mkdtemp(prefix="fricgen-bench-"))
    scripts = {"LAMMPS A": (str(PEERS / "in.A_2d_wca_langevin"), []), "plugin": (plugin_input(work), ["-var", "plugin", str(plugin)])}
    threads = [t for t in (1, 2) if t <= numba.config.NUMBA_NUM_THREADS]
    simulations = {t: engine(t) for t in threads}
    rates: dict[tuple[str, int], list[float]] = {}
    for _ in range(options.repeats):
        for ranks in (1, 2):
            for name, (script, extra) in scripts.items():
                rates.setdefault((name, ranks), []).append(lammps_rate(lammps, script, ranks, options.steps, extra, work))
        for t in threads:
            rates.setdefault(("fricgen", t), []).append(engine_rate(simulations[t], t, options.steps))
    median = {key: statistics.median(values) for key, values in rates.items()}
    print(f"2-D, N = {N}, dt = 1e-3, {options.steps} timed steps, medians of {options.repeats} alternating repeats (M particle-steps/s):")
    for (name, cores), values in sorted(rates.items()):
        unit = "threads" if name == "fricgen" else "ranks"
        spread = ", ".join(f"{v / 1e6:.2f}" for v in values)
        print(f"  {name:9s} {cores} {unit:7s}  {median[name, cores] / 1e6:6.2f}   ({spread})")
    ratio = {key: median["plugin", key[1]] / value for key, value in median.items() if key[0] != "plugin"}
    for ranks in (1, 2):
        print(f"plugin / LAMMPS A (frictionless), {ranks} rank(s): {ratio['LAMMPS A', ranks]:.2f}")
        if ("fricgen", ranks) in ratio:
            print(f"plugin ({ranks} rank(s)) / fricgen engine ({ranks} thread(s)): {ratio['fricgen', ranks]:.2f}")
    scaling = {name: median[name, 2] / median[name, 1] for name in scripts}
    print(f"strong scaling 1 -> 2 ranks: plugin {scaling['plugin']:.2f}x, LAMMPS A {scaling['LAMMPS A']:.2f}x")


if __name__ == "__main__":
    main()
