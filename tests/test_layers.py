"""Data flows one way: the runtime does not import SymPy, derive does not import the runtime."""

import subprocess
import sys


def _modules_after(statement):
    code = f"import sys; {statement}; print(' '.join(sorted(sys.modules)))"
    return set(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split())


def test_import_fricgen_leaves_sympy_out():
    loaded = _modules_after("import fricgen, fricgen.cli, fricgen.kernels; fricgen.kernels.load_law_kernels('coulomb_newton')")
    assert "sympy" not in loaded


def test_derive_does_not_import_the_runtime():
    loaded = _modules_after("import derive")
    assert not {"fricgen", "numba"} & loaded
