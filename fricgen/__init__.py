"""fricgen: thermodynamically consistent frictional contacts, derived symbolically.

The runtime package, in layers (docs/physics.md explains the physics they follow); each
subpackage's ``__init__`` is its public API:

- ``fricgen.derive``: the symbolic layer (SymPy): laws, their noise and its proof, the code generators;
- ``fricgen.generated``: the code that fricgen.derive emitted for the built-in laws and potentials;
- ``fricgen.kernels``: the one loader of generated kernels and their types (the kernel ABI);
- ``fricgen.rng``: counter-based random numbers and the one registry of noise streams;
- ``fricgen.schema``, ``fricgen.errors``: typed configuration sections, one error family;
- ``fricgen.langevin``: the Langevin engine of frictional spheres (2-D and 3-D);
- ``fricgen.rods``: Brownian cluster dynamics of rods, with the exact theory;
- ``fricgen.app``: the ``fricgen`` command line, runs, sweeps and studies (the demo, the thermostat check).

The engines import only the kernel layer, the RNG, schema/errors and derive's plain-data modules
(``fricgen.derive.calculus``, ``fricgen.derive.law.lawdata``); never each other, the application or SymPy
(tests/test_layers.py). ``import fricgen`` itself loads nothing but the error family
(:func:`load_law` and :class:`LawKernels` are loaded on first use); it puts TBB
where Numba finds it, sets the default thread count and clears Numba's cached code of the compiled
layers when their sources changed (:func:`clear_stale_caches`).
"""

import ctypes
import hashlib
import importlib.metadata
import importlib.util
import os
import warnings
from pathlib import Path

try:
    import fcntl
except ImportError:  # Windows: no lock around the clearing
    fcntl = None

#: The files whose compiled functions call each other: the engines, the kernel layer's compiled
#: parts, and fricgen.derive.calculus, whose constants are compiled in (paths relative to fricgen/;
#: derive/ lies beside fricgen/ in a source checkout and inside it once installed).
_CALCULUS = os.path.relpath(importlib.util.find_spec("fricgen.derive.calculus").origin, Path(__file__).parent)
COMPILED_SOURCES = ("langevin", "rods", "kernels.py", "rng.py", _CALCULUS)


def _load_tbb() -> None:
    """Put Intel TBB where Numba finds it. Numba takes the first threading layer it can load: TBB
    (work stealing), then OpenMP. Beside a busy process, OpenMP's barriers make 2 threads slower than
    1 (0.5x), TBB's stolen work keeps them near 1 thread (0.93x) and ahead on a quiet machine
    (benchmarks/contention.py). The tbb wheel puts libtbb into the environment's lib/, where the
    loader does not look: load it globally, so Numba's TBB layer links against it."""
    try:
        files = importlib.metadata.files("tbb") or []
    except importlib.metadata.PackageNotFoundError:
        return
    for file in files:
        if file.name in ("libtbb.so.12", "libtbb.12.dylib"):
            try:
                ctypes.CDLL(str(file.locate()), mode=ctypes.RTLD_GLOBAL)
            except OSError:  # Numba falls back to OpenMP or its work queue
                pass
            return


def clear_stale_caches(root: Path, sources: tuple[str, ...] = COMPILED_SOURCES) -> bool:
    """Delete Numba's cached code (``*.nbi``, ``*.nbc``) in the ``__pycache__`` folders under
    ``root`` if the Python files of ``sources`` (files, or folders searched recursively, relative to
    ``root``) changed since the last call; returns whether it did. Numba checks a cached function
    only against its own file, yet the cached code holds the compiled functions it calls: after an
    edit of ``neighbors.py``, ``integrator.advance`` would run the old code. Does nothing where
    ``root`` is not writable (Numba then caches elsewhere) or for a ``NUMBA_CACHE_DIR``.

    Args:
        root: the package folder whose ``__pycache__`` folders hold Numba's caches.
        sources: the compiled sources, relative to ``root``.

    Returns:
        Whether the caches were cleared.
    """
    digest = hashlib.sha256()
    for name in sources:
        path = root / name
        for file in sorted(path.rglob("*.py")) if path.is_dir() else [path] if path.exists() else []:
            digest.update(Path(os.path.relpath(file, root)).as_posix().encode() + file.read_bytes())
    stamp = root / "__pycache__" / "compiled-sources.sha256"
    try:
        stamp.parent.mkdir(exist_ok=True)
        with open(stamp, "a+") as handle:  # the lock keeps processes that start together from clearing each other's new caches
            if fcntl:
                fcntl.flock(handle, fcntl.LOCK_EX)
            handle.seek(0)
            if handle.read() == digest.hexdigest():
                return False
            for cache in root.rglob("__pycache__/*.nb[ic]"):
                cache.unlink(missing_ok=True)
            handle.seek(0)
            handle.truncate()
            handle.write(digest.hexdigest())
            return True
    except OSError:
        return False


_load_tbb()
clear_stale_caches(Path(__file__).parent)
#: The engines take their kernels as first-class functions by design: Numba's warning that the
#: feature is experimental, at each compile and each tuple type of such functions, says nothing new.
warnings.filterwarnings("ignore", message="First-class function type feature is experimental")

#: The default thread count is the number of CPUs this process may use (its affinity), not the
#: machine's; a user's own NUMBA_NUM_THREADS wins, and it acts only when fricgen is imported before
#: numba. (OpenMP's wait policy is left alone: passive waiting rescues two threads under contention
#: but costs 5-8 times on a quiet machine with small systems; benchmarks/contention.py.)
if hasattr(os, "sched_getaffinity"):
    os.environ.setdefault("NUMBA_NUM_THREADS", str(len(os.sched_getaffinity(0))))

from .errors import ConfigError, FricgenError, KernelError, SimulationError  # noqa: E402

__version__ = "0.1.0"

#: The names most used in a notebook, loaded on first use (``import fricgen`` stays light).
_LAZY = {"load_law": "fricgen.kernels", "LawKernels": "fricgen.kernels"}

__all__ = ["ConfigError", "FricgenError", "KernelError", "LawKernels", "SimulationError", "__version__", "load_law"]


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'fricgen' has no attribute {name!r}")
    import importlib

    return getattr(importlib.import_module(_LAZY[name]), name)
