"""Numba's cached code of the compiled layers is cleared when any of their sources changed.

Numba checks a cached function only against its own file, yet the cached code holds the compiled
functions it calls; fricgen.compiled.clear_stale_caches closes that gap (README, Layout). Run here on a
scratch tree, not on the package, whose caches the rest of the suite uses."""

import subprocess
import sys
from pathlib import Path

from fricgen.compiled import clear_stale_caches

SOURCES = ("engine", "rng.py")


def _tree(root: Path) -> list[Path]:
    (root / "engine" / "__pycache__").mkdir(parents=True)
    (root / "app").mkdir()
    (root / "engine" / "step.py").write_text("def step(): pass\n")
    (root / "engine" / "list.py").write_text("def build(): pass\n")
    (root / "rng.py").write_text("def normal(): pass\n")
    (root / "app" / "cli.py").write_text("def main(): pass\n")
    return _caches(root)


def _caches(root: Path) -> list[Path]:
    caches = [root / "engine" / "__pycache__" / name for name in ("step.advance-3.py311.nbi", "step.advance-3.py311.1.nbc")]
    for cache in caches:
        cache.write_bytes(b"code")
    return caches


def test_caches_are_cleared_when_a_compiled_source_changes_and_only_then(tmp_path):
    caches = _tree(tmp_path)
    keep = tmp_path / "engine" / "__pycache__" / "step.cpython-311.pyc"  # Python's own cache stays
    keep.write_bytes(b"bytecode")
    assert clear_stale_caches(tmp_path, SOURCES)  # no stamp yet: the caches' sources are unknown
    assert not any(c.exists() for c in caches) and keep.exists()
    caches = _caches(tmp_path)
    assert not clear_stale_caches(tmp_path, SOURCES)
    (tmp_path / "app" / "cli.py").write_text("def main(): return 1\n")  # not a compiled source
    assert not clear_stale_caches(tmp_path, SOURCES) and all(c.exists() for c in caches)
    (tmp_path / "engine" / "list.py").write_text("def build(): return 1\n")  # a callee of the cached function
    assert clear_stale_caches(tmp_path, SOURCES) and not any(c.exists() for c in caches)
    caches = _caches(tmp_path)
    (tmp_path / "engine" / "list.py").rename(tmp_path / "engine" / "cells.py")  # same bytes, another file
    assert clear_stale_caches(tmp_path, SOURCES) and not any(c.exists() for c in caches)


def test_a_tree_that_cannot_be_written_is_left_alone(tmp_path):
    caches = _tree(tmp_path)
    (tmp_path / "__pycache__").write_text("a file where the stamp's folder would go")
    assert not clear_stale_caches(tmp_path, SOURCES) and all(c.exists() for c in caches)


SCRATCH = """import fricgen.compiled  # first, as the engines do
import numba
import numpy as np
from numba import types


@numba.njit(parallel=True, cache=True)
def fill(a):
    for i in numba.prange(a.size):
        a[i] = i


@numba.njit(types.float64(types.int64), cache=True)  # compiled at import, as integrator.advance
def total(n):
    a = np.empty(n)
    fill(a)
    return a.sum()


print(total(10))
"""


def test_a_caller_compiled_against_cached_parallel_loops_loads_from_the_cache(tmp_path):
    """A function compiled with its signature while the parallel loop it calls came from the cache (what a process
    does that starts beside another after clear_stale_caches) is cached with references to the threading layer;
    fricgen.compiled launches the layer first, so loading it later does not abort LLVM."""
    (tmp_path / "scratch.py").write_text(SCRATCH)

    def run():
        done = subprocess.run([sys.executable, "-c", "import scratch"], cwd=tmp_path, capture_output=True, text=True, timeout=300)
        return done.returncode, (done.stdout + done.stderr)[-300:]

    assert run() == (0, "45.0\n")  # both compiled and cached
    for cache in (tmp_path / "__pycache__").glob("scratch.total-*"):
        cache.unlink()
    assert run() == (0, "45.0\n")  # total compiled again, fill from the cache
    assert run() == (0, "45.0\n")  # total from the cache
