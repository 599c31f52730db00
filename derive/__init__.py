"""Symbolic layer of fricgen (SymPy only): friction laws, noise derivation, verification, emission.

Stages, each returning a new frozen object::

    law = load_law("derive/catalogue/coulomb_newton.toml")   # or make_law(...), catalogue()
    model = derive_noise(law, "ito")                          # D(u, w, r) for the calculus
    report = verify(model)                                    # symbolic facts, report.verified
    generate([law])                                           # Numba kernels in generated/

Names are resolved lazily, so that ``derive.lawdata`` (no SymPy) can be imported by the runtime.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "CATALOGUE": "lawdata",
    "FrictionLaw": "laws",
    "LawError": "laws",
    "Parameter": "laws",
    "catalogue": "laws",
    "load_law": "laws",
    "make_law": "laws",
    "save_law": "laws",
    "Calculus": "calculus",
    "NoiseModel": "noise",
    "contact_mobility": "noise",
    "derive_noise": "noise",
    "Report": "verification",
    "verify": "verification",
    "generate": "emit",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module 'derive' has no attribute {name!r}")
    return getattr(importlib.import_module(f"derive.{_EXPORTS[name]}"), name)
