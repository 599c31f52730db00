"""The one loader of generated kernels: law kernels by name, refused when stale.

A law's kernels carry the hash of the law file they were generated from; if the law file was
edited since, loading fails with the command that regenerates them. After a regeneration in the
same process (a notebook), the module is reloaded, so the new kernels take effect at once.
SymPy is never imported here.
"""

from __future__ import annotations

import importlib
import sys
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType

import numpy as np

from derive.lawdata import CATALOGUE, LawFileError, read_law_data, source_hash


class KernelError(LookupError):
    """Kernels missing, stale, or asked for a calculus the law does not have."""


@dataclass(frozen=True)
class LawKernels:
    """Compiled kernels of one friction law (see the generated module for the equations).

    Kernel arguments: ``(u, w, r, p)`` for ``friction`` and ``friction_over_u``, ``(r, p)`` for
    ``weight``, ``(u, w, r, mu, kT, p)`` for the noise kernels, with ``p`` from
    :meth:`parameters`.
    """

    name: str
    module: ModuleType

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return self.module.PARAMETERS

    @property
    def calculi(self) -> tuple[str, ...]:
        return self.module.CALCULI

    @property
    def has_weight(self) -> bool:
        return self.module.HAS_WEIGHT

    def parameters(self, **overrides: float) -> np.ndarray:
        """Parameter values (float64 array) from the defaults and named overrides."""
        unknown = sorted(set(overrides) - set(self.parameter_names))
        if unknown:
            raise KernelError(f"law {self.name} has no parameter(s) {unknown}; it has {list(self.parameter_names)}")
        values = dict(zip(self.parameter_names, self.module.DEFAULTS))
        for key, value in overrides.items():
            if not (np.isfinite(value) and value > 0):
                raise KernelError(f"law {self.name}: parameter {key} must be finite and positive, got {value}")
            values[key] = float(value)
        return np.array([values[n] for n in self.parameter_names], dtype=np.float64)

    def _calculus(self, calculus: str) -> str:
        if calculus not in self.calculi:
            raise KernelError(f"law {self.name} has no kernels for the {calculus!r} calculus; it has {list(self.calculi)}")
        return calculus

    def noise_amplitude(self, calculus: str):
        """D(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"noise_amplitude_{self._calculus(calculus)}")

    def noise_sqrt(self, calculus: str):
        """sqrt(D)(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"noise_sqrt_{self._calculus(calculus)}")

    def contact(self, calculus: str):
        """(f/u, sqrt(D))(u, w, r, mu, kT, p) for the calculus."""
        return getattr(self.module, f"contact_{self._calculus(calculus)}")

    @property
    def friction(self):
        return self.module.friction

    @property
    def friction_over_u(self):
        return self.module.friction_over_u

    @property
    def weight(self):
        if not self.has_weight:
            raise KernelError(f"law {self.name} has no weight w(r)")
        return self.module.weight


def load_law_kernels(name: str, catalogue: Path = CATALOGUE) -> LawKernels:
    """Kernels of the catalogue law ``name``; raises KernelError if missing or stale."""
    path = Path(catalogue) / f"{name}.toml"
    if not path.exists():
        available = sorted(p.stem for p in Path(catalogue).glob("*.toml"))
        raise KernelError(f"no law {name!r} in the catalogue {catalogue}; it has {available}")
    try:
        digest = source_hash(read_law_data(path))
    except LawFileError as error:
        raise KernelError(str(error)) from error
    module_name = f"generated.laws.{name}"
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as error:
        raise KernelError(f"no generated kernels for law {name}: run `fricgen generate {name}`") from error
    if module.SOURCE_HASH != digest:
        module = importlib.reload(sys.modules[module_name])  # regenerated since it was imported?
    if module.SOURCE_HASH != digest:
        raise KernelError(f"the kernels of law {name} are stale: {path} changed after they were generated; run `fricgen generate {name}`")
    return LawKernels(name, module)


def load_potential(name: str) -> ModuleType:
    """Generated potential module (energy(x, params), force(x, params), PARAMETERS, DEFAULTS; external
    potentials also force_field(xs, params, out))."""
    try:
        return importlib.import_module(f"generated.potentials.{name}")
    except ModuleNotFoundError as error:
        import generated.potentials

        there = sorted(p.stem for p in Path(generated.potentials.__file__).parent.glob("*.py") if p.stem != "__init__")
        raise KernelError(f"no generated potential {name!r} (there are {there}): a new one needs `fricgen generate`") from error
