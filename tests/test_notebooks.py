"""The user's notebooks run end to end (small workloads: FRICGEN_NOTEBOOK_SMALL=1)."""

from pathlib import Path

import nbformat
import pytest
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


def _package_laws() -> list[str]:
    return sorted(p.name for p in [*(ROOT / "derive" / "law" / "catalogue").glob("*.toml"), *(ROOT / "generated" / "laws").glob("*.py")])


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, monkeypatch, tmp_path):
    assert NOTEBOOKS
    monkeypatch.setenv("FRICGEN_NOTEBOOK_SMALL", "1")
    monkeypatch.delenv("FRICGEN_LAWS", raising=False)  # a law of one's own folder is handed over as an object
    monkeypatch.setenv("FRICGEN_NOTEBOOK_LAWS", str(tmp_path))  # define_a_friction_law saves its law there (a user's law folder)
    notebook = nbformat.read(path, as_version=4)
    assert all(not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"), "store notebooks without outputs"
    before = _package_laws()
    NotebookClient(notebook, timeout=900, kernel_name="python3", resources={"metadata": {"path": str(ROOT)}}).execute()
    assert _package_laws() == before, "a notebook wrote into the package's catalogue or generated/"
