"""The plugin under test, built once per source hash, and the LAMMPS that runs it.

Nothing here skips: without LAMMPS, CMake or a C++ compiler the tests fail and say what is missing
(pip install -e ".[test]" installs lammps[mpi] and cmake; the compiler is the machine's).
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import pytest

from fricgen.app.cli.lammps import LammpsError, build_plugin, emit_plugin, locate_lammps, plugin_folder, sources_hash
from fricgen.derive.law.catalogues import BUILT_IN

BUILD_ROOT = Path(tempfile.gettempdir()) / "fricgen-lammps-tests"


@pytest.fixture(scope="session")
def lammps():
    try:
        return locate_lammps()
    except LammpsError as error:
        pytest.fail(f"LAMMPS is needed for tests/lammps: {error}")


@pytest.fixture(scope="session")
def plugin(lammps):
    """plugin(law) -> the built .so of the committed sources generated/lammps/<law>/, built into
    BUILD_ROOT/<law>-<hash> (reused across sessions while the sources and LAMMPS are unchanged)."""
    built = {}

    def get(law: str) -> Path:
        if law not in built:
            law_file = BUILT_IN.find(law)
            folder = plugin_folder(law_file)
            if not folder.is_dir():
                folder, _ = emit_plugin(law_file, out=BUILD_ROOT / "sources" / law)
            try:
                built[law] = build_plugin(folder, lammps, law_file, BUILD_ROOT / f"{law}-{sources_hash(folder, lammps)[:16]}")
            except LammpsError as error:
                pytest.fail(f"the plugin of {law} does not build: {error}")
        return built[law]

    return get
