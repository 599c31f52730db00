"""The user's notebooks run end to end (small workloads: FRICGEN_NOTEBOOK_SMALL=1) and use only the
public API. They run once per session, in the ``executed_notebooks`` fixture (tests/conftest.py),
whose outputs the documentation build shows (tests/test_docs.py)."""

import ast
import importlib

import nbformat
import pytest

from .conftest import NOTEBOOKS

#: The packages whose ``__all__`` is the public API a notebook may import from.
PUBLIC = {"fricgen", "fricgen.app", "fricgen.derive", "fricgen.kernels", "fricgen.langevin", "fricgen.rods"}


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs(path, executed_notebooks):
    notebook = nbformat.read(path, as_version=4)
    assert all(not cell.get("outputs") for cell in notebook.cells if cell.cell_type == "code"), "store notebooks without outputs"
    assert path.stem not in executed_notebooks.errors, executed_notebooks.errors[path.stem]


def _private_imports(source: str) -> list[str]:
    """The fricgen imports of a cell that are not names of a public package's ``__all__``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names if alias.name.startswith("fricgen") and alias.name not in PUBLIC]
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("fricgen"):
            public = importlib.import_module(node.module).__all__ if node.module in PUBLIC else []
            found += [f"{node.module}.{alias.name}" for alias in node.names if alias.name not in public]
    return found


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_imports_only_the_public_api(path):
    notebook = nbformat.read(path, as_version=4)
    private = [name for cell in notebook.cells if cell.cell_type == "code" for name in _private_imports(cell.source)]
    assert not private, f"{path.name} imports private names: {private}"


def test_private_imports_are_caught():
    assert _private_imports("from fricgen.derive.driver import generate\nimport fricgen.app.studies\nfrom fricgen import load_law") == [
        "fricgen.derive.driver.generate",
        "fricgen.app.studies",
    ]
