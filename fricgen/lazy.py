"""Names of a package that import their module when first read (a module's ``__getattr__`` and ``__dir__``, PEP 562).

A package's ``__init__`` uses it for the names whose modules are costly to import: on a cold Numba cache,
importing ``fricgen.langevin.simulation`` compiles the whole Langevin engine (about 200 s on 2 cores) and
``fricgen.rods.simulation`` the BCD engine (about 40 s). The command line's flags, ``fricgen noise``,
``fricgen lammps`` and ``import fricgen`` read only light modules and so compile nothing they do not run.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable


def on_first_use(package: str, modules: dict[str, tuple[str, ...]]) -> tuple[Callable[[str], object], Callable[[], list[str]]]:
    """The module functions ``__getattr__`` and ``__dir__`` for ``package``: reading one of the names ``modules[m]``
    imports ``m`` (a module path relative to ``package``, or absolute) and returns its attribute, any other missing
    name raises AttributeError; ``dir(package)`` lists the names before they are read (as autodoc and tab completion
    expect)."""
    home = {name: module for module, names in modules.items() for name in names}

    def __getattr__(name: str) -> object:
        if name not in home:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(home[name], package), name)

    def __dir__() -> list[str]:
        return sorted({*vars(sys.modules[package]), *home})

    return __getattr__, __dir__
