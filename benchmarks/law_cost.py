"""What a friction law costs per step: every catalogue law and two laws of a user's folder, against
Coulomb–Newton, in fricgen's engine and in the LAMMPS plugin, measured alternately in one run.

System (as benchmarks/langevin.py, smaller): 2-D, N = 4096 discs at area fraction 0.6, WCA + the solvent,
dt = 1e-3, kT = 1, each law with its defaults and its Itô noise; the engine on one thread with its
pairwise contact step, each simulation equilibrated EQUILIBRATE steps from the lattice before it is timed;
the plugin (generated/lammps/<law>/in.<law>_2d at 64 x 64 cells, `mpirun -np 1`) after a 500-step
warm-up. Costs are CPU time (the engine's process time on its one thread; LAMMPS's loop time times the
CPU share it reports), so a busy machine slows them less than wall time. The user's folder (a temporary one) holds a Stribeck law and the
sublinear law w gamma_f u / (1 + (u/u_c)^2)^(1/4), generated there with `fricgen generate --laws DIR`.

How each law's D is evaluated is printed beside it: a closed form, or the noise tables of an
integral-form D (fricgen.derive.backends.tables: built at the simulation's start, lazily in the plugin).
For the tabulated laws the engine is also timed on the quadrature alone (the parameters without the
tables), as every integral-form law ran before the tables.

Printed: CPU ns per particle-step (medians of the repeats) and the ratio to Coulomb–Newton of the same
program, engine and plugin. Run: python benchmarks/law_cost.py [--repeats 3] [--steps 300] [--no-lammps]
"""

from __future__ import annotations

import argparse
import math
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba

import fricgen
from fricgen.derive.driver import generate
from fricgen.derive.law.lawdata import CATALOGUE
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state
from fricgen.langevin.records import Couplings

N, CELLS, EQUILIBRATE = 4096, 64, 1000
LOOP = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
CPU = re.compile(r"([0-9.]+)% CPU use with")
USER_LAWS = {
    "user_stribeck": """name = "user_stribeck"
description = "Stribeck friction (a user's copy): static kappa_s falling to dynamic kappa_d above u_s."
friction = "w*(kappa_d + (kappa_s - kappa_d)*exp(-u/u_s))"
weight = "wca"
calculi = ["ito", "stratonovich"]

[parameters.kappa_s]
default = 6.0

[parameters.kappa_d]
default = 5.0

[parameters.u_s]
default = 0.5
""",
    "sublinear": """name = "sublinear"
description = "Viscous at small speeds, growing like sqrt(u) above u_c (a user's smooth law without a closed-form D)."
friction = "w*gamma_f*u/(1 + (u/u_c)**2)**(1/4)"
weight = "wca"
calculi = ["ito", "stratonovich", "hk"]

[parameters.gamma_f]
default = 6.0

[parameters.u_c]
default = 0.5
""",
}


def simulation(name: str, folder: Path | None) -> Simulation:
    """The law's passive 2-D fluid on one thread, equilibrated."""
    particles = Particles.spheres(N)
    config = LangevinConfig(law=Law(name), thermostat=Thermostat(dt=1e-3))
    law = fricgen.load_law(name, folder=folder) if folder else None
    sim = Simulation(config, particles, lattice_state(particles, 2, 0.6), law=law)
    sim.threads = 1
    sim.advance(EQUILIBRATE)
    return sim


def without_tables(sim: Simulation) -> Simulation:
    """The same simulation (a copy of its state) with the law's parameters alone: D by quadrature."""
    copy = Simulation.__new__(Simulation)
    copy.__dict__.update(sim.__dict__)
    copy.state = sim.state.copy()
    size = len(sim.kernels.parameter_names)
    copy.couplings = Couplings(sim.couplings.potential, sim.couplings.law[:size].copy(), sim.couplings.has_weight)
    return copy


def engine_cost(sim: Simulation, steps: int) -> float:
    """CPU seconds per particle-step of ``steps`` steps (one thread: the process's CPU time)."""
    start = time.process_time()
    sim.advance(steps)
    return (time.process_time() - start) / (N * steps)


def evaluation(sim: Simulation) -> str:
    """How the simulation's law evaluates D in its calculus."""
    module, calculus = sim.kernels.module, sim.config.law.calculus
    if module.CLOSED_FORM[calculus]:
        return "closed form"
    return "noise tables" if sim.couplings.law.size > len(sim.kernels.parameter_names) else "quadrature"


def plugin(name: str, folder: Path | None) -> tuple[Path, Path]:
    """(the built .so, the plugin's sources) of the law, written and built by `fricgen lammps LAW --build` (a build
    in the user's cache, reused while the sources and LAMMPS are unchanged)."""
    laws = ["--laws", str(folder)] if folder else []
    command = [sys.executable, "-m", "fricgen", "lammps", name, *laws, "--build"]
    done = subprocess.run(command, capture_output=True, text=True)
    built = re.findall(r"^built\s+(\S+\.so)$", done.stdout, re.MULTILINE)
    if done.returncode != 0 or not built:
        raise RuntimeError(f"{' '.join(command)} failed:\n{(done.stdout + done.stderr)[-2000:]}")
    sources = (folder / "generated" if folder else Path(fricgen.__file__).resolve().parents[1] / "generated") / "lammps" / name
    return Path(built[-1]), sources


def plugin_cost(lammps, library: Path, sources: Path, name: str, steps: int, work: Path) -> float:
    """CPU seconds per particle-step of the plugin's 2-D input at N = CELLS^2, after a 500-step warm-up: the
    loop time times the CPU share that LAMMPS reports for it; NaN if the run fails (atoms lost: the explicit
    first-order step of a stiff law at dt = 1e-3)."""
    script = (sources / f"in.{name}_2d").read_text().replace("run             ${nrun}", "run             500\nrun             ${nrun}")
    (work / f"in.{name}").write_text(script)
    command = [*lammps.command(1), "-in", f"in.{name}", "-var", "plugin", str(library), "-var", "seed", "1000",
               "-var", "nrun", str(steps), "-var", "cells", str(CELLS), "-log", "none", "-nocite"]  # fmt: skip
    done = subprocess.run(command, capture_output=True, text=True, env=lammps.environment(), cwd=work)
    if done.returncode != 0 or not LOOP.findall(done.stdout):
        return math.nan
    seconds, _, count, atoms = LOOP.findall(done.stdout)[-1]
    share = float(CPU.findall(done.stdout)[-1]) / 100.0
    return float(seconds) * share / (int(atoms) * int(count))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--steps", type=int, default=300, help="timed engine steps per measurement (the plugin runs 3x as many)")
    parser.add_argument("--no-lammps", action="store_true", help="the engine only")
    options = parser.parse_args()
    numba.set_num_threads(1)
    work = Path(tempfile.mkdtemp(prefix="fricgen-law-cost-"))
    folder = work / "laws"
    folder.mkdir()
    for name, text in USER_LAWS.items():
        (folder / f"{name}.toml").write_text(text)
    generate(catalogue=folder)
    laws = {name: None for name in sorted(p.stem for p in CATALOGUE.glob("*.toml"))} | {name: folder for name in USER_LAWS}
    engines = {name: simulation(name, where) for name, where in laws.items()}
    engines |= {f"{name} (quadrature)": without_tables(sim) for name, sim in list(engines.items()) if evaluation(sim) == "noise tables"}
    plugins, lammps = {}, None
    if not options.no_lammps:
        from fricgen.app.cli.lammps import locate_lammps

        lammps = locate_lammps()
        plugins = {name: plugin(name, where) for name, where in laws.items()}
    costs: dict[tuple[str, str], list[float]] = {}
    for _ in range(options.repeats):  # alternate: the machine's drift hits every law alike
        for name, sim in engines.items():
            costs.setdefault(("engine", name), []).append(engine_cost(sim, options.steps))
        for name, (library, sources) in plugins.items():
            costs.setdefault(("plugin", name), []).append(plugin_cost(lammps, library, sources, name, 3 * options.steps, work))
    median = {key: statistics.median(values) for key, values in costs.items()}
    print(f"2-D, N = {N}, area fraction 0.6, dt = 1e-3, Itô, one thread / one rank; CPU ns per particle-step, medians of "
          f"{options.repeats} alternating repeats; ratio to coulomb_newton of the same program")  # fmt: skip
    print(f"  {'law':28s} {'D':13s} {'engine':>8s} {'ratio':>6s}" + (f" {'plugin':>8s} {'ratio':>6s}" if plugins else ""))
    for name, sim in engines.items():
        cost = median["engine", name]
        row = f"  {name:28s} {evaluation(sim):13s} {1e9 * cost:8.0f} {cost / median['engine', 'coulomb_newton']:6.2f}"
        if ("plugin", name) in median and math.isnan(median["plugin", name]):
            row += "    fails (the explicit step at dt = 1e-3 loses atoms)"
        elif ("plugin", name) in median:
            row += f" {1e9 * median['plugin', name]:8.0f} {median['plugin', name] / median['plugin', 'coulomb_newton']:6.2f}"
        print(row)


if __name__ == "__main__":
    main()
