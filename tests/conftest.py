"""Fixtures shared by the suite.

``executed_notebooks``: the user's notebooks of notebooks/, executed once per session with small
workloads (FRICGEN_NOTEBOOK_SMALL=1) and their outputs stored in a jupyter-cache folder.
tests/test_notebooks.py checks that each ran; tests/test_docs.py builds the site from the same folder
(myst-nb's cache mode finds them there), so the suite runs each notebook once.
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


@dataclass(frozen=True)
class ExecutedNotebooks:
    """A jupyter-cache folder with every notebook that ran through, the error of each one that did not
    (by the notebook's stem) and the seconds each took."""

    cache: Path
    errors: dict[str, str]
    seconds: dict[str, float]


def _package_laws() -> list[str]:
    return sorted(p.name for p in [*(ROOT / "derive" / "law" / "catalogue").glob("*.toml"), *(ROOT / "generated" / "laws").glob("*.py")])


@pytest.fixture(scope="session")
def executed_notebooks(tmp_path_factory) -> ExecutedNotebooks:
    import nbformat
    from jupyter_cache import get_cache
    from jupyter_cache.base import CacheBundleIn
    from nbclient import NotebookClient

    folder = tmp_path_factory.mktemp("notebook-cache")
    cache = get_cache(folder)
    errors, seconds = {}, {}
    with pytest.MonkeyPatch.context() as env:
        env.setenv("FRICGEN_NOTEBOOK_SMALL", "1")
        env.delenv("FRICGEN_LAWS", raising=False)  # a law of one's own folder is handed over as an object
        env.delenv("MPLBACKEND", raising=False)  # the kernel's inline backend: figures become outputs
        for path in NOTEBOOKS:
            env.setenv("FRICGEN_NOTEBOOK_LAWS", str(tmp_path_factory.mktemp(f"laws-{path.stem}")))  # a user's law folder
            notebook = nbformat.read(path, as_version=4)
            before, start = _package_laws(), time.perf_counter()
            try:
                client = NotebookClient(notebook, timeout=900, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}})
                client.record_timing = False  # cell metadata enter the cache's key: keep them as stored
                client.execute()
            except Exception:  # a failing cell, a timeout, a dead kernel: the notebook's own test reports it
                errors[path.stem] = traceback.format_exc(limit=3)[-6000:]
                continue
            seconds[path.stem] = time.perf_counter() - start
            if _package_laws() != before:
                errors[path.stem] = "the notebook wrote into the package's catalogue or generated/"
                continue
            bundle = CacheBundleIn(notebook, str(path.resolve()), data={"execution_seconds": seconds[path.stem]})
            cache.cache_notebook_bundle(bundle, check_validity=False, overwrite=True)
    return ExecutedNotebooks(folder, errors, seconds)
