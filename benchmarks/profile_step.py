"""Where a step's time goes: Linux `perf` sampling of the compiled engine, with names for Numba's code.

perf cannot name JIT-compiled code by itself; it reads /tmp/perf-PID.map (start, size, name). This
script compiles the engine afresh (a temporary NUMBA_CACHE_DIR, so that every function's LLVM
library stays in memory), writes that map from the libraries' function addresses and symbol sizes,
then samples its own process with `perf record` while it
runs SECONDS of steps, and prints the top of `perf report`. Inlined helpers count towards their
caller (a parfor's body appears as `__numba_parfor_gufunc...`); libm's exp, expm1, erfc... appear by
name. System: 2-D, N = 10 000, area fraction 0.6, WCA + solvent + Coulomb–Newton with its noise
(pairwise), dt = 1e-3, one thread, after 1500 steps from the lattice; ``--no-solvent --dt 5e-3`` is the
system of benchmarks/lammps_engine.py (the contacts alone as the thermostat).

Run: python benchmarks/profile_step.py [SECONDS] [--dt DT] [--no-solvent]   (needs `perf`, e.g. Debian's linux-perf)
"""

from __future__ import annotations

import argparse
import gc
import os
import shutil
import subprocess
import sys
import tempfile
import threading

os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="fricgen-profile-")  # before numba is imported

import numba  # noqa: E402
from numba.core.registry import CPUDispatcher  # noqa: E402

from fricgen.kernels import load_law_kernels  # noqa: E402
from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state  # noqa: E402


def perf_map(path: str) -> int:
    """Write the perf map of every compiled Numba function in this process; returns the count. A
    function's address comes from its library, its size from the symbol table of the library's
    object code (``nm -S``), so that code outside any known function stays unnamed."""
    entries = {}
    with tempfile.TemporaryDirectory() as scratch:
        for dispatcher in (obj for obj in gc.get_objects() if isinstance(obj, CPUDispatcher)):
            owner = f"{dispatcher.py_func.__module__}.{dispatcher.py_func.__qualname__}"
            for result in list(dispatcher.overloads.values()):
                objfile = os.path.join(scratch, "library.o")
                with open(objfile, "wb") as out:
                    out.write(result.library._get_compiled_object())
                symbols = subprocess.run(["nm", "-S", "--defined-only", objfile], capture_output=True, text=True).stdout
                for fields in (line.split() for line in symbols.splitlines()):
                    if len(fields) == 4 and fields[2] in "tTwW" and int(fields[1], 16):
                        address = result.library.get_pointer_to_function(fields[3])
                        if address:
                            entries[address] = (int(fields[1], 16), f"{owner}:{fields[3][:80]}")
    with open(path, "w") as out:
        for start, (size, name) in sorted(entries.items()):
            out.write(f"{start:x} {size:x} {name}\n")
    return len(entries)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("seconds", nargs="?", type=float, default=8.0, help="seconds sampled")
    parser.add_argument("--dt", type=float, default=1e-3)
    parser.add_argument("--no-solvent", action="store_true", help="gamma = gamma_R = 0")
    options = parser.parse_args()
    seconds = options.seconds
    if shutil.which("perf") is None:
        sys.exit("perf is not installed (Debian: apt install linux-perf)")
    numba.set_num_threads(1)
    particles = Particles.spheres(10_000)
    solvent = {"gamma": 0.0, "gamma_rot": 0.0} if options.no_solvent else {}
    config = LangevinConfig(law=Law("coulomb_newton"), thermostat=Thermostat(dt=options.dt, **solvent))
    sim = Simulation(config, particles, lattice_state(particles, 2, 0.6), load_law_kernels("coulomb_newton"))
    sim.threads = 1
    sim.advance(1500)
    print(f"perf map: {perf_map(f'/tmp/perf-{os.getpid()}.map')} functions")
    data = os.path.join(os.environ["NUMBA_CACHE_DIR"], "perf.data")
    record = ["perf", "record", "-F", "2000", "-p", str(os.getpid()), "-o", data, "--", "sleep", str(seconds)]
    recorder = threading.Thread(target=subprocess.run, args=(record,), kwargs={"capture_output": True})
    recorder.start()
    while recorder.is_alive():
        sim.advance(50)
    report = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "sym"], capture_output=True, text=True)
    print("\n".join([line[:160] for line in report.stdout.splitlines() if "%" in line and not line.startswith("#")][:30]))


if __name__ == "__main__":
    main()
