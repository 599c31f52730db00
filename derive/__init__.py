"""The symbolic layer of fricgen (SymPy only), in three stages and one driver.

1. **The law** (:mod:`fricgen.derive.law`): a friction law as data, its parameters and ranges, the
   potentials, and the catalogues a law's name is looked up in.
2. **The noise and its proof** (:mod:`fricgen.derive.noise`): D(u, w, r) from the zero-current
   condition for a calculus, and the symbolic proof that it is right on the pair phase space.
3. **The backends** (:mod:`fricgen.derive.backends`): Numba kernels (generated/) and a LAMMPS plugin,
   printed by one printer and checked against the proof's reference values.

The driver (:mod:`fricgen.derive.driver`) reads top to bottom::

    law = load_law("laws/stribeck.toml")      # or make_law(...), catalogue()["coulomb_newton"]
    model = derive_noise(law, "ito")          # D(u, w, r) for the calculus
    report = verify(model)                    # symbolic facts and the kernel check: report.verified
    generate(["stribeck"], catalogue="laws")  # Numba kernels in laws/generated/

The package also exports the symbols that laws are written in, ``u``, ``r``, ``w``, ``kT`` and ``mu``
(docs/physics.md#units-and-symbols), and :func:`reference_amplitude`, D evaluated independently
of the kernels at high precision, for checks of one's own.

Names are resolved lazily, so that the plain-data modules (``fricgen.derive.calculus``,
``fricgen.derive.law.lawdata``, ``fricgen.derive.law.catalogues``) can be imported by the runtime
without SymPy.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "CATALOGUE": "law.lawdata",
    "FrictionLaw": "law.laws",
    "LawError": "law.laws",
    "Parameter": "law.laws",
    "catalogue": "law.law_files",
    "load_law": "law.law_files",
    "make_law": "law.laws",
    "save_law": "law.law_files",
    "Calculus": "calculus",
    "NoiseModel": "noise.derivation",
    "contact_mobility": "noise.derivation",
    "derive_noise": "noise.derivation",
    "Report": "noise.verification",
    "prove": "noise.verification",
    "reference_amplitude": "noise.reference",
    "u": "law.symbols",
    "r": "law.symbols",
    "w": "law.symbols",
    "kT": "law.symbols",
    "mu": "law.symbols",
    "verify": "driver",
    "generate": "driver",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    if name not in _EXPORTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f"{__name__}.{_EXPORTS[name]}"), name)


def __dir__() -> list[str]:
    return sorted([*globals(), *_EXPORTS])
