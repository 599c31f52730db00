"""Where a step's time goes: Linux `perf` sampling of the compiled engine, with names for Numba's code.

perf cannot name JIT-compiled code by itself; it reads /tmp/perf-PID.map (start, size, name). This
script compiles the engine afresh (a temporary NUMBA_CACHE_DIR, so that every function's LLVM
library stays in memory), writes that map from the libraries' function addresses (a function's size
is taken as the gap to the next address), then samples its own process with `perf record` while it
runs SECONDS of steps, and prints the top of `perf report`. Inlined helpers count towards their
caller (a parfor's body appears as `__numba_parfor_gufunc...`); libm's exp, expm1, erfc... appear by
name. System: 2-D, N = 10 000, area fraction 0.6, WCA + solvent + Coulomb–Newton with its noise
(pairwise), dt = 1e-3, one thread, after 1500 steps from the lattice.

Run: python benchmarks/profile_step.py [SECONDS]   (needs `perf`, e.g. Debian's linux-perf)
"""

from __future__ import annotations

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

from fricgen.langevin import LangevinConfig, Law, Particles, Simulation, Thermostat, lattice_state  # noqa: E402


def perf_map(path: str) -> int:
    """Write the perf map of every compiled Numba function in this process; returns the count."""
    names = {}
    for dispatcher in (obj for obj in gc.get_objects() if isinstance(obj, CPUDispatcher)):
        for result in list(dispatcher.overloads.values()):
            module = getattr(result.library, "_final_module", None)
            for function in module.functions if module is not None else ():
                if not function.is_declaration:
                    address = result.library.get_pointer_to_function(function.name)
                    if address:
                        names[address] = f"{dispatcher.py_func.__module__}.{dispatcher.py_func.__qualname__}:{function.name[:80]}"
    starts = sorted(names)
    with open(path, "w") as out:
        for start, end in zip(starts, starts[1:] + [starts[-1] + 4096] if starts else []):
            out.write(f"{start:x} {min(end - start, 1 << 20):x} {names[start]}\n")
    return len(starts)


def main() -> None:
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 8.0
    if shutil.which("perf") is None:
        sys.exit("perf is not installed (Debian: apt install linux-perf)")
    numba.set_num_threads(1)
    particles = Particles.spheres(10_000)
    sim = Simulation(LangevinConfig(law=Law("coulomb_newton"), thermostat=Thermostat(dt=1e-3)), particles, lattice_state(particles, 2, 0.6))
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
