"""Symbolic layer of fricgen (SymPy only): friction laws, noise derivation, verification.

Stages, each returning a new frozen object::

    law = load_law("derive/catalogue/coulomb_newton.toml")   # or make_law(...), catalogue()
    model = derive_noise(law, "ito")                          # D(u, w, r) for the calculus
    report = verify(model)                                    # symbolic facts, report.verified
"""

from __future__ import annotations

from .laws import CATALOGUE, FrictionLaw, LawError, Parameter, catalogue, load_law, make_law, save_law
from .noise import Calculus, NoiseModel, contact_mobility, derive_noise
from .verify import Report, verify

__all__ = [
    "CATALOGUE",
    "Calculus",
    "FrictionLaw",
    "LawError",
    "NoiseModel",
    "Parameter",
    "Report",
    "catalogue",
    "contact_mobility",
    "derive_noise",
    "load_law",
    "make_law",
    "save_law",
    "verify",
]
