"""The user's notebooks run end to end (small workloads: FRICGEN_NOTEBOOK_SMALL=1)."""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))
EXAMPLE_LAW = "stick_slip_example"  # saved to the catalogue by define_a_friction_law


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, monkeypatch):
    assert NOTEBOOKS
    monkeypatch.setenv("FRICGEN_NOTEBOOK_SMALL", "1")
    notebook = nbformat.read(path, as_version=4)
    assert all(not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"), "store notebooks without outputs"
    try:
        NotebookClient(notebook, timeout=900, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    finally:  # the example law must not stay in the catalogue (the freshness test would see it)
        for leftover in (ROOT / "derive" / "catalogue" / f"{EXAMPLE_LAW}.toml", ROOT / "generated" / "laws" / f"{EXAMPLE_LAW}.py"):
            leftover.unlink(missing_ok=True)
