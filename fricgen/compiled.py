"""The set-up of fricgen's compiled layers, done once, when the first of them is imported.

Importing this module (the first line of :mod:`fricgen.kernels`, :mod:`fricgen.rng` and of the
engines' packages, before they import Numba) puts TBB where Numba finds it, sets the default thread
count, clears Numba's cached code of the compiled layers when their sources changed
(:func:`clear_stale_caches`) and then launches Numba's threading layer (before any cached function loads).
``import fricgen`` alone does none of this: the command line's help, the symbolic layer and the errors never
touch Numba.
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

    Parameters
    ----------
    root : pathlib.Path
        The package folder whose ``__pycache__`` folders hold Numba's caches.
    sources : tuple of str
        The compiled sources, relative to ``root`` (default :data:`COMPILED_SOURCES`).

    Returns
    -------
    bool
        Whether the caches were cleared.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> from fricgen.compiled import clear_stale_caches
    >>> root = Path(tempfile.mkdtemp())
    >>> _ = (root / "engine.py").write_text("x = 1")
    >>> clear_stale_caches(root, ("engine.py",)), clear_stale_caches(root, ("engine.py",))
    (True, False)
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
#: machine's; a user's own NUMBA_NUM_THREADS wins, and it acts only when a compiled layer of fricgen is
#: imported before numba. (OpenMP's wait policy is left alone: passive waiting rescues two threads under contention
#: but costs 5-8 times on a quiet machine with small systems; benchmarks/contention.py.)
if hasattr(os, "sched_getaffinity"):
    os.environ.setdefault("NUMBA_NUM_THREADS", str(len(os.sched_getaffinity(0))))

# Launch Numba's threading layer now, before any cached function is loaded. A function compiled with its
# signature (compiled or loaded from the cache at import, as integrator.advance) links the parallel loops it calls;
# if it was compiled while those came from the cache, its cached code needs the layer's symbols when it loads,
# and without them LLVM aborts the process ("Symbol not found: allocate_sched"). That happens after the caches
# were cleared (clear_stale_caches) and two processes started together, as the workers of a sweep do.
import numba  # noqa: E402 (after the thread count and TBB above, which Numba reads when it starts)

numba.get_num_threads()
