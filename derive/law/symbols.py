"""Canonical SymPy symbols shared by the symbolic layer.

Conventions (docs/physics.md#units-and-symbols): ``u`` is the magnitude of the relative tangential contact
velocity (u >= 0), ``r`` the centre distance, ``w`` the value of a law's distance weight
w(r), ``kT`` the thermal energy and ``mu`` the contact mobility
mu = 1/m_i + 1/m_k + R_i^2/I_i + R_k^2/I_k (units 1/mass).
"""

from __future__ import annotations

import builtins
import keyword

import sympy as sp

u = sp.Symbol("u", positive=True)
r = sp.Symbol("r", positive=True)
w = sp.Symbol("w", positive=True)
kT = sp.Symbol("kT", positive=True)
mu = sp.Symbol("mu", positive=True)

#: Integration variable of the integral representation (F-22).
s = sp.Symbol("s", positive=True)

#: Names a law may not use for its parameters (symbols, and names of the generated kernels).
RESERVED = frozenset({"u", "r", "w", "kT", "mu", "s", "params", "math", "numba", "erfcx", "friction", "weight"})

#: Python's keywords and builtins: not parameter names (a parameter ``min`` would shadow the ``min``
#: that the printer writes for ``Min`` in a kernel).
PYTHON_NAMES = frozenset(keyword.kwlist) | frozenset(dir(builtins))
