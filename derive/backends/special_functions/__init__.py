"""The special functions that generated kernels call (erfcx, expm1_given_exp), shared by the backends.

``special.py`` beside this file is hand-written Numba code, copied verbatim into the kernels'
package (generated/special.py) by the Numba backend; the LAMMPS backend prints the same erfcx
tables into C++. Both check printed code by running it as plain Python (:func:`execute`), with
``numba.njit`` replaced by an identity decorator. ``pieces.py`` computes erfcx's Chebyshev tables
with mpmath (tests/codegen/test_special.py checks that special.py holds its output).
"""

from __future__ import annotations

import builtins
import importlib
import math
from pathlib import Path

#: The hand-written source of generated/special.py.
SPECIAL_SOURCE = Path(__file__).with_name("special.py")


class Numba:
    """Stands in for numba in the executed kernel code: ``njit`` leaves the function as it is."""

    @staticmethod
    def njit(*args, **kwargs):
        if len(args) == 1 and callable(args[0]) and not kwargs:
            return args[0]
        return lambda function: function


def execute(source: str, modules: dict[str, object]) -> dict:
    """Run module ``source`` as plain Python; its imports may reach only ``modules`` (by the name as
    written, with leading dots for relative imports). Returns the module's namespace."""

    def importer(name, globals=None, locals=None, fromlist=(), level=0):
        key = "." * level + name
        if key not in modules:
            raise ImportError(f"the checked kernel code may import only {sorted(modules)}, not {key!r}")
        return modules[key]

    namespace = {"__builtins__": {**vars(builtins), "__import__": importer}, "__name__": "derive_kernel_check"}
    exec(compile(source, "<printed kernels>", "exec"), namespace)  # noqa: S102 - code printed by fricgen.derive's backends
    return namespace


def special_namespace() -> dict:
    """special.py (copied into generated/special.py) run as plain Python: its functions and tables."""
    return execute(SPECIAL_SOURCE.read_text(), {"math": math, "numba": Numba(), "numpy": importlib.import_module("numpy")})


__all__ = ["SPECIAL_SOURCE", "Numba", "execute", "special_namespace"]
